#include "dda/static_stage.h"

#include <algorithm>

namespace ddafem::dda
{
ReleaseDetector::ReleaseDetector(const System& system, ReleaseCriterion criterion_)
    : criterion(criterion_), watches(system.blocks().list.size())
{
  for (const Block& b : system.blocks().list)
    last_centroids.push_back(b.moments.centroid);
}

std::vector<std::size_t> ReleaseDetector::observe(const System& system)
{
  std::vector<std::size_t> released;
  const std::vector<BlockBalance>& balances = system.block_balances();
  for (std::size_t i = 0; i < watches.size(); ++i)
  {
    const Point centroid = system.blocks().list[i].moments.centroid;
    const Vector2 step = centroid - last_centroids[i];
    last_centroids[i] = centroid;
    Watch& w = watches[i];
    const double force = balances[i].out_of_balance.norm();
    if (system.blocks().is_held(i) || balances[i].ratio() < criterion.min_ratio)
    {
      w = {};
      continue;
    }
    if (w.n_steps == 0)
      w.start_force = force;
    ++w.n_steps;
    w.travel += step;
    w.path += step.norm();
    if (w.n_steps < criterion.window)
      continue;
    const bool undiminished = force >= (1.0 - criterion.max_force_drop) * w.start_force;
    const bool straight = w.path > 0.0 && w.travel.norm() >= criterion.min_straightness * w.path;
    if (undiminished && straight)
      released.push_back(i);
    w = {};
  }
  return released;
}

namespace
{
TimeSettings pseudo_time(TimeSettings time)
{
  time.control = TimeControl::adaptive;
  return time;
}
} // namespace

StaticStageRun::StaticStageRun(System& system_, const Stage& stage_, const TimeSettings& time,
                               ReleaseCriterion criterion)
    : system(system_), stage(stage_), stepper(system_, pseudo_time(time), stage_.dt),
      detector(system_, criterion)
{
  result.smallest_dt = stepper.next_dt();
}

std::size_t StaticStageRun::release_blocks()
{
  const std::vector<std::size_t> released = detector.observe(system);
  for (const std::size_t i : released)
  {
    result.released.push_back({i, result.n_steps, system.blocks().mass_of(i),
                               system.blocks().list[i].moments.centroid,
                               system.block_balances()[i].ratio()});
    if (stage.release == ReleaseAction::remove)
      system.remove_block(i);
    else
      system.hold_block(i);
  }
  return released.size();
}

StaticStageResult StaticStageRun::run(const std::function<bool()>& after_step)
{
  // (A run loaded from a checkpoint taken at its equilibrium step has ended already.)
  while (result.outcome == StaticOutcome::not_converged && result.n_steps < stage.max_steps)
  {
    const StepStatus status = stepper.step();
    if (status.outcome != StepOutcome::success)
    {
      result.outcome = StaticOutcome::step_failed;
      result.failure = status;
      break;
    }
    ++result.n_steps;
    result.smallest_dt = std::min(result.smallest_dt, stepper.last_dt());
    result.ratio = status.unbalanced_force_ratio;
    result.block = status.unbalanced_block;
    // A step that released blocks measured them still: equilibrium is judged without them.
    if (release_blocks() == 0 && result.ratio <= stage.tolerance)
      result.outcome = StaticOutcome::equilibrium;
    if (after_step && !after_step())
    {
      result.stopped = result.outcome == StaticOutcome::not_converged;
      break;
    }
  }
  result.n_cuts = stepper.n_cuts();
  result.n_cut_steps = stepper.n_cut_steps();
  result.n_penalty_raises = stepper.n_penalty_raises();
  result.cuts_by_cause = stepper.cuts_by_cause();
  return result;
}

StaticStageResult run_static_stage(System& system, const Stage& stage, const TimeSettings& time,
                                   const std::function<bool()>& after_step,
                                   ReleaseCriterion criterion)
{
  system.begin_stage(StageMode::static_equilibrium);
  return StaticStageRun(system, stage, time, criterion).run(after_step);
}

} // namespace ddafem::dda
