// Contact detection: phases 1 and 2 of a step (broad phase, narrow phase with the vertices that
// intact joints tie, the contacts' frames).
#include "dda/contact/contact_set.h"

#include "dda/contact/broad_phase.h"
#include "dda/step_equations.h"
#include "dda/submatrices.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace ddafem::dda
{
namespace
{
/// Length [m] over which the leg of `poly` at `vertex` that runs parallel to `edge` overlaps it,
/// halved (each end of an edge-to-edge contact carries half); 0 if no leg is parallel within the
/// angle tolerance (`sin_tolerance` its sine).
double carried_length(const std::vector<Point>& poly, std::size_t vertex, const PolygonEdge& edge,
                      double sin_tolerance)
{
  const std::size_t n = poly.size();
  const Point& v = poly[vertex];
  const Point& e0 = edge.start;
  const double edge_length = edge.length;
  const Vector2& t = edge.tangent;
  double best = 0.0;
  for (const Point& w : {poly[(vertex + 1) % n], poly[(vertex + n - 1) % n]})
  {
    const Vector2 leg = w - v;
    if (std::abs(t.x() * leg.y() - t.y() * leg.x()) > sin_tolerance * leg.norm())
      continue;
    const double s0 = t.dot(v - e0), s1 = t.dot(w - e0);
    const double overlap =
        std::min(std::max(s0, s1), edge_length) - std::max(std::min(s0, s1), 0.0);
    best = std::max(best, 0.5 * std::max(overlap, 0.0));
  }
  return best;
}
} // namespace

ContactSet::BlockPairs ContactSet::candidates(const std::vector<Block>& blocks) const
{
  std::vector<BoundingBox> boxes;
  boxes.reserve(blocks.size());
  for (const Block& b : blocks)
    boxes.push_back(bounding_box(b.vertices, 0.5 * distances.search_distance));
  return overlapping_pairs(boxes);
}

ContactSet::BlockPairs ContactSet::detect(const DetectionInput& in, const BlockPairs& pairs,
                                          const Parallel& parallel)
{
  mark_jointed_vertices(in);
  BlockPairs touching = find_trial_contacts(in, pairs, parallel);
  detected.predecessors.clear();
  detected.epoch = geometry_epoch;
  return touching;
}

void ContactSet::refresh_exclusions(const DetectionInput& in)
{
  if (exclusions.revision == in.joint_revision)
    return;
  exclusions.revision = in.joint_revision;
  exclusions.bonded_pairs.clear();
  exclusions.candidates.clear();
  for (std::size_t k = 0; k < in.joints.size(); ++k)
  {
    const Joint& j = in.joints[k];
    if (convex[j.block_a] && convex[j.block_b])
      exclusions.bonded_pairs.emplace_back(j.block_a, j.block_b);
    const auto add = [&](std::size_t block, std::size_t edge, std::size_t other)
    {
      const std::size_t n = in.blocks[block].vertices.size();
      for (const std::size_t v : {edge, (edge + 1) % n})
        exclusions.candidates.push_back({block, v, other, k});
    };
    add(j.block_a, j.edge_a, j.block_b);
    add(j.block_b, j.edge_b, j.block_a);
  }
  std::sort(exclusions.bonded_pairs.begin(), exclusions.bonded_pairs.end());
  std::stable_sort(
      exclusions.candidates.begin(), exclusions.candidates.end(),
      [](const auto& x, const auto& y)
      { return std::tie(x.block, x.vertex, x.other) < std::tie(y.block, y.vertex, y.other); });
}

void ContactSet::mark_jointed_vertices(const DetectionInput& in)
{
  // Vertices tied by an intact bonded joint to the other block do not make contacts there. In a
  // static stage which vertices those are is decided in the initial configuration: in the
  // current one the joint's shear displacement (forces / springs, 1e-5 m under MN in-situ
  // forces) can carry an end vertex in and out of the tolerance from step to step, and the
  // contact it then makes came and went every other step (a 2-cycle that never reached
  // equilibrium). A dynamic stage follows the current configuration: a vertex that has left the
  // joint's end meets the other block through a contact.
  refresh_exclusions(in);
  const bool initial = in.initial_configuration;
  // Each joint's start p, unit tangent t and length along a's edge [m].
  joint_frames.resize(in.joints.size());
  for (std::size_t k = 0; k < in.joints.size(); ++k)
  {
    const Joint& j = in.joints[k];
    const Point& p = initial ? j.points[0].on_a.initial : j.points[0].on_a.position;
    const double length =
        ((initial ? j.points[1].on_a.initial : j.points[1].on_a.position) - p).norm();
    joint_frames[k] = {p, j.tangent(initial), length};
  }
  // A vertex within tol of the joint's stretch along it is tied (the candidates are sorted).
  jointed_vertices.clear();
  const double tol = 1e-6 * distances.w0;
  for (const JointExclusions::Candidate& c : exclusions.candidates)
  {
    const JointFrame& f = joint_frames[c.joint];
    const std::vector<Point>& v =
        initial ? in.blocks[c.block].initial_vertices : in.blocks[c.block].vertices;
    const double s = f.tangent.dot(v[c.vertex] - f.start);
    if (s > -tol && s < f.length + tol)
      jointed_vertices.emplace_back(c.block, c.vertex, c.other);
  }
}

bool ContactSet::jointed(std::size_t block, std::size_t vertex, std::size_t other) const
{
  return std::binary_search(jointed_vertices.begin(), jointed_vertices.end(),
                            std::make_tuple(block, vertex, other));
}

bool ContactSet::held_by_common_block(std::size_t a, std::size_t va, std::size_t b,
                                      std::size_t vb) const
{
  // The blocks vertex va of a is tied to: a range of the sorted list.
  auto it = std::lower_bound(jointed_vertices.begin(), jointed_vertices.end(),
                             std::make_tuple(a, va, std::size_t{0}));
  for (; it != jointed_vertices.end() && std::get<0>(*it) == a && std::get<1>(*it) == va; ++it)
    if (jointed(b, vb, std::get<2>(*it)))
      return true;
  return false;
}

ContactSet::BlockPairs ContactSet::find_trial_contacts(const DetectionInput& in,
                                                       const BlockPairs& pairs,
                                                       const Parallel& parallel)
{
  // Two convex blocks held by an intact joint touch only along it (their other vertices lie
  // more than d0 < a quarter of the shortest edge away): no narrow phase for exclusions'
  // bonded_pairs, nor features for blocks in no other pair (a bonded model's step computes
  // none). Each chunk of pairs lists its contacts apart; the lists are joined in chunk order, so
  // the result does not depend on the number of threads. A chunk is ~0.2 ms of work (a model
  // of fewer pairs stays on one thread: a parallel region costs tens of microseconds).
  const std::vector<Block>& blocks = in.blocks;
  narrow_pairs.clear();
  needs_features.assign(blocks.size(), 0);
  for (const auto& pair : pairs)
    if (!std::binary_search(exclusions.bonded_pairs.begin(), exclusions.bonded_pairs.end(), pair))
    {
      narrow_pairs.push_back(pair);
      needs_features[pair.first] = needs_features[pair.second] = 1;
    }
  block_features.resize(blocks.size());
  parallel.for_chunks(blocks.size(), 128,
                      [&](std::size_t begin, std::size_t end)
                      {
                        for (std::size_t k = begin; k < end; ++k)
                          if (needs_features[k])
                            compute_polygon_features(blocks[k].vertices, distances.angle_tolerance,
                                                     block_features[k]);
                      });
  constexpr std::size_t grain = 256;
  const std::size_t n_chunks = (narrow_pairs.size() + grain - 1) / grain;
  if (narrow_chunks.size() < n_chunks)
    narrow_chunks.resize(n_chunks);
  parallel.for_chunks(narrow_pairs.size(), grain,
                      [&](std::size_t begin, std::size_t end)
                      {
                        NarrowPhaseChunk& chunk = narrow_chunks[begin / grain];
                        chunk.found.clear();
                        for (std::size_t k = begin; k < end; ++k)
                          add_pair_contacts(in, narrow_pairs[k].first, narrow_pairs[k].second,
                                            chunk);
                      });
  // Sorted by key (unique: each pair is listed once and its contacts differ in vertex or
  // edge): counted into buckets by vertex block, then each bucket (a few contacts) by
  // insertion, through pointers that are cheaper to move than the contacts.
  std::vector<std::size_t> bucket(blocks.size() + 1, 0);
  for (std::size_t k = 0; k < n_chunks; ++k)
    for (const Contact& c : narrow_chunks[k].found)
      ++bucket[c.vertex_block + 1];
  for (std::size_t i = 0; i < blocks.size(); ++i)
    bucket[i + 1] += bucket[i];
  std::vector<const Contact*> order(bucket.back());
  std::vector<std::size_t> next(bucket.begin(), bucket.end() - 1);
  for (std::size_t k = 0; k < n_chunks; ++k)
    for (const Contact& c : narrow_chunks[k].found)
      order[next[c.vertex_block]++] = &c;
  for (std::size_t i = 0; i < blocks.size(); ++i)
    for (std::size_t k = bucket[i] + 1; k < bucket[i + 1]; ++k)
      for (std::size_t m = k; m > bucket[i] && order[m]->key() < order[m - 1]->key(); --m)
        std::swap(order[m], order[m - 1]);
  std::vector<Contact>& found = detected.contacts;
  found.resize(order.size());
  parallel.for_chunks(order.size(), 1024,
                      [&](std::size_t begin, std::size_t end)
                      {
                        for (std::size_t k = begin; k < end; ++k)
                          found[k] = *order[k];
                      });

  // The pairs with contacts: the chunks list them in the candidates' (lexicographic) order.
  BlockPairs touching;
  for (std::size_t k = 0; k < n_chunks; ++k)
    for (const Contact& c : narrow_chunks[k].found)
    {
      const std::pair<std::size_t, std::size_t> pair(std::min(c.vertex_block, c.edge_block),
                                                     std::max(c.vertex_block, c.edge_block));
      if (touching.empty() || touching.back() != pair)
        touching.emplace_back(pair);
    }
  return touching;
}

void ContactSet::add_pair_contacts(const DetectionInput& in, std::size_t a, std::size_t b,
                                   NarrowPhaseChunk& chunk) const
{
  const std::vector<Block>& blocks = in.blocks;
  find_vertex_edge_pairs(block_features[a], block_features[b], distances.search_distance,
                         chunk.work);
  for (const VertexEdgePair& f : chunk.work.pairs)
  {
    Contact c;
    c.vertex_block = f.vertex_polygon == 0 ? a : b;
    c.edge_block = f.vertex_polygon == 0 ? b : a;
    if (jointed(c.vertex_block, f.vertex, c.edge_block))
      continue;
    // Corners of diagonal neighbours (four blocks meeting at a point of a jointed grid): when
    // both corners are held by intact joints to a common third block, that block keeps them
    // apart and the vertex-vertex contact between them would only flip between states at
    // rounding-level gaps, costing open-close iterations.
    if (f.kind == ContactKind::vertex_vertex)
    {
      const std::vector<Point>& ev = blocks[c.edge_block].vertices;
      const std::size_t corner = f.ratio < 0.5 ? f.edge : (f.edge + 1) % ev.size();
      if (held_by_common_block(c.vertex_block, f.vertex, c.edge_block, corner))
        continue;
    }
    c.vertex = f.vertex;
    c.edge = f.edge;
    c.kind = f.kind;
    c.ratio = f.ratio;
    c.gap = f.distance;
    c.joint_material = joint_material_at_edge(*model, c.edge_block, c.edge, c.vertex_block);
    c.length =
        carried_length(blocks[c.vertex_block].vertices, c.vertex,
                       block_features[c.edge_block].edges[c.edge], distances.sin_angle_tolerance);
    chunk.found.push_back(c);
  }
}

void ContactSet::set_frames(const std::vector<Block>& blocks, const StepEquations& equations,
                            const Parallel& parallel)
{
  // Each contact's coupling and frame, in the configuration at the step start.
  frames.resize(detected.contacts.size());
  parallel.for_chunks(
      detected.contacts.size(), 1024,
      [&](std::size_t begin, std::size_t end)
      {
        for (std::size_t k = begin; k < end; ++k)
        {
          Contact& c = detected.contacts[k];
          c.coupling = equations.coupling_of(c.vertex_block, c.edge_block);
          const Block& vb = blocks[c.vertex_block];
          const Block& eb = blocks[c.edge_block];
          const Point& e0 = eb.vertices[c.edge];
          const Point& e1 = eb.vertices[(c.edge + 1) % eb.vertices.size()];
          ContactFrame& f = frames[k];
          const PolygonEdge& edge = block_features[c.edge_block].edges[c.edge]; // this detection
          f.tangent = edge.tangent;
          f.normal = edge.normal;
          f.t_vertex = displacement_matrix(vb.moments.centroid, vb.vertices[c.vertex]);
          f.t_edge = displacement_matrix(eb.moments.centroid, e0 + c.ratio * (e1 - e0));
        }
      });
}
} // namespace ddafem::dda
