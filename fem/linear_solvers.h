// Solvers of the far field's constant effective matrix K + gamma/(beta dt) C + M/(beta dt^2).
#pragma once

#include "fem/far_field_description.h"

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <memory>
#include <string>
#include <vector>

namespace ddafem::fem
{
/// A solver set up once for a constant symmetric positive definite matrix.
class EffectiveSolver
{
public:
  virtual ~EffectiveSolver() = default;
  /// Factorizes (direct) or builds the preconditioner (cg). The matrix must outlive the solver.
  virtual void initialize(const dealii::SparseMatrix<double>& matrix) = 0;
  /// Solves A x = b. On entry x is the initial guess (used by iterative solvers only).
  virtual void solve(const dealii::Vector<double>& b, dealii::Vector<double>& x) = 0;
  /// Solves A x_j = b_j for each column j (x_j start as zero guesses); direct solvers may solve
  /// them together, reading their factor once for several columns.
  virtual void solve_columns(const std::vector<dealii::Vector<double>>& b,
                             std::vector<dealii::Vector<double>>& x)
  {
    x.resize(b.size());
    for (std::size_t j = 0; j < b.size(); ++j)
    {
      x[j].reinit(b[j].size());
      solve(b[j], x[j]);
    }
  }
  /// Iterations of the last solve (0 for direct solvers).
  virtual unsigned int last_iterations() const { return 0; }
  virtual std::string name() const = 0;
};

/// direct -> `direct` (KLU or UMFPACK), cg -> SolverCG with a Jacobi preconditioner to
/// a residual of `relative_tolerance` |b|.
std::unique_ptr<EffectiveSolver> make_effective_solver(LinearSolver kind, DirectSolver direct,
                                                       double relative_tolerance);

} // namespace ddafem::fem
