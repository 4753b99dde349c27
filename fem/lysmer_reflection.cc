// Analytic Lysmer-Kuhlemeyer reflection coefficients (docs/lysmer.md).
#include "fem/lysmer_reflection.h"

#include <array>
#include <cmath>
#include <stdexcept>

namespace ddafem::fem
{
namespace
{
using cd = std::complex<double>;

struct PlaneWave
{
  std::array<cd, 2> slowness;     ///< (p, eta)
  std::array<cd, 2> polarisation; ///< unit (in the bilinear sense d.d = 1)
};

/// Vertical slowness of an upgoing wave of speed c: sqrt(1/c^2 - p^2), or i sqrt(p^2 - 1/c^2)
/// (decaying into y > 0 for exp(i omega (p x + eta y - t))).
cd upgoing_eta(const double p, const double c, bool& evanescent)
{
  const double q = 1.0 / (c * c) - p * p;
  evanescent = q < 0.0;
  return evanescent ? cd(0.0, std::sqrt(-q)) : cd(std::sqrt(q), 0.0);
}

PlaneWave p_wave(const double p, const cd eta, const double vp)
{
  return {{{cd(p), eta}}, {{vp * p, vp * eta}}};
}

PlaneWave s_wave(const double p, const cd eta, const double vs)
{
  return {{{cd(p), eta}}, {{-vs * eta, cd(vs * p)}}};
}

/// (sigma_xy, sigma_yy) / (i omega) + D d: the boundary residual of one wave of unit amplitude.
/// Boundary condition on y = 0 (outward normal -y): sigma n = -D v with v = -i omega u, i.e.
/// (sigma_xy, sigma_yy) = D v.
std::array<cd, 2> residual(const PlaneWave& w, const double lambda, const double mu,
                           const LysmerMedium& m)
{
  const auto& s = w.slowness;
  const auto& d = w.polarisation;
  const cd div = d[0] * s[0] + d[1] * s[1];
  const cd sxy = mu * (d[0] * s[1] + d[1] * s[0]);
  const cd syy = lambda * div + 2.0 * mu * d[1] * s[1];
  return {{sxy + m.density * m.b * m.vs * d[0], syy + m.density * m.a * m.vp * d[1]}};
}

} // namespace

std::optional<double> LysmerReflection::amplitude_p() const
{
  if (p_evanescent)
    return std::nullopt;
  return std::abs(r_p);
}

std::optional<double> LysmerReflection::amplitude_s() const
{
  if (s_evanescent)
    return std::nullopt;
  return std::abs(r_s);
}

LysmerReflection lysmer_reflection(const IncidentKind incident, const double theta,
                                   const LysmerMedium& m)
{
  if (!(m.vp > m.vs && m.vs > 0.0 && m.density > 0.0))
    throw std::invalid_argument("lysmer_reflection: need vp > vs > 0 and density > 0");
  if (!(theta >= 0.0 && theta < 0.5 * M_PI))
    throw std::invalid_argument("lysmer_reflection: theta must lie in [0, pi/2)");
  const double mu = m.density * m.vs * m.vs;
  const double lambda = m.density * m.vp * m.vp - 2.0 * mu;
  const double c_in = incident == IncidentKind::p ? m.vp : m.vs;
  const double p = std::sin(theta) / c_in;
  const cd eta_in(-std::cos(theta) / c_in);
  const PlaneWave in =
      incident == IncidentKind::p ? p_wave(p, eta_in, m.vp) : s_wave(p, eta_in, m.vs);
  LysmerReflection r;
  const PlaneWave rp = p_wave(p, upgoing_eta(p, m.vp, r.p_evanescent), m.vp);
  const PlaneWave rs = s_wave(p, upgoing_eta(p, m.vs, r.s_evanescent), m.vs);

  // g_P R_P + g_S R_S = -g_in (Cramer's rule).
  const auto gi = residual(in, lambda, mu, m);
  const auto gp = residual(rp, lambda, mu, m);
  const auto gs = residual(rs, lambda, mu, m);
  const cd det = gp[0] * gs[1] - gs[0] * gp[1];
  r.r_p = (-gi[0] * gs[1] + gs[0] * gi[1]) / det;
  r.r_s = (-gp[0] * gi[1] + gi[0] * gp[1]) / det;

  // Energy flux normal to the boundary ~ rho c |A|^2 cos(angle) = rho c^2 |A|^2 Re(eta).
  const double flux_in = c_in * c_in * std::cos(theta) / c_in;
  r.energy_p =
      r.p_evanescent ? 0.0 : std::norm(r.r_p) * m.vp * m.vp * rp.slowness[1].real() / flux_in;
  r.energy_s =
      r.s_evanescent ? 0.0 : std::norm(r.r_s) * m.vs * m.vs * rs.slowness[1].real() / flux_in;

  // Dashpot power: <v.D v> = omega^2 / 2 Re(U^H D U) with U the total boundary displacement;
  // incident flux: omega^2 / 2 rho c cos(theta).
  std::array<cd, 2> u{};
  for (int k = 0; k < 2; ++k)
    u[k] = in.polarisation[k] + r.r_p * rp.polarisation[k] + r.r_s * rs.polarisation[k];
  const double dashpot = m.density * (m.b * m.vs * std::norm(u[0]) + m.a * m.vp * std::norm(u[1]));
  r.energy_absorbed = dashpot / (m.density * c_in * std::cos(theta));
  return r;
}

} // namespace ddafem::fem
