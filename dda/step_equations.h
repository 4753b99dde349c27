// The step's linear system (K + c M) d = f over the blocks' six unknowns each (issue 55): the
// block pairs its matrix couples, the matrix and right-hand side as assembled, the same before
// the contacts' terms (where each open-close iteration starts), the dt and mass factor it was
// assembled for (a small-displacement analysis keeps it while they stay), each block's mass
// matrix of the attempt, and the solution d.
#pragma once

#include "dda/linear_solver.h"
#include "dda/types.h"

#include <Eigen/Core>

#include <cstddef>
#include <utility>
#include <vector>

namespace ddafem::dda
{
struct StepEquations
{
  using BlockPairs = std::vector<std::pair<std::size_t, std::size_t>>;

  /// The block pairs (i < j, sorted, unique) the matrix couples, over n_blocks blocks: a new
  /// (zero) matrix if they or n_blocks changed. Returns whether they did.
  bool set_couplings(std::size_t n_blocks, BlockPairs couplings);
  /// Index of the matrix's coupling block of blocks i != j (coupled by set_couplings).
  std::size_t coupling_of(std::size_t i, std::size_t j) const;
  /// The next step assembles the matrix anew (a hold, a stage or a removed block changed it).
  void reassemble() { dt = 0.0; }

  BlockPairs coupling_pairs; ///< sorted
  /// Where each block's couplings (i, j), i the block, start in coupling_pairs; one past the
  /// last block: their number.
  std::vector<std::size_t> coupling_rows;
  BlockSparseMatrix matrix{0, {}};
  BlockSparseMatrix base_matrix{0, {}}; ///< the matrix without contacts (when there are some)
  Eigen::VectorXd base_rhs;
  double dt = 0.0;          ///< dt the matrix was assembled for (small-displacement reuse) [s]
  double mass_factor = 0.0; ///< and its factor of M [1/s^2]
  /// Each block's mass matrix M in the configuration the attempt is linearised about, from
  /// its assembly; the update at its end uses it again.
  std::vector<Matrix6> masses;
  Eigen::VectorXd rhs;
  Eigen::VectorXd solution;
};

} // namespace ddafem::dda
