// The polygons of openings (rock_mass.h): circles and horseshoe roofs as inscribed chords.
#include "common/format.h"
#include "common/input_error.h"
#include "dda/geometry.h"
#include "dda/rock_mass.h"

#include <algorithm>
#include <cmath>

namespace ddafem::dda
{
namespace
{
/// Fewest chords for `angle` [rad] of arc of radius r such that each stays within `tolerance`
/// of the arc: a chord over the angle a deviates by r (1 - cos(a / 2)). A double: a tolerance
/// far below the radius asks for more chords than an integer holds (infinitely many at 1e-17 r).
double chords_needed(double angle, double r, double tolerance, double at_least)
{
  const double max_angle = 2.0 * std::acos(std::max(-1.0, 1.0 - tolerance / r));
  return std::max(at_least, std::ceil(angle / max_angle));
}

/// chords_needed as a count; throws InputError beyond max_opening_sides (the readers refuse
/// such a tolerance before the polygon is made: refuse_opening).
std::size_t n_chords(double angle, double r, double tolerance, double at_least)
{
  const double n = chords_needed(angle, r, tolerance, at_least);
  if (!(n <= max_opening_sides))
    throw InputError("a chord tolerance of " + format_number(tolerance) + " m on a radius of " +
                     format_number(r) + " m gives " + format_number(n) +
                     " chords: expected a tolerance that gives at most " +
                     format_number(max_opening_sides));
  return static_cast<std::size_t>(n);
}
} // namespace

double opening_side_count(const Opening& opening, double chord_tolerance)
{
  switch (opening.shape)
  {
  case Opening::Shape::circle:
    return chords_needed(2.0 * M_PI, opening.radius, chord_tolerance, 8);
  case Opening::Shape::horseshoe:
    // floor, walls (if any) and the roof's chords
    return (opening.wall_height > 0.0 ? 3.0 : 1.0) +
           chords_needed(M_PI, 0.5 * opening.width, chord_tolerance, 4);
  case Opening::Shape::polygon:
    return static_cast<double>(opening.vertices.size());
  }
  return 0.0;
}

std::vector<Point> opening_polygon(const Opening& opening, double chord_tolerance)
{
  std::vector<Point> polygon;
  switch (opening.shape)
  {
  case Opening::Shape::circle:
  {
    const std::size_t n = n_chords(2.0 * M_PI, opening.radius, chord_tolerance, 8);
    for (std::size_t i = 0; i < n; ++i)
    {
      const double a = 2.0 * M_PI * static_cast<double>(i) / static_cast<double>(n);
      polygon.push_back(opening.center + opening.radius * Vector2(std::cos(a), std::sin(a)));
    }
    return polygon;
  }
  case Opening::Shape::horseshoe:
  {
    // Floor from left to right, right wall up, roof arc from right to left, left wall down.
    const double r = 0.5 * opening.width;
    const Point springline = opening.center + Vector2(0.0, opening.wall_height);
    polygon.push_back(opening.center + Vector2(-r, 0.0));
    polygon.push_back(opening.center + Vector2(r, 0.0));
    if (opening.wall_height > 0.0)
      polygon.push_back(springline + Vector2(r, 0.0));
    const std::size_t n = n_chords(M_PI, r, chord_tolerance, 4);
    for (std::size_t i = 1; i < n; ++i)
    {
      const double a = M_PI * static_cast<double>(i) / static_cast<double>(n);
      polygon.push_back(springline + r * Vector2(std::cos(a), std::sin(a)));
    }
    if (opening.wall_height > 0.0)
      polygon.push_back(springline + Vector2(-r, 0.0));
    return polygon;
  }
  case Opening::Shape::polygon:
    return anticlockwise(opening.vertices);
  }
  return polygon;
}

} // namespace ddafem::dda
