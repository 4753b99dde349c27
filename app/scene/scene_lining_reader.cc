// `linings` (dda/lining.h): the polyline's nodes must lie on or in blocks, `installed_after` must
// name a stage; read after `stages`.
#include "app/scene/scene_readers.h"
#include "app/schema/bound_sections.h"

#include "common/format.h"
#include "dda/geometry.h"
#include "dda/lining.h"

#include <algorithm>
#include <map>

namespace ddafem::scene_reading
{
namespace
{
/// The largest extent of the model's blocks [m] (as dda::System's tolerances use).
double blocks_extent(const dda::ModelDescription& model)
{
  Point lo = Point::Constant(0.0), hi = Point::Constant(0.0);
  bool first = true;
  for (const dda::BlockDescription& b : model.blocks)
    for (const Point& v : b.vertices)
    {
      lo = first ? v : Point(lo.cwiseMin(v));
      hi = first ? v : Point(hi.cwiseMax(v));
      first = false;
    }
  return (hi - lo).maxCoeff();
}

/// Every node of the lining on or in a block, as dda::System attaches it.
void check_lining_nodes(const MapReader& r, const dda::LiningDescription& l,
                        const dda::ModelDescription& model)
{
  const double tol = 1e-9 * blocks_extent(model);
  const std::vector<Point> nodes = dda::lining_node_positions(l.points, l.segment_length, l.closed);
  for (std::size_t k = 0; k < nodes.size(); ++k)
  {
    const bool inside = std::any_of(
        model.blocks.begin(), model.blocks.end(),
        [&](const dda::BlockDescription& b)
        { return dda::locate_point(b.vertices, nodes[k], tol) != dda::PointLocation::outside; });
    if (!inside)
      throw r.error("points", "node " + std::to_string(k) + " of the lining at " +
                                  format_point(nodes[k]) +
                                  " lies outside every block: expected a polyline on the "
                                  "blocks' surface (every node on or inside a block)");
  }
}

/// The stage at whose start the lining is installed: the one after `installed_after`.
std::size_t install_stage(const MapReader& r, const dda::ModelDescription& model)
{
  if (!r.has("installed_after"))
    return 0;
  const std::string name = r.string("installed_after");
  for (std::size_t k = 0; k < model.stages.size(); ++k)
    if (model.stages[k].name == name)
    {
      if (k + 1 == model.stages.size())
        throw r.error("installed_after", "the stage '" + name +
                                             "' is the last one: expected a stage that another "
                                             "follows");
      return k + 1;
    }
  std::string names;
  for (const dda::Stage& s : model.stages)
    names += (names.empty() ? "" : ", ") + s.name;
  throw r.error("installed_after", "expected the name of a stage (" +
                                       (names.empty() ? std::string("the scene has none") : names) +
                                       ")");
}
/// `points` and `closed`, or `opening`: the polygon of an opening of the rock mass, closed.
void read_lining_path(const MapReader& r, const std::optional<RockMassReport>& rock_mass,
                      dda::LiningDescription& l)
{
  if (r.has("points") == r.has("opening"))
    throw r.error("points", "expected exactly one of `points` and `opening`");
  if (r.has("points"))
  {
    l.points = points_of(r.pair_list("points"));
    schema::lining_path_keys().fill(r, l); // closed
    return;
  }
  const long long k = r.integer("opening");
  const std::size_t n = rock_mass ? rock_mass->openings.size() : 0;
  if (k < 0 || static_cast<std::size_t>(k) >= n)
    throw r.error("opening",
                  n == 0 ? std::string("the scene has no rock_mass openings: expected "
                                       "`points` instead")
                         : "expected an index of rock_mass.openings below " + std::to_string(n));
  l.points = rock_mass->openings[static_cast<std::size_t>(k)];
  l.closed = true;
}
} // namespace

void read_linings(const MapReader& top, const std::optional<RockMassReport>& rock_mass,
                  dda::ModelDescription& model)
{
  std::map<std::string, std::string> paths;
  for (const MapReader& r : top.section_list("linings"))
  {
    dda::LiningDescription l;
    l.origin = r.key_path();
    l.name = r.has("name") ? r.string("name") : "lining" + std::to_string(model.linings.size());
    if (trim(l.name).empty())
      throw r.error("name", "expected a non-empty name");
    if (const auto [it, inserted] = paths.emplace(l.name, l.origin); !inserted)
      throw r.error("name", "duplicate lining name (also used by " + it->second +
                                "): expected unique names");
    read_lining_path(r, rock_mass, l);
    if (l.points.size() < (l.closed ? 3u : 2u))
      throw r.error("points", l.closed ? "expected at least three points for a closed lining"
                                       : "expected at least two points");
    for (std::size_t k = 0; k + 1 < l.points.size(); ++k)
      if (l.points[k] == l.points[k + 1])
        throw r.item_error("points", k + 1, "a point different from the one before");
    if (l.closed && l.points.front() == l.points.back())
      throw r.item_error("points", l.points.size() - 1,
                         "a point different from the first (a closed lining joins them itself)");
    schema::lining_section_keys().fill(r, l);
    l.install_stage = install_stage(r, model);
    check_lining_nodes(r, l, model);
    model.linings.push_back(l);
  }
}

} // namespace ddafem::scene_reading
