// The model of the bolt tests (tests/dda/test_bolt_system.cc, test_grouted_bolt_system.cc): a
// 1 m x 1 m block (y 0 to 1) below a 4 m x 1 m block (y top to top + 1) held by three fixed
// points, both of 2650 kg/m^3 rock under gravity; the tests add their bolt.
#pragma once

#include "dda/dynamic_stage.h"
#include "dda/model_description.h"
#include "tests/dda/checkpoint_round_trip.h"

#include <memory>

namespace ddafem::dda
{
inline ModelDescription block_below_fixed_block(double top)
{
  ModelDescription m;
  m.materials = {{"rock", 2650.0, 10e9, 0.25}};
  m.joint_materials = {{"joint", 1e10, 0.4, 30.0, 0.0, 0.0, false}};
  m.default_joint_material = 0;
  BlockDescription fixed;
  fixed.vertices = {{-2, top}, {2, top}, {2, top + 1}, {-2, top + 1}};
  m.blocks.push_back(fixed);
  BlockDescription hanging;
  hanging.vertices = {{-0.5, 0}, {0.5, 0}, {0.5, 1}, {-0.5, 1}};
  m.blocks.push_back(hanging);
  for (const Point& x : {Point(-1.5, top + 0.5), Point(1.5, top + 0.5), Point(0, top + 0.8)})
    m.fixed_points.push_back(
        {x, 0.0, TimeFunction::constant(0.0), TimeFunction::constant(0.0), ""});
  m.monitors.push_back({"block", {0.0, 0.5}});
  m.gravity = {0.0, -9.81};
  m.time.dt = 1e-3;
  m.time.end_time = 0.06;
  return m;
}

/// The model's dynamic stage to 0.06 s (released from rest, no displacement of the start) run
/// whole, and run again stopped after `steps` steps, checkpointed and resumed in a System built
/// anew: both Systems at the end, and the time of the stop [s].
struct ResumedRun
{
  std::unique_ptr<System> whole, resumed;
  double stop_time = 0.0;
};

inline ResumedRun run_whole_and_resumed(const ModelDescription& m, std::size_t steps)
{
  Stage stage;
  stage.end_time = 0.06;
  const auto at_rest = [](const System& s)
  { return std::vector<Vector2>(s.blocks().list.size(), Vector2::Zero()); };
  ResumedRun out{std::make_unique<System>(m), std::make_unique<System>(m), 0.0};
  out.whole->begin_stage(StageMode::dynamic);
  run_dynamic_stage(*out.whole, stage, m.time, at_rest(*out.whole));
  System first(m);
  first.begin_stage(StageMode::dynamic);
  DynamicStageRun first_run(first, stage, m.time, at_rest(first));
  std::size_t calls = 0;
  first_run.run([&](const TimeStepper&, const StepStatus&, bool) { return ++calls < steps; });
  out.stop_time = first.time();
  DynamicStageRun resumed_run(*out.resumed, stage, m.time, at_rest(first));
  round_trip(first, first_run, *out.resumed, resumed_run);
  resumed_run.run();
  return out;
}
} // namespace ddafem::dda
