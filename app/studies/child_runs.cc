#include "app/studies/child_runs.h"

#include "app/scene/map_reader.h"
#include "app/scene/scene.h"
#include "app/scene/scene_text.h"
#include "common/stopwatch.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace ddafem::child_runs
{
namespace
{
/// This process's environment without the MPI launcher's variables (OMPI_*, PMIX_*, PMI_*): a
/// child of a rank that mpirun started is a serial run of its own, not a rank of that job.
std::vector<std::string> environment_without_mpi()
{
  std::vector<std::string> kept;
  for (char** e = environ; *e != nullptr; ++e)
  {
    const std::string entry(*e);
    if (entry.rfind("OMPI_", 0) != 0 && entry.rfind("PMIX_", 0) != 0 && entry.rfind("PMI_", 0) != 0)
      kept.push_back(entry);
  }
  return kept;
}
} // namespace

Child start(const std::vector<std::string>& args, const std::string& log_file)
{
  std::vector<std::string> copy = args;
  std::vector<char*> argv;
  for (std::string& a : copy)
    argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log_file.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  Child child;
  child.started = std::chrono::steady_clock::now();
  std::vector<std::string> environment = environment_without_mpi();
  std::vector<char*> envp;
  for (std::string& e : environment)
    envp.push_back(e.data());
  envp.push_back(nullptr);
  const int error =
      posix_spawn(&child.pid, "/proc/self/exe", &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (error != 0)
    throw std::runtime_error("cannot start a run: " + std::string(strerror(error)));
  return child;
}

namespace
{
/// Records how a child ended from its wait status.
void record_end(Child& child, int status)
{
  child.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  child.wall_s = seconds_since(child.started);
}
} // namespace

std::size_t wait_for_any(std::vector<Child*>& children)
{
  while (true)
  {
    int status = 0;
    const pid_t pid = waitpid(-1, &status, 0);
    if (pid < 0)
      throw std::runtime_error("waiting for the runs: " + std::string(strerror(errno)));
    const auto it = std::find_if(children.begin(), children.end(),
                                 [&](const Child* c) { return c->pid == pid && c->exit_code < 0; });
    if (it == children.end())
      continue; // not one of these runs
    record_end(**it, status);
    return static_cast<std::size_t>(it - children.begin());
  }
}

void stop(Child& child)
{
  if (child.pid <= 0 || child.exit_code >= 0)
    return;
  kill(child.pid, SIGTERM);
  int status = 0;
  waitpid(child.pid, &status, 0);
  record_end(child, status);
}

std::pair<unsigned, unsigned> jobs_and_threads(const unsigned jobs, const unsigned threads)
{
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const unsigned j = jobs > 0 ? jobs : cores;
  return {j, threads > 0 ? threads : std::max(1u, cores / j)};
}

std::string file_text(const std::string& file)
{
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return scene_reading::trim(text.str());
}

std::optional<double> scene_value(const std::string& file, const std::vector<std::string>& settings,
                                  const std::string& key)
{
  YAML::Node root = scene_reading::load_yaml(file);
  for (const std::string& s : settings)
    scene_reading::apply_override(root, parse_override(s));
  YAML::Node node = root;
  for (const std::string& c : scene_reading::split(key, '.'))
  {
    const bool digits = !c.empty() && c.find_first_not_of("0123456789") == std::string::npos;
    YAML::Node child = node.IsSequence() && digits && c.size() < 10 ? node[std::stoul(c)]
                       : node.IsMap()                               ? node[c]
                                                                    : YAML::Node();
    if (!child.IsDefined())
      return std::nullopt;
    node.reset(child);
  }
  return node.IsScalar() ? scene_reading::parse_double(node.Scalar()) : std::nullopt;
}

} // namespace ddafem::child_runs
