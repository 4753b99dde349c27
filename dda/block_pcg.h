// Conjugate gradients on the step's block-sparse matrix, preconditioned by the inverses of its
// 6x6 diagonal blocks (block Jacobi). The preconditioner is rebuilt from the diagonal in one
// pass, so contacts that open, close or slide cost nothing beyond the new springs: no
// factorization. DDA's step matrix is c M + K with c = 1/(beta dt^2) the inertia term: each
// diagonal block holds its block's inertia, so D^-1 A has eigenvalues in [mu, 2] with
// mu ~ c m / (c m + sum of the block's contact stiffnesses) and the iteration count grows
// with dt (kappa ~ dt^2). Large dt, static stages and dense tie terms are the hard cases: the
// caller (StepSolver) falls back to a direct solve when the iteration does not converge.
//
// Every kernel runs over fixed chunks of block rows (common/parallel.h): the product row by
// row, the sums one partial per chunk added in order, so the iterates are the same bits on any
// number of threads.
#pragma once

#include "common/parallel.h"
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
  /// n_threads: see Parallel (results do not depend on it).
  explicit BlockJacobiPcg(unsigned n_threads = 1);

  /// Inverts the diagonal blocks of a and indexes its non-zero couplings by block row; false
  /// if a diagonal block is not positive definite (then the matrix is not either, and a
  /// direct solver reports it).
  bool set_preconditioner(const BlockSparseMatrix& a);

  /// Solves a x = b from the first guess x (a zero vector of b's size if x's size differs),
  /// with the preconditioner of the last set_preconditioner, which must have been given a.
  PcgStatus solve(const BlockSparseMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                  const PcgSettings& settings);

  unsigned n_threads() const { return parallel.n_threads(); }

  /// Block rows per chunk of every kernel.
  static constexpr std::size_t grain = 64;

private:
  /// A coupling in a block row: its upper block, transposed for the row of its second block.
  struct RowEntry
  {
    std::size_t coupling;
    std::size_t column; ///< the other block
    bool transposed;
  };
  /// z = D^-1 r; returns r^T z.
  double precondition(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;
  /// Block rows [begin, end) of z = D^-1 r; returns their part of r^T z.
  double precondition_rows(const Eigen::VectorXd& r, Eigen::VectorXd& z, std::size_t begin,
                           std::size_t end) const;
  /// y = A x over the non-zero couplings (those of contacts that are all open add nothing);
  /// returns x^T y.
  double multiply(const BlockSparseMatrix& a, const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  /// The product's table for `a` (product_blocks, product_columns, transposed).
  void index_product(const BlockSparseMatrix& a);

  Parallel parallel;
  std::vector<Matrix6> inverses;     ///< of the diagonal blocks
  std::vector<Matrix6> inverted;     ///< the diagonal blocks `inverses` were computed from
  std::vector<char> nonzero;         ///< per coupling of the last matrix: not all zero
  std::vector<char> indexed_nonzero; ///< and of the matrix row_entries index
  std::vector<std::pair<std::size_t, std::size_t>> indexed_couplings; ///< its couplings
  std::vector<std::size_t> row_start; ///< per block row into row_entries, and the end
  std::vector<RowEntry> row_entries;  ///< by row, in ascending coupling order
  /// The product's table, made by set_preconditioner for its matrix: per block row (from
  /// row_start[i] + i), its diagonal block and then its entries, each a column-major 6 x 6
  /// (a transposed upper block as a copy in `transposed`) with its column block.
  std::vector<const double*> product_blocks;
  std::vector<std::size_t> product_columns;
  std::vector<Matrix6> transposed;
  Eigen::VectorXd r, z, p, q;
};

} // namespace ddafem::dda
