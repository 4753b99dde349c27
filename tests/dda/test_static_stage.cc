// Static stages (issue 16): equilibrium judged per block against its own load, and blocks that
// cannot be in equilibrium released rather than reported as a failure; checkpoints of a stage in
// progress (issue 20).
#include "dda/static_stage.h"
#include "tests/dda/checkpoint_round_trip.h"
#include "tests/dda/step_parts.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace ddafem;
using namespace ddafem::dda;

namespace
{
constexpr double g = 9.81;

/// A fixed 8 m x 1 m base (three fixed points) and unit blocks of the given materials with their
/// lower left corners at `corners`, all with frictional (unbonded) joints. Materials: 0 rock
/// (base), 1 "slippery" (friction angle 0 against rock), 2 "rough" (45 degrees against rock);
/// the default joint material (30 degrees) acts between every other pair.
ModelDescription blocks_on_base(const std::vector<std::pair<std::size_t, Point>>& blocks)
{
  ModelDescription m;
  m.materials = {{"rock", 2650.0, 10e9, 0.25},
                 {"slippery", 2650.0, 10e9, 0.25},
                 {"rough", 2650.0, 10e9, 0.25}};
  m.joint_materials = {{"joint", 1e10, 0.4, 30.0, 0.0, 0.0, false},
                       {"frictionless", 1e10, 0.4, 0.0, 0.0, 0.0, false},
                       {"steep", 1e10, 0.4, 45.0, 0.0, 0.0, false}};
  m.default_joint_material = 0;
  m.joint_assignments = {{0, 1, 1}, {0, 2, 2}};
  BlockDescription base;
  base.vertices = {{-4, -1}, {4, -1}, {4, 0}, {-4, 0}};
  m.blocks.push_back(base);
  for (const auto& [material, c] : blocks)
  {
    BlockDescription b;
    b.material = material;
    b.vertices = {c, c + Vector2(1, 0), c + Vector2(1, 1), c + Vector2(0, 1)};
    m.blocks.push_back(b);
  }
  for (const Point& x : {Point(-3.5, -0.5), Point(3.5, -0.5), Point(0, -0.5)})
    m.fixed_points.push_back(
        {x, 0.0, TimeFunction::constant(0.0), TimeFunction::constant(0.0), ""});
  m.time.dt = 1e-3;
  m.time.end_time = 1.0;
  return m;
}

Stage static_stage(double tolerance, ReleaseAction release = ReleaseAction::fall)
{
  Stage s;
  s.name = "settle";
  s.mode = StageMode::static_equilibrium;
  s.dt = 1e-3;
  s.max_steps = 3000;
  s.tolerance = tolerance;
  s.release = release;
  return s;
}

/// Gravity tilted by 30 degrees: a slope of 30 degrees along +x.
Vector2 slope_gravity()
{
  const double b = 30.0 * M_PI / 180.0;
  return {g * std::sin(b), -g * std::cos(b)};
}
} // namespace

// A block on a frictionless 30 degree slope cannot be in equilibrium: it is released (held
// where it is) and the stage reaches equilibrium for the block beside it (friction 45 degrees,
// stable) and the base.
TEST(StaticStage, BlockOnFrictionlessSlopeIsReleasedAndTheRestConverges)
{
  ModelDescription m = blocks_on_base({{2, Point(-2.5, 0)}, {1, Point(0.5, 0)}});
  m.gravity = slope_gravity();
  System s(m);
  const StaticStageResult r = run_static_stage(s, static_stage(1e-6), m.time);
  std::cout << "slope: " << r.n_steps << " steps, ratio " << r.ratio << ", released "
            << r.released.size() << "\n";
  ASSERT_EQ(r.outcome, StaticOutcome::equilibrium);
  ASSERT_EQ(r.released.size(), 1u);
  EXPECT_EQ(r.released[0].block, 2u);
  EXPECT_NEAR(r.released[0].mass, 2650.0, 1e-9);
  // On a frictionless slope the resultant is W sin b and the load W + W cos b.
  const double b = 30.0 * M_PI / 180.0;
  EXPECT_NEAR(r.released[0].ratio, std::sin(b) / (1.0 + std::cos(b)), 0.02);
  EXPECT_TRUE(s.blocks().is_held(2));
  EXPECT_FALSE(s.blocks().is_held(1));
  EXPECT_LE(s.block_balances()[1].ratio(), 1e-6);
  // Released after about one window: it has barely moved.
  // The first window ends as the contacts take up the slope's normal share of the weight (the
  // resultant drops from W to W sin b); the second one releases it.
  EXPECT_LE(r.released[0].step, 2 * ReleaseCriterion().window);
  EXPECT_LT(s.blocks().list[2].displacement().norm(), 1e-3);

  // In the dynamic stage it is free again and slides down the slope at g sin b.
  s.begin_stage(StageMode::dynamic);
  EXPECT_FALSE(s.blocks().is_held(2));
  const double x0 = s.blocks().list[2].moments.centroid.x();
  for (std::size_t k = 0; k < 100; ++k)
    ASSERT_EQ(s.advance(1e-3, step_parts::of_call(s, k)).outcome, StepOutcome::success);
  const double slid = s.blocks().list[2].moments.centroid.x() - x0;
  EXPECT_NEAR(slid, 0.5 * g * std::sin(b) * 0.1 * 0.1, 0.05 * 0.5 * g * std::sin(b) * 0.01);
}

// `release: remove`: the block becomes inert, with no contacts, and stays where it was.
TEST(StaticStage, RemovedBlockIsInertForTheRestOfTheRun)
{
  ModelDescription m = blocks_on_base({{2, Point(-2.5, 0)}, {1, Point(0.5, 0)}});
  m.gravity = slope_gravity();
  System s(m);
  const StaticStageResult r =
      run_static_stage(s, static_stage(1e-6, ReleaseAction::remove), m.time);
  ASSERT_EQ(r.outcome, StaticOutcome::equilibrium);
  ASSERT_EQ(r.released.size(), 1u);
  EXPECT_TRUE(s.blocks().is_removed(2));
  s.begin_stage(StageMode::dynamic);
  const Point c = s.blocks().list[2].moments.centroid;
  for (std::size_t k = 0; k < 100; ++k)
    ASSERT_EQ(s.advance(1e-3, step_parts::of_call(s, k)).outcome, StepOutcome::success);
  EXPECT_LT((s.blocks().list[2].moments.centroid - c).norm(), 1e-9);
  for (const Contact& contact : s.contacts().accepted)
    EXPECT_TRUE(contact.vertex_block != 2 && contact.edge_block != 2);
}

// A block in the air under a fixed roof falls freely: ratio 1, released after one window.
TEST(StaticStage, FreeBlockIsReleasedWithRatioOne)
{
  ModelDescription m = blocks_on_base({{0, Point(-0.5, 0)}, {0, Point(2, 3)}});
  m.gravity = Vector2(0, -g);
  System s(m);
  const StaticStageResult r = run_static_stage(s, static_stage(1e-6), m.time);
  ASSERT_EQ(r.outcome, StaticOutcome::equilibrium);
  ASSERT_EQ(r.released.size(), 1u);
  EXPECT_EQ(r.released[0].block, 2u);
  EXPECT_NEAR(r.released[0].ratio, 1.0, 1e-9);
  EXPECT_EQ(r.released[0].step, ReleaseCriterion().window);
}

// A stack of three blocks on the base converges without releases.
TEST(StaticStage, StableStackConvergesWithoutReleases)
{
  ModelDescription m =
      blocks_on_base({{0, Point(-0.5, 0)}, {0, Point(-0.4, 1)}, {0, Point(-0.6, 2)}});
  m.gravity = Vector2(0, -g);
  System s(m);
  const StaticStageResult r = run_static_stage(s, static_stage(1e-7), m.time);
  std::cout << "stack: " << r.n_steps << " steps, ratio " << r.ratio << "\n";
  ASSERT_EQ(r.outcome, StaticOutcome::equilibrium);
  EXPECT_TRUE(r.released.empty());
  for (std::size_t i = 0; i < s.blocks().list.size(); ++i)
  {
    const BlockBalance& b = s.block_balances()[i];
    EXPECT_LE(b.ratio(), 1e-7) << "block " << i;
    EXPECT_LE(b.out_of_balance.norm(), b.load) << "block " << i;
    EXPECT_GE(b.load, b.weight) << "block " << i;
  }
  // The bottom block carries the two above: its load is its weight, the contact forces of the
  // base (3 W) and of the block above (2 W), 6 W.
  const BlockBalance& bottom = s.block_balances()[1];
  EXPECT_NEAR(bottom.load / bottom.weight, 6.0, 0.05);
}

// Equilibrium per block: a light block (1e-6 of the heavy one's density) starts 0.1 mm above the
// base beside a heavy block that rests on it. Against the heaviest block's weight the light
// block's whole weight is out of balance by only 1e-6: a tolerance of 1e-5 passes as soon as the
// heavy block has settled (about 10 steps), with the light one still in the air. Against its
// own load it is in free fall (ratio 1) until it lands (0.5 g dt^2 = 4.9 um per step: about 20
// steps, less than a release window) and settles.
TEST(StaticStage, LightBlockIsJudgedAgainstItsOwnLoad)
{
  ModelDescription m = blocks_on_base({{0, Point(-2, 0)}, {1, Point(1, 1e-4)}});
  m.materials[0].density = 2650.0;
  m.materials[1].density = 2650e-6;
  m.joint_assignments.clear(); // every pair 30 degrees
  m.gravity = Vector2(0, -g);
  System s(m);
  const StaticStageResult r = run_static_stage(s, static_stage(1e-5), m.time);
  std::cout << "heavy and light: " << r.n_steps << " steps, ratio " << r.ratio << "\n";
  ASSERT_EQ(r.outcome, StaticOutcome::equilibrium);
  EXPECT_TRUE(r.released.empty());
  EXPECT_GT(r.n_steps, 20u);
  const BlockBalance& light = s.block_balances()[2];
  const BlockBalance& heavy = s.block_balances()[1];
  EXPECT_NEAR(heavy.weight / light.weight, 1e6, 1e-3);
  EXPECT_LE(light.out_of_balance.norm(), 1e-5 * light.load);
  // It landed: its weight rests on the base (penalty penetration W / p at most).
  EXPECT_LT(s.blocks().list[2].moments.centroid.y(), 0.5 + 1e-9);
  EXPECT_GT(light.load, 1.9 * light.weight);
}

// Checkpoints (issue 20): the slope's static stage stopped after 30 steps (before the release,
// inside the detector's first window) and saved, then loaded into a System and a stage built
// anew, ends as the stage that was never stopped: the same steps, the same released block at
// the same step, every bit of the blocks' state the same.
TEST(StaticStage, ACheckpointedStageGoesOnBitForBit)
{
  ModelDescription m = blocks_on_base({{2, Point(-2.5, 0)}, {1, Point(0.5, 0)}});
  m.gravity = slope_gravity();
  const Stage stage = static_stage(1e-6);

  System whole(m);
  const StaticStageResult uninterrupted = run_static_stage(whole, stage, m.time);

  System first(m);
  first.begin_stage(StageMode::static_equilibrium);
  StaticStageRun first_run(first, stage, m.time);
  std::size_t calls = 0;
  first_run.run([&] { return ++calls < 30; });
  System resumed(m);
  StaticStageRun resumed_run(resumed, stage, m.time);
  round_trip(first, first_run, resumed, resumed_run);
  const StaticStageResult r = resumed_run.run();

  ASSERT_EQ(uninterrupted.released.size(), 1u);
  EXPECT_GT(uninterrupted.released[0].step, 30u);
  EXPECT_EQ(r.outcome, uninterrupted.outcome);
  EXPECT_EQ(r.n_steps, uninterrupted.n_steps);
  ASSERT_EQ(r.released.size(), 1u);
  EXPECT_EQ(r.released[0].step, uninterrupted.released[0].step);
  EXPECT_EQ(r.ratio, uninterrupted.ratio);
  for (std::size_t i = 0; i < whole.blocks().list.size(); ++i)
  {
    EXPECT_EQ(resumed.blocks().list[i].vertices, whole.blocks().list[i].vertices);
    EXPECT_EQ(resumed.blocks().list[i].stress, whole.blocks().list[i].stress);
  }
}
