// The `tunnel` section (issue 7): the scene it expands into (what the program chooses for a
// tunnel is tested in tests/app/scene/test_tunnel_plan.cc).
#include "app/scene/scene.h"
#include "app/scene/tunnel_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

using namespace ddafem;

namespace
{
const std::string default_scene =
    std::string(DDAFEM_SOURCE_DIR) + "/examples/tunnel/circular_sv.yaml";
/// The default tunnel with strong joints and the hybrid truncation.
const std::string stable_scene = std::string(DDAFEM_SOURCE_DIR) + "/examples/tunnel/stable_sv.yaml";

TEST(TunnelScene, HybridSceneExpandsIntoBlocksFarFieldInterfaceAndStages)
{
  const Scene s = read_scene(stable_scene);
  ASSERT_TRUE(s.tunnel.has_value());
  ASSERT_TRUE(s.coupled());
  ASSERT_TRUE(s.rock_mass.has_value());
  EXPECT_EQ(s.model.blocks.size(), s.tunnel->n_blocks);
  EXPECT_EQ(s.interface->part, fem::BoundaryPart::hole);
  EXPECT_DOUBLE_EQ(s.far_field->youngs_modulus, s.tunnel->rock_mass_modulus);
  // Excavate, shake and settle (Bathe's scheme on the blocks: the settle stage comes to rest);
  // adaptive dt on the ladder dt / 2^k.
  ASSERT_EQ(s.model.stages.size(), 3u);
  EXPECT_EQ(s.model.stages[0].mode, dda::StageMode::static_equilibrium);
  EXPECT_EQ(s.model.stages[1].mode, dda::StageMode::dynamic);
  EXPECT_TRUE(s.model.stages[2].settle.has_value());
  EXPECT_EQ(s.model.time.control, dda::TimeControl::adaptive);
  EXPECT_EQ(s.model.time.integrator, dda::Integrator::bathe);
  EXPECT_EQ(s.far_field->integrator, fem::Integrator::newmark_trapezoidal);
  const Scene unsettled = read_scene(stable_scene, {{"tunnel.settle.enabled", "false"}});
  ASSERT_EQ(unsettled.model.stages.size(), 2u);
  EXPECT_EQ(s.model.monitors.size(), 5u);
  EXPECT_NE(s.expanded_yaml.find("in_situ_stress"), std::string::npos);
}

// The settle stage falls by the keyblocks' threshold (1% of the 6 m opening) and is bounded by
// twice a fall across the opening after the rest duration (1 / 25 Hz < 0.1 s); it can be turned
// off and its keys overridden.
TEST(TunnelScene, SettleStageFollowsTheWaveByDefault)
{
  const Scene s = read_scene(default_scene);
  ASSERT_EQ(s.model.stages.size(), 3u);
  ASSERT_TRUE(s.model.stages[2].settle.has_value());
  const dda::SettleCriterion& c = *s.model.stages[2].settle;
  EXPECT_DOUBLE_EQ(c.fall_distance, 0.06);
  EXPECT_DOUBLE_EQ(c.rest_duration, 0.1);
  EXPECT_DOUBLE_EQ(c.rest_speed, 1e-3);
  EXPECT_NEAR(c.max_duration, 0.1 + 2.0 * std::sqrt(2.0 * 6.0 / 9.81), 1e-12);
  const Scene off = read_scene(default_scene, {{"tunnel.settle.enabled", "false"}});
  EXPECT_EQ(off.model.stages.size(), 2u);
  const Scene longer = read_scene(
      default_scene, {{"tunnel.settle.max_duration", "5"}, {"tunnel.settle.rest_speed", "1e-4"}});
  EXPECT_DOUBLE_EQ(longer.model.stages[2].settle->max_duration, 5.0);
  EXPECT_DOUBLE_EQ(longer.model.stages[2].settle->rest_speed, 1e-4);
}

// The default scene is the hybrid with realistic joints (issue 17: coupled runs cut dt).
TEST(TunnelScene, DefaultSceneIsTheHybridWithRealisticJoints)
{
  const Scene s = read_scene(default_scene);
  ASSERT_TRUE(s.tunnel.has_value());
  EXPECT_TRUE(s.coupled());
  EXPECT_EQ(s.tunnel->truncation, TunnelTruncation::hybrid);
  EXPECT_EQ(s.model.time.control, dda::TimeControl::adaptive);
  ASSERT_EQ(s.model.joint_materials.size(), 1u);
  const dda::JointMaterial& j = s.model.joint_materials[0];
  EXPECT_LE(j.cohesion, 0.2e6);
  EXPECT_EQ(j.tensile_strength, 0.0);
  EXPECT_GE(j.friction_angle, 30.0);
  EXPECT_LE(j.friction_angle, 35.0);
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

TEST(TunnelScene, BlocksTruncationPutsTheNearFieldInBondedOuterGridsWithDashpots)
{
  // Coarse outer blocks (2 per wavelength) keep the test fast.
  const Scene s = read_scene(
      stable_scene, {{"tunnel.truncation", "blocks"}, {"tunnel.points_per_wavelength", "2"}});
  ASSERT_TRUE(s.tunnel.has_value());
  EXPECT_FALSE(s.far_field.has_value());
  const TunnelPlan& plan = *s.tunnel;
  EXPECT_EQ(s.model.blocks.size(), plan.n_outer_blocks + plan.n_blocks);
  // The default scene's top is the ground surface: dashpots on the base and the sides only.
  ASSERT_TRUE(plan.top_is_surface);
  ASSERT_EQ(s.model.boundaries.size(), 3u);
  for (const dda::BoundaryDescription& b : s.model.boundaries)
    EXPECT_EQ(b.type, dda::BoundaryType::dashpot);
  const auto outer = std::find_if(s.model.materials.begin(), s.model.materials.end(),
                                  [](const dda::Material& m) { return m.name == "outer_rock"; });
  ASSERT_NE(outer, s.model.materials.end());
  EXPECT_DOUBLE_EQ(outer->youngs_modulus, plan.outer_youngs_modulus);
  EXPECT_NE(s.expanded_yaml.find("outer_bond"), std::string::npos);
}

} // namespace
