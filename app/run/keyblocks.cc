#include "app/run/keyblocks.h"

#include "common/enum_names.h"
#include "dda/geometry.h"
#include "dda/joints.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace ddafem
{
namespace
{
using dda::Point;
using dda::Vector2;
constexpr std::size_t npos = std::numeric_limits<std::size_t>::max();
} // namespace

namespace
{
/// Newmark's yield accelerations of the keyblocks of `geometry`: each block rigid on the joints
/// of its edges that are not on its opening (friction of the edge's joint material), under the
/// model's gravity, for horizontal and vertical shaking.
std::vector<KeyblockRecorder::Yield> keyblock_yields(const dda::ModelDescription& model,
                                                     const KeyblockGeometry& geometry, double tol)
{
  std::vector<KeyblockRecorder::Yield> yields;
  for (std::size_t k = 0; k < geometry.blocks.size(); ++k)
  {
    const std::size_t id = geometry.blocks[k];
    const std::vector<Point>& polygon = model.blocks[id].vertices;
    std::vector<double> tan_friction(polygon.size(), 0.0);
    for (std::size_t e = 0; e < polygon.size(); ++e)
    {
      const std::size_t jm = dda::joint_material_at_edge(model, id, e, id);
      if (jm < model.joint_materials.size())
        tan_friction[e] = std::tan(model.joint_materials[jm].friction_angle * M_PI / 180.0);
    }
    const std::vector<dda::BlockFace> faces = dda::block_faces(
        polygon, geometry.openings[geometry.opening_of[k]].segments, tan_friction, tol);
    yields.push_back({dda::yield_acceleration(faces, model.gravity, Vector2(1.0, 0.0)),
                      dda::yield_acceleration(faces, model.gravity, Vector2(0.0, 1.0))});
  }
  return yields;
}

/// A yield acceleration in summary.json: {"m_s2" (null if none), "mode", "edge"}.
nlohmann::json yield_json(const dda::YieldAcceleration& y)
{
  nlohmann::json j = {{"m_s2", std::isfinite(y.a_y) ? nlohmann::json(y.a_y) : nlohmann::json()},
                      {"mode", y.mode == dda::YieldMode::slide      ? "slide"
                               : y.mode == dda::YieldMode::lift_off ? "lift_off"
                                                                    : "none"}};
  if (y.mode == dda::YieldMode::slide)
    j["edge"] = y.edge;
  return j;
}
} // namespace

KeyblockRecorder::KeyblockRecorder(const dda::ModelDescription& model, FallCriterion fall)
    : criterion(fall), small_displacement(model.geometry == dda::GeometryMode::small_displacement)
{
  std::vector<std::vector<Point>> polygons;
  Point lower = Point::Constant(std::numeric_limits<double>::max());
  Point upper = -lower;
  for (const dda::BlockDescription& b : model.blocks)
  {
    polygons.push_back(b.vertices);
    for (const Point& v : b.vertices)
    {
      lower = lower.cwiseMin(v);
      upper = upper.cwiseMax(v);
    }
  }
  if (polygons.empty())
    return;
  // The collinearity tolerance of the System's joints.
  const double tol = 1e-9 * (upper - lower).maxCoeff();
  geometry = dda::find_keyblocks(polygons, tol);
  yields = keyblock_yields(model, geometry, 1e3 * tol);
  if (model.gravity.norm() > 0.0)
  {
    down = model.gravity.normalized();
    gravity = model.gravity.norm();
  }
  slot.assign(model.blocks.size(), npos);
  for (std::size_t k = 0; k < geometry.blocks.size(); ++k)
    slot[geometry.blocks[k]] = k;
  tracks.resize(geometry.blocks.size());
  released.assign(geometry.blocks.size(), false);
  removed.assign(model.blocks.size(), false);
  block_reference.assign(model.blocks.size(), Vector2::Zero());
  ring_reference.assign(geometry.openings.size(), Vector2::Zero());
  rings.resize(geometry.openings.size());
  std::vector<Point> centroids;
  for (const std::vector<Point>& p : polygons)
  {
    const dda::PolygonMoments m = dda::polygon_moments(dda::anticlockwise(p));
    block_area.push_back(m.area);
    centroids.push_back(m.centroid);
  }
  for (const std::size_t b : geometry.blocks)
    keyblock_centroid.push_back(centroids[b]);
  for (std::size_t o = 0; o < geometry.openings.size(); ++o)
  {
    const OpeningOutline& opening = geometry.openings[o];
    const Point centre = 0.5 * (opening.lower + opening.upper);
    for (std::size_t b = 0; b < polygons.size(); ++b)
      if (const double d = (centroids[b] - centre).norm();
          slot[b] == npos && d >= 0.75 * opening.size() && d <= 1.5 * opening.size())
        rings[o].emplace_back(b, block_area[b]);
  }
}

std::vector<Vector2>
KeyblockRecorder::ring_displacements(const std::vector<dda::Block>& blocks) const
{
  std::vector<Vector2> mean(rings.size(), Vector2::Zero());
  for (std::size_t o = 0; o < rings.size(); ++o)
  {
    double area = 0.0;
    for (const auto& [b, a] : rings[o])
    {
      mean[o] += a * blocks[b].displacement();
      area += a;
    }
    if (area > 0.0)
      mean[o] /= area;
  }
  return mean;
}

void KeyblockRecorder::mark_removed(std::size_t block)
{
  if (block < removed.size())
    removed[block] = true;
}

std::size_t KeyblockRecorder::opening_next_to(std::size_t block, const Point& centroid) const
{
  if (block < slot.size() && slot[block] != npos)
    return geometry.opening_of[slot[block]];
  std::size_t nearest = no_opening;
  double distance = std::numeric_limits<double>::infinity();
  for (std::size_t o = 0; o < geometry.openings.size(); ++o)
    if (const double d = dda::distance_to_boundary(geometry.openings[o], centroid); d < distance)
    {
      distance = d;
      nearest = o;
    }
  return nearest;
}

void KeyblockRecorder::mark_released(std::size_t block)
{
  if (block < slot.size() && slot[block] != npos)
    released[slot[block]] = true;
}

void KeyblockRecorder::add_channels(std::vector<HistoryChannel>& channels) const
{
  for (const std::size_t b : geometry.blocks)
  {
    const std::string prefix = "keyblocks/block_" + std::to_string(b);
    const std::string which = "keyblock " + std::to_string(b) + " (the block_id of the VTU)";
    channels.push_back(
        {prefix + "/displacement", 2, "m",
         "(ux, uy) of the centroid of " + which + ", from the start of the dynamic stage"});
    channels.push_back({prefix + "/relative_displacement", 2, "m",
                        "(ux, uy) of the centroid of " + which +
                            " less the mean of the rock around its opening (0.75 to 1.5 opening "
                            "sizes from its centre), from the start of the dynamic stage"});
    channels.push_back({prefix + "/joints", 2, "m",
                        "(largest |slip|, largest opening) of the joints (bonded joints and "
                        "contacts) of " +
                            which + " in this row"});
  }
}

void KeyblockRecorder::append_row(const dda::System& system, std::vector<double>& row)
{
  const std::vector<dda::Block>& blocks = system.blocks().list;
  if (!referenced)
  {
    // The dynamic stage after a static one is measured from the equilibrium reached.
    if (system.stage_mode() == dda::StageMode::dynamic)
    {
      for (std::size_t k = 0; k < tracks.size(); ++k)
        tracks[k].reference = blocks[geometry.blocks[k]].displacement();
      for (std::size_t b = 0; b < blocks.size(); ++b)
        block_reference[b] = blocks[b].displacement();
      ring_reference = ring_displacements(blocks);
    }
    referenced = true;
  }
  update_joints(system);
  std::vector<Vector2> ring = ring_displacements(blocks);
  for (std::size_t o = 0; o < ring.size(); ++o)
    ring[o] -= ring_reference[o];
  for (std::size_t k = 0; k < tracks.size(); ++k)
  {
    Track& t = tracks[k];
    t.last = blocks[geometry.blocks[k]].displacement() - t.reference;
    t.last_relative = t.last - ring[geometry.opening_of[k]];
    row.insert(row.end(), {t.last.x(), t.last.y(), t.last_relative.x(), t.last_relative.y(),
                           t.row_slip, t.row_opening});
    if (t.last.norm() > t.peak)
    {
      t.peak = t.last.norm();
      t.peak_time = system.time();
    }
    if (t.last_relative.norm() > t.peak_relative)
    {
      t.peak_relative = t.last_relative.norm();
      t.peak_relative_time = system.time();
    }
  }
  update_thrown_out(system);
}

void KeyblockRecorder::update_thrown_out(const dda::System& system)
{
  bool any = false;
  for (std::size_t k = 0; k < tracks.size(); ++k)
  {
    Track& t = tracks[k];
    t.thrown_out = dda::left_its_place(system.get_model().blocks[geometry.blocks[k]].vertices,
                                       t.last_relative);
    any = any || t.thrown_out;
  }
  if (!any)
    return;
  // Out of place but held (a contact, joint or bolt): lying somewhere else, not in flight.
  const std::vector<bool> held = held_keyblocks(system);
  for (std::size_t k = 0; k < tracks.size(); ++k)
    tracks[k].thrown_out = tracks[k].thrown_out && !held[k];
}

void KeyblockRecorder::update_joints(const dda::System& system)
{
  for (Track& t : tracks)
    t.row_slip = t.row_opening = 0.0;
  const auto record = [&](std::size_t block, double slip, double opening)
  {
    if (slot[block] == npos)
      return;
    Track& t = tracks[slot[block]];
    t.row_slip = std::max(t.row_slip, std::abs(slip));
    t.row_opening = std::max(t.row_opening, opening);
    t.max_slip = std::max(t.max_slip, t.row_slip);
    t.max_opening = std::max(t.max_opening, t.row_opening);
  };
  for (const dda::Contact& c : system.contacts().accepted)
  {
    // A contact opens once it has been closed; before, its gap is only a distance.
    if (c.forces.state != dda::ContactState::open)
      closed_contacts.insert(c.id);
    const double opening = closed_contacts.count(c.id) > 0 ? c.end_gap : 0.0;
    record(c.vertex_block, c.total_slip, opening);
    record(c.edge_block, c.total_slip, opening);
  }
  for (const dda::Joint& j : system.bonded_joints().list)
    for (const dda::JointPoint& p : j.points)
    {
      const Vector2 d = p.on_b.position - p.on_a.position;
      const double slip = j.tangent(small_displacement).dot(d);
      const double opening = j.normal(small_displacement).dot(d);
      record(j.block_a, slip, opening);
      record(j.block_b, slip, opening);
    }
}

nlohmann::json KeyblockRecorder::fallen_per_opening(const dda::System& system) const
{
  const std::vector<dda::Block>& blocks = system.blocks().list;
  nlohmann::json openings = nlohmann::json::array();
  std::vector<double> area(geometry.openings.size(), 0.0);
  std::vector<double> area_released(geometry.openings.size(), 0.0); // by a static stage [m^2]
  for (std::size_t o = 0; o < geometry.openings.size(); ++o)
    openings.push_back({{"fallen_blocks", nlohmann::json::array()}});
  for (std::size_t b = 0; b < blocks.size(); ++b)
  {
    const Point& c = blocks[b].moments.centroid;
    const std::size_t o = opening_next_to(b, c);
    if (o == no_opening)
      continue;
    const OpeningOutline& opening = geometry.openings[o];
    const bool near = slot[b] != npos || dda::distance_to_boundary(opening, c) <= opening.size();
    const bool fell = removed[b] || (blocks[b].displacement() - block_reference[b]).dot(down) >
                                        criterion.fall_fraction * opening.size();
    if (!near || !fell)
      continue;
    openings[o]["fallen_blocks"].push_back(b);
    area[o] += block_area[b];
    if (slot[b] != npos && released[slot[b]])
      area_released[o] += block_area[b];
  }
  for (std::size_t o = 0; o < area.size(); ++o)
  {
    openings[o]["fallen_area_m2"] = area[o];
    openings[o]["released_area_m2"] = area_released[o];
  }
  return openings;
}

std::vector<bool> KeyblockRecorder::held_keyblocks(const dda::System& system) const
{
  std::vector<bool> held(tracks.size(), false);
  const auto hold = [&](std::size_t block)
  {
    if (slot[block] != npos)
      held[slot[block]] = true;
  };
  for (const dda::Contact& c : system.contacts().accepted)
    if (c.forces.state != dda::ContactState::open)
    {
      hold(c.vertex_block);
      hold(c.edge_block);
    }
  for (const dda::Joint& j : system.bonded_joints().list)
  {
    hold(j.block_a);
    hold(j.block_b);
  }
  for (const std::unique_ptr<dda::ElementKind>& k : system.get_element_kinds())
    k->add_held_blocks(hold);
  return held;
}

std::optional<std::size_t> KeyblockRecorder::first_fallen() const
{
  // Not a block merely detached and beyond the fall threshold in one row: it may be hopping and
  // land back (a floor block the wave throws up); the verdict at the end judges it.
  for (std::size_t k = 0; k < tracks.size(); ++k)
  {
    const double size = geometry.openings[geometry.opening_of[k]].size();
    if (!released[k] &&
        (tracks[k].last.dot(down) > criterion.fall_fraction * size || tracks[k].thrown_out))
      return geometry.blocks[k];
  }
  return std::nullopt;
}

nlohmann::json KeyblockRecorder::keyblock_summary(std::size_t k, const dda::System& system,
                                                  bool held) const
{
  const std::size_t id = geometry.blocks[k];
  const Track& t = tracks[k];
  const Vector2 v = system.blocks().list[id].velocity.head<2>();
  const double size = geometry.openings[geometry.opening_of[k]].size();
  const dda::FallVerdict verdict = dda::keyblock_fell({t.last, t.last_relative, v, held}, down,
                                                      criterion.fall_fraction * size, gravity);
  const bool fell = verdict != dda::FallVerdict::no;
  // Where it is on the opening's perimeter: the angle of its centroid about the centre of the
  // opening's bounding box, from straight up (against gravity) and clockwise, in [0, 360).
  const OpeningOutline& opening = geometry.openings[geometry.opening_of[k]];
  const Vector2 from_centre = keyblock_centroid[k] - 0.5 * (opening.lower + opening.upper);
  const Vector2 up = -down, right(up.y(), -up.x());
  const double angle = std::atan2(from_centre.dot(right), from_centre.dot(up)) * 180.0 / M_PI;
  return {{"id", id},
          {"name", system.get_model().blocks[id].origin},
          {"opening", geometry.opening_of[k]},
          {"centroid_m", {keyblock_centroid[k].x(), keyblock_centroid[k].y()}},
          {"angle_deg", angle < 0.0 ? angle + 360.0 : angle},
          {"peak_displacement_m", t.peak},
          {"peak_time_s", t.peak_time},
          {"residual_displacement_m", {t.last.x(), t.last.y()}},
          {"residual_m", t.last.norm()},
          {"peak_relative_m", t.peak_relative},
          {"peak_relative_time_s", t.peak_relative_time},
          {"residual_relative_displacement_m", {t.last_relative.x(), t.last_relative.y()}},
          {"residual_relative_m", t.last_relative.norm()},
          {"final_velocity_m_s", {v.x(), v.y()}},
          {"max_slip_m", t.max_slip},
          {"max_opening_m", t.max_opening},
          {"detached", !held},
          {"fell", fell},
          {"fall", name_of(verdict)},
          {"loosened", !fell && t.last_relative.norm() > criterion.loosen_fraction * size},
          {"released", static_cast<bool>(released[k])},
          {"yield_acceleration",
           {{"horizontal", yield_json(yields[k].horizontal)},
            {"vertical", yield_json(yields[k].vertical)}}}};
}

nlohmann::json KeyblockRecorder::summary(const dda::System& system) const
{
  if (empty())
    return nullptr;
  nlohmann::json openings = fallen_per_opening(system);
  for (std::size_t k = 0; k < geometry.openings.size(); ++k)
  {
    const OpeningOutline& o = geometry.openings[k];
    const double threshold = criterion.fall_fraction * o.size();
    openings[k].update({{"size_m", o.size()},
                        {"area_m2", o.area},
                        {"lower_m", {o.lower.x(), o.lower.y()}},
                        {"upper_m", {o.upper.x(), o.upper.y()}},
                        {"fall_threshold_m", threshold},
                        {"fall_speed_m_s", std::sqrt(2.0 * gravity * threshold)},
                        {"loosen_threshold_m", criterion.loosen_fraction * o.size()},
                        {"ring_blocks", rings[k].size()}});
  }
  const std::vector<bool> held = held_keyblocks(system);
  nlohmann::json blocks = nlohmann::json::array();
  std::size_t n_detached = 0, n_fell = 0, n_loosened = 0, n_released = 0;
  std::size_t peak_block = geometry.blocks.front(), peak_relative_block = peak_block;
  double peak = -1.0, peak_relative = -1.0;
  for (std::size_t k = 0; k < tracks.size(); ++k)
  {
    blocks.push_back(keyblock_summary(k, system, held[k]));
    const nlohmann::json& b = blocks.back();
    n_detached += b["detached"].get<bool>() ? 1 : 0;
    n_fell += b["fell"].get<bool>() ? 1 : 0;
    n_loosened += b["loosened"].get<bool>() ? 1 : 0;
    n_released += released[k] ? 1 : 0;
    if (tracks[k].peak > peak)
    {
      peak = tracks[k].peak;
      peak_block = geometry.blocks[k];
    }
    if (tracks[k].peak_relative > peak_relative)
    {
      peak_relative = tracks[k].peak_relative;
      peak_relative_block = geometry.blocks[k];
    }
  }
  return {{"count", tracks.size()},
          {"fall_fraction_of_opening", criterion.fall_fraction},
          {"loosen_fraction_of_opening", criterion.loosen_fraction},
          {"openings", openings},
          {"blocks", blocks},
          {"keyblock_peak_m", peak},
          {"keyblock_peak_id", peak_block},
          {"keyblock_peak_relative_m", peak_relative},
          {"keyblock_peak_relative_id", peak_relative_block},
          {"detached", n_detached},
          {"fell", n_fell},
          {"loosened", n_loosened},
          {"released", n_released}};
}

} // namespace ddafem
