#include "app/run_support.h"

#include "common/input_error.h"

#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace ddafem::run_support
{
double elapsed(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string format(double value, int precision)
{
  std::ostringstream s;
  s << std::setprecision(precision) << value;
  return s.str();
}

double peak_memory_mb()
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0)
      return std::stod(line.substr(6)) / 1024.0; // kB -> MB
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

bool snapshot_due(double time, double interval, double dt, double& next)
{
  if (interval <= 0.0 || time < next - 1e-9 * dt)
    return false;
  while (next <= time + 1e-9 * dt)
    next += interval;
  return true;
}

void Progress::update(std::size_t step, double time, double wall, bool force)
{
  if (!enabled || (!force && wall - last < 0.2))
    return;
  last = wall;
  const double eta = step > 0 ? wall * static_cast<double>(n_steps - step) / step : 0.0;
  std::fprintf(stderr, "\rstep %zu/%zu  t = %.6g s  wall %.1f s  ETA %.1f s   ", step, n_steps,
               time, wall, eta);
  std::fflush(stderr);
}

void Progress::finish()
{
  if (enabled)
    std::fprintf(stderr, "\n");
}

} // namespace ddafem::run_support
