// The `run` command: one driver for every kind of scene (blocks alone, blocks tied to a far
// field, a far field alone), each a Simulation (app/run/simulation.h).
#include "app/run/run.h"

#include "app/far_field_module/far_field_module.h"
#include "app/run/checkpoint.h"
#include "app/run/run_summary.h"
#include "app/run/run_support.h"
#include "app/run/simulation.h"

#include "common/format.h"
#include "common/input_error.h"
#include "common/resource_limits.h"
#include "common/stopwatch.h"

#include <boost/archive/archive_exception.hpp>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

namespace ddafem
{
namespace
{
/// A run: set up, its stages in turn, the summary. From the start to the end, summary.json says
/// "running" with the time reached at the last flush of the histories (every
/// output.flush_interval of wall time), so that a killed run is told from a finished one.
class SceneRun
{
public:
  SceneRun(const Scene& scene_, const RunOptions& options_, std::ostream& log_,
           CheckpointReader* resume_from_)
      : scene(scene_), options(options_), log(log_), resume_from(resume_from_)
  {
  }

  /// Returns the exit code (run_scene).
  int run()
  {
    setup();
    try
    {
      const std::size_t first_stage = resume_from ? open_resumed_outputs() : open_outputs();
      for (std::size_t k = first_stage; k < simulation->n_stages(); ++k)
        if (!simulation->run_stage(k, [this] { return after_step(); }))
        {
          // Under mpirun a budget that another rank reached stops this one after the same step
          // (its own budget not reached): stopped too, not completed.
          if (stop_reason.empty() && simulation->end().failure.empty())
            stop_reason = "another MPI rank reached its budget";
          break;
        }
      return write_summary();
    }
    catch (const std::exception& e)
    {
      write_error_summary(e.what());
      throw;
    }
  }

private:
  void setup();
  /// Returns the stage to start with: the first.
  std::size_t open_outputs();
  /// Restores the checkpoint and reopens its outputs; returns the stage to go on with.
  std::size_t open_resumed_outputs();
  /// The header of this run's checkpoints.
  CheckpointHeader checkpoint_header() const;
  int write_summary();
  /// summary.json of a run stopped by an error (an output that cannot be written): status
  /// "error" and the message, if it can still be written; else the running one stays.
  void write_error_summary(const std::string& message) const;
  nlohmann::json summary_so_far(const std::string& status, double wall) const;
  /// Progress, flushes, and the budgets: false stops the run after this step.
  bool after_step()
  {
    const double wall = seconds_since(wall_start);
    progress->update(simulation->n_steps(), simulation->time(), wall, false);
    if (wall - last_flush >= scene.output.flush_interval)
      flush(wall);
    stop_reason = budget_exceeded(wall);
    if (options.stop_at_first_fall && stop_reason.empty())
      if (const std::optional<std::size_t> block = simulation->fallen_keyblock())
        stop_reason = "keyblock " + std::to_string(*block) + " fell (--stop-at-first-fall)";
    const double every = scene.output.checkpoint_every;
    if (every > 0.0 && simulation->can_checkpoint() &&
        (wall - last_checkpoint >= every || !stop_reason.empty()))
    {
      // The histories in the file must hold every row the checkpoint counts.
      flush(wall);
      const auto start = Clock::now();
      checkpoint_bytes = write_checkpoint(dir, header, *simulation);
      checkpoint_seconds += seconds_since(start);
      ++n_checkpoints;
      last_checkpoint = wall;
    }
    return stop_reason.empty();
  }
  /// Why the run must stop now (empty: it goes on): --max-wall-time reached, or the resident
  /// memory above --max-memory (read at most ten times a second).
  std::string budget_exceeded(double wall);
  /// Flushes the histories to disk, then says so in the running summary.json.
  void flush(double wall);

  const Scene& scene;
  const RunOptions& options;
  std::ostream& log;
  CheckpointReader* resume_from; ///< null: a new run
  CheckpointHeader header;
  const Clock::time_point wall_start = Clock::now();
  std::unique_ptr<Simulation> simulation;
  std::filesystem::path dir;
  std::vector<std::string> warnings;
  std::optional<run_support::Progress> progress;
  double last_flush = 0.0;          ///< wall time of the last flush [s]
  double last_checkpoint = 0.0;     ///< wall time of the last checkpoint [s]
  std::size_t n_checkpoints = 0;    ///< written by this process
  double checkpoint_seconds = 0.0;  ///< spent writing them [s]
  std::size_t checkpoint_bytes = 0; ///< size of the last
  std::optional<double> resumed_at; ///< a resumed run: the checkpoint's time [s]
  double last_memory_check = 0.0;   ///< wall time of the last look at the memory [s]
  std::string stop_reason;          ///< why a budget stopped the run; empty if none did
};

std::string SceneRun::budget_exceeded(double wall)
{
  if (options.max_wall_time > 0.0 && wall >= options.max_wall_time)
    return "the wall-time budget of " + format_significant(options.max_wall_time) +
           " s (--max-wall-time) was reached";
  if (options.max_memory > 0.0 && wall - last_memory_check >= 0.1)
  {
    last_memory_check = wall;
    const double resident = run_support::resident_memory_bytes();
    if (resident > options.max_memory)
      return "the memory budget of " + format_bytes(options.max_memory) +
             " (--max-memory) was exceeded: " + format_bytes(resident) + " resident";
  }
  return {};
}

/// Builds the models and collects the warnings, refusing unstable boundaries unless allowed:
/// input errors surface here, before anything is written.
void SceneRun::setup()
{
  const std::optional<unsigned int> rank = run_support::mpi_rank_from_environment();
  const bool far_field_alone = scene.far_field && !scene.coupled();
  if (rank && !scene.far_field)
    throw InputError(scene.file + ": started by mpirun, but the scene has no far field: only a "
                                  "far field is distributed (issue 22), the blocks run on every "
                                  "rank; expected a scene with a far field, or a run without "
                                  "mpirun");
  if (rank && resume_from)
    throw InputError("a run distributed with mpirun cannot be resumed yet: run it again");
  // Under mpirun a coupled scene's far field is distributed (FarFieldModule::tie).
  simulation = !far_field_alone ? make_blocks_simulation(scene)
               : rank           ? far_field_module().distributed_far_field_simulation(scene)
                                : far_field_module().far_field_simulation(scene);
  warnings = simulation->collect_warnings(options.allow_unstable);
  warnings.insert(warnings.begin(), scene.warnings.begin(), scene.warnings.end());
  dir = options.output_directory.empty() ? scene.output.directory : options.output_directory;
  if (rank && *rank > 0) // the driver's own files of the other ranks
                         // (app/far_field_module/distributed_far_field.cc)
    dir = dir / "ranks" / ("rank_" + std::to_string(*rank));
  header = checkpoint_header();
}

CheckpointHeader SceneRun::checkpoint_header() const
{
  if (resume_from)
    return resume_from->header();
  CheckpointHeader h;
  h.version = DDAFEM_VERSION;
  h.scene_file = std::filesystem::absolute(scene.file).string();
  h.scene_text = scene_file_text(scene.file);
  h.settings = options.settings;
  h.allow_unstable = options.allow_unstable;
  return h;
}

/// Creates the output directory, clears an earlier run's results from it and opens the
/// outputs, with summary.json "running".
std::size_t SceneRun::open_outputs()
{
  run_support::create_output_directory(dir);
  if (const std::size_t n = run_support::clear_earlier_results(dir); n > 0)
    log << "cleared " << n << " files of an earlier run from " << dir.string() << "\n";
  for (const std::string& w : warnings)
    log << "warning: " << w << "\n";
  if (scene.tunnel)
    run_support::write_text_file(dir / "expanded_scene.yaml",
                                 "# The scene " + scene.file +
                                     " as its `tunnel` section expanded it (ddafem check prints "
                                     "why)\n" +
                                     scene.expanded_yaml + "\n");
  simulation->open_outputs(dir);
  flush(seconds_since(wall_start));
  progress.emplace(!options.quiet && isatty(fileno(stderr)), simulation->end_time());
  return 0;
}

std::size_t SceneRun::open_resumed_outputs()
{
  for (const std::string& w : warnings)
    log << "warning: " << w << "\n";
  std::size_t stage = 0;
  try
  {
    stage = simulation->resume(resume_from->archive(), dir);
  }
  catch (const boost::archive::archive_exception& e)
  {
    throw InputError(resume_from->file().string() + ": cannot be restored (" + e.what() +
                     "): expected a checkpoint of this scene; run it again");
  }
  catch (const std::runtime_error& e)
  {
    throw InputError(resume_from->file().string() + ": cannot be restored: " + e.what());
  }
  resumed_at = simulation->time();
  log << "resumed " << dir.string() << " at t = " << format_significant(simulation->time())
      << " s, step " << simulation->n_steps() << "\n";
  flush(seconds_since(wall_start));
  progress.emplace(!options.quiet && isatty(fileno(stderr)), simulation->end_time());
  return stage;
}

void SceneRun::flush(double wall)
{
  simulation->flush_outputs();
  last_flush = wall;
  run_support::write_text_file(dir / "summary.json",
                               summary_so_far("running", wall).dump(2) + "\n");
}

nlohmann::json SceneRun::summary_so_far(const std::string& status, double wall) const
{
  return {{"scene", scene.file},
          {"name", scene.name},
          {"version", DDAFEM_VERSION},
          {"status", status},
          {"pid", static_cast<long>(getpid())},
          {"time_reached_s", simulation->time()},
          {"end_time_s", simulation->end_time()},
          {"steps", simulation->n_steps()},
          {"wall_time_s", wall},
          {"histories_flushed_at_wall_time_s", last_flush},
          {"flush_interval_s", scene.output.flush_interval}};
}

void SceneRun::write_error_summary(const std::string& message) const
{
  nlohmann::json summary = summary_so_far("error", seconds_since(wall_start));
  summary["failure"] = message;
  try
  {
    run_support::write_text_file(dir / "summary.json", summary.dump(2) + "\n");
  }
  catch (const std::exception&)
  {
    // The disk that failed the run fails this too: the running summary.json stays.
  }
}

/// Ends the outputs, writes summary.json and the run's last lines on the log.
int SceneRun::write_summary()
{
  progress->update(simulation->n_steps(), simulation->time(), seconds_since(wall_start), true);
  progress->finish();
  simulation->close_outputs();
  const double wall = seconds_since(wall_start);
  const RunEnd end = simulation->end();
  nlohmann::json summary = simulation->summary(warnings, wall);
  if (!stop_reason.empty())
  {
    summary["status"] = "stopped";
    summary["stopped"] = stop_reason;
  }
  if (nlohmann::json records = records_summary(scene); !records.empty())
    summary["records"] = std::move(records);
  summary["checkpoints"] = {{"every_s", scene.output.checkpoint_every},
                            {"written", n_checkpoints},
                            {"seconds", checkpoint_seconds},
                            {"last_bytes", checkpoint_bytes},
                            {"resumed_at_s", resumed_at ? nlohmann::json(*resumed_at) : nullptr}};
  if (stop_reason.empty())
  {
    // An ended run (completed or failed) has nothing to resume: its checkpoint goes.
    std::error_code ignored;
    std::filesystem::remove(checkpoint_path(dir), ignored);
  }
  return run_support::finish_run(dir, summary, end.failure, end.steps, end.time, wall,
                                 end.view_file, log);
}
} // namespace

int run_scene(const Scene& scene, const RunOptions& options, std::ostream& log,
              CheckpointReader* resume_from)
{
  SceneRun run(scene, options, log, resume_from);
  return run.run();
}

} // namespace ddafem
