// The radial bolt pattern's geometry (app/scene/tunnel_bolts.h) on shapes with exact answers.
#include "app/scene/tunnel_bolts.h"

#include <gtest/gtest.h>

#include <cmath>

using ddafem::dda::Opening;
using ddafem::dda::Point;

namespace
{
const std::vector<Point> square = {Point(-1, -1), Point(1, -1), Point(1, 1), Point(-1, 1)};
}

TEST(TunnelBolts, RayLeavesTheOpeningWhereTheEdgesAre)
{
  const Point c(0, 0);
  EXPECT_NEAR((ddafem::ray_exit(square, c, 0.0) - Point(1, 0)).norm(), 0.0, 1e-14);
  EXPECT_NEAR((ddafem::ray_exit(square, c, 45.0) - Point(1, 1)).norm(), 0.0, 1e-14);
  EXPECT_NEAR((ddafem::ray_exit(square, c, 90.0) - Point(0, 1)).norm(), 0.0, 1e-14);
  EXPECT_NEAR((ddafem::ray_exit(square, c, 206.565051177) - Point(-1, -0.5)).norm(), 0.0, 1e-9);
}

TEST(TunnelBolts, PerimeterBetweenTwoRays)
{
  // From (1, 0) up the right side and along the top to (0, 1): 2 m; the polyline through the
  // exits at steps under 0.1 deg (under 3.5 mm here) cuts the corner by less than a step.
  const double length = ddafem::perimeter_between(square, Point(0, 0), 0.0, 90.0);
  EXPECT_LE(length, 2.0);
  EXPECT_GT(length, 2.0 - 3.5e-3);
}

TEST(TunnelBolts, RadialBoltsEquallySpacedInAngle)
{
  const std::vector<ddafem::RadialBolt> b =
      ddafem::radial_bolts(square, Point(0, 0), 0.0, 90.0, 3, 2.0);
  ASSERT_EQ(b.size(), 3u);
  EXPECT_DOUBLE_EQ(b[1].angle, 45.0);
  EXPECT_NEAR((b[0].anchor - Point(3, 0)).norm(), 0.0, 1e-14);
  EXPECT_NEAR((b[1].head - Point(1, 1)).norm(), 0.0, 1e-14);
  EXPECT_NEAR((b[1].anchor - Point(1 + std::sqrt(2.0), 1 + std::sqrt(2.0))).norm(), 0.0, 1e-14);
  EXPECT_NEAR((b[2].anchor - Point(0, 3)).norm(), 0.0, 1e-14);
  // One bolt: in the middle.
  EXPECT_DOUBLE_EQ(ddafem::radial_bolts(square, Point(0, 0), 30.0, 150.0, 1, 1.0)[0].angle, 90.0);
}

TEST(TunnelBolts, PatternCentres)
{
  Opening circle;
  circle.center = Point(1, 2);
  EXPECT_EQ(ddafem::pattern_centre(circle), Point(1, 2));
  Opening horseshoe;
  horseshoe.shape = Opening::Shape::horseshoe;
  horseshoe.center = Point(0, -1);
  horseshoe.wall_height = 2.5;
  EXPECT_EQ(ddafem::pattern_centre(horseshoe), Point(0, 1.5));
  Opening polygon;
  polygon.shape = Opening::Shape::polygon;
  polygon.vertices = {Point(0, 0), Point(4, 0), Point(4, 2), Point(1, 3)};
  EXPECT_EQ(ddafem::pattern_centre(polygon), Point(2, 1.5));
}
