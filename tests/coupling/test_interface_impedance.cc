// The impedance contrast at the interface (coupling/interface_impedance.h) against numbers
// computed by hand.
#include "column_models.h"
#include "coupling/interface_impedance.h"

#include <gtest/gtest.h>

using namespace ddafem;
using namespace ddafem::coupling;

TEST(InterfaceImpedance, ReflectionOfAnImpedanceRatio)
{
  // E_blocks = E_far / 4: r = 1/2, reflection (1 - 1/2) / (1 + 1/2) = 1/3; and the other way.
  EXPECT_DOUBLE_EQ(impedance_contrast(12.5e9, 50e9).reflection, 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(impedance_contrast(200e9, 50e9).reflection, 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(impedance_contrast(50e9, 50e9).reflection, 0.0);
}

TEST(InterfaceImpedance, TiedColumnTopBlockWithItsJoint)
{
  test_models::ColumnSpec spec;
  spec.dda_top = 4.0;
  spec.fe_top = 8.0;
  const test_models::Column column(spec);
  const dda::ModelDescription& model = column.system.get_model();
  // The top block [0, 20] x [3, 4] is tied along its 20 m top edge, d = 1 m behind it, joints of
  // p = 500 E (20 m) / (1 m) = 5e14 N/m: E_eff = 1 / (1/E + 20 / (2 p 1)) = E / 1.001, and
  // r = sqrt(1 / 1.001) reflects (1 - r) / (1 + r) = 2.498750781e-4.
  const auto z = interface_impedance(model, column.system, *column.ties, test_models::young);
  ASSERT_TRUE(z);
  EXPECT_NEAR(z->blocks_modulus, 50e9 / 1.001, 1e-3);
  EXPECT_DOUBLE_EQ(z->far_field_modulus, 50e9);
  EXPECT_NEAR(z->reflection, 2.498750781e-4, 1e-12);
  // Without a default joint material nothing is estimated.
  dda::ModelDescription no_joints = model;
  no_joints.default_joint_material = no_joints.joint_materials.size();
  EXPECT_FALSE(interface_impedance(no_joints, column.system, *column.ties, test_models::young));
}
