#include "dda/step_equations.h"

#include <algorithm>

namespace ddafem::dda
{
bool StepEquations::set_couplings(std::size_t n_blocks, BlockPairs couplings)
{
  if (couplings == coupling_pairs && matrix.n_blocks() == n_blocks)
    return false;
  coupling_pairs = std::move(couplings);
  matrix = BlockSparseMatrix(n_blocks, coupling_pairs);
  coupling_rows.assign(n_blocks + 1, 0);
  for (const auto& pair : coupling_pairs)
    ++coupling_rows[pair.first + 1];
  for (std::size_t i = 0; i < n_blocks; ++i)
    coupling_rows[i + 1] += coupling_rows[i];
  return true;
}

std::size_t StepEquations::coupling_of(std::size_t i, std::size_t j) const
{
  // Within the couplings of the lower block (all of them lie in its row): the same index as a
  // search of all couplings, at the cost of a few comparisons.
  const auto key = std::make_pair(std::min(i, j), std::max(i, j));
  const auto row = coupling_pairs.begin();
  return static_cast<std::size_t>(
      std::lower_bound(row + coupling_rows[key.first], row + coupling_rows[key.first + 1], key) -
      row);
}

} // namespace ddafem::dda
