// The block count and the arrangement of a rock mass estimated before they are generated (issue
// 20: a scene too large for memory is refused before its arrangement is built; short traces and
// an opening's fine chords count as edges: CI's fuzzing found them uncounted).
#include "common/input_error.h"
#include "dda/rock_mass.h"
#include "joint_sets.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

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

JointSet short_traces(double dip, double spacing, double trace, double bridge)
{
  JointSet set = persistent_set(dip, spacing, 0.3);
  set.trace_length = trace;
  set.bridge = bridge;
  return set;
}

TEST(RockMassEstimate, ShortTracesAreCountedAsTheyAreInserted)
{
  // Traces of 4 cm with 4 cm bridges every 5 m: 40^2 / (5 x 0.08) = 4000 traces, plus one more
  // per line (8 lines), against the count inserted; they cut 8 % of the lines that cross them,
  // so they add little to the blocks, but each is an edge of the arrangement.
  RockMassDescription d = square_of_40_m();
  d.joint_sets = {persistent_set(30, 4.0, 0.5), short_traces(120, 5.0, 0.04, 0.04)};
  const ArrangementEstimate estimate = estimate_arrangement(d);
  ASSERT_EQ(estimate.traces.size(), 2u);
  const RockMassResult generated = generate_blocks(d);
  const double traces = estimate.traces[0] + estimate.traces[1];
  EXPECT_LT(relative_error(traces, generated.statistics.n_traces), 0.02)
      << traces << " estimated, " << generated.statistics.n_traces << " inserted";
  EXPECT_EQ(estimate.listed, 4.0); // the square's sides
  EXPECT_GT(estimate.edges(), traces);
}

TEST(RockMassEstimate, ShortTracesBeyondTheLimitAreRefusedByTheirPeriod)
{
  // 2 mm traces and bridges: 80,000 traces, 360 MB of arrangement, but about 50 blocks. The
  // refusal names the set's trace_length and a period that brings the whole within 50 MB:
  // (50 MB - 30 MB) / 4.5 kB = 4444 edges, of which the other set's 10 lines and the
  // crossings take some, so at least 0.004 x 80,000 / 4,300 = 0.074 m.
  RockMassDescription d = square_of_40_m();
  d.joint_sets = {persistent_set(30, 4.0, 0.5), short_traces(120, 5.0, 0.002, 0.002)};
  EXPECT_LT(estimate_block_count(d), 100.0);
  const auto refusal = refuse_beyond(d, 0, ResourceLimits{50e6, "50 MB"});
  ASSERT_TRUE(refusal);
  EXPECT_EQ(refusal->key, RockMassTooLarge::Key::trace_length);
  EXPECT_EQ(refusal->joint_set, 1u);
  EXPECT_NE(refusal->message.find("expected a trace_length + bridge of at least 0.07"),
            std::string::npos)
      << refusal->message;
  // The period it asks for fits.
  const double period = 0.075;
  d.joint_sets[1] = short_traces(120, 5.0, 0.5 * period, 0.5 * period);
  EXPECT_FALSE(refuse_beyond(d, 0, ResourceLimits{50e6, "50 MB"}));
}

TEST(RockMassEstimate, OpeningSidesAreCountedWithoutMakingThem)
{
  Opening circle;
  circle.radius = 3.0;
  Opening horseshoe;
  horseshoe.shape = Opening::Shape::horseshoe;
  horseshoe.width = 6.0;
  for (const double wall : {0.0, 2.0})
    for (const double tolerance : {0.02, 1e-4, 1e-6})
    {
      horseshoe.wall_height = wall;
      EXPECT_EQ(opening_side_count(circle, tolerance),
                static_cast<double>(opening_polygon(circle, tolerance).size()));
      EXPECT_EQ(opening_side_count(horseshoe, tolerance),
                static_cast<double>(opening_polygon(horseshoe, tolerance).size()));
    }
  // A tolerance far below rounding asks for infinitely many: counted, not made.
  EXPECT_EQ(opening_side_count(circle, 1e-300), std::numeric_limits<double>::infinity());
  EXPECT_THROW(opening_polygon(circle, 1e-300), InputError);
}

TEST(RockMassEstimate, AnOpeningBeyondTheLimitIsRefusedWithATolerenceThatFits)
{
  // 1e-6 m on a 3 m circle: 3848 chords, 47 MB; 40 MB holds (40 - 30) MB / 4.5 kB = 2222 edges,
  // which a tolerance of 2 r sin^2(pi / (2 x 2222)) = 3.0e-6 m gives.
  Opening circle;
  circle.radius = 3.0;
  const ResourceLimits limits{40e6, "40 MB"};
  const auto refusal = refuse_opening(circle, 1e-6, limits);
  ASSERT_TRUE(refusal);
  EXPECT_NE(refusal->find("its arcs have 3848 sides, which would need"), std::string::npos)
      << *refusal;
  EXPECT_NE(refusal->find("expected a chord_tolerance of at least 3.01e-06 m"), std::string::npos)
      << *refusal;
  EXPECT_FALSE(refuse_opening(circle, 3.02e-6, limits));
  // Without a limit, only beyond the most sides an opening may have (5000: 5.9e-7 m on 3 m).
  EXPECT_FALSE(refuse_opening(circle, 1e-6, ResourceLimits{}));
  const auto too_many = refuse_opening(circle, 1e-8, ResourceLimits{});
  ASSERT_TRUE(too_many);
  EXPECT_NE(too_many->find("its arcs have 38477 sides, more than the 5000 an opening may have"),
            std::string::npos)
      << *too_many;
  EXPECT_NE(too_many->find("expected a chord_tolerance of at least 5.9"), std::string::npos)
      << *too_many;
  EXPECT_TRUE(refuse_opening(circle, 1e-300, ResourceLimits{}));
}

} // namespace
} // namespace ddafem::dda
