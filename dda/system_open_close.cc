// Phase 4 of the step: the open-close iteration over the contacts' trial states, with the
// terms of a tied body (far field) and the contact law of each contact.
#include "dda/system.h"

#include "common/stopwatch.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace ddafem::dda
{
ContactLaw System::contact_law(const Contact& c) const
{
  const JointMaterial& jm = model.joint_materials[c.joint_material];
  ContactLaw law;
  law.normal_stiffness = c.penalty_factor * jm.normal_stiffness;
  law.shear_stiffness = jm.shear_ratio * law.normal_stiffness;
  law.tan_friction = tan_friction[c.joint_material];
  // A bonded joint material's contacts come from broken joints: residual friction only.
  law.cohesive_force = jm.bonded ? 0.0 : jm.cohesion * c.length;
  law.tensile_capacity = jm.bonded ? 0.0 : jm.tensile_strength * c.length;
  return law;
}

StepStatus System::solve_with_open_close(const StepLabel& when, bool new_matrix)
{
  // The matrix without contact and tie terms: just assembled, or kept from the last assembly
  // (small-displacement analysis, same dt).
  if (new_matrix || !base_matrix.same_structure(matrix))
    base_matrix = matrix;
  else
    matrix = base_matrix;
  base_rhs = rhs;
  // A tied body's terms (dense over the tied blocks) change only when its ties change state:
  // the iterations start from the matrix with them, rebuilt only then.
  // (matrix_is_base: matrix and rhs hold base_matrix and base_rhs already, no copy needed.)
  const auto add_ties_to_start = [&](const bool matrix_is_base)
  {
    if (!matrix_is_base)
    {
      matrix = base_matrix;
      rhs = base_rhs;
    }
    add_tie_terms();
    tied_matrix = matrix;
    tied_rhs = rhs;
  };
  if (tied_body)
    add_ties_to_start(true);
  bool ties_changed = false;
  StepStatus status;
  const unsigned max_iterations = std::max(1u, model.contacts.max_open_close_iterations);
  for (unsigned iteration = 1; iteration <= max_iterations; ++iteration)
  {
    if (iteration == 1 || ties_changed)
    {
      if (iteration > 1)
        add_ties_to_start(false);
      add_contact_terms();
    }
    else
    {
      rhs = tied_body ? tied_rhs : base_rhs;
      update_contact_terms(tied_body ? tied_matrix : base_matrix);
    }
    status.solve = solver.solve(matrix, rhs, solution, MatrixChange::unknown, matrix_mass_factor);
    ++status.n_open_close_iterations;
    ++timings.n_open_close_iterations;
    if (!status.solve.success)
    {
      status.outcome = StepOutcome::solver_failure;
      status.message = status.solve.message + " " + when.text();
      return status;
    }
    std::size_t n_changes = update_trial_states(iteration, status.n_flips_ignored);
    const std::size_t ignored_before = status.n_flips_ignored;
    const std::size_t n_tie_changes =
        tied_body
            ? tied_body->update_trial_states(tie_increments(solution), iteration,
                                             negligible_contact_force(), status.n_flips_ignored)
            : 0;
    ties_changed = n_tie_changes > 0 || status.n_flips_ignored > ignored_before;
    n_changes += n_tie_changes;
    status.n_state_changes += n_changes;
    if (n_changes == 0)
      return status;
  }
  status.outcome = StepOutcome::not_converged;
  status.message = "the open-close iteration did not converge in " +
                   std::to_string(max_iterations) + " iterations " + when.text();
  return status;
}

void System::add_tie_terms()
{
  if (!tied_body)
    return;
  const auto start = Clock::now();
  const Eigen::MatrixXd& h = tied_body->stiffness();
  const Eigen::VectorXd& g = tied_body->force();
  const auto m = static_cast<Eigen::Index>(tie_points.size());
  if (tied_body->stiffness_is_block_diagonal())
  {
    // Each tie point on its own: T_k^T H_kk T_k on its block's diagonal, O(m).
    for (Eigen::Index k = 0; k < m; ++k)
    {
      const std::size_t bk = tie_points[k].block;
      const Matrix26& tk = tie_matrices[k];
      rhs.segment<6>(6 * bk).noalias() += tk.transpose() * g.segment<2>(2 * k);
      matrix.diagonal(bk).noalias() += tk.transpose() * h.block<2, 2>(2 * k, 2 * k) * tk;
    }
    timings.tie_terms += seconds_since(start);
    return;
  }
  // (A + T^T H T) d = b + T^T g over the runs of tie points on one block: the blocks of runs
  // a <= b gain X_ab = T_a^T H_ab T_b (its transpose into the stored upper block when a's block
  // comes after b's; X + X^T on the diagonal for two runs on one block), computed pair by pair
  // (dda/tie_terms.h) and added to the matrix in one order: the same bits on any number of
  // threads.
  tie_pairs.compute(h, tied_body->stiffness_id(), tie_matrices, tie_points, blocks,
                    small_displacement(), parallel);
  const std::vector<TieRun>& runs = tie_pairs.runs();
  for (std::size_t a = 0; a < runs.size(); ++a)
  {
    const TieRun& ra = runs[a];
    rhs.segment<6>(static_cast<Eigen::Index>(6 * ra.block)).noalias() += tie_pairs.force(a, g);
    for (std::size_t b = a; b < runs.size(); ++b)
    {
      const std::size_t bb = runs[b].block;
      const Matrix6& x = tie_pairs.pair(a, b);
      if (b == a)
        matrix.diagonal(ra.block) += x;
      else if (bb == ra.block)
        matrix.diagonal(ra.block) += x + x.transpose();
      else if (ra.block < bb)
        matrix.upper(coupling_of(ra.block, bb)) += x;
      else
        matrix.upper(coupling_of(ra.block, bb)) += x.transpose();
    }
  }
  timings.tie_terms += seconds_since(start);
}

Eigen::VectorXd System::tie_increments(const Eigen::VectorXd& d) const
{
  Eigen::VectorXd delta(2 * tie_points.size());
  for (std::size_t k = 0; k < tie_points.size(); ++k)
    delta.segment<2>(2 * k) = tie_matrices[k] * d.segment<6>(6 * tie_points[k].block);
  return delta;
}

double System::negligible_contact_force() const
{
  double largest_force = 0.0;
  for (const Contact& c : contact_set.trial)
    largest_force = std::max(largest_force, c.trial.normal_force);
  return model.contacts.flip_force_ratio * largest_force;
}

std::size_t System::update_trial_states(unsigned iteration, std::size_t& n_ignored)
{
  // Each contact's trial on the threads (it depends on the contact alone); the changes are
  // counted per chunk and added afterwards (integers: in any order the same).
  const double negligible = negligible_contact_force();
  const bool localising = localising_slip_reversals();
  constexpr std::size_t grain = 1024;
  std::vector<std::array<std::size_t, 2>> counts((contact_set.trial.size() + grain - 1) / grain,
                                                 {0, 0});
  parallel.for_chunks(contact_set.trial.size(), grain,
                      [&](std::size_t begin, std::size_t end)
                      {
                        std::array<std::size_t, 2>& n = counts[begin / grain];
                        for (std::size_t k = begin; k < end; ++k)
                          update_trial_state(k, iteration, negligible, localising, n);
                      });
  std::size_t n_changes = 0;
  for (const std::array<std::size_t, 2>& n : counts)
  {
    n_changes += n[0];
    n_ignored += n[1];
  }
  return n_changes;
}

void System::update_trial_state(std::size_t k, unsigned iteration, double negligible,
                                bool localising, std::array<std::size_t, 2>& n)
{
  Contact& c = contact_set.trial[k];
  const ContactFrame& f = contact_set.frames[k];
  const Vector2 relative = f.t_vertex * solution.segment<6>(6 * c.vertex_block) -
                           f.t_edge * solution.segment<6>(6 * c.edge_block);
  c.end_gap = c.gap + f.normal.dot(relative);
  c.step_slip = f.tangent.dot(relative);
  // A sticking contact's dashpot is in its shear demand; from the third iteration on it may
  // hold a contact at the limit but no longer push it to slide, or the contact flips on the
  // dashpot's last newton between a lock (dashpot on) and a slide (off) for ever.
  const ContactForces law =
      evaluate_contact(contact_law(c), c.forces, c.end_gap, c.step_slip, viscous_shear(k),
                       iteration < 3 ? DashpotDemand::total : DashpotDemand::never_pushes);
  // With slip reversals localised, sliding that reverses between trials is taken as lock
  // (only on a slide of at least 10 steps: slides_long_enough).
  const ContactForces next = localising && slides_long_enough(c, matrix_dt)
                                 ? iteration_trial(iteration, c.trial, law)
                                 : law;
  // A contact that ends the step within rounding of zero gap (1e-12 of the model size; its
  // forces are then p x that, e.g. 0.5 N) is decided by rounding noise: it carries nothing
  // in either state and may flip between iterations (the head joints of bricks falling
  // together). Its change is taken but does not hold the iteration back (n[1]; the others
  // n[0]). From the third iteration on, so does one that carries almost nothing before and
  // after (contacts flipping between slide and lock under a kN where the rock carries MN).
  if (state_changed(c.trial, next) && std::abs(c.end_gap) > 2e-12 * contact_set.distances.w0)
    ++n[change_holds_iteration(iteration, c.trial, next, negligible) ? 0 : 1];
  c.trial = next;
}

bool System::raise_penalties()
{
  const double cap = model.contacts.max_penalty_factor;
  bool raised = false;
  for (const Contact& c : contact_set.trial)
    if (c.trial.state != ContactState::open && -c.end_gap > contact_set.distances.max_penetration &&
        c.penalty_factor < cap)
    {
      contact_set.raised_penalties[c.key()] = std::min(cap, 10.0 * c.penalty_factor);
      raised = true;
    }
  return raised;
}

} // namespace ddafem::dda
