// Linings in the step (issue 21): a block hanging from a fixed block on one lining element.
//
// The model: a fixed block A (x -2 to 0, y 0 to 1, on three fixed points) and a 1 m x 1 m block
// B (x 0.5 to 1.5), 0.5 m apart (no contact). A lining along their bottom (y = 0) from
// (-0.25, 0) on A to (0.75, 0) on B, one element of L = 1 m, t = 0.5 m, E = 30e9 Pa
// (EI = 3.125e8 N m). B weighs W = 2650 x 9.81 = 25 996.5 N at its centroid (1, 0.5), 0.25 m
// beyond node b: a cantilever, statically determinate: V = W, M(L) = -0.25 W at node b and
// M(0) = M(L) - V L = -1.25 W at the clamp (hogging), N = 0. The extreme fibre at the clamp:
// 6 x 1.25 W / t^2 = 779.9 kPa.
#include "common/input_error.h"
#include "dda/dynamic_stage.h"
#include "dda/lining.h"
#include "dda/static_stage.h"
#include "tests/dda/checkpoint_round_trip.h"
#include "tests/dda/hanging_static_stage.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace ddafem;
using namespace ddafem::dda;

namespace
{
constexpr double g = 9.81;
constexpr double weight = 2650.0 * g;                       // [N/m]
constexpr double clamp_stress = 6.0 * 1.25 * weight / 0.25; // [Pa]

ModelDescription hanging_block(double tensile_strength)
{
  ModelDescription m;
  m.materials = {{"rock", 2650.0, 10e9, 0.25}};
  m.joint_materials = {{"joint", 1e10, 0.4, 30.0, 0.0, 0.0, false}};
  m.default_joint_material = 0;
  BlockDescription a;
  a.vertices = {{-2, 0}, {0, 0}, {0, 1}, {-2, 1}};
  m.blocks.push_back(a);
  BlockDescription b;
  b.vertices = {{0.5, 0}, {1.5, 0}, {1.5, 1}, {0.5, 1}};
  m.blocks.push_back(b);
  for (const Point& x : {Point(-1.5, 0.5), Point(-0.5, 0.5), Point(-1, 0.8)})
    m.fixed_points.push_back(
        {x, 0.0, TimeFunction::constant(0.0), TimeFunction::constant(0.0), ""});
  LiningDescription l;
  l.name = "lining";
  l.points = {{-0.25, 0.0}, {0.75, 0.0}};
  l.segment_length = 1.0;
  l.thickness = 0.5;
  l.youngs_modulus = 30e9;
  l.compressive_strength = 40e6;
  l.tensile_strength = tensile_strength;
  l.origin = "linings[0]";
  m.linings.push_back(l);
  m.gravity = {0.0, -g};
  m.time.dt = 1e-3;
  m.time.end_time = 0.03;
  return m;
}
} // namespace

// The static stage hangs B on the element: V, M and N are the cantilever's within 1e-3 (the
// rotations are 1e-4 rad: second-order effects are below that).
TEST(LiningSystem, StaticStageHangsTheBlockOnTheCantilever)
{
  System s(hanging_block(4e6));
  ASSERT_EQ(s.elements<Linings>().all().size(), 1u);
  const Lining& l = s.elements<Linings>().all()[0];
  ASSERT_EQ(l.elements.size(), 1u);
  EXPECT_EQ(l.nodes[0].point.block, 0u);
  EXPECT_EQ(l.nodes[1].point.block, 1u);
  s.begin_stage(StageMode::static_equilibrium);
  ASSERT_EQ(run_static_stage(s, hanging_static_stage(), s.get_model().time).outcome,
            StaticOutcome::equilibrium);
  const FrameForces& f = s.elements<Linings>().all()[0].elements[0].forces;
  EXPECT_NEAR(f.shear_force / weight, 1.0, 1e-3);
  EXPECT_NEAR(f.bending_moment_b() / (-0.25 * weight), 1.0, 1e-3);
  EXPECT_NEAR(f.bending_moment_a() / (-1.25 * weight), 1.0, 1e-3);
  EXPECT_LT(std::abs(f.axial_force), 1e-3 * weight);
  EXPECT_NEAR(s.elements<Linings>().all()[0].elements[0].check.utilisation / (clamp_stress / 4e6),
              1.0, 1e-3);
  EXPECT_GT(s.energy().spring, 0.0);
}

// 2 % above the demand it holds; 2 % below the element breaks and B is released.
TEST(LiningSystem, TheElementHoldsAboveAndBreaksBelowItsDemand)
{
  System strong(hanging_block(1.02 * clamp_stress));
  strong.begin_stage(StageMode::static_equilibrium);
  const StaticStageResult held =
      run_static_stage(strong, hanging_static_stage(), strong.get_model().time);
  EXPECT_EQ(held.outcome, StaticOutcome::equilibrium);
  EXPECT_EQ(strong.elements<Linings>().all()[0].n_broken(), 0u);

  System weak(hanging_block(0.98 * clamp_stress));
  weak.begin_stage(StageMode::static_equilibrium);
  const StaticStageResult r = run_static_stage(weak, hanging_static_stage(), weak.get_model().time);
  const Lining& l = weak.elements<Linings>().all()[0];
  EXPECT_EQ(l.n_broken(), 1u);
  EXPECT_FALSE(std::isnan(l.first_break_time));
  EXPECT_EQ(l.first_break_element, 0u);
  EXPECT_GT(l.max_utilisation, 1.0);
  ASSERT_EQ(r.released.size(), 1u);
  EXPECT_EQ(r.released[0].block, 1u);
}

// A lining installed at the start of the second stage carries nothing of the first: B falls
// freely in a first dynamic stage, and the second stage installs the lining at the nodes'
// positions then, with zero forces and rotations.
TEST(LiningSystem, ALiningInstalledLaterStartsFromTheCurrentPositions)
{
  ModelDescription m = hanging_block(4e6);
  m.linings[0].install_stage = 1;
  System s(m);
  EXPECT_FALSE(s.elements<Linings>().all()[0].installed);
  s.begin_stage(StageMode::dynamic);
  Stage stage;
  stage.end_time = 0.01;
  const std::vector<Vector2> zero(2, Vector2::Zero());
  run_dynamic_stage(s, stage, m.time, zero);
  EXPECT_EQ(s.elements<Linings>().all()[0].elements[0].forces.shear_force, 0.0);
  const Point moved = s.elements<Linings>().all()[0].nodes[1].point.position;
  EXPECT_LT(moved.y(), -1e-4);
  s.begin_stage(StageMode::static_equilibrium);
  EXPECT_TRUE(s.elements<Linings>().all()[0].installed);
  EXPECT_EQ(s.elements<Linings>().all()[0].nodes[1].installed, moved);
  EXPECT_EQ(s.elements<Linings>().all()[0].nodes[1].rotation, 0.0);
}

// A checkpoint keeps the linings' nodes, elements and records: a run stopped after 3 steps,
// saved and loaded into a System built anew ends with the same bits as the one never stopped
// (B released from rest swings towards twice its static demand: at 1.5 x it breaks after the
// checkpoint, at 6 ms).
TEST(LiningSystem, ACheckpointKeepsTheLiningBitForBit)
{
  const ModelDescription m = hanging_block(1.5 * clamp_stress);
  Stage stage;
  stage.end_time = 0.03;
  const std::vector<Vector2> zero(2, Vector2::Zero());
  System whole(m);
  whole.begin_stage(StageMode::dynamic);
  run_dynamic_stage(whole, stage, m.time, zero);

  System first(m);
  first.begin_stage(StageMode::dynamic);
  DynamicStageRun first_run(first, stage, m.time, zero);
  std::size_t calls = 0;
  first_run.run([&](const TimeStepper&, const StepStatus&, bool) { return ++calls < 3; });
  System resumed(m);
  DynamicStageRun resumed_run(resumed, stage, m.time, zero);
  round_trip(first, first_run, resumed, resumed_run);
  resumed_run.run();

  const Lining& a = whole.elements<Linings>().all()[0];
  const Lining& b = resumed.elements<Linings>().all()[0];
  ASSERT_FALSE(std::isnan(a.first_break_time));
  EXPECT_GT(a.first_break_time, first.time()); // it broke after the checkpoint
  EXPECT_EQ(b.first_break_time, a.first_break_time);
  EXPECT_EQ(b.max_utilisation, a.max_utilisation);
  EXPECT_EQ(b.elements[0].state, a.elements[0].state);
  EXPECT_EQ(b.nodes[1].point.position, a.nodes[1].point.position);
  EXPECT_EQ(b.nodes[1].rotation, a.nodes[1].rotation);
}

// A node outside every block is refused naming the lining.
TEST(LiningSystem, ANodeOutsideTheBlocksIsRefused)
{
  ModelDescription m = hanging_block(4e6);
  m.linings[0].segment_length = 0.5; // a node at (0.25, 0), in the gap
  try
  {
    System s(m);
    FAIL() << "expected an InputError";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("linings[0] node 1"), std::string::npos) << e.what();
  }
}
