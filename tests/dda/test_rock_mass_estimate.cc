// The block count of a rock mass estimated before it is generated (issue 20: a scene too large
// for memory is refused before its arrangement is built).
#include "dda/rock_mass.h"
#include "joint_sets.h"

#include <gtest/gtest.h>

#include <cmath>

namespace ddafem::dda
{
namespace
{
using test_models::persistent_set;

RockMassDescription square_of_40_m()
{
  RockMassDescription d;
  d.region = {Point(-20, -20), Point(20, -20), Point(20, 20), Point(-20, 20)};
  return d;
}

double relative_error(double estimate, std::size_t generated)
{
  return std::abs(estimate / static_cast<double>(generated) - 1.0);
}

TEST(RockMassEstimate, TwoPersistentSetsWithinTwoPercent)
{
  // Sets at 30 and 120 deg every 0.5 m: 40^2 / 0.25 = 6400 crossings, a face each.
  RockMassDescription d = square_of_40_m();
  d.joint_sets = {persistent_set(30, 0.5, 0.1), persistent_set(120, 0.5, 0.2)};
  const std::size_t generated = generate_blocks(d).blocks.size();
  EXPECT_LT(relative_error(estimate_block_count(d), generated), 0.02)
      << estimate_block_count(d) << " estimated, " << generated << " generated";
}

TEST(RockMassEstimate, NonPersistentAndThreeSetsNotFarBelow)
{
  // The rock-mass example's sets at 0.5 m: one persistent, one of 12 m traces and 3 m bridges
  // (persistence 0.8), within 5 %; and a third set at 75 deg, 1 m apart: three sets cross near
  // one another where the estimate counts a face per crossing, and the slivers between them are
  // merged into their neighbours (11 % fewer blocks). An estimate above the count refuses a
  // little early; one far below would let memory run out.
  RockMassDescription d = square_of_40_m();
  JointSet bridged = persistent_set(120, 0.5, 0.3);
  bridged.trace_length = 12.0;
  bridged.bridge = 3.0;
  d.joint_sets = {persistent_set(30, 0.5, 0.5), bridged};
  std::size_t generated = generate_blocks(d).blocks.size();
  EXPECT_LT(relative_error(estimate_block_count(d), generated), 0.05)
      << estimate_block_count(d) << " estimated, " << generated << " generated";
  d.joint_sets.push_back(persistent_set(75, 1.0, 0.4));
  generated = generate_blocks(d).blocks.size();
  EXPECT_LT(relative_error(estimate_block_count(d), generated), 0.15)
      << estimate_block_count(d) << " estimated, " << generated << " generated";
  EXPECT_GT(estimate_block_count(d), static_cast<double>(generated));
}

TEST(RockMassEstimate, CloseSpacingIsCountedWithoutGeneratingIt)
{
  // What the refusal relies on: at 1 cm in a 40 m square, A / s^2 = 1.6e7 blocks (the traces
  // add 0.05 %), estimated at once; the refusal's "a spacing of at least" scales it as 1 / s^2.
  RockMassDescription d = square_of_40_m();
  d.joint_sets = {persistent_set(0, 0.01), persistent_set(90, 0.01)};
  EXPECT_NEAR(estimate_block_count(d), 1.6e7, 0.001 * 1.6e7);
}

} // namespace
} // namespace ddafem::dda
