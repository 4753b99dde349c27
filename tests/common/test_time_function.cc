// Time functions (common/time_function.h) against values worked out by hand: a constant, an
// n-cycle sine pulse that is zero outside its cycles, a piecewise-linear table that holds its end
// values, and what each reports of itself (end of activity, highest frequency, description).
#include "common/time_function.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{
using ddafem::TimeFunction;

TEST(TimeFunction, DefaultIsOneAndConstantIsItsValue)
{
  EXPECT_EQ(TimeFunction().value(3.0), 1.0);
  const TimeFunction c = TimeFunction::constant(-2.5);
  EXPECT_EQ(c.value(0.0), -2.5);
  EXPECT_EQ(c.value(1e6), -2.5);
  EXPECT_EQ(c.active_until(), 0.0);
  EXPECT_EQ(c.characteristic_frequency(), 0.0);
  EXPECT_EQ(c.describe(), "constant -2.5");
}

TEST(TimeFunction, SinePulseIsZeroOutsideItsCycles)
{
  // 2 cycles of 10 Hz from t = 0.05 s, amplitude 3: the pulse lasts 0.2 s, to 0.25 s.
  const TimeFunction f = TimeFunction::sine_pulse(3.0, 10.0, 2.0, 0.05);
  EXPECT_EQ(f.value(0.0), 0.0);
  EXPECT_EQ(f.value(0.049), 0.0);
  EXPECT_NEAR(f.value(0.05), 0.0, 1e-15);
  EXPECT_NEAR(f.value(0.075), 3.0, 1e-12);  // a quarter period in: the crest
  EXPECT_NEAR(f.value(0.125), -3.0, 1e-12); // three quarters: the trough
  EXPECT_NEAR(f.value(0.05 + 1.0 / 12.0), 3.0 * std::sin(2.0 * M_PI * 10.0 / 12.0), 1e-12);
  EXPECT_EQ(f.value(0.2501), 0.0);
  EXPECT_DOUBLE_EQ(f.active_until(), 0.25);
  EXPECT_EQ(f.characteristic_frequency(), 10.0);
  EXPECT_EQ(f.describe(), "sine pulse 10 Hz x 2 cycle(s), amplitude 3, start 0.05 s");
}

TEST(TimeFunction, TableInterpolatesLinearlyAndHoldsItsEnds)
{
  // Points (0, 1), (0.1, 3), (0.3, -1): slopes 20 /s and -20 /s.
  const TimeFunction f = TimeFunction::table({0.0, 0.1, 0.3}, {1.0, 3.0, -1.0});
  EXPECT_EQ(f.value(-1.0), 1.0);
  EXPECT_EQ(f.value(0.0), 1.0);
  EXPECT_NEAR(f.value(0.025), 1.5, 1e-12);
  EXPECT_NEAR(f.value(0.1), 3.0, 1e-12);
  EXPECT_NEAR(f.value(0.2), 1.0, 1e-12);
  EXPECT_EQ(f.value(0.3), -1.0);
  EXPECT_EQ(f.value(5.0), -1.0);
  EXPECT_EQ(f.active_until(), 0.3);
  // The shortest interval, 0.1 s, sets the highest frequency the table can carry.
  EXPECT_DOUBLE_EQ(f.characteristic_frequency(), 10.0);
  EXPECT_EQ(f.describe(), "table of 3 points, 0 to 0.3 s");
}

TEST(TimeFunction, OnePointTableIsAConstantFromItsTime)
{
  const TimeFunction f = TimeFunction::table({0.5}, {4.0});
  EXPECT_EQ(f.value(0.0), 4.0);
  EXPECT_EQ(f.value(1.0), 4.0);
  EXPECT_EQ(f.active_until(), 0.5);
  EXPECT_EQ(f.characteristic_frequency(), 0.0);
}
} // namespace
