#include "dda/block_pcg.h"

#include "dda/dense6.h"

#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>

namespace ddafem::dda
{
namespace
{
Eigen::Index at(std::size_t block)
{
  return static_cast<Eigen::Index>(6 * block);
}

// The product's kernel is compiled twice, for the baseline x86-64 and for x86-64-v3 (AVX2 and
// FMA), and the loader picks the one the machine runs (GCC's function multiversioning): a
// 6 x 6 block times a 6-vector takes a quarter of the instructions with 4-wide fused
// multiply-adds. The bits then depend on the machine, as every result of ddafem does, never on
// the threads.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define DDAFEM_WIDE_KERNEL __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define DDAFEM_WIDE_KERNEL
#endif

/// Block rows [begin, end) of y = A x: row i is the sum of blocks[k] x(columns[k]) over k from
/// start[i] + i to start[i + 1] + i (column-major 6 x 6 blocks, the diagonal first); returns
/// their part of x^T y. Columns c, c + 3 of every block go to accumulator c (c = 0, 1, 2),
/// summed at the row's end: three independent chains of additions instead of one, whose
/// latency (not the arithmetic, the matrix being in cache) bounded the product.
DDAFEM_WIDE_KERNEL
double multiply_block_rows(const std::size_t* start, const double* const* blocks,
                           const std::size_t* columns, const double* x, double* y,
                           std::size_t begin, std::size_t end)
{
  // A block's column as a 4-vector and a 2-vector (GCC's vector types: one AVX register and
  // one SSE register in the x86-64-v3 clone, three SSE registers in the default one).
  using Four = double __attribute__((vector_size(32)));
  using Two = double __attribute__((vector_size(16)));
  double xy = 0.0;
  for (std::size_t i = begin; i < end; ++i)
  {
    Four head[3] = {{0.0, 0.0, 0.0, 0.0}, {0.0, 0.0, 0.0, 0.0}, {0.0, 0.0, 0.0, 0.0}};
    Two tail[3] = {{0.0, 0.0}, {0.0, 0.0}, {0.0, 0.0}};
    for (std::size_t k = start[i] + i; k <= start[i + 1] + i; ++k)
    {
      const double* a = blocks[k];
      const double* xk = x + 6 * columns[k];
      for (int c = 0; c < 6; ++c)
      {
        Four a_head;
        Two a_tail;
        std::memcpy(&a_head, a + 6 * c, sizeof a_head);
        std::memcpy(&a_tail, a + 6 * c + 4, sizeof a_tail);
        head[c % 3] += a_head * xk[c];
        tail[c % 3] += a_tail * xk[c];
      }
    }
    const Four row_head = (head[0] + head[1]) + head[2];
    const Two row_tail = (tail[0] + tail[1]) + tail[2];
    double yi[6];
    std::memcpy(yi, &row_head, sizeof row_head);
    std::memcpy(yi + 4, &row_tail, sizeof row_tail);
    for (int r = 0; r < 6; ++r)
    {
      y[6 * i + r] = yi[r];
      xy += x[6 * i + r] * yi[r];
    }
  }
  return xy;
}
} // namespace

BlockJacobiPcg::BlockJacobiPcg(const unsigned n_threads) : parallel(n_threads) {}

bool BlockJacobiPcg::set_preconditioner(const BlockSparseMatrix& a)
{
  const std::size_t n = a.n_blocks();
  if (inverted.size() != n)
  {
    // Nothing inverted yet (NaN never compares equal byte for byte to a finite block).
    inverted.assign(n, Matrix6::Constant(std::numeric_limits<double>::quiet_NaN()));
    inverses.resize(n);
  }
  std::atomic<bool> positive{true};
  parallel.for_chunks(
      n, grain,
      [&](std::size_t begin, std::size_t end)
      {
        for (std::size_t i = begin; i < end; ++i)
        {
          // Between open-close iterations only the blocks whose contacts
          // changed state have a new diagonal: the others keep their inverse.
          if (std::memcmp(inverted[i].data(), a.diagonal(i).data(), sizeof(Matrix6)) == 0)
            continue;
          if (!spd_inverse_6(a.diagonal(i), inverses[i]))
          {
            positive.store(false, std::memory_order_relaxed);
            inverted[i].setConstant(std::numeric_limits<double>::quiet_NaN());
          }
          else
            inverted[i] = a.diagonal(i);
        }
      });
  if (!positive)
    return false;
  // Row index of the non-zero couplings (those whose contacts are all open add nothing):
  // count, prefix sum, fill in coupling order; kept while the couplings and which of them are
  // zero stay the same (between most open-close iterations).
  nonzero.resize(a.n_couplings());
  parallel.for_chunks(a.n_couplings(), 4 * grain,
                      [&](std::size_t begin, std::size_t end)
                      {
                        for (std::size_t k = begin; k < end; ++k)
                          nonzero[k] = !a.upper(k).isZero(0.0);
                      });
  if (row_start.size() == n + 1 && nonzero == indexed_nonzero && a.couplings() == indexed_couplings)
  {
    index_product(a);
    return true;
  }
  indexed_nonzero = nonzero;
  indexed_couplings = a.couplings();
  row_start.assign(n + 1, 0);
  for (std::size_t k = 0; k < a.n_couplings(); ++k)
    if (nonzero[k])
    {
      ++row_start[a.coupling(k).first + 1];
      ++row_start[a.coupling(k).second + 1];
    }
  for (std::size_t i = 0; i < n; ++i)
    row_start[i + 1] += row_start[i];
  row_entries.resize(row_start[n]);
  std::vector<std::size_t> fill(row_start.begin(), row_start.end() - 1);
  for (std::size_t k = 0; k < a.n_couplings(); ++k)
    if (nonzero[k])
    {
      const auto [i, j] = a.coupling(k);
      row_entries[fill[i]++] = {k, j, false};
      row_entries[fill[j]++] = {k, i, true};
    }
  index_product(a);
  return true;
}

void BlockJacobiPcg::index_product(const BlockSparseMatrix& a)
{
  // Row i's blocks from row_start[i] + i: its diagonal, then its entries in their order.
  const std::size_t n = a.n_blocks();
  product_blocks.resize(row_entries.size() + n);
  product_columns.resize(row_entries.size() + n);
  std::size_t n_transposed = 0;
  for (const RowEntry& e : row_entries)
    n_transposed += e.transposed ? 1 : 0;
  transposed.resize(n_transposed);
  std::size_t t = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    std::size_t k = row_start[i] + i;
    product_blocks[k] = a.diagonal(i).data();
    product_columns[k] = i;
    for (std::size_t e = row_start[i]; e < row_start[i + 1]; ++e)
    {
      const RowEntry& entry = row_entries[e];
      ++k;
      if (entry.transposed)
      {
        transposed[t] = a.upper(entry.coupling).transpose();
        product_blocks[k] = transposed[t++].data();
      }
      else
        product_blocks[k] = a.upper(entry.coupling).data();
      product_columns[k] = entry.column;
    }
  }
}

double BlockJacobiPcg::multiply(const BlockSparseMatrix& a, const Eigen::VectorXd& x,
                                Eigen::VectorXd& y) const
{
  y.resize(x.size());
  return parallel.sum_chunks(a.n_blocks(), grain,
                             [&](std::size_t begin, std::size_t end)
                             {
                               return multiply_block_rows(row_start.data(), product_blocks.data(),
                                                          product_columns.data(), x.data(),
                                                          y.data(), begin, end);
                             });
}

double BlockJacobiPcg::precondition_rows(const Eigen::VectorXd& r_, Eigen::VectorXd& z_,
                                         std::size_t begin, std::size_t end) const
{
  double rz = 0.0;
  for (std::size_t i = begin; i < end; ++i)
  {
    z_.segment<6>(at(i)).noalias() = inverses[i] * r_.segment<6>(at(i));
    rz += r_.segment<6>(at(i)).dot(z_.segment<6>(at(i)));
  }
  return rz;
}

double BlockJacobiPcg::precondition(const Eigen::VectorXd& r_, Eigen::VectorXd& z_) const
{
  return parallel.sum_chunks(inverses.size(), grain,
                             [&](std::size_t begin, std::size_t end)
                             { return precondition_rows(r_, z_, begin, end); });
}

PcgStatus BlockJacobiPcg::solve(const BlockSparseMatrix& a, const Eigen::VectorXd& b,
                                Eigen::VectorXd& x, const PcgSettings& settings)
{
  PcgStatus status;
  const Eigen::Index n = b.size();
  const std::size_t n_blocks = a.n_blocks();
  if (x.size() != n || !x.allFinite())
    x.setZero(n);
  r.resize(n);
  z.resize(n);
  p.resize(n);
  // The D^-1 norm of b: every block's equations weigh by their own stiffness, so a held block
  // (its diagonal scaled by 1e8) or a fixed point does not dominate the stopping test.
  const double b_norm2 = precondition(b, z);
  if (!(b_norm2 > 0.0))
  {
    x.setZero(n);
    status.converged = b_norm2 == 0.0;
    return status;
  }
  const double target2 = settings.tolerance * settings.tolerance * b_norm2;
  // Restarted from the true residual once the recursive one converged: CG's updated r drifts
  // from b - A x by rounding, and the answer must satisfy the true one.
  for (int pass = 0;; ++pass)
  {
    multiply(a, x, q);
    r = b - q;
    double rz = precondition(r, z);
    status.relative_residual = std::sqrt(std::max(rz, 0.0) / b_norm2);
    if (rz <= target2)
    {
      status.converged = true;
      return status;
    }
    if (pass == 2)
      return status;
    p = z;
    while (rz > target2)
    {
      if (status.n_iterations == settings.max_iterations)
        return status;
      ++status.n_iterations;
      const double pq = multiply(a, p, q);
      if (!(pq > 0.0))
        return status; // A is not positive definite along p, or NaN
      const double alpha = rz / pq;
      const double rz_new =
          parallel.sum_chunks(n_blocks, grain,
                              [&](std::size_t begin, std::size_t end)
                              {
                                const Eigen::Index first = at(begin), size = at(end) - at(begin);
                                x.segment(first, size).noalias() += alpha * p.segment(first, size);
                                r.segment(first, size).noalias() -= alpha * q.segment(first, size);
                                return precondition_rows(r, z, begin, end);
                              });
      const double beta = rz_new / rz;
      parallel.for_chunks(n_blocks, grain,
                          [&](std::size_t begin, std::size_t end)
                          {
                            const Eigen::Index first = at(begin), size = at(end) - at(begin);
                            p.segment(first, size) =
                                z.segment(first, size) + beta * p.segment(first, size);
                          });
      rz = rz_new;
      status.relative_residual = std::sqrt(std::max(rz, 0.0) / b_norm2);
    }
  }
}

} // namespace ddafem::dda
