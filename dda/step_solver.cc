#include "dda/step_solver.h"

namespace ddafem::dda
{
StepSolver::StepSolver(const SolverSettings& settings_)
    : settings(settings_), direct(settings_.direct), pcg(settings_.threads)
{
}

std::string StepSolver::name() const
{
  return settings.method == SolverMethod::direct
             ? direct.name()
             : std::string(name_of(settings.method)) + "+" + direct.name();
}

SolveStatus StepSolver::solve(const BlockSparseMatrix& a, const Eigen::VectorXd& b,
                              Eigen::VectorXd& x, MatrixChange change, const double key)
{
  if (settings.method == SolverMethod::direct)
    return direct.solve(a, b, x, change, key);
  if (direct_solves_left > 0 && key == direct_key)
  {
    --direct_solves_left;
    return solve_directly(a, b, x, change, key);
  }
  return solve_by_pcg(a, b, x, change, key);
}

SolveStatus StepSolver::solve_directly(const BlockSparseMatrix& a, const Eigen::VectorXd& b,
                                       Eigen::VectorXd& x, MatrixChange change, const double key)
{
  // `unchanged` vouches for the matrix of this solver's previous call; the direct solver may
  // not have seen that one (CG solved it), so it must compare.
  const SolveStatus status =
      direct.solve(a, b, x, previous_call_direct ? change : MatrixChange::unknown, key);
  previous_call_direct = true;
  return status;
}

SolveStatus StepSolver::solve_by_pcg(const BlockSparseMatrix& a, const Eigen::VectorXd& b,
                                     Eigen::VectorXd& x, MatrixChange change, const double key)
{
  SolveStatus status;
  ++pcg_solve_count;
  previous_call_direct = false;
  if (pcg.set_preconditioner(a))
  {
    const PcgStatus pcg_status = pcg.solve(a, b, x, {settings.tolerance, settings.max_iterations});
    pcg_iteration_count += pcg_status.n_iterations;
    status.n_refinements = pcg_status.n_iterations;
    status.relative_residual = pcg_status.relative_residual;
    if (pcg_status.converged && x.allFinite())
      return status;
  }
  // Not converged, or a diagonal block not positive definite (the direct solver says which).
  ++fallback_count;
  direct_key = key;
  direct_solves_left = direct_run;
  return solve_directly(a, b, x, change, key);
}

} // namespace ddafem::dda
