// The lining's frame law (dda/lining.h) against the textbook Euler-Bernoulli frame element and
// hand values.
//
// The section of every test: t = 0.2 m, E = 30e9 Pa, so EA = 6e9 N/m and EI = 30e9 x 0.008 / 12
// = 2e7 N m; elements of L0 = 2 m. Every expected value is a product or quotient of those; the
// tolerances are relative 1e-12 for closed forms evaluated in a few operations, and 1e-6 where
// the co-rotational law is compared with the linear stiffness at deformations of 1e-7 (its
// second-order terms are 1e-7 of the first-order ones).
#include "dda/lining.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace ddafem::dda;

namespace
{
constexpr double l0 = 2.0;
constexpr double ea = 6e9, ei = 2e7;

LiningSection section()
{
  return {0.2, 30e9, 40e6, 4e6, 0.0};
}
} // namespace

TEST(LiningLaw, SectionStiffnesses)
{
  EXPECT_DOUBLE_EQ(section().axial_stiffness(), ea);
  EXPECT_NEAR(section().bending_stiffness() / ei, 1.0, 1e-12);
}

// The textbook matrix (e.g. Przemieniecki, Theory of Matrix Structural Analysis, 1968, eq. 5.
// 111) with its rigid-body modes: translation along and across the chord, and a rotation about
// node a (theta = 1, v_b = L).
TEST(LiningLaw, LocalStiffnessIsTheTextbookFrameElement)
{
  const Matrix6 k = frame_stiffness_local(section(), l0);
  const double k1 = 12 * ei / 8, k2 = 6 * ei / 4, k3 = 4 * ei / 2, k4 = 2 * ei / 2;
  Matrix6 expected;
  expected << ea / l0, 0, 0, -ea / l0, 0, 0, 0, k1, k2, 0, -k1, k2, 0, k2, k3, 0, -k2, k4, -ea / l0,
      0, 0, ea / l0, 0, 0, 0, -k1, -k2, 0, k1, -k2, 0, k2, k4, 0, -k2, k3;
  EXPECT_LT((k - expected).norm(), 1e-12 * expected.norm());
  EXPECT_LT((k - k.transpose()).norm(), 1e-12 * k.norm());
  Vector6 along, across, turn;
  along << 1, 0, 0, 1, 0, 0;
  across << 0, 1, 0, 0, 1, 0;
  turn << 0, 0, 1, 0, l0, 1;
  for (const Vector6& mode : {along, across, turn})
    EXPECT_LT((k * mode).norm(), 1e-12 * k.norm());
}

// A vertical element (e = (0, 1)): u_x is across the chord, u_y along it.
TEST(LiningLaw, GlobalStiffnessRotatesTheLocalOne)
{
  const Matrix6 k = frame_stiffness_global(section(), l0, Vector2(0, 1));
  EXPECT_NEAR(k(0, 0), 12 * ei / 8, 1e-12 * ea);
  EXPECT_NEAR(k(1, 1), ea / l0, 1e-12 * ea);
  EXPECT_NEAR(k(0, 2), -6 * ei / 4, 1e-12 * ea); // v_local = -u_x
  EXPECT_NEAR(k(2, 2), 4 * ei / l0, 1e-12 * ea);
  EXPECT_NEAR(k(0, 1), 0.0, 1e-12 * ea);
}

// A clamped-pinned rotation: theta_b = phi at node b, node a clamped, no translation:
// m_a = 2 EI phi / L, m_b = 4 EI phi / L, V = 6 EI phi / L^2; M(0) = -m_a, M(L) = m_b.
TEST(LiningLaw, ForcesOfAnEndRotation)
{
  const double phi = 1e-3;
  const FrameDeformation q =
      frame_deformation(Point(0, 0), Point(l0, 0), Point(0, 0), Point(l0, 0), 0.0, phi);
  EXPECT_DOUBLE_EQ(q.elongation, 0.0);
  const FrameForces f = frame_forces(section(), l0, q);
  EXPECT_NEAR(f.end_moment_a, 2 * ei * phi / l0, 1e-12 * ei);
  EXPECT_NEAR(f.end_moment_b, 4 * ei * phi / l0, 1e-12 * ei);
  EXPECT_NEAR(f.shear_force, 6 * ei * phi / (l0 * l0), 1e-12 * ei);
  EXPECT_NEAR(f.bending_moment_a(), -2 * ei * phi / l0, 1e-12 * ei);
  EXPECT_DOUBLE_EQ(f.axial_force, 0.0);
}

// A clamped-guided beam: node b moved across the chord by delta, both ends held from turning:
// V = 12 EI delta / L^3, M = -+6 EI delta / L^2 at the ends (statics: M_b - M_a = V L).
TEST(LiningLaw, ForcesOfAGuidedEnd)
{
  const double delta = -1e-4; // node b down
  const FrameForces f = frame_forces(
      section(), l0,
      frame_deformation(Point(0, 0), Point(l0, 0), Point(0, 0), Point(l0, delta), 0.0, 0.0));
  EXPECT_NEAR(f.shear_force, -12 * ei * delta / 8, 1e-6 * std::abs(12 * ei * delta / 8));
  EXPECT_NEAR(f.bending_moment_a(), 6 * ei * delta / 4, 1e-6 * std::abs(6 * ei * delta / 4));
  EXPECT_NEAR(f.bending_moment_b() - f.bending_moment_a(), f.shear_force * l0,
              1e-12 * std::abs(f.shear_force * l0));
  // The chord lengthens by delta^2 / (2 L) (co-rotational, second order): N = EA delta^2 /
  // (2 L^2) = 7.5 N/m, 2.5e-3 of V (the difference of two lengths of 2 m: rounding 2e-7).
  EXPECT_NEAR(f.axial_force, ea * delta * delta / (2 * l0 * l0), 1e-5 * 7.5);
}

// A stretch gives N = EA u / L0; a rigid rotation of the whole element (0.5 rad, nodes turned
// with it) and a translation give nothing (co-rotational).
TEST(LiningLaw, StretchAndRigidMotion)
{
  const FrameForces stretch = frame_forces(
      section(), l0,
      frame_deformation(Point(0, 0), Point(l0, 0), Point(0, 0), Point(l0 + 1e-4, 0), 0, 0));
  EXPECT_NEAR(stretch.axial_force, ea * 1e-4 / l0, 1e-9 * ea * 1e-4 / l0);
  const double a = 0.5;
  const Point xb = Point(3, 1) + l0 * Point(std::cos(a), std::sin(a));
  const FrameForces rigid = frame_forces(
      section(), l0, frame_deformation(Point(0, 0), Point(l0, 0), Point(3, 1), xb, a, a));
  EXPECT_LT(std::abs(rigid.axial_force) + std::abs(rigid.shear_force), 1e-12 * ea);
  EXPECT_LT(std::abs(rigid.end_moment_a) + std::abs(rigid.end_moment_b), 1e-12 * ea);
}

// For small displacements the forces on the nodes are -K q of the global stiffness, for an
// element at 30 degrees and an arbitrary q of 1e-7; the energy is q^T K q / 2.
TEST(LiningLaw, CorotationalForcesMatchTheLinearStiffness)
{
  const Vector2 e(std::cos(M_PI / 6), std::sin(M_PI / 6));
  const Point xa0(1, 2), xb0 = xa0 + l0 * e;
  Vector6 q;
  q << 0.3, -0.7, 0.2, -0.4, 0.9, -0.5;
  q *= 1e-7;
  const FrameDeformation d =
      frame_deformation(xa0, xb0, xa0 + q.segment<2>(0), xb0 + q.segment<2>(3), q(2), q(5));
  const FrameForces f = frame_forces(section(), l0, d);
  const Matrix6 k = frame_stiffness_global(section(), l0, e);
  const Vector6 linear = -(k * q);
  EXPECT_LT((forces_on_nodes(f, e) - linear).norm(), 1e-6 * linear.norm());
  EXPECT_NEAR(frame_energy(section(), l0, d) / (0.5 * q.dot(k * q)), 1.0, 1e-6);
}

// The extreme fibres: M = 1e4 N m/m on t = 0.2 m gives 6 M / t^2 = 1.5 MPa; with N = -2e5 N/m
// (-1 MPa) the fibres are 0.5 MPa and -2.5 MPa: tension 0.5 / 4 = 0.125, compression 2.5 / 40
// = 0.0625. With f_v = 1 MPa, V = 2e5 N/m gives 1.5 V / t = 1.5 MPa: shear governs at 1.5.
TEST(LiningLaw, CapacityCheckOfTheExtremeFibres)
{
  FrameForces f;
  f.end_moment_b = 1e4;
  LiningCheck c = check_lining_section(section(), f);
  EXPECT_NEAR(c.utilisation, 1.5e6 / 4e6, 1e-12);
  EXPECT_EQ(c.mode, LiningFailureMode::tension);
  f.axial_force = -2e5;
  c = check_lining_section(section(), f);
  EXPECT_NEAR(c.utilisation, 0.5e6 / 4e6, 1e-12);
  f.axial_force = -7.6e6; // -38 MPa - 1.5 MPa: compression 39.5 / 40
  c = check_lining_section(section(), f);
  EXPECT_NEAR(c.utilisation, 39.5 / 40, 1e-12);
  EXPECT_EQ(c.mode, LiningFailureMode::compression);
  LiningSection s = section();
  s.shear_strength = 1e6;
  f = {};
  f.shear_force = -2e5;
  c = check_lining_section(s, f);
  EXPECT_NEAR(c.utilisation, 1.5, 1e-12);
  EXPECT_EQ(c.mode, LiningFailureMode::shear);
}

// An element past its capacity breaks for good: its forces are zero from then on, its record
// keeps the demand that broke it and the time.
TEST(LiningLaw, AnElementBeyondItsCapacityBreaksForGood)
{
  LiningSection s = section();
  LiningNode a, b;
  a.point.position = a.installed = Point(0, 0);
  b.point.position = b.installed = Point(l0, 0);
  LiningElement e;
  e.a = 0;
  e.b = 1;
  e.length0 = l0;
  b.rotation = 1e-4; // m_b = 4e3 N m/m: 6 m_b / t^2 = 0.6 MPa, 0.15 of f_t
  update_lining_element(e, s, a, b, 1.0);
  EXPECT_EQ(e.state, LiningElementState::intact);
  EXPECT_NEAR(e.check.utilisation, 0.15, 1e-12);
  b.rotation = 1e-3; // 1.5 of f_t
  update_lining_element(e, s, a, b, 2.0);
  EXPECT_EQ(e.state, LiningElementState::broken);
  EXPECT_EQ(e.break_time, 2.0);
  EXPECT_NEAR(e.max_utilisation, 1.5, 1e-12);
  EXPECT_EQ(e.forces.shear_force, 0.0);
  b.rotation = 0.0;
  update_lining_element(e, s, a, b, 3.0);
  EXPECT_EQ(e.state, LiningElementState::broken);
  EXPECT_EQ(e.break_time, 2.0);
}

// Each leg is split into ceil(leg / segment) equal parts; a closed polyline does not repeat its
// first point.
TEST(LiningLaw, NodesAlongThePolyline)
{
  const std::vector<Point> open =
      lining_node_positions({Point(0, 0), Point(1, 0), Point(1, 0.5)}, 0.3, false);
  ASSERT_EQ(open.size(), 7u); // 4 parts of 0.25, 2 of 0.25, and the end
  EXPECT_NEAR(open[1].x(), 0.25, 1e-15);
  EXPECT_NEAR(open[5].y(), 0.25, 1e-15);
  EXPECT_EQ(open.back(), Point(1, 0.5));
  const std::vector<Point> ring =
      lining_node_positions({Point(0, 0), Point(1, 0), Point(1, 1), Point(0, 1)}, 0.5, true);
  ASSERT_EQ(ring.size(), 8u);
  EXPECT_EQ(ring[7], Point(0, 0.5));
  // A leg of exactly two segments is not split into three by rounding.
  EXPECT_EQ(lining_node_positions({Point(0, 0), Point(0.3, 0)}, 0.1, false).size(), 4u);
}
