// A dynamic stage: the motion in time to a fixed end, or a settle stage (issue 16) that runs
// until every block is at rest or has fallen, so that "fell" in the results means fell.
#pragma once

#include "common/checkpoint_fwd.h"
#include "dda/model_description.h"
#include "dda/system.h"
#include "dda/time_stepper.h"

#include <cstddef>
#include <functional>
#include <map>
#include <optional>
#include <utility>
#include <vector>

namespace ddafem::dda
{
/// The largest speed of a block's vertices [m/s]: |T(x) v| over its vertices x (rigid motion
/// and strain rate alike).
double block_speed(const Block& block);

/// Watches a settle stage's blocks, step by step, for the SettleCriterion.
class SettleDetector
{
public:
  /// `reference`: per block, its centroid displacement [m] where falls are measured from (the
  /// start of the first dynamic stage); the fall direction is the model's gravity.
  SettleDetector(const System& system, const SettleCriterion& criterion,
                 std::vector<Vector2> reference);

  /// After an accepted step of `dt` [s]: whether every block is now at rest (speed at most
  /// rest_speed for rest_duration without a break) or has fallen. Blocks tied to a body (the far
  /// field) move as it does, its residual vibration included, and cannot fall: they are not
  /// judged (the body's dashpots are what brings them to rest).
  bool observe(const System& system, double dt);

  /// Blocks neither at rest nor fallen at the last observe, ascending.
  std::vector<std::size_t> moving() const;
  /// Blocks that have fallen (once fallen, always), ascending.
  std::vector<std::size_t> fallen() const;
  /// Fallen blocks not yet removed that have left their place: along the direction the block
  /// moved since the reference, the interval of its vertices no longer overlaps the interval
  /// they covered then (SettleCriterion::remove_fallen), ascending.
  std::vector<std::size_t> out_of_place(const System& system) const;
  /// The largest block_speed of the blocks neither at rest nor fallen [m/s] (0 if none).
  double largest_moving_speed() const { return moving_speed; }

  /// Checkpoints (dda/stage_checkpoint.cc): the blocks' time at rest and falls.
  void save(CheckpointOut& archive) const;
  void load(CheckpointIn& archive);

private:
  SettleCriterion criterion;
  std::vector<Vector2> reference;
  Vector2 down = Vector2::Zero(); ///< unit vector along gravity; zero without gravity
  std::vector<double> quiet;      ///< per block: time spent at rest without a break [s]
  std::vector<bool> has_fallen;
  std::vector<bool> tied; ///< per block: carries a tie point, not judged
  double moving_speed = 0.0;
};

/// What a dynamic (or settle) stage did.
struct DynamicStageResult
{
  StepStatus failure; ///< outcome success unless a step failed even at the smallest dt
  std::size_t n_steps = 0;
  std::size_t n_cuts = 0, n_cut_steps = 0, n_penalty_raises = 0, n_flips_ignored = 0;
  std::size_t n_reversals = 0; ///< steps shortened at a slip reversal (TimeStepper::n_reversals)
  std::map<StepOutcome, std::size_t> cuts_by_cause; ///< TimeStepper::cuts_by_cause
  double smallest_dt = 0.0;                         ///< of the accepted steps [s]
  double end_time = 0.0; ///< the time the stage was to reach [s] (settle: its bound)
  /// Settle stages: every block came to rest or fell before the bound.
  bool settled = false;
  std::vector<std::size_t> moving; ///< settle: blocks still moving at the end
  std::vector<std::size_t> fallen; ///< settle: blocks fallen
  /// settle with remove_fallen: the fallen blocks removed as debris and when [s].
  std::vector<std::pair<std::size_t, double>> removed;
  double moving_speed = 0.0; ///< settle: the fastest moving block's speed at the end [m/s]
  bool stopped = false;      ///< after_step asked to stop before the stage's end
};

/// Called after every accepted step with the stepper, the step's status and whether it is the
/// stage's last; returns false to stop the stage there (a wall-time or memory budget).
using AfterDynamicStep = std::function<bool(const TimeStepper&, const StepStatus&, bool)>;

/// A dynamic stage in progress: its time stepper, settle detector and result so far, which a
/// checkpoint keeps between two steps (save, and load into a run of the same stage, System and
/// settings) so that it goes on as the saved one would have.
class DynamicStageRun
{
public:
  /// See run_dynamic_stage; starts at the System's time.
  DynamicStageRun(System& system, const Stage& stage, const TimeSettings& time,
                  const std::vector<Vector2>& fall_reference);

  /// Steps to the stage's end (run_dynamic_stage), or until `after_step` returns false.
  DynamicStageResult run(const AfterDynamicStep& after_step = {});

  void save(CheckpointOut& archive) const;
  void load(CheckpointIn& archive);

private:
  bool at_end() const;
  /// The settle detector's verdict after an accepted step, and the removal of fallen debris.
  void observe_settling();

  System& system;
  const Stage& stage;
  TimeSettings time;
  DynamicStageResult result;
  std::size_t first_step = 0; ///< System::n_steps() at the stage's start
  TimeStepper stepper;
  std::optional<SettleDetector> detector;
};

/// Runs a dynamic stage of `system` (begin_stage(dynamic) first) with the scene's time control:
/// to stage.end_time, or for a settle stage (stage.settle) until SettleDetector::observe says
/// every block is at rest or has fallen, at most settle->max_duration after the stage's start;
/// with settle->remove_fallen, blocks out of place are removed after the step that takes them
/// there (before `after_step`).
/// `fall_reference`: SettleDetector's reference. A failed step ends the stage with its status
/// (nothing throws).
DynamicStageResult run_dynamic_stage(System& system, const Stage& stage, const TimeSettings& time,
                                     const std::vector<Vector2>& fall_reference,
                                     const AfterDynamicStep& after_step = {});

} // namespace ddafem::dda
