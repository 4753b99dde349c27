// The suggested time step (dda/time_step_advice.h) against numbers computed by hand for a row of
// unit blocks of the paper's rock (rho 2650 kg/m^3, E 50 GPa, nu 0.25).
#include "dda/jointed_block_modulus.h"
#include "dda/time_step_advice.h"
#include "row_of_blocks.h"

#include <gtest/gtest.h>

using namespace ddafem;
using namespace ddafem::dda;

namespace
{
/// n unit blocks in a row with a 1 kN point load of one sine cycle at `frequency` [Hz] (none if
/// 0), integrated by `integrator`.
ModelDescription loaded_row(std::size_t n, double frequency, Integrator integrator)
{
  ModelDescription m = test_models::row_of_blocks(n, 2.5e12);
  if (frequency > 0.0)
    m.point_loads.push_back(
        {{0.5, 0.5}, {1e3, 0.0}, TimeFunction::sine_pulse(1.0, frequency, 1, 0), ""});
  m.time = {1e-4, 0.1, integrator};
  return m;
}
} // namespace

TEST(TimeStepAdvice, WaveSpeedsOfThePapersRock)
{
  const WaveSpeeds c = wave_speeds({"rock", test_models::rho, test_models::young, test_models::nu});
  // sqrt(50e9 * 0.75 / (2650 * 1.25 * 0.5)), sqrt(50e9 / (2650 * 0.9375)), sqrt(50e9 / 2650),
  // sqrt(50e9 / (2 * 2650 * 1.25)).
  EXPECT_NEAR(c.p_body, 4758.3095, 1e-3);
  EXPECT_NEAR(c.p_plate, 4486.1772, 1e-3);
  EXPECT_NEAR(c.p_bar, 4343.7224, 1e-3);
  EXPECT_NEAR(c.s, 2747.2113, 1e-3);
}

TEST(TimeStepAdvice, UnloadedBlocksAskForOneTransitOfTheSmallestBlock)
{
  ModelDescription m = loaded_row(3, 0.0, Integrator::bathe);
  m.blocks[1].vertices = {{1, 0}, {2, 0}, {2, 0.25}, {1, 0.25}}; // 1 m x 0.25 m
  const SmallestBlock small = smallest_block(m.blocks);
  EXPECT_EQ(small.index, 1u);
  EXPECT_DOUBLE_EQ(small.area, 0.25);
  EXPECT_DOUBLE_EQ(small.shortest_edge, 0.25);
  // Plane stress: sqrt(0.25 m^2) / 4486.18 m/s.
  TimeStepAdvice advice = suggest_time_step(m);
  EXPECT_EQ(advice.limit, TimeStepLimit::block_transit);
  EXPECT_NEAR(advice.dt_max, 0.5 * 2.2290693e-4, 1e-12);
  EXPECT_DOUBLE_EQ(advice.dt_min, advice.dt_max / 10.0);
  EXPECT_DOUBLE_EQ(advice.max_frequency, 0.0);
  // Plane strain: the body speed, 0.5 m / 4758.31 m/s.
  m.plane_mode = PlaneMode::strain;
  advice = suggest_time_step(m);
  EXPECT_NEAR(advice.dt_max, 0.5 * 2.1015867e-4, 1e-12);
}

TEST(TimeStepAdvice, FastLoadsAskForTwentyStepsPerPeriod)
{
  // 1 / (20 * 1 kHz) = 5e-5 s, below the transit of 2.229e-4 s.
  const TimeStepAdvice advice = suggest_time_step(loaded_row(20, 1000.0, Integrator::bathe));
  EXPECT_EQ(advice.limit, TimeStepLimit::load_period);
  EXPECT_DOUBLE_EQ(advice.dt_max, 5e-5);
  EXPECT_DOUBLE_EQ(advice.max_frequency, 1000.0);
}

TEST(TimeStepAdvice, DdaIntegratorKeepsItsDampingBelowFivePercent)
{
  // 100 Hz over a 20 m row: T = 20 m / 4486.18 m/s, -4 ln(0.95) / ((200 pi)^2 T) = 1.1658e-4 s,
  // below the transit (2.229e-4 s) and 1 / (20 f) = 5e-4 s. Bathe does not damp: the transit.
  TimeStepAdvice advice = suggest_time_step(loaded_row(20, 100.0, Integrator::dda));
  EXPECT_EQ(advice.limit, TimeStepLimit::dda_damping);
  EXPECT_NEAR(advice.dt_max, 1.16575498e-4, 1e-12);
  advice = suggest_time_step(loaded_row(20, 100.0, Integrator::bathe));
  EXPECT_EQ(advice.limit, TimeStepLimit::block_transit);
  EXPECT_NEAR(advice.dt_max, 2.2290693e-4, 1e-11);
}

TEST(JointedBlockModulus, BlockAndJointInSeries)
{
  // E = 10 GPa, p = 1e10 N/m, a 1 m edge in front of 2 m^2 (d = 2 m):
  // 1 / (1e-10 + 1 / (2 * 1e10 * 2)) = 8 GPa.
  EXPECT_NEAR(jointed_block_modulus(10e9, 1e10, 2.0, 1.0), 8e9, 1e-3);
  // Rigid joints leave the block's modulus.
  EXPECT_DOUBLE_EQ(jointed_block_modulus(10e9, 1e300, 2.0, 1.0), 10e9);
}
