// A run of a far field alone (deal.II continuum, issue 5; module side) behind the driver's
// Simulation interface: one stage of the scene's steps of dt to its end time.
#include "app/far_field_module/far_field_parts.h"
#include "app/run/run_support.h"
#include "common/checkpoint_archive.h"

#include <cmath>
#include <optional>

namespace ddafem
{
namespace
{
class FarFieldSimulation : public Simulation
{
public:
  explicit FarFieldSimulation(const Scene& scene_)
      : scene(scene_), description(*scene.far_field), model(description)
  {
  }

  /// A far field alone has nothing to warn about.
  std::vector<std::string> collect_warnings(bool) const override { return {}; }
  /// Opens the outputs and writes the initial state.
  void open_outputs(const std::filesystem::path& dir) override
  {
    outputs.emplace(dir, scene.file, model, description, scene.output.vtu_compression);
    outputs->write_state(true);
  }
  std::size_t n_stages() const override { return 1; }
  bool run_stage(std::size_t k, const std::function<bool()>& report) override;
  void close_outputs() override
  {
    if (failed() || stopped)
      outputs->write_state(true);
    outputs->flush();
  }
  void flush_outputs() override { outputs->flush(); }
  bool can_checkpoint() const override { return running; }
  void save_checkpoint(CheckpointOut& archive) const override
  {
    transfer_marker(archive, "far-field simulation");
    archive << step << next_snapshot;
    model.save(archive);
    outputs->save(archive);
  }
  std::size_t resume(CheckpointIn& archive, const std::filesystem::path& dir) override
  {
    transfer_marker(archive, "far-field simulation");
    archive >> step >> next_snapshot;
    model.load(archive);
    outputs.emplace(dir, model, description, scene.output.vtu_compression, archive);
    resumed = true;
    return 0;
  }
  std::size_t n_steps() const override { return model.timings().n_steps; }
  double time() const override { return model.time(); }
  double end_time() const override { return description.end_time; }
  nlohmann::json summary(const std::vector<std::string>& warnings, double wall_time) const override
  {
    return far_field_run_summary({scene, model, failure, *outputs, warnings, wall_time});
  }
  RunEnd end() const override
  {
    return {failed() ? failure.why : std::string(),
            std::to_string(model.timings().n_steps) + " steps", model.time(), "far_field.pvd"};
  }

private:
  bool failed() const { return !failure.taken; }

  const Scene& scene;
  const fem::FarFieldDescription& description;
  fem::ElasticWaveModel model;
  std::optional<FarFieldOutputs> outputs;
  StepResult failure;         ///< outcome success unless a step failed
  bool stopped = false;       ///< stopped at a budget (report returned false)
  bool running = false;       ///< between two steps of run_stage
  bool resumed = false;       ///< run_stage goes on from a checkpoint's step
  std::size_t step = 0;       ///< steps taken
  double next_snapshot = 0.0; ///< [s]
};

bool FarFieldSimulation::run_stage(std::size_t, const std::function<bool()>& report)
{
  const double dt = description.dt;
  const auto n_steps = static_cast<std::size_t>(std::llround(description.end_time / dt));
  if (!resumed)
  {
    step = 0;
    next_snapshot = scene.output.interval;
  }
  running = true;
  while (step < n_steps)
  {
    const StepResult status = model.advance(dt);
    if (!status.taken)
    {
      failure = status;
      running = false;
      return false;
    }
    ++step;
    const bool last = step == n_steps;
    const bool snapshot =
        run_support::snapshot_due(model.time(), scene.output.interval, dt, next_snapshot) || last;
    if (step % scene.output.history_every == 0 || snapshot)
      outputs->write_state(snapshot);
    if (!report())
    {
      stopped = !last;
      running = false;
      return last;
    }
  }
  running = false;
  return true;
}
} // namespace

std::unique_ptr<Simulation> make_far_field_simulation(const Scene& scene)
{
  return std::make_unique<FarFieldSimulation>(scene);
}

} // namespace ddafem
