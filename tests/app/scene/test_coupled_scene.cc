// Scenes with blocks tied to a far field (`interface`, issue 6).
#include "app/run/run.h"
#include "app/scene/scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace ddafem;

namespace
{
const std::string bar = std::string(DDAFEM_SOURCE_DIR) + "/examples/coupled/p_wave_bar_hybrid.yaml";

TEST(CoupledScene, HybridBarReadsBothSidesAndTheInterface)
{
  const Scene s = read_scene(bar);
  ASSERT_TRUE(s.coupled());
  ASSERT_TRUE(s.interface.has_value());
  EXPECT_EQ(s.interface->part, fem::BoundaryPart::left);
  // The ties take joints.default's springs and have unlimited strength.
  EXPECT_DOUBLE_EQ(s.interface->normal_stiffness, 2.5e12);
  EXPECT_DOUBLE_EQ(s.interface->shear_ratio, 0.4);
  EXPECT_TRUE(std::isinf(s.interface->cohesion));
  // M1 lies in a block, M2 beyond the blocks in the far field.
  ASSERT_EQ(s.model.monitors.size(), 1u);
  EXPECT_EQ(s.model.monitors[0].name, "M1");
  ASSERT_EQ(s.far_field->monitors.size(), 1u);
  EXPECT_EQ(s.far_field->monitors[0].name, "M2");
  // Adaptive dt (on the levels dt / 2^k); the far field follows the blocks' DDA scheme.
  EXPECT_EQ(s.model.time.control, dda::TimeControl::adaptive);
  EXPECT_EQ(s.far_field->integrator, fem::Integrator::dda);
  EXPECT_DOUBLE_EQ(s.far_field->dt, 1e-5);
}

TEST(CoupledScene, OverridesSelectTheFarFieldIntegratorAndAFrictionalInterface)
{
  const Scene s = read_scene(bar, {{"far_field.integrator", "newmark_trapezoidal"},
                                   {"interface.joint_material", "bonded"},
                                   {"interface.normal_stiffness", "1e13"}});
  EXPECT_EQ(s.far_field->integrator, fem::Integrator::newmark_trapezoidal);
  EXPECT_EQ(s.model.time.integrator, dda::Integrator::dda);
  // Strength and friction from the joint material, the spring from the explicit key.
  EXPECT_DOUBLE_EQ(s.interface->cohesion, 20e6);
  EXPECT_DOUBLE_EQ(s.interface->tensile_strength, 10e6);
  EXPECT_DOUBLE_EQ(s.interface->friction_angle, 45.0);
  EXPECT_DOUBLE_EQ(s.interface->normal_stiffness, 1e13);
}

TEST(CoupledScene, CheckReportsBothSidesAndTheTies)
{
  const std::string report = check_scene(read_scene(bar));
  // 60 blocks of 6 DOFs; 40 Q2 elements of 1 m: 81 x 3 nodes; one tied edge of 3 ties.
  EXPECT_NE(report.find("blocks: 60"), std::string::npos) << report;
  EXPECT_NE(report.find("DOFs: 360"), std::string::npos) << report;
  EXPECT_NE(report.find("40 cells"), std::string::npos) << report;
  EXPECT_NE(report.find("486 DOFs"), std::string::npos) << report;
  EXPECT_NE(report.find("interface: part left (1 m), 1 block edges of 1 blocks, 3 ties"),
            std::string::npos)
      << report;
}
} // namespace

namespace
{
const std::string column =
    std::string(DDAFEM_SOURCE_DIR) + "/examples/coupled/s_wave_column_hybrid.yaml";

TEST(CoupledScene, CheckEstimatesTheInterfaceReflectionOfTheFarFieldMaterial)
{
  // The layers with their joints: E_eff = 1 / (1/E + 50 m / (2 p)) = 33.3 GPa. A far field of
  // that rock mass matches them; one of the intact rock (50 GPa) reflects
  // (1 - sqrt(2/3)) / (1 + sqrt(2/3)) = 10.1% and `check` warns.
  const std::string matched = check_scene(read_scene(column));
  EXPECT_NE(matched.find("E_eff 3.333e+10 Pa"), std::string::npos) << matched;
  EXPECT_EQ(matched.find("warning"), std::string::npos) << matched;
  const std::string intact = check_scene(read_scene(column, {{"far_field.material", "rock"}}));
  EXPECT_NE(intact.find("reflects about 10%"), std::string::npos) << intact;
}
} // namespace
