// Which joint each generated block edge lies on (RockMassBlock::edge_joints): the set or explicit
// joint whose trace cut it, none on the region's and the openings' boundaries.
#include "dda/geometry.h"
#include "dda/rock_mass.h"
#include "joint_sets.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace ddafem::dda;

namespace
{
using test_models::persistent_set;

/// Distance [m] from p to the closed polygon's boundary.
double distance_to_boundary(const std::vector<Point>& polygon, const Point& p)
{
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < polygon.size(); ++i)
  {
    const Point& a = polygon[i];
    const Point& b = polygon[(i + 1) % polygon.size()];
    const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    d = std::min(d, (a + t * (b - a) - p).norm());
  }
  return d;
}

/// Sine of the angle between the edge from a to b and the direction at `dip` degrees.
double sine_to(const Point& a, const Point& b, double dip)
{
  const Vector2 e = (b - a).normalized();
  const double r = dip * M_PI / 180.0;
  return std::abs(e.x() * std::sin(r) - e.y() * std::cos(r));
}
} // namespace

// A 6 m x 4 m region cut by horizontal joints 1 m apart (set 0, lines at y = 0.5 + k) and
// vertical ones 1.5 m apart (set 1): every interior horizontal edge is on set 0, every interior
// vertical edge on set 1, every edge on the region's boundary on none.
TEST(RockMassEdgeJoints, GridEdgesCarryTheirSet)
{
  RockMassDescription d;
  d.region = {{0, 0}, {6, 0}, {6, 4}, {0, 4}};
  d.joint_sets = {persistent_set(0, 1.0, 0.5), persistent_set(90, 1.5, -0.75)};
  const RockMassResult r = generate_blocks(d);
  ASSERT_EQ(r.blocks.size(), 5u * 5u);
  std::size_t n_on_sets[2] = {0, 0};
  for (const RockMassBlock& b : r.blocks)
  {
    ASSERT_EQ(b.edge_joints.size(), b.vertices.size());
    for (std::size_t k = 0; k < b.vertices.size(); ++k)
    {
      const Point& p = b.vertices[k];
      const Point& q = b.vertices[(k + 1) % b.vertices.size()];
      const Point mid = 0.5 * (p + q);
      const EdgeJoint& e = b.edge_joints[k];
      if (distance_to_boundary(d.region, mid) < 1e-9)
      {
        EXPECT_EQ(e.kind, EdgeJoint::Kind::none) << "edge at " << mid.transpose();
        continue;
      }
      ASSERT_EQ(e.kind, EdgeJoint::Kind::joint_set) << "edge at " << mid.transpose();
      EXPECT_EQ(e.index, p.y() == q.y() ? 0u : 1u) << "edge at " << mid.transpose();
      ++n_on_sets[e.index];
    }
  }
  // 4 horizontal lines x 5 columns and 4 vertical lines x 5 rows, seen from both sides.
  EXPECT_EQ(n_on_sets[0], 2u * 4u * 5u);
  EXPECT_EQ(n_on_sets[1], 2u * 4u * 5u);
}

// An explicit joint along a trace of set 0 wins there (explicit joints before sets); a short
// explicit joint is on its own; the opening's edges are on none even where a set's trace runs
// along them, and the straight edge above the opening, which the set and the opening share in
// part, is on the set that covers most of it.
TEST(RockMassEdgeJoints, ExplicitJointsAndOpenings)
{
  RockMassDescription d;
  d.region = {{0, 0}, {6, 0}, {6, 4}, {0, 4}};
  d.joint_sets = {persistent_set(0, 2.0, 1.0)}; // y = 1 and y = 3
  d.joints = {{{0, 1}, {6, 1}}, {{2, 0}, {2, 1}}};
  Opening square;
  square.shape = Opening::Shape::polygon;
  square.vertices = {{4, 2.5}, {5, 2.5}, {5, 3}, {4, 3}}; // its top lies on y = 3
  d.openings = {square};
  const RockMassResult r = generate_blocks(d);
  std::size_t n_checked = 0;
  for (const RockMassBlock& b : r.blocks)
    for (std::size_t k = 0; k < b.vertices.size(); ++k)
    {
      const Point& p = b.vertices[k];
      const Point& q = b.vertices[(k + 1) % b.vertices.size()];
      const Point mid = 0.5 * (p + q);
      const EdgeJoint& e = b.edge_joints[k];
      if (distance_to_boundary(d.region, mid) < 1e-9 ||
          distance_to_boundary(r.openings.front(), mid) < 1e-9)
        EXPECT_EQ(e.kind, EdgeJoint::Kind::none) << "edge at " << mid.transpose();
      else if (std::abs(mid.y() - 1.0) < 1e-9)
        EXPECT_EQ(e, (EdgeJoint{EdgeJoint::Kind::explicit_joint, 0})) << mid.transpose();
      else if (mid.y() < 1.0)
        EXPECT_EQ(e, (EdgeJoint{EdgeJoint::Kind::explicit_joint, 1})) << mid.transpose();
      else
        EXPECT_EQ(e, (EdgeJoint{EdgeJoint::Kind::joint_set, 0})) << mid.transpose();
      ++n_checked;
    }
  EXPECT_GT(n_checked, 10u);
}

// A rock mass with perturbed, non-persistent and oblique sets, explicit joints and a circular
// opening, where short edges were collapsed and straight vertices removed: every edge off the
// boundaries carries a set (or explicit joint) it runs along, within the few degrees a collapse
// may turn it, or none on a vertical cut around an island.
TEST(RockMassEdgeJoints, EveryInteriorEdgeIsOnAParallelJoint)
{
  RockMassDescription d;
  d.region = {{-15, -15}, {15, -15}, {15, 15}, {-15, 15}};
  JointSet a = persistent_set(30, 2.5, 0.3), b = persistent_set(110, 3.0);
  a.perturbation.spacing = 0.3;
  b.trace_length = 8.0;
  b.bridge = 2.0;
  b.perturbation.position = 0.3;
  d.joint_sets = {a, b};
  d.joints = {{{-14, -14}, {14, 3}}};
  Opening c;
  c.center = {1, 1};
  c.radius = 4;
  d.openings = {c};
  d.seed = 3;
  const RockMassResult r = generate_blocks(d);
  ASSERT_GT(r.blocks.size(), 50u);
  const double explicit_dip = std::atan2(17.0, 28.0) * 180.0 / M_PI;
  std::size_t n_labelled = 0;
  for (const RockMassBlock& block : r.blocks)
    for (std::size_t k = 0; k < block.vertices.size(); ++k)
    {
      const Point& p = block.vertices[k];
      const Point& q = block.vertices[(k + 1) % block.vertices.size()];
      const Point mid = 0.5 * (p + q);
      const EdgeJoint& e = block.edge_joints[k];
      const bool boundary = distance_to_boundary(d.region, mid) < 1e-9 ||
                            distance_to_boundary(r.openings.front(), mid) < 1e-9;
      if (boundary || e.kind == EdgeJoint::Kind::none)
      {
        EXPECT_TRUE(boundary || std::abs(p.x() - q.x()) < 1e-12) << mid.transpose();
        continue;
      }
      const double dip =
          e.kind == EdgeJoint::Kind::explicit_joint ? explicit_dip : d.joint_sets[e.index].dip;
      EXPECT_LT(sine_to(p, q, dip), std::sin(5.0 * M_PI / 180.0)) << mid.transpose();
      ++n_labelled;
    }
  EXPECT_GT(n_labelled, 4 * r.blocks.size() / 2);
}
