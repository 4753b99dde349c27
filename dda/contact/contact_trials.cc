// The contacts' trial states in the open-close iteration (phase 4): each from the solution
// through its contact law (dda/contact/contact_law), on the threads; and the penalties raised
// for a retry when contacts penetrate too deep.
#include "dda/contact/contact_set.h"

#include "dda/contact/slip_reversal.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace ddafem::dda
{
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
} // namespace ddafem::dda
