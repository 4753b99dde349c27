// Conjugate gradients on the step's block-sparse matrix, preconditioned by the inverses of its
// 6x6 diagonal blocks (block Jacobi). The preconditioner is rebuilt from the diagonal in one
// pass, so contacts that open, close or slide cost nothing beyond the new springs: no
// factorization. DDA's step matrix is c M + K with c = 1/(beta dt^2) the inertia term: each
// diagonal block holds its block's inertia, so D^-1 A has eigenvalues in [mu, 2] with
// mu ~ c m / (c m + sum of the block's contact stiffnesses) and the iteration count grows
// with dt (kappa ~ dt^2). Large dt, static stages and dense tie terms are the hard cases: the
// caller (StepSolver) falls back to a direct solve when the iteration does not converge.
#pragma once

#include "dda/linear_solver.h"
#include "dda/types.h"

#include <Eigen/Core>

#include <vector>

namespace ddafem::dda
{
/// When block-Jacobi CG stops.
struct PcgSettings
{
  /// Stop when sqrt(r^T D^-1 r) <= tolerance sqrt(b^T D^-1 b) (D: the diagonal blocks).
  /// The error in the D norm is then below kappa x tolerance of the solution's.
  double tolerance = 1e-10;
  unsigned max_iterations = 200;
};

/// The outcome of one solve (a numerical outcome the caller acts on, not an exception).
struct PcgStatus
{
  bool converged = false;
  unsigned n_iterations = 0;
  double relative_residual = 0; ///< sqrt(r^T D^-1 r / b^T D^-1 b) at the end
};

/// Block-Jacobi preconditioned conjugate gradients with its work vectors.
class BlockJacobiPcg
{
public:
  /// Inverts the diagonal blocks of a; false if one is not positive definite (then the
  /// matrix is not either, and a direct solver reports it).
  bool set_preconditioner(const BlockSparseMatrix& a);

  /// Solves a x = b from the first guess x (a zero vector of b's size if x's size differs),
  /// with the preconditioner of the last set_preconditioner, which must have been given a
  /// (its diagonal and its zero couplings).
  PcgStatus solve(const BlockSparseMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                  const PcgSettings& settings);

private:
  /// z = D^-1 r; returns r^T z.
  double precondition(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;
  /// y = A x over the couplings whose block is not zero (those of contacts that are all open
  /// add nothing; skipping them is exact).
  void multiply(const BlockSparseMatrix& a, const Eigen::VectorXd& x, Eigen::VectorXd& y) const;

  std::vector<Matrix6> inverses;              ///< of the diagonal blocks
  std::vector<std::size_t> nonzero_couplings; ///< of the matrix of set_preconditioner
  Eigen::VectorXd r, z, p, q;
};

} // namespace ddafem::dda
