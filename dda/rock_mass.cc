// The rock mass generator's driver (dda/rock_mass.h): the description checked, the arrangement
// built and settled, rounds of tidying and sliver merging, the blocks collected, ordered and
// counted. The steps live in dda/rock_mass_*.cc (see dda/rock_mass_arrangement.h).
#include "dda/rock_mass.h"

#include "common/format.h"
#include "common/input_error.h"
#include "dda/exact_area.h"
#include "dda/geometry.h"
#include "dda/rock_mass_arrangement.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

namespace ddafem::dda
{
namespace
{
using namespace rock_mass_internal;

double perimeter(const std::vector<Point>& vertices)
{
  double p = 0.0;
  for (std::size_t i = 0; i < vertices.size(); ++i)
    p += (vertices[(i + 1) % vertices.size()] - vertices[i]).norm();
  return p;
}

/// Input problems the generator cannot work around.
void check_description(const RockMassDescription& d)
{
  const auto expect = [](bool ok, const std::string& what)
  {
    if (!ok)
      throw InputError("rock mass: " + what);
  };
  expect(is_simple_polygon(anticlockwise(d.region)),
         "the region is not a simple polygon: expected at least 3 vertices, no self-intersection "
         "and a non-zero area");
  for (std::size_t s = 0; s < d.joint_sets.size(); ++s)
  {
    const JointSet& set = d.joint_sets[s];
    const std::string name = "joint set " + std::to_string(s) + ": ";
    expect(std::isfinite(set.dip),
           name + "dip = " + format_number(set.dip) + ": expected a number");
    expect(set.spacing > 0.0 && std::isfinite(set.spacing),
           name + "spacing = " + format_number(set.spacing) + " m: expected > 0");
    expect(set.bridge >= 0.0 && std::isfinite(set.bridge),
           name + "bridge = " + format_number(set.bridge) + " m: expected >= 0");
    expect(set.persistent() || (set.trace_length > 0.0 && std::isfinite(set.trace_length)),
           name + "trace_length = " + format_number(set.trace_length) +
               " m with a bridge: expected a finite length > 0");
    expect(set.perturbation.spacing >= 0.0 && set.perturbation.spacing < 1.0,
           name + "spacing perturbation = " + format_number(set.perturbation.spacing) +
               ": expected a fraction in [0, 1)");
    expect(set.perturbation.position >= 0.0 && std::isfinite(set.perturbation.position),
           name + "position perturbation = " + format_number(set.perturbation.position) +
               ": expected a fraction >= 0");
  }
  for (std::size_t j = 0; j < d.joints.size(); ++j)
    expect(d.joints[j].from != d.joints[j].to,
           "joint " + std::to_string(j) + " starts and ends at " +
               format_point(d.joints[j].from.x(), d.joints[j].from.y()) +
               ": expected two different points");
  if (d.min_edge_length)
    expect(*d.min_edge_length >= 0.0 && std::isfinite(*d.min_edge_length),
           "min_edge_length = " + format_number(*d.min_edge_length) + " m: expected >= 0");
  expect(d.straight_angle >= 0.0 && d.straight_angle < 90.0,
         "straight_angle = " + format_number(d.straight_angle) +
             " deg: expected an angle in [0, 90)");
  expect(d.chord_tolerance > 0.0,
         "chord_tolerance = " + format_number(d.chord_tolerance) + " m: expected > 0");
  for (std::size_t k = 0; k < d.openings.size(); ++k)
  {
    const Opening& o = d.openings[k];
    const std::string name = "opening " + std::to_string(k) + ": ";
    if (o.shape == Opening::Shape::circle)
      expect(o.radius > 0.0, name + "radius = " + format_number(o.radius) + " m: expected > 0");
    if (o.shape == Opening::Shape::horseshoe)
      expect(o.width > 0.0 && o.wall_height >= 0.0,
             name + "width = " + format_number(o.width) + " m, wall_height = " +
                 format_number(o.wall_height) + " m: expected width > 0 and wall_height >= 0");
    expect(is_simple_polygon(opening_polygon(o, d.chord_tolerance)),
           name + "not a simple polygon: expected at least 3 vertices, no self-intersection and "
                  "a non-zero area");
  }
}

/// Rounds of tidy() and sliver merging at most (two or three are usual).
constexpr std::size_t max_tidy_rounds = 16;

/// A few hundred rounding errors of the region's coordinates [m]: a vertex this close to the
/// line between its neighbours is straight (see without_collinear_vertices).
double rounding_tolerance(const RockMassDescription& d)
{
  return 1e-14 * extent(d.region);
}

/// The shortest block edge [m] (see RockMassDescription::min_edge_length).
double min_edge_length(const RockMassDescription& d, double mean_spacing)
{
  const double wanted =
      d.min_edge_length.value_or(d.joint_sets.empty() ? d.chord_tolerance : 0.01 * mean_spacing);
  return std::max(wanted, 1e-9 * extent(d.region));
}

/// The mean spacing of the joint sets [m]; 0 without sets.
double mean_spacing(const RockMassDescription& d)
{
  double mean = 0.0;
  for (const JointSet& set : d.joint_sets)
    mean += set.spacing / static_cast<double>(d.joint_sets.size());
  return mean;
}

/// Puts the joint traces, the boundary of the region (`region`, anticlockwise [m]) and the
/// openings' polygons into the empty arrangement and settles it (faces classified, islands cut).
/// Records the openings' polygons and the numbers of traces and island cuts in `result`.
void arrange(const RockMassDescription& d, const std::vector<Point>& region,
             Arrangement& arrangement, RockMassResult& result)
{
  std::vector<Traits::Curve_2> curves = joint_curves(d);
  result.statistics.n_traces = curves.size();
  append_polygon(region, {CurveSource::Kind::region, 0}, curves);
  for (std::size_t k = 0; k < d.openings.size(); ++k)
  {
    result.openings.push_back(opening_polygon(d.openings[k], d.chord_tolerance));
    append_polygon(result.openings.back(), {CurveSource::Kind::opening, k}, curves);
  }
  CGAL::insert(arrangement, curves.begin(), curves.end()); // sweep line, exact
  result.statistics.n_island_cuts = settle(arrangement, d.openings.size());
}

/// Short edges and slivers, in rounds until neither changes anything (at most max_tidy_rounds):
/// a collapse may fold a small face over, a merge may leave a straight vertex. Adds what was
/// done to the counts in `stats`.
void tidy_and_merge(Arrangement& arrangement, const RockMassDescription& d,
                    const EdgeCriteria& edge_criteria, const SliverCriteria& criteria,
                    RockMassStatistics& stats)
{
  const std::size_t n_openings = d.openings.size();
  for (std::size_t round = 0; round < max_tidy_rounds; ++round)
  {
    const TidyCounts tidied = tidy(arrangement, edge_criteria);
    stats.n_collapsed_edges += tidied.n_collapsed;
    stats.n_straight_vertices += tidied.n_straight;
    if (tidied.changed())
      stats.n_island_cuts += settle(arrangement, n_openings);
    std::size_t n_merged = 0;
    if (d.slivers.action == SliverAction::merge)
      while (const std::size_t n = merge_pass(arrangement, criteria))
      {
        n_merged += n;
        stats.n_island_cuts += settle(arrangement, n_openings);
      }
    stats.n_merged += n_merged;
    if (!tidied.changed() && n_merged == 0)
      break;
  }
}

/// The block faces as blocks, in the arrangement's order, and the areas of the region
/// (`region`, anticlockwise [m]) and of its excavated part [m^2].
void collect_blocks(Arrangement& arrangement, const RockMassDescription& d,
                    const std::vector<Point>& region, RockMassResult& result)
{
  Kernel::FT excavated = 0;
  for (auto f = arrangement.faces_begin(); f != arrangement.faces_end(); ++f)
    if (f->data().block)
      result.blocks.push_back(make_block(f, rounding_tolerance(d)));
    else if (f->data().in_region)
      excavated += face_area(f);
  std::vector<ExactPoint> exact_region;
  for (const Point& v : region)
    exact_region.push_back(exact_point(v));
  result.statistics.region_area =
      CGAL::to_double(polygon_area(exact_region.begin(), exact_region.end(), Kernel()));
  result.statistics.excavated_area = CGAL::to_double(excavated);
}

/// Orders the blocks bottom row first (by centroid y, then x) and lists the slivers among them.
void order_blocks(const SliverCriteria& criteria, RockMassResult& result)
{
  std::vector<std::pair<Point, RockMassBlock>> by_centroid;
  for (RockMassBlock& b : result.blocks)
    by_centroid.emplace_back(polygon_moments(b.vertices).centroid, std::move(b));
  std::sort(by_centroid.begin(), by_centroid.end(),
            [](const auto& a, const auto& b) {
              return a.first.y() < b.first.y() ||
                     (a.first.y() == b.first.y() && a.first.x() < b.first.x());
            });
  result.blocks.clear();
  for (auto& [centroid, block] : by_centroid)
  {
    const double p = perimeter(block.vertices);
    if (criteria.is_sliver(block.area, p))
      result.slivers.push_back({result.blocks.size(), centroid, block.area, 2.0 * block.area / p});
    result.blocks.push_back(std::move(block));
  }
}

/// The statistics of the final blocks: their number, areas and edges (against
/// stats.min_edge_length), and the number of slivers reported.
void count_blocks(RockMassResult& result)
{
  RockMassStatistics& stats = result.statistics;
  stats.n_blocks = result.blocks.size();
  stats.n_reported = result.slivers.size();
  if (result.blocks.empty())
    return;
  stats.smallest_area = result.blocks.front().area;
  for (const RockMassBlock& b : result.blocks)
  {
    stats.smallest_area = std::min(stats.smallest_area, b.area);
    stats.total_area += b.area;
  }
  stats.mean_area = stats.total_area / static_cast<double>(stats.n_blocks);
  stats.shortest_edge = std::numeric_limits<double>::infinity();
  for (const RockMassBlock& b : result.blocks)
    for (std::size_t k = 0; k < b.vertices.size(); ++k)
    {
      const double l = (b.vertices[(k + 1) % b.vertices.size()] - b.vertices[k]).norm();
      stats.shortest_edge = std::min(stats.shortest_edge, l);
      stats.n_short_edges += l < stats.min_edge_length;
    }
}

} // namespace

RockMassResult generate_blocks(const RockMassDescription& d)
{
  check_description(d);
  RockMassResult result;
  RockMassStatistics& stats = result.statistics;
  const std::vector<Point> region = anticlockwise(d.region);
  Arrangement arrangement;
  arrange(d, region, arrangement, result);

  const double spacing = mean_spacing(d);
  const SliverCriteria criteria{
      d.slivers.min_area.value_or(d.slivers.min_area_fraction * spacing * spacing),
      d.slivers.min_inscribed_radius};
  stats.min_area = criteria.min_area;
  const EdgeCriteria edge_criteria{min_edge_length(d, spacing), d.straight_angle * M_PI / 180.0};
  stats.min_edge_length = edge_criteria.min_length;
  tidy_and_merge(arrangement, d, edge_criteria, criteria, stats);

  collect_blocks(arrangement, d, region, result);
  order_blocks(criteria, result);
  count_blocks(result);
  return result;
}

} // namespace ddafem::dda
