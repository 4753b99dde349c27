// Child `ddafem run` processes of the commands that run a scene many times (`sweep`,
// `ensemble`): started with posix_spawn of /proc/self/exe (this very executable), their output
// into a log file, waited for in any order, stopped with SIGTERM. Also what those commands share
// in reading their scene: the number at a key with the --set overrides applied.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace ddafem::child_runs
{
/// A child run: its process and when it started. exit_code is -1 while it runs, then the exit
/// status (128 + n if killed by signal n).
struct Child
{
  pid_t pid = 0;
  std::chrono::steady_clock::time_point started;
  int exit_code = -1;
  double wall_s = 0.0; ///< wall time from start to end [s]
};

/// Starts this executable with `args` (args[0] the program's name), its stdout and stderr into
/// `log_file` (truncated), in this process's environment less the MPI launcher's variables
/// (OMPI_*, PMIX_*, PMI_*): under mpirun the child is a serial run of its own. Throws
/// std::runtime_error if it cannot.
Child start(const std::vector<std::string>& args, const std::string& log_file);

/// Waits until one of the running `children` (exit_code < 0) ends; records its exit code and
/// wall time and returns its index. Other children of the process are reaped and ignored.
std::size_t wait_for_any(std::vector<Child*>& children);

/// Stops a running child (SIGTERM) and waits for it; records its exit code and wall time.
void stop(Child& child);

/// The runs at a time (`jobs`, 0: the cores) and the threads of each (the cores shared, at
/// least 1; `threads` > 0 given by the user wins).
std::pair<unsigned, unsigned> jobs_and_threads(unsigned jobs, unsigned threads = 0);

/// The text of a file, trimmed (a child's log, for messages); empty if it cannot be read.
std::string file_text(const std::string& file);

/// The number at the dotted `key` (list items by index) of the scene file with `settings`
/// (--set KEY=VALUE) applied, if there is one.
std::optional<double> scene_value(const std::string& file, const std::vector<std::string>& settings,
                                  const std::string& key);

} // namespace ddafem::child_runs
