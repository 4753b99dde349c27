// Joint materials of block edges (BlockDescription::edge_joint_materials): bonded joints and
// contacts along an edge with its own joint material use it instead of the materials' default.
#include "dda/joints.h"
#include "dda/system.h"
#include "dda/time_stepper.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace ddafem;
using namespace ddafem::dda;

namespace
{
constexpr double rho = 2650.0, young = 10e9, nu = 0.25, g = 9.81;

BlockDescription square(double x0, double y0, double size)
{
  BlockDescription b;
  b.vertices = {{x0, y0}, {x0 + size, y0}, {x0 + size, y0 + size}, {x0, y0 + size}};
  return b;
}

/// Index of the joint between blocks a < b.
const Joint& joint_between(const System& s, std::size_t a, std::size_t b)
{
  for (const Joint& j : s.bonded_joints().list)
    if (j.block_a == a && j.block_b == b)
      return j;
  throw std::runtime_error("no joint between the blocks");
}
} // namespace

// A 2 m x 1 m base whose top edge (edge 2) is on joint material 1, under two 1 m blocks: the
// left one's bottom edge (edge 0) on joint material 2, the right one's on none. The left joint
// takes the shorter edge's (2), the right one the base's (1); the joint between the two upper
// blocks, on no labelled edge, joints.default (0).
TEST(EdgeJointMaterials, BondedJointsTakeTheSharedEdgesJointMaterial)
{
  ModelDescription m;
  m.materials.push_back({"rock", rho, young, nu});
  for (const char* name : {"default", "set_a", "set_b"})
    m.joint_materials.push_back({name, 1e10, 0.4, 30.0, 1e6, 1e6, true});
  m.default_joint_material = 0;
  BlockDescription base;
  base.vertices = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  base.edge_joint_materials = {std::nullopt, std::nullopt, 1, std::nullopt};
  BlockDescription left = square(0, 1, 1), right = square(1, 1, 1);
  left.edge_joint_materials = {2, std::nullopt, std::nullopt, std::nullopt};
  m.blocks = {base, left, right};
  m.time.dt = 1e-4;
  m.time.end_time = 1e-3;
  const System s(m);
  ASSERT_EQ(s.bonded_joints().list.size(), 3u);
  EXPECT_EQ(joint_between(s, 0, 1).joint_material, 2u);
  EXPECT_EQ(joint_between(s, 0, 2).joint_material, 1u);
  EXPECT_EQ(joint_between(s, 1, 2).joint_material, 0u);
  EXPECT_EQ(joint_material_at_edge(m, 0, 2, 1), 1u);
  EXPECT_EQ(joint_material_at_edge(m, 1, 1, 2), 0u);
}

// A unit block on a fixed 6 m base under gravity tilted by 20 degrees (an incline): on the
// default joint material (phi 40 deg) it stays; with the base's top edge on a frictional
// bedding material of phi 10 deg, its contacts use that friction and it slides at
// g (sin 20 - cos 20 tan 10) (Contacts.BlockSlidesDownAnInclineAtTheFrictionalAcceleration).
TEST(EdgeJointMaterials, ContactsAlongAFrictionalEdgeUseItsFriction)
{
  const double slope = 20.0 * M_PI / 180.0, phi_bedding = 10.0, end = 0.3;
  const auto slid = [&](bool bedding)
  {
    ModelDescription m;
    m.materials.push_back({"rock", rho, young, nu});
    m.joint_materials.push_back({"rough", 1e10, 0.4, 40.0, 0.0, 0.0, false});
    m.joint_materials.push_back({"bedding", 1e10, 0.4, phi_bedding, 0.0, 0.0, false});
    m.default_joint_material = 0;
    BlockDescription base;
    base.vertices = {{-3, -1}, {3, -1}, {3, 0}, {-3, 0}};
    if (bedding)
      base.edge_joint_materials = {std::nullopt, std::nullopt, 1, std::nullopt};
    m.blocks = {base, square(-0.5, 0, 1)};
    for (const Point& x : {Point(-2.5, -0.5), Point(2.5, -0.5), Point(0, -0.5)})
      m.fixed_points.push_back(
          {x, 0.0, TimeFunction::constant(0.0), TimeFunction::constant(0.0), ""});
    m.monitors.push_back({"block", {0.0, 0.5}});
    m.gravity = Vector2(g * std::sin(slope), -g * std::cos(slope));
    m.time.dt = 1e-3;
    m.time.end_time = end;
    System s(m);
    TimeStepper stepper(s, m.time);
    while (s.time() < end - 1e-12)
    {
      const StepStatus status = stepper.step(end - s.time());
      EXPECT_EQ(status.outcome, StepOutcome::success) << status.message;
      if (status.outcome != StepOutcome::success)
        break;
    }
    EXPECT_FALSE(s.contacts().accepted.empty());
    for (const Contact& c : s.contacts().accepted)
      EXPECT_EQ(c.joint_material, bedding ? 1u : 0u);
    return s.sample_monitor(0).displacement.x();
  };
  const double expected =
      0.5 * g * (std::sin(slope) - std::cos(slope) * std::tan(phi_bedding * M_PI / 180.0)) * end *
      end;
  EXPECT_NEAR(slid(true), expected, 0.02 * expected);
  EXPECT_LT(std::abs(slid(false)), 1e-3 * expected);
}
