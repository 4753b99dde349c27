// The tunnel plan (app/scene/tunnel_plan.h, issue 7): the near field, far field or outer blocks,
// element sizes and time steps it chooses for a tunnel, against hand estimates.
#include "app/scene/tunnel_plan.h"

#include "common/input_error.h"
#include "dda/jointed_block_modulus.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

using namespace ddafem;
using ddafem::dda::jointed_block_modulus;

namespace
{
/// A 6 m circular opening at the origin in rock cut by a horizontal and a vertical set of
/// persistent joints 3 m apart (lines at multiples of 3 m), 50 m deep, under a 25 Hz SV pulse.
TunnelDescription grid_tunnel()
{
  TunnelDescription t;
  t.rock = "rock";
  t.density = 2650.0;
  t.youngs_modulus = 20e9;
  t.poisson_ratio = 0.25;
  t.joint_normal_stiffness = 2e11;
  dda::JointSet horizontal, vertical;
  horizontal.dip = 0.0;
  horizontal.spacing = 3.0;
  vertical.dip = 90.0;
  vertical.spacing = 3.0;
  t.rock_mass.joint_sets = {horizontal, vertical};
  dda::Opening circle;
  circle.center = Point(0.0, 0.0);
  circle.radius = 3.0;
  t.rock_mass.openings = {circle};
  t.rock_mass.chord_tolerance = 0.02;
  t.depth = 50.0;
  t.wave_type = WaveType::sv;
  t.wave_frequency = 25.0;
  t.max_frequency = 50.0;
  t.wave_duration = 0.04;
  return t;
}

TEST(TunnelPlan, NearFieldIsFourOpeningsWideAroundTheOpening)
{
  const TunnelPlan plan = plan_tunnel(grid_tunnel());
  // The inscribed polygon of the circle touches it at the axes: a 6 m x 6 m box.
  EXPECT_NEAR(plan.opening_upper.x() - plan.opening_lower.x(), 6.0, 1e-12);
  EXPECT_NEAR(plan.near_lower.x(), -12.0, 1e-12);
  EXPECT_NEAR(plan.near_upper.y(), 12.0, 1e-12);
  // 8 x 8 blocks of 3 m; the circle (radius 3) lies in the four middle ones, which become four
  // blocks around the opening.
  EXPECT_EQ(plan.n_blocks, 64u);
}

TEST(TunnelPlan, RockMassModulusIsTheBoundaryBlocksWithTheirJoints)
{
  const TunnelDescription t = grid_tunnel();
  const TunnelPlan plan = plan_tunnel(t);
  // 24 side blocks with 3 m on the boundary and 3 m depth behind it, 4 corner blocks with 6 m
  // and 1.5 m: E_eff = 1 / (1/E + L / (2 p d)), averaged over the boundary's 96 m.
  const double e = t.youngs_modulus, p = t.joint_normal_stiffness;
  const double side = 1.0 / (1.0 / e + 3.0 / (2.0 * p * 3.0));
  const double corner = 1.0 / (1.0 / e + 6.0 / (2.0 * p * 1.5));
  EXPECT_NEAR(plan.rock_mass_modulus, (24 * 3.0 * side + 4 * 6.0 * corner) / 96.0, 1e-6 * e);
  EXPECT_DOUBLE_EQ(jointed_block_modulus(e, p, 9.0, 3.0), side);
  const double vs = std::sqrt(plan.rock_mass_modulus / (2.0 * 2650.0 * 1.25));
  EXPECT_NEAR(plan.vs, vs, 1e-9 * vs);
  EXPECT_NEAR(plan.wave_speed, plan.vs, 1e-12);
}

TEST(TunnelPlan, HybridFarFieldIsOneWavelengthBeyondWithElementsFromTheShortestWavelength)
{
  const TunnelDescription t = grid_tunnel();
  const TunnelPlan plan = plan_tunnel(t);
  ASSERT_TRUE(plan.far_field);
  const double wavelength = plan.vs / 25.0;
  EXPECT_NEAR(plan.margin, wavelength, 1e-9);
  EXPECT_NEAR(plan.far_lower.x(), -12.0 - wavelength, 1e-9);
  // The top is the ground surface (50 m above the axis), inside one wavelength: free.
  EXPECT_TRUE(plan.top_is_surface);
  EXPECT_DOUBLE_EQ(plan.far_upper.y(), 50.0);
  // FE_Q2: two nodes per element edge, 10 nodes per S wavelength at 50 Hz.
  EXPECT_NEAR(plan.far_element_size, 2.0 * (plan.vs / 50.0) / 10.0, 1e-12);
  EXPECT_NEAR(plan.elements_per_wavelength, 5.0, 1e-12);
  // The wave crosses the margin, then the 24 m near field twice, the 0.04 s pulse and two
  // periods of 25 Hz; 20 steps per period at 50 Hz.
  EXPECT_NEAR(plan.arrival_time, wavelength / plan.vs, 1e-12);
  EXPECT_NEAR(plan.end_time, plan.arrival_time + 24.0 / plan.vs + 0.04 + 0.08, 1e-12);
  EXPECT_DOUBLE_EQ(plan.dt, 1e-3);
}

TEST(TunnelPlan, ReferenceIsFarEnoughThatNoReflectionReturns)
{
  TunnelDescription t = grid_tunnel();
  t.truncation = TunnelTruncation::reference;
  t.depth = 1000.0;
  const TunnelPlan plan = plan_tunnel(t);
  const double window = 24.0 / plan.vs + 0.04 + 0.08;
  EXPECT_NEAR(plan.margin, 0.5 * plan.vp * window, 1e-9);
  // A P wave from the near field's edge to the truncation and back takes the whole window.
  EXPECT_GE(2.0 * plan.margin / plan.vp, window - 1e-12);
  EXPECT_FALSE(plan.top_is_surface);
}

TEST(TunnelPlan, BlocksOnlyTakeTheWaveAtTheirBaseWithinVbOnesLimit)
{
  TunnelDescription t = grid_tunnel();
  t.truncation = TunnelTruncation::vb1;
  const TunnelPlan plan = plan_tunnel(t);
  EXPECT_FALSE(plan.far_field);
  EXPECT_DOUBLE_EQ(plan.arrival_time, 0.0);
  // VB I's bound m / cn = A / (L VP) is 1.5 / VP for the corner blocks (intact rock's VP).
  const double vp = std::sqrt(20e9 * 0.75 / (2650.0 * 1.25 * 0.5));
  EXPECT_NEAR(plan.dt, std::min(1e-3, 0.9 * 1.5 / vp), 1e-15);
}

TEST(TunnelPlan, OuterBlocksReachTheReferencesExtent)
{
  TunnelDescription t = grid_tunnel();
  t.truncation = TunnelTruncation::reference;
  const TunnelPlan reference = plan_tunnel(t);
  t.truncation = TunnelTruncation::blocks;
  const TunnelPlan plan = plan_tunnel(t);
  EXPECT_FALSE(plan.far_field);
  EXPECT_DOUBLE_EQ(plan.margin, reference.margin);
  EXPECT_DOUBLE_EQ(reference.side_margin, reference.margin);
  EXPECT_DOUBLE_EQ(plan.far_lower.y(), reference.far_lower.y());
  // Wider at the sides: a P wave from a base corner, sqrt(side^2 + margin^2) from the near
  // field, arrives when the window ends, margin / VS + window after the wave entered the base.
  const double window = plan.end_time - plan.arrival_time;
  const double reach = plan.vp * (plan.margin / plan.vs + window);
  EXPECT_NEAR(std::hypot(plan.side_margin, plan.margin), reach, 1e-9 * reach);
  EXPECT_GT(plan.side_margin, plan.margin);
  EXPECT_DOUBLE_EQ(plan.far_lower.x(), plan.near_lower.x() - plan.side_margin);
  EXPECT_DOUBLE_EQ(plan.far_upper.x(), plan.near_upper.x() + plan.side_margin);
  // 50 m deep: the ground surface lies within the margin, the top is free there.
  EXPECT_TRUE(plan.top_is_surface);
  EXPECT_DOUBLE_EQ(plan.far_upper.y(), 50.0);
  EXPECT_DOUBLE_EQ(plan.arrival_time, reference.arrival_time);
  EXPECT_DOUBLE_EQ(plan.end_time, reference.end_time);
  EXPECT_DOUBLE_EQ(plan.dt, 1e-3);
  // The static stage's pseudo step grows with the model: 1 ms x its width over the near field's.
  EXPECT_DOUBLE_EQ(reference.static_dt, 1e-3);
  EXPECT_NEAR(plan.static_dt, 1e-3 * (plan.far_upper.x() - plan.far_lower.x()) / 24.0, 1e-15);
}

TEST(TunnelPlan, OuterBlocksHaveTheShortestSWavelengthOverPointsPerWavelength)
{
  TunnelDescription t = grid_tunnel();
  t.truncation = TunnelTruncation::blocks;
  const TunnelPlan plan = plan_tunnel(t);
  const double size = (plan.vs / 50.0) / 10.0;
  EXPECT_NEAR(plan.outer_block_size, size, 1e-12);
  ASSERT_EQ(plan.outer_grids.size(), 8u);
  std::size_t n = 0;
  for (const BlockGrid& g : plan.outer_grids)
    for (int k = 0; k < 2; ++k)
    {
      // Each side of the ring's pieces is cut into the whole number of cells nearest to
      // length / size.
      const double length = g.cell_size[k] * static_cast<double>(g.count[k]);
      EXPECT_EQ(g.count[k], std::max<std::size_t>(1, std::llround(length / size)));
      EXPECT_LE(std::abs(g.cell_size[k] - size), 0.5 * size / static_cast<double>(g.count[k]));
      if (k == 0)
        n += g.count[0] * g.count[1];
    }
  EXPECT_EQ(plan.n_outer_blocks, n);
}

TEST(TunnelPlan, OuterBlocksWithTheirJointsHaveTheRockMassModulus)
{
  TunnelDescription t = grid_tunnel();
  t.truncation = TunnelTruncation::blocks;
  const TunnelPlan plan = plan_tunnel(t);
  const double e_eff = plan.rock_mass_modulus, p = t.joint_normal_stiffness;
  // By hand: a square cell of side s and E_o shortens by sigma s / E_o, its joint (two springs
  // p, 1 m thick) by sigma s / (2 p): 1 / E_eff = 1 / E_o + 1 / (2 p).
  const double e_o = 1.0 / (1.0 / e_eff - 1.0 / (2.0 * p));
  EXPECT_NEAR(plan.outer_youngs_modulus, e_o, 1e-12 * e_o);
  EXPECT_DOUBLE_EQ(plan.outer_joint_stiffness, p);
  for (const double s : {plan.outer_block_size, 1.0, 7.5})
    EXPECT_NEAR(jointed_block_modulus(plan.outer_youngs_modulus, p, s * s, s), e_eff,
                1e-12 * e_eff);
  // Shear: both joint sets slip, tau s / (2 p_s) each per cell: 1 / G = 1 / G_o + 1 / p_s.
  const double nu = t.poisson_ratio;
  const double g_grid =
      1.0 / (2.0 * (1.0 + nu) / plan.outer_youngs_modulus + 1.0 / (plan.outer_shear_ratio * p));
  EXPECT_NEAR(g_grid, e_eff / (2.0 * (1.0 + nu)), 1e-12 * e_eff);
  EXPECT_GT(plan.outer_strength, 1e3 * t.density * t.gravity * (50.0 + plan.margin));
  // Springs softer than the rock mass cannot make it.
  EXPECT_THROW(outer_block_modulus(e_eff, 0.4 * e_eff), InputError);
}

TEST(TunnelPlan, OuterGridsTileTheRingAroundTheNearField)
{
  TunnelDescription t = grid_tunnel();
  t.truncation = TunnelTruncation::blocks;
  t.depth = 1000.0; // the top is a dashpot, the ring closed on four sides
  const TunnelPlan plan = plan_tunnel(t);
  EXPECT_FALSE(plan.top_is_surface);
  using Box = std::array<Point, 2>;
  const auto area = [](const Box& b)
  { return std::max(0.0, b[1].x() - b[0].x()) * std::max(0.0, b[1].y() - b[0].y()); };
  const auto overlap = [&](const Box& a, const Box& b) {
    return area({a[0].cwiseMax(b[0]), a[1].cwiseMin(b[1])});
  };
  std::vector<Box> boxes;
  for (const BlockGrid& g : plan.outer_grids)
    boxes.push_back(
        {g.origin, g.origin + Point(g.cell_size.x() * static_cast<double>(g.count[0]),
                                    g.cell_size.y() * static_cast<double>(g.count[1]))});
  const Box near = {plan.near_lower, plan.near_upper};
  const Box far = {plan.far_lower, plan.far_upper};
  const double tolerance = 1e-9 * area(far);
  double sum = 0.0;
  for (std::size_t i = 0; i < boxes.size(); ++i)
  {
    sum += area(boxes[i]);
    EXPECT_NEAR(overlap(boxes[i], far), area(boxes[i]), tolerance) << "grid " << i;
    EXPECT_NEAR(overlap(boxes[i], near), 0.0, tolerance) << "grid " << i;
    for (std::size_t j = i + 1; j < boxes.size(); ++j)
      EXPECT_NEAR(overlap(boxes[i], boxes[j]), 0.0, tolerance) << "grids " << i << ", " << j;
  }
  EXPECT_NEAR(sum, area(far) - area(near), tolerance);
}

TEST(TunnelPlan, NearFieldAboveTheSurfaceIsAnInputError)
{
  TunnelDescription t = grid_tunnel();
  t.depth = 10.0;
  EXPECT_THROW(plan_tunnel(t), InputError);
}
} // namespace
