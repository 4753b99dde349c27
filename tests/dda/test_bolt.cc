// The bolt law (dda/bolt.h) against hand values.
//
// The law of every test: head (0, 0), anchor (0, 4) m, so L0 = 4 m; E_s = 200e9 Pa and
// A_s = 5e-4 m^2 give k = E_s A_s / L0 = 2.5e7 N/m; yield force 1e5 N; rupture strain 0.1, so
// it ruptures beyond 0.4 m of elongation. Every expected value is a product or quotient of
// numbers exactly representable or nearly so; the tolerances are far below the smallest value
// that tells two outcomes apart (1 N, 1 um).
#include "dda/bolt.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace ddafem::dda;

namespace
{
constexpr double force_tol = 1e-6;   // [N]
constexpr double length_tol = 1e-12; // [m]

BoltLaw law(double pretension = 0.0)
{
  return make_bolt_law(Point(0.0, 0.0), Point(0.0, 4.0), 200e9, 5e-4, pretension, 1e5, 0.1);
}
} // namespace

TEST(BoltLaw, FreeLengthStiffnessAndRuptureElongation)
{
  const BoltLaw l = law(2e4);
  EXPECT_DOUBLE_EQ(l.free_length, 4.0);
  EXPECT_DOUBLE_EQ(l.stiffness, 2.5e7);
  EXPECT_DOUBLE_EQ(l.pretension, 2e4);
  EXPECT_DOUBLE_EQ(l.yield_force, 1e5);
  EXPECT_DOUBLE_EQ(l.rupture_elongation, 0.4);
}

TEST(BoltLaw, ElasticForceIsPretensionPlusKTimesElongation)
{
  // 2 mm of stretch: N = 2e4 + 2.5e7 x 2e-3 = 7e4 N.
  const BoltForces f = evaluate_bolt(law(2e4), BoltForces{}, 4.002);
  EXPECT_EQ(f.state, BoltState::elastic);
  EXPECT_NEAR(f.axial_force, 7e4, force_tol);
  EXPECT_EQ(f.plastic_elongation, 0.0);
  EXPECT_EQ(bolt_tangent_stiffness(law(2e4), f), 2.5e7);
  // As installed (L = L0) it carries its pretension.
  EXPECT_NEAR(evaluate_bolt(law(2e4), BoltForces{}, 4.0).axial_force, 2e4, force_tol);
}

TEST(BoltLaw, SlackBoltCarriesNoCompression)
{
  // Shortened by 1 mm without pretension: the spring would push with 2.5e4 N.
  const BoltForces f = evaluate_bolt(law(), BoltForces{}, 3.999);
  EXPECT_EQ(f.state, BoltState::slack);
  EXPECT_EQ(f.axial_force, 0.0);
  EXPECT_EQ(bolt_tangent_stiffness(law(), f), 0.0);
  // With 2e4 N of pretension it stays taut down to 0.8 mm of shortening: 2e4 - 2.5e7 x 5e-4.
  const BoltForces taut = evaluate_bolt(law(2e4), BoltForces{}, 3.9995);
  EXPECT_EQ(taut.state, BoltState::elastic);
  EXPECT_NEAR(taut.axial_force, 7.5e3, force_tol);
}

TEST(BoltLaw, YieldKeepsTheForceAndGrowsThePlasticElongation)
{
  // 10 mm of stretch: the trial 2.5e5 N is beyond 1e5 N; elastic part 1e5 / 2.5e7 = 4 mm, so
  // 6 mm are plastic.
  const BoltForces f = evaluate_bolt(law(), BoltForces{}, 4.01);
  EXPECT_EQ(f.state, BoltState::yielding);
  EXPECT_NEAR(f.axial_force, 1e5, force_tol);
  EXPECT_NEAR(f.plastic_elongation, 6e-3, length_tol);
  EXPECT_EQ(bolt_tangent_stiffness(law(), f), 0.0);
  // With 2e4 N of pretension the elastic part is (1e5 - 2e4) / 2.5e7 = 3.2 mm.
  EXPECT_NEAR(evaluate_bolt(law(2e4), BoltForces{}, 4.01).plastic_elongation, 6.8e-3, length_tol);
}

TEST(BoltLaw, UnloadingAfterYieldIsElasticAboutThePlasticElongation)
{
  const BoltForces yielded = evaluate_bolt(law(), BoltForces{}, 4.01);
  // Back by 1 mm: N = 2.5e7 (0.009 - 0.006) = 7.5e4 N, the plastic elongation stays.
  const BoltForces back = evaluate_bolt(law(), yielded, 4.009);
  EXPECT_EQ(back.state, BoltState::elastic);
  EXPECT_NEAR(back.axial_force, 7.5e4, force_tol);
  EXPECT_NEAR(back.plastic_elongation, 6e-3, length_tol);
  // Slack once shorter than L0 + plastic, 4.006 m.
  EXPECT_EQ(evaluate_bolt(law(), back, 4.005).state, BoltState::slack);
  EXPECT_NEAR(evaluate_bolt(law(), back, 4.005).plastic_elongation, 6e-3, length_tol);
  // Stretched again beyond: it yields further.
  const BoltForces again = evaluate_bolt(law(), back, 4.02);
  EXPECT_EQ(again.state, BoltState::yielding);
  EXPECT_NEAR(again.plastic_elongation, 1.6e-2, length_tol);
}

TEST(BoltLaw, RuptureBeyondItsStrainIsForGood)
{
  EXPECT_EQ(evaluate_bolt(law(), BoltForces{}, 4.399).state, BoltState::yielding);
  const BoltForces broken = evaluate_bolt(law(), BoltForces{}, 4.401);
  EXPECT_EQ(broken.state, BoltState::ruptured);
  EXPECT_EQ(broken.axial_force, 0.0);
  EXPECT_EQ(bolt_tangent_stiffness(law(), broken), 0.0);
  // Back to its free length, it carries nothing still.
  const BoltForces after = evaluate_bolt(law(), broken, 4.0);
  EXPECT_EQ(after.state, BoltState::ruptured);
  EXPECT_EQ(after.axial_force, 0.0);
  EXPECT_EQ(bolt_energy(law(), after), 0.0);
}

TEST(BoltLaw, EnergyIsForceSquaredOverTwiceTheStiffness)
{
  // 7e4 N on 2.5e7 N/m: 4.9e9 / 5e7 = 98 J.
  const BoltForces f = evaluate_bolt(law(2e4), BoltForces{}, 4.002);
  EXPECT_NEAR(bolt_energy(law(2e4), f), 98.0, 1e-9);
}

TEST(BoltRecord, ExtremesAndFirstTimesOfYieldAndRupture)
{
  BoltRecord r;
  EXPECT_TRUE(std::isnan(r.yield_time));
  r = record_bolt(r, evaluate_bolt(law(), BoltForces{}, 4.002), 2e-3, 0.1);
  EXPECT_NEAR(r.max_force, 5e4, force_tol);
  EXPECT_TRUE(std::isnan(r.yield_time));
  const BoltForces yielded = evaluate_bolt(law(), BoltForces{}, 4.01);
  r = record_bolt(r, yielded, 1e-2, 0.2);
  r = record_bolt(r, evaluate_bolt(law(), yielded, 4.02), 2e-2, 0.3);
  EXPECT_EQ(r.yield_time, 0.2);
  EXPECT_NEAR(r.max_force, 1e5, force_tol);
  EXPECT_EQ(r.max_elongation, 2e-2);
  r = record_bolt(r, evaluate_bolt(law(), yielded, 4.5), 0.5, 0.4);
  EXPECT_EQ(r.rupture_time, 0.4);
  EXPECT_EQ(r.max_elongation, 0.5);
  EXPECT_EQ(r.yield_time, 0.2);
  // The broken bolt's ends fly apart: its record stays that of the rupture.
  r = record_bolt(r, evaluate_bolt(law(), yielded, 6.0), 2.0, 0.5);
  EXPECT_EQ(r.rupture_time, 0.4);
  EXPECT_EQ(r.max_elongation, 0.5);
}

TEST(Bolt, LengthAndDirectionFromItsMaterialPoints)
{
  Bolt b;
  b.head = {0, Point(1.0, 1.0), Point(1.0, 1.0)};
  b.anchor = {1, Point(4.0, 5.0), Point(1.0, 5.0)};
  EXPECT_DOUBLE_EQ(b.length(), 5.0);
  EXPECT_DOUBLE_EQ(b.length(true), 4.0);
  EXPECT_NEAR(b.direction().x(), 0.6, 1e-15);
  EXPECT_NEAR(b.direction().y(), 0.8, 1e-15);
  EXPECT_NEAR(b.direction(true).y(), 1.0, 1e-15);
}
