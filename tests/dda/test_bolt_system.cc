// Bolts in the step (issue 21): a block hanging on an end-anchored bolt from a fixed block.
//
// The model: a fixed 4 m x 1 m block (top, y 2 to 3) and a 1 m x 1 m block (y 0 to 1) below it,
// 1 m apart (no contact); a vertical bolt from the hanging block's centre (0, 0.5) to (0, 2.5)
// in the fixed block: L0 = 2 m, A_s = 1e-4 m^2, E_s = 200e9 Pa, so k = E_s A_s / L0 = 1e7 N/m.
// The block weighs W = 2650 x 9.81 = 25 996.5 N, so it hangs W / k = 2.59965 mm lower.
#include "common/input_error.h"
#include "dda/bolt.h"
#include "dda/dynamic_stage.h"
#include "dda/static_stage.h"
#include "tests/dda/checkpoint_round_trip.h"
#include "tests/dda/hanging_block_model.h"
#include "tests/dda/hanging_static_stage.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace ddafem;
using namespace ddafem::dda;

namespace
{
constexpr double g = 9.81;
constexpr double weight = 2650.0 * g; // [N]
constexpr double stiffness = 1e7;     // [N/m]

ModelDescription hanging_block(double yield_force, double pretension = 0.0)
{
  ModelDescription m = block_below_fixed_block(2.0);
  BoltDescription b;
  b.name = "bolt";
  b.head = {0.0, 0.5};
  b.anchor = {0.0, 2.5};
  b.area = 1e-4;
  b.yield_force = yield_force;
  b.pretension = pretension;
  b.origin = "bolts[0]";
  m.bolts.push_back(b);
  return m;
}

std::vector<Vector2> no_displacement(const System& s)
{
  return std::vector<Vector2>(s.blocks().list.size(), Vector2::Zero());
}
} // namespace

// The static stage settles the block into its bolt: N = W, and the block's sag is W / k (the
// fixed block, on three fixed points of 1e11 N/m, moves by 5 W / 3e11 = 4.3e-7 m, 1.7e-4 of it).
TEST(BoltSystem, StaticStageHangsTheBlockOnItsBolt)
{
  System s(hanging_block(2.0 * weight));
  ASSERT_EQ(s.elements<Bolts>().all().size(), 1u);
  EXPECT_EQ(s.elements<Bolts>().all()[0].head.block, 1u);
  EXPECT_EQ(s.elements<Bolts>().all()[0].anchor.block, 0u);
  EXPECT_DOUBLE_EQ(s.elements<Bolts>().all()[0].law.stiffness, stiffness);
  s.begin_stage(StageMode::static_equilibrium);
  const StaticStageResult r = run_static_stage(s, hanging_static_stage(), s.get_model().time);
  ASSERT_EQ(r.outcome, StaticOutcome::equilibrium);
  const Bolt& b = s.elements<Bolts>().all()[0];
  EXPECT_EQ(b.forces.state, BoltState::elastic);
  EXPECT_NEAR(b.forces.axial_force / weight, 1.0, 1e-6);
  const double sag = -s.sample_monitor(0).displacement.y();
  EXPECT_NEAR(sag / (weight / stiffness), 1.0, 1e-3);
  // The springs' energy: the bolt's N^2 / (2 k) = 33.8 J and the fixed points', which carry W
  // and the fixed block's own weight 4 W, translating together: (5 W)^2 / (2 x 3 K) = 0.028 J.
  const double fixed = 3.0 * s.points().default_stiffness;
  const double expected =
      weight * weight / (2.0 * stiffness) + 25.0 * weight * weight / (2.0 * fixed);
  EXPECT_NEAR(s.energy().spring / expected, 1.0, 2e-5);
}

// With pretension P the bolt stretches by (W - P) / k only.
TEST(BoltSystem, PretensionTakesPartOfTheSag)
{
  System s(hanging_block(2.0 * weight, 0.5 * weight));
  s.begin_stage(StageMode::static_equilibrium);
  ASSERT_EQ(run_static_stage(s, hanging_static_stage(), s.get_model().time).outcome,
            StaticOutcome::equilibrium);
  const Bolt& b = s.elements<Bolts>().all()[0];
  EXPECT_NEAR(b.forces.axial_force / weight, 1.0, 1e-6);
  EXPECT_NEAR((b.length() - b.law.free_length) / (0.5 * weight / stiffness), 1.0, 1e-3);
}

// Below the block's weight the bolt yields, stretches to its rupture strain (0.2 m) and breaks:
// the block, in free fall then, is released.
TEST(BoltSystem, TooWeakABoltYieldsRupturesAndReleasesTheBlock)
{
  System s(hanging_block(0.98 * weight));
  s.begin_stage(StageMode::static_equilibrium);
  const StaticStageResult r = run_static_stage(s, hanging_static_stage(), s.get_model().time);
  const Bolt& b = s.elements<Bolts>().all()[0];
  EXPECT_EQ(b.forces.state, BoltState::ruptured);
  EXPECT_EQ(b.forces.axial_force, 0.0);
  EXPECT_NEAR(b.record.max_force, 0.98 * weight, 1e-6 * weight);
  EXPECT_GT(b.record.max_elongation, 0.2);
  EXPECT_FALSE(std::isnan(b.record.yield_time));
  EXPECT_FALSE(std::isnan(b.record.rupture_time));
  ASSERT_EQ(r.released.size(), 1u);
  EXPECT_EQ(r.released[0].block, 1u);
}

// Released from rest on a bolt at its free length, the block swings about W / k with amplitude
// W / k: the bolt's force peaks at 2 W half a period (pi sqrt(m / k) = 51 ms) later.
TEST(BoltSystem, SuddenlyLoadedBoltPeaksAtTwiceTheWeight)
{
  System s(hanging_block(3.0 * weight));
  s.begin_stage(StageMode::dynamic);
  Stage stage;
  stage.end_time = 0.06;
  const DynamicStageResult r = run_dynamic_stage(s, stage, s.get_model().time, no_displacement(s));
  ASSERT_EQ(r.failure.outcome, StepOutcome::success);
  EXPECT_NEAR(s.elements<Bolts>().all()[0].record.max_force / (2.0 * weight), 1.0, 0.01);
  EXPECT_NEAR(s.elements<Bolts>().all()[0].record.max_elongation / (2.0 * weight / stiffness), 1.0,
              0.01);
}

// A checkpoint keeps the bolts' ends, state and record: a run stopped after 20 steps, saved and
// loaded into a System built anew ends with the same bits as the one never stopped.
TEST(BoltSystem, ACheckpointKeepsTheBoltsBitForBit)
{
  const ModelDescription m = hanging_block(1.5 * weight);
  const ResumedRun run = run_whole_and_resumed(m, 20);
  const System& whole = *run.whole;
  const System& resumed = *run.resumed;

  const Bolt& a = whole.elements<Bolts>().all()[0];
  const Bolt& b = resumed.elements<Bolts>().all()[0];
  ASSERT_GT(a.record.yield_time, run.stop_time); // it yielded after the checkpoint
  EXPECT_EQ(b.forces.state, a.forces.state);
  EXPECT_EQ(b.forces.axial_force, a.forces.axial_force);
  EXPECT_EQ(b.forces.plastic_elongation, a.forces.plastic_elongation);
  EXPECT_EQ(b.record.max_elongation, a.record.max_elongation);
  EXPECT_EQ(b.record.yield_time, a.record.yield_time);
  EXPECT_EQ(b.head.position, a.head.position);
  EXPECT_EQ(b.anchor.position, a.anchor.position);
}

// A bolt with both ends in one block, or an end outside every block, is refused naming it.
TEST(BoltSystem, BadEndsAreRefused)
{
  ModelDescription m = hanging_block(2.0 * weight);
  m.bolts[0].anchor = {0.0, 0.9};
  try
  {
    System s(m);
    FAIL() << "expected an InputError";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("bolts[0].anchor"), std::string::npos) << e.what();
  }
  m.bolts[0].anchor = {0.0, 1.5};
  try
  {
    System s(m);
    FAIL() << "expected an InputError";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("bolts[0].anchor"), std::string::npos) << e.what();
  }
}
