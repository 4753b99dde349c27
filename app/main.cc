// ddafem command line: check and run scenes (CLI11: subcommands, each with --help).
//
//   ddafem check SCENE [--set key=value]...
//   ddafem run SCENE [-o DIR] [--quiet] [--allow-unstable] [--set key=value]...
//   ddafem resume DIR [--quiet] [--max-wall-time S] [--max-memory SIZE]
//   ddafem sweep SCENE --key KEY [--find first_fall|displacement] [--threshold M] [-o DIR] ...
//   ddafem ensemble SCENE -n N [-o DIR] [--vary KEY=DIST]... [--roundoff [KEY]] [--seed S] ...
//   ddafem fragility SCENE --key KEY [--levels V1,V2,...] [--members M] [-o DIR] ...
//   ddafem scene-reference
//
// Exit codes: 0 success, 1 numerical failure (or an I/O failure while writing results),
// 2 bad input (scene, command line, missing file, a scene too large for memory), 3 stopped at a
// budget (--max-wall-time, --max-memory).
#include "app/far_field_module/far_field_module.h"
#include "app/run/checkpoint.h"
#include "app/run/run.h"
#include "app/run/run_support.h"
#include "app/scene/scene.h"
#include "app/studies/ensemble.h"
#include "app/studies/fragility.h"
#include "app/studies/sweep.h"
#include "common/input_error.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <malloc.h>
#include <optional>
#include <string>
#include <vector>

namespace
{
/// What the command line asks for.
struct CommandLine
{
  std::string scene;
  std::vector<std::string> settings; ///< --set key=value, in the order given
  std::string max_memory;            ///< --max-memory SIZE; empty: 90 % of what is available
  std::string directory;             ///< resume: the output directory of the run
  ddafem::RunOptions options;
};

/// The `--set` option and the scene argument that check and run share.
void add_scene_arguments(CLI::App& command, CommandLine& cl)
{
  command.add_option("SCENE", cl.scene, "the scene file (YAML)")->required();
  command
      .add_option("--set", cl.settings,
                  "override any scene key, e.g. --set time.dt=1e-4 (repeatable)")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  command
      .add_option("--max-memory", cl.max_memory,
                  "refuse a scene estimated to need more memory, e.g. 8G (default: 90 % of the "
                  "memory available); `run` also stops cleanly, exit code 3, if it uses more")
      ->type_name("SIZE");
}

/// Freed memory stays in the process's heap: glibc otherwise maps blocks above 128 KiB afresh
/// on each allocation and unmaps them on free, and trims the heap's top. With a second thread
/// (--threads 2, a far field's step), every unmap stops the other core to flush its address
/// translations; on this project's 2-core virtual machines that made the serial phases of the
/// 2000-block collapsing wall twice as slow and two threads slower than one (narrow phase 0.82 s
/// against 0.58 s over its first 98 steps; 0.46 s with this). The peak memory is unchanged
/// (within 1 MiB); memory freed after the peak is kept for reuse.
void keep_freed_memory()
{
  mallopt(M_MMAP_THRESHOLD, 32 << 20); // glibc's largest: blocks up to 32 MiB from the heap
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
}

/// Reads a scene with its --set overrides against the memory limit (--max-memory), and the run's
/// options with the settings kept for checkpoints.
ddafem::Scene read_scene_for(const CommandLine& cl, const std::string& file,
                             const std::vector<std::string>& settings, ddafem::RunOptions& options)
{
  std::vector<ddafem::Override> overrides;
  for (const std::string& s : settings)
    overrides.push_back(ddafem::parse_override(s));
  const ddafem::ResourceLimits limits = cl.max_memory.empty()
                                            ? ddafem::ResourceLimits::of_this_machine()
                                            : ddafem::ResourceLimits::given(cl.max_memory);
  ddafem::Scene scene = ddafem::read_scene(file, overrides, limits);
  options = cl.options;
  options.settings = settings;
  if (!cl.max_memory.empty())
    options.max_memory = limits.memory; // also a budget while the run runs
  scene.model.solver.threads = cl.options.threads;
  return scene;
}

/// Reads the scene and checks or runs it; returns the exit code.
int check_or_run(const CommandLine& cl, bool run)
{
  ddafem::RunOptions options;
  const ddafem::Scene scene = read_scene_for(cl, cl.scene, cl.settings, options);
  try
  {
    if (!run)
    {
      std::cout << ddafem::check_scene(scene);
      return 0;
    }
    // Under mpirun the other ranks run quietly beside rank 0
    // (app/far_field_module/distributed_far_field.cc).
    const std::optional<unsigned int> rank = ddafem::run_support::mpi_rank_from_environment();
    std::ofstream nowhere; // never opened: what the other ranks would print is dropped
    if (rank && *rank > 0)
      options.quiet = true;
    return ddafem::run_scene(scene, options, rank && *rank > 0 ? nowhere : std::cout);
  }
  catch (const ddafem::InputError& e)
  {
    // Problems only the engine sees (e.g. blocks sharing an edge without a joint material).
    throw ddafem::InputError(scene.file + ": " + e.what());
  }
}

/// Continues the run whose checkpoint is in cl.directory, or the ensemble whose report is there;
/// returns the exit code.
int resume(const CommandLine& cl)
{
  if (std::filesystem::exists(std::filesystem::path(cl.directory) / "ensemble.json"))
    return ddafem::resume_ensemble(cl.directory, cl.options.quiet, cl.options.threads, std::cerr);
  ddafem::CheckpointReader checkpoint(cl.directory);
  const ddafem::CheckpointHeader& header = checkpoint.header();
  if (ddafem::scene_file_text(header.scene_file) != header.scene_text)
    throw ddafem::InputError(header.scene_file + ": changed or missing since the run in " +
                             cl.directory +
                             " started: expected the scene it ran (or run it again)");
  ddafem::RunOptions options;
  const ddafem::Scene scene = read_scene_for(cl, header.scene_file, header.settings, options);
  options.output_directory = cl.directory;
  options.allow_unstable = header.allow_unstable;
  return ddafem::run_scene(scene, options, std::cout, &checkpoint);
}

/// The `sweep` command's options.
void add_sweep_options(CLI::App& command, ddafem::SweepOptions& o)
{
  command.add_option("SCENE", o.scene, "the scene file (YAML)")->required();
  command.add_option("--key", o.key, "the scene key to sweep, e.g. tunnel.wave.velocity.amplitude")
      ->required();
  command
      .add_option("--find", o.find,
                  "first_fall: the smallest value at which a keyblock falls (not one the "
                  "excavation released); displacement: at which a keyblock's residual "
                  "displacement relative to the rock exceeds --threshold")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, ddafem::SweepCriterion>{
              {"first_fall", ddafem::SweepCriterion::first_fall},
              {"displacement", ddafem::SweepCriterion::displacement}},
          CLI::ignore_case));
  command.add_option("--threshold", o.threshold, "[m] for --find displacement")
      ->check(CLI::PositiveNumber);
  command.add_option("--low", o.low,
                     "lowest value to run (with --high; default: bracket from "
                     "the scene's value by doubling or halving)");
  command.add_option("--high", o.high, "highest value to run");
  command
      .add_option("--tolerance", o.tolerance,
                  "stop when the bracket is this narrow "
                  "relative to its upper end (default 0.05)")
      ->check(CLI::Range(1e-6, 1.0));
  command.add_option("-j,--jobs", o.jobs, "runs at a time (default 0: the cores)")
      ->check(CLI::Range(0u, 256u));
  command.add_option("-o,--output", o.directory, "output directory (default results/sweep)")
      ->type_name("DIR");
  command.add_option("--set", o.settings, "override a scene key in every run (repeatable)")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  command.add_flag("-q,--quiet", o.quiet, "no line per run");
}

/// The `sweep` command, its results by default in results/sweep.
CLI::App* add_sweep_command(CLI::App& app, ddafem::SweepOptions& o)
{
  o.directory = "results/sweep";
  CLI::App* sweep = app.add_subcommand(
      "sweep", "find the critical value of a key (e.g. the wave's amplitude): runs in parallel");
  add_sweep_options(*sweep, o);
  return sweep;
}

/// Runs the sweep; returns the exit code.
int sweep_command(const ddafem::SweepOptions& o)
{
  if (o.find == ddafem::SweepCriterion::displacement && !(o.threshold > 0.0))
    throw ddafem::InputError("sweep: --find displacement needs --threshold M (> 0)");
  return ddafem::run_sweep(o, std::cerr);
}

/// The options that `ensemble` and `fragility` share: how each member differs and runs.
void add_member_options(CLI::App& e, ddafem::EnsembleOptions& o)
{
  e.add_option("SCENE", o.scene, "the scene file (YAML)")->required();
  e.add_option("--set", o.settings, "override a scene key in every member (repeatable)")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  e.add_option("--vary", o.vary,
               "draw a numeric key for each member: normal(mean,sd), lognormal(median,beta), "
               "uniform(low,high), truncnormal(mean,sd,low,high) (repeatable)")
      ->type_name("KEY=DIST")
      ->allow_extra_args(false);
  e.add_option("--roundoff", o.roundoff,
               "member k's KEY x (1 + k 1e-12), chaos apart from uncertainty (default key "
               "tunnel.wave.velocity.amplitude)")
      ->expected(0, 1)
      ->type_name("[KEY]");
  e.add_option("--seed", o.seed, "seed of the members' seeds and of every draw (default 1)");
  e.add_option("-j,--jobs", o.jobs, "runs at a time (default 0: the cores)")
      ->check(CLI::Range(0u, 256u));
  e.add_option("--threads", o.threads, "threads of each run (default 0: the cores shared)")
      ->check(CLI::Range(0u, 1024u));
  e.add_option("--max-wall-time", o.max_wall_time, "budget of each member (exit code 3)")
      ->check(CLI::PositiveNumber)
      ->type_name("SECONDS");
  e.add_flag("--snapshots", o.snapshots,
             "VTU snapshots at the scene's output.interval (default: first and last only)");
  e.add_flag("-q,--quiet", o.quiet, "no line per member");
}

/// The `ensemble` command, its results by default in results/ensemble.
CLI::App* add_ensemble_command(CLI::App& app, ddafem::EnsembleOptions& o)
{
  o.directory = "results/ensemble";
  CLI::App* e = app.add_subcommand(
      "ensemble", "run a scene N times, perturbed, in parallel: keyblock probabilities");
  add_member_options(*e, o);
  e->add_option("-n,--members", o.members, "members to run")
      ->required()
      ->check(CLI::Range(std::size_t(1), std::size_t(100000)));
  e->add_option("-o,--output", o.directory, "output directory (default results/ensemble)")
      ->type_name("DIR");
  e->add_option("--sector", o.sector_deg,
                "width of the sectors of an opening's perimeter in the report [deg] (default 10)")
      ->check(CLI::Range(1.0, 180.0));
  return e;
}

/// The `fragility` command, its results by default in results/fragility.
CLI::App* add_fragility_command(CLI::App& app, ddafem::FragilityOptions& o)
{
  o.ensemble.directory = "results/fragility";
  o.ensemble.members = 16;
  CLI::App* f = app.add_subcommand(
      "fragility", "fragility curves: an ensemble at each level of a key (e.g. the wave's "
                   "amplitude), lognormal fits by maximum likelihood");
  add_member_options(*f, o.ensemble);
  f->add_option("--key", o.key,
                "the key whose value is the intensity, e.g. "
                "tunnel.wave.velocity.amplitude")
      ->required();
  f->add_option("--levels", o.levels,
                "the key's values to run, e.g. --levels 0.5,1,1.5 "
                "(default: chosen, bracketed as `sweep` does)")
      ->delimiter(',')
      ->type_name("V1,V2,...");
  f->add_option("--n-levels", o.n_levels, "levels to choose (default 6)");
  f->add_option("--low", o.low, "lowest value of the bracketing (with --high)");
  f->add_option("--high", o.high, "highest value of the bracketing");
  f->add_option("--members", o.ensemble.members, "members per level (default 16)")
      ->check(CLI::Range(std::size_t(1), std::size_t(100000)));
  f->add_option("--fallen-area", o.fallen_area,
                "also the damage state: fallen area above A [m^2] (blocks the "
                "excavation released not counted)")
      ->type_name("A");
  f->add_option("--state", o.states,
                "also the damage state block:ID:fell or block:ID:loosened "
                "(repeatable)")
      ->allow_extra_args(false);
  f->add_option("-o,--output", o.ensemble.directory, "output directory (default results/fragility)")
      ->type_name("DIR");
  return f;
}

/// Runs the ensemble; returns the exit code.
int ensemble_command(const CLI::App& command, ddafem::EnsembleOptions o)
{
  if (command.get_option("--roundoff")->count() > 0 && !o.roundoff)
    o.roundoff = ""; // given without a key: the default key
  return ddafem::run_ensemble(o, std::cerr);
}

/// Runs the fragility analysis; returns the exit code.
int fragility_command(const CLI::App& command, ddafem::FragilityOptions o)
{
  if (command.get_option("--roundoff")->count() > 0 && !o.ensemble.roundoff)
    o.ensemble.roundoff = ""; // given without a key: the default key
  return ddafem::run_fragility(o, std::cerr);
}

/// The options of a run that `run` and `resume` share.
void add_run_options(CLI::App& command, CommandLine& cl)
{
  command.add_flag("-q,--quiet", cl.options.quiet, "no progress line");
  command
      .add_option("--threads", cl.options.threads,
                  "threads of contact detection and of the blocks' iterative solver "
                  "(solver.method block_pcg; default 0: all cores); results do not depend on it")
      ->check(CLI::Range(0u, 1024u))
      ->type_name("N");
  command
      .add_option("--max-wall-time", cl.options.max_wall_time,
                  "stop cleanly after the step at which the run has taken this wall time, writing "
                  "its state, a checkpoint and summary.json (status stopped, exit code 3)")
      ->check(CLI::PositiveNumber)
      ->type_name("SECONDS");
}
/// The `run` command.
CLI::App* add_run_command(CLI::App& app, CommandLine& cl)
{
  CLI::App* run = app.add_subcommand("run", "run a scene, results into DIR");
  add_scene_arguments(*run, cl);
  run->add_option("-o,--output", cl.options.output_directory,
                  "output directory (default: the scene's output.directory)")
      ->type_name("DIR");
  add_run_options(*run, cl);
  run->add_flag("--allow-unstable", cl.options.allow_unstable,
                "run although a boundary feeds energy in at this dt (it will fail)");
  run->add_flag("--stop-at-first-fall", cl.options.stop_at_first_fall,
                "stop (exit code 3) once a keyblock has fallen that the excavation did not "
                "release");
  return run;
}

/// Whether `word` names one of the app's commands.
bool is_command(CLI::App& app, const std::string& word)
{
  const std::vector<CLI::App*> commands = app.get_subcommands({});
  return std::any_of(commands.begin(), commands.end(),
                     [&](const CLI::App* c) { return c->get_name() == word; });
}

} // namespace

int main(int argc, char** argv)
{
  keep_freed_memory();
  CLI::App app("ddafem: jointed rock dynamics, DDA blocks with a deal.II far field.\n"
               "Exit codes: 0 success, 1 numerical failure, 2 bad input, 3 stopped at a budget.",
               "ddafem");
  app.set_version_flag("--version", std::string("ddafem ") + DDAFEM_VERSION);
  app.require_subcommand(1);
  CommandLine cl;
  CLI::App* check = app.add_subcommand("check", "validate a scene and print a model summary");
  add_scene_arguments(*check, cl);
  CLI::App* run = add_run_command(app, cl);
  CLI::App* resume_command = app.add_subcommand(
      "resume", "continue a killed or stopped run from the checkpoint in its DIR");
  resume_command->add_option("DIR", cl.directory, "the run's output directory")->required();
  add_run_options(*resume_command, cl);
  resume_command
      ->add_option("--max-memory", cl.max_memory,
                   "stop cleanly, exit code 3, if the run uses more memory than this, e.g. 8G")
      ->type_name("SIZE");
  ddafem::SweepOptions sweep_options;
  CLI::App* sweep = add_sweep_command(app, sweep_options);
  ddafem::EnsembleOptions ensemble_options;
  CLI::App* ensemble = add_ensemble_command(app, ensemble_options);
  ddafem::FragilityOptions fragility_options;
  CLI::App* fragility = add_fragility_command(app, fragility_options);
  CLI::App* reference =
      app.add_subcommand("scene-reference", "print the scene key reference (Markdown)");
  if (argc > 1 && argv[1][0] != '-' && !is_command(app, argv[1]))
  {
    std::cerr << "error: unknown command '" << argv[1]
              << "': expected check, run, resume, sweep, ensemble, fragility or scene-reference "
                 "(ddafem --help)\n";
    return 2;
  }
  try
  {
    app.parse(argc, argv);
  }
  catch (const CLI::ParseError& e)
  {
    if (e.get_exit_code() == 0) // --help, --version
      return app.exit(e);
    std::cerr << "error: " << e.what() << " (ddafem --help, ddafem COMMAND --help)\n";
    return 2;
  }
  try
  {
    if (reference->parsed())
    {
      std::cout << ddafem::scene_reference_markdown();
      return 0;
    }
    if (resume_command->parsed())
      return resume(cl);
    if (sweep->parsed())
      return sweep_command(sweep_options);
    if (ensemble->parsed())
      return ensemble_command(*ensemble, ensemble_options);
    if (fragility->parsed())
      return fragility_command(*fragility, fragility_options);
    return check_or_run(cl, run->parsed());
  }
  catch (const ddafem::InputError& e)
  {
    std::cerr << "error: " << e.what() << std::endl;
    ddafem::end_every_rank_after_error(2);
    return 2;
  }
  catch (const std::exception& e)
  {
    std::cerr << "error: " << e.what() << std::endl;
    ddafem::end_every_rank_after_error(1);
    return 1;
  }
}
