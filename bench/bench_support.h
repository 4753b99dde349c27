// Small helpers of the benchmark drivers (bench/*.cc).
#pragma once

#include <chrono>
#include <fstream>
#include <string>

namespace ddafem::bench
{
/// This process's peak resident memory (VmHWM) [MB].
inline double peak_memory_mb()
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0)
      return std::stod(line.substr(6)) / 1024.0;
  return 0.0;
}

/// Wall time since `start` [s].
inline double seconds(const std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
} // namespace ddafem::bench
