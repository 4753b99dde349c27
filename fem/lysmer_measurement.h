// Measures the reflection of a plane P or SV pulse at a Lysmer boundary with the FE far field
// (issue 5 acceptance "Oblique incidence"; docs/lysmer.md).
#pragma once

#include "fem/lysmer_reflection.h"

#include <optional>

namespace ddafem::fem
{
struct LysmerMeasurementSettings
{
  IncidentKind incident = IncidentKind::p;
  double angle_deg = 0.0;
  double frequency = 10.0;              ///< Ricker peak frequency f0 [Hz]
  double elements_per_wavelength = 5.0; ///< Q2 elements per S wavelength VS / f0
  double steps_per_period = 25.0;       ///< dt = 1 / (f0 steps_per_period)
  /// Half-width of the domain and height above the monitor, in units of VP t_end (the distance
  /// the fastest wave covers in the measurement window).
  double domain_factor = 1.0;
};

struct LysmerMeasurement
{
  std::optional<double> r_p;     ///< measured |R_P|, empty where the reflected P is evanescent
  std::optional<double> r_s;     ///< measured |R_S|
  double energy_reflected = 0.0; ///< from the measured amplitudes and the flux factors
  LysmerReflection analytic;
  std::size_t n_dofs = 0;
  std::size_t n_steps = 0;
  double seconds = 0.0; ///< wall time
};

/// Bottom boundary y = 0 is the Lysmer boundary under test (all other sides Lysmer too, far
/// enough not to reach the monitor in the window). A plane Ricker pulse (displacement) set as
/// the initial state travels down at the incidence angle; the velocity at a monitor above the
/// boundary is fitted, after the incident pulse has passed, by the reflected P and S pulses
/// (each as a f'(t - tau) + b H[f'](t - tau) along its polarisation, H the Hilbert transform,
/// so that complex coefficients are captured) with the analytic delays; |R| = sqrt(a^2 + b^2).
LysmerMeasurement measure_lysmer_reflection(const LysmerMeasurementSettings& settings);

} // namespace ddafem::fem
