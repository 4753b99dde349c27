// A plane P or S pulse crossing the tie interface between DDA blocks and the deal.II far field,
// both ways: the spurious reflection against a model without the interface, long enough to
// reflect nothing within the window, and the energy balance across the interface (issue 6).
//
// The blocks take the trapezoidal rule (no algorithmic damping) or Bathe's composite scheme (the
// coupled scenes' default; the far field then takes the trapezoidal rule on each half step, and
// so does the reference), the rock has nu = 0 (plane waves in a column of one-block layers are
// then one-dimensional) and the joints and ties are
// stiff enough (0.1% of a layer's compliance) for the blocks to carry the continuum's
// impedance: what reflects is the interface's doing.
#include "column_models.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <tuple>

namespace ddafem::coupling
{
namespace
{
using test_models::Column;
using test_models::ColumnSpec;
using test_models::UpwardColumn;
using test_models::UpwardSpec;
using test_models::Wave;

/// The window: the incident pulse (10 ms) passes the monitor 10 m from the source and its
/// reflection from the interface (20 m) comes back; the far ends (60 m) answer after it.
constexpr double window = 0.03;                                     // [s]
constexpr double interface = 40.0, far_end = 100.0, monitor = 20.5; // [m]

double component(Wave wave, double x, double y)
{
  return wave == Wave::s ? x : y;
}

/// max |a - b| / max |b| over the common length.
double relative_difference(const std::vector<double>& a, const std::vector<double>& b)
{
  double peak = 0.0, difference = 0.0;
  for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k)
  {
    peak = std::max(peak, std::abs(b[k]));
    difference = std::max(difference, std::abs(a[k] - b[k]));
  }
  return difference / peak;
}

/// With DDAFEM_TRANSPARENCY_RECORDS=FILE set, each measurement appends one JSON line to FILE
/// (tools/verify_coupling.py turns them into docs/verification/interface.*): the numbers and
/// both monitor histories.
void record(const std::string& wave, const std::string& direction, double block_size,
            double element_size, double reflection, double energy_mismatch, double dt,
            dda::Integrator integrator, const std::vector<double>& coupled,
            const std::vector<double>& reference)
{
  const char* file = std::getenv("DDAFEM_TRANSPARENCY_RECORDS");
  if (file == nullptr)
    return;
  std::ofstream out(file, std::ios::app);
  const auto list = [](const std::vector<double>& v)
  {
    std::string s = "[";
    char number[32];
    for (std::size_t k = 0; k < v.size(); ++k)
    {
      std::snprintf(number, sizeof(number), "%s%.6e", k ? ", " : "", v[k]);
      s += number;
    }
    return s + "]";
  };
  char head[512];
  std::snprintf(head, sizeof(head),
                "{\"wave\": \"%s\", \"direction\": \"%s\", \"block_size_m\": %g, "
                "\"element_size_m\": %g, \"reflection\": %.6g, \"energy_mismatch\": %.6g, "
                "\"dt_s\": %g, \"integrator\": \"%s\", ",
                wave.c_str(), direction.c_str(), block_size, element_size, reflection,
                energy_mismatch, dt,
                integrator == dda::Integrator::bathe ? "bathe" : "newmark_trapezoidal");
  out << head << "\"coupled\": " << list(coupled) << ", \"reference\": " << list(reference)
      << "}\n";
}

struct Transparency
{
  double reflection = 0.0;      ///< max |coupled - reference| / max |reference| at the monitor
  double energy_mismatch = 0.0; ///< |arrived - crossed| / crossed
};

/// Blocks (source side) into the far field.
Transparency blocks_into_far_field(Wave wave, double element_size, dda::Integrator integrator)
{
  ColumnSpec s;
  s.wave = wave;
  s.integrator = integrator;
  s.element_size = element_size;
  s.dda_top = interface;
  s.monitor_heights = {monitor};
  const auto n_steps = static_cast<std::size_t>(std::llround(window / s.dt));
  const auto history = [&](Column& c)
  {
    std::vector<double> h;
    for (std::size_t k = 0; k < n_steps; ++k)
    {
      const dda::StepStatus status = test_models::step_blocks(c.system, s.dt, s.integrator);
      EXPECT_EQ(status.outcome, dda::StepOutcome::success) << status.message;
      if (status.outcome != dda::StepOutcome::success)
        break;
      const dda::MonitorSample m = c.system.sample_monitor(0);
      h.push_back(component(wave, m.displacement.x(), m.displacement.y()));
    }
    return h;
  };
  ColumnSpec reference_spec = s;
  reference_spec.dda_top = far_end;
  Column reference(reference_spec);
  const std::vector<double> expected = history(reference);
  s.fe_top = far_end;
  Column coupled(s);
  const std::vector<double> got = history(coupled);

  Transparency t;
  t.reflection = relative_difference(got, expected);
  // What left the blocks through the ties against what the far field holds and absorbed.
  const double crossed = -coupled.ties->work_on_blocks();
  const fem::EnergyBalance e = coupled.far_field->energy();
  const double arrived = e.stored() - e.work_of_dashpots;
  t.energy_mismatch = std::abs(arrived - crossed) / crossed;
  std::printf("%s blocks -> far field, element %.2f m: reflection %.4f, energy crossed %.6g J, "
              "arrived %.6g J (mismatch %.2e), in the tie springs %.3g J\n",
              wave == Wave::s ? "S" : "P", coupled.far_field->element_size(), t.reflection, crossed,
              arrived, t.energy_mismatch, coupled.ties->tie_energy());
  record(wave == Wave::s ? "S" : "P", "blocks_to_far_field", s.block_size,
         coupled.far_field->element_size(), t.reflection, t.energy_mismatch, s.dt, integrator, got,
         expected);
  return t;
}

/// Far field (source side) into the blocks.
Transparency far_field_into_blocks(Wave wave, dda::Integrator integrator)
{
  UpwardSpec s;
  s.wave = wave;
  s.integrator = integrator;
  s.interface = interface;
  s.dda_top = s.reference_top = far_end;
  s.monitor_height = monitor;
  const auto n_steps = static_cast<std::size_t>(std::llround(window / s.dt));
  const auto history = [&](UpwardColumn& c)
  {
    std::vector<double> h;
    for (std::size_t k = 0; k < n_steps; ++k)
    {
      const bool ok = c.advance(s.dt);
      EXPECT_TRUE(ok);
      if (!ok)
        break;
      const fem::MonitorSample m = c.far_field->sample_monitor(0);
      h.push_back(component(wave, m.displacement[0], m.displacement[1]));
    }
    return h;
  };
  UpwardSpec reference_spec = s;
  reference_spec.dda_top = 0.0;
  UpwardColumn reference(reference_spec);
  const std::vector<double> expected = history(reference);
  UpwardColumn coupled(s);
  const std::vector<double> got = history(coupled);

  Transparency t;
  t.reflection = relative_difference(got, expected);
  // What left the far field through the ties against what the blocks hold.
  const double crossed = -coupled.ties->work_on_far_field();
  const dda::EnergyBalance e = coupled.system.energy();
  const double arrived = e.stored() - e.initial;
  t.energy_mismatch = std::abs(arrived - crossed) / crossed;
  std::printf("%s far field -> blocks: reflection %.4f, energy crossed %.6g J, arrived %.6g J "
              "(mismatch %.2e), in the tie springs %.3g J\n",
              wave == Wave::s ? "S" : "P", t.reflection, crossed, arrived, t.energy_mismatch,
              coupled.ties->tie_energy());
  record(wave == Wave::s ? "S" : "P", "far_field_to_blocks", s.block_size,
         coupled.far_field->element_size(), t.reflection, t.energy_mismatch, s.dt, integrator, got,
         expected);
  return t;
}

/// One crossing of the interface: the wave, its direction, the far field's element size over the
/// blocks' and the reflection allowed (the issue's: 1 % at equal sizes, 3 % at 1:4).
struct Crossing
{
  const char* name;
  Wave wave;
  bool from_blocks; ///< blocks into the far field, else the far field into the blocks
  double size_ratio;
  double max_reflection;
};

constexpr Crossing crossings[] = {
    {"SWaveBlocksIntoFarFieldEqualSizes", Wave::s, true, 1.0, 0.01},
    {"PWaveBlocksIntoFarFieldEqualSizes", Wave::p, true, 1.0, 0.01},
    {"SWaveBlocksIntoElementsFourTimesLarger", Wave::s, true, 4.0, 0.03},
    {"PWaveBlocksIntoElementsFourTimesLarger", Wave::p, true, 4.0, 0.03},
    {"SWaveFarFieldIntoBlocks", Wave::s, false, 1.0, 0.01},
    {"PWaveFarFieldIntoBlocks", Wave::p, false, 1.0, 0.01}};

// Every crossing on both of the blocks' integrators: the trapezoidal rule and Bathe's composite
// scheme (the coupled scenes' default); the far field takes the trapezoidal rule on each of the
// blocks' (half) steps. The energy that crosses arrives within 1 %.
class InterfaceTransparency : public ::testing::TestWithParam<std::tuple<Crossing, dda::Integrator>>
{
};

TEST_P(InterfaceTransparency, ReflectsLittleAndKeepsEnergy)
{
  const auto& [crossing, integrator] = GetParam();
  const Transparency t = crossing.from_blocks
                             ? blocks_into_far_field(crossing.wave, crossing.size_ratio, integrator)
                             : far_field_into_blocks(crossing.wave, integrator);
  EXPECT_LT(t.reflection, crossing.max_reflection);
  EXPECT_LT(t.energy_mismatch, 0.01);
}

INSTANTIATE_TEST_SUITE_P(
    Crossings, InterfaceTransparency,
    ::testing::Combine(::testing::ValuesIn(crossings),
                       ::testing::Values(dda::Integrator::newmark_trapezoidal,
                                         dda::Integrator::bathe)),
    [](const ::testing::TestParamInfo<std::tuple<Crossing, dda::Integrator>>& param_info)
    {
      return std::string(std::get<0>(param_info.param).name) +
             (std::get<1>(param_info.param) == dda::Integrator::bathe ? "Bathe" : "Trapezoidal");
    });

} // namespace
} // namespace ddafem::coupling
