// Wall-clock timing of the phases of a computation.
#pragma once

#include <chrono>

namespace ddafem
{
/// A monotonic clock for measuring phases (not the time of day).
using Clock = std::chrono::steady_clock;

/// Wall time elapsed since `start` [s].
inline double seconds_since(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

} // namespace ddafem
