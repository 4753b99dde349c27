// A static stage (Shi's static analysis) to equilibrium, releasing the blocks that cannot be in
// equilibrium (issue 16): a roof wedge that must fall is a result, not a numerical failure.
#pragma once

#include "common/checkpoint_fwd.h"
#include "dda/model_description.h"
#include "dda/system.h"
#include "dda/time_stepper.h"

#include <cstddef>
#include <functional>
#include <map>
#include <vector>

namespace ddafem::dda
{
/// When a static stage releases a block. In Shi's static analysis (velocities zeroed before
/// every step) a block that converges, however slowly, moves into springs (bonded joints,
/// contacts, supports) whose forces grow with its motion and take up its out-of-balance force;
/// a block that cannot be in equilibrium (free under gravity, or on a slope steeper than its
/// friction angle) is driven by an out-of-balance force that nothing takes up, and moves the
/// same way step after step. Block i is released after `window` consecutive static steps in
/// which
/// 1. its BlockBalance::ratio() >= min_ratio in every step: its resultant force F_i is a sizable
///    fraction of its own load (1 in free fall, 0.41 on a frictionless 45 degree slope, where
///    the load is W + N = W (1 + cos 45));
/// 2. |F_i| at the window's last step >= (1 - max_force_drop) x |F_i| at its first: its motion
///    does not take up its load;
/// 3. its centroid moved, monotonically: |sum of its step displacements| >= min_straightness x
///    the sum of their lengths > 0.
/// A window in which one of them fails starts again at the next step. Held blocks are not
/// watched. A block that converges at a rate slower than max_force_drop per window while
/// moving straight with a ratio above min_ratio would be released too: none of the tunnel
/// scenes has one (see docs/design.md).
struct ReleaseCriterion
{
  std::size_t window = 50;       ///< consecutive static steps [-]
  double min_ratio = 0.05;       ///< of |F_i| over the block's own load [-]
  double max_force_drop = 0.1;   ///< relative drop of |F_i| over the window [-]
  double min_straightness = 0.9; ///< |sum d_k| / sum |d_k| of the centroid's step motions [-]
};

/// Watches the blocks of a static stage, step by step, for the ReleaseCriterion.
class ReleaseDetector
{
public:
  /// Starts watching at the system's current centroids.
  explicit ReleaseDetector(const System& system, ReleaseCriterion criterion = {});

  /// After an accepted static step: the blocks, not held, that meet the criterion now.
  std::vector<std::size_t> observe(const System& system);

  /// Checkpoints (dda/stage_checkpoint.cc): the windows and the last centroids.
  void save(CheckpointOut& archive) const;
  void load(CheckpointIn& archive);

private:
  /// A block's current window.
  struct Watch
  {
    std::size_t n_steps = 0;          ///< steps in the window so far
    double start_force = 0.0;         ///< |F_i| at the window's first step [N]
    Vector2 travel = Vector2::Zero(); ///< sum of the centroid's step motions [m]
    double path = 0.0;                ///< sum of their lengths [m]
  };

  ReleaseCriterion criterion;
  std::vector<Point> last_centroids; ///< [m]
  std::vector<Watch> watches;
};

/// A block a static stage released.
struct ReleasedBlock
{
  std::size_t block = 0;
  std::size_t step = 0;           ///< the stage's step (from 1) at which it was released
  double mass = 0.0;              ///< [kg]
  Point centroid = Point::Zero(); ///< where it was released [m]
  double ratio = 0.0;             ///< its BlockBalance::ratio() then [-]
};

enum class StaticOutcome
{
  equilibrium,   ///< every block not released is in balance within the stage's tolerance
  not_converged, ///< Stage::max_steps taken without equilibrium
  step_failed    ///< a step failed even at the smallest dt (StaticStageResult::failure)
};

struct StaticStageResult
{
  StaticOutcome outcome = StaticOutcome::not_converged;
  std::size_t n_steps = 0;
  double ratio = 0.0;    ///< StepStatus::unbalanced_force_ratio of the last step [-]
  std::size_t block = 0; ///< the block with that ratio
  std::vector<ReleasedBlock> released;
  StepStatus failure;                               ///< of the failed step (step_failed)
  std::size_t n_cuts = 0, n_cut_steps = 0;          ///< of the pseudo time step (TimeStepper)
  std::size_t n_penalty_raises = 0;                 ///< TimeStepper::n_penalty_raises
  std::map<StepOutcome, std::size_t> cuts_by_cause; ///< TimeStepper::cuts_by_cause
  double smallest_dt = 0.0;                         ///< of the accepted pseudo steps [s]
  bool stopped = false; ///< after_step asked to stop (a wall-time or memory budget)
};

/// A static stage in progress (run_static_stage, after System::begin_stage): its time stepper,
/// release detector and result so far, which a checkpoint keeps between two steps (save, and
/// load into a run of the same stage, System and settings) so that it goes on as the saved one
/// would have.
class StaticStageRun
{
public:
  StaticStageRun(System& system, const Stage& stage, const TimeSettings& time,
                 ReleaseCriterion criterion = {});

  /// Steps to equilibrium (run_static_stage), or until `after_step` returns false.
  StaticStageResult run(const std::function<bool()>& after_step = {});

  void save(CheckpointOut& archive) const;
  void load(CheckpointIn& archive);

private:
  /// Releases the blocks the detector finds after a step; returns how many.
  std::size_t release_blocks();

  System& system;
  const Stage& stage;
  StaticStageResult result;
  TimeStepper stepper;
  ReleaseDetector detector;
};

/// Starts a static stage of `system` (System::begin_stage) and steps it with a pseudo time step
/// of at most stage.dt, always adaptive (it has no physical meaning), until the ratio falls to
/// stage.tolerance or stage.max_steps are taken. Blocks that meet `criterion` are released
/// (System::hold_block or remove_block after stage.release) and no longer count. `after_step`,
/// if given, runs after every accepted step (progress) and returns false to stop the stage there
/// (a budget: StaticStageResult::stopped). The outcome is a status: nothing throws for a model
/// that is not in equilibrium.
StaticStageResult run_static_stage(System& system, const Stage& stage, const TimeSettings& time,
                                   const std::function<bool()>& after_step = {},
                                   ReleaseCriterion criterion = {});

} // namespace ddafem::dda
