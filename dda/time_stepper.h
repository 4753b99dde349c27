// Time-step control of a DDA System: cut dt on a failed step, grow it back after successes.
#pragma once

#include "dda/model_description.h"
#include "dda/system.h"

#include <cstddef>
#include <limits>

namespace ddafem::dda
{
/// Takes accepted steps of a System with the scene's time control (Shi's scheme):
/// - adaptive: try the current dt; on an outcome a smaller step can cure (open-close iteration
///   not converged, a vertex moving beyond g2 w0, too deep a penetration) multiply dt by
///   cut_factor and try again; after an accepted step multiply dt by growth_factor, up to the
///   largest dt. Below dt_min the step fails with a message naming the cause.
/// - fixed: every step has the largest dt; any failure is final.
class TimeStepper
{
public:
  /// `dt_max` [s]: the largest (and first) step; 0 takes settings.dt.
  TimeStepper(System& system, const TimeSettings& settings, double dt_max = 0.0);

  /// One accepted step no longer than `dt_limit` [s] (to land on a stage's end). The status is
  /// that of the accepted step, or of the final failure (the System is then unchanged).
  StepStatus step(double dt_limit = std::numeric_limits<double>::infinity());

  double next_dt() const { return dt; }          ///< what the next step tries [s]
  double last_dt() const { return accepted_dt; } ///< of the last accepted step [s]
  double smallest_dt() const { return dt_min; }
  std::size_t n_cuts() const { return cut_count; } ///< failed attempts retried with a smaller dt
  std::size_t n_cut_steps() const { return cut_step_count; } ///< steps that needed a cut

private:
  System& system;
  TimeControl control;
  double dt_max, dt_min, cut_factor, growth_factor;
  double dt;
  double accepted_dt = 0.0;
  std::size_t cut_count = 0;
  std::size_t cut_step_count = 0;
};

} // namespace ddafem::dda
