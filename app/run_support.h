// Small pieces shared by the run commands of the DDA and far-field models.
#pragma once

#include <chrono>
#include <cstddef>
#include <filesystem>
#include <string>

namespace ddafem::run_support
{
using Clock = std::chrono::steady_clock;

/// Seconds since `start`.
double elapsed(Clock::time_point start);

/// `value` with `precision` significant digits.
std::string format(double value, int precision = 4);

/// Peak resident memory of this process [MB]: VmHWM from /proc/self/status (getrusage's
/// ru_maxrss would include the image of a parent that forked us, e.g. a Python driver); 0 where
/// /proc is not available.
double peak_memory_mb();

/// Creates the output directory (and parents); InputError naming it on failure.
void create_output_directory(const std::filesystem::path& directory);

/// Whether a snapshot is due at `time` with the given interval [s], advancing `next`;
/// interval 0 writes only where the caller asks (first and last).
bool snapshot_due(double time, double interval, double dt, double& next);

/// One-line progress display on a terminal, at most five updates a second.
class Progress
{
public:
  Progress(bool enabled_, std::size_t n_steps_) : enabled(enabled_), n_steps(n_steps_) {}
  void update(std::size_t step, double time, double wall, bool force = false);
  void finish();

private:
  bool enabled;
  std::size_t n_steps;
  double last = -1.0;
};

} // namespace ddafem::run_support
