// Damping of the rock (issue 53): stiffness-proportional dashpots beside the blocks' elasticity
// and the joints' springs, never on rigid-body motion nor on a sliding contact's slip.
//
// Each stiffness K of the rock (a block's elastic stiffness on its strain unknowns, a bonded
// joint's springs, a closed contact's normal spring and a sticking contact's shear spring) gets
// a dashpot C = beta K beside it, beta = zeta / (pi f0) [s]. For the linear system of blocks and
// joints this is Rayleigh's stiffness-proportional damping C = beta K of the whole: every mode of
// frequency f has the damping ratio zeta f / f0, exactly zeta at f0 (the scene input's dominant
// frequency unless given), zeta / 2 at f0 / 2, 2 zeta at 2 f0. It acts on strain rates and
// relative velocities only, so a falling or sliding block is not slowed, and it does not depend on
// dt (unlike DDA's kinetic damping, a velocity cut per step). Coefficients come from the joint
// material's stiffness, not from a contact's penalty raised on penetration. The dashpot forces
// are kept out of the Mohr-Coulomb check: the contact law sees the springs' forces only.
// docs/damping.md.
#pragma once

#include "dda/types.h"

#include <cmath>
#include <vector>

namespace ddafem::dda
{
/// `damping` of a material or joint material: the fraction of critical damping `ratio` held at
/// `frequency`.
struct RockDamping
{
  double ratio = 0.0;     ///< zeta [-], in [0, 1); 0: undamped
  double frequency = 0.0; ///< f0 [Hz] where the ratio holds; > 0 once the scene is read

  bool active() const { return ratio > 0.0; }
  /// The stiffness factor beta = zeta / (pi f0) [s] (0 when undamped).
  double stiffness_factor() const { return active() ? ratio / (M_PI * frequency) : 0.0; }
  /// The damping ratio of a mode of frequency f [Hz]: zeta f / f0 [-].
  double ratio_at(double f) const { return active() ? ratio * f / frequency : 0.0; }
};

class BlockSet;
struct StepScheme;
struct ModelDescription;

/// The dashpots' share of the step being tried (dda/step_dashpots.cc): Newmark's end velocity
/// of each block is v1 = velocity_factor d + offsets[i] (common/newmark.h).
struct StepDashpots
{
  double velocity_factor = 0.0; ///< gamma / (beta dt) [1/s]; 0: no dashpot acts in this step
  std::vector<Vector6> offsets; ///< per block [m/s, rad/s, 1/s]
  std::vector<Vector6> start;   ///< per block: the velocity at the step's start (for the work)

  /// The share of a step of dt [s]: none unless `active` (a dynamic stage of a model with
  /// damping); else Newmark's velocity factor and each block's offset from the start state the
  /// scheme's updates take (Bathe's second half: the equivalent start of backward_euler_start).
  void prepare(const BlockSet& blocks, const StepScheme& scheme, double dt, bool active);
  /// Each block's mean velocity over the step of unknowns d (6 per block) [m/s, rad/s, 1/s],
  /// the start's and the end's (exact for the trapezoidal rule); empty when no dashpot acts.
  std::vector<Vector6> mean_velocities(const Eigen::VectorXd& d) const;
  /// Adds the work [J] of the blocks' own dashpots, -beta K_e on the mean velocities `mean`,
  /// on the step's d to `work` (negative: absorbed).
  void add_work_of_blocks(const BlockSet& blocks, const ModelDescription& model,
                          const std::vector<Vector6>& mean, const Eigen::VectorXd& d,
                          double& work) const;
};

/// A material's stiffness-proportional factor beta [s] in this step: 0 when no dashpot acts.
inline double dashpot_factor(const StepDashpots& dashpots, const RockDamping& damping)
{
  return dashpots.velocity_factor > 0.0 ? damping.stiffness_factor() : 0.0;
}

/// Exact response of the damped oscillator m x'' + c x' + k x = 0 from x(0) = x0, x'(0) = 0:
/// x(t) = x0 exp(-zeta w t) (cos(wd t) + zeta / sqrt(1 - zeta^2) sin(wd t)), w = sqrt(k / m),
/// wd = w sqrt(1 - zeta^2), zeta = c / (2 sqrt(k m)) < 1. Units of x0; t [s], w [rad/s].
inline double damped_free_decay(double x0, double omega, double zeta, double t)
{
  const double root = std::sqrt(1.0 - zeta * zeta);
  const double wd = omega * root;
  return x0 * std::exp(-zeta * omega * t) * (std::cos(wd * t) + zeta / root * std::sin(wd * t));
}

} // namespace ddafem::dda
