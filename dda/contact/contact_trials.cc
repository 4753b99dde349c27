// The contacts' trial states in the open-close iteration (phase 4): each from the solution
// through its contact law (dda/contact/contact_law), on the threads; the penalties raised for a
// retry when contacts penetrate too deep; and the scan for slip reversals within the step
// (dda/contact/slip_reversal), the event adaptive step control localises.
#include "dda/contact/contact_set.h"

#include "dda/contact/slip_reversal.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace ddafem::dda
{
namespace
{
/// Reversals earlier in the step than this fraction are taken within it [-].
constexpr double min_reversal_fraction = 0.05;
} // namespace
double ContactSet::negligible_force() const
{
  double largest_force = 0.0;
  for (const Contact& c : trial)
    largest_force = std::max(largest_force, c.trial.normal_force);
  return model->contacts.flip_force_ratio * largest_force;
}

std::size_t ContactSet::update_trial_states(const TrialInput& in, std::size_t& n_ignored,
                                            const Parallel& parallel)
{
  // Each contact's trial on the threads (it depends on the contact alone); the changes are
  // counted per chunk and added afterwards (integers: in any order the same).
  const double negligible = negligible_force();
  constexpr std::size_t grain = 1024;
  std::vector<std::array<std::size_t, 2>> counts((trial.size() + grain - 1) / grain, {0, 0});
  parallel.for_chunks(trial.size(), grain,
                      [&](std::size_t begin, std::size_t end)
                      {
                        std::array<std::size_t, 2>& n = counts[begin / grain];
                        for (std::size_t k = begin; k < end; ++k)
                          update_trial_state(k, in, negligible, n);
                      });
  std::size_t n_changes = 0;
  for (const std::array<std::size_t, 2>& n : counts)
  {
    n_changes += n[0];
    n_ignored += n[1];
  }
  return n_changes;
}

void ContactSet::update_trial_state(std::size_t k, const TrialInput& in, double negligible,
                                    std::array<std::size_t, 2>& n)
{
  const unsigned iteration = in.iteration;
  const Eigen::VectorXd& solution = in.solution;
  Contact& c = trial[k];
  const ContactFrame& f = frames[k];
  const Vector2 relative = f.t_vertex * solution.segment<6>(6 * c.vertex_block) -
                           f.t_edge * solution.segment<6>(6 * c.edge_block);
  c.end_gap = c.gap + f.normal.dot(relative);
  c.step_slip = f.tangent.dot(relative);
  // A sticking contact's dashpot is in its shear demand; from the third iteration on it may
  // hold a contact at the limit but no longer push it to slide, or the contact flips on the
  // dashpot's last newton between a lock (dashpot on) and a slide (off) for ever.
  const ContactForces evaluated = evaluate_contact(
      law(c), c.forces, c.end_gap, c.step_slip, viscous_shear(k, in.dashpots, solution),
      iteration < 3 ? DashpotDemand::total : DashpotDemand::never_pushes);
  // With slip reversals localised, sliding that reverses between trials is taken as lock
  // (only on a slide of at least 10 steps: slides_long_enough).
  const ContactForces next = in.localising && slides_long_enough(c, in.dt)
                                 ? iteration_trial(iteration, c.trial, evaluated)
                                 : evaluated;
  // A contact that ends the step within rounding of zero gap (1e-12 of the model size; its
  // forces are then p x that, e.g. 0.5 N) is decided by rounding noise: it carries nothing
  // in either state and may flip between iterations (the head joints of bricks falling
  // together). Its change is taken but does not hold the iteration back (n[1]; the others
  // n[0]). From the third iteration on, so does one that carries almost nothing before and
  // after (contacts flipping between slide and lock under a kN where the rock carries MN).
  if (state_changed(c.trial, next) && std::abs(c.end_gap) > 2e-12 * distances.w0)
    ++n[change_holds_iteration(iteration, c.trial, next, negligible) ? 0 : 1];
  c.trial = next;
}

bool ContactSet::raise_penalties()
{
  const double cap = model->contacts.max_penalty_factor;
  bool raised = false;
  for (const Contact& c : trial)
    if (c.trial.state != ContactState::open && -c.end_gap > distances.max_penetration &&
        c.penalty_factor < cap)
    {
      raised_penalties[c.key()] = std::min(cap, 10.0 * c.penalty_factor);
      raised = true;
    }
  return raised;
}

ContactSet::ReversalScan ContactSet::scan_reversals(const ReversalInput& in) const
{
  const double dt = in.dt;
  const double negligible = negligible_force();
  ReversalScan scan;
  for (std::size_t k = 0; k < trial.size(); ++k)
  {
    const Contact& c = trial[k];
    // A contact that stuck at the step's start after a slide (a lock as short as the step
    // that ended at the reversal) still holds the old friction in its spring: sliding the
    // other way at the step's end, friction turns around within the step as from a slide.
    const bool stuck_after_slide =
        c.forces.state == ContactState::lock && slides_long_enough(c, dt);
    if ((c.forces.state != ContactState::slide && !stuck_after_slide) ||
        c.trial.state == ContactState::open || std::abs(c.forces.shear_force) <= negligible)
      continue;
    const ContactFrame& f = frames[k];
    const Block& v = in.blocks[c.vertex_block];
    const Block& e = in.blocks[c.edge_block];
    // The end velocity from the state the step's Newmark updates start from (Bathe's second
    // half: an equivalent one), the reversal from the velocity the blocks had.
    const KinematicState sv = in.step_start(c.vertex_block), se = in.step_start(c.edge_block);
    TangentialMotion m;
    m.velocity = f.tangent.dot(f.t_vertex * sv.velocity - f.t_edge * se.velocity);
    m.acceleration = f.tangent.dot(f.t_vertex * sv.acceleration - f.t_edge * se.acceleration);
    m.slip = c.step_slip;
    const double v1 = end_velocity(in.integration, dt, m);
    m.velocity = f.tangent.dot(f.t_vertex * v.velocity - f.t_edge * e.velocity);
    const SlipReversal r = slip_reversal(c.forces, c.trial, m.velocity, v1);
    // A reversal in the first 5% of the step cannot be ended before in a useful step (and
    // would shorten steps to nanoseconds when the iteration's slip and the velocities disagree).
    const double duration = c.slide_duration + dt;
    // Bathe's scheme localises reversals of long slides only: the mid velocities of its
    // generalized-alpha half alternate in sign on stiff contact modes, which flagged 12 527
    // reversals in the settling horseshoe of failure_matrix --quick (dashpot) and cut its dt
    // 20-fold (189 s instead of 9.9 s with the gate; generalized-alpha: 319 events).
    const bool counted = !in.bathe || slides_long_enough(c, dt);
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
        slip_error(in.start_force_lag * std::abs(v1 - m.velocity), duration) > reversal_tolerance)
      scan.friction_turns.push_back(k);
  }
  return scan;
}

void ContactSet::add_friction_jumps(
    const std::vector<std::size_t>& turning,
    const std::function<void(std::size_t, const Vector6&)>& add) const
{
  for (const std::size_t k : turning)
  {
    const Contact& c = trial[k];
    const ContactFrame& f = frames[k];
    // S acts on the vertex block as -S t and on the edge block as +S t.
    const Vector2 jump = (c.trial.shear_force - c.forces.shear_force) * f.tangent;
    add(c.vertex_block, -f.t_vertex.transpose() * jump);
    add(c.edge_block, f.t_edge.transpose() * jump);
  }
}
} // namespace ddafem::dda
