// Contact mechanics end to end against hand calculations (issue 4 acceptance).
#include "dda/system.h"
#include "dda/time_stepper.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace ddafem;
using namespace ddafem::dda;

namespace
{
constexpr double rho = 2650.0, young = 10e9, nu = 0.25, g = 9.81;

/// A unit block resting on a fixed 6 m x 1 m base (held by three fixed points), frictional
/// joints with normal stiffness p [N/m], friction angle phi [deg] and cohesion c [Pa].
ModelDescription block_on_base(double phi, double cohesion, double p = 1e10)
{
  ModelDescription m;
  m.materials.push_back({"rock", rho, young, nu});
  m.joint_materials.push_back({"joint", p, 0.4, phi, cohesion, 0.0, false});
  m.default_joint_material = 0;
  BlockDescription base, block;
  base.vertices = {{-3, -1}, {3, -1}, {3, 0}, {-3, 0}};
  block.vertices = {{-0.5, 0}, {0.5, 0}, {0.5, 1}, {-0.5, 1}};
  m.blocks = {base, block};
  for (const Point& x : {Point(-2.5, -0.5), Point(2.5, -0.5), Point(0, -0.5)})
    m.fixed_points.push_back(
        {x, 0.0, TimeFunction::constant(0.0), TimeFunction::constant(0.0), ""});
  m.monitors.push_back({"block", {0.0, 0.5}});
  m.time.dt = 1e-3;
  m.time.end_time = 1.0;
  return m;
}

/// Runs to `end_time` with the scene's time control; fails the test on a failed step.
void run_to(System& s, const TimeSettings& time, double end_time)
{
  TimeStepper stepper(s, time);
  while (s.time() < end_time - 1e-12)
  {
    const StepStatus status = stepper.step(end_time - s.time());
    ASSERT_EQ(status.outcome, StepOutcome::success) << status.message;
  }
}
} // namespace

TEST(Contacts, BlockSlidesDownAnInclineAtTheFrictionalAcceleration)
{
  // Tilting gravity by the slope angle b is the same as tilting the base: s(t) = g (sin b -
  // cos b tan phi) t^2 / 2 along the slope once sliding (from t = 0, the block starts at rest
  // on the base).
  const double b = 30.0 * M_PI / 180.0, phi = 20.0;
  ModelDescription m = block_on_base(phi, 0.0);
  m.gravity = Vector2(g * std::sin(b), -g * std::cos(b));
  System s(m);
  run_to(s, m.time, 1.0);
  const double expected =
      0.5 * g * (std::sin(b) - std::cos(b) * std::tan(phi * M_PI / 180.0)) * 1.0 * 1.0;
  const double slid = s.sample_monitor(0).displacement.x();
  EXPECT_NEAR(slid, expected, 0.01 * expected);
              s.get_timings().n_attempts, s.get_timings().n_open_close_iterations);
  ASSERT_FALSE(s.get_contacts().empty());
  EXPECT_EQ(s.contact_counts().slide, 2u);
}

TEST(Contacts, BlockStaysOnAFlatterIncline)
{
  const double b = 15.0 * M_PI / 180.0, phi = 20.0;
  ModelDescription m = block_on_base(phi, 0.0);
  m.gravity = Vector2(g * std::sin(b), -g * std::cos(b));
  System s(m);
  run_to(s, m.time, 0.2); // the penalty springs settle
  const double settled = s.sample_monitor(0).displacement.x();
  run_to(s, m.time, 1.0);
  EXPECT_LT(std::abs(s.sample_monitor(0).displacement.x() - settled), 1e-6);
  EXPECT_EQ(s.contact_counts().lock, 2u);
}
