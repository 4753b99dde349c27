// Recorded ground motions: the processing of a uniformly sampled record (conversion to
// acceleration, window, taper, baseline correction) and its engineering measures (peaks, Arias
// intensity, significant duration, mean frequency). Pure functions of the samples; the scene
// reader (app/scene/record_reader) reads the files and builds the TimeFunction that scenes use.
#pragma once

#include "common/enum_names.h"

#include <array>
#include <string>
#include <vector>

namespace ddafem
{
/// Standard gravity [m/s^2], the unit "g" of accelerograms.
constexpr double standard_gravity = 9.80665;

/// What the samples of a record measure.
enum class MotionQuantity
{
  acceleration,
  velocity,
  displacement
};

constexpr std::array<EnumName<MotionQuantity>, 3> enum_names(MotionQuantity)
{
  return {{{MotionQuantity::acceleration, "acceleration"},
           {MotionQuantity::velocity, "velocity"},
           {MotionQuantity::displacement, "displacement"}}};
}

/// Acceleration [m/s^2] at the samples t_i = i dt of samples of `quantity` (SI units): as they
/// are for acceleration, central differences for velocity, second central differences for
/// displacement (one-sided at the ends). Needs at least 3 samples for a derivative.
std::vector<double> to_acceleration(const std::vector<double>& samples, double dt,
                                    MotionQuantity quantity);

/// Running integral by the trapezoidal rule from 0 at t_0: y_0 = 0,
/// y_{i+1} = y_i + dt (x_i + x_{i+1}) / 2.
std::vector<double> integrate(const std::vector<double>& x, double dt);

/// Multiplies the first and last `seconds` [s] of x by a half cosine rising from 0 (falling to
/// 0): a Tukey window, so that a cut record starts and ends at rest. seconds <= 0 leaves x.
void taper_ends(std::vector<double>& x, double dt, double seconds);

/// The polynomial baseline correction of an accelerogram (documented in docs/ground_motions.md).
/// The acceleration loses w(t) sum_{k=0}^{degree-2} c_k (t/T)^k (T the record's length, w the
/// taper of taper_ends with `taper` seconds, 1 for 0), that is about a displacement polynomial
/// from t^2 to t^degree, so that displacement and velocity stay 0 at t = 0 and a tapered record
/// still starts and ends at zero acceleration. The c_k make the corrected displacement (by the
/// trapezoidal rule twice) as small as they can in the least-squares sense, under the
/// constraint that the corrected velocity ends at exactly 0: the motion ends at rest, with the
/// permanent displacement the fit leaves.
struct BaselineCorrection
{
  std::vector<double> coefficients;     ///< c_k [m/s^2], k = 0 .. degree - 2
  double end_velocity_before = 0.0;     ///< [m/s]
  double end_displacement_before = 0.0; ///< [m]
  double end_displacement_after = 0.0;  ///< [m]
};

/// Corrects `a` [m/s^2] sampled every dt [s] in place; degree >= 2, at least 2 samples.
BaselineCorrection correct_baseline(std::vector<double>& a, double dt, int degree,
                                    double taper = 0.0);

/// Engineering measures of an accelerogram.
struct MotionSummary
{
  double duration = 0.0;        ///< (n - 1) dt [s]
  double pga = 0.0;             ///< peak |a| [m/s^2]
  double pgv = 0.0;             ///< peak |v| [m/s], v by the trapezoidal rule
  double pgd = 0.0;             ///< peak |u| [m]
  double arias_intensity = 0.0; ///< I_a = pi / (2 g) int a^2 dt [m/s]
  double t5 = 0.0;              ///< time [s] at which 5 % of I_a has built up
  double t95 = 0.0;             ///< time [s] at which 95 % of I_a has built up (D5-95 = t95 - t5)
  /// 1 / T_m, T_m = sum C_j^2 / f_j / sum C_j^2 over 0.25 <= f_j <= 20 Hz, C_j the Fourier
  /// amplitudes of a (Rathje, Abrahamson & Bray 1998): the record's mean frequency [Hz].
  double mean_frequency = 0.0;
  /// Frequency [Hz] below which 99 % of sum C_j^2 lies: the highest frequency the model must
  /// carry (element sizes, time step).
  double f99 = 0.0;
};

/// Measures of `a` [m/s^2] sampled every dt [s] (at least 2 samples).
MotionSummary summarize_motion(const std::vector<double>& a, double dt);

/// Where a record was taken, which sets the incident wave a model receives at its base.
enum class RecordMotion
{
  /// At a rock outcrop (the free surface of the base rock): the incident wave is half of it,
  /// the free surface doubling the incident wave of a uniform half-space.
  outcrop,
  /// At depth, in the free field: taken as the incident wave, which it is where nothing above
  /// the base reflects during the record (a model without a free ground surface above).
  within,
  /// The incident (upgoing) wave itself.
  incident
};

constexpr std::array<EnumName<RecordMotion>, 3> enum_names(RecordMotion)
{
  return {{{RecordMotion::outcrop, "outcrop"},
           {RecordMotion::within, "within"},
           {RecordMotion::incident, "incident"}}};
}

/// Incident wave / record: 0.5 for an outcrop record, 1 otherwise.
double incident_factor(RecordMotion motion);

/// What a scene's record is, for `check`, summary.json and report.md.
struct RecordInfo
{
  std::string file;                            ///< as the scene names it
  RecordMotion motion = RecordMotion::outcrop; ///< where it was taken
  double scale = 1.0;                          ///< factor on the file's samples (SI units) [-]
  double window_from = 0.0;                    ///< the part of the record used, in its own time [s]
  double window_to = 0.0;                      ///< [s]
  double start = 0.0;                          ///< model time of the window's first sample [s]
  double dt = 0.0;                             ///< sampling interval [s]
  BaselineCorrection baseline;                 ///< of the unscaled window
  MotionSummary summary; ///< of the scaled, corrected window (the record, not the incident)
};

} // namespace ddafem
