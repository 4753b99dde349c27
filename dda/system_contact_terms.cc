// The contacts' terms of the open-close iteration (phase 4): each closed contact's springs
// T^T k T between its vertex's and its edge's block, and its forces on the right-hand side.
#include "dda/system.h"

#include "dda/system_helpers.h"

#include <algorithm>
#include <array>

namespace ddafem::dda
{
void System::contact_spring(std::size_t k, Eigen::Matrix2d& k2, Vector2& force_on_vertex) const
{
  const Contact& c = contact_set.trial[k];
  const ContactFrame& f = contact_set.frames[k];
  const ContactLaw law = contact_law(c);
  k2 = law.normal_stiffness * (f.normal * f.normal.transpose());
  // Lock: the shear spring on the step's slip, starting from the previous shear force;
  // slide: the friction force of the trial, no shear spring.
  const bool was_closed = c.forces.state != ContactState::open;
  double shear = c.trial.shear_force;
  if (c.trial.state == ContactState::lock)
  {
    k2 += law.shear_stiffness * (f.tangent * f.tangent.transpose());
    shear = was_closed ? c.forces.shear_force : 0.0;
  }
  force_on_vertex = -law.normal_stiffness * c.gap * f.normal - shear * f.tangent;
  add_contact_dashpot(c, f, k2, force_on_vertex);
}

void System::add_contact_terms()
{
  contact_terms.states.resize(contact_set.trial.size());
  contact_terms.indexed = false; // the contacts of a new attempt
  Eigen::Matrix2d k2;
  Vector2 force;
  for (std::size_t k = 0; k < contact_set.trial.size(); ++k)
  {
    const Contact& c = contact_set.trial[k];
    contact_terms.states[k] = c.trial.state;
    if (c.trial.state == ContactState::open)
      continue;
    const ContactFrame& f = contact_set.frames[k];
    contact_spring(k, k2, force);
    add_pair_spring(matrix, rhs, c.coupling, c.vertex_block, f.t_vertex, c.edge_block, f.t_edge, k2,
                    force);
  }
}

void System::update_contact_terms(const BlockSparseMatrix& start)
{
  // A contact's springs depend on its state alone, its forces also on its friction (which
  // follows the normal force): the blocks and couplings of contacts that changed state are
  // summed again from the start matrix, every contact in ascending order as add_contact_terms
  // does (the same additions in the same order: the same bits), and the right-hand side is
  // added again whole.
  index_contact_terms();
  ContactTermsIndex& x = contact_terms;
  x.changed_blocks.clear();
  x.changed_couplings.clear();
  for (std::size_t k = 0; k < contact_set.trial.size(); ++k)
  {
    const Contact& c = contact_set.trial[k];
    if (c.trial.state == x.states[k])
      continue;
    x.states[k] = c.trial.state;
    x.changed_blocks.push_back(c.vertex_block);
    x.changed_blocks.push_back(c.edge_block);
    x.changed_couplings.push_back(c.coupling);
  }
  for (std::vector<std::size_t>* list : {&x.changed_blocks, &x.changed_couplings})
  {
    std::sort(list->begin(), list->end());
    list->erase(std::unique(list->begin(), list->end()), list->end());
  }
  Eigen::Matrix2d k2;
  Vector2 force;
  for (const std::size_t i : x.changed_blocks)
  {
    matrix.diagonal(i) = start.diagonal(i);
    for (std::size_t e = x.block_start[i]; e < x.block_start[i + 1]; ++e)
    {
      const std::size_t k = x.block_contacts[e];
      if (contact_set.trial[k].trial.state == ContactState::open)
        continue;
      contact_spring(k, k2, force);
      const Matrix26& t = contact_set.trial[k].vertex_block == i ? contact_set.frames[k].t_vertex
                                                                 : contact_set.frames[k].t_edge;
      const Matrix26 k_t = k2 * t;
      matrix.diagonal(i).noalias() += t.transpose() * k_t;
    }
  }
  for (const std::size_t u : x.changed_couplings)
  {
    matrix.upper(u) = start.upper(u);
    for (std::size_t e = x.coupling_start[u]; e < x.coupling_start[u + 1]; ++e)
    {
      const std::size_t k = x.coupling_contacts[e];
      const Contact& c = contact_set.trial[k];
      if (c.trial.state == ContactState::open)
        continue;
      contact_spring(k, k2, force);
      const ContactFrame& f = contact_set.frames[k];
      if (c.vertex_block < c.edge_block)
      {
        const Matrix26 k_t = k2 * f.t_edge;
        matrix.upper(u).noalias() -= f.t_vertex.transpose() * k_t;
      }
      else
      {
        const Matrix26 k_t = k2 * f.t_vertex;
        matrix.upper(u).noalias() -= f.t_edge.transpose() * k_t;
      }
    }
  }
  for (std::size_t k = 0; k < contact_set.trial.size(); ++k)
  {
    const Contact& c = contact_set.trial[k];
    if (c.trial.state == ContactState::open)
      continue;
    contact_spring(k, k2, force);
    rhs.segment<6>(6 * c.vertex_block).noalias() +=
        contact_set.frames[k].t_vertex.transpose() * force;
    rhs.segment<6>(6 * c.edge_block).noalias() -= contact_set.frames[k].t_edge.transpose() * force;
  }
}

void System::index_contact_terms()
{
  // Counting sorts by block (each contact under its two blocks) and by coupling; contacts are
  // visited in ascending order, so each list is ascending.
  ContactTermsIndex& x = contact_terms;
  if (x.indexed)
    return;
  const auto index = [&](std::size_t n, auto&& keys_of, std::vector<std::size_t>& start,
                         std::vector<std::size_t>& entries)
  {
    start.assign(n + 1, 0);
    for (std::size_t k = 0; k < contact_set.trial.size(); ++k)
      for (const std::size_t key : keys_of(contact_set.trial[k]))
        ++start[key + 1];
    for (std::size_t i = 0; i < n; ++i)
      start[i + 1] += start[i];
    entries.resize(start[n]);
    std::vector<std::size_t> next(start.begin(), start.end() - 1);
    for (std::size_t k = 0; k < contact_set.trial.size(); ++k)
      for (const std::size_t key : keys_of(contact_set.trial[k]))
        entries[next[key]++] = k;
  };
  index(
      matrix.n_blocks(),
      [](const Contact& c) {
        return std::array<std::size_t, 2>{c.vertex_block, c.edge_block};
      },
      x.block_start, x.block_contacts);
  index(
      matrix.n_couplings(), [](const Contact& c) { return std::array<std::size_t, 1>{c.coupling}; },
      x.coupling_start, x.coupling_contacts);
  x.indexed = true;
}

} // namespace ddafem::dda
