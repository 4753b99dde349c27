// Shared test models of the coupling tests: a column of bonded DDA blocks driven at its base,
// optionally continued by a deal.II far-field column above it (issue 6).
#pragma once

#include "coupling/far_field_ties.h"
#include "dda/model_description.h"
#include "dda/system.h"
#include "fem/elastic_wave_model.h"

#include <cmath>
#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

namespace ddafem::coupling::test_models
{
/// Rock with nu = 0: plane waves in a column of blocks are then exactly one-dimensional.
constexpr double rho = 2650.0, young = 50e9;

enum class Wave
{
  p, ///< vertical particle motion
  s  ///< horizontal particle motion
};

/// A column of width `width` [m]: a driven base block [0, width] x [0, h], layers of
/// blocks_per_row blocks of height h up to `dda_top`, and (fe_top > dda_top) a far-field column up
/// to fe_top with elements of `element_size`, rollers on its sides and Lysmer dashpots on top. The
/// base follows one sine cycle of displacement (frequency [Hz], amplitude 1 mm) along the wave's
/// particle motion. Both sides integrate with the trapezoidal rule (energy-conserving).
struct ColumnSpec
{
  Wave wave = Wave::s;
  double width = 20.0;
  double block_size = 1.0; ///< layer thickness h [m]
  std::size_t blocks_per_row = 1;
  double dda_top = 40.0;
  double fe_top = 0.0;
  double element_size = 1.0;
  double frequency = 100.0;
  double dt = 2e-5;
  std::vector<double> monitor_heights; ///< in the blocks, at the column's centre line
  /// The blocks' integrator (the far field takes the trapezoidal rule on each of their steps,
  /// each half of Bathe's)
  dda::Integrator integrator = dda::Integrator::newmark_trapezoidal;
};

/// One step of dt [s] of a System with `integrator`: two System steps of dt / 2 for Bathe's
/// composite scheme.
inline dda::StepStatus step_blocks(dda::System& system, double dt, dda::Integrator integrator)
{
  if (integrator != dda::Integrator::bathe)
    return system.advance(dt);
  const dda::StepStatus first = system.advance(0.5 * dt, dda::StepPart::first_half);
  return first.outcome == dda::StepOutcome::success
             ? system.advance(0.5 * dt, dda::StepPart::second_half)
             : first;
}

/// Joint and tie normal spring p [N/m] at each end of a horizontal edge: the two springs over
/// the width add 0.1% to a layer's normal compliance (width / (2 p) against h / E) and 0.25% to
/// its shear compliance (shear ratio 0.4), so that the blocks carry the continuum's impedance.
inline double joint_stiffness(const ColumnSpec& s)
{
  return 500.0 * young * s.width / static_cast<double>(s.blocks_per_row) / s.block_size;
}

inline dda::BlockDescription block(std::vector<dda::Point> vertices)
{
  dda::BlockDescription b;
  b.vertices = std::move(vertices);
  return b;
}

inline dda::ModelDescription column_blocks(const ColumnSpec& s)
{
  dda::ModelDescription m;
  m.plane_mode = dda::PlaneMode::strain;
  m.geometry = dda::GeometryMode::small_displacement;
  m.materials.push_back({"rock", rho, young, 0.0});
  m.joint_materials.push_back({"bond", joint_stiffness(s), 0.4, 45.0, 1e9, 1e9, true});
  m.default_joint_material = 0;
  const double h = s.block_size;
  m.blocks.push_back(block({{0, 0}, {s.width, 0}, {s.width, h}, {0, h}}));
  const std::size_t n_x = s.blocks_per_row;
  const double w = s.width / static_cast<double>(n_x);
  const auto n_y = static_cast<std::size_t>(std::llround(s.dda_top / h)) - 1;
  for (std::size_t j = 0; j < n_y; ++j)
    for (std::size_t i = 0; i < n_x; ++i)
    {
      const double x = w * static_cast<double>(i), y = h * static_cast<double>(j + 1);
      m.blocks.push_back(block({{x, y}, {x + w, y}, {x + w, y + h}, {x, y + h}}));
    }
  const TimeFunction pulse = TimeFunction::sine_pulse(1e-3, s.frequency, 1.0, 0.0);
  for (const double x : {0.125 * s.width, 0.5 * s.width, 0.875 * s.width})
  {
    dda::FixedPoint f;
    f.point = {x, 0.5 * h};
    f.stiffness = 1e14;
    (s.wave == Wave::s ? f.displacement_x : f.displacement_y) = pulse;
    m.fixed_points.push_back(f);
  }
  for (const double y : s.monitor_heights)
    m.monitors.push_back({"m", {w * (static_cast<double>(n_x / 2) + 0.5), y}});
  m.time.dt = s.dt;
  m.time.end_time = 1.0;
  m.time.integrator = s.integrator;
  m.time.control = dda::TimeControl::fixed;
  return m;
}

inline fem::FarFieldDescription column_far_field(const ColumnSpec& s)
{
  fem::FarFieldDescription d;
  d.lower = {{0.0, s.dda_top}};
  d.upper = {{s.width, s.fe_top}};
  d.element_size = s.element_size;
  d.degree = 2;
  d.density = rho;
  d.youngs_modulus = young;
  d.poisson_ratio = 0.0;
  d.plane_mode = fem::PlaneMode::strain;
  d.incident.type = s.wave == Wave::s ? fem::IncidentWave::Type::sv : fem::IncidentWave::Type::p;
  d.boundaries = {{fem::BoundaryPart::left, fem::BoundaryKind::roller, 1.0, 1.0, {}},
                  {fem::BoundaryPart::right, fem::BoundaryKind::roller, 1.0, 1.0, {}},
                  {fem::BoundaryPart::top, fem::BoundaryKind::lysmer, 1.0, 1.0, {}}};
  d.dt = s.dt;
  d.integrator = fem::Integrator::newmark_trapezoidal;
  return d;
}

/// A column model in time; `ties` is empty for blocks only.
struct Column
{
  explicit Column(const ColumnSpec& spec) : system(column_blocks(spec))
  {
    if (spec.fe_top > spec.dda_top)
    {
      far_field = std::make_unique<fem::ElasticWaveModel>(column_far_field(spec));
      InterfaceDescription tie;
      tie.part = fem::BoundaryPart::bottom;
      tie.normal_stiffness = joint_stiffness(spec);
      ties = std::make_unique<FarFieldTies>(system, *far_field, tie);
    }
  }
  dda::System system;
  std::unique_ptr<fem::ElasticWaveModel> far_field;
  std::unique_ptr<FarFieldTies> ties;
};

} // namespace ddafem::coupling::test_models

namespace ddafem::coupling::test_models
{
/// The wave the other way: a far-field column [0, width] x [0, interface] with an absorbing
/// base through which a plane pulse enters (0.1 m/s, one sine cycle), rollers on its sides, and
/// (dda_top > interface) a column of one-block layers from the interface up to dda_top, free on
/// top; else the far field reaches up to `reference_top`, free on top.
struct UpwardSpec
{
  Wave wave = Wave::s;
  double width = 20.0;
  double block_size = 1.0;
  double element_size = 1.0;
  double interface = 40.0;
  double dda_top = 100.0;
  double reference_top = 100.0;
  double frequency = 100.0;
  double dt = 2e-5;
  double monitor_height = 20.0;
  dda::Integrator integrator = dda::Integrator::newmark_trapezoidal; ///< as ColumnSpec's
};

struct UpwardColumn
{
  explicit UpwardColumn(const UpwardSpec& s) : system(blocks(s)), integrator(s.integrator)
  {
    fem::FarFieldDescription d;
    ColumnSpec c;
    c.wave = s.wave;
    c.width = s.width;
    c.element_size = s.element_size;
    c.dt = s.dt;
    c.dda_top = 0.0;
    c.fe_top = s.dda_top > s.interface ? s.interface : s.reference_top;
    d = column_far_field(c);
    d.boundaries = {{fem::BoundaryPart::left, fem::BoundaryKind::roller, 1.0, 1.0, {}},
                    {fem::BoundaryPart::right, fem::BoundaryKind::roller, 1.0, 1.0, {}},
                    {fem::BoundaryPart::bottom, fem::BoundaryKind::input, 1.0, 1.0, {}}};
    d.incident.velocity = TimeFunction::sine_pulse(0.1, s.frequency, 1.0, 0.0);
    d.monitors.push_back({"m", {{0.5 * s.width, s.monitor_height}}});
    far_field = std::make_unique<fem::ElasticWaveModel>(d);
    if (s.dda_top > s.interface)
    {
      InterfaceDescription tie;
      tie.part = fem::BoundaryPart::top;
      tie.normal_stiffness = joint_stiffness(c);
      ties = std::make_unique<FarFieldTies>(system, *far_field, tie);
    }
  }

  /// The layers above the interface (a single layer stands in when there are none: the System
  /// needs a block; it is then never stepped).
  static dda::ModelDescription blocks(const UpwardSpec& s)
  {
    ColumnSpec c;
    c.width = s.width;
    c.block_size = s.block_size;
    c.dt = s.dt;
    c.integrator = s.integrator;
    dda::ModelDescription m = column_blocks(c);
    m.blocks.clear();
    m.fixed_points.clear();
    const double h = s.block_size;
    const auto n = std::max<long>(1, std::lround((s.dda_top - s.interface) / h));
    for (long j = 0; j < n; ++j)
    {
      const double y = s.interface + h * static_cast<double>(j);
      m.blocks.push_back(block({{0, y}, {s.width, y}, {s.width, y + h}, {0, y + h}}));
    }
    return m;
  }

  /// One step of both sides (the blocks step the far field through the ties).
  bool advance(double dt)
  {
    if (ties)
      return step_blocks(system, dt, integrator).outcome == dda::StepOutcome::success;
    // The far field alone as it steps in the coupled model: per half step with Bathe's scheme.
    const int n = integrator == dda::Integrator::bathe ? 2 : 1;
    for (int k = 0; k < n; ++k)
      if (!far_field->advance(dt / n).taken)
        return false;
    return true;
  }

  dda::System system;
  dda::Integrator integrator;
  std::unique_ptr<fem::ElasticWaveModel> far_field;
  std::unique_ptr<FarFieldTies> ties;
};
} // namespace ddafem::coupling::test_models
