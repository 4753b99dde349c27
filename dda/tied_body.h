// A body outside the DDA model tied to points of its blocks: the System's view of the deal.II
// far field (coupling/ implements it; dda/ never sees fem/).
#pragma once

#include "common/step_result.h"
#include "dda/model_description.h"

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <optional>

namespace ddafem::dda
{
/// A linear body tied to m points of the blocks, condensed onto those points. Over a step, in
/// each trial state of its ties, the ties' forces on the blocks at the end of the step are
///   f = g - H delta   [N] (2m: x, y per tie point),
/// delta the displacement increments of the tie points over the step [m] (2m) and H (2m x 2m,
/// symmetric positive semidefinite) [N/m] the stiffness of the ties in series with the body's
/// condensed dynamic stiffness. The System adds T^T H T and T^T g to its step and hands back
/// the increments; the body advances itself in end_step() with the same dt: one implicit system
/// per step, no lag between the two sides. The ties may carry preloads (the in-situ stress's
/// traction across the interface), which act on the blocks only: the body itself carries the
/// dynamic increment.
class TiedBody
{
public:
  virtual ~TiedBody() = default;

  /// Starts a stage (System::begin_stage). Static: the body is held, its ties are springs to
  /// fixed ground with their preloads, and it does not advance. Dynamic after static: each
  /// tie's force on the blocks (preload + spring) becomes its constant preload, and the tie
  /// displacements the System passes are measured from the state reached (they restart at 0).
  virtual void begin_stage(StageMode mode) = 0;
  /// Whether begin_step may run on another thread while the blocks find their contacts
  /// (false for a body whose calls are MPI collectives: MPI is started for one thread at a time,
  /// and a request begun on one thread and completed on another can hang).
  virtual bool begins_step_on_any_thread() const { return true; }
  /// Starts (or restarts, after a cut) a step of dt [s]. `displacements` (2m) are the tie points'
  /// displacements since the ties were made [m]. The ties' trial states start from their
  /// accepted ones. Returns whether the body can take the step, and if not why.
  virtual StepResult begin_step(double dt, const Eigen::VectorXd& displacements) = 0;
  /// H of the ties' trial states [N/m].
  virtual const Eigen::MatrixXd& stiffness() const = 0;
  /// Whether H couples no two tie points (its only non-zero entries are the 2 x 2 blocks on its
  /// diagonal, e.g. ties to a held body): the System then adds the tie terms point by point.
  virtual bool stiffness_is_block_diagonal() const { return false; }
  /// An id of H's contents when they repeat from step to step (e.g. the ties bonded, one H per
  /// dt): equal ids, equal H, bit for bit, also after a checkpoint's resume. The System then
  /// keeps H's terms at the blocks' initial geometry per id and turns them with the blocks
  /// (dda/tie_terms.h). None: H is taken as new at every call.
  virtual std::optional<std::uint64_t> stiffness_id() const { return std::nullopt; }
  /// g of the ties' trial states [N].
  virtual const Eigen::VectorXd& force() const = 0;
  /// Sets the ties' trial states from the trial increments `delta` (2m) [m] in open-close
  /// iteration `iteration` (from 1); returns the number of ties whose state change holds the
  /// iteration back (H and g change with every change). As for the blocks' contacts
  /// (change_holds_iteration): from the third iteration on, a tie carrying at most `negligible`
  /// [N] before and after changes without holding it back; those are counted in `n_ignored`.
  virtual std::size_t update_trial_states(const Eigen::VectorXd& delta, unsigned iteration,
                                          double negligible, std::size_t& n_ignored) = 0;
  /// Accepts the step with the increments of the converged trial: the body advances to t + dt.
  /// Returns whether it did, and if not why (the System then reports a solver failure).
  virtual StepResult end_step(const Eigen::VectorXd& delta) = 0;
  /// Work [J] done by the ties on the blocks (preloads included) since the ties were made or the
  /// first dynamic stage started (the energy that crossed the interface into the blocks,
  /// negative when it left them).
  virtual double work_on_blocks() const = 0;
};

} // namespace ddafem::dda
