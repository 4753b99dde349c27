#include "dda/time_stepper.h"

#include <algorithm>
#include <sstream>

namespace ddafem::dda
{
TimeStepper::TimeStepper(System& system_, const TimeSettings& settings, double dt_max_)
    : system(system_), control(settings.control), dt_max(dt_max_ > 0.0 ? dt_max_ : settings.dt),
      dt_min(settings.dt_min > 0.0 ? std::min(settings.dt_min, dt_max) : 1e-4 * dt_max),
      cut_factor(settings.cut_factor), growth_factor(settings.growth_factor), dt(dt_max)
{
}

StepStatus TimeStepper::step(double dt_limit)
{
  bool was_cut = false;
  while (true)
  {
    const double trial = std::min(dt, dt_limit);
    StepStatus status = system.advance(trial);
    if (status.outcome == StepOutcome::success)
    {
      accepted_dt = trial;
      if (was_cut)
        ++cut_step_count;
      else if (control == TimeControl::adaptive)
        dt = std::min(dt_max, dt * growth_factor);
      return status;
    }
    if (!can_retry_with_smaller_step(status.outcome))
      return status;
    std::ostringstream m;
    if (control == TimeControl::fixed)
    {
      m << status.message << "; `time.control: fixed` keeps dt, expected a smaller `time.dt` or "
        << "`time.control: adaptive`";
      status.message = m.str();
      return status;
    }
    if (trial * cut_factor < dt_min * (1.0 - 1e-12))
    {
      m << status.message << "; dt cannot be cut below `time.dt_min` = " << dt_min << " s";
      status.message = m.str();
      return status;
    }
    dt = trial * cut_factor;
    ++cut_count;
    was_cut = true;
  }
}

} // namespace ddafem::dda
