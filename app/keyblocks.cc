#include "app/keyblocks.h"

#include "dda/contact/broad_phase.h"
#include "dda/geometry.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <limits>
#include <numeric>
#include <string>

namespace ddafem
{
namespace
{
using dda::Point;
using dda::Vector2;
constexpr std::size_t npos = std::numeric_limits<std::size_t>::max();

/// A piece of block edge that no other block shares, in the block's anticlockwise direction.
struct Piece
{
  Point from, to;
  std::size_t block;
};

/// The pieces of the blocks' edges (anticlockwise polygons) that no other block's edge runs
/// along.
std::vector<Piece> unshared_pieces(const std::vector<std::vector<Point>>& polygons, double tol)
{
  // Per block and edge: the stretches [s0, s1] (distance from the edge's start) shared.
  std::vector<std::vector<std::vector<std::pair<double, double>>>> shared(polygons.size());
  std::vector<dda::BoundingBox> boxes;
  for (std::size_t b = 0; b < polygons.size(); ++b)
  {
    shared[b].resize(polygons[b].size());
    boxes.push_back(dda::bounding_box(polygons[b], tol));
  }
  for (const auto& [i, j] : dda::overlapping_pairs(boxes))
    for (const dda::SharedSegment& s : dda::shared_segments(polygons[i], polygons[j], tol))
    {
      // p and q run along i's edge, so against j's.
      const Point& a = polygons[i][s.a_edge];
      const Point& b = polygons[j][s.b_edge];
      shared[i][s.a_edge].emplace_back((s.p - a).norm(), (s.q - a).norm());
      shared[j][s.b_edge].emplace_back((s.q - b).norm(), (s.p - b).norm());
    }

  std::vector<Piece> pieces;
  for (std::size_t b = 0; b < polygons.size(); ++b)
  {
    const std::vector<Point>& v = polygons[b];
    for (std::size_t e = 0; e < v.size(); ++e)
    {
      const Point& a = v[e];
      const Vector2 edge = v[(e + 1) % v.size()] - a;
      const double length = edge.norm();
      const Vector2 t = edge / length;
      std::vector<std::pair<double, double>>& stretches = shared[b][e];
      std::sort(stretches.begin(), stretches.end());
      double covered = 0.0; // the edge is shared from its start up to here
      stretches.emplace_back(length, length);
      for (const auto& [s0, s1] : stretches)
      {
        if (s0 - covered > tol)
          pieces.push_back({a + covered * t, a + s0 * t, b});
        covered = std::max(covered, s1);
      }
    }
  }
  return pieces;
}

/// Groups the pieces into connected loops (pieces meeting at an end within tol); returns each
/// piece's loop number and the number of loops.
std::pair<std::vector<std::size_t>, std::size_t> loops_of(const std::vector<Piece>& pieces,
                                                          double tol)
{
  std::vector<std::size_t> parent(pieces.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](std::size_t k)
  {
    while (parent[k] != k)
      k = parent[k] = parent[parent[k]];
    return k;
  };
  // Ends sorted by x: each is compared only with those within tol in x.
  std::vector<std::pair<Point, std::size_t>> ends;
  for (std::size_t k = 0; k < pieces.size(); ++k)
  {
    ends.emplace_back(pieces[k].from, k);
    ends.emplace_back(pieces[k].to, k);
  }
  std::sort(ends.begin(), ends.end(),
            [](const auto& a, const auto& b) { return a.first.x() < b.first.x(); });
  for (std::size_t i = 0; i < ends.size(); ++i)
    for (std::size_t j = i + 1; j < ends.size() && ends[j].first.x() - ends[i].first.x() <= tol;
         ++j)
      if ((ends[j].first - ends[i].first).norm() <= tol)
        parent[root(ends[i].second)] = root(ends[j].second);

  std::vector<std::size_t> loop(pieces.size(), npos), number(pieces.size(), npos);
  std::size_t n_loops = 0;
  for (std::size_t k = 0; k < pieces.size(); ++k)
  {
    const std::size_t r = root(k);
    if (number[r] == npos)
      number[r] = n_loops++;
    loop[k] = number[r];
  }
  return {loop, n_loops};
}

/// Distance from p to the segment [a, b].
double distance_to_segment(const Point& p, const Point& a, const Point& b)
{
  const Vector2 ab = b - a;
  const double s = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + s * ab)).norm();
}

bool boxes_overlap(const OpeningOutline& o, const dda::BoundingBox& b)
{
  return b.x_min <= o.upper.x() && b.x_max >= o.lower.x() && b.y_min <= o.upper.y() &&
         b.y_max >= o.lower.y();
}
} // namespace

KeyblockGeometry find_keyblocks(const std::vector<std::vector<Point>>& blocks, double tol)
{
  std::vector<std::vector<Point>> polygons = blocks;
  for (std::vector<Point>& p : polygons)
    if (dda::signed_area(p) < 0.0)
      std::reverse(p.begin(), p.end());
  const std::vector<Piece> pieces = unshared_pieces(polygons, tol);
  const auto [loop, n_loops] = loops_of(pieces, tol);

  // Each loop's area by the shoelace formula over its directed pieces (no need to chain them),
  // about a common origin against cancellation: outer boundaries are anticlockwise (> 0).
  const Point origin = pieces.empty() ? Point::Zero() : pieces.front().from;
  std::vector<OpeningOutline> loops(n_loops);
  std::vector<bool> started(n_loops, false);
  for (std::size_t k = 0; k < pieces.size(); ++k)
  {
    OpeningOutline& o = loops[loop[k]];
    const Piece& p = pieces[k];
    o.segments.emplace_back(p.from, p.to);
    const Vector2 a = p.from - origin, b = p.to - origin;
    o.area -= 0.5 * (a.x() * b.y() - a.y() * b.x()); // clockwise: a hole's area > 0
    o.lower = started[loop[k]] ? o.lower.cwiseMin(p.from) : p.from;
    o.upper = started[loop[k]] ? o.upper.cwiseMax(p.from) : p.from;
    started[loop[k]] = true;
  }
  // The holes: clockwise loops wider than round-off (2 area / perimeter, half the width of a
  // strip, above 1000 tol: not a gap between edges that miss each other by a little more than
  // tol).
  KeyblockGeometry g;
  for (const OpeningOutline& o : loops)
  {
    double perimeter = 0.0;
    for (const auto& [from, to] : o.segments)
      perimeter += (to - from).norm();
    if (2.0 * o.area > 1e3 * tol * perimeter)
      g.openings.push_back(o);
  }
  std::sort(g.openings.begin(), g.openings.end(),
            [](const OpeningOutline& a, const OpeningOutline& b) {
              return std::make_pair(a.lower.y(), a.lower.x()) <
                     std::make_pair(b.lower.y(), b.lower.x());
            });

  // Keyblocks: blocks with a point of their boundary on an opening's (the blocks do not
  // overlap, so edges that do not cross are within tol where an end of one is).
  for (std::size_t b = 0; b < polygons.size(); ++b)
  {
    const std::vector<Point>& v = polygons[b];
    const dda::BoundingBox box = dda::bounding_box(v, tol);
    std::size_t found = npos;
    for (std::size_t o = 0; o < g.openings.size() && found == npos; ++o)
    {
      if (!boxes_overlap(g.openings[o], box))
        continue;
      for (std::size_t e = 0; e < v.size() && found == npos; ++e)
      {
        const Point& p = v[e];
        const Point& q = v[(e + 1) % v.size()];
        for (const auto& [from, to] : g.openings[o].segments)
          if (std::min({distance_to_segment(p, from, to), distance_to_segment(q, from, to),
                        distance_to_segment(from, p, q), distance_to_segment(to, p, q)}) <= tol)
            found = o;
      }
    }
    if (found != npos)
    {
      g.blocks.push_back(b);
      g.opening_of.push_back(found);
    }
  }
  return g;
}

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
  geometry = find_keyblocks(polygons, 1e-9 * (upper - lower).maxCoeff());
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
    for (const auto& [from, to] : geometry.openings[o].segments)
      if (const double d = distance_to_segment(centroid, from, to); d < distance)
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
  const std::vector<dda::Block>& blocks = system.get_blocks();
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
  for (const dda::Contact& c : system.get_contacts())
  {
    // A contact opens once it has been closed; before, its gap is only a distance.
    if (c.forces.state != dda::ContactState::open)
      closed_contacts.insert(c.id);
    const double opening = closed_contacts.count(c.id) > 0 ? c.end_gap : 0.0;
    record(c.vertex_block, c.total_slip, opening);
    record(c.edge_block, c.total_slip, opening);
  }
  for (const dda::Joint& j : system.get_joints())
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
  const std::vector<dda::Block>& blocks = system.get_blocks();
  nlohmann::json openings = nlohmann::json::array();
  std::vector<double> area(geometry.openings.size(), 0.0);
  for (std::size_t o = 0; o < geometry.openings.size(); ++o)
    openings.push_back({{"fallen_blocks", nlohmann::json::array()}});
  for (std::size_t b = 0; b < blocks.size(); ++b)
  {
    const Point& c = blocks[b].moments.centroid;
    const std::size_t o = opening_next_to(b, c);
    if (o == no_opening)
      continue;
    const OpeningOutline& opening = geometry.openings[o];
    double distance = std::numeric_limits<double>::infinity();
    for (const auto& [from, to] : opening.segments)
      distance = std::min(distance, distance_to_segment(c, from, to));
    const bool near = slot[b] != npos || distance <= opening.size();
    const bool fell = removed[b] || (blocks[b].displacement() - block_reference[b]).dot(down) >
                                        criterion.fall_fraction * opening.size();
    if (!near || !fell)
      continue;
    openings[o]["fallen_blocks"].push_back(b);
    area[o] += block_area[b];
  }
  for (std::size_t o = 0; o < area.size(); ++o)
    openings[o]["fallen_area_m2"] = area[o];
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
  for (const dda::Contact& c : system.get_contacts())
    if (c.forces.state != dda::ContactState::open)
    {
      hold(c.vertex_block);
      hold(c.edge_block);
    }
  for (const dda::Joint& j : system.get_joints())
  {
    hold(j.block_a);
    hold(j.block_b);
  }
  return held;
}

nlohmann::json KeyblockRecorder::keyblock_summary(std::size_t k, const dda::System& system,
                                                  bool held) const
{
  const std::size_t id = geometry.blocks[k];
  const Track& t = tracks[k];
  const Vector2 v = system.get_blocks()[id].velocity.head<2>();
  const double size = geometry.openings[geometry.opening_of[k]].size();
  const double threshold = criterion.fall_fraction * size;
  const bool fell =
      t.last.dot(down) > threshold || (!held && v.dot(down) > std::sqrt(2.0 * gravity * threshold));
  return {{"id", id},
          {"name", system.get_model().blocks[id].origin},
          {"opening", geometry.opening_of[k]},
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
          {"loosened", !fell && t.last_relative.norm() > criterion.loosen_fraction * size},
          {"released", static_cast<bool>(released[k])}};
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
