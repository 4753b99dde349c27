// The example scenes against analytic answers: the P-wave bar of Bao et al. (2012) section 4.1
// and a block stack at rest under gravity.
#include "app/scene/scene.h"
#include "dda/system.h"
#include "dda/time_stepper.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace ddafem;
using namespace ddafem::dda;

namespace
{
const std::string examples = std::string(DDAFEM_SOURCE_DIR) + "/examples/";

struct History
{
  std::vector<double> time;
  std::vector<std::vector<double>> sxx; ///< per monitor
};

History run(const Scene& scene)
{
  System system(scene.model);
  History h;
  h.sxx.resize(scene.model.monitors.size());
  const double dt = scene.model.time.dt;
  const auto n = static_cast<std::size_t>(std::llround(scene.model.time.end_time / dt));
  for (std::size_t k = 0; k < n; ++k)
  {
    const StepStatus s = system.advance(dt);
    EXPECT_EQ(s.outcome, StepOutcome::success) << s.message;
    if (s.outcome != StepOutcome::success)
      break;
    h.time.push_back(system.time());
    for (std::size_t m = 0; m < h.sxx.size(); ++m)
      h.sxx[m].push_back(system.sample_monitor(m).stress[0]);
  }
  return h;
}

/// Value at the sample closest to time t.
double value_at(const History& h, std::size_t m, double t)
{
  std::size_t best = 0;
  for (std::size_t k = 0; k < h.time.size(); ++k)
    if (std::abs(h.time[k] - t) < std::abs(h.time[best] - t))
      best = k;
  return h.sxx[m][best];
}

/// Extremum (signed) of the monitor's sxx within [t0, t1].
double extremum(const History& h, std::size_t m, double t0, double t1)
{
  double e = 0.0;
  for (std::size_t k = 0; k < h.time.size(); ++k)
    if (h.time[k] >= t0 && h.time[k] <= t1 && std::abs(h.sxx[m][k]) > std::abs(e))
      e = h.sxx[m][k];
  return e;
}
} // namespace

class PWaveBar : public ::testing::Test
{
protected:
  static void SetUpTestSuite()
  {
    scene = new Scene(read_scene(examples + "bao2012/p_wave_bar.yaml"));
    history = new History(run(*scene));
  }
  static void TearDownTestSuite()
  {
    delete history;
    delete scene;
  }
  /// P speed of the jointed bar: 1 m blocks of modulus E in series with a joint of two normal
  /// springs p per 1 m^2 of section: E_eff = 1 / (1/E + 1 m^2 / (2 p 1 m)); c = sqrt(E_eff/rho).
  static double wave_speed()
  {
    const Material& m = scene->model.materials[0];
    const double p = scene->model.joint_materials[0].normal_stiffness;
    return std::sqrt(1.0 / (1.0 / m.youngs_modulus + 1.0 / (2.0 * p)) / m.density);
  }
  static Scene* scene;
  static History* history;
};
Scene* PWaveBar::scene = nullptr;
History* PWaveBar::history = nullptr;

TEST_F(PWaveBar, SceneIsThePapersBar)
{
  EXPECT_EQ(scene->model.blocks.size(), 100u);
  EXPECT_EQ(scene->model.monitors.size(), 2u);
  EXPECT_DOUBLE_EQ(scene->model.time.dt, 1e-5);
  EXPECT_NEAR(wave_speed(), 4322.2, 0.5); // 0.5% below the bar speed sqrt(E/rho) = 4343.6 m/s
}

TEST_F(PWaveBar, PulseArrivesWhenTheWaveSpeedPredicts)
{
  // The same bar made 200 m long, so that no reflection reaches M2 (98.5 m) before the pulse has
  // passed. The compressive first lobe peaks a quarter period (2.5 ms) after the pulse front,
  // which travels at c: t = 2.5 ms + x / c at M1 (50.5 m) and M2 (98.5 m), and the lag between
  // them is 48 m / c.
  const Scene long_bar =
      read_scene(examples + "bao2012/p_wave_bar.yaml", {{"blocks.0.grid.count", "[200, 1]"},
                                                        {"boundaries.0.on_line.point", "[200, 0]"},
                                                        {"time.end_time", "0.03"}});
  const History h = run(long_bar);
  const double c = wave_speed();
  const double x[2] = {50.5, 98.5};
  double t_peak[2] = {0.0, 0.0};
  for (std::size_t m = 0; m < 2; ++m)
  {
    double s_min = 0.0;
    for (std::size_t k = 0; k < h.time.size(); ++k)
      if (h.sxx[m][k] < s_min)
      {
        s_min = h.sxx[m][k];
        t_peak[m] = h.time[k];
      }
    const double expected = 0.0025 + x[m] / c;
    EXPECT_NEAR(t_peak[m], expected, 0.02 * expected) << "monitor " << m;
  }
  const double lag = 48.0 / c;
  EXPECT_NEAR(t_peak[1] - t_peak[0], lag, 0.02 * lag);
}

TEST_F(PWaveBar, IncidentPeakIsOneMegapascal)
{
  // 1000 kN over the 1 m^2 section; at dt = 1e-5 s DDA's damping costs ~1% by M1.
  const double c = wave_speed();
  const double t_inc = 50.5 / c;
  const double peak = extremum(*history, 0, t_inc, t_inc + 0.01);
  EXPECT_LT(peak, 0.0); // compression first: the load pushes into the bar
  EXPECT_NEAR(std::abs(peak), 1e6, 0.02e6);
}

TEST_F(PWaveBar, FreeEndReflectsWithOppositeSign)
{
  // At M1 the incident pulse's first lobe (compression) returns from the free end as tension
  // after travelling 100 + 49.5 m.
  const double c = wave_speed();
  const double incident = value_at(*history, 0, 0.0025 + 50.5 / c);
  const double reflected = value_at(*history, 0, 0.0025 + 149.5 / c);
  EXPECT_LT(incident, -0.9e6);
  EXPECT_GT(reflected, 0.9e6);
  // The reflection carries (almost) the whole pulse: |reflected| / |incident| > 0.97 (DDA's
  // damping over the extra 99 m costs about 1-2% at dt = 1e-5 s).
  EXPECT_GT(std::abs(reflected / incident), 0.97);
}

TEST(BlockStack, ReachesTheStaticStressOfItsWeight)
{
  // A unit block with a load P on top and the support below carries mean
  // syy = -(2P + W) / (2 w) (virtual work of a uniform strain); W = rho g (1 m^2).
  const Scene scene = read_scene(examples + "block_stack/stack.yaml");
  ASSERT_EQ(scene.model.stages.size(), 2u);
  const Stage& settle = scene.model.stages[0];
  ASSERT_EQ(settle.mode, StageMode::static_equilibrium);
  System system(scene.model);
  system.begin_stage(StageMode::static_equilibrium);
  TimeStepper stepper(system, scene.model.time, settle.dt);
  bool converged = false;
  for (std::size_t k = 0; k < settle.max_steps && !converged; ++k)
  {
    const StepStatus status = stepper.step();
    ASSERT_EQ(status.outcome, StepOutcome::success) << status.message;
    converged = status.unbalanced_force_ratio <= settle.tolerance;
  }
  ASSERT_TRUE(converged);
  EXPECT_EQ(system.time(), 0.0); // the clock stands still in a static stage
  const Material& m = scene.model.materials[0];
  const double w = m.density * std::abs(scene.model.gravity.y()) * 1.0;
  // Blocks 1, 2, 3 are stacked bottom to top on the base block 0.
  const auto& blocks = system.blocks().list;
  ASSERT_EQ(blocks.size(), 4u);
  const double load_on_top[3] = {2 * w, w, 0.0};
  for (std::size_t i = 0; i < 3; ++i)
  {
    const double expected = -(2 * load_on_top[i] + w) / 2.0;
    EXPECT_NEAR(blocks[i + 1].stress[1], expected, 0.01 * std::abs(expected)) << "block " << i + 1;
  }
  // Every contact of the stack is closed and locked (4 pairs of corners).
  EXPECT_EQ(system.contacts().counts().lock, 6u);
  EXPECT_EQ(system.contacts().counts().slide, 0u);

  // The dynamic stage starts at rest from the equilibrium and stays there until the push.
  system.begin_stage(StageMode::dynamic);
  TimeStepper dynamic(system, scene.model.time);
  while (system.time() < 0.1) // the push starts at 0.1 s
    ASSERT_EQ(dynamic.step().outcome, StepOutcome::success);
  EXPECT_LT(system.sample_monitor(0).displacement.norm(), 1e-6);
  EXPECT_LT(system.energy().kinetic, 1e-6 * (system.energy().strain + system.energy().spring));
}
