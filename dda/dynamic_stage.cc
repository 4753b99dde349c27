#include "dda/dynamic_stage.h"

#include "dda/submatrices.h"

#include <algorithm>
#include <limits>
#include <optional>
#include <utility>

namespace ddafem::dda
{
double block_speed(const Block& block)
{
  double speed = 0.0;
  for (const Point& x : block.vertices)
    speed =
        std::max(speed, (displacement_matrix(block.moments.centroid, x) * block.velocity).norm());
  return speed;
}

SettleDetector::SettleDetector(const System& system, const SettleCriterion& criterion_,
                               std::vector<Vector2> reference_)
    : criterion(criterion_), reference(std::move(reference_)),
      quiet(system.blocks().list.size(), 0.0), has_fallen(system.blocks().list.size(), false),
      tied(system.blocks().list.size(), false)
{
  for (const MaterialPoint& p : system.ties().points)
    tied[p.block] = true;
  const Vector2 g = system.get_model().gravity;
  if (g.norm() > 0.0)
    down = g.normalized();
  reference.resize(quiet.size(), Vector2::Zero());
}

bool SettleDetector::observe(const System& system, double dt)
{
  const std::vector<Block>& blocks = system.blocks().list;
  bool settled = true;
  moving_speed = 0.0;
  for (std::size_t i = 0; i < blocks.size(); ++i)
  {
    if (tied[i])
      continue;
    const double speed = block_speed(blocks[i]);
    quiet[i] = speed <= criterion.rest_speed ? quiet[i] + dt : 0.0;
    if (criterion.fall_distance > 0.0 && down.squaredNorm() > 0.0 && !has_fallen[i] &&
        (blocks[i].displacement() - reference[i]).dot(down) >= criterion.fall_distance)
      has_fallen[i] = true;
    if (has_fallen[i] || quiet[i] >= criterion.rest_duration)
      continue;
    settled = false;
    moving_speed = std::max(moving_speed, speed);
  }
  return settled;
}

std::vector<std::size_t> SettleDetector::moving() const
{
  std::vector<std::size_t> ids;
  for (std::size_t i = 0; i < quiet.size(); ++i)
    if (!tied[i] && !has_fallen[i] && quiet[i] < criterion.rest_duration)
      ids.push_back(i);
  return ids;
}

std::vector<std::size_t> SettleDetector::fallen() const
{
  std::vector<std::size_t> ids;
  for (std::size_t i = 0; i < has_fallen.size(); ++i)
    if (has_fallen[i])
      ids.push_back(i);
  return ids;
}

std::vector<std::size_t> SettleDetector::out_of_place(const System& system) const
{
  std::vector<std::size_t> ids;
  const std::vector<Block>& blocks = system.blocks().list;
  for (std::size_t i = 0; i < blocks.size(); ++i)
  {
    const Vector2 moved = blocks[i].displacement() - reference[i];
    if (!has_fallen[i] || system.blocks().is_removed(i) || moved.squaredNorm() == 0.0)
      continue;
    // Along the direction it moved (a separating axis): the nearest of its vertices now has
    // passed the farthest of where they were (at t = 0, shifted by the reference displacement).
    const Vector2 u = moved.normalized();
    double farthest_before = -std::numeric_limits<double>::infinity();
    for (const Point& x : blocks[i].initial_vertices)
      farthest_before = std::max(farthest_before, x.dot(u));
    farthest_before += reference[i].dot(u);
    double nearest_now = std::numeric_limits<double>::infinity();
    for (const Point& x : blocks[i].vertices)
      nearest_now = std::min(nearest_now, x.dot(u));
    if (nearest_now >= farthest_before)
      ids.push_back(i);
  }
  return ids;
}

DynamicStageRun::DynamicStageRun(System& system_, const Stage& stage_, const TimeSettings& time_,
                                 const std::vector<Vector2>& fall_reference)
    : system(system_), stage(stage_), time(time_), first_step(system_.n_steps()),
      stepper(system_, time_)
{
  result.end_time = stage.settle ? system.time() + stage.settle->max_duration : stage.end_time;
  result.smallest_dt = time.dt;
  if (stage.settle)
    detector.emplace(system, *stage.settle, fall_reference);
}

bool DynamicStageRun::at_end() const
{
  // Within round-off of the end (1e-9 dt) counts as there.
  return system.time() >= result.end_time - 1e-9 * time.dt;
}

void DynamicStageRun::observe_settling()
{
  result.settled = detector->observe(system, stepper.last_dt());
  if (stage.settle->remove_fallen)
    for (const std::size_t i : detector->out_of_place(system))
    {
      system.remove_block(i);
      result.removed.emplace_back(i, system.time());
    }
}

DynamicStageResult DynamicStageRun::run(const AfterDynamicStep& after_step)
{
  // (A run loaded from a checkpoint taken after the settling step has settled already.)
  while (!result.settled && !at_end())
  {
    const StepStatus status = stepper.step(result.end_time - system.time());
    if (status.outcome != StepOutcome::success)
    {
      result.failure = status;
      break;
    }
    result.n_flips_ignored += status.n_flips_ignored;
    result.smallest_dt = std::min(result.smallest_dt, stepper.last_dt());
    if (detector)
      observe_settling();
    if (after_step && !after_step(stepper, status, result.settled || at_end()))
    {
      result.stopped = !result.settled && !at_end();
      break;
    }
    if (result.settled)
      break;
  }
  result.n_steps = system.n_steps() - first_step;
  result.n_cuts = stepper.n_cuts();
  result.n_cut_steps = stepper.n_cut_steps();
  result.n_penalty_raises = stepper.n_penalty_raises();
  result.cuts_by_cause = stepper.cuts_by_cause();
  result.n_reversals = stepper.n_reversals();
  if (detector)
  {
    result.moving = detector->moving();
    result.fallen = detector->fallen();
    result.moving_speed = detector->largest_moving_speed();
  }
  return result;
}

DynamicStageResult run_dynamic_stage(System& system, const Stage& stage, const TimeSettings& time,
                                     const std::vector<Vector2>& fall_reference,
                                     const AfterDynamicStep& after_step)
{
  return DynamicStageRun(system, stage, time, fall_reference).run(after_step);
}

} // namespace ddafem::dda
