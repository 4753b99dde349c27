// The step's linear solver as the system sees it: the sparse direct solver with reused factors,
// or block-Jacobi conjugate gradients falling back to it (SolverSettings::method).
#pragma once

#include "common/checkpoint_fwd.h"
#include "dda/block_pcg.h"
#include "dda/linear_solver.h"
#include "dda/model_description.h"

#include <Eigen/Core>

#include <cstddef>
#include <string>

namespace ddafem::dda
{
/// Solves each step's system A x = b by the scene's method.
///
/// block_pcg starts from x (the last solution: the previous open-close iteration's, or the
/// previous step's, whose increment is close to this one's) and needs no factorization, so
/// contacts changing state cost nothing beyond the springs. When it does not reach its
/// tolerance in max_iterations (large dt, static stages, stiff ties: kappa grows as dt^2), the
/// direct solver solves and keeps serving the same key (c [1/s^2], see
/// FactorizationReusingSolver) for its next `direct_run` solves, since the next ones are as
/// hard; then CG is tried again.
class StepSolver
{
public:
  explicit StepSolver(const SolverSettings& settings);

  /// x: in, the first guess (block_pcg); out, the solution.
  SolveStatus solve(const BlockSparseMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                    MatrixChange change, double key);

  std::string name() const;
  std::size_t n_factorizations() const { return direct.n_factorizations(); }
  std::size_t n_solves() const { return direct.n_solves(); }
  std::size_t n_refinements() const { return direct.n_refinements(); }
  std::size_t n_pcg_solves() const { return pcg_solve_count; }
  std::size_t n_pcg_iterations() const { return pcg_iteration_count; }
  /// block_pcg solves that did not converge and were solved directly.
  std::size_t n_fallbacks() const { return fallback_count; }

  /// Solves of a key given to the direct solver after one of its CG solves failed.
  static constexpr std::size_t direct_run = 100;

  /// Checkpoints (dda/solver_checkpoint.cc): the counters and the kept factors' matrices, which
  /// `load` factorizes again (the same bits: a refinement with them gives what it would have).
  void save(CheckpointOut& archive) const;
  void load(CheckpointIn& archive);

private:
  SolveStatus solve_by_pcg(const BlockSparseMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                           MatrixChange change, double key);
  SolveStatus solve_directly(const BlockSparseMatrix& a, const Eigen::VectorXd& b,
                             Eigen::VectorXd& x, MatrixChange change, double key);

  SolverSettings settings;
  FactorizationReusingSolver direct;
  BlockJacobiPcg pcg;
  double direct_key = 0.0;            ///< the key last given to the direct solver
  std::size_t direct_solves_left = 0; ///< of that key
  bool previous_call_direct = false;  ///< this solver's previous call went to `direct`
  std::size_t pcg_solve_count = 0;
  std::size_t pcg_iteration_count = 0;
  std::size_t fallback_count = 0;
};

} // namespace ddafem::dda
