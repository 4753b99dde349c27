// The integrator's form of each step (issue 55): generalized-alpha and the Newmark schemes take
// one form throughout; Bathe's composite scheme alternates a generalized-alpha first half and a
// three-point backward Euler second half (dda/integrator.h), whose start the first half keeps.
// The scheme also keeps the blocks' accepted state where the step being tried restarted the
// integrator at a friction jump (System::restart_at_friction_jumps).
#pragma once

#include "dda/block.h"
#include "dda/integrator.h"
#include "dda/types.h"

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace ddafem::dda
{
struct StepScheme
{
  /// The scene's integrator (`spectral_radius` for generalized-alpha's and Bathe's first half).
  void set_up(Integrator integrator_, double spectral_radius);
  /// Phase 0: the coefficients for `part` of a step of dt (`dynamic`: in a dynamic stage).
  /// Generalized-alpha and Bathe's scheme start motion with DDA's scheme; Bathe's second half
  /// must follow an accepted first half of the same dt (std::logic_error if not), and in a
  /// dynamic stage Bathe takes no full step.
  void choose(double dt, StepPart part, bool dynamic);
  /// Block b's (index i) state the step's Newmark updates start from: its own, or in a composite
  /// pair's second half the equivalent start of backward_euler_start.
  KinematicState start(const Block& b, std::size_t i, double dt) const;
  /// The acceleration block i keeps after a step that ended in `end` with mass matrix m:
  /// Newmark's, except after Bathe's second half, where the next pair's generalized-alpha half
  /// needs its own a_n, M^-1 ((1 - alpha_f) r_n + alpha_f r_{n-1/2}) with r_{n-1/2} the force at
  /// the pair's middle (kept by the first half): with the true a_n the composite would be first
  /// order.
  Vector6 composite_acceleration(std::size_t i, const Matrix6& m, const KinematicState& end,
                                 bool dynamic);
  /// After an accepted dynamic step of the displacements d: a Bathe pair's first half keeps
  /// what its second needs (first_halves, open_half); any other step closes the pair.
  void record_half(double dt, const Eigen::VectorXd& d, const std::vector<Block>& blocks,
                   bool dynamic);
  /// IntegratorCoefficients::start_force_lag of the step being tried (0 in Bathe's second
  /// half, which starts from velocities alone).
  double start_force_lag() const;
  /// The blocks' accepted acceleration and force where a friction jump changed them.
  void undo_friction_jumps(std::vector<Block>& blocks);

  Integrator integrator = Integrator::generalized_alpha;
  IntegratorCoefficients integration;  ///< of the scene's integrator
  IntegratorCoefficients coefficients; ///< of the step being tried
  /// The blocks' acceleration and force are not known (at t = 0, or set at rest): the next step
  /// of generalized-alpha takes DDA's scheme, in which neither enters and after which M a = r
  /// holds (the Newmark schemes start from a = 0 as they always have).
  bool motion_starts = true;
  /// A block's accepted acceleration and force before a friction jump changed them.
  struct StateBeforeJump
  {
    std::size_t block = 0;
    Vector6 acceleration, force;
  };
  std::vector<StateBeforeJump> friction_jumps; ///< of the step being tried
  /// Integrator::bathe: whether the step being tried is a pair's second half (three-point
  /// backward Euler, StepPart::second_half in a dynamic stage)
  bool second_half = false;
  /// Integrator::bathe: the dt of the last accepted step when it was a pair's first half [s];
  /// 0 when the last step closed a pair (or was static)
  double open_half = 0.0;
  /// Integrator::bathe, per block: the velocity at the pair's start and the first half's
  /// displacement (dda/integrator.h, backward_euler_start)
  struct FirstHalf
  {
    Vector6 start_velocity = Vector6::Zero(), displacement = Vector6::Zero();
    Vector6 mid_force = Vector6::Zero(); ///< r at the pair's middle [N, N m]
  };
  std::vector<FirstHalf> first_halves;
};

} // namespace ddafem::dda
