// The step's linear system: a symmetric block-sparse matrix of 6x6 blocks and sparse direct
// solvers whose factorization is reused across steps.
#pragma once

#include "common/checkpoint_fwd.h"
#include "common/recent_cache.h"
#include "dda/model_description.h"
#include "dda/types.h"

#include <Eigen/Core>

#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace ddafem::dda
{
/// Symmetric matrix of n_blocks x n_blocks blocks of 6x6: the diagonal blocks and, for each
/// coupling (i, j) with i < j, the upper block (i, j); the lower block is its transpose.
class BlockSparseMatrix
{
public:
  BlockSparseMatrix(std::size_t n_blocks,
                    std::vector<std::pair<std::size_t, std::size_t>> couplings);

  std::size_t n_blocks() const { return diagonal_blocks.size(); }
  std::size_t n_rows() const { return 6 * diagonal_blocks.size(); }
  std::size_t n_couplings() const { return coupling_pairs.size(); }
  const std::pair<std::size_t, std::size_t>& coupling(std::size_t k) const
  {
    return coupling_pairs[k];
  }
  /// The couplings (i, j), i < j, in the order of their upper blocks.
  const std::vector<std::pair<std::size_t, std::size_t>>& couplings() const
  {
    return coupling_pairs;
  }

  void set_zero();
  Matrix6& diagonal(std::size_t i) { return diagonal_blocks[i]; }
  const Matrix6& diagonal(std::size_t i) const { return diagonal_blocks[i]; }
  /// Upper block (i, j), i < j, of coupling k.
  Matrix6& upper(std::size_t k) { return upper_blocks[k]; }
  const Matrix6& upper(std::size_t k) const { return upper_blocks[k]; }

  /// y = A x.
  Eigen::VectorXd multiply(const Eigen::VectorXd& x) const;
  /// y = A x into y (resized), without allocating when y has the size already.
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;

  /// Whether both have the same blocks and couplings, in the same order.
  bool same_structure(const BlockSparseMatrix& other) const;
  /// Whether every entry equals the other matrix's (same structure assumed).
  bool same_values(const BlockSparseMatrix& other) const;

  /// Checkpoints: the structure and the blocks' values.
  template <class Archive>
  void serialize(Archive& archive, const unsigned int /*version*/)
  {
    transfer_all(archive, coupling_pairs, diagonal_blocks, upper_blocks);
  }

private:
  std::vector<std::pair<std::size_t, std::size_t>> coupling_pairs;
  std::vector<Matrix6> diagonal_blocks;
  std::vector<Matrix6> upper_blocks;
};

/// A sparse direct solver for a symmetric positive definite BlockSparseMatrix.
class SparseDirectSolver
{
public:
  virtual ~SparseDirectSolver() = default;
  /// Symbolic analysis (ordering, fill-in) of the matrix's structure; values ignored.
  virtual void analyze_pattern(const BlockSparseMatrix& a) = 0;
  /// Numeric factorization; false if the matrix is singular or not positive definite.
  virtual bool factorize(const BlockSparseMatrix& a) = 0;
  /// x = A^-1 b with the last factorization.
  virtual void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) = 0;
  virtual std::string name() const = 0;
};

std::unique_ptr<SparseDirectSolver> make_sparse_direct_solver(SolverKind kind);

/// The outcome of one solve; the caller acts on it (a numerical outcome, not an exception).
struct SolveStatus
{
  bool success = true;
  bool factorized = false;      ///< a new numeric factorization was computed
  unsigned n_refinements = 0;   ///< preconditioned CG iterations on a reused factorization
  double relative_residual = 0; ///< ||b - A x|| / ||b|| where it was computed, else 0
  std::string message;          ///< why it failed
};

/// What the caller knows about the matrix since the previous solve.
enum class MatrixChange
{
  unknown,  ///< compare with the factored matrix
  unchanged ///< the caller guarantees A is the matrix of the previous call: skip the comparison
};

/// Solves A x = b reusing the last factorization while it serves. If A equals the factored
/// matrix, one solve. If A changed (DDA updates block geometry every step, so its entries drift
/// by the order of the strains; contacts that open, close or slide change a few springs), the
/// old factors precondition conjugate gradients on A (both are symmetric positive definite),
/// which converge in a few iterations for a small or a low-rank change; if the residual is not
/// below `tolerance` * ||b|| after `max_refinements` iterations, A is factorized again (one
/// factorization costs about as much as 30 solves of a large model). The old factors also serve
/// when A's block structure changed (contacts appearing between new block pairs); only a
/// refactorization then analyzes the new structure. The result always
/// satisfies the residual tolerance of a fresh direct solve or the given one. The default 1e-9
/// lies far below what matters physically: the geometry update changes A by about the step's
/// strain increment (1e-8 to 1e-5 relative) and the discretisation error is of order 1e-2.
///
/// Matrices of different kinds (the inertia term c M of another dt, or of the other half step
/// of Bathe's scheme) differ by far more than a few springs: the caller gives each kind a key
/// (c [1/s^2]), and the factors of the last few keys are kept, most recently used first, each
/// preconditioning only matrices of its own key. A run that alternates Bathe's two half steps,
/// or cuts dt and regrows it on levels dt / 2^k, then factorizes once per key instead of at
/// every change.
class FactorizationReusingSolver
{
public:
  explicit FactorizationReusingSolver(SolverKind kind, double tolerance = 1e-9,
                                      unsigned max_refinements = 12, std::size_t max_kept = 8);

  /// `key`: the kind of A (see above); `change` compares with the last call's matrix.
  SolveStatus solve(const BlockSparseMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                    MatrixChange change = MatrixChange::unknown, double key = 0.0);

  std::string name() const;
  std::size_t n_factorizations() const { return factorization_count; }
  std::size_t n_solves() const { return solve_count; }
  std::size_t n_refinements() const { return refinement_count; }

  /// Checkpoints (dda/solver_checkpoint.cc): the counters and the matrix of each kept
  /// factorization, most recent first; `load` analyses and factorizes them again.
  void save(CheckpointOut& archive) const;
  void load(CheckpointIn& archive);

private:
  /// One key's factors and the matrix they belong to (none until the first factorization).
  struct Factored
  {
    std::unique_ptr<SparseDirectSolver> solver;
    std::unique_ptr<BlockSparseMatrix> matrix;
  };
  SolveStatus factorize_and_solve(Factored& f, const BlockSparseMatrix& a, const Eigen::VectorXd& b,
                                  Eigen::VectorXd& x);
  SolveStatus refine(Factored& f, const BlockSparseMatrix& a, const Eigen::VectorXd& b,
                     Eigen::VectorXd& x);
  SolverKind kind;
  double tolerance;
  unsigned max_refinements;
  RecentCache<double, Factored> kept;      ///< by key
  bool last_call_used_own_factors = false; ///< A of the last call is the factored matrix
  std::size_t factorization_count = 0;
  std::size_t solve_count = 0;
  std::size_t refinement_count = 0;
};

} // namespace ddafem::dda
