#include "dda/block_cholesky.h"

#include "dda/dense6.h"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace ddafem::dda
{
namespace
{
/// Fill-reducing order of the block graph: new index -> old index. Approximate minimum degree
/// (Eigen::AMDOrdering, which returns the inverse permutation P^-1 of P A P^T) on the
/// n_blocks x n_blocks pattern; natural order for graphs of at most `max_natural` blocks.
std::vector<std::size_t> block_ordering(const BlockSparseMatrix& a, std::size_t max_natural)
{
  const std::size_t n = a.n_blocks();
  std::vector<std::size_t> old_of_new(n);
  for (std::size_t k = 0; k < n; ++k)
    old_of_new[k] = k;
  if (n <= max_natural || a.n_couplings() == 0)
    return old_of_new;

  std::vector<Eigen::Triplet<double, int>> triplets;
  triplets.reserve(n + a.n_couplings());
  for (std::size_t k = 0; k < n; ++k)
    triplets.emplace_back(static_cast<int>(k), static_cast<int>(k), 1.0);
  for (std::size_t c = 0; c < a.n_couplings(); ++c)
  {
    const auto [i, j] = a.coupling(c);
    triplets.emplace_back(static_cast<int>(i), static_cast<int>(j), 1.0);
  }
  Eigen::SparseMatrix<double, Eigen::ColMajor, int> pattern(static_cast<Eigen::Index>(n),
                                                            static_cast<Eigen::Index>(n));
  pattern.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::AMDOrdering<int>::PermutationType inverse_permutation;
  Eigen::AMDOrdering<int>()(pattern.selfadjointView<Eigen::Upper>(), inverse_permutation);
  for (std::size_t k = 0; k < n; ++k)
    old_of_new[k] = static_cast<std::size_t>(inverse_permutation.indices()[static_cast<int>(k)]);
  return old_of_new;
}

} // namespace

void BlockCholeskySolver::analyze_pattern(const BlockSparseMatrix& a)
{
  const std::size_t n = a.n_blocks();
  analyzed_couplings.resize(a.n_couplings());
  for (std::size_t c = 0; c < a.n_couplings(); ++c)
    analyzed_couplings[c] = a.coupling(c);
  old_of_new = block_ordering(a, max_n_blocks_natural_order);
  new_of_old.assign(n, 0);
  for (std::size_t k = 0; k < n; ++k)
    new_of_old[old_of_new[k]] = k;

  sort_entries_by_row(a);
  const std::vector<std::size_t> column_count = find_row_patterns();
  find_fill();
  build_column_storage(column_count);

  factor_blocks.assign(row_cols.size(), Matrix6::Zero());
  diagonal_inverse.assign(n, Matrix6::Zero());
  workspace.assign(n, Matrix6::Zero());
  permuted.setZero(static_cast<Eigen::Index>(6 * n));
}

void BlockCholeskySolver::sort_entries_by_row(const BlockSparseMatrix& a)
{
  const std::size_t n = a.n_blocks();
  entry_start.assign(n + 1, 0);
  for (std::size_t c = 0; c < a.n_couplings(); ++c)
  {
    const auto [i, j] = a.coupling(c);
    ++entry_start[std::max(new_of_old[i], new_of_old[j]) + 1];
  }
  for (std::size_t k = 0; k < n; ++k)
    entry_start[k + 1] += entry_start[k];
  entries.resize(a.n_couplings());
  std::vector<std::size_t> next(entry_start.begin(), entry_start.end() - 1);
  for (std::size_t c = 0; c < a.n_couplings(); ++c)
  {
    const auto [i, j] = a.coupling(c);
    const std::size_t ni = new_of_old[i];
    const std::size_t nj = new_of_old[j];
    // The upper block A(i, j) lands at (ni, nj); below the diagonal if ni > nj, else its
    // transpose A(j, i) does at (nj, ni).
    const std::size_t row = std::max(ni, nj);
    entries[next[row]++] = MatrixEntry{std::min(ni, nj), c, ni < nj, false};
  }
}

std::vector<std::size_t> BlockCholeskySolver::find_row_patterns()
{
  // The pattern of row k is the union of the paths in the elimination tree from each j with
  // A(k, j) != 0 towards k (Liu; Davis' ldl_symbolic).
  const std::size_t n = old_of_new.size();
  constexpr std::size_t none = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> parent(n, none);
  std::vector<std::size_t> flag(n, none);
  std::vector<std::size_t> column_count(n, 0);
  row_start.assign(n + 1, 0);
  row_cols.clear();
  for (std::size_t k = 0; k < n; ++k)
  {
    flag[k] = k;
    for (std::size_t e = entry_start[k]; e < entry_start[k + 1]; ++e)
      for (std::size_t i = entries[e].col; flag[i] != k; i = parent[i])
      {
        if (parent[i] == none)
          parent[i] = k;
        row_cols.push_back(i);
        ++column_count[i];
        flag[i] = k;
      }
    // Ascending columns are a topological order of the row's subtree.
    std::sort(row_cols.begin() + static_cast<std::ptrdiff_t>(row_start[k]), row_cols.end());
    row_start[k + 1] = row_cols.size();
  }
  return column_count;
}

void BlockCholeskySolver::find_fill()
{
  const std::size_t n = old_of_new.size();
  std::vector<std::size_t> flag(n, std::numeric_limits<std::size_t>::max());
  fill_start.assign(n + 1, 0);
  fill_cols.clear();
  for (std::size_t k = 0; k < n; ++k)
  {
    for (std::size_t e = entry_start[k]; e < entry_start[k + 1]; ++e)
    {
      entries[e].first = flag[entries[e].col] != k;
      flag[entries[e].col] = k;
    }
    for (std::size_t p = row_start[k]; p < row_start[k + 1]; ++p)
      if (flag[row_cols[p]] != k)
        fill_cols.push_back(row_cols[p]);
    fill_start[k + 1] = fill_cols.size();
  }
}

void BlockCholeskySolver::build_column_storage(const std::vector<std::size_t>& column_count)
{
  // Rows are appended in ascending order.
  const std::size_t n = old_of_new.size();
  column_start.assign(n + 1, 0);
  for (std::size_t j = 0; j < n; ++j)
    column_start[j + 1] = column_start[j] + column_count[j];
  column_rows.resize(row_cols.size());
  row_slots.resize(row_cols.size());
  std::vector<std::size_t> next(column_start.begin(), column_start.end() - 1);
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t p = row_start[k]; p < row_start[k + 1]; ++p)
    {
      const std::size_t slot = next[row_cols[p]]++;
      column_rows[slot] = k;
      row_slots[p] = slot;
    }
}

bool BlockCholeskySolver::has_analyzed_pattern(const BlockSparseMatrix& a) const
{
  if (a.n_blocks() != old_of_new.size() || a.n_couplings() != analyzed_couplings.size())
    return false;
  for (std::size_t c = 0; c < a.n_couplings(); ++c)
    if (a.coupling(c) != analyzed_couplings[c])
      return false;
  return true;
}

bool BlockCholeskySolver::factorize(const BlockSparseMatrix& a)
{
  if (!has_analyzed_pattern(a))
    analyze_pattern(a);
  const std::size_t n = old_of_new.size();
  for (std::size_t k = 0; k < n; ++k)
  {
    const std::size_t row_begin = row_start[k];
    const std::size_t row_end = row_start[k + 1];

    // y = row k of P A P^T on the pattern of row k of L (which contains that of A).
    for (std::size_t p = fill_start[k]; p < fill_start[k + 1]; ++p)
      workspace[fill_cols[p]].setZero();
    for (std::size_t e = entry_start[k]; e < entry_start[k + 1]; ++e)
    {
      const MatrixEntry& entry = entries[e];
      Matrix6& y = workspace[entry.col];
      const Matrix6& a_kj = a.upper(entry.coupling);
      if (entry.first)
      {
        if (entry.transposed)
          y = a_kj.transpose();
        else
          y = a_kj;
      }
      else if (entry.transposed)
        y += a_kj.transpose();
      else
        y += a_kj;
    }

    // Sparse triangular solve for row k of L, column by column in ascending (topological) order,
    // and the pivot block A_kk - sum_j L_kj L_kj^T.
    const Matrix6& a_kk = a.diagonal(old_of_new[k]);
    Matrix6 pivot;
    if (row_begin == row_end)
      pivot = a_kk;
    for (std::size_t p = row_begin; p < row_end; ++p)
    {
      const std::size_t j = row_cols[p];
      const std::size_t slot = row_slots[p];
      Matrix6& l_kj = factor_blocks[slot];
      l_kj.noalias() = workspace[j] * diagonal_inverse[j].transpose();
      // Blocks of column j above row k were all stored before row k.
      for (std::size_t q = column_start[j]; q < slot; ++q)
        workspace[column_rows[q]].noalias() -= l_kj * factor_blocks[q].transpose();
      if (p == row_begin)
        pivot.noalias() = a_kk - l_kj.lazyProduct(l_kj.transpose());
      else
        pivot.noalias() -= l_kj * l_kj.transpose();
    }

    // Dense Cholesky of the 6x6 pivot block: L_kk^-1.
    if (!cholesky_inverse_6(pivot, diagonal_inverse[k]))
      return false;
  }
  return true;
}

void BlockCholeskySolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x)
{
  const std::size_t n = old_of_new.size();
  assert(static_cast<std::size_t>(b.size()) == 6 * n);
  const auto segment = [](Eigen::VectorXd& v, std::size_t k)
  { return v.segment<6>(static_cast<Eigen::Index>(6 * k)); };

  for (std::size_t k = 0; k < n; ++k)
    segment(permuted, k) = b.segment<6>(static_cast<Eigen::Index>(6 * old_of_new[k]));

  // Forward substitution L z = P b by columns: z_j = L_jj^-1 z_j, then z_i -= L_ij z_j.
  for (std::size_t j = 0; j < n; ++j)
  {
    const Vector6 z_j = diagonal_inverse[j] * segment(permuted, j);
    segment(permuted, j) = z_j;
    for (std::size_t q = column_start[j]; q < column_start[j + 1]; ++q)
      segment(permuted, column_rows[q]).noalias() -= factor_blocks[q] * z_j;
  }

  // Backward substitution L^T w = z by columns: w_j = L_jj^-T (z_j - sum_i L_ij^T w_i).
  for (std::size_t j = n; j-- > 0;)
  {
    Vector6 z_j = segment(permuted, j);
    for (std::size_t q = column_start[j]; q < column_start[j + 1]; ++q)
      z_j.noalias() -= factor_blocks[q].transpose() * segment(permuted, column_rows[q]);
    segment(permuted, j).noalias() = diagonal_inverse[j].transpose() * z_j;
  }

  x.resize(b.size());
  for (std::size_t k = 0; k < n; ++k)
    x.segment<6>(static_cast<Eigen::Index>(6 * old_of_new[k])) = segment(permuted, k);
}

} // namespace ddafem::dda
