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
  if (new_matrix || !equations.base_matrix.same_structure(equations.matrix))
    equations.base_matrix = equations.matrix;
  else
    equations.matrix = equations.base_matrix;
  equations.base_rhs = equations.rhs;
  // A tied body's terms (dense over the tied blocks) change only when its ties change state:
  // the iterations start from the matrix with them, rebuilt only then.
  // (matrix_is_base: matrix and rhs hold base_matrix and base_rhs already, no copy needed.)
  const auto add_ties_to_start = [&](const bool matrix_is_base)
  {
    if (!matrix_is_base)
    {
      equations.matrix = equations.base_matrix;
      equations.rhs = equations.base_rhs;
    }
    const auto start = Clock::now();
    tie_set.add_terms(equations, block_set, block_set.list, parallel);
    timings.tie_terms += seconds_since(start);
    tie_set.matrix = equations.matrix;
    tie_set.rhs = equations.rhs;
  };
  if (tie_set.has_body())
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
      contact_set.add_terms(equations, dashpots);
    }
    else
    {
      equations.rhs = tie_set.has_body() ? tie_set.rhs : equations.base_rhs;
      contact_set.update_terms(
          equations, tie_set.has_body() ? tie_set.matrix : equations.base_matrix, dashpots);
    }
    status.solve = solver.solve(equations.matrix, equations.rhs, equations.solution,
                                MatrixChange::unknown, equations.mass_factor);
    ++status.n_open_close_iterations;
    ++timings.n_open_close_iterations;
    if (!status.solve.success)
    {
      status.outcome = StepOutcome::solver_failure;
      status.message = status.solve.message + " " + when.text();
      return status;
    }
    std::size_t n_changes = contact_set.update_trial_states(
        {equations.solution, dashpots, equations.dt, iteration,
         contact_set.localises_reversals(mode == StageMode::dynamic)},
        status.n_flips_ignored, parallel);
    const std::size_t ignored_before = status.n_flips_ignored;
    const std::size_t n_tie_changes =
        tie_set.has_body()
            ? tie_set.body->update_trial_states(tie_set.increments(equations.solution), iteration,
                                                contact_set.negligible_force(),
                                                status.n_flips_ignored)
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

} // namespace ddafem::dda
