// The `tunnel` section (issue 7): what the program chooses for a tunnel, and the scene it expands
// into.
#include "app/scene.h"
#include "app/tunnel_scene.h"
#include "common/input_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace ddafem;

namespace
{
const std::string default_scene =
    std::string(DDAFEM_SOURCE_DIR) + "/examples/tunnel/circular_sv.yaml";

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
  t.wave_type = "sv";
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

TEST(TunnelPlan, NearFieldAboveTheSurfaceIsAnInputError)
{
  TunnelDescription t = grid_tunnel();
  t.depth = 10.0;
  EXPECT_THROW(plan_tunnel(t), InputError);
}

TEST(TunnelScene, DefaultSceneExpandsIntoBlocksFarFieldInterfaceAndStages)
{
  const Scene s = read_scene(default_scene);
  ASSERT_TRUE(s.tunnel.has_value());
  ASSERT_TRUE(s.coupled());
  ASSERT_TRUE(s.rock_mass.has_value());
  EXPECT_EQ(s.model.blocks.size(), s.tunnel->n_blocks);
  EXPECT_EQ(s.interface->part, fem::BoundaryPart::hole);
  EXPECT_DOUBLE_EQ(s.far_field->youngs_modulus, s.tunnel->rock_mass_modulus);
  ASSERT_EQ(s.model.stages.size(), 2u);
  EXPECT_EQ(s.model.stages[0].mode, dda::StageMode::static_equilibrium);
  EXPECT_EQ(s.model.stages[1].mode, dda::StageMode::dynamic);
  EXPECT_EQ(s.model.monitors.size(), 5u);
  EXPECT_NE(s.expanded_yaml.find("in_situ_stress"), std::string::npos);
}

TEST(TunnelScene, OneSettingSwitchesToBlocksOnlyWithVbOne)
{
  const Scene s = read_scene(default_scene, {{"tunnel.truncation", "vb1"}});
  ASSERT_TRUE(s.tunnel.has_value());
  EXPECT_FALSE(s.far_field.has_value());
  ASSERT_EQ(s.model.boundaries.size(), 4u);
  for (const dda::BoundaryDescription& b : s.model.boundaries)
    EXPECT_EQ(b.type, dda::BoundaryType::vb1);
}

} // namespace
