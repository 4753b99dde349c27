// Measures the reflection of a plane P or SV pulse at a Lysmer boundary with the FE far field
// (issue 5 acceptance "Oblique incidence"; docs/lysmer.md).
#pragma once

#include "fem/lysmer_reflection.h"

#include <array>
#include <optional>
#include <vector>

namespace ddafem::fem
{
struct LysmerMeasurementSettings
{
  IncidentKind incident = IncidentKind::p;
  double angle_deg = 0.0;
  double frequency = 10.0;              ///< Ricker peak frequency f0 [Hz]
  double elements_per_wavelength = 5.0; ///< Q2 elements per S wavelength VS / f0
  double steps_per_period = 25.0;       ///< dt = 1 / (f0 steps_per_period)
  /// Scales the distances of the left, right and top sides from the monitor; 1 is the least
  /// from which nothing they do reaches the monitor before the end of the window (docs/lysmer.md).
  double domain_factor = 1.0;
  /// Time [in periods 1/f0] from t = 0 until the incident pulse starts to reach the boundary
  /// point that reflects each measured wave to the monitor (its specular point). It keeps the
  /// bottom edge of the initial incident stripe (the boundary has reflected nothing before t = 0)
  /// away from that point.
  double margin_periods = 1.0;
  /// Runs of the fixed-point iteration: run k > 1 starts with the incident wave plus the
  /// reflected plane waves measured by run k - 1 (what the boundary would have reflected
  /// before t = 0), so the edge effect scales with the change of the measurement.
  unsigned int max_runs = 4;
  /// Stop when no measured coefficient (in-phase or quadrature part) changes by more.
  double tolerance = 0.002;
  /// Fit the reflected pulses as the trapezoidal rule delivers them (its frequency warping)
  /// rather than the continuum pulses.
  bool warp_time = true;
  /// ... and as the mesh of square Q2 elements propagates them (Bloch analysis).
  bool mesh_dispersion = true;
  bool record_trace = false; ///< keep the monitor velocity and the fit of every run
};

/// One run of the fixed-point iteration.
struct LysmerRun
{
  std::optional<double> r_p; ///< measured |R_P|, empty where the reflected P is evanescent
  std::optional<double> r_s; ///< measured |R_S|
  double rms_residual = 0.0; ///< rms misfit of the fit / rms incident velocity
  double incident = 0.0;     ///< fitted amplitude of the incident pulse at the monitor (1 exact)
  /// (in-phase, quadrature) coefficients of the propagating reflected waves, P first
  std::vector<std::array<double, 2>> coefficients;
  /// With record_trace: (t, v_x, v_y, fitted v_x, fitted v_y) per step; the fit is evaluated
  /// over the whole run (it applies from the start of the window).
  std::vector<std::array<double, 5>> trace;
};

struct LysmerMeasurement
{
  std::optional<double> r_p;     ///< measured |R_P|, empty where the reflected P is evanescent
  std::optional<double> r_s;     ///< measured |R_S|
  double energy_reflected = 0.0; ///< from the measured amplitudes and the flux factors
  LysmerReflection analytic;
  std::vector<LysmerRun> runs;    ///< the iteration history; the last one is the result
  std::array<double, 3> domain{}; ///< x0, x1 and top y1 of the rectangle [0 <= y <= y1] [m]
  double monitor_height = 0.0;    ///< y of the monitor (x = 0) [m]
  std::array<double, 2> window{}; ///< fitted time window of each run [s]
  std::size_t n_dofs = 0;
  std::size_t n_steps = 0; ///< per run
  double seconds = 0.0;    ///< wall time
};

/// Bottom boundary y = 0 is the Lysmer boundary under test (all other sides Lysmer too, far
/// enough not to reach the monitor in the window). A plane Ricker pulse (displacement) set as
/// the initial state travels down at the incidence angle; the velocity at a monitor above the
/// boundary is fitted, after the incident pulse has passed, by the reflected P and S pulses
/// (each as a f'(t - tau) + b H[f'](t - tau) along its polarisation, H the Hilbert transform,
/// so that complex coefficients are captured) with the analytic delays; |R| = sqrt(a^2 + b^2).
/// See docs/lysmer.md for the geometry and the fixed-point iteration.
LysmerMeasurement measure_lysmer_reflection(const LysmerMeasurementSettings& settings);

/// Hilbert transforms (1/pi) p.v. int f(s) / (t - s) ds of the Ricker wavelet
/// (1 - 2 a t^2) exp(-a t^2), a = (pi f0)^2, and of its time derivative, in closed form through
/// Dawson's function (exposed for the tests).
double ricker_hilbert(double t, double f0);
double ricker_rate_hilbert(double t, double f0);
/// Dawson's function exp(-x^2) int_0^x exp(s^2) ds.
double dawson(double x);

} // namespace ddafem::fem
