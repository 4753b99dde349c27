// Time-step control of a DDA System: cut dt on a failed step, grow it back after successes.
#pragma once

#include "common/checkpoint_fwd.h"
#include "dda/model_description.h"
#include "dda/system.h"

#include <cstddef>
#include <limits>
#include <map>
#include <string>

namespace ddafem::dda
{
/// What TimeStepper does after an attempt at a step (TimeStepper::decide).
enum class StepDecision
{
  accept,  ///< the attempt stands
  shorten, ///< redo it to end before a sliding contact's slip reversal
  retry,   ///< redo the same dt: a contact's penalty was raised
  cut,     ///< redo it with a smaller dt (adaptive control, not below dt_min)
  fail     ///< no step can cure it: the status goes to the caller, the model unchanged
};

/// Takes accepted steps of a System with the scene's time control (Shi's and ntdda's guards):
/// - adaptive: try the current dt; on an outcome a smaller step can cure, cut it and try again:
///   the open-close iteration not converged: dt x cut_factor (Shi: 0.3); a vertex moving r times
///   the allowed g2 w0: dt x min(0.9, 1 / sqrt(r)); too deep a penetration: the same dt again
///   with the penetrating contacts' penalty raised x 10 (System::advance does it, up to
///   ContactSettings::max_penalty_factor), then dt x cut_factor. After an accepted step dt grows
///   by growth_factor, up to the largest dt. Below dt_min the step fails with a message naming
///   the cause. A step in which a sliding contact reverses its slip with a slip error above
///   reversal_tolerance (System::localize_slip_reversals) is not a failure but an event: it is
///   redone to end just before the reversal, and the next step tries the dt of before again.
///   With a tied body (the far field, whose factorization and condensation belong to one dt)
///   dt keeps to the levels dt_max / 2^k: a cut goes down to the level at or below the dt the
///   failure asks for (a shortened step before a reversal too), and dt doubles after as many
///   accepted steps at a level as growth_factor takes to double it. Only a step shortened to land
///   on a stage's end leaves the ladder.
/// - fixed: every step has the largest dt; any failure is final.
/// With Bathe's composite scheme (Integrator::bathe) a step of dt is two System steps of dt/2,
/// the pair's trapezoidal and backward Euler halves. When the second half fails, the first
/// stands (a trapezoidal step of dt/2, a state the next pair starts from): step() returns it as
/// the accepted step and the next step tries the dt the failure asks for (a final failure is
/// returned with the model at the pair's middle).
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
  /// Failed attempts retried with a smaller dt, by the failure that asked for them
  const std::map<StepOutcome, std::size_t>& cuts_by_cause() const { return cut_causes; }
  std::size_t n_cuts() const; ///< failed attempts retried with a smaller dt
  std::size_t n_cut_steps() const { return cut_step_count; } ///< steps that needed a cut
  std::size_t n_last_step_cuts() const { return last_cuts; } ///< cuts of the last step
  /// Retries of the same dt after a contact's penalty was raised
  std::size_t n_penalty_raises() const { return penalty_raise_count; }
  /// Steps shortened to end at a sliding contact's slip reversal
  std::size_t n_reversals() const { return reversal_count; }

  /// Checkpoints (dda/stage_checkpoint.cc): the dt to try, the counters and a broken pair.
  void save(CheckpointOut& archive) const;
  void load(CheckpointIn& archive);

private:
  System& system;
  TimeControl control;
  double dt_max, dt_min, cut_factor, growth_factor;
  double dt;
  double accepted_dt = 0.0;
  std::map<StepOutcome, std::size_t> cut_causes;
  std::size_t cut_step_count = 0;
  std::size_t last_cuts = 0;
  std::size_t penalty_raise_count = 0;
  std::size_t reversal_count = 0;
  double reversal_tolerance = 0.0; ///< [m]; 0: fixed control, no localisation
  double resume_dt = 0.0;          ///< after a step shortened at a reversal: the dt to go on with
  bool composite = false;          ///< Integrator::bathe: a step is a pair of half steps
  bool ladder = false;             ///< adaptive with a tied body: dt on levels dt_max / 2^k
  std::size_t regrow_steps = 1;    ///< ladder: accepted steps at a level before dt doubles
  std::size_t level_successes = 0; ///< ladder: accepted steps since dt last changed

  /// Ladder: the largest level dt_max / 2^k at or below `x` [s]; otherwise x.
  double on_ladder(double x) const;
  /// The dt after an accepted step of adaptive control.
  double grown_dt(const StepStatus& accepted);
  /// Composite: the failure of the last pair's second half when its first half stood
  StepStatus broken_pair;
  bool pair_broken = false;

  /// The System's step of `trial` [s], or a composite pair of halves (sets pair_broken and
  /// broken_pair when only the first half stands).
  StepStatus advance(double trial);
  /// advance(trial), redone with the reversal taken within the step when it is too close to
  /// dt_min to end before it.
  StepStatus attempt(double trial);
  /// What to do after an attempt of `trial` [s] that ended in `status`.
  StepDecision decide(const StepStatus& status, double trial) const;
  /// StepDecision::accept: the dt of the next step (grown, or resumed after a reversal).
  void accept(const StepStatus& status, double trial);
  /// StepDecision::shorten: the next step, of a (half) step of `trial` [s], ends before the
  /// reversal; the one after it resumes the dt of before.
  void shorten(const StepStatus& status, double trial);
  /// StepDecision::cut: the next attempt's dt, from the failure of one of `trial` [s].
  void cut(const StepStatus& status, double trial);
  /// StepDecision::fail: what the failure's message gains (why no smaller dt is tried).
  std::string why_final(const StepStatus& status) const;
  /// After a composite pair of `trial` [s] whose first half stood: the dt of the next step from
  /// the second half's failure (success), or that failure when no step can cure it.
  StepStatus after_broken_pair(const StepStatus& first_half, double trial);

  /// The dt of the step that ends before a slip reversal found by a trial of `trial` [s]; 0 when
  /// that would be below dt_min (the reversal is then taken within the step).
  double reversal_dt(const StepStatus& status, double trial) const;

  /// The dt to retry after a failed step of `trial` [s] (adaptive control).
  double reduced_dt(const StepStatus& status, double trial) const;
};

} // namespace ddafem::dda
