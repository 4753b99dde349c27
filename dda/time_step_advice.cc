#include "dda/time_step_advice.h"

#include "common/elasticity.h"
#include "dda/geometry.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace ddafem::dda
{
WaveSpeeds wave_speeds(const Material& m)
{
  const double e = m.youngs_modulus, nu = m.poisson_ratio, rho = m.density;
  WaveSpeeds c;
  c.p_body = p_wave_speed(e, nu, rho);
  c.p_plate = std::sqrt(e / (rho * (1.0 - nu * nu)));
  c.p_bar = std::sqrt(e / rho);
  c.s = s_wave_speed(e, nu, rho);
  return c;
}

double governing_p_speed(PlaneMode plane_mode, const Material& material)
{
  const WaveSpeeds c = wave_speeds(material);
  return plane_mode == PlaneMode::stress ? c.p_plate : c.p_body;
}

SmallestBlock smallest_block(const std::vector<BlockDescription>& blocks)
{
  SmallestBlock s;
  for (std::size_t i = 0; i < blocks.size(); ++i)
  {
    const auto& v = blocks[i].vertices;
    const double area = std::abs(signed_area(v));
    if (area < s.area)
    {
      s.area = area;
      s.index = i;
    }
    for (std::size_t k = 0; k < v.size(); ++k)
      s.shortest_edge = std::min(s.shortest_edge, (v[(k + 1) % v.size()] - v[k]).norm());
  }
  return s;
}

namespace
{
/// Highest characteristic frequency [Hz] of the point loads, fixed-point motions and boundary
/// inputs; 0 if none varies.
double max_load_frequency(const ModelDescription& model)
{
  double f_max = 0.0;
  for (const PointLoad& l : model.point_loads)
    f_max = std::max(f_max, l.time_function.characteristic_frequency());
  for (const FixedPoint& f : model.fixed_points)
    f_max = std::max({f_max, f.displacement_x.characteristic_frequency(),
                      f.displacement_y.characteristic_frequency()});
  for (const BoundaryDescription& b : model.boundaries)
    if (b.has_input)
      f_max = std::max(f_max, b.input.velocity.characteristic_frequency());
  return f_max;
}

/// Largest side of the blocks' bounding box [m].
double model_extent(const ModelDescription& model)
{
  Eigen::AlignedBox2d box;
  for (const BlockDescription& b : model.blocks)
    for (const Point& v : b.vertices)
      box.extend(v);
  return box.sizes().maxCoeff();
}
} // namespace

TimeStepAdvice suggest_time_step(const ModelDescription& model)
{
  double c_max = 0.0;
  for (const Material& m : model.materials)
    c_max = std::max(c_max, governing_p_speed(model.plane_mode, m));
  const SmallestBlock small = smallest_block(model.blocks);
  TimeStepAdvice advice;
  advice.transit = std::sqrt(small.area) / c_max;
  advice.max_frequency = max_load_frequency(model);
  const double f_max = advice.max_frequency;
  advice.dt_max = advice.transit;
  if (f_max > 0.0 && 1.0 / (20.0 * f_max) < advice.dt_max)
  {
    advice.dt_max = 1.0 / (20.0 * f_max);
    advice.limit = TimeStepLimit::load_period;
  }
  if (f_max > 0.0 && model.time.integrator == Integrator::dda)
  {
    // Keep the loss exp(-omega^2 dt t / 4) over the time a wave crosses the model below 5%.
    const double crossing = model_extent(model) / c_max;
    const double omega = 2.0 * M_PI * f_max;
    const double dt_damping = -4.0 * std::log(0.95) / (omega * omega * crossing);
    if (dt_damping < advice.dt_max)
    {
      advice.dt_max = dt_damping;
      advice.limit = TimeStepLimit::dda_damping;
    }
  }
  advice.dt_min = advice.dt_max / 10.0;
  return advice;
}

} // namespace ddafem::dda
