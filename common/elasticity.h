// Isotropic linear elasticity shared by the blocks (dda/) and the far field (fem/): the 2D
// idealisation, the moduli from Young's modulus E [Pa] and Poisson's ratio nu [-], and the
// body-wave speeds with the density rho [kg/m^3]. Each formula is written once, in the order of
// operations its callers used, so that results are bitwise those of the former copies.
#pragma once

#include "common/enum_names.h"

#include <array>
#include <cmath>

namespace ddafem
{
/// 2D idealisation of the elasticity of the blocks and of the far field.
enum class PlaneMode
{
  stress, ///< plane stress (Shi's default; a thin slab or a one-block-high bar)
  strain  ///< plane strain (a section through a long tunnel)
};

constexpr std::array<EnumName<PlaneMode>, 2> enum_names(PlaneMode)
{
  return {{{PlaneMode::stress, "stress"}, {PlaneMode::strain, "strain"}}};
}

/// Lamé's first parameter lambda = E nu / ((1 + nu) (1 - 2 nu)) [Pa] (3D, so plane strain).
inline double lame_lambda(double e, double nu)
{
  return e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
}

/// Shear modulus, Lamé's mu = G = E / (2 (1 + nu)) [Pa].
inline double shear_modulus(double e, double nu)
{
  return e / (2.0 * (1.0 + nu));
}

/// P-wave (constrained) modulus M = lambda + 2 mu = E (1 - nu) / ((1 + nu) (1 - 2 nu)) [Pa].
inline double p_wave_modulus(double e, double nu)
{
  return e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
}

/// P-wave speed in an unbounded body (plane strain)
/// vp = sqrt(E (1 - nu) / (rho (1 + nu) (1 - 2 nu))) = sqrt(M / rho) [m/s].
inline double p_wave_speed(double e, double nu, double rho)
{
  return std::sqrt(e * (1.0 - nu) / (rho * (1.0 + nu) * (1.0 - 2.0 * nu)));
}

/// S-wave speed vs = sqrt(E / (2 rho (1 + nu))) = sqrt(G / rho) [m/s].
inline double s_wave_speed(double e, double nu, double rho)
{
  return std::sqrt(e / (2.0 * rho * (1.0 + nu)));
}

} // namespace ddafem
