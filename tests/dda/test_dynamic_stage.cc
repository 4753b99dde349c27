// Dynamic and settle stages (issue 16): a settle stage runs until every block is at rest or has
// fallen, bounded by its max_duration; checkpoints of a stage in progress (issue 20).
#include "common/checkpoint_archive.h"
#include "dda/dynamic_stage.h"
#include "tests/dda/checkpoint_round_trip.h"
#include "tests/dda/recording_body.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <stdexcept>

using namespace ddafem;
using namespace ddafem::dda;

namespace
{
constexpr double g = 9.81;

/// A fixed 8 m x 1 m base (three fixed points) and a 1 m x 1 m block with its lower left corner
/// at `corner`, frictional joint (30 degrees, `friction` if given), gravity (0, -g) turned by
/// `tilt` [deg] (a slope of that angle along +x).
ModelDescription block_on_base(const Point& corner, double tilt = 0.0, double friction = 30.0)
{
  ModelDescription m;
  m.materials = {{"rock", 2650.0, 10e9, 0.25}};
  m.joint_materials = {{"joint", 1e10, 0.4, friction, 0.0, 0.0, false}};
  m.default_joint_material = 0;
  BlockDescription base;
  base.vertices = {{-4, -1}, {4, -1}, {4, 0}, {-4, 0}};
  m.blocks.push_back(base);
  BlockDescription b;
  b.vertices = {corner, corner + Vector2(1, 0), corner + Vector2(1, 1), corner + Vector2(0, 1)};
  m.blocks.push_back(b);
  for (const Point& x : {Point(-3.5, -0.5), Point(3.5, -0.5), Point(0, -0.5)})
    m.fixed_points.push_back(
        {x, 0.0, TimeFunction::constant(0.0), TimeFunction::constant(0.0), ""});
  const double a = tilt * M_PI / 180.0;
  m.gravity = {g * std::sin(a), -g * std::cos(a)};
  m.time.dt = 1e-3;
  m.time.end_time = 1.0;
  return m;
}

Stage settle_stage(double fall_distance, double max_duration)
{
  Stage s;
  s.name = "settle";
  s.settle = SettleCriterion{1e-3, 0.1, fall_distance, max_duration};
  return s;
}

/// The frictionless 20 degree slope of block_on_base with a block sliding on it and a unit
/// square (block 2) with nothing below it.
ModelDescription slope_and_falling_block()
{
  ModelDescription m = block_on_base({-2.0, 0.0}, 20.0, 0.0);
  BlockDescription debris;
  debris.vertices = {{6, 0}, {7, 0}, {7, 1}, {6, 1}};
  m.blocks.push_back(debris);
  return m;
}

std::vector<Vector2> no_displacement(const System& s)
{
  return std::vector<Vector2>(s.blocks().list.size(), Vector2::Zero());
}
} // namespace

// A unit square turning at w about its centroid: its corners move at w / sqrt(2).
TEST(DynamicStage, BlockSpeedIsTheFastestVertex)
{
  Block b(0, {{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  b.velocity << 0.0, 0.0, 2.0, 0.0, 0.0, 0.0;
  EXPECT_NEAR(block_speed(b), 2.0 * std::sqrt(0.5), 1e-12);
  b.velocity << 0.3, -0.4, 0.0, 0.0, 0.0, 0.0;
  EXPECT_NEAR(block_speed(b), 0.5, 1e-12);
}

// A block set down on a flat base rings on its contact springs and comes to rest: the stage
// ends once it has been slower than 1 mm/s for 0.1 s, long before its bound.
TEST(DynamicStage, BlockOnFlatBaseSettles)
{
  const ModelDescription m = block_on_base({-0.5, 0.0});
  System s(m);
  s.begin_stage(StageMode::dynamic);
  const DynamicStageResult r =
      run_dynamic_stage(s, settle_stage(0.0, 2.0), m.time, no_displacement(s));
  EXPECT_EQ(r.failure.outcome, StepOutcome::success) << r.failure.message;
  EXPECT_TRUE(r.settled);
  EXPECT_TRUE(r.moving.empty());
  EXPECT_TRUE(r.fallen.empty());
  EXPECT_GE(s.time(), 0.1 - 1e-9); // at least rest_duration
  EXPECT_LT(s.time(), 0.5);
  EXPECT_EQ(r.n_steps, s.n_steps());
}

// On a frictionless 20 degree slope the block slides on: without a fall distance the stage runs
// to its bound and says which block still moves and how fast, g sin 20 t at t = 0.3 s.
TEST(DynamicStage, SlidingBlockRunsToTheBound)
{
  const ModelDescription m = block_on_base({-2.0, 0.0}, 20.0, 0.0);
  System s(m);
  s.begin_stage(StageMode::dynamic);
  const DynamicStageResult r =
      run_dynamic_stage(s, settle_stage(0.0, 0.3), m.time, no_displacement(s));
  EXPECT_EQ(r.failure.outcome, StepOutcome::success) << r.failure.message;
  EXPECT_FALSE(r.settled);
  EXPECT_NEAR(s.time(), 0.3, 1e-9);
  EXPECT_NEAR(r.end_time, 0.3, 1e-12);
  ASSERT_EQ(r.moving, std::vector<std::size_t>{1});
  const double v = g * std::sin(20.0 * M_PI / 180.0) * 0.3;
  EXPECT_NEAR(r.moving_speed, v, 0.02 * v);
}

// The same slope with the sliding block tied to a body (one that carries nothing, so it slides
// as before): a tied block moves as the body does and is not judged, so the stage ends once the
// base has rested for 0.1 s.
TEST(DynamicStage, TiedBlocksAreNotJudged)
{
  const ModelDescription m = block_on_base({-2.0, 0.0}, 20.0, 0.0);
  System s(m);
  test_models::RecordingBody body;
  s.tie(body, {{1, Point(-2.0, 0.5), Point(-2.0, 0.5)}}); // its left edge
  s.begin_stage(StageMode::dynamic);
  const DynamicStageResult r =
      run_dynamic_stage(s, settle_stage(0.0, 0.3), m.time, no_displacement(s));
  EXPECT_EQ(r.failure.outcome, StepOutcome::success) << r.failure.message;
  EXPECT_TRUE(r.settled);
  EXPECT_TRUE(r.moving.empty());
  EXPECT_GE(s.time(), 0.1 - 1e-9);                 // rest_duration
  EXPECT_LT(s.time(), 0.15);                       // long before the bound
  EXPECT_GT(block_speed(s.blocks().list[1]), 0.3); // still sliding: g sin 20 x 0.1 s = 0.34 m/s
}

// A block with nothing below falls; once its centroid is 0.1 m lower it has fallen and is not
// waited for: the stage ends at sqrt(2 x 0.1 / g) = 0.143 s (the base, fixed, rests from 0.1 s).
TEST(DynamicStage, FallenBlockIsNotWaitedFor)
{
  const ModelDescription m = block_on_base({6.0, 0.0});
  System s(m);
  s.begin_stage(StageMode::dynamic);
  const DynamicStageResult r =
      run_dynamic_stage(s, settle_stage(0.1, 2.0), m.time, no_displacement(s));
  EXPECT_EQ(r.failure.outcome, StepOutcome::success) << r.failure.message;
  EXPECT_TRUE(r.settled);
  EXPECT_EQ(r.fallen, std::vector<std::size_t>{1});
  EXPECT_TRUE(r.moving.empty());
  EXPECT_NEAR(s.time(), std::sqrt(2.0 * 0.1 / g), 2e-3); // within two steps
}

// The frictionless 20 degree slope keeps the stage going while a second block falls with
// nothing below. With remove_fallen it is removed as debris once it has left its place: along
// gravity (20 degrees off the vertical) the unit square is cos 20 + sin 20 = 1.282 m wide, so
// it goes when it has fallen that far, at sqrt(2 x 1.282 / g) = 0.511 s, taking its kinetic
// energy m g 1.282 m with it (EnergyBalance::removed), and stays there, still, to the end.
TEST(DynamicStage, FallenBlockIsRemovedOnceOutOfPlace)
{
  const ModelDescription m = slope_and_falling_block();
  System s(m);
  s.begin_stage(StageMode::dynamic);
  Stage stage = settle_stage(0.5, 0.6); // the slider moves 0.2 m along gravity by 0.6 s
  stage.settle->remove_fallen = true;
  const DynamicStageResult r = run_dynamic_stage(s, stage, m.time, no_displacement(s));
  EXPECT_EQ(r.failure.outcome, StepOutcome::success) << r.failure.message;
  EXPECT_FALSE(r.settled); // the slider slides to the bound
  ASSERT_EQ(r.removed.size(), 1u);
  EXPECT_EQ(r.removed[0].first, 2u);
  const double width = std::cos(20.0 * M_PI / 180.0) + std::sin(20.0 * M_PI / 180.0);
  const double t_out = std::sqrt(2.0 * width / g);
  EXPECT_GE(r.removed[0].second, t_out - 1e-9);
  EXPECT_LT(r.removed[0].second, t_out + 2e-3); // the step that takes it there
  const double t_r = r.removed[0].second, mass = 2650.0;
  EXPECT_NEAR(s.energy().removed, 0.5 * mass * g * g * t_r * t_r, 1e-3 * mass * g * width);
  const Block& b = s.blocks().list[2];
  EXPECT_TRUE(s.blocks().is_removed(2));
  EXPECT_EQ(b.velocity.norm(), 0.0);
  EXPECT_NEAR(b.displacement().norm(), 0.5 * g * t_r * t_r, 1e-6);
  EXPECT_NEAR(s.time(), 0.6, 1e-9);
}

// Without remove_fallen the same block falls on to the bound.
TEST(DynamicStage, FallenBlockIsKeptWithoutRemoveFallen)
{
  const ModelDescription m = slope_and_falling_block();
  System s(m);
  s.begin_stage(StageMode::dynamic);
  const DynamicStageResult r =
      run_dynamic_stage(s, settle_stage(0.5, 0.6), m.time, no_displacement(s));
  EXPECT_EQ(r.failure.outcome, StepOutcome::success) << r.failure.message;
  EXPECT_TRUE(r.removed.empty());
  EXPECT_FALSE(s.blocks().is_removed(2));
  EXPECT_NEAR(s.blocks().list[2].displacement().norm(), 0.5 * g * 0.36, 1e-3);
  EXPECT_EQ(s.energy().removed, 0.0);
}

/// A dynamic stage "shake" without settle, to 0.05 s.
Stage shake_stage()
{
  Stage stage;
  stage.name = "shake";
  stage.end_time = 0.05;
  return stage;
}

// A dynamic stage without settle runs to its end_time.
TEST(DynamicStage, DynamicStageRunsToItsEnd)
{
  const ModelDescription m = block_on_base({-0.5, 0.0});
  System s(m);
  s.begin_stage(StageMode::dynamic);
  const Stage stage = shake_stage();
  std::size_t calls = 0;
  bool last_seen = false;
  const DynamicStageResult r =
      run_dynamic_stage(s, stage, m.time, no_displacement(s),
                        [&](const TimeStepper&, const StepStatus&, bool last)
                        {
                          ++calls;
                          last_seen = last;
                          return true;
                        });
  EXPECT_NEAR(s.time(), 0.05, 1e-12);
  // The callback sees every step; n_steps counts the System's steps, two per step of the default
  // composite scheme (bathe).
  EXPECT_EQ(2 * calls, r.n_steps);
  EXPECT_TRUE(last_seen);
  EXPECT_FALSE(r.settled);
  EXPECT_FALSE(r.stopped);
}

TEST(DynamicStage, StopsWhereTheCallerAsks)
{
  // A budget: the callback returns false after the third step; the stage ends there, before its
  // end time, as stopped (not failed).
  const ModelDescription m = block_on_base({-0.5, 0.0});
  System s(m);
  s.begin_stage(StageMode::dynamic);
  std::size_t calls = 0;
  const DynamicStageResult r =
      run_dynamic_stage(s, shake_stage(), m.time, no_displacement(s),
                        [&](const TimeStepper&, const StepStatus&, bool) { return ++calls < 3; });
  EXPECT_EQ(calls, 3u);
  EXPECT_TRUE(r.stopped);
  EXPECT_EQ(r.failure.outcome, StepOutcome::success);
  EXPECT_LT(s.time(), 0.05);
  EXPECT_EQ(2 * calls, r.n_steps);
}

namespace
{
/// What a settle stage leaves of the blocks, every bit of it.
std::vector<double> final_state(const System& s)
{
  std::vector<double> x = {s.time(), s.energy().kinetic, s.energy().dissipated};
  for (const Block& b : s.blocks().list)
  {
    x.insert(x.end(), b.velocity.data(), b.velocity.data() + 6);
    x.insert(x.end(), b.acceleration.data(), b.acceleration.data() + 6);
    x.insert(x.end(), b.stress.data(), b.stress.data() + 3);
    for (const Point& v : b.vertices)
      x.insert(x.end(), {v.x(), v.y()});
  }
  for (const Contact& c : s.contacts().accepted)
    x.insert(x.end(), {static_cast<double>(c.id), c.forces.normal_force, c.forces.shear_force,
                       c.total_slip});
  return x;
}
} // namespace

// Checkpoints (issue 20): a settle stage on the slope (a block sliding, one falling and removed
// as debris) stopped after 40 steps and saved, then loaded into a System and a stage built anew
// from the same model, ends exactly as the stage that was never stopped: the same steps, removed
// blocks and every bit of the blocks' and contacts' state.
TEST(DynamicStage, ACheckpointedStageGoesOnBitForBit)
{
  const ModelDescription m = slope_and_falling_block();
  Stage stage = settle_stage(0.5, 0.6);
  stage.settle->remove_fallen = true;

  System whole(m);
  whole.begin_stage(StageMode::dynamic);
  const DynamicStageResult uninterrupted =
      run_dynamic_stage(whole, stage, m.time, no_displacement(whole));

  System first(m);
  first.begin_stage(StageMode::dynamic);
  DynamicStageRun first_run(first, stage, m.time, no_displacement(first));
  std::size_t calls = 0;
  first_run.run([&](const TimeStepper&, const StepStatus&, bool) { return ++calls < 40; });
  System resumed(m);
  DynamicStageRun resumed_run(resumed, stage, m.time, no_displacement(first));
  round_trip(first, first_run, resumed, resumed_run);
  const DynamicStageResult r = resumed_run.run();

  EXPECT_EQ(r.n_steps, uninterrupted.n_steps);
  EXPECT_EQ(r.removed, uninterrupted.removed);
  EXPECT_EQ(r.fallen, uninterrupted.fallen);
  EXPECT_EQ(r.settled, uninterrupted.settled);
  EXPECT_EQ(resumed.n_steps(), whole.n_steps());
  ASSERT_FALSE(uninterrupted.removed.empty()); // the debris was removed after the checkpoint
  EXPECT_GT(uninterrupted.removed.front().second, 40 * 2 * m.time.dt);
  EXPECT_EQ(final_state(resumed), final_state(whole));
}

// A checkpoint of another model is refused, naming what differs, instead of being restored.
TEST(DynamicStage, ACheckpointOfAnotherModelIsRefused)
{
  const ModelDescription m = slope_and_falling_block();
  System saved(m);
  std::stringstream text;
  {
    CheckpointOut archive(text);
    saved.save(archive);
  }
  System other(block_on_base({-0.5, 0.0}));
  CheckpointIn archive(text);
  try
  {
    other.load(archive);
    FAIL() << "a checkpoint of 3 blocks loaded into 2";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_NE(std::string(e.what()).find("3 blocks saved, the scene has 2"), std::string::npos)
        << e.what();
  }
}
