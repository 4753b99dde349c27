// Newmark's yield acceleration of a rigid block on its joints (dda/yield_acceleration.h) against
// the closed forms: a block on a slope, a block on a flat joint, a hanging wedge, a block that
// cannot leave.
#include "dda/yield_acceleration.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{
using namespace ddafem::dda;

const Vector2 g(0.0, -9.81);
const Vector2 horizontal(1.0, 0.0), vertical(0.0, 1.0);

TEST(YieldAcceleration, BlockOnASlopeYieldsAtGTanPhiMinusBeta)
{
  // A slope dipping beta = 20 deg to +x, phi = 30 deg: Newmark's a_y = g tan(phi - beta), the
  // ground accelerating towards -x (the block thrown downhill).
  const double beta = 20.0 * M_PI / 180.0, phi = 30.0 * M_PI / 180.0;
  BlockFace slope;
  slope.normal = Vector2(std::sin(beta), std::cos(beta));
  slope.tangent = Vector2(std::cos(beta), -std::sin(beta));
  slope.tan_friction = std::tan(phi);
  const YieldAcceleration y = yield_acceleration({slope}, g, horizontal);
  EXPECT_EQ(y.mode, YieldMode::slide);
  EXPECT_NEAR(y.a_y, 9.81 * std::tan(phi - beta), 1e-12);
  EXPECT_EQ(y.sign, -1.0);
  // Steeper than the friction angle: gravity alone moves it.
  slope.tan_friction = std::tan(15.0 * M_PI / 180.0);
  EXPECT_EQ(yield_acceleration({slope}, g, horizontal).a_y, 0.0);
}

TEST(YieldAcceleration, SquareOnAFlatJointSlidesAtMuGAndLiftsOffAtG)
{
  // A unit square whose bottom edge is a joint (phi 35 deg) and whose other edges face an
  // opening.
  const std::vector<Point> square = {Point(0, 0), Point(1, 0), Point(1, 1), Point(0, 1)};
  const std::vector<std::pair<Point, Point>> opening = {
      {Point(1, 0), Point(1, 1)}, {Point(1, 1), Point(0, 1)}, {Point(0, 1), Point(0, 0)}};
  const double mu = std::tan(35.0 * M_PI / 180.0);
  const std::vector<BlockFace> faces = block_faces(square, opening, {mu, mu, mu, mu}, 1e-9);
  ASSERT_EQ(faces.size(), 1u);
  EXPECT_EQ(faces[0].edge, 0u);
  EXPECT_NEAR(faces[0].normal.y(), 1.0, 1e-15); // into the block, up
  const YieldAcceleration h = yield_acceleration(faces, g, horizontal);
  EXPECT_EQ(h.mode, YieldMode::slide);
  EXPECT_NEAR(h.a_y, mu * 9.81, 1e-12);
  const YieldAcceleration v = yield_acceleration(faces, g, vertical);
  EXPECT_EQ(v.mode, YieldMode::lift_off);
  EXPECT_NEAR(v.a_y, 9.81, 1e-12);
  EXPECT_EQ(v.sign, -1.0); // the ground dropping faster than g
}

TEST(YieldAcceleration, AHangingWedgeFallsUnderGravityAlone)
{
  // A roof wedge, apex up, between two joints dipping 70 deg: nothing holds it without clamping.
  const std::vector<Point> wedge = {Point(-1, 0), Point(1, 0), Point(0, 2.75)};
  const std::vector<std::pair<Point, Point>> opening = {{Point(-1, 0), Point(1, 0)}};
  const std::vector<BlockFace> faces = block_faces(wedge, opening, {0.7, 0.7, 0.7}, 1e-9);
  ASSERT_EQ(faces.size(), 2u);
  const YieldAcceleration y = yield_acceleration(faces, g, horizontal);
  EXPECT_EQ(y.a_y, 0.0);
  EXPECT_EQ(y.mode, YieldMode::lift_off);
}

TEST(YieldAcceleration, ABlockThatCannotLeaveDoesNotYield)
{
  // Joints on all four sides: no translation leaves them all.
  const std::vector<Point> square = {Point(0, 0), Point(1, 0), Point(1, 1), Point(0, 1)};
  const std::vector<BlockFace> faces = block_faces(square, {}, {0.5, 0.5, 0.5, 0.5}, 1e-9);
  const YieldAcceleration y = yield_acceleration(faces, g, horizontal);
  EXPECT_EQ(y.mode, YieldMode::none);
  EXPECT_TRUE(std::isinf(y.a_y));
}
} // namespace
