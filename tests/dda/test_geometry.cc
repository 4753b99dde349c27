// Polygon geometry against hand-computed values.
#include "dda/geometry.h"

#include <gtest/gtest.h>

using namespace ddafem::dda;

namespace
{
std::vector<Point> rectangle(double x0, double y0, double w, double h)
{
  return {{x0, y0}, {x0 + w, y0}, {x0 + w, y0 + h}, {x0, y0 + h}};
}
/// L-shape: 2 x 2 square minus its upper-right 1 x 1 quarter (concave at (1, 1)).
std::vector<Point> l_shape()
{
  return {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
}
} // namespace

TEST(Geometry, RectangleMomentsMatchClosedForm)
{
  // w x h rectangle far from the origin: A = wh, Sxx = w^3 h / 12, Syy = w h^3 / 12, Sxy = 0.
  const double w = 3.0, h = 0.5;
  const PolygonMoments m = polygon_moments(rectangle(1000.0, -250.0, w, h));
  EXPECT_NEAR(m.area, w * h, 1e-12);
  EXPECT_NEAR(m.centroid.x(), 1000.0 + w / 2, 1e-9);
  EXPECT_NEAR(m.centroid.y(), -250.0 + h / 2, 1e-9);
  EXPECT_NEAR(m.sxx, w * w * w * h / 12.0, 1e-10);
  EXPECT_NEAR(m.syy, w * h * h * h / 12.0, 1e-10);
  EXPECT_NEAR(m.sxy, 0.0, 1e-10);
}

TEST(Geometry, TriangleMomentsMatchClosedForm)
{
  // Right triangle (0,0), (b,0), (0,h): centroid (b/3, h/3); central Sxx = b^3 h / 36,
  // Syy = b h^3 / 36, Sxy = -b^2 h^2 / 72.
  const double b = 2.0, h = 3.0;
  const PolygonMoments m = polygon_moments({{0, 0}, {b, 0}, {0, h}});
  EXPECT_NEAR(m.area, b * h / 2, 1e-12);
  EXPECT_NEAR(m.centroid.x(), b / 3, 1e-12);
  EXPECT_NEAR(m.centroid.y(), h / 3, 1e-12);
  EXPECT_NEAR(m.sxx, b * b * b * h / 36, 1e-12);
  EXPECT_NEAR(m.syy, b * h * h * h / 36, 1e-12);
  EXPECT_NEAR(m.sxy, -b * b * h * h / 72, 1e-12);
}

TEST(Geometry, ConcaveLShapeMoments)
{
  // Three unit squares centred at (0.5,0.5), (1.5,0.5), (0.5,1.5): A = 3, centroid (5/6, 5/6).
  // Sxx about the centroid = 3 * 1/12 + sum (xi - 5/6)^2 = 1/4 + (1/9 + 4/9 + 1/9) = 11/12;
  // Syy = 11/12 by symmetry; Sxy = sum (xi - 5/6)(yi - 5/6) = 1/9 - 2/9 - 2/9 = -1/3.
  const PolygonMoments m = polygon_moments(l_shape());
  EXPECT_NEAR(m.area, 3.0, 1e-12);
  EXPECT_NEAR(m.centroid.x(), 5.0 / 6.0, 1e-12);
  EXPECT_NEAR(m.centroid.y(), 5.0 / 6.0, 1e-12);
  EXPECT_NEAR(m.sxx, 11.0 / 12.0, 1e-12);
  EXPECT_NEAR(m.syy, 11.0 / 12.0, 1e-12);
  EXPECT_NEAR(m.sxy, -1.0 / 3.0, 1e-12);
}

TEST(Geometry, SignedAreaOrientation)
{
  std::vector<Point> p = rectangle(0, 0, 2, 1);
  EXPECT_DOUBLE_EQ(signed_area(p), 2.0);
  std::reverse(p.begin(), p.end());
  EXPECT_DOUBLE_EQ(signed_area(p), -2.0);
}

TEST(Geometry, SimplePolygons)
{
  EXPECT_TRUE(is_simple_polygon(l_shape()));
  EXPECT_TRUE(is_simple_polygon(rectangle(0, 0, 1, 1)));
  EXPECT_FALSE(is_simple_polygon({{0, 0}, {1, 1}, {1, 0}, {0, 1}})); // bow tie
  EXPECT_FALSE(is_simple_polygon({{0, 0}, {1, 0}}));                 // not closed
  EXPECT_FALSE(is_simple_polygon({{0, 0}, {1, 0}, {2, 0}}));         // zero area
  EXPECT_FALSE(is_simple_polygon({{0, 0}, {1, 0}, {1, 1}, {1, 0}})); // repeated vertex
}

TEST(Geometry, LocatePointInConcavePolygon)
{
  const auto l = l_shape();
  EXPECT_EQ(locate_point(l, {0.5, 0.5}, 1e-9), PointLocation::inside);
  EXPECT_EQ(locate_point(l, {1.5, 1.5}, 1e-9), PointLocation::outside); // the notch
  EXPECT_EQ(locate_point(l, {1.0, 1.5}, 1e-9), PointLocation::on_boundary);
  EXPECT_EQ(locate_point(l, {2.0, 0.0}, 1e-9), PointLocation::on_boundary);
  EXPECT_EQ(locate_point(l, {-0.1, 0.5}, 1e-9), PointLocation::outside);
}

TEST(Geometry, OverlapArea)
{
  EXPECT_NEAR(overlap_area(rectangle(0, 0, 1, 1), rectangle(0.5, 0.5, 1, 1)), 0.25, 1e-12);
  EXPECT_NEAR(overlap_area(rectangle(0, 0, 1, 1), rectangle(1, 0, 1, 1)), 0.0, 1e-15);
  EXPECT_NEAR(overlap_area(l_shape(), rectangle(1.2, 1.2, 1, 1)), 0.0, 1e-15); // in the notch
  EXPECT_NEAR(overlap_area(l_shape(), rectangle(0.5, 0.5, 1, 1)), 0.75, 1e-12);
}

TEST(Geometry, SharedSegmentsOfNeighbours)
{
  // A 1 x 1 square and a 1 x 2 rectangle to its right, offset by 0.5 upwards: they share
  // x = 1 for y in [0.5, 1].
  const auto a = rectangle(0, 0, 1, 1);
  const auto b = rectangle(1, 0.5, 1, 2);
  const auto s = shared_segments(a, b, 1e-9);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].a_edge, 1u); // (1,0) -> (1,1)
  EXPECT_EQ(s[0].b_edge, 3u); // (1,2.5) -> (1,0.5)
  EXPECT_NEAR((s[0].p - Point(1, 0.5)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((s[0].q - Point(1, 1)).norm(), 0.0, 1e-12);
  // Corner contact only: nothing shared.
  EXPECT_TRUE(shared_segments(a, rectangle(1, 1, 1, 1), 1e-9).empty());
}
