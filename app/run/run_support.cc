#include "app/run/run_support.h"

#include "common/format.h"
#include "common/input_error.h"
#include "common/vtk_collection.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace ddafem::run_support
{
double peak_memory_mb()
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0)
      return std::stod(line.substr(6)) / 1024.0; // kB -> MB
  return 0.0;
}

std::optional<unsigned int> mpi_rank_from_environment()
{
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"})
    if (const char* value = std::getenv(name); value != nullptr && *value != '\0')
      return static_cast<unsigned int>(std::strtoul(value, nullptr, 10));
  return std::nullopt;
}

std::optional<MpiJob> mpi_job_from_environment()
{
  const std::optional<unsigned int> rank = mpi_rank_from_environment();
  if (!rank)
    return std::nullopt;
  MpiJob job{*rank, 1, ""};
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
    if (const char* value = std::getenv(name); value != nullptr && *value != '\0')
    {
      job.size = static_cast<unsigned int>(std::strtoul(value, nullptr, 10));
      break;
    }
  for (const char* name : {"PMIX_NAMESPACE", "OMPI_MCA_ess_base_jobid"})
    if (const char* value = std::getenv(name); value != nullptr && *value != '\0')
    {
      job.name = value;
      break;
    }
  return job;
}

double resident_memory_bytes()
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmRSS:", 0) == 0)
      return std::stod(line.substr(6)) * 1024.0; // kB -> bytes
  return 0.0;
}

void create_output_directory(const std::filesystem::path& directory)
{
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec)
    throw InputError("cannot create output directory '" + directory.string() +
                     "': " + ec.message());
}

void write_text_file(const std::filesystem::path& path, const std::string& text)
{
  try
  {
    write_file_atomically(path, text);
  }
  catch (const std::runtime_error& e)
  {
    throw std::runtime_error(std::string(e.what()) + "; the previous " + path.filename().string() +
                             ", if any, is kept");
  }
}

std::size_t clear_earlier_results(const std::filesystem::path& dir)
{
  static const std::regex ours(
      R"((summary\.json|histories\.h5|checkpoint\.bin|expanded_scene\.yaml|report\.md|)"
      R"(report_[a-z_]+\.png|)"
      R"((model|blocks|contacts|ties|far_field)\.pvd|(blocks|contacts|ties|far_field)_[0-9]+\.vtu|)"
      R"(far_field_[0-9]+\.pvtu|far_field_[0-9]+\.[0-9]+\.vtu)"
      R"()(\.tmp)?)");
  std::size_t n_removed = 0;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
  {
    if (!entry.is_regular_file() || !std::regex_match(entry.path().filename().string(), ours))
      continue;
    if (!std::filesystem::remove(entry.path(), ec) || ec)
      throw std::runtime_error("cannot remove " + entry.path().string() +
                               " of an earlier run: " + ec.message());
    ++n_removed;
  }
  if (ec)
    throw std::runtime_error("cannot list the output directory " + dir.string() + ": " +
                             ec.message());
  return n_removed;
}

bool snapshot_due(double time, double interval, double dt, double& next)
{
  if (interval <= 0.0 || time < next - 1e-9 * dt)
    return false;
  while (next <= time + 1e-9 * dt)
    next += interval;
  return true;
}

void add_monitor_channels(std::vector<HistoryChannel>& channels, const std::string& name,
                          const std::string& point_where, const std::string& stress_where)
{
  const std::string base = "monitors/" + name + "/";
  channels.push_back({base + "displacement", 2, "m", "(ux, uy) " + point_where});
  channels.push_back({base + "velocity", 2, "m/s", "(vx, vy) " + point_where});
  channels.push_back(
      {base + "stress", 3, "Pa", "(sxx, syy, sxy) " + stress_where + ", tension positive"});
}

int finish_run(const std::filesystem::path& dir, const nlohmann::json& summary,
               const std::string& failure, const std::string& steps, double time, double wall,
               const std::string& view_file, std::ostream& log)
{
  write_text_file(dir / "summary.json", summary.dump(2) + "\n");
  if (summary.value("status", "") == "stopped")
  {
    log << "stopped: " << summary["stopped"].get<std::string>() << " at t = " << time << " s\n"
        << "results up to there are in " << dir.string() << "\n";
    return 3;
  }
  if (!failure.empty())
  {
    log << "error: numerical failure: " << failure << "\n"
        << "results up to t = " << time << " s are in " << dir.string() << "\n";
    return 1;
  }
  if (summary.contains("energy_source"))
    log << "warning: " << summary["energy_source"].get<std::string>() << "\n";
  log << "completed " << steps << " to t = " << time << " s in " << format_significant(wall, 3)
      << " s wall time\n"
      << "results: " << (dir / view_file).string() << " (ParaView), "
      << (dir / "histories.h5").string() << ", " << (dir / "summary.json").string() << "\n";
  return 0;
}

void Progress::update(std::size_t step, double time, double wall, bool force)
{
  if (!enabled || (!force && wall - last < 0.2))
    return;
  last = wall;
  if (time > 0.0 && time < end_time)
    std::fprintf(stderr, "\rstep %zu  t = %.6g of %.6g s  wall %.1f s  ETA %.1f s   ", step, time,
                 end_time, wall, wall * (end_time - time) / time);
  else
    std::fprintf(stderr, "\rstep %zu  t = %.6g s  wall %.1f s                 ", step, time, wall);
  std::fflush(stderr);
}

void Progress::finish()
{
  if (enabled)
    std::fprintf(stderr, "\n");
}

} // namespace ddafem::run_support
