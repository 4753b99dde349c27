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
    return true;
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
  return true;
}

void BlockJacobiPcg::multiply_rows(const BlockSparseMatrix& a, const Eigen::VectorXd& x,
                                   Eigen::VectorXd& y, std::size_t begin, std::size_t end) const
{
  for (std::size_t i = begin; i < end; ++i)
  {
    Vector6 yi = a.diagonal(i) * x.segment<6>(at(i));
    for (std::size_t e = row_start[i]; e < row_start[i + 1]; ++e)
    {
      const RowEntry& entry = row_entries[e];
      const Matrix6& u = a.upper(entry.coupling);
      if (entry.transposed)
        yi.noalias() += u.transpose() * x.segment<6>(at(entry.column));
      else
        yi.noalias() += u * x.segment<6>(at(entry.column));
    }
    y.segment<6>(at(i)) = yi;
  }
}

double BlockJacobiPcg::multiply(const BlockSparseMatrix& a, const Eigen::VectorXd& x,
                                Eigen::VectorXd& y) const
{
  y.resize(x.size());
  return parallel.sum_chunks(a.n_blocks(), grain,
                             [&](std::size_t begin, std::size_t end)
                             {
                               multiply_rows(a, x, y, begin, end);
                               return x.segment(at(begin), at(end) - at(begin))
                                   .dot(y.segment(at(begin), at(end) - at(begin)));
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
