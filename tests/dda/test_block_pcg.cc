// Block-Jacobi conjugate gradients (dda/block_pcg) and the step solver that falls back to the
// direct one (dda/step_solver), on DDA-like matrices: inertia c M on each block plus springs
// T^T k T between coupled blocks (each positive semi-definite), so that the condition number of
// D^-1 A is bounded by about 2 (c m + sum k) / (c m) and is set by k / c.
#include "dda/block_pcg.h"
#include "dda/step_solver.h"
#include "tests/dda/block_matrices.h"

#include <Eigen/Cholesky>
#include <Eigen/Dense>

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <utility>
#include <vector>

namespace ddafem::dda
{
namespace
{
using test_matrices::grid_couplings;
using test_matrices::to_dense;

/// c M (M a random symmetric positive definite 6x6 per block, of order 1) plus, per coupling,
/// two contact-like springs of stiffness k: T^T k T with T = [T_a, -T_b] random 2x6.
BlockSparseMatrix dda_like(std::size_t n_x, std::size_t n_y, double c, double k, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  BlockSparseMatrix a(n_x * n_y, grid_couplings(n_x, n_y));
  for (std::size_t i = 0; i < a.n_blocks(); ++i)
  {
    const Matrix6 s =
        Matrix6::NullaryExpr([&](Eigen::Index, Eigen::Index) { return uniform(rng); });
    a.diagonal(i) = c * (s * s.transpose() / 6.0 + Matrix6::Identity());
  }
  for (std::size_t p = 0; p < a.n_couplings(); ++p)
  {
    const auto [i, j] = a.coupling(p);
    const auto t = [&]
    {
      return Eigen::Matrix<double, 2, 6>::NullaryExpr([&](Eigen::Index, Eigen::Index)
                                                      { return uniform(rng); });
    };
    const Eigen::Matrix<double, 2, 6> ti = t(), tj = t();
    a.diagonal(i) += k * ti.transpose() * ti;
    a.diagonal(j) += k * tj.transpose() * tj;
    a.upper(p) -= k * ti.transpose() * tj;
  }
  return a;
}

Eigen::VectorXd right_hand_side(const BlockSparseMatrix& a)
{
  return Eigen::VectorXd::LinSpaced(static_cast<Eigen::Index>(a.n_rows()), -1.0, 2.0);
}

/// ||x - x*||_D / ||x*||_D, D the diagonal blocks.
double relative_error_d(const BlockSparseMatrix& a, const Eigen::VectorXd& x,
                        const Eigen::VectorXd& exact)
{
  double e2 = 0.0, n2 = 0.0;
  for (std::size_t i = 0; i < a.n_blocks(); ++i)
  {
    const auto at = static_cast<Eigen::Index>(6 * i);
    const Vector6 e = x.segment<6>(at) - exact.segment<6>(at);
    e2 += e.dot(a.diagonal(i) * e);
    n2 += exact.segment<6>(at).dot(a.diagonal(i) * exact.segment<6>(at));
  }
  return std::sqrt(e2 / n2);
}

TEST(BlockSparseMatrix, MultiplyIntoEqualsMultiply)
{
  const BlockSparseMatrix a = dda_like(7, 5, 1.0, 3.0, 1);
  const Eigen::VectorXd x = right_hand_side(a);
  Eigen::VectorXd y = Eigen::VectorXd::Constant(3, 7.0); // wrong size: resized
  a.multiply(x, y);
  EXPECT_EQ(y, a.multiply(x));
  EXPECT_LT((y - to_dense(a) * x).norm(), 1e-12 * y.norm());
}

// The error bound of the stopping test: ||x - x*||_D <= kappa tol ||x*||_D, and CG's iteration
// count grows as sqrt(kappa): stiffer springs against the same inertia take more iterations.
TEST(BlockJacobiPcg, AgreesWithDenseCholeskyWithinKappaTimesTolerance)
{
  unsigned previous_iterations = 0;
  for (const double k : {1.0, 30.0, 1000.0})
  {
    const BlockSparseMatrix a = dda_like(12, 10, 1.0, k, 7);
    const Eigen::MatrixXd dense = to_dense(a);
    const Eigen::VectorXd b = right_hand_side(a);
    const Eigen::VectorXd exact = dense.llt().solve(b);
    // kappa of D^-1 A from the dense generalized eigenvalues
    Eigen::MatrixXd d = Eigen::MatrixXd::Zero(dense.rows(), dense.cols());
    for (std::size_t i = 0; i < a.n_blocks(); ++i)
      d.block<6, 6>(6 * static_cast<Eigen::Index>(i), 6 * static_cast<Eigen::Index>(i)) =
          a.diagonal(i);
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(dense, d,
                                                                        Eigen::EigenvaluesOnly);
    const double kappa = eig.eigenvalues().maxCoeff() / eig.eigenvalues().minCoeff();
    BlockJacobiPcg pcg;
    ASSERT_TRUE(pcg.set_preconditioner(a));
    Eigen::VectorXd x;
    const PcgSettings settings{1e-10, 1000};
    const PcgStatus status = pcg.solve(a, b, x, settings);
    ASSERT_TRUE(status.converged) << "k " << k;
    EXPECT_LE(status.relative_residual, 1e-10);
    EXPECT_LT(relative_error_d(a, x, exact), kappa * 1e-10) << "k " << k << " kappa " << kappa;
    // CG's bound: iterations <= sqrt(kappa)/2 ln(2/tol) (+1 for the final true-residual check)
    EXPECT_LE(status.n_iterations, std::ceil(0.5 * std::sqrt(kappa) * std::log(2.0 / 1e-10)) + 1)
        << "k " << k;
    EXPECT_GT(status.n_iterations, previous_iterations) << "k " << k;
    previous_iterations = status.n_iterations;
  }
}

TEST(BlockJacobiPcg, SameBitsOnAnyThreadCount)
{
  const BlockSparseMatrix a = dda_like(30, 20, 1.0, 30.0, 13); // 600 blocks: 10 chunks
  const Eigen::VectorXd b = right_hand_side(a);
  Eigen::VectorXd one;
  BlockJacobiPcg serial(1);
  ASSERT_TRUE(serial.set_preconditioner(a));
  const PcgStatus status = serial.solve(a, b, one, {});
  ASSERT_TRUE(status.converged);
  for (const unsigned threads : {2u, 3u})
  {
    BlockJacobiPcg pcg(threads);
    ASSERT_TRUE(pcg.set_preconditioner(a));
    Eigen::VectorXd x;
    const PcgStatus s = pcg.solve(a, b, x, {});
    EXPECT_EQ(s.n_iterations, status.n_iterations);
    EXPECT_TRUE(x == one) << threads << " threads";
  }
}

TEST(BlockJacobiPcg, ExactFirstGuessTakesNoIteration)
{
  const BlockSparseMatrix a = dda_like(6, 6, 1.0, 10.0, 3);
  const Eigen::VectorXd b = right_hand_side(a);
  Eigen::VectorXd x = to_dense(a).llt().solve(b);
  BlockJacobiPcg pcg;
  ASSERT_TRUE(pcg.set_preconditioner(a));
  const PcgStatus status = pcg.solve(a, b, x, {});
  EXPECT_TRUE(status.converged);
  EXPECT_EQ(status.n_iterations, 0u);
  // A zero right-hand side: x = 0 at once.
  const PcgStatus zero = pcg.solve(a, Eigen::VectorXd::Zero(b.size()), x, {});
  EXPECT_TRUE(zero.converged);
  EXPECT_EQ(x, Eigen::VectorXd::Zero(b.size()));
}

TEST(BlockJacobiPcg, ReportsWhatItCannotDo)
{
  BlockSparseMatrix a = dda_like(5, 4, 1.0, 1e4, 5);
  const Eigen::VectorXd b = right_hand_side(a);
  BlockJacobiPcg pcg;
  ASSERT_TRUE(pcg.set_preconditioner(a));
  Eigen::VectorXd x;
  const PcgStatus capped = pcg.solve(a, b, x, {1e-12, 3});
  EXPECT_FALSE(capped.converged);
  EXPECT_EQ(capped.n_iterations, 3u);
  EXPECT_GT(capped.relative_residual, 1e-12);
  a.diagonal(7)(2, 2) = -1.0; // not positive definite
  EXPECT_FALSE(pcg.set_preconditioner(a));
}

TEST(StepSolver, BlockPcgFallsBackToTheDirectSolverAndRetriesLater)
{
  SolverSettings settings;
  settings.method = SolverMethod::block_pcg;
  settings.max_iterations = 20; // too few for kappa ~ 1e4, enough for ~1
  StepSolver solver(settings);
  const BlockSparseMatrix hard = dda_like(10, 8, 1.0, 1e4, 9);
  const BlockSparseMatrix easy = dda_like(10, 8, 1.0, 0.01, 9);
  const Eigen::VectorXd b = right_hand_side(hard);
  Eigen::VectorXd x;
  SolveStatus status = solver.solve(hard, b, x, MatrixChange::unknown, 1.0);
  ASSERT_TRUE(status.success);
  EXPECT_LT((hard.multiply(x) - b).norm(), 1e-9 * b.norm()); // the direct tolerance
  EXPECT_EQ(solver.n_fallbacks(), 1u);
  EXPECT_EQ(solver.n_factorizations(), 1u);
  // The same key stays with the direct solver for its next solves: no CG attempt.
  ASSERT_TRUE(solver.solve(hard, b, x, MatrixChange::unknown, 1.0).success);
  EXPECT_EQ(solver.n_pcg_solves(), 1u);
  // Another key (another dt) tries CG again; this one converges within 20 iterations.
  x.setZero();
  status = solver.solve(easy, b, x, MatrixChange::unknown, 2.0);
  ASSERT_TRUE(status.success);
  EXPECT_EQ(solver.n_pcg_solves(), 2u);
  EXPECT_EQ(solver.n_fallbacks(), 1u);
  EXPECT_LT(relative_error_d(easy, x, to_dense(easy).llt().solve(b)), 1e-9);
  // After direct_run solves of the first key, CG is tried on it again.
  for (std::size_t k = 1; k < StepSolver::direct_run; ++k)
    ASSERT_TRUE(solver.solve(hard, b, x, MatrixChange::unknown, 1.0).success);
  EXPECT_EQ(solver.n_pcg_solves(), 2u);
  ASSERT_TRUE(solver.solve(hard, b, x, MatrixChange::unknown, 1.0).success);
  EXPECT_EQ(solver.n_pcg_solves(), 3u);
  EXPECT_EQ(solver.name(), "block_pcg+block_ldlt");
}

// `unchanged` vouches for the matrix of the step solver's previous call. When CG solved that
// one and falls back on the next, the direct solver's own previous matrix (an older one of the
// same key) must not be trusted.
TEST(StepSolver, FallbackAfterCgDoesNotTrustTheDirectSolversOlderMatrix)
{
  SolverSettings settings;
  settings.method = SolverMethod::block_pcg;
  settings.max_iterations = 20;
  StepSolver solver(settings);
  const BlockSparseMatrix older = dda_like(10, 8, 1.0, 1e4, 9);
  const BlockSparseMatrix current = dda_like(10, 8, 1.0, 1e4, 10); // same structure
  const Eigen::VectorXd b = right_hand_side(older);
  Eigen::VectorXd x;
  for (std::size_t k = 0; k <= StepSolver::direct_run; ++k) // fallback, then direct_run solves
    ASSERT_TRUE(solver.solve(older, b, x, MatrixChange::unknown, 1.0).success);
  EXPECT_EQ(solver.n_pcg_solves(), 1u);
  x = to_dense(current).llt().solve(b); // CG from the exact answer: no iteration, no fallback
  ASSERT_TRUE(solver.solve(current, b, x, MatrixChange::unknown, 1.0).success);
  EXPECT_EQ(solver.n_fallbacks(), 1u);
  const Eigen::VectorXd b2 = Eigen::VectorXd::Ones(b.size());
  x.setZero(); // CG from zero does not converge in 20 iterations: the direct solver takes over
  ASSERT_TRUE(solver.solve(current, b2, x, MatrixChange::unchanged, 1.0).success);
  EXPECT_EQ(solver.n_fallbacks(), 2u);
  EXPECT_LT((current.multiply(x) - b2).norm(), 1e-9 * b2.norm());
}

TEST(StepSolver, DirectMethodIsTheFactorizationReusingSolver)
{
  StepSolver solver(SolverSettings{});
  const BlockSparseMatrix a = dda_like(6, 5, 1.0, 10.0, 2);
  const Eigen::VectorXd b = right_hand_side(a);
  Eigen::VectorXd x;
  ASSERT_TRUE(solver.solve(a, b, x, MatrixChange::unknown, 1.0).success);
  EXPECT_EQ(solver.n_factorizations(), 1u);
  EXPECT_EQ(solver.n_pcg_solves(), 0u);
  EXPECT_EQ(solver.name(), "block_ldlt");
}

} // namespace
} // namespace ddafem::dda
