// Analytic reflection of plane P and SV waves at a Lysmer-Kuhlemeyer boundary (issue 5,
// docs/reference/physics.md section 4; derivation in docs/lysmer.md).
#pragma once

#include <complex>
#include <optional>

namespace ddafem::fem
{
enum class IncidentKind
{
  p,
  sv
};

/// Medium and dashpots. a = b = 1 is the Lysmer-Kuhlemeyer boundary; a = b = 0 a free surface.
struct LysmerMedium
{
  double density = 1.0; ///< rho [kg/m^3]
  double vp = 1.0;      ///< [m/s]
  double vs = 1.0;      ///< [m/s], < vp
  double a = 1.0;       ///< normal dashpot rho a VP
  double b = 1.0;       ///< tangential dashpot rho b VS
};

/// Reflection of a plane wave of unit displacement amplitude. Conventions (docs/lysmer.md): the
/// body is y > 0, the boundary y = 0; a wave of slowness s = (p, eta) has displacement
/// amplitude along d = s / |s| (P) or d = (-eta, p) / |s| (SV).
struct LysmerReflection
{
  std::complex<double> r_p; ///< reflected P displacement amplitude / incident (complex)
  std::complex<double> r_s; ///< reflected SV displacement amplitude / incident (complex)
  bool p_evanescent = false;
  bool s_evanescent = false;
  /// |r_p|, |r_s|; empty where that reflected wave is evanescent.
  std::optional<double> amplitude_p() const;
  std::optional<double> amplitude_s() const;
  double energy_p = 0.0; ///< reflected P energy flux / incident (0 if evanescent)
  double energy_s = 0.0; ///< reflected SV energy flux / incident (0 if evanescent)
  double energy_reflected() const { return energy_p + energy_s; }
  /// Time-averaged power into the dashpots / incident flux, from the total boundary motion
  /// (independent of energy_p, energy_s; energy_reflected + energy_absorbed = 1).
  double energy_absorbed = 0.0;
};

/// theta [rad] in [0, pi/2): incidence angle from the boundary normal.
LysmerReflection lysmer_reflection(IncidentKind incident, double theta, const LysmerMedium& medium);

} // namespace ddafem::fem
