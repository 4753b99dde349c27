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
  const Contact& c = trial_contacts[k];
  const ContactFrame& f = frames[k];
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
}

void System::add_contact_terms(const BlockSparseMatrix& start)
{
  // Every block and coupling with a contact is summed from `start` (which `matrix` holds):
  // the same additions in the same order as adding each contact's springs in turn.
  contact_terms.states.resize(trial_contacts.size());
  contact_terms.indexed = false; // the contacts of a new attempt
  index_contact_terms();
  ContactTermsIndex& x = contact_terms;
  for (std::size_t k = 0; k < trial_contacts.size(); ++k)
    x.states[k] = trial_contacts[k].trial.state;
  x.changed_blocks.clear();
  x.changed_couplings.clear();
  for (std::size_t i = 0; i + 1 < x.block_start.size(); ++i)
    if (x.block_start[i + 1] > x.block_start[i])
      x.changed_blocks.push_back(i);
  for (std::size_t u = 0; u + 1 < x.coupling_start.size(); ++u)
    if (x.coupling_start[u + 1] > x.coupling_start[u])
      x.changed_couplings.push_back(u);
  sum_contact_terms(start);
}

void System::update_contact_terms(const BlockSparseMatrix& start)
{
  // A contact's springs depend on its state alone, its forces also on its friction (which
  // follows the normal force): the blocks and couplings of contacts that changed state are
  // summed again from the start matrix, and the right-hand side is added again whole.
  index_contact_terms();
  ContactTermsIndex& x = contact_terms;
  x.changed_blocks.clear();
  x.changed_couplings.clear();
  for (std::size_t k = 0; k < trial_contacts.size(); ++k)
  {
    const Contact& c = trial_contacts[k];
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
  sum_contact_terms(start);
}

void System::sum_contact_terms(const BlockSparseMatrix& start)
{
  // On the threads, each writing only its own: every closed contact's springs and force; then
  // each changed block's diagonal and each changed coupling from `start`, and each block's
  // right-hand side, adding its contacts in ascending order (add_pair_spring's order: the
  // same bits on any number of threads).
  ContactTermsIndex& x = contact_terms;
  x.springs.resize(trial_contacts.size());
  x.forces.resize(trial_contacts.size());
  parallel.for_chunks(trial_contacts.size(), 1024,
                      [&](std::size_t begin, std::size_t end)
                      {
                        for (std::size_t k = begin; k < end; ++k)
                          if (trial_contacts[k].trial.state != ContactState::open)
                            contact_spring(k, x.springs[k], x.forces[k]);
                      });
  const auto closed = [&](std::size_t k)
  { return trial_contacts[k].trial.state != ContactState::open; };
  parallel.for_chunks(x.changed_blocks.size(), 64,
                      [&](std::size_t begin, std::size_t end)
                      {
                        for (std::size_t n = begin; n < end; ++n)
                          sum_block_terms(start, x.changed_blocks[n]);
                      });
  parallel.for_chunks(x.changed_couplings.size(), 64,
                      [&](std::size_t begin, std::size_t end)
                      {
                        for (std::size_t n = begin; n < end; ++n)
                          sum_coupling_terms(start, x.changed_couplings[n]);
                      });
  parallel.for_chunks(x.block_start.size() - 1, 256,
                      [&](std::size_t begin, std::size_t end)
                      {
                        for (std::size_t i = begin; i < end; ++i)
                          for (std::size_t e = x.block_start[i]; e < x.block_start[i + 1]; ++e)
                          {
                            const std::size_t k = x.block_contacts[e];
                            if (!closed(k))
                              continue;
                            if (trial_contacts[k].vertex_block == i)
                              rhs.segment<6>(6 * i).noalias() +=
                                  frames[k].t_vertex.transpose() * x.forces[k];
                            else
                              rhs.segment<6>(6 * i).noalias() -=
                                  frames[k].t_edge.transpose() * x.forces[k];
                          }
                      });
}

void System::sum_block_terms(const BlockSparseMatrix& start, std::size_t i)
{
  const ContactTermsIndex& x = contact_terms;
  matrix.diagonal(i) = start.diagonal(i);
  for (std::size_t e = x.block_start[i]; e < x.block_start[i + 1]; ++e)
  {
    const std::size_t k = x.block_contacts[e];
    if (trial_contacts[k].trial.state == ContactState::open)
      continue;
    const Matrix26& t = trial_contacts[k].vertex_block == i ? frames[k].t_vertex : frames[k].t_edge;
    const Matrix26 k_t = x.springs[k] * t;
    matrix.diagonal(i).noalias() += t.transpose() * k_t;
  }
}

void System::sum_coupling_terms(const BlockSparseMatrix& start, std::size_t u)
{
  const ContactTermsIndex& x = contact_terms;
  matrix.upper(u) = start.upper(u);
  for (std::size_t e = x.coupling_start[u]; e < x.coupling_start[u + 1]; ++e)
  {
    const std::size_t k = x.coupling_contacts[e];
    const Contact& c = trial_contacts[k];
    if (c.trial.state == ContactState::open)
      continue;
    const ContactFrame& f = frames[k];
    // The upper block (i, j), i < j: -T_i^T K2 T_j.
    if (c.vertex_block < c.edge_block)
    {
      const Matrix26 k_t = x.springs[k] * f.t_edge;
      matrix.upper(u).noalias() -= f.t_vertex.transpose() * k_t;
    }
    else
    {
      const Matrix26 k_t = x.springs[k] * f.t_vertex;
      matrix.upper(u).noalias() -= f.t_edge.transpose() * k_t;
    }
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
    for (std::size_t k = 0; k < trial_contacts.size(); ++k)
      for (const std::size_t key : keys_of(trial_contacts[k]))
        ++start[key + 1];
    for (std::size_t i = 0; i < n; ++i)
      start[i + 1] += start[i];
    entries.resize(start[n]);
    std::vector<std::size_t> next(start.begin(), start.end() - 1);
    for (std::size_t k = 0; k < trial_contacts.size(); ++k)
      for (const std::size_t key : keys_of(trial_contacts[k]))
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
