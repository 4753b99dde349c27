// common/klu: solves against a hand solution, value replacement, and failures as
// statuses (a singular matrix, a value outside the pattern).
#include "common/klu.h"

#include <gtest/gtest.h>

#include <vector>

namespace
{
using ddafem::Klu;

/// A = [[4, -1, 0], [-1, 4, -1], [0, -1, 4]] times `scale`, its pattern finished.
void tridiagonal(Klu& klu, double scale)
{
  klu.start_pattern(3, {2, 3, 2});
  klu.set_row(0, {0, 1}, {4 * scale, -scale});
  klu.set_row(1, {0, 1, 2}, {-scale, 4 * scale, -scale});
  klu.set_row(2, {1, 2}, {-scale, 4 * scale});
}
} // namespace

// A x = (2, 4, 10) has x = (1, 2, 3) (4 - 2 = 2, -1 + 8 - 3 = 4, -2 + 12 = 10); with every value
// doubled through set_row after the pattern, x halves.
TEST(Klu, SolvesAndRefactorizesReplacedValues)
{
  Klu klu;
  tridiagonal(klu, 1.0);
  ASSERT_TRUE(klu.finish_pattern());
  ASSERT_TRUE(klu.factorize());
  const std::vector<double> b{2.0, 4.0, 10.0};
  std::vector<double> x(3);
  ASSERT_TRUE(klu.solve(b.data(), x.data()));
  EXPECT_NEAR(x[0], 1.0, 1e-14);
  EXPECT_NEAR(x[1], 2.0, 1e-14);
  EXPECT_NEAR(x[2], 3.0, 1e-14);
  klu.set_row(0, {0, 1}, {8.0, -2.0});
  klu.set_row(1, {0, 1, 2}, {-2.0, 8.0, -2.0});
  klu.set_row(2, {1, 2}, {-2.0, 8.0});
  ASSERT_TRUE(klu.factorize());
  ASSERT_TRUE(klu.solve(b.data(), x.data()));
  EXPECT_NEAR(x[2], 1.5, 1e-14);
}

// A singular matrix (two equal rows) fails to factorize: a status, no exception.
TEST(Klu, SingularMatrixIsAStatus)
{
  Klu klu;
  klu.start_pattern(2, {2, 2});
  klu.set_row(0, {0, 1}, {1.0, 1.0});
  klu.set_row(1, {0, 1}, {1.0, 1.0});
  ASSERT_TRUE(klu.finish_pattern());
  EXPECT_FALSE(klu.factorize());
}

// After the pattern, a value at a column outside it is not stored: the next
// factorization reports the failure instead.
TEST(Klu, ValueOutsideThePatternFails)
{
  Klu klu;
  tridiagonal(klu, 1.0);
  ASSERT_TRUE(klu.finish_pattern());
  ASSERT_TRUE(klu.factorize());
  klu.set_row(0, {2}, {1.0}); // (0, 2) is not in the pattern
  EXPECT_FALSE(klu.factorize());
  std::vector<double> x(3);
  const std::vector<double> b{1.0, 1.0, 1.0};
  Klu unused;
  EXPECT_FALSE(unused.solve(b.data(), x.data())); // nothing factorized
}
