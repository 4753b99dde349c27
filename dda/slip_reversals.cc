// System::scan_slip_reversals: when, within the step being tried, a sliding contact's slip
// reverses (dda/contact/slip_reversal), the event adaptive step control localises.
#include "dda/contact/slip_reversal.h"
#include "dda/system.h"

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
  const double negligible = negligible_contact_force();
  ReversalScan scan;
  for (std::size_t k = 0; k < trial_contacts.size(); ++k)
  {
    const Contact& c = trial_contacts[k];
    if (c.forces.state != ContactState::slide || c.trial.state == ContactState::open ||
        std::abs(c.forces.shear_force) <= negligible)
      continue;
    const ContactFrame& f = frames[k];
    const Block& v = blocks[c.vertex_block];
    const Block& e = blocks[c.edge_block];
    TangentialMotion m;
    m.velocity = f.tangent.dot(f.t_vertex * v.velocity - f.t_edge * e.velocity);
    m.acceleration = f.tangent.dot(f.t_vertex * v.acceleration - f.t_edge * e.acceleration);
    m.slip = c.step_slip;
    const double v1 = end_velocity(step_integration, dt, m);
    const SlipReversal r = slip_reversal(c.forces, c.trial, m.velocity, v1);
    // A reversal in the first 5% of the step cannot be ended before in a useful step (and
    // would shorten steps to nanoseconds when the iteration's slip and the velocities disagree).
    const double duration = c.slide_duration + dt;
    if (r.at >= min_reversal_fraction && slip_error(r.speed_error, duration) > reversal_tolerance &&
        (scan.earliest == 0.0 || r.at < scan.earliest))
      scan.earliest = r.at;
    // Friction turned around in this step: generalized-alpha's velocity lag alpha_f Delta v.
    const bool turns = c.trial.shear_force != 0.0 &&
                       std::signbit(c.forces.shear_force) != std::signbit(c.trial.shear_force);
    if (turns && slip_error(step_integration.alpha_f * std::abs(v1 - m.velocity), duration) >
                     reversal_tolerance)
      scan.friction_turns = true;
  }
  return scan;
}

} // namespace ddafem::dda
