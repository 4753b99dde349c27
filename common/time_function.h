// Scalar functions of time used to scale loads and prescribed motions.
#pragma once

#include "common/ground_motion.h"

#include <memory>
#include <string>
#include <vector>

namespace ddafem
{
/// A dimensionless or dimensional scalar function of time t [s].
///
/// Three kinds, as a rock engineer specifies loads:
/// - constant: f(t) = value;
/// - sine pulse: f(t) = amplitude * sin(2 pi frequency (t - start)) for
///   start <= t <= start + n_cycles / frequency, zero elsewhere (an n-cycle sine pulse);
/// - table: piecewise-linear interpolation of (time, value) pairs, holding the first value before
///   the first time and the last value after the last time (from the scene or a CSV file);
/// - record: a table made from a recorded ground motion (app/scene/record_reader), which keeps what
///   the record is (RecordInfo) and whose frequencies come from its spectrum, not its sampling.
class TimeFunction
{
public:
  /// f(t) = value.
  static TimeFunction constant(double value);
  /// n-cycle sine pulse; frequency [Hz] > 0, n_cycles > 0, start [s].
  static TimeFunction sine_pulse(double amplitude, double frequency, double n_cycles, double start);
  /// Piecewise-linear table; times strictly increasing, same length as values, at least one
  /// point. The caller validates; this constructor asserts.
  static TimeFunction table(std::vector<double> times, std::vector<double> values);
  /// A table from a record; `info` says what it is.
  static TimeFunction record(std::vector<double> times, std::vector<double> values,
                             RecordInfo info);

  /// f(t) = 1.
  TimeFunction() = default;

  /// Value at time t [s].
  double value(double t) const;

  /// Highest frequency [Hz] of interest in this function: the pulse frequency for a sine pulse,
  /// 1/(smallest table interval) for a table, 99 % of the Fourier power of a record's
  /// acceleration below it (MotionSummary::f99), 0 for a constant.
  double characteristic_frequency() const;
  /// Dominant frequency [Hz]: the pulse frequency, a record's mean frequency
  /// (MotionSummary::mean_frequency), 0 for a constant or a table (not known).
  double dominant_frequency() const;
  /// What a record is; nullptr for the other kinds.
  const RecordInfo* record_info() const { return info.get(); }

  /// Time [s] after which the function keeps its final value: the end of a sine pulse, the
  /// last time of a table, 0 for a constant.
  double active_until() const;
  /// Human-readable one-line description, e.g. "sine pulse 100 Hz x 1 cycle".
  std::string describe() const;

private:
  enum class Kind
  {
    constant,
    sine_pulse,
    table,
    record
  };
  Kind kind = Kind::constant;
  double amplitude = 1.0;
  double frequency = 0.0;
  double n_cycles = 0.0;
  double start = 0.0;
  std::vector<double> times;
  std::vector<double> values;
  std::shared_ptr<const RecordInfo> info; ///< record only
};

} // namespace ddafem
