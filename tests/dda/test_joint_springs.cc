// The end springs of a bonded joint (dda/joints.h): their matrix, forces and energy, and the
// contact law that decides when they break, against hand calculations.
//
// p = 1e9 N/m, p_s = 0.4 p = 4e8 N/m, the joint's tangent t = (0.8, 0.6) and normal
// n = (t_y, -t_x) = (0.6, -0.8); gaps of a few um give forces of kN, whose rounding stays below
// 1e-9 N.
#include "dda/joints.h"

#include <gtest/gtest.h>

using namespace ddafem::dda;

namespace
{
JointMaterial joint_material()
{
  JointMaterial jm;
  jm.normal_stiffness = 1e9;
  jm.shear_ratio = 0.4;
  jm.cohesion = 1e5;
  jm.tensile_strength = 5e4;
  return jm;
}

Vector2 tangent()
{
  return Vector2(0.8, 0.6);
}

Vector2 normal()
{
  return Vector2(0.6, -0.8);
}

/// A joint end with the preloads N0 = 100 N and S0 = -50 N, its point on b at x_a + (3, 4) um.
JointPoint end_with_gap()
{
  JointPoint p;
  p.on_a.position = Point(0.0, 0.0);
  p.on_b.position = Point(3e-6, 4e-6);
  p.normal_preload = 100.0;
  p.shear_preload = -50.0;
  return p;
}
} // namespace

// p n n^T + p_s t t^T = 1e9 [0.36 -0.48; -0.48 0.64] + 4e8 [0.64 0.48; 0.48 0.36].
TEST(JointSprings, MatrixIsNormalAndShearSpringAlongTheirDirections)
{
  const Eigen::Matrix2d k = joint_spring_matrix(joint_material(), normal(), tangent());
  const double tol = 1e-6; // [N/m], of 1e9
  EXPECT_NEAR(k(0, 0), 6.16e8, tol);
  EXPECT_NEAR(k(0, 1), -2.88e8, tol);
  EXPECT_NEAR(k(1, 0), -2.88e8, tol);
  EXPECT_NEAR(k(1, 1), 7.84e8, tol);
  const Vector2 n = normal(), t = tangent();
  const Eigen::Matrix2d expected = 1e9 * n * n.transpose() + 4e8 * t * t.transpose();
  EXPECT_TRUE(k.isApprox(expected, 1e-14));
}

// n.g = 1.8 - 3.2 = -1.4 um, t.g = 2.4 + 2.4 = 4.8 um:
// N = 100 + 1e9 (-1.4e-6) = -1300 N (compressed), S = -50 + 4e8 4.8e-6 = 1870 N.
TEST(JointSprings, ForcesArePreloadsPlusSpringsOnTheGap)
{
  JointPoint p = end_with_gap();
  update_joint_point_forces(p, joint_material(), normal(), tangent());
  EXPECT_NEAR(p.normal_force, -1300.0, 1e-9);
  EXPECT_NEAR(p.shear_force, 1870.0, 1e-9);
  // The preloads are kept.
  EXPECT_EQ(p.normal_preload, 100.0);
  EXPECT_EQ(p.shear_preload, -50.0);
}

// N^2 / (2 p) + S^2 / (2 p_s) = 1.69e6 / 2e9 + 3.4969e6 / 8e8 = 8.45e-4 + 4.371125e-3 J.
TEST(JointSprings, EnergyIsThatOfBothSprings)
{
  JointPoint p;
  p.normal_force = -1300.0;
  p.shear_force = 1870.0;
  EXPECT_NEAR(joint_point_energy(p, joint_material()), 5.216125e-3, 1e-15);
  EXPECT_EQ(joint_point_energy(JointPoint{}, joint_material()), 0.0);
}

// Over half of a 1 m joint: cohesive force 1e5 x 0.5 = 5e4 N, tensile capacity 2.5e4 N.
TEST(JointSprings, LawOfAnEndCarriesItsLength)
{
  const ContactLaw law = joint_point_law(joint_material(), 0.5, 0.5);
  EXPECT_EQ(law.normal_stiffness, 1e9);
  EXPECT_EQ(law.shear_stiffness, 4e8);
  EXPECT_EQ(law.tan_friction, 0.5);
  EXPECT_EQ(law.cohesive_force, 5e4);
  EXPECT_EQ(law.tensile_capacity, 2.5e4);
}
