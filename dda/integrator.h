// Time integration of the DDA step: Newmark schemes and generalized-alpha (Chung & Hulbert
// 1993) in one form. Pure functions of one block's 6 unknowns, no geometry.
#pragma once

#include "dda/types.h"

#include <utility>

namespace ddafem::dda
{
/// The time integrator.
enum class Integrator
{
  /// Chung & Hulbert's generalized-alpha: second order, high frequencies damped to the chosen
  /// spectral radius rho_inf (TimeSettings::spectral_radius) with the least low-frequency damping
  generalized_alpha,
  /// Shi's scheme, beta = 1/2, gamma = 1: first order; dissipative at omega dt near 1 but not
  /// at high frequencies (spectral radius 1 as omega dt grows: a stiff contact's velocity
  /// flips sign each step instead of decaying)
  dda,
  newmark_trapezoidal ///< beta = 1/4, gamma = 1/2: second order, conserves energy
};

/// The integrator's name in scene files and outputs ("generalized_alpha", "dda",
/// "newmark_trapezoidal").
const char* integrator_name(Integrator integrator);

/// The scheme's parameters. The step's equation of motion is the generalized-alpha one,
///   M a_{n+1-alpha_m} = (1 - alpha_f) r_{n+1} + alpha_f r_n,
/// with a_{n+1-alpha_m} = (1 - alpha_m) a_{n+1} + alpha_m a_n and r the generalised force on the
/// block that is not inertia (loads, stress, springs, contacts, boundaries, ties) [N, N m];
/// Newmark's updates give a_{n+1} and v_{n+1} from the step's displacement d:
///   a_{n+1} = (d - dt v_n - dt^2 (1/2 - beta) a_n) / (beta dt^2),
///   v_{n+1} = v_n + dt ((1 - gamma) a_n + gamma a_{n+1}).
/// Newmark schemes (dda, trapezoidal) have alpha_m = alpha_f = 0.
struct IntegratorCoefficients
{
  double beta = 0.5, gamma = 1.0;
  double alpha_m = 0.0, alpha_f = 0.0;

  /// The factor of M in the step's matrix K + factor M [1/s^2]: the equation above divided by
  /// (1 - alpha_f), so that every force term keeps its Newmark form (r_{n+1} = f - K d).
  double mass_factor(double dt) const
  {
    return (1.0 - alpha_m) / ((1.0 - alpha_f) * beta * dt * dt);
  }
};

/// Chung & Hulbert's optimal parameters for a spectral radius at infinite frequency
/// rho_inf in [0, 1]: alpha_m = (2 rho - 1) / (rho + 1), alpha_f = rho / (rho + 1),
/// gamma = 1/2 - alpha_m + alpha_f, beta = (1 - alpha_m + alpha_f)^2 / 4 (rho is ignored by
/// the Newmark schemes).
IntegratorCoefficients integrator_coefficients(Integrator integrator, double spectral_radius);

/// One block's state between steps: velocity, acceleration and non-inertial force r.
struct KinematicState
{
  Vector6 velocity = Vector6::Zero();
  Vector6 acceleration = Vector6::Zero();
  Vector6 force = Vector6::Zero(); ///< r_n [N, N m]; M a_n for the Newmark schemes
};

/// The part of the step's right-hand side that carries the block's past [N, N m]:
/// [(1 - alpha_m) M (v_n / (beta dt) + (1 / (2 beta) - 1) a_n) - alpha_m M a_n + alpha_f r_n]
/// / (1 - alpha_f), with M the block's mass matrix [kg, kg m, kg m^2].
Vector6 inertia_force(const IntegratorCoefficients& c, const Matrix6& mass,
                      const KinematicState& start, double dt);

/// Newmark's acceleration and velocity at the end of a step of displacement d from velocity v
/// and acceleration a at its start: a_{n+1} = (d - dt v - dt^2 (1/2 - beta) a) / (beta dt^2),
/// v_{n+1} = v + dt ((1 - gamma) a + gamma a_{n+1}). T: a scalar or an Eigen vector.
template <typename T>
std::pair<T, T> newmark_end(const IntegratorCoefficients& c, double dt, const T& d, const T& v,
                            const T& a)
{
  const T a1 = (d - dt * v - dt * dt * (0.5 - c.beta) * a) / (c.beta * dt * dt);
  const T v1 = v + dt * ((1.0 - c.gamma) * a + c.gamma * a1);
  return {a1, v1};
}

/// The state at the step's end from the step's displacement d, the state at its start and the
/// mass matrix the step used: Newmark's a_{n+1}, v_{n+1}, and r_{n+1} from the equation of
/// motion.
KinematicState advance_state(const IntegratorCoefficients& c, const Matrix6& mass,
                             const KinematicState& start, const Vector6& d, double dt);

} // namespace ddafem::dda
