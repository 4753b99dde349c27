// A scene's static stage as the run records it: summary.json's stage record with the released
// blocks, and the failure that stops the run when equilibrium is not reached.
#pragma once

#include "app/keyblocks.h"
#include "dda/static_stage.h"
#include "dda/system.h"

#include <nlohmann/json.hpp>

namespace ddafem
{
/// The stage's record in summary.json: name, mode, steps, converged, unbalanced_force_ratio,
/// tolerance, release (fall | remove) and `released`, one entry per released block:
/// {block, name, step, mass_kg, centroid_m [x, y], ratio, opening (index into the keyblocks'
/// openings, null without openings)}.
nlohmann::json static_stage_record(const dda::Stage& stage, const dda::StaticStageResult& result,
                                   const dda::System& system, const KeyblockRecorder& keyblocks);

/// What stops the run after the stage: the failed step, or not_converged with a message naming
/// the block farthest from balance; outcome success when the stage reached equilibrium.
dda::StepStatus static_stage_failure(const dda::Stage& stage, const dda::StaticStageResult& result,
                                     const dda::System& system);

} // namespace ddafem
