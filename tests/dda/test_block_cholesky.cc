// BlockCholeskySolver (SolverKind::block_ldlt) against Eigen's dense LLT on random symmetric
// positive definite block-sparse matrices: a chain, a 2D grid with fill-in, a random graph.
#include "dda/block_cholesky.h"
#include "dda/linear_solver.h"
#include "tests/dda/block_matrices.h"

#include <Eigen/Cholesky>
#include <Eigen/Dense>

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <utility>
#include <vector>

namespace ddafem::dda
{
namespace
{
using test_matrices::Couplings;
using test_matrices::grid_couplings;
using test_matrices::to_dense;

Couplings chain_couplings(std::size_t n_blocks)
{
  Couplings couplings;
  for (std::size_t i = 0; i + 1 < n_blocks; ++i)
    couplings.emplace_back(i, i + 1);
  return couplings;
}

Couplings random_couplings(std::size_t n_blocks, std::size_t n_couplings, std::mt19937& rng)
{
  std::uniform_int_distribution<std::size_t> pick(0, n_blocks - 1);
  std::set<std::pair<std::size_t, std::size_t>> pairs;
  while (pairs.size() < n_couplings)
  {
    const std::size_t i = pick(rng);
    const std::size_t j = pick(rng);
    if (i != j)
      pairs.emplace(std::min(i, j), std::max(i, j));
  }
  return Couplings(pairs.begin(), pairs.end());
}

/// Random values on the pattern of `a`: off-diagonal blocks uniform in [-1, 1], diagonal blocks
/// S S^T + shift I plus enough to make the matrix diagonally dominant (hence SPD) when
/// `positive_definite`, else an indefinite diagonal block in the middle.
void fill_random(BlockSparseMatrix& a, std::mt19937& rng, bool positive_definite = true)
{
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const auto random_block = [&]
  { return Matrix6::NullaryExpr([&](Eigen::Index, Eigen::Index) { return uniform(rng); }); };
  a.set_zero();
  std::vector<double> row_sum(a.n_blocks(), 0.0);
  for (std::size_t k = 0; k < a.n_couplings(); ++k)
  {
    a.upper(k) = random_block();
    const auto [i, j] = a.coupling(k);
    row_sum[i] += a.upper(k).cwiseAbs().rowwise().sum().maxCoeff();
    row_sum[j] += a.upper(k).cwiseAbs().colwise().sum().maxCoeff();
  }
  for (std::size_t i = 0; i < a.n_blocks(); ++i)
  {
    const Matrix6 s = random_block();
    a.diagonal(i) = s * s.transpose() + (row_sum[i] + 0.5) * Matrix6::Identity();
  }
  if (!positive_definite)
    a.diagonal(a.n_blocks() / 2)(3, 3) = -100.0 * (row_sum[a.n_blocks() / 2] + 10.0);
}

/// Relative error of the block Cholesky solution against the dense LLT solution.
double relative_error(SparseDirectSolver& solver, const BlockSparseMatrix& a,
                      const Eigen::VectorXd& b)
{
  const Eigen::LLT<Eigen::MatrixXd> dense(to_dense(a));
  EXPECT_EQ(dense.info(), Eigen::Success);
  const Eigen::VectorXd expected = dense.solve(b);
  Eigen::VectorXd x;
  solver.solve(b, x);
  return (x - expected).norm() / expected.norm();
}

void check_random_matrices(const Couplings& couplings, std::size_t n_blocks, unsigned seed)
{
  std::mt19937 rng(seed);
  BlockSparseMatrix a(n_blocks, couplings);
  fill_random(a, rng);
  const auto solver = make_sparse_direct_solver(SolverKind::block_ldlt);
  ASSERT_EQ(solver->name(), "block_ldlt");
  solver->analyze_pattern(a);
  ASSERT_TRUE(solver->factorize(a));
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const auto random_vector = [&]
  {
    return Eigen::VectorXd::NullaryExpr(static_cast<Eigen::Index>(a.n_rows()),
                                        [&](Eigen::Index) { return uniform(rng); })
        .eval();
  };
  for (int r = 0; r < 3; ++r)
    EXPECT_LT(relative_error(*solver, a, random_vector()), 1e-10);

  // Refactorization with new values on the same pattern.
  fill_random(a, rng);
  ASSERT_TRUE(solver->factorize(a));
  EXPECT_LT(relative_error(*solver, a, random_vector()), 1e-10);
}

TEST(BlockCholesky, ChainMatchesDenseLlt)
{
  check_random_matrices(chain_couplings(100), 100, 1);
}

TEST(BlockCholesky, GridWithFillInMatchesDenseLlt)
{
  check_random_matrices(grid_couplings(12, 9), 12 * 9, 2);
}

TEST(BlockCholesky, RandomGraphMatchesDenseLlt)
{
  std::mt19937 rng(3);
  check_random_matrices(random_couplings(80, 200, rng), 80, 4);
}

TEST(BlockCholesky, TinyGraphsInNaturalOrder)
{
  check_random_matrices({}, 1, 5);
  check_random_matrices({{0, 1}}, 2, 6);
  check_random_matrices({{0, 2}, {1, 2}, {0, 1}}, 3, 7);
  check_random_matrices({}, 7, 8); // no couplings: block diagonal
}

TEST(BlockCholesky, GridOrderingCreatesFillIn)
{
  const std::size_t n_x = 20;
  const std::size_t n_y = 20;
  BlockSparseMatrix a(n_x * n_y, grid_couplings(n_x, n_y));
  BlockCholeskySolver solver;
  solver.analyze_pattern(a);
  EXPECT_EQ(solver.n_blocks(), n_x * n_y);
  // The factor contains the pattern of A plus fill-in, far less than the bandwidth n_x of the
  // natural order would create (about n_x blocks per column).
  EXPECT_GT(solver.n_factor_blocks(), a.n_couplings());
  EXPECT_LT(solver.n_factor_blocks(), n_x * n_y * n_x / 2);
}

TEST(BlockCholesky, ChainHasNoFillIn)
{
  BlockSparseMatrix a(100, chain_couplings(100));
  BlockCholeskySolver solver;
  solver.analyze_pattern(a);
  EXPECT_EQ(solver.n_factor_blocks(), a.n_couplings());
}

TEST(BlockCholesky, NotPositiveDefiniteFails)
{
  for (const auto& [n_blocks, couplings] : {std::make_pair(std::size_t{50}, chain_couplings(50)),
                                            std::make_pair(std::size_t{48}, grid_couplings(8, 6))})
  {
    std::mt19937 rng(9);
    BlockSparseMatrix a(n_blocks, couplings);
    fill_random(a, rng, false);
    BlockCholeskySolver solver;
    solver.analyze_pattern(a);
    EXPECT_FALSE(solver.factorize(a));
    // A positive definite matrix on the same pattern factorizes again afterwards.
    fill_random(a, rng);
    ASSERT_TRUE(solver.factorize(a));
    const Eigen::VectorXd b = Eigen::VectorXd::Ones(static_cast<Eigen::Index>(a.n_rows()));
    EXPECT_LT(relative_error(solver, a, b), 1e-10);
  }
}

TEST(BlockCholesky, SingularMatrixFails)
{
  BlockSparseMatrix a(3, chain_couplings(3));
  std::mt19937 rng(10);
  fill_random(a, rng);
  a.diagonal(1).row(2).setZero();
  a.diagonal(1).col(2).setZero();
  a.upper(0).col(2).setZero();
  a.upper(1).row(2).setZero();
  BlockCholeskySolver solver;
  solver.analyze_pattern(a);
  EXPECT_FALSE(solver.factorize(a));
}

TEST(BlockCholesky, NewPatternIsAnalyzedAgain)
{
  std::mt19937 rng(12);
  BlockSparseMatrix a(40, chain_couplings(40));
  fill_random(a, rng);
  BlockCholeskySolver solver;
  solver.analyze_pattern(a);
  ASSERT_TRUE(solver.factorize(a));
  // The same number of couplings between other blocks, and then more blocks.
  Couplings couplings = chain_couplings(40);
  couplings[10] = {3, 30};
  BlockSparseMatrix b(40, couplings);
  fill_random(b, rng);
  ASSERT_TRUE(solver.factorize(b));
  const Eigen::VectorXd rhs = Eigen::VectorXd::Ones(static_cast<Eigen::Index>(b.n_rows()));
  EXPECT_LT(relative_error(solver, b, rhs), 1e-10);
  BlockSparseMatrix c(45, grid_couplings(9, 5));
  fill_random(c, rng);
  ASSERT_TRUE(solver.factorize(c));
  EXPECT_EQ(solver.n_blocks(), 45u);
  EXPECT_LT(relative_error(solver, c, Eigen::VectorXd::Ones(6 * 45)), 1e-10);
}

TEST(BlockCholesky, WorksInFactorizationReusingSolver)
{
  std::mt19937 rng(11);
  BlockSparseMatrix a(60, grid_couplings(10, 6));
  fill_random(a, rng);
  FactorizationReusingSolver solver(SolverKind::block_ldlt);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(static_cast<Eigen::Index>(a.n_rows()));
  Eigen::VectorXd x;
  const SolveStatus status = solver.solve(a, b, x);
  ASSERT_TRUE(status.success) << status.message;
  EXPECT_LT((a.multiply(x) - b).norm() / b.norm(), 1e-12);
  EXPECT_EQ(solver.name(), "block_ldlt");
}

// Bathe's two half steps (or two dt levels) alternate two matrices that differ in c M: each key
// keeps its own factors, so the alternation factorizes twice, not at every change; a small
// change within a key refines on that key's factors.
TEST(FactorizationReusingSolver, KeepsTheFactorsOfEachKey)
{
  std::mt19937 rng(5);
  BlockSparseMatrix a(40, grid_couplings(8, 5));
  fill_random(a, rng);
  BlockSparseMatrix heavier = a; // + c M: a large change of the diagonal
  for (std::size_t i = 0; i < heavier.n_blocks(); ++i)
    heavier.diagonal(i) += 50.0 * heavier.diagonal(i).trace() * Matrix6::Identity();
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(static_cast<Eigen::Index>(a.n_rows()), 1, 2);
  FactorizationReusingSolver solver(SolverKind::block_ldlt);
  Eigen::VectorXd x;
  for (int k = 0; k < 5; ++k)
  {
    ASSERT_TRUE(solver.solve(a, b, x, MatrixChange::unknown, 16.0).success);
    EXPECT_LT((a.multiply(x) - b).norm() / b.norm(), 1e-9);
    ASSERT_TRUE(solver.solve(heavier, b, x, MatrixChange::unknown, 9.0).success);
    EXPECT_LT((heavier.multiply(x) - b).norm() / b.norm(), 1e-9);
  }
  EXPECT_EQ(solver.n_factorizations(), 2u);
  // A small change under key 16: conjugate gradients on a's factors, no factorization.
  BlockSparseMatrix drifted = a;
  drifted.diagonal(3) *= 1.0 + 1e-6;
  const SolveStatus status = solver.solve(drifted, b, x, MatrixChange::unknown, 16.0);
  ASSERT_TRUE(status.success);
  EXPECT_FALSE(status.factorized);
  EXPECT_GT(status.n_refinements, 0u);
  EXPECT_EQ(solver.n_factorizations(), 2u);
  // `unchanged` after a refined solve: the factors are a's, not drifted's; the answer must
  // still be drifted's to the tolerance.
  const Eigen::VectorXd b2 = Eigen::VectorXd::Ones(static_cast<Eigen::Index>(a.n_rows()));
  ASSERT_TRUE(solver.solve(drifted, b2, x, MatrixChange::unchanged, 16.0).success);
  EXPECT_LT((drifted.multiply(x) - b2).norm() / b2.norm(), 1e-9);
}

} // namespace
} // namespace ddafem::dda
