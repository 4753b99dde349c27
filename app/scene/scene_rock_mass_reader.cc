// The `rock_mass` section: its region, joint sets, explicit joints and openings, and the blocks
// dda::generate_blocks cuts from them.
#include "app/scene/rock_mass_scene.h"
#include "app/scene/scene_readers.h"
#include "app/schema/bound_sections.h"

namespace ddafem::scene_reading
{
namespace
{
/// The names of the keys of r among `names` that are present, quoted.
std::vector<std::string> present(const MapReader& r, const std::vector<std::string>& names)
{
  std::vector<std::string> found;
  for (const std::string& name : names)
    if (r.has(name))
      found.push_back("'" + name + "'");
  return found;
}

/// `rock_mass.region`: the rectangle's or the polygon's corners, anticlockwise.
std::vector<Point> read_region(const MapReader& r)
{
  const std::vector<std::string> given = present(r, {"rectangle", "polygon"});
  if (given.size() != 1)
    throw r.ctx().locator.error(
        r.yaml(), r.key_path(), "",
        (given.empty() ? std::string("no region given") : "both " + join(given, " and ")) +
            ": expected exactly one of 'rectangle: {lower: [x, y], upper: [x, y]}' or "
            "'polygon: [[x, y], ...]'");
  if (r.has("polygon"))
    return clean_polygon(r, "polygon", points_of(r.pair_list("polygon")));
  const MapReader rectangle = r.section_reader("rectangle");
  const Vector2 lower = rectangle.vector2("lower"), upper = rectangle.vector2("upper");
  if (!(upper.x() > lower.x() && upper.y() > lower.y()))
    throw rectangle.error("upper",
                          "expected upper > lower in both x and y, lower = " + format_point(lower));
  return {lower, Point(upper.x(), lower.y()), upper, Point(lower.x(), upper.y())};
}
} // namespace

dda::JointSet read_joint_set(const MapReader& r)
{
  dda::JointSet set;
  schema::joint_set_keys().fill(r, set); // dip, spacing, offset
  const bool has_trace = r.has("trace_length"), has_bridge = r.has("bridge");
  if (has_trace != has_bridge)
    throw r.error(has_trace ? "trace_length" : "bridge",
                  std::string(has_trace ? "a trace length needs a `bridge`"
                                        : "a bridge needs a `trace_length`") +
                      ": expected both (non-persistent joints) or neither (persistent joints)");
  if (has_trace)
  {
    set.trace_length = r.number("trace_length");
    set.bridge = r.number("bridge");
  }
  const MapReader p = r.section_reader("perturbation");
  schema::perturbation_keys().fill(p, set.perturbation);
  return set;
}

/// `rock_mass.openings[i]`, checked to lie inside the region (as the polygon excavated).
dda::Opening read_opening(const MapReader& r, const std::vector<Point>& region,
                          double chord_tolerance)
{
  const std::vector<std::string> given = present(r, {"circle", "horseshoe", "polygon"});
  if (given.size() != 1)
    throw r.ctx().locator.error(
        r.yaml(), r.key_path(), "",
        (given.empty() ? std::string("no shape given")
                       : "more than one shape (" + join(given, ", ") + ")") +
            ": expected exactly one of 'circle: {center, radius}', 'horseshoe: {floor_center, "
            "width, wall_height}' or 'polygon: [[x, y], ...]'");
  dda::Opening o;
  std::string shape = "polygon";
  if (r.has("circle"))
  {
    shape = "circle";
    const MapReader c = r.section_reader("circle");
    o.shape = dda::Opening::Shape::circle;
    o.center = c.vector2("center");
    schema::circle_keys().fill(c, o);
  }
  else if (r.has("horseshoe"))
  {
    shape = "horseshoe";
    const MapReader h = r.section_reader("horseshoe");
    o.shape = dda::Opening::Shape::horseshoe;
    o.center = h.vector2("floor_center");
    schema::horseshoe_keys().fill(h, o);
  }
  else
  {
    o.shape = dda::Opening::Shape::polygon;
    o.vertices = clean_polygon(r, "polygon", points_of(r.pair_list("polygon")));
  }
  if (const auto refusal = dda::refuse_opening(o, chord_tolerance, r.ctx().limits))
    throw r.error(shape, *refusal);
  const std::vector<Point> polygon = dda::opening_polygon(o, chord_tolerance);
  const double area = dda::signed_area(polygon);
  const double outside = area - dda::overlap_area(polygon, region);
  if (outside > 1e-9 * area)
    throw r.error(shape, "the opening reaches outside the region (" + format_number(outside) +
                             " of its " + format_number(area) +
                             " m^2): expected an opening inside the region");
  return o;
}

/// The `joint_material` of a joint set or explicit joint (an index into joint_names), if given.
std::optional<std::size_t> read_joint_material(const MapReader& r,
                                               const std::vector<std::string>& joint_names)
{
  if (!r.has("joint_material"))
    return std::nullopt;
  return find_name(r, "joint_material", r.string("joint_material"), joint_names, "joint material");
}

/// The `rock_mass` section: generates its blocks and appends them to the model.
RockMassReport read_rock_mass(const MapReader& r, const SceneNames& names,
                              dda::ModelDescription& model, std::vector<BlockSource>& sources)
{
  const std::vector<std::string>& material_names = names.materials;
  const std::vector<std::string>& joint_names = names.joint_materials;
  dda::RockMassDescription d;
  RockMassReport report;
  const std::size_t material =
      find_name(r, "material", r.string("material"), material_names, "material");
  d.region = read_region(r.section_reader("region"));
  schema::rock_mass_keys().fill(r, d); // chord tolerance, seed, sliver width and action
  for (const MapReader& j : r.section_list("joint_sets"))
  {
    d.joint_sets.push_back(read_joint_set(j));
    report.joint_set_materials.push_back(read_joint_material(j, joint_names));
  }
  for (const MapReader& j : r.section_list("joints"))
  {
    d.joints.push_back({j.vector2("from"), j.vector2("to")});
    report.joint_materials.push_back(read_joint_material(j, joint_names));
    if (d.joints.back().from == d.joints.back().to)
      throw j.error("to", "the joint ends where it starts: expected a point other than `from`");
  }
  for (const MapReader& o : r.section_list("openings"))
    d.openings.push_back(read_opening(o, d.region, d.chord_tolerance));
  if (r.has("min_block_area"))
    d.slivers.min_area = r.number("min_block_area");

  if (const auto refusal = dda::refuse_beyond(d, model.blocks.size(), r.ctx().limits))
  {
    using Key = dda::RockMassTooLarge::Key;
    const char* key = name_of(refusal->key);
    if (refusal->key == Key::spacing || refusal->key == Key::trace_length)
      throw r.section_list("joint_sets")[refusal->joint_set].error(key, refusal->message);
    if (refusal->key == Key::chord_tolerance)
      throw r.error(key, refusal->message);
    throw r.ctx().locator.error(r.yaml(), r.key_path(), "", refusal->message);
  }
  dda::RockMassResult result;
  try
  {
    result = dda::generate_blocks(d);
  }
  catch (const InputError& e)
  {
    throw r.ctx().locator.error(r.yaml(), r.key_path(), "", e.what());
  }
  if (result.blocks.empty())
    throw r.ctx().locator.error(r.yaml(), r.key_path(), "",
                                "the openings cover the whole region: expected rock left");
  report.first_block = model.blocks.size();
  report.statistics = result.statistics;
  report.joint_sets = d.joint_sets;
  report.joints = d.joints;
  report.openings = result.openings;
  for (std::size_t i = 0; i < result.blocks.size(); ++i)
  {
    dda::BlockDescription block;
    block.vertices = std::move(result.blocks[i].vertices);
    block.edge_joint_materials = edge_joint_materials(result.blocks[i], report);
    block.material = material;
    block.origin = "rock_mass block " + std::to_string(i);
    model.blocks.push_back(std::move(block));
    sources.push_back({r.yaml(), r.key_path(), true});
  }
  for (dda::Sliver sliver : result.slivers)
  {
    sliver.block += report.first_block;
    report.slivers.push_back(sliver);
  }
  return report;
}

} // namespace ddafem::scene_reading
