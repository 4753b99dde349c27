// Pure polygon geometry for DDA blocks: exact integrals and point/polygon predicates.
#pragma once

#include "dda/types.h"

#include <optional>
#include <vector>

namespace ddafem::dda
{
/// Exact area integrals of a simple polygon (convex or concave), anticlockwise.
struct PolygonMoments
{
  double area = 0.0;              ///< S0 = integral of 1 dA [m^2]
  Point centroid = Point::Zero(); ///< (x0, y0) [m]
  /// Central second moments [m^4]: integral of (x-x0)^2, (y-y0)^2, (x-x0)(y-y0) dA.
  double sxx = 0.0, syy = 0.0, sxy = 0.0;
};

/// Signed area [m^2]: positive for anticlockwise vertex order.
double signed_area(const std::vector<Point>& vertices);

/// The polygon in anticlockwise order, without a repeated closing vertex.
std::vector<Point> anticlockwise(std::vector<Point> polygon);

/// Area, centroid and central second moments by Green's theorem over the edges (exact).
/// Requires a simple polygon with non-zero area in anticlockwise order.
PolygonMoments polygon_moments(const std::vector<Point>& vertices);

/// Whether the polygon is simple: at least 3 vertices, no repeated vertex, no two edges that
/// intersect except adjacent edges at their common vertex, non-zero area, finite coordinates
/// (uses CGAL).
bool is_simple_polygon(const std::vector<Point>& vertices);

/// Where a point lies relative to a simple polygon, within tolerance `tol` [m] of the boundary.
enum class PointLocation
{
  inside,
  on_boundary,
  outside
};
PointLocation locate_point(const std::vector<Point>& vertices, const Point& p, double tol);

/// Area [m^2] of the intersection of the interiors of two simple polygons (exact CGAL boolean
/// operations, then converted to double). Zero for polygons that only share edges or vertices.
double overlap_area(const std::vector<Point>& a, const std::vector<Point>& b);

/// A common stretch of two polygon edges: block a's edge (a_edge) and block b's edge (b_edge)
/// lie on one line with opposite directions and overlap over the segment [p, q] of positive
/// length (p, q ordered along a's edge). This is where two blocks share a joint.
struct SharedSegment
{
  std::size_t a_edge = 0; ///< edge index in a: from vertex a_edge to a_edge + 1 (cyclic)
  std::size_t b_edge = 0;
  Point p = Point::Zero();
  Point q = Point::Zero();
};

/// All shared segments of two anticlockwise polygons, with collinearity tolerance `tol` [m].
std::vector<SharedSegment> shared_segments(const std::vector<Point>& a, const std::vector<Point>& b,
                                           double tol);

} // namespace ddafem::dda
