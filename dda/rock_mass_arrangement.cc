// Points, numbers and edges of the rock mass arrangement (dda/rock_mass_arrangement.h).
#include "dda/rock_mass_arrangement.h"

#include <algorithm>
#include <cmath>

namespace ddafem::dda::rock_mass_internal
{
ExactPoint exact_point(const Point& p)
{
  return ExactPoint(p.x(), p.y());
}

Point rounded(const ExactPoint& p)
{
  const auto& e = CGAL::exact(p);
  return Point(CGAL::to_double(e.x()), CGAL::to_double(e.y()));
}

Point approximate(const ExactPoint& p)
{
  return Point(CGAL::to_double(p.x()), CGAL::to_double(p.y()));
}

Box bounding_box(const std::vector<Point>& points)
{
  Box box{points.front(), points.front()};
  for (const Point& v : points)
  {
    box.lower = box.lower.cwiseMin(v);
    box.upper = box.upper.cwiseMax(v);
  }
  return box;
}

double extent(const std::vector<Point>& region)
{
  const Box box = bounding_box(region);
  return (box.upper - box.lower).maxCoeff();
}

double length(Halfedge h)
{
  return std::sqrt(
      CGAL::to_double(CGAL::squared_distance(h->source()->point(), h->target()->point())));
}

bool on_boundary(Halfedge h)
{
  return std::any_of(h->curve().data().begin(), h->curve().data().end(),
                     [](const CurveSource& s) {
                       return s.kind == CurveSource::Kind::region ||
                              s.kind == CurveSource::Kind::opening;
                     });
}

std::vector<CurveSource> sources(Halfedge h)
{
  return {h->curve().data().begin(), h->curve().data().end()};
}

} // namespace ddafem::dda::rock_mass_internal
