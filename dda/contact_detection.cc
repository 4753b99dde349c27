#include "dda/system.h"

#include "dda/contact/broad_phase.h"
#include "dda/submatrices.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

// Contact detection of System: phases 1 and 2 of a step (broad phase, narrow phase, contacts
// matched to the previous step's) and the matrix structure they give.

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

std::vector<std::pair<std::size_t, std::size_t>> System::find_contact_candidates() const
{
  std::vector<BoundingBox> boxes;
  boxes.reserve(blocks.size());
  for (const Block& b : blocks)
    boxes.push_back(bounding_box(b.vertices, 0.5 * contact_set.distances.search_distance));
  return overlapping_pairs(boxes);
}

void System::update_contacts(const std::vector<std::pair<std::size_t, std::size_t>>& pairs)
{
  mark_jointed_vertices();
  set_contact_structure(find_trial_contacts(pairs));
  contact_set.detected.predecessors.clear();
  contact_set.detected.epoch = contact_set.geometry_epoch;
  contact_set.inherit(parallel, contact_set.distances.w0);
}

void System::refresh_joint_lists()
{
  if (joint_lists.revision == joint_revision)
    return;
  joint_lists.revision = joint_revision;
  joint_lists.bonded_pairs.clear();
  joint_lists.joined.clear();
  joint_lists.candidates.clear();
  for (std::size_t k = 0; k < joints.size(); ++k)
  {
    const Joint& j = joints[k];
    joint_lists.joined.emplace_back(j.block_a, j.block_b);
    if (contact_set.convex[j.block_a] && contact_set.convex[j.block_b])
      joint_lists.bonded_pairs.emplace_back(j.block_a, j.block_b);
    const auto add = [&](std::size_t block, std::size_t edge, std::size_t other)
    {
      const std::size_t n = blocks[block].vertices.size();
      for (const std::size_t v : {edge, (edge + 1) % n})
        joint_lists.candidates.push_back({block, v, other, k});
    };
    add(j.block_a, j.edge_a, j.block_b);
    add(j.block_b, j.edge_b, j.block_a);
  }
  // An element between two blocks (a bolt, a frame) couples them in the matrix like a joint
  // (not in contact detection).
  for (const std::unique_ptr<ElementKind>& k : element_kinds)
    k->add_couplings(joint_lists.joined);
  std::sort(joint_lists.bonded_pairs.begin(), joint_lists.bonded_pairs.end());
  std::sort(joint_lists.joined.begin(), joint_lists.joined.end());
  std::stable_sort(
      joint_lists.candidates.begin(), joint_lists.candidates.end(),
      [](const auto& x, const auto& y)
      { return std::tie(x.block, x.vertex, x.other) < std::tie(y.block, y.vertex, y.other); });
}

void System::mark_jointed_vertices()
{
  // Vertices tied by an intact bonded joint to the other block do not make contacts there. In a
  // static stage which vertices those are is decided in the initial configuration: in the
  // current one the joint's shear displacement (forces / springs, 1e-5 m under MN in-situ
  // forces) can carry an end vertex in and out of the tolerance from step to step, and the
  // contact it then makes came and went every other step (a 2-cycle that never reached
  // equilibrium). A dynamic stage follows the current configuration: a vertex that has left the
  // joint's end meets the other block through a contact.
  refresh_joint_lists();
  const bool initial = mode == StageMode::static_equilibrium;
  // Each joint's start p, unit tangent t and length along a's edge [m].
  joint_frames.resize(joints.size());
  for (std::size_t k = 0; k < joints.size(); ++k)
  {
    const Joint& j = joints[k];
    const Point& p = initial ? j.points[0].on_a.initial : j.points[0].on_a.position;
    const double length =
        ((initial ? j.points[1].on_a.initial : j.points[1].on_a.position) - p).norm();
    joint_frames[k] = {p, j.tangent(initial), length};
  }
  // A vertex within tol of the joint's stretch along it is tied (the candidates are sorted).
  jointed_vertices.clear();
  const double tol = 1e-6 * contact_set.distances.w0;
  for (const JointLists::Candidate& c : joint_lists.candidates)
  {
    const JointFrame& f = joint_frames[c.joint];
    const std::vector<Point>& v =
        initial ? blocks[c.block].initial_vertices : blocks[c.block].vertices;
    const double s = f.tangent.dot(v[c.vertex] - f.start);
    if (s > -tol && s < f.length + tol)
      jointed_vertices.emplace_back(c.block, c.vertex, c.other);
  }
}

bool System::jointed(std::size_t block, std::size_t vertex, std::size_t other) const
{
  return std::binary_search(jointed_vertices.begin(), jointed_vertices.end(),
                            std::make_tuple(block, vertex, other));
}

bool System::held_by_common_block(std::size_t a, std::size_t va, std::size_t b,
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

std::vector<std::pair<std::size_t, std::size_t>>
System::find_trial_contacts(const std::vector<std::pair<std::size_t, std::size_t>>& pairs)
{
  // Two convex blocks held by an intact joint touch only along it (their other vertices lie
  // more than d0 away, d0 being below a quarter of the shortest edge): no narrow phase for the
  // pairs of joint_lists.bonded_pairs (update_contacts refreshed the lists), nor features for
  // blocks in no other pair (a bonded model's step computes none).
  // Each chunk of pairs lists its contacts apart; the lists are joined in chunk order, so the
  // result does not depend on the number of threads. A chunk is ~0.2 ms of work (a model of
  // fewer pairs stays on one thread: a parallel region costs tens of microseconds).
  narrow_pairs.clear();
  needs_features.assign(blocks.size(), 0);
  for (const auto& pair : pairs)
    if (!std::binary_search(joint_lists.bonded_pairs.begin(), joint_lists.bonded_pairs.end(), pair))
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
                            compute_polygon_features(blocks[k].vertices,
                                                     contact_set.distances.angle_tolerance,
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
                          add_pair_contacts(narrow_pairs[k].first, narrow_pairs[k].second, chunk);
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
  std::vector<Contact>& found = contact_set.detected.contacts;
  found.resize(order.size());
  parallel.for_chunks(order.size(), 1024,
                      [&](std::size_t begin, std::size_t end)
                      {
                        for (std::size_t k = begin; k < end; ++k)
                          found[k] = *order[k];
                      });

  // The pairs with contacts: the chunks list them in the candidates' (lexicographic) order.
  std::vector<std::pair<std::size_t, std::size_t>> touching;
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

void System::add_pair_contacts(std::size_t a, std::size_t b, NarrowPhaseChunk& chunk) const
{
  find_vertex_edge_pairs(block_features[a], block_features[b],
                         contact_set.distances.search_distance, chunk.work);
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
    c.joint_material = joint_material_at_edge(model, c.edge_block, c.edge, c.vertex_block);
    c.length = carried_length(blocks[c.vertex_block].vertices, c.vertex,
                              block_features[c.edge_block].edges[c.edge],
                              contact_set.distances.sin_angle_tolerance);
    chunk.found.push_back(c);
  }
}

void System::set_contact_structure(std::vector<std::pair<std::size_t, std::size_t>> touching)
{
  // The matrix couples joined blocks and blocks in contact (both lists sorted: merged).
  const std::vector<std::pair<std::size_t, std::size_t>>& joined = joint_lists.joined;
  std::vector<std::pair<std::size_t, std::size_t>> couplings(joined.size() + touching.size());
  std::merge(joined.begin(), joined.end(), touching.begin(), touching.end(), couplings.begin());
  set_matrix_structure(std::move(couplings));

  // Each contact's coupling and frame, in the configuration at the step start.
  frames.resize(contact_set.detected.contacts.size());
  parallel.for_chunks(contact_set.detected.contacts.size(), 1024,
                      [&](std::size_t begin, std::size_t end)
                      {
                        for (std::size_t k = begin; k < end; ++k)
                          set_contact_frame(k);
                      });
}

void System::set_contact_frame(std::size_t k)
{
  Contact& c = contact_set.detected.contacts[k];
  c.coupling = coupling_of(c.vertex_block, c.edge_block);
  const Block& vb = blocks[c.vertex_block];
  const Block& eb = blocks[c.edge_block];
  const Point& e0 = eb.vertices[c.edge];
  const Point& e1 = eb.vertices[(c.edge + 1) % eb.vertices.size()];
  ContactFrame& f = frames[k];
  const PolygonEdge& edge = block_features[c.edge_block].edges[c.edge]; // of this detection
  f.tangent = edge.tangent;
  f.normal = edge.normal;
  f.t_vertex = displacement_matrix(vb.moments.centroid, vb.vertices[c.vertex]);
  f.t_edge = displacement_matrix(eb.moments.centroid, e0 + c.ratio * (e1 - e0));
}

void System::set_matrix_structure(std::vector<std::pair<std::size_t, std::size_t>> couplings)
{
  // The tied body couples every pair of blocks with tie points (its condensed stiffness is
  // dense over them): those pairs, sorted by construction (tie_blocks is), merged into the
  // contacts' sorted couplings in one pass (a sort of both took 2.5 % of a tunnel's run).
  std::vector<std::pair<std::size_t, std::size_t>> tied_block_pairs;
  tied_block_pairs.reserve(tie_blocks.size() * tie_blocks.size() / 2);
  for (std::size_t i = 0; i < tie_blocks.size(); ++i)
    for (std::size_t j = i + 1; j < tie_blocks.size(); ++j)
      tied_block_pairs.emplace_back(tie_blocks[i], tie_blocks[j]);
  if (!std::is_sorted(couplings.begin(), couplings.end()))
    std::sort(couplings.begin(), couplings.end());
  if (!tied_block_pairs.empty())
  {
    std::vector<std::pair<std::size_t, std::size_t>> merged(couplings.size() +
                                                            tied_block_pairs.size());
    std::merge(couplings.begin(), couplings.end(), tied_block_pairs.begin(), tied_block_pairs.end(),
               merged.begin());
    couplings = std::move(merged);
  }
  couplings.erase(std::unique(couplings.begin(), couplings.end()), couplings.end());
  if (couplings != coupling_pairs || matrix.n_blocks() != blocks.size())
  {
    coupling_pairs = std::move(couplings);
    matrix = BlockSparseMatrix(blocks.size(), coupling_pairs);
    coupling_rows.assign(blocks.size() + 1, 0);
    for (const auto& pair : coupling_pairs)
      ++coupling_rows[pair.first + 1];
    for (std::size_t i = 0; i < blocks.size(); ++i)
      coupling_rows[i + 1] += coupling_rows[i];
  }
  else if (joint_couplings_revision == joint_revision)
    return; // the joints' couplings are where they were
  for (Joint& j : joints)
    j.coupling = coupling_of(j.block_a, j.block_b);
  joint_couplings_revision = joint_revision;
}

std::size_t System::coupling_of(std::size_t i, std::size_t j) const
{
  // Within the couplings of the lower block (all of them lie in its row): the same index as a
  // search of all couplings, at the cost of a few comparisons.
  const auto key = std::make_pair(std::min(i, j), std::max(i, j));
  const auto row = coupling_pairs.begin();
  return static_cast<std::size_t>(
      std::lower_bound(row + coupling_rows[key.first], row + coupling_rows[key.first + 1], key) -
      row);
}

ContactCounts System::contact_counts() const
{
  ContactCounts n;
  for (const Contact& c : contact_set.accepted)
    switch (c.forces.state)
    {
    case ContactState::open:
      ++n.open;
      break;
    case ContactState::slide:
      ++n.slide;
      break;
    case ContactState::lock:
      ++n.lock;
      break;
    }
  return n;
}

std::vector<ContactSnapshot> System::contact_snapshot() const
{
  std::vector<ContactSnapshot> out;
  out.reserve(contact_set.accepted.size() + 2 * joints.size());
  for (const Contact& c : contact_set.accepted)
  {
    const std::vector<Point>& ev = blocks[c.edge_block].vertices;
    const Vector2 t = (ev[(c.edge + 1) % ev.size()] - ev[c.edge]).normalized();
    ContactSnapshot s;
    s.id = c.id;
    s.block_a = c.vertex_block;
    s.block_b = c.edge_block;
    s.state = c.forces.state == ContactState::open    ? ContactPointState::open
              : c.forces.state == ContactState::slide ? ContactPointState::slide
                                                      : ContactPointState::lock;
    s.position = blocks[c.vertex_block].vertices[c.vertex];
    s.normal = Vector2(t.y(), -t.x());
    s.normal_force = c.forces.normal_force;
    s.shear_force = c.forces.shear_force;
    s.gap = c.end_gap;
    s.slip = c.total_slip;
    out.push_back(s);
  }
  for (const Joint& j : joints)
    for (const JointPoint& p : j.points)
    {
      ContactSnapshot s;
      s.id = j.id;
      s.block_a = j.block_a;
      s.block_b = j.block_b;
      s.state = ContactPointState::bonded;
      s.position = p.on_a.position;
      s.normal = j.normal(small_displacement());
      s.normal_force = -p.normal_force;
      s.shear_force = p.shear_force;
      s.gap = s.normal.dot(p.on_b.position - p.on_a.position);
      out.push_back(s);
    }
  return out;
}
} // namespace ddafem::dda
