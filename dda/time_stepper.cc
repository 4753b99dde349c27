#include "dda/time_stepper.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace ddafem::dda
{
TimeStepper::TimeStepper(System& system_, const TimeSettings& settings, double dt_max_)
    : system(system_), control(settings.control), dt_max(dt_max_ > 0.0 ? dt_max_ : settings.dt),
      dt_min(settings.dt_min > 0.0 ? std::min(settings.dt_min, dt_max) : 1e-4 * dt_max),
      cut_factor(settings.cut_factor), growth_factor(settings.growth_factor), dt(dt_max),
      reversal_tolerance(control == TimeControl::adaptive ? settings.reversal_tolerance : 0.0)
{
  system.localize_slip_reversals(reversal_tolerance);
}

double TimeStepper::reversal_dt(const StepStatus& status, double trial) const
{
  // End 5% short of the estimated reversal, so that the next step meets it at its very start.
  const double shortened = 0.95 * status.reversal_fraction * trial;
  return shortened < dt_min ? 0.0 : shortened;
}

double TimeStepper::reduced_dt(const StepStatus& status, double trial) const
{
  if (status.outcome == StepOutcome::displacement_too_large && status.max_displacement > 0.0)
  {
    const double ratio = status.max_displacement / system.max_step_displacement();
    return trial * std::min(0.9, 1.0 / std::sqrt(ratio));
  }
  return trial * cut_factor;
}

StepStatus TimeStepper::step(double dt_limit)
{
  last_cuts = 0;
  while (true)
  {
    const double trial = std::min(dt, dt_limit);
    StepStatus status = system.advance(trial);
    if (status.outcome == StepOutcome::slip_reversal)
    {
      const double shortened = reversal_dt(status, trial);
      if (shortened == 0.0)
      {
        // Too close to dt_min to end before it: take the reversal within this step.
        system.localize_slip_reversals(0.0);
        status = system.advance(trial);
        system.localize_slip_reversals(reversal_tolerance);
      }
      else
      {
        if (resume_dt == 0.0)
          resume_dt = dt;
        dt = shortened;
        continue;
      }
    }
    if (status.outcome == StepOutcome::success)
    {
      accepted_dt = trial;
      if (last_cuts > 0)
        ++cut_step_count;
      else if (resume_dt > 0.0)
      {
        dt = resume_dt;
        ++reversal_count;
      }
      else if (control == TimeControl::adaptive)
        dt = std::min(dt_max, dt * growth_factor);
      resume_dt = 0.0;
      return status;
    }
    if (!can_retry_with_smaller_step(status.outcome))
      return status;
    if (status.penalty_raised)
    {
      ++penalty_raise_count;
      continue;
    }
    std::ostringstream m;
    if (control == TimeControl::fixed)
    {
      m << status.message << "; `time.control: fixed` keeps dt, expected a smaller `time.dt` or "
        << "`time.control: adaptive`";
      status.message = m.str();
      return status;
    }
    const double next = reduced_dt(status, trial);
    if (next < dt_min * (1.0 - 1e-12))
    {
      m << status.message << "; dt cannot be cut below `time.dt_min` = " << dt_min << " s";
      status.message = m.str();
      return status;
    }
    dt = next;
    ++cut_count;
    ++last_cuts;
  }
}

} // namespace ddafem::dda
