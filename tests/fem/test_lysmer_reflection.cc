// Analytic Lysmer-Kuhlemeyer reflection coefficients: normal incidence, the free-surface limit
// (Aki & Richards 2002, eq. 5.27-5.28) and the energy balance.
#include "fem/lysmer_reflection.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{
using namespace ddafem::fem;

LysmerMedium medium(const double dashpots)
{
  LysmerMedium m;
  m.density = 2000.0;
  m.vs = 1000.0;
  m.vp = std::sqrt(3.0) * 1000.0;
  m.a = dashpots;
  m.b = dashpots;
  return m;
}

double deg(const double d)
{
  return d * M_PI / 180.0;
}

TEST(LysmerReflection, NormalIncidenceIsAbsorbed)
{
  for (const auto kind : {IncidentKind::p, IncidentKind::sv})
  {
    const auto r = lysmer_reflection(kind, 0.0, medium(1.0));
    EXPECT_NEAR(std::abs(r.r_p), 0.0, 1e-12);
    EXPECT_NEAR(std::abs(r.r_s), 0.0, 1e-12);
    EXPECT_NEAR(r.energy_absorbed, 1.0, 1e-12);
  }
}

// Aki & Richards (2002) eq. 5.27 (P incidence) and 5.28 (SV incidence) on a free surface, as
// moduli (their sign conventions for the polarisations differ from ours).
TEST(LysmerReflection, ZeroDashpotsGiveTheFreeSurfaceCoefficients)
{
  const auto m = medium(0.0);
  const double alpha = m.vp, beta = m.vs;
  for (const double angle : {5.0, 15.0, 30.0, 45.0, 60.0, 80.0})
  {
    // P incidence at i = angle; reflected S at j.
    {
      const double i = deg(angle);
      const double p = std::sin(i) / alpha;
      const double j = std::asin(p * beta);
      const double q = 1.0 / (beta * beta) - 2.0 * p * p;
      const double c = 4.0 * p * p * std::cos(i) / alpha * std::cos(j) / beta;
      const double D = q * q + c;
      const double pp = (-q * q + c) / D;
      const double ps = 4.0 * alpha / beta * p * std::cos(i) / alpha * q / D;
      const auto r = lysmer_reflection(IncidentKind::p, i, m);
      EXPECT_NEAR(std::abs(r.r_p), std::abs(pp), 1e-12) << angle;
      EXPECT_NEAR(std::abs(r.r_s), std::abs(ps), 1e-12) << angle;
      EXPECT_NEAR(r.energy_reflected(), 1.0, 1e-12) << angle;
      EXPECT_NEAR(r.energy_absorbed, 0.0, 1e-12) << angle;
    }
    // SV incidence at j = angle, below the critical angle asin(beta / alpha) = 35.26 deg.
    {
      const double j = deg(angle);
      const double p = std::sin(j) / beta;
      const auto r = lysmer_reflection(IncidentKind::sv, j, m);
      if (p * alpha < 1.0)
      {
        const double i = std::asin(p * alpha);
        const double q = 1.0 / (beta * beta) - 2.0 * p * p;
        const double c = 4.0 * p * p * std::cos(i) / alpha * std::cos(j) / beta;
        const double D = q * q + c;
        const double ss = (q * q - c) / D;
        const double sp = 4.0 * beta / alpha * p * std::cos(j) / beta * q / D;
        EXPECT_FALSE(r.p_evanescent);
        EXPECT_NEAR(std::abs(r.r_p), std::abs(sp), 1e-12) << angle;
        EXPECT_NEAR(std::abs(r.r_s), std::abs(ss), 1e-12) << angle;
      }
      else
      {
        EXPECT_TRUE(r.p_evanescent);
        EXPECT_FALSE(r.amplitude_p().has_value());
        EXPECT_NEAR(std::abs(r.r_s), 1.0, 1e-12) << angle; // total reflection
      }
      EXPECT_NEAR(r.energy_reflected(), 1.0, 1e-12) << angle;
    }
  }
}

TEST(LysmerReflection, EnergyBalanceWithDashpots)
{
  for (const auto kind : {IncidentKind::p, IncidentKind::sv})
    for (double angle = 0.0; angle < 89.0; angle += 2.5)
    {
      const auto r = lysmer_reflection(kind, deg(angle), medium(1.0));
      EXPECT_NEAR(r.energy_reflected() + r.energy_absorbed, 1.0, 1e-12) << angle;
      EXPECT_GE(r.energy_absorbed, 0.0);
    }
}

TEST(LysmerReflection, ReflectionGrowsWithAngle)
{
  const auto r15 = lysmer_reflection(IncidentKind::p, deg(15.0), medium(1.0));
  const auto r60 = lysmer_reflection(IncidentKind::p, deg(60.0), medium(1.0));
  EXPECT_GT(r15.energy_reflected(), 0.0);
  EXPECT_LT(r15.energy_reflected(), r60.energy_reflected());
  EXPECT_LT(r60.energy_reflected(), 1.0);
}

} // namespace

// FE measurement (issue 5 acceptance "Oblique incidence", coarse and fast; all angles:
// tools/verify_lysmer.py).
#include "fem/lysmer_measurement.h"

namespace
{
using namespace ddafem::fem;

void expect_measured(const IncidentKind kind, const double angle)
{
  LysmerMeasurementSettings s;
  s.incident = kind;
  s.angle_deg = angle;
  s.elements_per_wavelength = 4.0;
  s.steps_per_period = 20.0;
  s.domain_factor = 0.5;
  const auto m = measure_lysmer_reflection(s);
  const auto ap = m.analytic.amplitude_p();
  const auto as = m.analytic.amplitude_s();
  ASSERT_EQ(m.r_p.has_value(), ap.has_value());
  ASSERT_TRUE(m.r_s.has_value() && as.has_value());
  if (ap)
  {
    EXPECT_NEAR(*m.r_p, *ap, 0.02);
  }
  EXPECT_NEAR(*m.r_s, *as, 0.02);
  EXPECT_NEAR(m.energy_reflected, m.analytic.energy_reflected(), 0.02);
}

TEST(LysmerMeasured, PWaveAt30Degrees)
{
  expect_measured(IncidentKind::p, 30.0);
}

TEST(LysmerMeasured, SvWaveAt45DegreesBeyondCritical)
{
  expect_measured(IncidentKind::sv, 45.0);
}
} // namespace
