// The time step a model of blocks asks for: its materials' wave speeds, its smallest block and
// the frequencies of its loads bound the dt that resolves them (`ddafem check` prints the
// advice, `run` warns beyond it).
#pragma once

#include "dda/model_description.h"

#include <cstddef>
#include <limits>
#include <vector>

namespace ddafem::dda
{
/// Wave speeds of an isotropic elastic material [m/s].
struct WaveSpeeds
{
  double p_body = 0.0;  ///< sqrt(E (1-nu) / (rho (1+nu)(1-2nu))), plane strain / 3D P wave
  double p_plate = 0.0; ///< sqrt(E / (rho (1-nu^2))), P wave in plane stress
  double p_bar = 0.0;   ///< sqrt(E / rho), one-block-high bar (free lateral faces)
  double s = 0.0;       ///< sqrt(E / (2 rho (1+nu)))
};
WaveSpeeds wave_speeds(const Material& material);

/// P-wave speed that governs blocks of `material` [m/s]: the plate speed in plane stress, the
/// body speed in plane strain.
double governing_p_speed(PlaneMode plane_mode, const Material& material);

/// The smallest block of a model: its index, area [m^2] and the shortest edge of all blocks [m].
struct SmallestBlock
{
  std::size_t index = 0;
  double area = std::numeric_limits<double>::max();
  double shortest_edge = std::numeric_limits<double>::max();
};
SmallestBlock smallest_block(const std::vector<BlockDescription>& blocks);

/// Which rule set TimeStepAdvice::dt_max.
enum class TimeStepLimit
{
  block_transit, ///< a P wave crosses the smallest block in one step
  load_period,   ///< 20 steps per period of the highest load frequency
  dda_damping    ///< DDA's algorithmic damping costs < 5% amplitude over a model crossing
};

/// Suggested time-step range [s] for a model and the rule that bounds it.
struct TimeStepAdvice
{
  double dt_min = 0.0; ///< dt_max / 10 [s]
  double dt_max = 0.0; ///< [s]
  TimeStepLimit limit = TimeStepLimit::block_transit;
  double transit = 0.0;       ///< sqrt(A_min) / VP_max: a P wave across the smallest block [s]
  double max_frequency = 0.0; ///< highest characteristic frequency of the loads [Hz], 0: none
};

/// dt_max = min(sqrt(A_min) / VP_max, 1 / (20 f_max), and with the dda integrator
/// -4 ln(0.95) / (omega^2 T)) with VP_max the fastest governing P speed, f_max the highest
/// characteristic frequency of point loads, fixed-point motions and boundary inputs,
/// omega = 2 pi f_max and T = (largest side of the blocks' bounding box) / VP_max: DDA's scheme
/// damps amplitude by about exp(-omega^2 dt t / 4) (docs/reference/physics.md section 2).
TimeStepAdvice suggest_time_step(const ModelDescription& model);

} // namespace ddafem::dda
