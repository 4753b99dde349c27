#include "dda/block_pcg.h"

#include <Eigen/Cholesky>

#include <cmath>

namespace ddafem::dda
{
bool BlockJacobiPcg::set_preconditioner(const BlockSparseMatrix& a)
{
  inverses.resize(a.n_blocks());
  for (std::size_t i = 0; i < a.n_blocks(); ++i)
  {
    const Eigen::LLT<Matrix6> llt(a.diagonal(i));
    if (llt.info() != Eigen::Success)
      return false;
    inverses[i] = llt.solve(Matrix6::Identity());
  }
  nonzero_couplings.clear();
  for (std::size_t k = 0; k < a.n_couplings(); ++k)
    if (!a.upper(k).isZero(0.0))
      nonzero_couplings.push_back(k);
  return true;
}

void BlockJacobiPcg::multiply(const BlockSparseMatrix& a, const Eigen::VectorXd& x,
                              Eigen::VectorXd& y) const
{
  y.resize(x.size());
  for (std::size_t i = 0; i < a.n_blocks(); ++i)
    y.segment<6>(6 * i).noalias() = a.diagonal(i) * x.segment<6>(6 * i);
  for (const std::size_t k : nonzero_couplings)
  {
    const auto [i, j] = a.coupling(k);
    y.segment<6>(6 * i).noalias() += a.upper(k) * x.segment<6>(6 * j);
    y.segment<6>(6 * j).noalias() += a.upper(k).transpose() * x.segment<6>(6 * i);
  }
}

double BlockJacobiPcg::precondition(const Eigen::VectorXd& r_, Eigen::VectorXd& z_) const
{
  double rz = 0.0;
  for (std::size_t i = 0; i < inverses.size(); ++i)
  {
    const auto at = static_cast<Eigen::Index>(6 * i);
    z_.segment<6>(at).noalias() = inverses[i] * r_.segment<6>(at);
    rz += r_.segment<6>(at).dot(z_.segment<6>(at));
  }
  return rz;
}

PcgStatus BlockJacobiPcg::solve(const BlockSparseMatrix& a, const Eigen::VectorXd& b,
                                Eigen::VectorXd& x, const PcgSettings& settings)
{
  PcgStatus status;
  const Eigen::Index n = b.size();
  if (x.size() != n || !x.allFinite())
    x.setZero(n);
  r.resize(n);
  z.resize(n);
  q.resize(n);
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
      multiply(a, p, q);
      const double pq = p.dot(q);
      if (!(pq > 0.0))
        return status; // A is not positive definite along p, or NaN
      const double alpha = rz / pq;
      x.noalias() += alpha * p;
      r.noalias() -= alpha * q;
      const double rz_new = precondition(r, z);
      p = z + (rz_new / rz) * p;
      rz = rz_new;
      status.relative_residual = std::sqrt(std::max(rz, 0.0) / b_norm2);
    }
  }
}

} // namespace ddafem::dda
