// The rock's damping (dda/damping.h) against the damped oscillator, on rigid-body motion (none)
// and in the energy budget.
#include "dda/system.h"
#include "tests/dda/step_parts.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace ddafem;
using namespace ddafem::dda;

namespace
{
// A 1 m block ("top", 2650 kg) on a 1 m block ("base") held by three fixed points, bonded by a
// joint whose two end springs p = 1e9 N/m carry the top's vertical motion: k = 2 p, w =
// sqrt(2 p / m) = 868.8 rad/s (138.3 Hz). The blocks are stiff (E = 1e13 Pa: the block's own
// axial stiffness, about E x 1 m / 0.5 m, is 1e4 times k) so that the top moves as a rigid mass
// on the joint, the single-degree-of-freedom oscillator of damped_free_decay.
constexpr double density = 2650.0, p = 1e9, v0 = 0.01; // kg/m^3, N/m, m/s (upwards at t = 0)
const double omega = std::sqrt(2.0 * p / density);

ModelDescription oscillator(const RockDamping& joint_damping, const RockDamping& block_damping,
                            Integrator integrator)
{
  ModelDescription m;
  m.materials.push_back({"stiff", density, 1e13, 0.25, block_damping});
  JointMaterial joint{"joint", p, 0.4, 45.0, 1e9, 1e9, true};
  joint.damping = joint_damping;
  m.joint_materials.push_back(joint);
  m.default_joint_material = 0;
  m.blocks.push_back(
      {{{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 0, Vector2::Zero(), Voigt::Zero(), "base", {}});
  m.blocks.push_back(
      {{{0, 1}, {1, 1}, {1, 2}, {0, 2}}, 0, Vector2(0.0, v0), Voigt::Zero(), "top", {}});
  for (const Point& x : {Point(0.1, 0.1), Point(0.9, 0.1), Point(0.5, 0.9)})
    m.fixed_points.push_back({x, 0.0, TimeFunction::constant(0), TimeFunction::constant(0), ""});
  m.monitors.push_back({"top", {0.5, 1.5}});
  m.time.integrator = integrator;
  return m;
}

/// The top's vertical displacement [m] every step over `periods` periods at 200 steps a period.
std::vector<double> free_decay(System& s, double periods, double& dt)
{
  dt = 2.0 * M_PI / omega / 200.0;
  s.begin_stage(StageMode::dynamic);
  std::vector<double> y;
  const auto n = static_cast<std::size_t>(std::lround(200.0 * periods));
  for (std::size_t k = 0; k < n; ++k)
  {
    EXPECT_EQ(s.advance(dt, step_parts::of_call(s, k)).outcome, StepOutcome::success);
    y.push_back(s.sample_monitor(0).displacement.y());
  }
  return y;
}
} // namespace

TEST(Damping, StiffnessFactorHoldsTheRatioAtItsFrequency)
{
  // beta = zeta / (pi f0): the mode at f0 has beta w0 / 2 = zeta; at 2 f0 twice that.
  const RockDamping d{0.05, 25.0};
  EXPECT_DOUBLE_EQ(d.stiffness_factor(), 0.05 / (M_PI * 25.0));
  EXPECT_DOUBLE_EQ(d.stiffness_factor() * 2.0 * M_PI * 25.0 / 2.0, 0.05);
  EXPECT_DOUBLE_EQ(d.ratio_at(50.0), 0.1);
  EXPECT_EQ(RockDamping{}.stiffness_factor(), 0.0);
}

TEST(Damping, BlockOnAJointDecaysAsTheDampedOscillator)
{
  // zeta = 5 % at the oscillator's own frequency, on the joint and the blocks alike (C = beta K
  // of the whole: the mode keeps beta w / 2 = zeta). Over 4 periods the history follows
  // x(t) = v0 / wd exp(-zeta w t) sin(wd t) within 2 % of its first peak v0 / w; 200 steps a
  // period leave period errors of (w dt)^2 / 12 = 8e-5 a period (trapezoidal) and the blocks'
  // own compliance 1e-4: both far inside. Bathe's scheme adds its own damping, 1e-6 at w dt =
  // 0.031, and starts with one step of DDA's scheme.
  const double zeta = 0.05;
  const RockDamping d{zeta, omega / (2.0 * M_PI)};
  for (const Integrator integrator : {Integrator::newmark_trapezoidal, Integrator::bathe})
  {
    System s(oscillator(d, d, integrator));
    double dt = 0.0;
    const std::vector<double> y = free_decay(s, 4.0, dt);
    const double wd = omega * std::sqrt(1.0 - zeta * zeta), peak = v0 / omega;
    double worst = 0.0;
    for (std::size_t k = 0; k < y.size(); ++k)
    {
      const double t = static_cast<double>(k + 1) * dt;
      const double exact = v0 / wd * std::exp(-zeta * omega * t) * std::sin(wd * t);
      worst = std::max(worst, std::abs(y[k] - exact));
    }
    EXPECT_LT(worst, 0.02 * peak) << name_of(integrator);
    // The logarithmic decrement: the largest |x| of the 4th period against the 1st's, three
    // damped periods later: exp(-3 2 pi zeta / sqrt(1 - zeta^2)) = 0.389, within 2 % (zeta
    // within 2 % of itself; the peaks sampled 200 times a period are within 5e-4).
    const auto largest = [&](std::size_t from)
    {
      double a = 0.0;
      for (std::size_t k = from; k < from + 200; ++k)
        a = std::max(a, std::abs(y[k]));
      return a;
    };
    const double decrement = std::exp(-6.0 * M_PI * zeta / std::sqrt(1.0 - zeta * zeta));
    EXPECT_NEAR(largest(600) / largest(0), decrement, 0.02 * decrement) << name_of(integrator);
  }
}

TEST(Damping, EnergyBudgetBalancesWithTheDashpotsWork)
{
  // Trapezoidal Newmark conserves energy on a linear model: what the oscillator loses is the
  // dashpots' work, and the residual (`dissipated`) stays below 1 % of what they absorbed.
  const RockDamping d{0.05, omega / (2.0 * M_PI)};
  System s(oscillator(d, d, Integrator::newmark_trapezoidal));
  double dt = 0.0;
  const double initial = 0.5 * density * v0 * v0;
  free_decay(s, 4.0, dt);
  const EnergyBalance e = s.energy();
  EXPECT_NEAR(e.initial, initial, 1e-9 * initial);
  EXPECT_LT(e.work_of_damping, -0.5 * initial); // most of it absorbed
  EXPECT_LT(std::abs(e.dissipated), 0.01 * -e.work_of_damping);
  // Undamped: no work of damping, and the energy kept.
  System undamped(oscillator({}, {}, Integrator::newmark_trapezoidal));
  free_decay(undamped, 4.0, dt);
  EXPECT_EQ(undamped.energy().work_of_damping, 0.0);
  EXPECT_NEAR(undamped.energy().stored(), initial, 1e-3 * initial);
}

TEST(Damping, RigidBodyMotionIsNotDamped)
{
  // A damped block alone, thrown sideways and falling: y = -g t^2 / 2, x = v t as without
  // damping (no strain rate, no joint), and the dashpots do no work.
  ModelDescription m;
  m.materials.push_back({"rock", 2650.0, 50e9, 0.25, RockDamping{0.05, 10.0}});
  m.blocks.push_back(
      {{{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 0, Vector2(0.5, 0.0), Voigt::Zero(), "block", {}});
  m.monitors.push_back({"centre", {0.5, 0.5}});
  m.gravity = {0.0, -9.81};
  System s(m);
  s.begin_stage(StageMode::dynamic);
  const double dt = 1e-4; // a step moves it less than the step displacement limit
  for (std::size_t k = 0; k < 2000; ++k)
    ASSERT_EQ(s.advance(dt, step_parts::of_call(s, k)).outcome, StepOutcome::success);
  const double t = 0.2;
  EXPECT_NEAR(s.sample_monitor(0).displacement.y(), -0.5 * 9.81 * t * t, 1e-9);
  EXPECT_NEAR(s.sample_monitor(0).displacement.x(), 0.5 * t, 1e-9);
  EXPECT_NEAR(s.energy().work_of_damping, 0.0, 1e-12);
}
