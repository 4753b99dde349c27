// Coefficients of Newmark's scheme (docs/reference/physics.md section 2) shared by the blocks'
// boundary dashpots (dda/) and the far field (fem/): with u1 - u0 = d over a step dt,
//   a1 = d / (beta dt^2) - v0 / (beta dt) - (1 / (2 beta) - 1) a0,
//   v1 = gamma / (beta dt) d + (1 - gamma / beta) v0 + dt (1 - gamma / (2 beta)) a0.
#pragma once

namespace ddafem
{
/// The factors of the new displacement in Newmark's a1 and v1 (and so of the mass and the
/// damping in the effective stiffness), for beta [-], gamma [-] and a step dt [s].
struct NewmarkCoefficients
{
  double mass_u = 0.0;    ///< 1 / (beta dt^2) [1/s^2]: d(a1)/d(u1)
  double mass_v = 0.0;    ///< 1 / (beta dt) [1/s]: the factor of v0 in a1 (with a minus sign)
  double damping_u = 0.0; ///< gamma / (beta dt) [1/s]: d(v1)/d(u1)
};

inline NewmarkCoefficients newmark_coefficients(double beta, double gamma, double dt)
{
  NewmarkCoefficients c;
  c.mass_u = 1.0 / (beta * dt * dt);
  c.mass_v = 1.0 / (beta * dt);
  c.damping_u = gamma / (beta * dt);
  return c;
}

/// The part of Newmark's end velocity that the step's displacement d does not set:
/// v1 = damping_u d + offset, offset = (1 - gamma / beta) v0 + dt (1 - gamma / (2 beta)) a0,
/// from the velocity v0 and acceleration a0 at the step's start. A dashpot of C on v1 adds
/// damping_u C to the step's matrix and -C offset to its right-hand side. T: a scalar or an
/// Eigen vector [m/s, and the block's other unknowns' rates].
template <typename T>
T newmark_velocity_offset(double beta, double gamma, double dt, const T& v0, const T& a0)
{
  return (1.0 - gamma / beta) * v0 + dt * (1.0 - gamma / (2.0 * beta)) * a0;
}

} // namespace ddafem
