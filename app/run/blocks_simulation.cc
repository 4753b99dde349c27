// A run of blocks, alone or tied to a far field, behind the driver's Simulation interface: the
// scene's stages (or one dynamic stage to the end time), each static or dynamic, with the
// keyblocks followed and the outputs written as the steps go.
#include "app/far_field_module/far_field_module.h"
#include "app/run/checkpoint_types.h"
#include "app/run/keyblocks.h"
#include "app/run/run_outputs.h"
#include "app/run/run_summary.h"
#include "app/run/run_support.h"
#include "app/run/run_warnings.h"
#include "app/run/simulation.h"
#include "app/run/stage_records.h"

#include "common/checkpoint_archive.h"
#include "common/format.h"
#include "common/input_error.h"
#include "dda/dynamic_stage.h"
#include "dda/static_stage.h"
#include "dda/system.h"
#include "dda/time_step_advice.h"
#include "dda/time_stepper.h"

#include <optional>
#include <sstream>

namespace ddafem
{
namespace
{

/// The scene's stages, or one dynamic stage to the end time if it has none.
std::vector<dda::Stage> stage_plan(const dda::ModelDescription& model)
{
  std::vector<dda::Stage> plan = model.stages;
  if (plan.empty())
  {
    dda::Stage only;
    only.name = "dynamic";
    only.end_time = model.time.end_time;
    plan.push_back(only);
  }
  return plan;
}

class BlocksSimulation : public Simulation
{
public:
  explicit BlocksSimulation(const Scene& scene);

  std::vector<std::string> collect_warnings(bool allow_unstable) const override;
  void open_outputs(const std::filesystem::path& dir) override
  {
    outputs.emplace(dir, scene.file, system, tied.get(), keyblocks, scene.output.vtu_compression);
  }
  std::size_t n_stages() const override { return plan.size(); }
  bool run_stage(std::size_t k, const std::function<bool()>& report) override;
  void close_outputs() override;
  void flush_outputs() override { outputs->flush(); }
  bool can_checkpoint() const override
  {
    return (stage_run || static_run) && (!tied || tied->can_checkpoint());
  }
  void save_checkpoint(CheckpointOut& archive) const override;
  std::size_t resume(CheckpointIn& archive, const std::filesystem::path& dir) override;
  std::optional<std::size_t> fallen_keyblock() const override { return keyblocks.first_fallen(); }
  std::size_t n_steps() const override { return system.n_steps(); }
  double time() const override { return system.time(); }
  double end_time() const override { return scene.model.time.end_time; }
  nlohmann::json summary(const std::vector<std::string>& warnings, double wall_time) const override
  {
    return run_summary(
        {scene, system, tied.get(), stages, *outputs, keyblocks, warnings, wall_time});
  }
  RunEnd end() const override;

private:
  void run_static_stage(const dda::Stage& stage, const std::function<bool()>& report);
  void run_dynamic_stage(const dda::Stage& stage, const std::function<bool()>& report);
  /// The dynamic stage's start, unless it resumes from a checkpoint.
  void begin_dynamic_stage();
  /// After each accepted step of a dynamic stage: its outputs, then `report`.
  bool after_dynamic_step(const dda::TimeStepper& stepper, const dda::StepStatus& status, bool last,
                          const std::function<bool()>& report);
  /// A resumed run: the checkpoint's state of its stage into `run`, once.
  template <class StageRun>
  void load_resumed_stage(StageRun& run)
  {
    if (resumed_stage.empty())
      return;
    std::istringstream text(resumed_stage);
    CheckpointIn archive(text);
    run.load(archive);
    resumed_stage.clear();
  }
  /// save_checkpoint and resume: the run's own state around the System's and the stage's.
  template <class Archive>
  void transfer_run_state(Archive& archive);

  const Scene& scene;
  const std::vector<dda::Stage> plan;
  dda::System system;
  std::unique_ptr<TiedFarField> tied; ///< the far field tied to the blocks, if any
  KeyblockRecorder keyblocks;
  std::optional<RunOutputs> outputs;
  StageTotals stages;
  LastStep last_step;
  bool initial_written = false;
  bool stopped = false; ///< a stage stopped at a budget (report returned false)
  std::optional<std::vector<dda::Vector2>> fall_reference; ///< per block [m]
  std::optional<dda::DynamicStageRun> stage_run;           ///< the dynamic stage running, if any
  std::optional<dda::StaticStageRun> static_run;           ///< the static stage running, if any
  std::size_t current_stage = 0;
  /// Steps of the running dynamic stage as the user sets dt: with bathe one step is two System
  /// half steps.
  std::size_t stage_steps = 0;
  double next_snapshot = 0.0; ///< [s]
  /// A resumed run: the checkpoint's state of the stage to continue (empty otherwise), an
  /// archive of its own: the stage's run is built when run_stage reaches it.
  std::string resumed_stage;
};

BlocksSimulation::BlocksSimulation(const Scene& scene_)
    : scene(scene_), plan(stage_plan(scene.model)), system(scene.model), keyblocks(scene.model)
{
  if (scene.coupled())
    tied = far_field_module().tie(scene, system);
  stages.smallest_dt = scene.model.time.dt;
}

std::vector<std::string> BlocksSimulation::collect_warnings(bool allow_unstable) const
{
  const dda::TimeSettings& time = scene.model.time;
  std::vector<std::string> found;
  for (const std::string& w : unstable_boundary_messages(system, time.dt))
  {
    if (!allow_unstable)
      throw InputError(w + ": expected a smaller time.dt, or --allow-unstable to watch it fail");
    found.push_back(w + " (run with --allow-unstable)");
  }
  if (tied)
    if (std::string w = tied->impedance_warning(); !w.empty())
      found.push_back(std::move(w));
  const dda::TimeStepAdvice advice = dda::suggest_time_step(scene.model);
  if (time.dt > advice.dt_max)
    found.push_back("dt = " + format_significant(time.dt) + " s exceeds the suggested " +
                    format_significant(advice.dt_max, 3) + " s (" + time_step_reason(advice) + ")");
  if (scene.rock_mass && !scene.rock_mass->slivers.empty())
    found.push_back("rock_mass: " + std::to_string(scene.rock_mass->slivers.size()) +
                    " blocks below the sliver threshold kept (`check` lists them)");
  return found;
}

bool BlocksSimulation::run_stage(std::size_t k, const std::function<bool()>& report)
{
  current_stage = k;
  const dda::Stage& stage = plan[k];
  // Across MPI ranks a budget one rank reaches stops every rank after the same step.
  const std::function<bool()> agreed = [&]
  {
    const bool go = report();
    return tied ? tied->all_go_on(go) : go;
  };
  if (stage.mode == dda::StageMode::static_equilibrium)
    run_static_stage(stage, agreed);
  else
    run_dynamic_stage(stage, agreed);
  return !stages.failed() && !stopped;
}

void BlocksSimulation::run_static_stage(const dda::Stage& stage,
                                        const std::function<bool()>& report)
{
  if (resumed_stage.empty())
    system.begin_stage(dda::StageMode::static_equilibrium);
  static_run.emplace(system, stage, scene.model.time);
  load_resumed_stage(*static_run);
  const dda::StaticStageResult result = static_run->run(report);
  static_run.reset();
  stages.add(result);
  stopped = result.stopped;
  for (const dda::ReleasedBlock& r : result.released)
  {
    keyblocks.mark_released(r.block);
    if (stage.release == dda::ReleaseAction::remove)
      keyblocks.mark_removed(r.block);
  }
  stages.records.push_back(static_stage_record(stage, result, system, keyblocks));
  if (!result.stopped)
    stages.failure = static_stage_failure(stage, result, system);
}

void BlocksSimulation::begin_dynamic_stage()
{
  system.begin_stage(dda::StageMode::dynamic);
  if (!fall_reference)
  {
    // Falls in settle stages are measured from the first dynamic stage's start.
    fall_reference.emplace();
    for (const dda::Block& b : system.blocks().list)
      fall_reference->push_back(b.displacement());
  }
  if (!initial_written)
  {
    outputs->write_state(true, last_step);
    initial_written = true;
  }
  stage_steps = 0;
  next_snapshot = system.time() + scene.output.interval;
}

bool BlocksSimulation::after_dynamic_step(const dda::TimeStepper& stepper,
                                          const dda::StepStatus& status, bool last,
                                          const std::function<bool()>& report)
{
  const dda::TimeSettings& time = scene.model.time;
  last_step = {stepper.last_dt(), status.n_open_close_iterations, stepper.n_last_step_cuts()};
  const bool snapshot =
      run_support::snapshot_due(system.time(), scene.output.interval, time.dt, next_snapshot) ||
      last;
  ++stage_steps;
  if (stage_steps % scene.output.history_every == 0 || last || snapshot)
    outputs->write_state(snapshot, last_step);
  return report();
}

void BlocksSimulation::run_dynamic_stage(const dda::Stage& stage,
                                         const std::function<bool()>& report)
{
  if (resumed_stage.empty())
    begin_dynamic_stage();
  stage_run.emplace(system, stage, scene.model.time, *fall_reference);
  load_resumed_stage(*stage_run);
  const dda::DynamicStageResult result =
      stage_run->run([&](const dda::TimeStepper& stepper, const dda::StepStatus& status, bool last)
                     { return after_dynamic_step(stepper, status, last, report); });
  stage_run.reset();
  stages.add(result);
  stopped = result.stopped;
  for (const auto& [block, when] : result.removed)
    keyblocks.mark_removed(block);
  stages.records.push_back(dynamic_stage_record(stage, result, system, keyblocks));
  stages.failure = result.failure;
}

template <class Archive>
void BlocksSimulation::transfer_run_state(Archive& a)
{
  transfer_object(a, system);
  if (tied)
    transfer_object(a, *tied);
  transfer_object(a, keyblocks);
  transfer_stage_totals(a, stages);
  transfer_all(a, last_step.dt, last_step.n_open_close_iterations, last_step.n_cuts,
               initial_written);
  transfer_optional(a, fall_reference);
  transfer_all(a, current_stage, stage_steps, next_snapshot);
}

void BlocksSimulation::save_checkpoint(CheckpointOut& archive) const
{
  transfer_marker(archive, "blocks simulation");
  std::ostringstream text;
  {
    CheckpointOut stage_archive(text);
    if (stage_run)
      stage_run->save(stage_archive);
    else
      static_run->save(stage_archive);
  }
  archive << text.str();
  const_cast<BlocksSimulation*>(this)->transfer_run_state(archive);
  outputs->save(archive);
}

std::size_t BlocksSimulation::resume(CheckpointIn& archive, const std::filesystem::path& dir)
{
  transfer_marker(archive, "blocks simulation");
  archive >> resumed_stage;
  transfer_run_state(archive);
  outputs.emplace(dir, system, tied.get(), keyblocks, scene.output.vtu_compression, archive);
  return current_stage;
}

void BlocksSimulation::close_outputs()
{
  // Keep the state reached readable (a static-only analysis writes its equilibrium here).
  if (stages.failed() || stopped || !initial_written)
    outputs->write_state(true, last_step);
  outputs->flush();
}

RunEnd BlocksSimulation::end() const
{
  return {stages.failed() ? stages.failure.message : std::string(),
          std::to_string(system.n_steps()) +
              (scene.model.time.integrator == dda::Integrator::bathe ? " half steps" : " steps"),
          system.time(), "model.pvd"};
}
} // namespace

std::unique_ptr<Simulation> make_blocks_simulation(const Scene& scene)
{
  return std::make_unique<BlocksSimulation>(scene);
}

} // namespace ddafem
