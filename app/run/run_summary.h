// summary.json of a run (docs/outputs.md). Blocks (alone or tied to a far field): status, time
// steps and their cuts, stages, the model, the far field and the interface, contacts, timings,
// energies, keyblocks and outputs. A far field alone: status, steps, solver, model, timings,
// energies and outputs (app/far_field_module/far_field_outputs.cc).
#pragma once

#include "app/run/keyblocks.h"
#include "app/run/run_outputs.h"
#include "app/scene/scene.h"
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
  const TiedFarField* tied; ///< null for blocks alone
  const StageTotals& stages;
  const RunOutputs& outputs;
  const KeyblockRecorder& keyblocks;
  const std::vector<std::string>& warnings;
  double wall_time = 0.0; ///< [s]
};

nlohmann::json run_summary(const RunRecord& run);

/// Makes a completed run's status "completed_energy_source", with the reason in
/// `energy_source`, if its viscous boundaries fed energy in (net work above 1 % of what the
/// loads, supports and ties put in): a boundary beyond its stability limit, run with
/// --allow-unstable, whose growth stayed below the run's stop at 10 times the input.
void mark_energy_source(nlohmann::json& summary, const dda::EnergyBalance& e);

/// The fields every summary.json opens with: the scene, the program's version, the status (and
/// the failure), the time reached and the end time [s], the steps and dt [s].
nlohmann::json summary_head(const Scene& scene, bool failed, const std::string& failure,
                            double time_reached, double end_time, std::size_t n_steps, double dt);
/// The recorded ground motions of a scene (`record` time functions), each with where it acts,
/// what it is and its measures; empty if none.
nlohmann::json records_summary(const Scene& scene);

/// The wall time [s], the peak memory and the warnings of a run.
void add_run_facts(nlohmann::json& summary, double wall_time,
                   const std::vector<std::string>& warnings);

} // namespace ddafem
