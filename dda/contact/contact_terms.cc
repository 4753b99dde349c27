// The contacts' terms of the open-close iteration (phase 4): each closed contact's law, springs
// T^T k T between its vertex's and its edge's block, dashpots (dda/damping.h: normal while
// closed, shear while it sticks, on Newmark's end velocity) and forces on the right-hand side.
#include "dda/contact/contact_set.h"

#include "dda/step_equations.h"
#include "dda/system_helpers.h"

#include <algorithm>
#include <array>

namespace ddafem::dda
{
ContactLaw ContactSet::law(const Contact& c) const
{
  const JointMaterial& jm = model->joint_materials[c.joint_material];
  ContactLaw law;
  law.normal_stiffness = c.penalty_factor * jm.normal_stiffness;
  law.shear_stiffness = jm.shear_ratio * law.normal_stiffness;
  law.tan_friction = tan_friction[c.joint_material];
  // A bonded joint material's contacts come from broken joints: residual friction only.
  law.cohesive_force = jm.bonded ? 0.0 : jm.cohesion * c.length;
  law.tensile_capacity = jm.bonded ? 0.0 : jm.tensile_strength * c.length;
  return law;
}

void ContactSet::spring(std::size_t k, const StepDashpots& dashpots, Eigen::Matrix2d& k2,
                        Vector2& force_on_vertex) const
{
  const Contact& c = trial[k];
  const ContactFrame& f = frames[k];
  const ContactLaw law = this->law(c);
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
  add_dashpot(c, f, dashpots, k2, force_on_vertex);
}

void ContactSet::add_terms(StepEquations& step, const StepDashpots& dashpots)
{
  terms.states.resize(trial.size());
  terms.indexed = false; // the contacts of a new attempt
  Eigen::Matrix2d k2;
  Vector2 force;
  for (std::size_t k = 0; k < trial.size(); ++k)
  {
    const Contact& c = trial[k];
    terms.states[k] = c.trial.state;
    if (c.trial.state == ContactState::open)
      continue;
    const ContactFrame& f = frames[k];
    spring(k, dashpots, k2, force);
    add_pair_spring(step.matrix, step.rhs, c.coupling, c.vertex_block, f.t_vertex, c.edge_block,
                    f.t_edge, k2, force);
  }
}

void ContactSet::update_terms(StepEquations& step, const BlockSparseMatrix& start,
                              const StepDashpots& dashpots)
{
  // A contact's springs depend on its state alone, its forces also on its friction (which
  // follows the normal force): the blocks and couplings of contacts that changed state are
  // summed again from the start matrix, every contact in ascending order as add_terms
  // does (the same additions in the same order: the same bits), and the right-hand side is
  // added again whole.
  BlockSparseMatrix& matrix = step.matrix;
  index_terms(matrix.n_blocks(), matrix.n_couplings());
  TermsIndex& x = terms;
  x.changed_blocks.clear();
  x.changed_couplings.clear();
  for (std::size_t k = 0; k < trial.size(); ++k)
  {
    const Contact& c = trial[k];
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
      if (trial[k].trial.state == ContactState::open)
        continue;
      spring(k, dashpots, k2, force);
      const Matrix26& t = trial[k].vertex_block == i ? frames[k].t_vertex : frames[k].t_edge;
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
      const Contact& c = trial[k];
      if (c.trial.state == ContactState::open)
        continue;
      spring(k, dashpots, k2, force);
      const ContactFrame& f = frames[k];
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
  for (std::size_t k = 0; k < trial.size(); ++k)
  {
    const Contact& c = trial[k];
    if (c.trial.state == ContactState::open)
      continue;
    spring(k, dashpots, k2, force);
    step.rhs.segment<6>(6 * c.vertex_block).noalias() += frames[k].t_vertex.transpose() * force;
    step.rhs.segment<6>(6 * c.edge_block).noalias() -= frames[k].t_edge.transpose() * force;
  }
}

void ContactSet::index_terms(std::size_t n_blocks, std::size_t n_couplings)
{
  // Counting sorts by block (each contact under its two blocks) and by coupling; contacts are
  // visited in ascending order, so each list is ascending.
  TermsIndex& x = terms;
  if (x.indexed)
    return;
  const auto index = [&](std::size_t n, auto&& keys_of, std::vector<std::size_t>& start,
                         std::vector<std::size_t>& entries)
  {
    start.assign(n + 1, 0);
    for (std::size_t k = 0; k < trial.size(); ++k)
      for (const std::size_t key : keys_of(trial[k]))
        ++start[key + 1];
    for (std::size_t i = 0; i < n; ++i)
      start[i + 1] += start[i];
    entries.resize(start[n]);
    std::vector<std::size_t> next(start.begin(), start.end() - 1);
    for (std::size_t k = 0; k < trial.size(); ++k)
      for (const std::size_t key : keys_of(trial[k]))
        entries[next[key]++] = k;
  };
  index(
      n_blocks,
      [](const Contact& c) {
        return std::array<std::size_t, 2>{c.vertex_block, c.edge_block};
      },
      x.block_start, x.block_contacts);
  index(
      n_couplings, [](const Contact& c) { return std::array<std::size_t, 1>{c.coupling}; },
      x.coupling_start, x.coupling_contacts);
  x.indexed = true;
}

Eigen::Matrix2d ContactSet::dashpot(const Contact& c, const ContactFrame& f,
                                    const StepDashpots& dashpots) const
{
  // From the joint material's springs, not the penalty raised on penetration; normal while
  // closed, shear only while it sticks (never on a sliding contact's slip). Only over a step
  // that the contact spends in that state from its start: a contact that closes within the step
  // (an impact) would otherwise be stopped by its dashpot before it touches (the gap still
  // open at the end, the trial opening it again, the iteration never settling), and a
  // sliding contact that sticks within the step likewise.
  const JointMaterial& jm = model->joint_materials[c.joint_material];
  const double beta = dashpot_factor(dashpots, jm.damping);
  Eigen::Matrix2d cd = Eigen::Matrix2d::Zero();
  if (beta == 0.0 || c.trial.state == ContactState::open || c.forces.state == ContactState::open)
    return cd;
  cd = beta * jm.normal_stiffness * (f.normal * f.normal.transpose());
  if (c.trial.state == ContactState::lock && c.forces.state == ContactState::lock)
    cd += beta * jm.shear_ratio * jm.normal_stiffness * (f.tangent * f.tangent.transpose());
  return cd;
}

void ContactSet::add_dashpot(const Contact& c, const ContactFrame& f, const StepDashpots& dashpots,
                             Eigen::Matrix2d& k2, Vector2& force_on_vertex) const
{
  const Eigen::Matrix2d cd = dashpot(c, f, dashpots);
  if (cd.isZero(0.0))
    return;
  k2 += dashpots.velocity_factor * cd;
  force_on_vertex -= cd * (f.t_vertex * dashpots.offsets[c.vertex_block] -
                           f.t_edge * dashpots.offsets[c.edge_block]);
}

double ContactSet::viscous_shear(std::size_t k, const StepDashpots& dashpots,
                                 const Eigen::VectorXd& solution) const
{
  // The shear force of the dashpot a sticking contact has over this step (dashpot's rule:
  // locked at the start), at the end velocity of the solution being tried.
  const Contact& c = trial[k];
  if (c.forces.state != ContactState::lock)
    return 0.0;
  const JointMaterial& jm = model->joint_materials[c.joint_material];
  const double beta = dashpot_factor(dashpots, jm.damping);
  if (beta == 0.0)
    return 0.0;
  const ContactFrame& f = frames[k];
  const Vector2 velocity =
      f.t_vertex * (dashpots.velocity_factor * solution.segment<6>(6 * c.vertex_block) +
                    dashpots.offsets[c.vertex_block]) -
      f.t_edge * (dashpots.velocity_factor * solution.segment<6>(6 * c.edge_block) +
                  dashpots.offsets[c.edge_block]);
  return beta * jm.shear_ratio * jm.normal_stiffness * f.tangent.dot(velocity);
}

void ContactSet::add_work_of_damping(double& work, const std::vector<Vector6>& mean,
                                     const Eigen::VectorXd& d, const StepDashpots& dashpots) const
{
  for (std::size_t k = 0; k < trial.size(); ++k)
  {
    const Contact& c = trial[k];
    const ContactFrame& f = frames[k];
    const Eigen::Matrix2d cd = dashpot(c, f, dashpots);
    if (cd.isZero(0.0))
      continue;
    const Vector2 v = f.t_vertex * mean[c.vertex_block] - f.t_edge * mean[c.edge_block];
    const Vector2 du =
        f.t_vertex * d.segment<6>(6 * c.vertex_block) - f.t_edge * d.segment<6>(6 * c.edge_block);
    work -= (cd * v).dot(du);
  }
}

} // namespace ddafem::dda
