// Phase 4 of the step: the open-close iteration over the contacts' trial states, with the
// terms of a tied body (far field) and the contact law of each contact.
#include "dda/system.h"

#include "common/stopwatch.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace ddafem::dda
{
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
  StepSystem step{matrix, rhs};
  for (unsigned iteration = 1; iteration <= max_iterations; ++iteration)
  {
    if (iteration == 1 || ties_changed)
    {
      if (iteration > 1)
        add_ties_to_start(false);
      contact_set.add_terms(step, dashpots);
    }
    else
    {
      rhs = tied_body ? tied_rhs : base_rhs;
      contact_set.update_terms(step, tied_body ? tied_matrix : base_matrix, dashpots);
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
    std::size_t n_changes = contact_set.update_trial_states(
        {solution, dashpots, matrix_dt, iteration, localising_slip_reversals()},
        status.n_flips_ignored, parallel);
    const std::size_t ignored_before = status.n_flips_ignored;
    const std::size_t n_tie_changes =
        tied_body
            ? tied_body->update_trial_states(tie_increments(solution), iteration,
                                             contact_set.negligible_force(), status.n_flips_ignored)
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

} // namespace ddafem::dda
