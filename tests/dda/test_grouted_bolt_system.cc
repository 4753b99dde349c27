// Grouted bolts in the step (issue 21): a block hanging from a fixed block on a grouted bolt
// that crosses the joint between them.
//
// The model: a fixed 4 m x 1 m block (top, y 1 to 2) and a 1 m x 1 m block (y 0 to 1) touching
// it from below along a frictional joint without cohesion or tension; a vertical grouted bolt
// from (0, 0.2) in the hanging block to (0, 1.8) in the fixed one crosses the joint at (0, 1).
// (tests/dda/hanging_block_model.h, top = 1). A_s = 1e-4 m^2, E_s = 200e9 Pa, L_d = 0.4 m: k_a =
// E_s A_s / L_d = 5e7 N/m. The block weighs W = 2650 x 9.81 = 25 996.5 N: the joint opens and the
// crossing carries W at an opening W / k_a = 0.52 mm.
#include "dda/dynamic_stage.h"
#include "dda/grouted_bolt.h"
#include "dda/static_stage.h"
#include "tests/dda/checkpoint_round_trip.h"
#include "tests/dda/hanging_block_model.h"
#include "tests/dda/hanging_static_stage.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace ddafem;
using namespace ddafem::dda;

namespace
{
constexpr double g = 9.81;
constexpr double weight = 2650.0 * g;   // [N]
constexpr double axial_stiffness = 5e7; // [N/m]

ModelDescription hanging_block(double yield_force, double side_load = 0.0)
{
  ModelDescription m = block_below_fixed_block(1.0);
  BoltDescription b;
  b.name = "grouted";
  b.type = BoltType::grouted;
  b.head = {0.0, 0.2};
  b.anchor = {0.0, 1.8};
  b.area = 1e-4;
  b.yield_force = yield_force;
  b.shear_capacity = 1e5;
  b.debonded_length = 0.4;
  b.origin = "bolts[0]";
  std::vector<std::vector<Point>> polygons;
  for (const BlockDescription& d : m.blocks)
    polygons.push_back(d.vertices);
  b.crossings = find_bolt_crossings(polygons, b.head, b.anchor, 1e-9);
  m.bolts.push_back(b);
  if (side_load != 0.0) // at the crossing's height: a pure dowel load
    m.point_loads.push_back({{0.0, 0.999}, {side_load, 0.0}, TimeFunction::constant(1.0), ""});
  return m;
}

StaticStageResult settle(System& s)
{
  s.begin_stage(StageMode::static_equilibrium);
  return run_static_stage(s, hanging_static_stage(), s.get_model().time);
}

} // namespace

TEST(GroutedBoltSystem, TheCrossingCarriesTheHangingBlock)
{
  System s(hanging_block(2.0 * weight));
  ASSERT_EQ(s.elements<GroutedBolts>().all().size(), 1u);
  const GroutedBolt& b = s.elements<GroutedBolts>().all()[0];
  ASSERT_EQ(b.crossings.size(), 1u);
  EXPECT_EQ(b.crossings[0].on_a.block, 1u); // the head's side: the hanging block
  EXPECT_EQ(b.crossings[0].on_b.block, 0u);
  EXPECT_DOUBLE_EQ(b.law.axial_stiffness, axial_stiffness);
  ASSERT_EQ(settle(s).outcome, StaticOutcome::equilibrium);
  const GroutedCrossing& c = s.elements<GroutedBolts>().all()[0].crossings[0];
  EXPECT_EQ(c.forces.state, BoltState::elastic);
  EXPECT_NEAR(c.forces.axial_force / weight, 1.0, 1e-6);
  EXPECT_NEAR(std::abs(c.forces.shear_force), 0.0, 1e-6 * weight);
  const auto [opening, slip] = s.elements<GroutedBolts>().all()[0].opening_and_slip(c);
  EXPECT_NEAR(opening / (weight / axial_stiffness), 1.0, 1e-3);
  // The block's centre sags by the opening and a little more: the fixed block moves 5 W / 3e11 =
  // 4e-7 m (8e-4 of it) and the block, hanging from its top, stretches by about
  // rho g h / E x 0.5 m = 1.3e-6 m (2.5e-3).
  EXPECT_NEAR(-s.sample_monitor(0).displacement.y() / (weight / axial_stiffness), 1.0, 5e-3);
}

// A side load at the crossing's height (the joint is open, so only the dowel resists it):
// S = P at a slip P / k_s (the block slides +x, the anchor side's point moves -x relative). The
// load's 1 mm below the crossing turns the hanging block by P x 1 mm / (W x 0.5 m) = 4e-4 rad,
// which moves the head 0.3 mm sideways and turns the bolt's direction (head to anchor) by 3e-4
// rad: N's horizontal part (8 N) takes 1.4e-3 of the load from the dowel.
TEST(GroutedBoltSystem, TheDowelCarriesASideLoad)
{
  const double load = 0.2 * weight;
  System s(hanging_block(2.0 * weight, load));
  ASSERT_EQ(settle(s).outcome, StaticOutcome::equilibrium);
  const GroutedBolt& b = s.elements<GroutedBolts>().all()[0];
  const GroutedCrossing& c = b.crossings[0];
  // e = (0, 1) from head to anchor, t = (-1, 0): the block's +x slip is a positive slip.
  EXPECT_NEAR(c.forces.shear_force / load, 1.0, 2e-3);
  EXPECT_NEAR(c.forces.axial_force / weight, 1.0, 1e-3);
  EXPECT_NEAR(b.opening_and_slip(c)[1] / (load / b.law.shear_stiffness), 1.0, 2e-3);
}

// A checkpoint keeps the crossings: a run stopped after 5 steps, saved and loaded into a System
// built anew ends with the same bits as the one never stopped (released from rest the crossing
// swings up to 2 W and yields at 1.5 W after the checkpoint).
TEST(GroutedBoltSystem, ACheckpointKeepsTheCrossingsBitForBit)
{
  const ModelDescription m = hanging_block(1.5 * weight);
  const ResumedRun run = run_whole_and_resumed(m, 5);
  const System& whole = *run.whole;
  const System& resumed = *run.resumed;

  const GroutedCrossing& a = whole.elements<GroutedBolts>().all()[0].crossings[0];
  const GroutedCrossing& b = resumed.elements<GroutedBolts>().all()[0].crossings[0];
  ASSERT_GT(a.record.yield_time, run.stop_time); // it yielded after the checkpoint
  EXPECT_EQ(b.forces.state, a.forces.state);
  EXPECT_EQ(b.forces.axial_force, a.forces.axial_force);
  EXPECT_EQ(b.forces.shear_force, a.forces.shear_force);
  EXPECT_EQ(b.forces.plastic_opening, a.forces.plastic_opening);
  EXPECT_EQ(b.record.max_opening, a.record.max_opening);
  EXPECT_EQ(b.record.yield_time, a.record.yield_time);
  EXPECT_EQ(b.on_a.position, a.on_a.position);
  EXPECT_EQ(b.on_b.position, a.on_b.position);
}
