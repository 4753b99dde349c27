// System::scan_slip_reversals: when, within the step being tried, a sliding contact's slip
// reverses (dda/contact/slip_reversal), the event adaptive step control localises; and the
// restart of generalized-alpha where friction turns around within a step.
#include "dda/contact/slip_reversal.h"
#include "dda/submatrices.h"
#include "dda/system.h"

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>

namespace ddafem::dda
{
namespace
{
/// Reversals earlier in the step than this fraction are taken within it [-].
constexpr double min_reversal_fraction = 0.05;
} // namespace

System::ReversalScan System::scan_slip_reversals(double dt) const
{
  const double negligible = contact_set.negligible_force();
  ReversalScan scan;
  for (std::size_t k = 0; k < contact_set.trial.size(); ++k)
  {
    const Contact& c = contact_set.trial[k];
    // A contact that stuck at the step's start after a slide (a lock as short as the step
    // that ended at the reversal) still holds the old friction in its spring: sliding the
    // other way at the step's end, friction turns around within the step as from a slide.
    const bool stuck_after_slide =
        c.forces.state == ContactState::lock && slides_long_enough(c, dt);
    if ((c.forces.state != ContactState::slide && !stuck_after_slide) ||
        c.trial.state == ContactState::open || std::abs(c.forces.shear_force) <= negligible)
      continue;
    const ContactFrame& f = contact_set.frames[k];
    const Block& v = blocks[c.vertex_block];
    const Block& e = blocks[c.edge_block];
    // The end velocity from the state the step's Newmark updates start from (Bathe's second
    // half: an equivalent one), the reversal from the velocity the blocks had.
    const KinematicState sv = step_start(c.vertex_block, dt), se = step_start(c.edge_block, dt);
    TangentialMotion m;
    m.velocity = f.tangent.dot(f.t_vertex * sv.velocity - f.t_edge * se.velocity);
    m.acceleration = f.tangent.dot(f.t_vertex * sv.acceleration - f.t_edge * se.acceleration);
    m.slip = c.step_slip;
    const double v1 = end_velocity(step_integration, dt, m);
    m.velocity = f.tangent.dot(f.t_vertex * v.velocity - f.t_edge * e.velocity);
    const SlipReversal r = slip_reversal(c.forces, c.trial, m.velocity, v1);
    // A reversal in the first 5% of the step cannot be ended before in a useful step (and
    // would shorten steps to nanoseconds when the iteration's slip and the velocities disagree).
    const double duration = c.slide_duration + dt;
    // Bathe's scheme localises reversals of long slides only: the mid velocities of its
    // generalized-alpha half alternate in sign on stiff contact modes, which flagged 12 527
    // reversals in the settling horseshoe of failure_matrix --quick (dashpot) and cut its dt
    // 20-fold (189 s instead of 9.9 s with the gate; generalized-alpha: 319 events).
    const bool counted = model.time.integrator != Integrator::bathe || slides_long_enough(c, dt);
    if (r.at >= min_reversal_fraction && counted &&
        slip_error(r.speed_error, duration) > reversal_tolerance &&
        (scan.earliest == 0.0 || r.at < scan.earliest))
      scan.earliest = r.at;
    // Friction turned around in this step, from a slide or from a stuck spring that still
    // holds the old friction (a spring loaded through a long stick reaches the new side's
    // limit continuously, with no jump): generalized-alpha's velocity lag alpha_f Delta v.
    const bool turns = c.trial.state == ContactState::slide &&
                       std::signbit(c.forces.shear_force) != std::signbit(c.trial.shear_force);
    if (turns && slides_long_enough(c, dt) &&
        slip_error(start_force_lag() * std::abs(v1 - m.velocity), duration) > reversal_tolerance)
      scan.friction_turns.push_back(k);
  }
  return scan;
}

double System::start_force_lag() const
{
  // Bathe's second half starts from velocities alone (backward_euler_start).
  return second_half ? 0.0 : step_integration.start_force_lag();
}

void System::restart_at_friction_jumps(const std::vector<std::size_t>& turning)
{
  const auto add = [this](std::size_t i, const Vector6& jump)
  {
    Block& b = blocks[i];
    if (std::none_of(friction_jumps.begin(), friction_jumps.end(),
                     [i](const StateBeforeJump& s) { return s.block == i; }))
      friction_jumps.push_back({i, b.acceleration, b.force});
    const Matrix6 m = mass_matrix(linearisation_moments(b), block_density(b));
    // The Newmark schemes and Bathe's first half restart the translation only: the jump's
    // moment would set off the block's stiff rocking on its contacts (whose normal forces take
    // that moment up at once in the rigid limit), which they damp little or not at all
    // (two-way sliding at 4 Hz with Bathe's scheme: 0.65% with the translation, 1.07% with the
    // full restart). Generalized-alpha at rho_inf 0.2 damps it.
    Vector6 applied = jump;
    if (step_integration.alpha_f == 0.0 || model.time.integrator == Integrator::bathe)
      applied.tail<4>().setZero();
    b.force += applied;
    b.acceleration += m.ldlt().solve(applied);
  };
  for (const std::size_t k : turning)
  {
    const Contact& c = contact_set.trial[k];
    const ContactFrame& f = contact_set.frames[k];
    // S acts on the vertex block as -S t and on the edge block as +S t.
    const Vector2 jump = (c.trial.shear_force - c.forces.shear_force) * f.tangent;
    add(c.vertex_block, -f.t_vertex.transpose() * jump);
    add(c.edge_block, f.t_edge.transpose() * jump);
  }
}

void System::undo_friction_jumps()
{
  for (const StateBeforeJump& s : friction_jumps)
  {
    blocks[s.block].acceleration = s.acceleration;
    blocks[s.block].force = s.force;
  }
  friction_jumps.clear();
}

} // namespace ddafem::dda
