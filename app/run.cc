// The `run` command: one driver for every kind of scene (blocks alone, blocks tied to a far
// field, a far field alone), each a Simulation (app/simulation.h).
#include "app/run.h"

#include "app/far_field_module.h"
#include "app/run_support.h"
#include "app/simulation.h"

#include "common/stopwatch.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <memory>

namespace ddafem
{
namespace
{
/// A run: set up, its stages in turn, the summary.
class SceneRun
{
public:
  SceneRun(const Scene& scene_, const RunOptions& options_, std::ostream& log_)
      : scene(scene_), options(options_), log(log_)
  {
  }

  /// Returns the exit code (run_scene).
  int run()
  {
    setup();
    for (std::size_t k = 0; k < simulation->n_stages(); ++k)
      if (!simulation->run_stage(k, [this] { report_progress(); }))
        break;
    return write_summary();
  }

private:
  void setup();
  int write_summary();
  void report_progress(bool force = false)
  {
    progress->update(simulation->n_steps(), simulation->time(), seconds_since(wall_start), force);
  }

  const Scene& scene;
  const RunOptions& options;
  std::ostream& log;
  const Clock::time_point wall_start = Clock::now();
  std::unique_ptr<Simulation> simulation;
  std::filesystem::path dir;
  std::vector<std::string> warnings;
  std::optional<run_support::Progress> progress;
};

/// Builds the models (input errors surface here, before anything is written), creates the
/// output directory, collects the warnings (refusing unstable boundaries unless allowed) and
/// opens the outputs.
void SceneRun::setup()
{
  simulation = scene.far_field && !scene.coupled() ? far_field_module().far_field_simulation(scene)
                                                   : make_blocks_simulation(scene);
  dir = options.output_directory.empty() ? scene.output.directory : options.output_directory;
  run_support::create_output_directory(dir);
  if (scene.tunnel)
    run_support::write_text_file(dir / "expanded_scene.yaml",
                                 "# The scene " + scene.file +
                                     " as its `tunnel` section expanded it (ddafem check prints "
                                     "why)\n" +
                                     scene.expanded_yaml + "\n");
  warnings = simulation->collect_warnings(options.allow_unstable);
  for (const std::string& w : warnings)
    log << "warning: " << w << "\n";
  simulation->open_outputs(dir);
  progress.emplace(!options.quiet && isatty(fileno(stderr)), simulation->end_time());
}

/// Ends the outputs, writes summary.json and the run's last lines on the log.
int SceneRun::write_summary()
{
  report_progress(true);
  progress->finish();
  simulation->close_outputs();
  const double wall = seconds_since(wall_start);
  const RunEnd end = simulation->end();
  return run_support::finish_run(dir, simulation->summary(warnings, wall), end.failure, end.steps,
                                 end.time, wall, end.view_file, log);
}
} // namespace

int run_scene(const Scene& scene, const RunOptions& options, std::ostream& log)
{
  SceneRun run(scene, options, log);
  return run.run();
}

} // namespace ddafem
