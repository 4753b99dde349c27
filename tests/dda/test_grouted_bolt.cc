// The grouted bolt's crossing law and its crossings (dda/grouted_bolt.h) against hand values.
//
// The law of every test: E_s = 200e9 Pa, A_s = 5e-4 m^2, K = 10e9 Pa, L_d = 0.5 m, so
// k_a = E_s A_s / L_d = 2e8 N/m; pretension 1e4 N, yield force 1e5 N, shear capacity 4e4 N,
// rupture strain 0.1 (0.05 m of the steel over L_d). The dowel: a round bar of area A has
// I = A^2 / (4 pi), so beta^4 = K / (4 E I) = pi K / (E A^2) and k_s = K / (4 beta).
#include "dda/grouted_bolt.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace ddafem::dda;

namespace
{
constexpr double force_tol = 1e-6; // [N]
const double pi = std::acos(-1.0);

GroutedBoltLaw law()
{
  return make_grouted_bolt_law(200e9, 5e-4, 10e9, 0.5, 1e4, 1e5, 4e4, 0.1);
}

double expected_shear_stiffness()
{
  const double beta = std::pow(pi * 10e9 / (200e9 * 5e-4 * 5e-4), 0.25);
  return 10e9 / (4.0 * beta);
}

std::vector<Point> square(double x0, double x1)
{
  return {Point(x0, 0.0), Point(x1, 0.0), Point(x1, 1.0), Point(x0, 1.0)};
}
} // namespace

TEST(GroutedBoltLaw, StiffnessesFromSteelAndGrout)
{
  const GroutedBoltLaw l = law();
  EXPECT_DOUBLE_EQ(l.axial_stiffness, 2e8);
  // beta = 28.15 1/m (a 25.2 mm bar in 10 GPa grout): k_s = 8.88e7 N/m.
  EXPECT_NEAR(l.shear_stiffness / expected_shear_stiffness(), 1.0, 1e-14);
  EXPECT_NEAR(l.shear_stiffness, 8.879e7, 1e4);
  EXPECT_DOUBLE_EQ(l.rupture_elongation, 0.05);
  EXPECT_DOUBLE_EQ(l.debonded_length, 0.5);
}

TEST(GroutedBoltLaw, ElasticAxialAndShear)
{
  const GroutedBoltLaw l = law();
  // 0.1 mm of opening: N = 1e4 + 2e8 x 1e-4 = 3e4 N; -0.2 mm of slip: S = -k_s 2e-4.
  const CrossingForces f = evaluate_crossing(l, CrossingForces{}, 1e-4, -2e-4);
  EXPECT_EQ(f.state, BoltState::elastic);
  EXPECT_TRUE(f.axial_elastic && f.shear_elastic);
  EXPECT_NEAR(f.axial_force, 3e4, force_tol);
  EXPECT_NEAR(f.shear_force, -2e-4 * expected_shear_stiffness(), force_tol);
  // As installed it carries its pretension and no shear.
  const CrossingForces installed = evaluate_crossing(l, CrossingForces{}, 0.0, 0.0);
  EXPECT_NEAR(installed.axial_force, 1e4, force_tol);
  EXPECT_EQ(installed.shear_force, 0.0);
  EXPECT_NEAR(crossing_energy(l, f),
              0.5 * 3e4 * 3e4 / 2e8 + 0.5 * f.shear_force * f.shear_force / l.shear_stiffness,
              1e-9);
}

TEST(GroutedBoltLaw, AxialAndShearYieldIndependently)
{
  const GroutedBoltLaw l = law();
  // 1 mm of opening: trial 1e4 + 2e5 > 1e5: N = 1e5, plastic opening 1e-3 - 9e4 / 2e8.
  const CrossingForces a = evaluate_crossing(l, CrossingForces{}, 1e-3, 1e-4);
  EXPECT_EQ(a.state, BoltState::yielding);
  EXPECT_FALSE(a.axial_elastic);
  EXPECT_TRUE(a.shear_elastic);
  EXPECT_NEAR(a.axial_force, 1e5, force_tol);
  EXPECT_NEAR(a.plastic_opening, 1e-3 - 4.5e-4, 1e-15);
  // Unloading 0.1 mm is elastic about the plastic opening: N = 1e5 - 2e4.
  EXPECT_NEAR(evaluate_crossing(l, a, 0.9e-3, 1e-4).axial_force, 8e4, force_tol);
  // -1 mm of slip: |trial| = 8.9e4 > 4e4: S = -4e4, plastic slip -1e-3 + 4e4 / k_s.
  const CrossingForces s = evaluate_crossing(l, CrossingForces{}, 0.0, -1e-3);
  EXPECT_EQ(s.state, BoltState::yielding);
  EXPECT_TRUE(s.axial_elastic);
  EXPECT_FALSE(s.shear_elastic);
  EXPECT_NEAR(s.shear_force, -4e4, force_tol);
  EXPECT_NEAR(s.plastic_slip, -1e-3 + 4e4 / l.shear_stiffness, 1e-15);
  EXPECT_NEAR(s.axial_force, 1e4, force_tol);
}

TEST(GroutedBoltLaw, ClosingCrossingIsSlackButStillADowel)
{
  // Closed by 0.1 mm: trial 1e4 - 2e4 < 0: no axial force; the shear part still acts, so the
  // crossing is elastic; without slip it carries nothing: slack.
  EXPECT_EQ(evaluate_crossing(law(), CrossingForces{}, -1e-4, 0.0).state, BoltState::slack);
  const CrossingForces f = evaluate_crossing(law(), CrossingForces{}, -1e-4, 1e-4);
  EXPECT_EQ(f.state, BoltState::elastic);
  EXPECT_FALSE(f.axial_elastic);
  EXPECT_TRUE(f.shear_elastic);
  EXPECT_EQ(f.axial_force, 0.0);
  EXPECT_NEAR(f.shear_force, 1e-4 * expected_shear_stiffness(), force_tol);
}

TEST(GroutedBoltLaw, RupturesWhenTheSteelOverTheDebondedLengthStretches)
{
  // Pure slip s stretches the steel over L_d to hypot(0.5, s): 0.05 m more at
  // s = sqrt(0.55^2 - 0.5^2) = 0.229129 m.
  const GroutedBoltLaw l = law();
  CrossingForces f = evaluate_crossing(l, CrossingForces{}, 0.0, 0.2291);
  EXPECT_EQ(f.state, BoltState::yielding);
  f = evaluate_crossing(l, f, 0.0, 0.2292);
  EXPECT_EQ(f.state, BoltState::ruptured);
  EXPECT_EQ(f.axial_force, 0.0);
  EXPECT_EQ(f.shear_force, 0.0);
  EXPECT_FALSE(f.axial_elastic || f.shear_elastic);
  // For good, even back at no displacement.
  EXPECT_EQ(evaluate_crossing(l, f, 0.0, 0.0).state, BoltState::ruptured);
  // Pure opening: beyond 0.05 m.
  EXPECT_EQ(evaluate_crossing(l, CrossingForces{}, 0.0499, 0.0).state, BoltState::yielding);
  EXPECT_EQ(evaluate_crossing(l, CrossingForces{}, 0.0501, 0.0).state, BoltState::ruptured);
}

TEST(GroutedBoltLaw, RecordKeepsExtremesAndEvents)
{
  const GroutedBoltLaw l = law();
  const CrossingForces yielding = evaluate_crossing(l, CrossingForces{}, 0.0, -1e-3);
  CrossingRecord r = record_crossing(CrossingRecord{}, yielding, 0.0, -1e-3, 0.25);
  EXPECT_NEAR(r.max_shear_force, 4e4, force_tol);
  EXPECT_DOUBLE_EQ(r.max_slip, 1e-3);
  EXPECT_DOUBLE_EQ(r.yield_time, 0.25);
  EXPECT_TRUE(std::isnan(r.rupture_time));
  const CrossingForces broken = evaluate_crossing(l, yielding, 0.0, -0.3);
  r = record_crossing(r, broken, 0.0, -0.3, 0.5);
  EXPECT_DOUBLE_EQ(r.rupture_time, 0.5);
  EXPECT_DOUBLE_EQ(r.yield_time, 0.25);
  EXPECT_DOUBLE_EQ(r.max_slip, 0.3);
  // Frozen after the rupture.
  EXPECT_DOUBLE_EQ(record_crossing(r, broken, 0.0, -0.9, 0.75).max_slip, 0.3);
}

TEST(BoltCrossings, ThroughARowOfBlocks)
{
  // Three unit squares side by side; the bolt from the first to the third crosses x = 1 and 2.
  const std::vector<std::vector<Point>> blocks = {square(0, 1), square(1, 2), square(2, 3)};
  std::array<double, 2> gap = {-1.0, -1.0};
  const std::vector<BoltCrossing> c =
      find_bolt_crossings(blocks, Point(0.5, 0.25), Point(2.5, 0.75), 1e-9, &gap);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0].block_a, 0u);
  EXPECT_EQ(c[0].block_b, 1u);
  EXPECT_NEAR(c[0].point.x(), 1.0, 1e-12);
  EXPECT_NEAR(c[0].point.y(), 0.375, 1e-12);
  EXPECT_NEAR(c[0].distance, 0.5 * std::hypot(1.0, 0.25), 1e-12);
  EXPECT_EQ(c[1].block_a, 1u);
  EXPECT_EQ(c[1].block_b, 2u);
  EXPECT_NEAR(c[1].point.x(), 2.0, 1e-12);
  EXPECT_NEAR(c[1].point.y(), 0.625, 1e-12);
  EXPECT_EQ(gap[1], 0.0);
  // Listed in another order, the blocks give the same crossings (sorted along the bolt).
  const std::vector<BoltCrossing> reversed = find_bolt_crossings(
      {square(2, 3), square(0, 1), square(1, 2)}, Point(0.5, 0.25), Point(2.5, 0.75), 1e-9);
  ASSERT_EQ(reversed.size(), 2u);
  EXPECT_EQ(reversed[0].block_a, 1u);
  EXPECT_EQ(reversed[1].block_b, 0u);
}

TEST(BoltCrossings, HeadOnTheBoundaryAndVoids)
{
  const std::vector<std::vector<Point>> blocks = {square(0, 1), square(2, 3)};
  // From the first block's left face into it: no crossing.
  EXPECT_TRUE(find_bolt_crossings(blocks, Point(0.0, 0.5), Point(0.9, 0.5), 1e-9).empty());
  // Across the void between x = 1 and 2: a gap, no crossing.
  std::array<double, 2> gap = {0.0, 0.0};
  EXPECT_TRUE(find_bolt_crossings(blocks, Point(0.5, 0.5), Point(2.5, 0.5), 1e-9, &gap).empty());
  EXPECT_NEAR(gap[0], 0.5, 1e-12);
  EXPECT_NEAR(gap[1], 1.5, 1e-12);
  // An end outside every block is a gap too.
  find_bolt_crossings({square(0, 1), square(1, 2)}, Point(0.5, 0.5), Point(2.5, 0.5), 1e-9, &gap);
  EXPECT_NEAR(gap[0], 1.5, 1e-12);
  EXPECT_NEAR(gap[1], 2.0, 1e-12);
}
