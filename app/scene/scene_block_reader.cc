// Blocks: `blocks` (polygons and grids) and `rock_mass`, the overlap check, `in_situ_stress`, and
// the points that must lie in some block (`point_loads`, `fixed_points`, `monitors`).
#include "app/scene/scene_readers.h"
#include "app/schema/bound_sections.h"

#include "common/format.h"
#include "dda/contact/broad_phase.h"
#include "dda/geometry.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace ddafem::scene_reading
{
namespace
{
/// The cells of `blocks[i].grid`, appended to the model as blocks like `block` (material, initial
/// velocity and stress).
void read_block_grid(const MapReader& r, dda::BlockDescription block, dda::ModelDescription& model,
                     std::vector<BlockSource>& sources)
{
  const MapReader grid = r.section_reader("grid");
  const Vector2 origin = grid.vector2("origin");
  const Vector2 cell = grid.vector2("cell_size");
  const std::array<long long, 2> count = grid.integer_pair("count");
  constexpr long long max_cells = 1000000;
  if (count[0] > max_cells || count[1] > max_cells || count[0] * count[1] > max_cells)
    throw grid.error("count", "expected at most " + std::to_string(max_cells) + " cells in all");
  const double n_blocks = static_cast<double>(model.blocks.size() + count[0] * count[1]);
  const ResourceLimits& limits = r.ctx().limits;
  if (!limits.fits(MemoryModel::of_blocks(n_blocks)))
  {
    const double largest =
        MemoryModel::blocks_within(limits.memory) - static_cast<double>(model.blocks.size());
    throw grid.error(
        "count", format_number(static_cast<double>(count[0] * count[1])) + " blocks would need " +
                     limits.too_much(MemoryModel::of_blocks(n_blocks)) + ": expected at most " +
                     format_number(std::floor(std::max(largest, 0.0))) + " cells");
  }
  for (long long iy = 0; iy < count[1]; ++iy)
    for (long long ix = 0; ix < count[0]; ++ix)
    {
      const double x0 = origin.x() + static_cast<double>(ix) * cell.x();
      const double x1 = origin.x() + static_cast<double>(ix + 1) * cell.x();
      const double y0 = origin.y() + static_cast<double>(iy) * cell.y();
      const double y1 = origin.y() + static_cast<double>(iy + 1) * cell.y();
      block.vertices = {Point(x0, y0), Point(x1, y0), Point(x1, y1), Point(x0, y1)};
      block.origin =
          r.key_path() + " (grid cell " + std::to_string(ix) + ", " + std::to_string(iy) + ")";
      model.blocks.push_back(block);
      sources.push_back({r.yaml(), r.key_path(), false, r.has("initial_stress")});
    }
}

/// Interval [min, max] of the projections of a polygon's vertices onto a direction.
std::pair<double, double> projection(const std::vector<Point>& vertices, const Vector2& direction)
{
  double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
  for (const Point& v : vertices)
  {
    const double x = v.dot(direction);
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  return {lo, hi};
}

/// An upper bound of the overlap area of two polygons [m^2], from their projections onto the
/// edge normals of both: the intersection lies in the slab where the projections overlap, and its
/// length along the slab is at most the smaller extent of the two polygons along it. Zero for
/// convex polygons that are separated or only touch; cheap next to the exact computation.
double overlap_area_bound(const std::vector<Point>& a, const std::vector<Point>& b)
{
  double bound = std::numeric_limits<double>::max();
  for (const std::vector<Point>* polygon : {&a, &b})
  {
    const std::size_t n = polygon->size();
    for (std::size_t k = 0; k < n; ++k)
    {
      const Vector2 edge = (*polygon)[(k + 1) % n] - (*polygon)[k];
      if (edge.norm() == 0.0)
        continue;
      const Vector2 along = edge.normalized();
      const Vector2 normal(-along.y(), along.x());
      const auto [a_lo, a_hi] = projection(a, normal);
      const auto [b_lo, b_hi] = projection(b, normal);
      const double width = std::min(a_hi, b_hi) - std::max(a_lo, b_lo);
      if (width <= 0.0)
        return 0.0;
      const auto [a_first, a_last] = projection(a, along);
      const auto [b_first, b_last] = projection(b, along);
      bound = std::min(bound, width * std::min(a_last - a_first, b_last - b_first));
    }
  }
  return bound;
}

/// The first block that p lies inside or on the boundary of (the one dda::System attaches it
/// to), if any.
std::optional<std::size_t> block_containing(const Point& p, const dda::ModelDescription& model,
                                            const BlockBoxes& boxes)
{
  for (std::size_t b = 0; b < model.blocks.size(); ++b)
    if (boxes.boxes[b].contains(p, boxes.tolerance) &&
        dda::locate_point(model.blocks[b].vertices, p, boxes.tolerance) !=
            dda::PointLocation::outside)
      return b;
  return std::nullopt;
}

/// Points of loads, supports and monitors must be inside or on the boundary of some block.
bool in_some_block(const Point& p, const dda::ModelDescription& model, const BlockBoxes& boxes)
{
  return block_containing(p, model, boxes).has_value();
}

void check_point_in_blocks(const MapReader& r, const std::string& key, const Point& p,
                           const dda::ModelDescription& model, const BlockBoxes& boxes)
{
  if (in_some_block(p, model, boxes))
    return;
  throw r.error(key, "the point " + format_point(p) +
                         " lies outside every block; expected a point inside or on the boundary "
                         "of a block");
}
} // namespace

/// Drops a repeated closing vertex, checks that the polygon (at key `key` of r) is simple and
/// orders it anticlockwise.
std::vector<Point> clean_polygon(const MapReader& r, const std::string& key,
                                 std::vector<Point> vertices)
{
  if (vertices.size() > 1 && vertices.front() == vertices.back())
    vertices.pop_back();
  std::vector<Point> distinct;
  for (const Point& v : vertices)
    if (std::find(distinct.begin(), distinct.end(), v) == distinct.end())
      distinct.push_back(v);
  if (distinct.size() < 3)
    throw r.error(key, "polygon is not closed: needs at least 3 distinct vertices");
  if (!dda::is_simple_polygon(vertices))
    throw r.error(key, "polygon of " + r.key_path() +
                           " is self-intersecting (or repeats a vertex or has zero "
                           "area): expected a simple polygon");
  if (dda::signed_area(vertices) < 0.0)
    std::reverse(vertices.begin(), vertices.end());
  return vertices;
}

/// [[x, y], ...] as points [m].
std::vector<Point> points_of(const std::vector<std::array<double, 2>>& pairs)
{
  std::vector<Point> points;
  for (const auto& [x, y] : pairs)
    points.emplace_back(x, y);
  return points;
}

void read_blocks(const MapReader& top, const SceneNames& names, dda::ModelDescription& model,
                 std::vector<BlockSource>& sources, std::optional<RockMassReport>& rock_mass)
{
  const std::vector<MapReader> items = top.section_list("blocks");
  const bool has_blocks = !items.empty() || top.has("rock_mass");
  if (!has_blocks && !top.has("far_field"))
    throw top.error("blocks", "expected at least one block (or a `rock_mass` or a `far_field`)");
  if (has_blocks && top.has("far_field") && !top.has("interface"))
    throw top.error("far_field", "blocks and a far field need an `interface` section: expected "
                                 "`interface: {part: PART}` naming the far field's part the "
                                 "blocks fill (e.g. hole)");
  if (top.has("interface") && (!has_blocks || !top.has("far_field")))
    throw top.error("interface", "an interface ties blocks to a far field: expected both "
                                 "`blocks` and `far_field`");
  for (std::size_t i = 0; i < items.size(); ++i)
  {
    const MapReader& r = items[i];
    dda::BlockDescription block;
    block.material = find_name(r, "material", r.string("material"), names.materials, "material");
    schema::block_keys().fill(r, block); // initial velocity and stress
    const bool has_vertices = r.has("vertices"), has_grid = r.has("grid");
    if (has_vertices == has_grid)
      throw top.ctx().locator.error(r.yaml(), r.key_path(), "",
                                    has_vertices ? "give either 'vertices' or 'grid', not both"
                                                 : "missing key: give 'vertices' or 'grid'");
    if (has_vertices)
    {
      std::vector<Point> vertices;
      for (const auto& [x, y] : r.pair_list("vertices"))
        vertices.emplace_back(x, y);
      block.vertices = clean_polygon(r, "vertices", std::move(vertices));
      block.origin = r.key_path();
      model.blocks.push_back(block);
      sources.push_back({r.yaml(), r.key_path(), false, r.has("initial_stress")});
      continue;
    }
    read_block_grid(r, block, model, sources);
  }
  if (top.has("rock_mass"))
    rock_mass = read_rock_mass(top.section_reader("rock_mass"), names, model, sources);
}

/// Overlapping blocks are an error. Candidate pairs come from the contact detection's broad
/// phase (their bounding boxes overlap or touch); only pairs whose boxes (and projections onto
/// their edge normals) overlap by more than the tolerated area are handed to the exact but slow
/// overlap computation. Pairs are checked in index order, so the first overlap reported is the
/// one with the lowest indices.
void check_overlaps(const dda::ModelDescription& model, const std::vector<BlockSource>& sources,
                    const Locator& locator)
{
  std::vector<dda::BoundingBox> boxes;
  std::vector<double> areas;
  for (const dda::BlockDescription& b : model.blocks)
  {
    boxes.push_back(dda::bounding_box(b.vertices, 0.0));
    areas.push_back(std::abs(dda::signed_area(b.vertices)));
  }
  for (const auto& [i, j] : dda::overlapping_pairs(boxes))
  {
    if (sources[i].generated && sources[j].generated)
      continue; // faces of one arrangement
    const double tolerated = 1e-9 * std::min(areas[i], areas[j]);
    const double wx =
        std::min(boxes[i].x_max, boxes[j].x_max) - std::max(boxes[i].x_min, boxes[j].x_min);
    const double wy =
        std::min(boxes[i].y_max, boxes[j].y_max) - std::max(boxes[i].y_min, boxes[j].y_min);
    if (wx <= 0.0 || wy <= 0.0 || wx * wy <= tolerated ||
        overlap_area_bound(model.blocks[i].vertices, model.blocks[j].vertices) <= tolerated)
      continue;
    const double overlap = dda::overlap_area(model.blocks[i].vertices, model.blocks[j].vertices);
    if (overlap > tolerated)
      throw locator.error(sources[j].node, sources[j].key_path, "",
                          "blocks overlap: " + model.blocks[i].origin + " and " +
                              model.blocks[j].origin + " share an area of " +
                              format_number(overlap) + " m^2; expected blocks that touch at most");
  }
}

void read_in_situ_stress(const MapReader& top, const std::vector<BlockSource>& sources,
                         dda::ModelDescription& model)
{
  const MapReader r = top.section_reader("in_situ_stress");
  schema::in_situ_stress_keys().fill(r, model.in_situ_stress);
  for (std::size_t i = 0; i < model.blocks.size(); ++i)
    if (!sources[i].initial_stress)
      model.blocks[i].initial_stress =
          model.in_situ_stress.at(dda::polygon_moments(model.blocks[i].vertices).centroid);
}

BlockBoxes block_boxes(const dda::ModelDescription& model)
{
  BlockBoxes result;
  if (model.blocks.empty())
    return result;
  Box all(model.blocks.front().vertices);
  for (const dda::BlockDescription& b : model.blocks)
  {
    result.boxes.emplace_back(b.vertices);
    all.lower = all.lower.cwiseMin(result.boxes.back().lower);
    all.upper = all.upper.cwiseMax(result.boxes.back().upper);
  }
  result.tolerance = 1e-9 * (all.upper - all.lower).norm();
  return result;
}

void read_point_loads(const MapReader& top, const BlockBoxes& boxes, dda::ModelDescription& model)
{
  for (const MapReader& r : top.section_list("point_loads"))
  {
    dda::PointLoad load;
    schema::point_load_keys().fill(r, load); // point and force
    load.time_function = read_time_function(r, "time_function", TimeFunctionUse::factor);
    load.origin = r.key_path();
    check_point_in_blocks(r, "point", load.point, model, boxes);
    model.point_loads.push_back(load);
  }
}

void read_fixed_points(const MapReader& top, const BlockBoxes& boxes, dda::ModelDescription& model)
{
  for (const MapReader& r : top.section_list("fixed_points"))
  {
    dda::FixedPoint f;
    schema::fixed_point_keys().fill(r, f); // point and stiffness
    f.displacement_x = read_time_function(r, "displacement_x", TimeFunctionUse::displacement);
    f.displacement_y = read_time_function(r, "displacement_y", TimeFunctionUse::displacement);
    f.origin = r.key_path();
    check_point_in_blocks(r, "point", f.point, model, boxes);
    model.fixed_points.push_back(f);
  }
}

void read_bolts(const MapReader& top, const BlockBoxes& boxes, dda::ModelDescription& model)
{
  std::map<std::string, std::string> bolt_paths;
  for (const MapReader& r : top.section_list("bolts"))
  {
    dda::BoltDescription b;
    b.origin = r.key_path();
    b.name = r.has("name") ? r.string("name") : "bolt" + std::to_string(model.bolts.size());
    if (trim(b.name).empty())
      throw r.error("name", "expected a non-empty name");
    if (const auto [it, inserted] = bolt_paths.emplace(b.name, b.origin); !inserted)
      throw r.error("name",
                    "duplicate bolt name (also used by " + it->second + "): expected unique names");
    b.head = r.vector2("head");
    b.anchor = r.vector2("anchor");
    schema::bolt_keys().fill(r, b); // the steel, the type and the grout
    if (b.pretension >= b.yield_force)
      throw r.error("pretension", "expected a pretension below the yield force (" +
                                      format_significant(b.yield_force) + " N)");
    const std::optional<std::size_t> head = block_containing(b.head, model, boxes);
    if (!head)
      check_point_in_blocks(r, "head", b.head, model, boxes);
    const std::optional<std::size_t> anchor = block_containing(b.anchor, model, boxes);
    if (!anchor)
      check_point_in_blocks(r, "anchor", b.anchor, model, boxes);
    read_bolt_type(r, b, model); // a grouted bolt's crossings: refused naming the bolt
    if (*head == *anchor)
      throw r.error("anchor", "the anchor " + format_point(b.anchor) +
                                  " lies in the same block as the head (" +
                                  model.blocks[*head].origin +
                                  "): expected the anchor in another block");
    model.bolts.push_back(b);
  }
}

void read_monitors(const MapReader& top, const BlockBoxes& boxes, dda::ModelDescription& model,
                   std::optional<fem::FarFieldDescription>& far_field)
{
  std::map<std::string, std::string> monitor_paths;
  for (const MapReader& r : top.section_list("monitors"))
  {
    dda::Monitor m;
    schema::monitor_keys().fill(r, m); // name and point
    if (trim(m.name).empty())
      throw r.error("name", "expected a non-empty name");
    const auto [it, inserted] = monitor_paths.emplace(m.name, r.key_path());
    if (!inserted)
      throw r.error("name", "duplicate monitor name (also used by " + it->second +
                                "): expected unique names");
    // In a coupled scene a monitor belongs to the block it lies in, else to the far field.
    const bool in_blocks = !model.blocks.empty() && in_some_block(m.point, model, boxes);
    if (far_field && !in_blocks)
    {
      if (far_field->mesh_file.file.empty())
        check_point_in_far_field(r, "point", m.point, *far_field);
      far_field->monitors.push_back({m.name, {m.point.x(), m.point.y()}});
      continue;
    }
    check_point_in_blocks(r, "point", m.point, model, boxes);
    model.monitors.push_back(m);
  }
}

} // namespace ddafem::scene_reading
