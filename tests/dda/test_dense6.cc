// The 6x6 block kernels (dda/dense6): the direct solver's pivot inverse L^-1 and the
// block-Jacobi preconditioner's inverse, against Eigen's LLT on random blocks of DDA scale.
#include "dda/dense6.h"

#include <Eigen/Cholesky>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace ddafem::dda
{
namespace
{
/// S S^T + shift I with S uniform in [-1, 1], scaled: symmetric positive definite for shift > 0,
/// condition number up to about 6 / shift.
Matrix6 random_spd(std::mt19937& rng, double shift, double scale)
{
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const Matrix6 s = Matrix6::NullaryExpr([&](Eigen::Index, Eigen::Index) { return uniform(rng); });
  return scale * (s * s.transpose() + shift * Matrix6::Identity());
}

TEST(Dense6, CholeskyInverseIsTheInverseOfEigensFactor)
{
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial)
  {
    const Matrix6 a = random_spd(rng, 0.1, 1e10);
    Matrix6 x;
    ASSERT_TRUE(cholesky_inverse_6(a, x));
    const Matrix6 l = Eigen::LLT<Matrix6>(a).matrixL();
    // X L = I to the rounding of a factor whose condition number is at most sqrt(60).
    EXPECT_LT((x * l - Matrix6::Identity()).cwiseAbs().maxCoeff(), 1e-13);
    EXPECT_TRUE((x.triangularView<Eigen::StrictlyUpper>().toDenseMatrix().array() == 0.0).all());
  }
}

TEST(Dense6, SpdInverseIsSymmetricAndInvertsTheBlock)
{
  std::mt19937 rng(11);
  for (int trial = 0; trial < 200; ++trial)
  {
    // Block-scale entries as in the DDA matrix: c M + springs, 1e8 to 1e12.
    const Matrix6 a = random_spd(rng, 0.05, std::pow(10.0, 8 + trial % 5));
    Matrix6 inverse;
    ASSERT_TRUE(spd_inverse_6(a, inverse));
    EXPECT_TRUE((inverse.array() == inverse.transpose().array()).all()); // bit for bit
    // cond(a) <= (6 + 0.05) / 0.05 = 121: the residual of A A^-1 is about cond * 1e-16.
    EXPECT_LT((inverse * a - Matrix6::Identity()).cwiseAbs().maxCoeff(), 1e-12);
    const Matrix6 reference = Eigen::LLT<Matrix6>(a).solve(Matrix6::Identity());
    EXPECT_LT((inverse - reference).norm(), 1e-12 * reference.norm());
  }
}

TEST(Dense6, FailsExactlyWhenEigensLltFailsOrOnNaN)
{
  std::mt19937 rng(3);
  int failures = 0;
  for (int trial = 0; trial < 400; ++trial)
  {
    // Shifts from -0.5 to 0.5: about half of these blocks are indefinite.
    const double shift = -0.5 + (trial % 100) / 100.0;
    Matrix6 a = random_spd(rng, shift, 1.0);
    if (trial % 50 == 0)
      a(2, 2) = std::numeric_limits<double>::quiet_NaN();
    Matrix6 inverse;
    const bool ours = spd_inverse_6(a, inverse);
    // Eigen's LLT lets a NaN pivot through (its test is `pivot <= 0`); ours refuses it.
    const bool eigens = Eigen::LLT<Matrix6>(a).info() == Eigen::Success && !a.hasNaN();
    EXPECT_EQ(ours, eigens) << "trial " << trial << ", shift " << shift;
    Matrix6 x;
    EXPECT_EQ(cholesky_inverse_6(a, x), eigens);
    failures += !eigens;
  }
  EXPECT_GT(failures, 50); // the test saw both outcomes
  EXPECT_LT(failures, 350);
}

} // namespace
} // namespace ddafem::dda
