// dda/exact_area.h: the exact area of a polygon as CGAL::polygon_area_2 sums it, without the
// lazy kernel's depth limit (a 385,000-sided circle overflowed the stack in CGAL's).
#include "dda/exact_area.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace ddafem::dda
{
namespace
{
using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;

/// A regular polygon of n vertices on a circle of radius r [m], anticlockwise.
std::vector<Kernel::Point_2> regular_polygon(std::size_t n, double r)
{
  std::vector<Kernel::Point_2> points;
  for (std::size_t i = 0; i < n; ++i)
  {
    const double a = 2.0 * M_PI * static_cast<double>(i) / static_cast<double>(n);
    points.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  return points;
}

TEST(ExactArea, SameValueAndApproximationAsCgalUpToTheChainLength)
{
  // Up to exact_area_chain + 1 vertices (as many triangles less 2), the very sum CGAL makes:
  // equal exactly, and the double the blocks' areas are read as (to_double, from the
  // approximation) equal bit for bit. Beyond, the partial sum made exact refines the
  // approximation; the exact value stays the same.
  for (const std::size_t n : {3ul, 17ul, 1000ul, exact_area_chain + 1, exact_area_chain + 2})
  {
    const std::vector<Kernel::Point_2> points = regular_polygon(n, 3.0);
    const Kernel::FT ours = polygon_area(points.begin(), points.end(), Kernel());
    const Kernel::FT cgal = CGAL::polygon_area_2(points.begin(), points.end(), Kernel());
    if (n <= exact_area_chain + 1)
      EXPECT_EQ(CGAL::to_double(ours), CGAL::to_double(cgal)) << n << " vertices";
    EXPECT_TRUE(ours == cgal) << n << " vertices";
  }
  // No points, or two: no area.
  const std::vector<Kernel::Point_2> triangle = regular_polygon(3, 1.0);
  EXPECT_EQ(CGAL::to_double(polygon_area(triangle.begin(), triangle.begin(), Kernel())), 0.0);
  EXPECT_EQ(CGAL::to_double(polygon_area(triangle.begin(), triangle.begin() + 2, Kernel())), 0.0);
}

TEST(ExactArea, HundredsOfThousandsOfVerticesWithinTheStack)
{
  // 300,000 vertices: CGAL's running sum is a chain 300,000 deep (its destruction overflowed an
  // 8 MB stack at 385,000); ours is cut every exact_area_chain terms. The area is the regular
  // polygon's, n r^2 sin(2 pi / n) / 2, to rounding of the vertices.
  const std::size_t n = 300000;
  const double r = 3.0;
  const std::vector<Kernel::Point_2> points = regular_polygon(n, r);
  const double area = CGAL::to_double(polygon_area(points.begin(), points.end(), Kernel()));
  const double expected = 0.5 * static_cast<double>(n) * r * r * std::sin(2.0 * M_PI / n);
  EXPECT_NEAR(area, expected, 1e-12 * expected);
}

} // namespace
} // namespace ddafem::dda
