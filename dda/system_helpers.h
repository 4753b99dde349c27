// Small helpers of the System implementation files and the element kinds (private: only
// dda/system*.cc and dda/*.cc of element kinds include it).
#pragma once

#include "common/format.h"
#include "dda/block.h"
#include "dda/linear_solver.h"

#include <Eigen/Core>

#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

namespace ddafem::dda
{
/// Largest extent of the model [m], for tolerances.
inline double model_size(const std::vector<Block>& blocks)
{
  double x_min = blocks[0].vertices[0].x(), x_max = x_min;
  double y_min = blocks[0].vertices[0].y(), y_max = y_min;
  for (const Block& b : blocks)
    for (const Point& v : b.vertices)
    {
      x_min = std::min(x_min, v.x());
      x_max = std::max(x_max, v.x());
      y_min = std::min(y_min, v.y());
      y_max = std::max(y_max, v.y());
    }
  return std::max(x_max - x_min, y_max - y_min);
}

/// Adds a spring K2 [N/m] between point i (T_i) and point j (T_j) of two different blocks, with
/// the force `force` [N] acting on i (and -force on j), to the matrix and the right-hand side.
inline void add_pair_spring(BlockSparseMatrix& matrix, Eigen::VectorXd& rhs, std::size_t coupling,
                            std::size_t i, const Matrix26& t_i, std::size_t j, const Matrix26& t_j,
                            const Eigen::Matrix2d& k2, const Vector2& force)
{
  const Matrix26 k_ti = k2 * t_i;
  const Matrix26 k_tj = k2 * t_j;
  matrix.diagonal(i).noalias() += t_i.transpose() * k_ti;
  matrix.diagonal(j).noalias() += t_j.transpose() * k_tj;
  if (i < j)
    matrix.upper(coupling).noalias() -= t_i.transpose() * k_tj;
  else
    matrix.upper(coupling).noalias() -= t_j.transpose() * k_ti;
  rhs.segment<6>(6 * i).noalias() += t_i.transpose() * force;
  rhs.segment<6>(6 * j).noalias() -= t_j.transpose() * force;
}

} // namespace ddafem::dda
