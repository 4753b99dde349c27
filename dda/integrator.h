// Time integration of the DDA step: Newmark schemes and generalized-alpha (Chung & Hulbert
// 1993) in one form. Pure functions of one block's 6 unknowns, no geometry.
#pragma once

#include "common/enum_names.h"
#include "dda/types.h"

#include <algorithm>
#include <array>
#include <utility>

namespace ddafem::dda
{
/// The time integrator.
enum class Integrator
{
  /// Chung & Hulbert's generalized-alpha: second order, high frequencies damped to the chosen
  /// spectral radius rho_inf (TimeSettings::spectral_radius) with the least low-frequency damping
  generalized_alpha,
  /// Bathe's composite scheme (Bathe & Baig 2005; Bathe 2007, gamma = 1/2): a step of dt is a
  /// half step of dt/2 then a three-point backward Euler half step of dt/2. Bathe's first half
  /// is trapezoidal, which lets a block pushed along its base rock on its contacts; ours is
  /// generalized-alpha (bathe_first_half_spectral_radius) from its own a_n
  /// (StepScheme::composite_acceleration). Second order; stiff modes fall about 4-fold per step;
  /// less period error than generalized-alpha at the same dt; two solves per step
  /// (TimeStepper takes the pairs); docs/design.md, Integrators
  bathe,
  /// Shi's scheme, beta = 1/2, gamma = 1: first order; dissipative at omega dt near 1 but not
  /// at high frequencies (spectral radius 1 as omega dt grows: a stiff contact's velocity
  /// flips sign each step instead of decaying)
  dda,
  newmark_trapezoidal ///< beta = 1/4, gamma = 1/2: second order, conserves energy
};

/// Which part of the integrator's step a call of System::advance takes; the caller (TimeStepper)
/// says it, the system does not guess it from dt.
enum class StepPart
{
  /// the whole step: every integrator but Bathe's in a dynamic stage (and Bathe's too in a
  /// static stage, where there is no motion to integrate)
  full,
  /// Bathe's first half step (generalized-alpha, or DDA's scheme while the motion starts)
  first_half,
  /// Bathe's second half step (three-point backward Euler): follows an accepted first half of
  /// the same dt
  second_half
};

constexpr std::array<EnumName<Integrator>, 4> enum_names(Integrator)
{
  return {{{Integrator::generalized_alpha, "generalized_alpha"},
           {Integrator::bathe, "bathe"},
           {Integrator::dda, "dda"},
           {Integrator::newmark_trapezoidal, "newmark_trapezoidal"}}};
}

/// rho_inf of Integrator::bathe's first half [-]: generalized-alpha with alpha_m = 0,
/// alpha_f = 1/3 (docs/design.md, Integrators).
constexpr double bathe_first_half_spectral_radius = 0.5;

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

  /// The fraction of a jump in the force at the step's start that the step's end velocity
  /// misses while the start state keeps the force of before the jump [-]: generalized-alpha's
  /// alpha_f (it applies r_{n+1-alpha_f}), Newmark's 1 - gamma (v_{n+1} takes (1 - gamma) a_n:
  /// 1/2 for the trapezoidal rule, 0 for DDA's scheme).
  double start_force_lag() const { return alpha_f > 0.0 ? alpha_f : std::max(0.0, 1.0 - gamma); }

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

/// The coefficients of a composite step's second half (Integrator::bathe): Newmark with
/// beta = 4/9, gamma = 2/3 over the half step h, from the start state of
/// backward_euler_start. (integrator_coefficients(bathe) gives the first half's:
/// generalized-alpha with bathe_first_half_spectral_radius.)
IntegratorCoefficients backward_euler_half_coefficients();

/// Bathe's second half step as a Newmark step. Over a step dt = 2h from u_n through u_{n+1/2},
/// the three-point backward Euler formulas
///   v_{n+1} = (u_n - 4 u_{n+1/2} + 3 u_{n+1}) / dt,  a_{n+1} = (v_n - 4 v_{n+1/2} + 3 v_{n+1}) /
///   dt
/// are, in the second half's displacement d = u_{n+1} - u_{n+1/2} and the first half's d1:
///   v_{n+1} = 3 d / dt + V,  a_{n+1} = 9 d / dt^2 + A,
///   V = -d1 / dt,  A = (v_n - 4 v_{n+1/2}) / dt - 3 d1 / dt^2.
/// Newmark's updates with backward_euler_half_coefficients over h give the same d-terms, and
/// the same V and A from the start state (v*, a*) returned: v* = -(V + 2 h A) / 5,
/// a* = (18 V / h - 4 A) / 5. So every force that uses Newmark's velocity (dashpots, slip
/// reversals) is right unchanged. T: a scalar or an Eigen vector; v in m/s, d in m (and the
/// blocks' other unknowns alike).
template <typename T>
std::pair<T, T> backward_euler_start(double h, const T& start_velocity, const T& mid_velocity,
                                     const T& first_displacement)
{
  const double dt = 2.0 * h;
  const T v = -first_displacement / dt;
  const T a = (start_velocity - 4.0 * mid_velocity) / dt - 3.0 * first_displacement / (dt * dt);
  return {-(v + 2.0 * h * a) / 5.0, (18.0 / h * v - 4.0 * a) / 5.0};
}

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
