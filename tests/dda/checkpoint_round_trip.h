// Tests of checkpoints (issue 20): a System and its stage in progress saved into a checkpoint
// and loaded into ones built anew.
#pragma once

#include "common/checkpoint_archive.h"
#include "dda/system.h"

#include <sstream>

namespace ddafem::dda
{
/// Saves `system` and `run` (a StaticStageRun or DynamicStageRun) and loads them into
/// `into_system` and `into_run`, built from the same model and stage.
template <class StageRun>
void round_trip(const System& system, const StageRun& run, System& into_system, StageRun& into_run)
{
  std::stringstream text;
  {
    CheckpointOut archive(text);
    system.save(archive);
    run.save(archive);
  }
  CheckpointIn archive(text);
  into_system.load(archive);
  into_run.load(archive);
}
} // namespace ddafem::dda
