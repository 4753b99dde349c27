// The processing of recorded ground motions (common/ground_motion.h) against motions whose
// integrals, peaks, Arias intensity and spectrum are known in closed form.
#include "common/ground_motion.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace
{
using namespace ddafem;

std::vector<double> sampled(double dt, double length, double (*f)(double))
{
  std::vector<double> x(static_cast<std::size_t>(std::llround(length / dt)) + 1);
  for (std::size_t i = 0; i < x.size(); ++i)
    x[i] = f(dt * static_cast<double>(i));
  return x;
}

double peak(const std::vector<double>& x)
{
  double p = 0.0;
  for (const double xi : x)
    p = std::max(p, std::abs(xi));
  return p;
}

/// A motion that starts and ends at rest with no permanent displacement: 10 cycles of 2 Hz in
/// a sin^2 envelope over 5 s, u(t) = 0.01 sin^2(pi t / 5) sin(4 pi t) [m].
double clean_displacement(double t)
{
  return 0.01 * std::pow(std::sin(M_PI * t / 5.0), 2) * std::sin(4.0 * M_PI * t);
}

TEST(GroundMotion, TrapezoidalIntegralIsExactForALine)
{
  const std::vector<double> y = integrate(sampled(0.1, 2.0, [](double t) { return t; }), 0.1);
  for (std::size_t i = 0; i < y.size(); ++i)
    EXPECT_NEAR(y[i], 0.5 * std::pow(0.1 * static_cast<double>(i), 2), 1e-14);
}

TEST(GroundMotion, DerivativesOfVelocityAndDisplacement)
{
  // v = sin(2 pi t): central differences err by (omega dt)^2 / 6 = 6.6e-5 of omega at dt = 1 ms.
  const double dt = 1e-3, omega = 2.0 * M_PI;
  const std::vector<double> from_v =
      to_acceleration(sampled(dt, 1.0, [](double t) { return std::sin(2.0 * M_PI * t); }), dt,
                      MotionQuantity::velocity);
  const std::vector<double> from_u =
      to_acceleration(sampled(dt, 1.0, [](double t) { return -std::cos(2.0 * M_PI * t); }), dt,
                      MotionQuantity::displacement);
  for (std::size_t i = 1; i + 1 < from_v.size(); ++i)
  {
    const double t = dt * static_cast<double>(i);
    EXPECT_NEAR(from_v[i], omega * std::cos(omega * t), 1e-4 * omega);
    EXPECT_NEAR(from_u[i], omega * omega * std::cos(omega * t), 1e-4 * omega * omega);
  }
}

TEST(GroundMotion, TaperRisesAndFallsAsAHalfCosine)
{
  std::vector<double> x(101, 1.0);
  taper_ends(x, 0.01, 0.1); // 10 samples at each end
  EXPECT_EQ(x.front(), 0.0);
  EXPECT_EQ(x.back(), 0.0);
  EXPECT_NEAR(x[5], 0.5, 1e-12); // half way up the half cosine
  EXPECT_NEAR(x[95], 0.5, 1e-12);
  EXPECT_EQ(x[10], 1.0);
  EXPECT_EQ(x[50], 1.0);
}

TEST(GroundMotion, BaselineCorrectionRemovesAnOffsetAndEndsAtRest)
{
  const double dt = 0.005;
  const std::vector<double> clean =
      to_acceleration(sampled(dt, 5.0, clean_displacement), dt, MotionQuantity::displacement);
  const double pga = peak(clean);

  // A clean motion: the fit finds almost nothing to take out. Its displacement is 10 cycles
  // under an envelope; its projection on t^2 and t^3 over 5 s is below 1e-3 of its peak, and so
  // is the change of the acceleration.
  std::vector<double> a = clean;
  correct_baseline(a, dt, 3);
  for (std::size_t i = 0; i < a.size(); ++i)
    EXPECT_NEAR(a[i], clean[i], 1e-3 * pga);

  // The same motion with a constant offset of 2 % of its peak (a shifted accelerometer zero):
  // it would end at 0.02 pga x 5 s = 0.16 m/s and 0.4 m away. Corrected, it ends at rest,
  // within a millimetre of where it started, and the offset is gone to 1e-3 of the peak.
  a = clean;
  for (double& x : a)
    x += 0.02 * pga;
  const BaselineCorrection c = correct_baseline(a, dt, 3);
  EXPECT_NEAR(c.end_velocity_before, 0.02 * pga * 5.0, 1e-3);
  EXPECT_NEAR(c.end_displacement_before, 0.5 * 0.02 * pga * 25.0, 1e-2);
  const std::vector<double> v = integrate(a, dt);
  EXPECT_NEAR(v.back(), 0.0, 1e-12);
  EXPECT_LT(std::abs(c.end_displacement_after), 1e-3);
  EXPECT_NEAR(c.end_displacement_after, integrate(v, dt).back(), 1e-15);
  for (std::size_t i = 0; i < a.size(); ++i)
    EXPECT_NEAR(a[i], clean[i], 1e-3 * pga);
}

TEST(GroundMotion, SummaryOfASineTrain)
{
  // a = 3 sin(2 pi 5 t) for 10 s (50 cycles), sampled every 2 ms: peaks fall on samples.
  const double dt = 0.002;
  const std::vector<double> a =
      sampled(dt, 10.0, [](double t) { return 3.0 * std::sin(10.0 * M_PI * t); });
  const MotionSummary s = summarize_motion(a, dt);
  EXPECT_DOUBLE_EQ(s.duration, 10.0);
  EXPECT_NEAR(s.pga, 3.0, 1e-9);
  // v = 3 / omega (1 - cos omega t): peak 6 / omega; u drifts: 3 t / omega at most.
  const double omega = 10.0 * M_PI;
  EXPECT_NEAR(s.pgv, 6.0 / omega, 1e-4);
  EXPECT_NEAR(s.pgd, 3.0 * 10.0 / omega, 1e-3);
  // I_a = pi / (2 g) A^2 T / 2; the trapezoidal rule of sin^2 over whole cycles is exact.
  EXPECT_NEAR(s.arias_intensity, M_PI / (2.0 * standard_gravity) * 9.0 * 5.0, 1e-9);
  // Energy builds up evenly: 5 % at 0.5 s and 95 % at 9.5 s, to within a quarter period.
  EXPECT_NEAR(s.t5, 0.5, 0.05);
  EXPECT_NEAR(s.t95, 9.5, 0.05);
  // The spectrum is the 5 Hz line, widened by the 10 s window (main lobe +-0.1 Hz) and its
  // sidelobes, which fall as 1 / (f - 5)^2 in power: the mean frequency is within 1 %, and 99 %
  // of the power lies within 1 Hz of the line.
  EXPECT_NEAR(s.mean_frequency, 5.0, 0.05);
  EXPECT_GT(s.f99, 5.0);
  EXPECT_LT(s.f99, 6.0);
}

TEST(GroundMotion, OutcropRecordsAreHalvedForTheIncidentWave)
{
  EXPECT_EQ(incident_factor(RecordMotion::outcrop), 0.5);
  EXPECT_EQ(incident_factor(RecordMotion::within), 1.0);
  EXPECT_EQ(incident_factor(RecordMotion::incident), 1.0);
}

} // namespace
