#include "app/scene/tunnel_bolts.h"
#include "app/schema/bound_sections.h"

#include "common/format.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ddafem
{
namespace
{
using dda::Point;
using dda::Vector2;

Vector2 unit_at(double angle)
{
  const double a = angle * std::acos(-1.0) / 180.0;
  return {std::cos(a), std::sin(a)};
}

/// The pattern's count: `count`, or from `spacing` along the perimeter between the angles.
std::size_t pattern_count(const scene_reading::MapReader& r, const std::vector<Point>& polygon,
                          const Point& centre, double from, double to)
{
  if (r.has("count") == r.has("spacing"))
    throw r.error("count", "expected exactly one of `count` and `spacing`");
  if (r.has("count"))
    return static_cast<std::size_t>(r.integer("count"));
  const double perimeter = perimeter_between(polygon, centre, from, to);
  return static_cast<std::size_t>(std::llround(perimeter / r.number("spacing"))) + 1;
}
} // namespace

Point pattern_centre(const dda::Opening& opening)
{
  switch (opening.shape)
  {
  case dda::Opening::Shape::circle:
    return opening.center;
  case dda::Opening::Shape::horseshoe:
    return opening.center + Vector2(0.0, opening.wall_height);
  case dda::Opening::Shape::polygon:
    break;
  }
  Point lower = opening.vertices.front(), upper = lower;
  for (const Point& v : opening.vertices)
  {
    lower = lower.cwiseMin(v);
    upper = upper.cwiseMax(v);
  }
  return 0.5 * (lower + upper);
}

Point ray_exit(const std::vector<Point>& polygon, const Point& centre, double angle)
{
  const Vector2 d = unit_at(angle);
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < polygon.size(); ++i)
  {
    const Point& a = polygon[i];
    const Vector2 e = polygon[(i + 1) % polygon.size()] - a;
    const double denominator = d.x() * e.y() - d.y() * e.x();
    if (denominator == 0.0)
      continue;
    const Vector2 w = a - centre;
    const double along = (w.x() * e.y() - w.y() * e.x()) / denominator; // [m] along the ray
    const double on_edge = (w.x() * d.y() - w.y() * d.x()) / denominator;
    if (along > 0.0 && on_edge >= 0.0 && on_edge <= 1.0)
      nearest = std::min(nearest, along);
  }
  return std::isfinite(nearest) ? Point(centre + nearest * d) : centre;
}

double perimeter_between(const std::vector<Point>& polygon, const Point& centre, double from,
                         double to)
{
  const auto n = static_cast<std::size_t>(std::ceil((to - from) / 0.1)) + 1;
  double length = 0.0;
  Point last = ray_exit(polygon, centre, from);
  for (std::size_t k = 1; k <= n; ++k)
  {
    const Point p = ray_exit(polygon, centre, from + (to - from) * k / n);
    length += (p - last).norm();
    last = p;
  }
  return length;
}

std::vector<RadialBolt> radial_bolts(const std::vector<Point>& polygon, const Point& centre,
                                     double from, double to, std::size_t count, double length)
{
  std::vector<RadialBolt> bolts;
  for (std::size_t k = 0; k < count; ++k)
  {
    const double angle =
        count == 1 ? 0.5 * (from + to) : from + (to - from) * static_cast<double>(k) / (count - 1);
    const Point head = ray_exit(polygon, centre, angle);
    bolts.push_back({angle, head, head + length * unit_at(angle)});
  }
  return bolts;
}

void write_tunnel_bolts(const scene_reading::MapReader& r, const dda::Opening& opening,
                        double chord_tolerance, YAML::Node& root)
{
  BoltPattern pattern;
  schema::tunnel_bolt_pattern_keys().fill(r, pattern);
  const double from = pattern.from_angle;
  const double to = pattern.to_angle;
  if (!(to > from) || to > from + 360.0)
    throw r.error("to_angle", "expected from_angle < to_angle <= from_angle + 360 (got " +
                                  format_number(from) + " and " + format_number(to) + ")");
  const std::vector<Point> polygon = dda::opening_polygon(opening, chord_tolerance);
  const Point centre = pattern_centre(opening);
  const std::size_t count = pattern_count(r, polygon, centre, from, to);
  // The bolt keys, checked here against tunnel.bolts' ranges, then copied as written.
  YAML::Node keys(YAML::NodeType::Map);
  for (const std::string& key : r.ctx().schema.section("bolts[i]").key_names())
  {
    if (key == "name" || key == "head" || key == "anchor" || !r.has(key))
      continue;
    if (key == "type")
      static_cast<void>(r.choice(key));
    else
      static_cast<void>(r.number(key));
    keys[key] = YAML::Clone(r.yaml()[key]);
  }
  const YAML::Node& given = root;
  YAML::Node bolts =
      given["bolts"] ? YAML::Clone(given["bolts"]) : YAML::Node(YAML::NodeType::Sequence);
  const std::vector<RadialBolt> lines =
      radial_bolts(polygon, centre, from, to, count, pattern.length);
  for (std::size_t k = 0; k < lines.size(); ++k)
  {
    YAML::Node b = YAML::Clone(keys);
    b["name"] = "tunnel_bolt" + std::to_string(k) + "_" + format_number(lines[k].angle) + "deg";
    for (const auto& [key, p] : {std::pair{"head", lines[k].head}, {"anchor", lines[k].anchor}})
    {
      YAML::Node xy(YAML::NodeType::Sequence);
      xy.push_back(p.x());
      xy.push_back(p.y());
      xy.SetStyle(YAML::EmitterStyle::Flow);
      b[key] = xy;
    }
    bolts.push_back(b);
  }
  root["bolts"] = bolts;
}

} // namespace ddafem
