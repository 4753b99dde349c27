// Shared test helpers for block-sparse matrices: couplings of a grid of blocks and the dense
// matrix of a BlockSparseMatrix.
#pragma once

#include "dda/linear_solver.h"

#include <Eigen/Dense>

#include <cstddef>
#include <utility>
#include <vector>

namespace ddafem::dda::test_matrices
{
using Couplings = std::vector<std::pair<std::size_t, std::size_t>>;

/// Blocks of an n_x x n_y grid, each coupled to its right and upper neighbours.
inline Couplings grid_couplings(std::size_t n_x, std::size_t n_y)
{
  Couplings couplings;
  for (std::size_t y = 0; y < n_y; ++y)
    for (std::size_t x = 0; x < n_x; ++x)
    {
      const std::size_t b = y * n_x + x;
      if (x + 1 < n_x)
        couplings.emplace_back(b, b + 1);
      if (y + 1 < n_y)
        couplings.emplace_back(b, b + n_x);
    }
  return couplings;
}

/// The dense symmetric matrix.
inline Eigen::MatrixXd to_dense(const BlockSparseMatrix& a)
{
  const auto n = static_cast<Eigen::Index>(a.n_rows());
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t i = 0; i < a.n_blocks(); ++i)
    dense.block<6, 6>(6 * static_cast<Eigen::Index>(i), 6 * static_cast<Eigen::Index>(i)) =
        a.diagonal(i);
  for (std::size_t k = 0; k < a.n_couplings(); ++k)
  {
    const auto i = 6 * static_cast<Eigen::Index>(a.coupling(k).first);
    const auto j = 6 * static_cast<Eigen::Index>(a.coupling(k).second);
    dense.block<6, 6>(i, j) += a.upper(k);
    dense.block<6, 6>(j, i) += a.upper(k).transpose();
  }
  return dense;
}
} // namespace ddafem::dda::test_matrices
