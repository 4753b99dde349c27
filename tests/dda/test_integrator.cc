// Time integrators of the DDA step (dda/integrator.h) on a linear oscillator, whose exact
// motion is known: order of accuracy, algorithmic damping at high frequency, constant force.
#include "dda/integrator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <tuple>
#include <utility>

namespace ddafem::dda
{
namespace
{
/// The free vibration u'' + omega^2 u = 0 from u(0) = 1, v(0) = 0 with the DDA step's
/// algebra on one unknown (mass 1, stiffness omega^2; the force at the step's start is
/// -k u_n, its end -k (u_n + d)): (u, v / omega) after n_steps of dt.
std::pair<double, double> oscillate_state(const IntegratorCoefficients& c, double omega, double dt,
                                          int n_steps)
{
  const Matrix6 mass = Matrix6::Identity();
  const double k = omega * omega;
  double u = 1.0;
  KinematicState state;
  state.force.setConstant(-k * u); // consistent start: r0 = -k u0 = M a0
  state.acceleration = state.force;
  for (int n = 0; n < n_steps; ++n)
  {
    const Vector6 rhs = Vector6::Constant(-k * u) + inertia_force(c, mass, state, dt);
    const Vector6 d = rhs / (k + c.mass_factor(dt));
    state = advance_state(c, mass, state, d, dt);
    u += d[0];
  }
  return {u, state.velocity[0] / omega};
}

double oscillate(const IntegratorCoefficients& c, double omega, double dt, int n_steps)
{
  return oscillate_state(c, omega, dt, n_steps).first;
}

/// Distance in the phase plane from the exact state after one period, (1, 0), at n steps per
/// period: amplitude and phase errors alike.
double period_error(const IntegratorCoefficients& c, int n)
{
  const double omega = 2.0 * M_PI;
  const auto [u, w] = oscillate_state(c, omega, 1.0 / n, n);
  return std::hypot(u - 1.0, w);
}

TEST(Integrator, ChungHulbertParameters)
{
  // rho_inf = 1 is the trapezoidal rule in the alpha form (alpha_m = alpha_f = 1/2).
  const IntegratorCoefficients one = integrator_coefficients(Integrator::generalized_alpha, 1.0);
  EXPECT_DOUBLE_EQ(one.beta, 0.25);
  EXPECT_DOUBLE_EQ(one.gamma, 0.5);
  EXPECT_DOUBLE_EQ(one.alpha_m, 0.5);
  EXPECT_DOUBLE_EQ(one.alpha_f, 0.5);
  // rho_inf = 0.5: alpha_m = 0, alpha_f = 1/3, gamma = 5/6, beta = 4/9.
  const IntegratorCoefficients half = integrator_coefficients(Integrator::generalized_alpha, 0.5);
  EXPECT_NEAR(half.alpha_m, 0.0, 1e-15);
  EXPECT_NEAR(half.alpha_f, 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(half.gamma, 5.0 / 6.0, 1e-15);
  EXPECT_NEAR(half.beta, 4.0 / 9.0, 1e-15);
  const IntegratorCoefficients shi = integrator_coefficients(Integrator::dda, 0.5);
  EXPECT_EQ(shi.beta, 0.5);
  EXPECT_EQ(shi.gamma, 1.0);
  EXPECT_EQ(shi.alpha_f, 0.0);
}

TEST(Integrator, SecondOrderExceptShisScheme)
{
  // Error after one period at 40 and 80 steps per period: the ratio is 2^order.
  for (const auto& [integrator, rho, order] :
       {std::tuple{Integrator::generalized_alpha, 0.5, 2.0},
        std::tuple{Integrator::generalized_alpha, 0.0, 2.0},
        std::tuple{Integrator::newmark_trapezoidal, 1.0, 2.0},
        std::tuple{Integrator::dda, 1.0, 1.0}})
  {
    const IntegratorCoefficients c = integrator_coefficients(integrator, rho);
    EXPECT_NEAR(std::log2(period_error(c, 40) / period_error(c, 80)), order, 0.1)
        << name_of(integrator) << " rho " << rho;
  }
}

TEST(Integrator, HighFrequenciesDecayAtTheSpectralRadius)
{
  // omega dt = 1e4 (a stiff contact spring): the amplification's eigenvalues tend to -rho_inf
  // (a double root), so |u_n| ~ n rho^n; the ratio over 10 steps from step 100 is
  // (110 / 100) rho^10.
  for (const double rho : {0.0, 0.3, 0.5, 0.8})
  {
    const IntegratorCoefficients c = integrator_coefficients(Integrator::generalized_alpha, rho);
    const double u100 = oscillate(c, 1e4, 1.0, 100);
    const double u110 = oscillate(c, 1e4, 1.0, 110);
    if (rho == 0.0)
      EXPECT_LT(std::abs(u110), 1e-12);
    else
      EXPECT_NEAR(std::pow(std::abs(u110 / u100) / 1.1, 0.1), rho, 0.02 * rho) << rho;
  }
  // The trapezoidal rule keeps them: the amplitude in the phase plane stays 1 (its energy
  // u^2 + (v / omega)^2 is conserved to the rounding of k d at omega^2 = 1e8).
  const IntegratorCoefficients trapezoidal =
      integrator_coefficients(Integrator::newmark_trapezoidal, 1.0);
  const auto [u, w] = oscillate_state(trapezoidal, 1e4, 1.0, 101);
  EXPECT_NEAR(std::hypot(u, w), 1.0, 1e-6);
}

TEST(Integrator, ConstantForceIsExact)
{
  // A block under gravity alone from rest (r0 = M g, a0 = g): u = g t^2 / 2 at every step, for
  // every scheme.
  const double g = -9.81, dt = 0.01;
  for (const Integrator integrator :
       {Integrator::generalized_alpha, Integrator::dda, Integrator::newmark_trapezoidal})
  {
    const IntegratorCoefficients c = integrator_coefficients(integrator, 0.5);
    const Matrix6 mass = 2.0 * Matrix6::Identity();
    KinematicState state;
    state.force.setConstant(2.0 * g);
    state.acceleration.setConstant(g);
    double u = 0.0;
    for (int n = 1; n <= 50; ++n)
    {
      const Vector6 rhs = Vector6::Constant(2.0 * g) + inertia_force(c, mass, state, dt);
      const Vector6 d = rhs / (2.0 * c.mass_factor(dt));
      state = advance_state(c, mass, state, d, dt);
      u += d[0];
      EXPECT_NEAR(u, 0.5 * g * (n * dt) * (n * dt), 1e-12) << name_of(integrator);
    }
    EXPECT_NEAR(state.force[0], 2.0 * g, 1e-9);
  }
}

/// Bathe's composite scheme on the oscillator: n pairs of a generalized-alpha and a
/// three-point backward Euler half step of dt / 2 each, (u, v / omega) at the end. The
/// generalized-alpha half starts from its own a_n (StepScheme::composite_acceleration).
std::pair<double, double> oscillate_bathe(double omega, double dt, int n_steps)
{
  const Matrix6 mass = Matrix6::Identity();
  const double k = omega * omega, h = 0.5 * dt;
  const IntegratorCoefficients first = integrator_coefficients(Integrator::bathe, 0.0);
  const IntegratorCoefficients second = backward_euler_half_coefficients();
  double u = 1.0;
  KinematicState state;
  state.force.setConstant(-k * u);
  state.acceleration = state.force;
  const auto half = [&](const IntegratorCoefficients& c, const KinematicState& start)
  {
    const Vector6 rhs = Vector6::Constant(-k * u) + inertia_force(c, mass, start, h);
    const Vector6 d = rhs / (k + c.mass_factor(h));
    u += d[0];
    return std::pair{advance_state(c, mass, start, d, h), d};
  };
  for (int n = 0; n < n_steps; ++n)
  {
    const Vector6 v0 = state.velocity;
    const auto [mid, d1] = half(first, state);
    KinematicState start;
    std::tie(start.velocity, start.acceleration) =
        backward_euler_start<Vector6>(h, v0, mid.velocity, d1);
    state = half(second, start).first;
    state.acceleration = (1.0 - first.alpha_f) * state.force + first.alpha_f * mid.force;
  }
  return {u, state.velocity[0] / omega};
}

TEST(Integrator, BatheSecondHalfIsThreePointBackwardEuler)
{
  // Newmark's updates from backward_euler_start give Bathe's formulas for any data.
  const double h = 0.37;
  const double u0 = 0.3, v0 = -1.2, d1 = 0.45, v_mid = 0.8, d2 = -0.21;
  const auto [v_star, a_star] = backward_euler_start(h, v0, v_mid, d1);
  const auto [a1, v1] = newmark_end(backward_euler_half_coefficients(), h, d2, v_star, a_star);
  const double dt = 2.0 * h, u_mid = u0 + d1, u1 = u_mid + d2;
  const double v_expected = (u0 - 4.0 * u_mid + 3.0 * u1) / dt;
  EXPECT_NEAR(v1, v_expected, 1e-13);
  EXPECT_NEAR(a1, (v0 - 4.0 * v_mid + 3.0 * v_expected) / dt, 1e-12);
}

TEST(Integrator, BatheSecondOrderWithLessPeriodErrorAndStiffModesAnnihilated)
{
  // Error after one period: ratio 2^2 from 40 to 80 steps per period; below generalized-alpha
  // 0.2's at the same steps per period.
  const double omega = 2.0 * M_PI;
  const auto error = [&](int n)
  {
    const auto [u, w] = oscillate_bathe(omega, 1.0 / n, n);
    return std::hypot(u - 1.0, w);
  };
  EXPECT_NEAR(std::log2(error(40) / error(80)), 2.0, 0.1);
  EXPECT_LT(error(100),
            period_error(integrator_coefficients(Integrator::generalized_alpha, 0.2), 100));
  // omega dt = 1e4: a stiff mode falls about 4.3-fold per step (the generalized-alpha half's
  // -1/2, the backward Euler half's 0, coupled through a_n): 1.1e-4 after 6 steps.
  const auto [u, w] = oscillate_bathe(1e4, 1.0, 6);
  EXPECT_LT(std::hypot(u, w), 2e-4);
}

} // namespace
} // namespace ddafem::dda
