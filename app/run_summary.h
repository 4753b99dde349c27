// summary.json of a run (docs/outputs.md). Blocks (alone or tied to a far field): status, time
// steps and their cuts, stages, the model, the far field and the interface, contacts, timings,
// energies, keyblocks and outputs. A far field alone: status, steps, solver, model, timings,
// energies and outputs.
#pragma once

#include "app/keyblocks.h"
#include "app/run_outputs.h"
#include "app/scene.h"
#include "dda/dynamic_stage.h"
#include "dda/static_stage.h"
#include "dda/system.h"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace ddafem
{
/// What the stages of a run did, gathered for summary.json.
struct StageTotals
{
  std::size_t n_cut_steps = 0, n_penalty_raises = 0, n_flips_ignored = 0, n_reversals = 0;
  std::map<dda::StepOutcome, std::size_t> cuts_by_cause; ///< of every stage's TimeStepper
  double smallest_dt = 0.0;                              ///< of the accepted steps [s]
  nlohmann::json records = nlohmann::json::array();      ///< one per stage run
  dda::StepStatus failure; ///< outcome success unless a stage stopped the run

  void add(const dda::StaticStageResult& result);
  void add(const dda::DynamicStageResult& result);
  bool failed() const { return failure.outcome != dda::StepOutcome::success; }
};

/// Everything summary.json says about a run that has ended (completed or not).
struct RunRecord
{
  const Scene& scene;
  const dda::System& system;
  CoupledParts coupled;
  const StageTotals& stages;
  const RunOutputs& outputs;
  const KeyblockRecorder& keyblocks;
  const std::vector<std::string>& warnings;
  double wall_time = 0.0; ///< [s]
};

nlohmann::json run_summary(const RunRecord& run);

/// Everything summary.json says about a run of a far field alone that has ended.
struct FarFieldRunRecord
{
  const Scene& scene;
  const fem::ElasticWaveModel& model;
  const fem::StepStatus& failure; ///< outcome success if the run completed
  const FarFieldOutputs& outputs;
  const std::vector<std::string>& warnings;
  double wall_time = 0.0; ///< [s]
};

nlohmann::json far_field_run_summary(const FarFieldRunRecord& run);

} // namespace ddafem
