// The contacts' persistence from step to step (dda/contact/contact_set.h).
#include "dda/contact/contact_set.h"

#include "common/input_error.h"
#include "dda/joints.h"

#include <algorithm>
#include <cmath>

namespace ddafem::dda
{
namespace
{
/// Throws InputError if two blocks that may touch have materials no joint material applies to.
void check_contact_materials(const ModelDescription& model, const std::vector<Block>& blocks)
{
  // Any two blocks may come into contact: every pair of materials needs a joint material.
  std::vector<bool> used(model.materials.size(), false);
  for (const Block& b : blocks)
    used[b.material] = true;
  for (std::size_t m1 = 0; m1 < used.size(); ++m1)
    for (std::size_t m2 = m1; m2 < used.size(); ++m2)
      if (used[m1] && used[m2] && joint_material_for(model, m1, m2) >= model.joint_materials.size())
        throw InputError("blocks of materials '" + model.materials[m1].name + "' and '" +
                         model.materials[m2].name +
                         "' may come into contact but no joint material applies to them: "
                         "expected `joints: {default: NAME}` or a `joints.pairs` entry");
}

/// w0, the step displacement bound g2 w0, the search distance d0, the penetration limit and
/// the angle tolerance, from the model's size [m] and its ContactSettings.
ContactDistances contact_distances(const std::vector<Block>& blocks, double size,
                                   const ContactSettings& cs)
{
  // Shi's w0 and the contact distances derived from it. Shi's bound g2 w0 alone would let a
  // long model of small blocks (a bar) move vertices farther than a block in one step; the
  // bound is also kept below a tenth of the shortest edge, so that the search distance
  // (2.5 times the bound) stays below a quarter of it and only neighbours are candidates.
  ContactDistances d;
  d.w0 = 0.5 * size;
  double shortest_edge = size;
  for (const Block& b : blocks)
    for (std::size_t k = 0; k < b.vertices.size(); ++k)
      shortest_edge =
          std::min(shortest_edge, (b.vertices[(k + 1) % b.vertices.size()] - b.vertices[k]).norm());
  d.max_step_displacement = std::min(cs.max_displacement_ratio * d.w0, 0.1 * shortest_edge);
  d.search_distance = cs.search_distance > 0.0 ? cs.search_distance : 2.5 * d.max_step_displacement;
  d.max_penetration = cs.max_penetration > 0.0 ? cs.max_penetration : d.max_step_displacement;
  d.angle_tolerance = cs.angle_tolerance_deg * M_PI / 180.0;
  d.sin_angle_tolerance = std::sin(d.angle_tolerance);
  return d;
}
} // namespace

void ContactSet::set_up(const ModelDescription& description, const std::vector<Block>& blocks,
                        double size, bool contacts_enabled)
{
  enabled = contacts_enabled;
  model = &description;
  for (const JointMaterial& jm : description.joint_materials)
    tan_friction.push_back(std::tan(jm.friction_angle * M_PI / 180.0));
  if (enabled && blocks.size() > 1)
    check_contact_materials(description, blocks);
  for (const Block& b : blocks)
  {
    bool is_convex = true;
    const std::size_t n = b.vertices.size();
    for (std::size_t k = 0; k < n; ++k)
      is_convex = is_convex && interior_angle(b.vertices, k) < M_PI;
    convex.push_back(is_convex);
  }
  distances = contact_distances(blocks, size, description.contacts);
}

void ContactSet::inherit(const Parallel& parallel)
{
  // The trial contacts start as detected; each finds its predecessor on the threads (copied
  // there too: the contact is at hand when it inherits); the new ones take ids afterwards, in
  // contact order, so the ids do not depend on the number of threads either.
  constexpr std::size_t none = std::numeric_limits<std::size_t>::max();
  const std::vector<Contact>& found = detected.contacts;
  std::vector<std::size_t>& predecessors = detected.predecessors;
  const bool search = predecessors.size() != found.size();
  if (search)
    predecessors.resize(found.size());
  trial.resize(found.size());
  parallel.for_chunks(found.size(), 1024,
                      [&](std::size_t begin, std::size_t end)
                      {
                        // Both lists are in key order: one search per chunk, then a walk.
                        auto at = accepted.begin();
                        if (search && begin < end)
                          at = std::lower_bound(
                              accepted.begin(), accepted.end(), found[begin].key(),
                              [](const Contact& x, const auto& key) { return x.key() < key; });
                        for (std::size_t k = begin; k < end; ++k)
                        {
                          trial[k] = found[k];
                          if (search)
                          {
                            const auto key = trial[k].key();
                            while (at != accepted.end() && at->key() < key)
                              ++at;
                            predecessors[k] = find_predecessor(trial[k], at, none);
                          }
                          const std::size_t p = predecessors[k];
                          inherit_state(trial[k], p == none ? nullptr : &accepted[p], none);
                        }
                      });
  for (Contact& c : trial)
    if (c.id == none)
      c.id = next_id++;
}

std::size_t ContactSet::find_predecessor(const Contact& c, std::vector<Contact>::const_iterator at,
                                         std::size_t none) const
{
  // The same key; else a vertex that moved on to another edge of the same block inherits its
  // previous contact there (sliding past a corner): the last one not open.
  if (at != accepted.end() && at->key() == c.key())
    return static_cast<std::size_t>(at - accepted.begin());
  const auto same_vertex = [&](const Contact& x)
  {
    return x.vertex_block == c.vertex_block && x.vertex == c.vertex && x.edge_block == c.edge_block;
  };
  auto first = at;
  while (first != accepted.begin() && same_vertex(*(first - 1)))
    --first;
  std::size_t previous = none;
  for (auto it = first; it != accepted.end() && same_vertex(*it); ++it)
    if (it->forces.state != ContactState::open)
      previous = static_cast<std::size_t>(it - accepted.begin());
  return previous;
}

void ContactSet::inherit_state(Contact& c, const Contact* previous, std::size_t no_id) const
{
  // Keep id, state and forces of contacts that persist.
  if (previous)
  {
    c.id = previous->id;
    c.forces = previous->forces;
    c.total_slip = previous->total_slip;
    c.slide_duration = previous->slide_duration;
    c.penalty_factor = previous->penalty_factor;
  }
  else
  {
    // A new contact starts closed if its blocks touch (within the 1e-9 of the model size that
    // joins shared edges): blocks stacked in the scene then start closed together, where
    // starting open would close them one course per open-close iteration (a stack of n
    // courses would need n iterations, and Shi's 6 then cut dt without end). Those in
    // tension open in the first iteration.
    c.id = no_id;
    c.forces.state = c.gap <= 2e-9 * distances.w0 ? ContactState::lock : ContactState::open;
  }
  if (!raised_penalties.empty())
    if (const auto raised = raised_penalties.find(c.key()); raised != raised_penalties.end())
      c.penalty_factor = std::max(c.penalty_factor, raised->second);
  c.trial = c.forces;
}

ContactCounts ContactSet::counts() const
{
  ContactCounts n;
  for (const Contact& c : accepted)
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

void ContactSet::add_snapshots(const std::vector<Block>& blocks,
                               std::vector<ContactSnapshot>& out) const
{
  for (const Contact& c : accepted)
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
}

void ContactSet::accept(double dt)
{
  for (Contact& c : trial)
  {
    if (c.trial.state == ContactState::slide)
      c.total_slip += c.step_slip;
    const bool slides_on = c.forces.state == ContactState::slide &&
                           c.trial.state == ContactState::slide &&
                           std::signbit(c.forces.shear_force) == std::signbit(c.trial.shear_force);
    // A lock keeps the duration of the slide it ended (scan_reversals: friction that
    // turns around after a short stick); an opening forgets it.
    c.slide_duration = c.trial.state == ContactState::open   ? 0.0
                       : c.trial.state == ContactState::lock ? c.slide_duration
                       : slides_on                           ? c.slide_duration + dt
                                                             : dt;
    c.forces = c.trial;
  }
  accepted.swap(trial);
  raised_penalties.clear();
  ++geometry_epoch;
}

const Contact* ContactSet::deepest(double& depth) const
{
  const Contact* found = nullptr;
  for (const Contact& c : trial)
    if (c.trial.state != ContactState::open && -c.end_gap > depth)
    {
      depth = -c.end_gap;
      found = &c;
    }
  return found;
}

void ContactSet::add_loads(const std::function<void(std::size_t, double)>& add) const
{
  for (const Contact& c : trial)
    if (c.forces.state != ContactState::open)
    {
      const double magnitude = std::hypot(c.forces.normal_force, c.forces.shear_force);
      add(c.vertex_block, magnitude);
      add(c.edge_block, magnitude);
    }
}

void ContactSet::add_energy(double& e) const
{
  for (const Contact& c : accepted)
    if (c.forces.state != ContactState::open)
    {
      const ContactLaw springs = law(c);
      e += 0.5 * (c.forces.normal_force * c.forces.normal_force / springs.normal_stiffness +
                  c.forces.shear_force * c.forces.shear_force / springs.shear_stiffness);
    }
}

} // namespace ddafem::dda
