#include "dda/geometry.h"

#include "dda/exact_area.h"

#include <CGAL/Boolean_set_operations_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_2.h>
#include <CGAL/Polygon_with_holes_2.h>

#include <algorithm>
#include <cmath>
#include <iterator>

namespace ddafem::dda
{
namespace
{
using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using CgalPolygon = CGAL::Polygon_2<Kernel>;
using CgalPolygonWithHoles = CGAL::Polygon_with_holes_2<Kernel>;

CgalPolygon to_cgal(const std::vector<Point>& vertices)
{
  CgalPolygon polygon;
  for (const Point& v : vertices)
    polygon.push_back(Kernel::Point_2(v.x(), v.y()));
  return polygon;
}

double cross(const Vector2& a, const Vector2& b)
{
  return a.x() * b.y() - a.y() * b.x();
}

/// Distance from p to segment [a, b].
double distance_to_segment(const Point& p, const Point& a, const Point& b)
{
  const Vector2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + s * ab)).norm();
}
} // namespace

double signed_area(const std::vector<Point>& vertices)
{
  double twice_area = 0.0;
  const std::size_t n = vertices.size();
  for (std::size_t i = 0; i < n; ++i)
    twice_area += cross(vertices[i], vertices[(i + 1) % n]);
  return 0.5 * twice_area;
}

std::vector<Point> anticlockwise(std::vector<Point> polygon)
{
  if (polygon.size() > 1 && polygon.front() == polygon.back())
    polygon.pop_back();
  if (signed_area(polygon) < 0.0)
    std::reverse(polygon.begin(), polygon.end());
  return polygon;
}

PolygonMoments polygon_moments(const std::vector<Point>& vertices)
{
  // Green's theorem over the edges, with coordinates relative to the first vertex to limit
  // cancellation for blocks far from the origin. For an edge (xi, yi) -> (xj, yj) with
  // c = xi yj - xj yi:
  //   A   = 1/2  sum c
  //   Sx  = 1/6  sum c (xi + xj),             Sy similarly
  //   Sxx = 1/12 sum c (xi^2 + xi xj + xj^2), Syy similarly
  //   Sxy = 1/24 sum c (xi yj + 2 xi yi + 2 xj yj + xj yi)
  const Point origin = vertices.front();
  double a = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, syy = 0.0, sxy = 0.0;
  const std::size_t n = vertices.size();
  for (std::size_t k = 0; k < n; ++k)
  {
    const Point pi = vertices[k] - origin;
    const Point pj = vertices[(k + 1) % n] - origin;
    const double xi = pi.x(), yi = pi.y(), xj = pj.x(), yj = pj.y();
    const double c = xi * yj - xj * yi;
    a += c;
    sx += c * (xi + xj);
    sy += c * (yi + yj);
    sxx += c * (xi * xi + xi * xj + xj * xj);
    syy += c * (yi * yi + yi * yj + yj * yj);
    sxy += c * (xi * yj + 2.0 * xi * yi + 2.0 * xj * yj + xj * yi);
  }
  a *= 0.5;
  sx /= 6.0;
  sy /= 6.0;
  sxx /= 12.0;
  syy /= 12.0;
  sxy /= 24.0;

  PolygonMoments m;
  m.area = a;
  const double cx = sx / a, cy = sy / a; // relative to origin
  m.centroid = origin + Point(cx, cy);
  // Parallel-axis theorem to central moments.
  m.sxx = sxx - a * cx * cx;
  m.syy = syy - a * cy * cy;
  m.sxy = sxy - a * cx * cy;
  return m;
}

bool is_simple_polygon(const std::vector<Point>& vertices)
{
  if (vertices.size() < 3)
    return false;
  for (const Point& v : vertices)
    if (!v.allFinite())
      return false;
  // No vertex twice: sorted by (x, y), equal vertices are neighbours (n log n, an opening's
  // circle may have tens of thousands).
  std::vector<Point> sorted = vertices;
  const auto by_xy = [](const Point& a, const Point& b)
  { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); };
  std::sort(sorted.begin(), sorted.end(), by_xy);
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
    return false;
  const CgalPolygon polygon = to_cgal(vertices);
  return polygon.is_simple() &&
         polygon_area(polygon.vertices_begin(), polygon.vertices_end(), Kernel()) != 0;
}

PointLocation locate_point(const std::vector<Point>& vertices, const Point& p, double tol)
{
  const std::size_t n = vertices.size();
  for (std::size_t i = 0; i < n; ++i)
    if (distance_to_segment(p, vertices[i], vertices[(i + 1) % n]) <= tol)
      return PointLocation::on_boundary;
  // Crossing number (ray towards +x); the boundary case was handled above.
  bool inside = false;
  for (std::size_t i = 0, j = n - 1; i < n; j = i++)
  {
    const Point& a = vertices[i];
    const Point& b = vertices[j];
    if ((a.y() > p.y()) != (b.y() > p.y()))
    {
      const double x_cross = a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      if (p.x() < x_cross)
        inside = !inside;
    }
  }
  return inside ? PointLocation::inside : PointLocation::outside;
}

double overlap_area(const std::vector<Point>& a, const std::vector<Point>& b)
{
  CgalPolygon pa = to_cgal(a);
  CgalPolygon pb = to_cgal(b);
  if (pa.is_clockwise_oriented())
    pa.reverse_orientation();
  if (pb.is_clockwise_oriented())
    pb.reverse_orientation();
  std::vector<CgalPolygonWithHoles> pieces;
  CGAL::intersection(pa, pb, std::back_inserter(pieces));
  Kernel::FT area = 0;
  for (const CgalPolygonWithHoles& piece : pieces)
  {
    const CgalPolygon& outer = piece.outer_boundary();
    area += polygon_area(outer.vertices_begin(), outer.vertices_end(), Kernel());
    for (auto hole = piece.holes_begin(); hole != piece.holes_end(); ++hole)
      area += polygon_area(hole->vertices_begin(), hole->vertices_end(),
                           Kernel()); // holes are clockwise: negative area
  }
  return CGAL::to_double(area);
}

std::vector<SharedSegment> shared_segments(const std::vector<Point>& a, const std::vector<Point>& b,
                                           double tol)
{
  std::vector<SharedSegment> result;
  const std::size_t na = a.size(), nb = b.size();
  for (std::size_t i = 0; i < na; ++i)
  {
    const Point& a1 = a[i];
    const Point& a2 = a[(i + 1) % na];
    const Vector2 ea = a2 - a1;
    const double la = ea.norm();
    const Vector2 ta = ea / la;
    for (std::size_t j = 0; j < nb; ++j)
    {
      const Point& b1 = b[j];
      const Point& b2 = b[(j + 1) % nb];
      // Both endpoints of b's edge on a's line, and opposite direction.
      if (std::abs(cross(ta, b1 - a1)) > tol || std::abs(cross(ta, b2 - a1)) > tol)
        continue;
      if ((b2 - b1).dot(ta) >= 0.0)
        continue;
      // Overlap of the projections onto a's edge: a spans [0, la], b spans [s2, s1].
      const double s1 = (b1 - a1).dot(ta);
      const double s2 = (b2 - a1).dot(ta);
      const double lo = std::max(0.0, s2);
      const double hi = std::min(la, s1);
      if (hi - lo <= tol)
        continue;
      result.push_back({i, j, a1 + lo * ta, a1 + hi * ta});
    }
  }
  return result;
}

} // namespace ddafem::dda
