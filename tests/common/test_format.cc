// The number formatters of messages and scenes (common/format.h) against hand-written strings:
// std::ostream's default, six significant digits, fixed or scientific whichever is shorter.
#include "common/format.h"

#include <gtest/gtest.h>

namespace
{
using namespace ddafem;

TEST(Format, NumbersWithSixSignificantDigits)
{
  EXPECT_EQ(format_number(2.0), "2");
  EXPECT_EQ(format_number(-0.5), "-0.5");
  EXPECT_EQ(format_number(0.0125), "0.0125");
  EXPECT_EQ(format_number(1e-5), "1e-05");
  EXPECT_EQ(format_number(2.5e9), "2.5e+09");
  EXPECT_EQ(format_number(123456.0), "123456");
  EXPECT_EQ(format_number(1234567.0), "1.23457e+06");
  EXPECT_EQ(format_number(1.0 / 3.0), "0.333333");
}

TEST(Format, NumbersWithGivenSignificantDigits)
{
  EXPECT_EQ(format_significant(2.5e10), "2.5e+10");
  EXPECT_EQ(format_significant(1.0 / 3.0), "0.3333");
  EXPECT_EQ(format_significant(1.0 / 3.0, 2), "0.33");
  EXPECT_EQ(format_significant(123456.0), "1.235e+05");
  EXPECT_EQ(format_significant(12.0, 3), "12");
  EXPECT_EQ(format_significant(1.0 / 3.0, 6), format_number(1.0 / 3.0));
}

TEST(Format, TimesAndPoints)
{
  EXPECT_EQ(format_time(0.0125), "0.0125 s");
  EXPECT_EQ(format_time(2e-4), "0.0002 s");
  EXPECT_EQ(format_point(1.5, -2.0), "(1.5, -2)");
  EXPECT_EQ(format_point(0.0, 1e-7), "(0, 1e-07)");
}
} // namespace
