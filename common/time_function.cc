#include "common/time_function.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace ddafem
{
TimeFunction TimeFunction::constant(double value)
{
  TimeFunction f;
  f.kind = Kind::constant;
  f.amplitude = value;
  return f;
}

TimeFunction TimeFunction::sine_pulse(double amplitude, double frequency, double n_cycles,
                                      double start)
{
  assert(frequency > 0.0 && n_cycles > 0.0);
  TimeFunction f;
  f.kind = Kind::sine_pulse;
  f.amplitude = amplitude;
  f.frequency = frequency;
  f.n_cycles = n_cycles;
  f.start = start;
  return f;
}

TimeFunction TimeFunction::table(std::vector<double> times, std::vector<double> values)
{
  assert(!times.empty() && times.size() == values.size());
  assert(std::is_sorted(times.begin(), times.end()));
  TimeFunction f;
  f.kind = Kind::table;
  f.times = std::move(times);
  f.values = std::move(values);
  return f;
}

TimeFunction TimeFunction::record(std::vector<double> times, std::vector<double> values,
                                  RecordInfo info)
{
  TimeFunction f = table(std::move(times), std::move(values));
  f.kind = Kind::record;
  f.info = std::make_shared<const RecordInfo>(std::move(info));
  return f;
}

double TimeFunction::value(double t) const
{
  switch (kind)
  {
  case Kind::constant:
    return amplitude;
  case Kind::sine_pulse:
  {
    const double tau = t - start;
    if (tau < 0.0 || tau > n_cycles / frequency)
      return 0.0;
    return amplitude * std::sin(2.0 * M_PI * frequency * tau);
  }
  case Kind::table:
  case Kind::record:
  {
    if (t <= times.front())
      return values.front();
    if (t >= times.back())
      return values.back();
    const auto it = std::upper_bound(times.begin(), times.end(), t);
    const std::size_t i = static_cast<std::size_t>(it - times.begin());
    const double w = (t - times[i - 1]) / (times[i] - times[i - 1]);
    return (1.0 - w) * values[i - 1] + w * values[i];
  }
  }
  return 0.0;
}

double TimeFunction::active_until() const
{
  switch (kind)
  {
  case Kind::constant:
    return 0.0;
  case Kind::sine_pulse:
    return start + n_cycles / frequency;
  case Kind::table:
  case Kind::record:
    return times.back();
  }
  return 0.0;
}

double TimeFunction::dominant_frequency() const
{
  switch (kind)
  {
  case Kind::sine_pulse:
    return frequency;
  case Kind::record:
    return info->summary.mean_frequency;
  case Kind::constant:
  case Kind::table:
    break;
  }
  return 0.0;
}

double TimeFunction::characteristic_frequency() const
{
  switch (kind)
  {
  case Kind::constant:
    return 0.0;
  case Kind::sine_pulse:
    return frequency;
  case Kind::table:
  {
    double smallest = 0.0;
    for (std::size_t i = 1; i < times.size(); ++i)
    {
      const double h = times[i] - times[i - 1];
      if (h > 0.0 && (smallest == 0.0 || h < smallest))
        smallest = h;
    }
    return smallest > 0.0 ? 1.0 / smallest : 0.0;
  }
  case Kind::record:
    return info->summary.f99;
  }
  return 0.0;
}

std::string TimeFunction::describe() const
{
  std::ostringstream s;
  switch (kind)
  {
  case Kind::constant:
    s << "constant " << amplitude;
    break;
  case Kind::sine_pulse:
    s << "sine pulse " << frequency << " Hz x " << n_cycles << " cycle(s), amplitude " << amplitude
      << ", start " << start << " s";
    break;
  case Kind::table:
    s << "table of " << times.size() << " points, " << times.front() << " to " << times.back()
      << " s";
    break;
  case Kind::record:
  {
    const RecordInfo& r = *info;
    const MotionSummary& m = r.summary;
    s << std::setprecision(3) << "record " << r.file << " (" << name_of(r.motion)
      << ", the incident wave " << incident_factor(r.motion) << " x it): " << r.window_from
      << " to " << r.window_to << " s of it every " << r.dt << " s from t = " << r.start
      << " s, scale " << r.scale << "; PGA " << m.pga << " m/s^2 (" << m.pga / standard_gravity
      << " g), PGV " << m.pgv << " m/s, PGD " << m.pgd << " m, Arias " << m.arias_intensity
      << " m/s, D5-95 " << m.t95 - m.t5 << " s, mean frequency " << m.mean_frequency << " Hz, f99 "
      << m.f99 << " Hz; baseline: end velocity " << r.scale * r.baseline.end_velocity_before
      << " -> 0 m/s, end displacement " << r.scale * r.baseline.end_displacement_before << " -> "
      << r.scale * r.baseline.end_displacement_after << " m";
    break;
  }
  }
  return s.str();
}

} // namespace ddafem
