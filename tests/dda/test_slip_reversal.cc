// slip_reversal and end_velocity: when a sliding contact's slip turns around within a step,
// against hand calculations.
//
// The motions are uniform decelerations a (v(t) = v0 + a t), for which the Newmark update of
// the step's slip is exact with any beta and gamma; every expected number is a ratio of small
// decimals, so the tolerance 1e-12 is rounding only.
#include "dda/contact/slip_reversal.h"

#include <gtest/gtest.h>

using namespace ddafem::dda;

namespace
{
constexpr double tol = 1e-12;

ContactForces with(ContactState state, double shear)
{
  ContactForces f;
  f.state = state;
  f.normal_force = 1000.0;
  f.shear_force = shear;
  return f;
}

/// The step's motion of a point at v0 [m/s] decelerated uniformly by a [m/s^2] over dt [s].
TangentialMotion uniform(double v0, double a, double dt)
{
  return {v0, a, v0 * dt + 0.5 * a * dt * dt};
}
} // namespace

TEST(SlipReversal, EndVelocityIsExactForAUniformAccelerationWithEveryIntegrator)
{
  for (const Integrator i :
       {Integrator::generalized_alpha, Integrator::dda, Integrator::newmark_trapezoidal})
  {
    // v(t) = 0.3 - 4 t: at dt = 0.1 s, v1 = -0.1 m/s.
    const IntegratorCoefficients c = integrator_coefficients(i, 0.2);
    EXPECT_NEAR(end_velocity(c, 0.1, uniform(0.3, -4.0, 0.1)), -0.1, tol) << ddafem::name_of(i);
  }
}

TEST(SlipReversal, FrictionTurnedAroundActedTheWrongWayBeforeTheReversal)
{
  // Slid along +t at 0.3 m/s, stops at t = 0.075 s of a 0.1 s step, slides back: the step's
  // friction (the new direction's) was wrong for the first 75% of it.
  const SlipReversal r =
      slip_reversal(with(ContactState::slide, 500.0), with(ContactState::slide, -500.0), 0.3, -0.1);
  EXPECT_NEAR(r.at, 0.75, tol);
  EXPECT_NEAR(r.mistimed, 0.75, tol);
  EXPECT_NEAR(r.speed_error, 0.4 * 0.75, tol);
}

TEST(SlipReversal, FrictionKeptActedTheWrongWayAfterTheReversal)
{
  // The step's slip is still along +t, so friction kept its direction past the stop at 75%.
  const SlipReversal r =
      slip_reversal(with(ContactState::slide, 500.0), with(ContactState::slide, 480.0), 0.3, -0.1);
  EXPECT_NEAR(r.at, 0.75, tol);
  EXPECT_NEAR(r.mistimed, 0.25, tol);
  EXPECT_NEAR(r.speed_error, 0.4 * 0.25, tol);
}

TEST(SlipReversal, ALockedSpringThatTurnsTheSlipAroundIsAReversal)
{
  // Sliding along -t, locked at the end with the relative velocity turned to +t.
  const SlipReversal r =
      slip_reversal(with(ContactState::slide, -500.0), with(ContactState::lock, 20.0), -0.2, 0.2);
  EXPECT_NEAR(r.at, 0.5, tol);
  EXPECT_NEAR(r.mistimed, 0.5, tol);
}

TEST(SlipReversal, NoReversalWithoutATurnOfTheRelativeVelocity)
{
  const ContactForces slide = with(ContactState::slide, 500.0);
  // Decelerating but still sliding along +t.
  EXPECT_EQ(slip_reversal(slide, slide, 0.3, 0.1).at, 0.0);
  // Already moving the new way at the start: the reversal was at the step's start.
  EXPECT_EQ(slip_reversal(slide, with(ContactState::slide, -500.0), -0.01, -0.1).at, 0.0);
  // Not sliding at the start, or open at the end.
  EXPECT_EQ(slip_reversal(with(ContactState::lock, 500.0), slide, 0.3, -0.1).at, 0.0);
  EXPECT_EQ(slip_reversal(slide, ContactForces{}, 0.3, -0.1).at, 0.0);
}

TEST(SlipReversal, SlipErrorIsTheSpeedErrorOverTheSlideItEnds)
{
  // A block sliding for 0.125 s (half a 4 Hz cycle) with 1.5 mm/s of speed error: 0.19 mm; a
  // contact chattering for 0.3 ms with 0.1 mm/s: 30 nm.
  EXPECT_NEAR(slip_error(1.5e-3, 0.125), 1.875e-4, tol);
  EXPECT_NEAR(slip_error(1e-4, 3e-4), 3e-8, tol);
}
