// Newmark's coefficients (common/newmark.h) against numbers worked by hand.
#include "common/newmark.h"

#include <gtest/gtest.h>

namespace
{
TEST(Newmark, TrapezoidalCoefficientsAtAMillisecond)
{
  // beta = 1/4, gamma = 1/2, dt = 1 ms: 1 / (beta dt^2) = 4e6 1/s^2, 1 / (beta dt) = 4000 1/s,
  // gamma / (beta dt) = 2000 1/s.
  const ddafem::NewmarkCoefficients c = ddafem::newmark_coefficients(0.25, 0.5, 1e-3);
  EXPECT_NEAR(c.mass_u, 4e6, 1e-12 * 4e6);
  EXPECT_NEAR(c.mass_v, 4000.0, 1e-12 * 4000.0);
  EXPECT_NEAR(c.damping_u, 2000.0, 1e-12 * 2000.0);
}
} // namespace
