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
      reversal_tolerance(control == TimeControl::adaptive ? settings.reversal_tolerance : 0.0),
      composite(settings.integrator == Integrator::bathe),
      ladder(control == TimeControl::adaptive && system_.ties().has_body())
{
  system.localize_slip_reversals(reversal_tolerance);
  if (ladder && growth_factor > 1.0)
    regrow_steps = static_cast<std::size_t>(std::ceil(std::log(2.0) / std::log(growth_factor)));
}

std::size_t TimeStepper::n_cuts() const
{
  std::size_t n = 0;
  for (const auto& [outcome, count] : cut_causes)
    n += count;
  return n;
}

double TimeStepper::on_ladder(const double x) const
{
  if (!ladder || x >= dt_max)
    return std::min(x, dt_max);
  const double k = std::ceil(std::log2(dt_max / x) - 1e-9);
  return dt_max * std::exp2(-k);
}

double TimeStepper::grown_dt(const StepStatus& accepted)
{
  if (!ladder)
    return std::min(dt_max, dt * growth_factor);
  // A vertex's step displacement grows about as dt: doubling dt when the accepted step used
  // more than 0.45 of the limit only moves it past the limit and cuts back (a block falling
  // freely would climb and be cut every few steps); stay on the level while it would.
  if (2.0 * accepted.max_displacement > 0.9 * system.contacts().distances.max_step_displacement)
    return dt;
  if (++level_successes < regrow_steps || dt >= dt_max)
    return dt;
  level_successes = 0;
  return std::min(dt_max, 2.0 * dt);
}

double TimeStepper::reversal_dt(const StepStatus& status, double trial) const
{
  // End 5% short of the estimated reversal, so that the next step meets it at its very start.
  const double shortened = on_ladder(0.95 * status.reversal_fraction * trial);
  return shortened < dt_min ? 0.0 : shortened;
}

double TimeStepper::reduced_dt(const StepStatus& status, double trial) const
{
  if (status.outcome == StepOutcome::displacement_too_large && status.max_displacement > 0.0)
  {
    const double ratio =
        status.max_displacement / system.contacts().distances.max_step_displacement;
    return on_ladder(trial * std::min(0.9, 1.0 / std::sqrt(ratio)));
  }
  return on_ladder(trial * cut_factor);
}

StepStatus TimeStepper::advance(double trial)
{
  pair_broken = false;
  if (!composite)
    return system.advance(trial);
  const StepStatus first = system.advance(0.5 * trial, StepPart::first_half);
  if (first.outcome != StepOutcome::success)
    return first;
  StepStatus second = system.advance(0.5 * trial, StepPart::second_half);
  // A raised penalty is retried at once (bounded by ContactSettings::max_penalty_factor); a
  // reversal too early in the half to end before is taken within it.
  while (second.outcome == StepOutcome::penetration_too_large && second.penalty_raised)
  {
    ++penalty_raise_count;
    second = system.advance(0.5 * trial, StepPart::second_half);
  }
  if (second.outcome == StepOutcome::slip_reversal && reversal_dt(second, 0.5 * trial) == 0.0)
  {
    system.localize_slip_reversals(0.0);
    second = system.advance(0.5 * trial, StepPart::second_half);
    system.localize_slip_reversals(reversal_tolerance);
  }
  if (second.outcome != StepOutcome::success)
  {
    pair_broken = true;
    broken_pair = second;
    return first;
  }
  second.n_open_close_iterations += first.n_open_close_iterations;
  second.n_state_changes += first.n_state_changes;
  second.n_flips_ignored += first.n_flips_ignored;
  second.max_displacement = std::max(second.max_displacement, first.max_displacement);
  second.max_penetration = std::max(second.max_penetration, first.max_penetration);
  return second;
}

StepDecision TimeStepper::decide(const StepStatus& status, double trial) const
{
  if (status.outcome == StepOutcome::success)
    return StepDecision::accept;
  if (status.outcome == StepOutcome::slip_reversal)
    return StepDecision::shorten;
  if (!can_retry_with_smaller_step(status.outcome))
    return StepDecision::fail;
  if (status.penalty_raised)
    return StepDecision::retry;
  if (control == TimeControl::fixed || reduced_dt(status, trial) < dt_min * (1.0 - 1e-12))
    return StepDecision::fail;
  return StepDecision::cut;
}

std::string TimeStepper::why_final(const StepStatus& status) const
{
  if (!can_retry_with_smaller_step(status.outcome))
    return "";
  std::ostringstream m;
  if (control == TimeControl::fixed)
    m << "; `time.control: fixed` keeps dt, expected a smaller `time.dt` or "
      << "`time.control: adaptive`";
  else
    m << "; dt cannot be cut below `time.dt_min` = " << dt_min << " s";
  return m.str();
}

void TimeStepper::cut(const StepStatus& status, double trial)
{
  dt = reduced_dt(status, trial);
  level_successes = 0;
  ++cut_causes[status.outcome];
}

void TimeStepper::shorten(const StepStatus& status, double trial)
{
  // End the next (pair of half) step(s) before the reversal, then go on with the dt of before.
  if (resume_dt == 0.0)
    resume_dt = dt;
  dt = reversal_dt(status, trial);
}

StepStatus TimeStepper::after_broken_pair(const StepStatus& first_half, double trial)
{
  accepted_dt = 0.5 * trial;
  StepStatus failure = broken_pair;
  switch (decide(failure, trial))
  {
  case StepDecision::shorten:
    shorten(failure, 0.5 * trial);
    return first_half;
  case StepDecision::cut:
    cut(failure, trial);
    ++cut_step_count;
    return first_half;
  default: // accept and retry cannot follow a broken pair (advance retries raised penalties)
    failure.message +=
        " (the second half of a composite step; its first half stands)" + why_final(failure);
    return failure;
  }
}

StepStatus TimeStepper::attempt(double trial)
{
  StepStatus status = advance(trial);
  // Too close to dt_min to end before a reversal: take it within this step.
  if (!pair_broken && status.outcome == StepOutcome::slip_reversal &&
      reversal_dt(status, composite ? 0.5 * trial : trial) == 0.0)
  {
    system.localize_slip_reversals(0.0);
    status = advance(trial);
    system.localize_slip_reversals(reversal_tolerance);
  }
  return status;
}

void TimeStepper::accept(const StepStatus& status, double trial)
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
    dt = grown_dt(status);
  resume_dt = 0.0;
}

StepStatus TimeStepper::step(double dt_limit)
{
  last_cuts = 0;
  while (true)
  {
    const double trial = std::min(dt, dt_limit);
    StepStatus status = attempt(trial);
    if (pair_broken)
      return after_broken_pair(status, trial);
    switch (decide(status, trial))
    {
    case StepDecision::accept:
      accept(status, trial);
      return status;
    case StepDecision::shorten: // a composite pair ends before a reversal in its first half
      shorten(status, composite ? 0.5 * trial : trial);
      break;
    case StepDecision::retry:
      ++penalty_raise_count;
      break;
    case StepDecision::cut:
      cut(status, trial);
      ++last_cuts;
      break;
    case StepDecision::fail:
      status.message += why_final(status);
      return status;
    }
  }
}

} // namespace ddafem::dda
