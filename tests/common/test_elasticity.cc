// Isotropic elasticity (common/elasticity.h) against numbers worked by hand.
#include "common/elasticity.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{
// A rock: E = 20 GPa, nu = 0.25, rho = 2500 kg/m^3.
constexpr double e = 2e10, nu = 0.25, rho = 2500.0;

TEST(Elasticity, LameParametersOfARock)
{
  // lambda = 2e10 * 0.25 / (1.25 * 0.5) = 8e9 Pa; mu = 2e10 / 2.5 = 8e9 Pa.
  EXPECT_NEAR(ddafem::lame_lambda(e, nu), 8e9, 1e-12 * 8e9);
  EXPECT_NEAR(ddafem::shear_modulus(e, nu), 8e9, 1e-12 * 8e9);
  // M = lambda + 2 mu = 2e10 * 0.75 / 0.625 = 2.4e10 Pa.
  EXPECT_NEAR(ddafem::p_wave_modulus(e, nu), 2.4e10, 1e-12 * 2.4e10);
}

TEST(Elasticity, WaveSpeedsOfARock)
{
  // vp = sqrt(2.4e10 / 2500) = 3098.39 m/s; vs = sqrt(8e9 / 2500) = 1788.85 m/s.
  EXPECT_NEAR(ddafem::p_wave_speed(e, nu, rho), 3098.386677, 1e-6);
  EXPECT_NEAR(ddafem::s_wave_speed(e, nu, rho), 1788.854382, 1e-6);
  EXPECT_NEAR(ddafem::p_wave_speed(e, nu, rho), std::sqrt(ddafem::p_wave_modulus(e, nu) / rho),
              1e-12 * 3098.4);
  EXPECT_NEAR(ddafem::s_wave_speed(e, nu, rho), std::sqrt(ddafem::shear_modulus(e, nu) / rho),
              1e-12 * 1788.9);
}
} // namespace
