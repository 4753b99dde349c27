#include "dda/contact/contact_law.h"

#include <algorithm>
#include <cmath>

namespace ddafem::dda
{
ContactForces evaluate_contact(const ContactLaw& law, const ContactForces& start, double gap,
                               double slip, double viscous_shear, DashpotDemand demand)
{
  ContactForces out;
  out.intact = start.intact;
  const bool was_closed = start.state != ContactState::open;
  const double normal_force = -law.normal_stiffness * gap; // compression positive
  if (gap >= 0.0)
  {
    // A pull: only an intact closed contact resists it, within its tensile capacity.
    const bool holds = was_closed && start.intact && -normal_force <= law.tensile_capacity &&
                       law.tensile_capacity > 0.0;
    if (!holds)
    {
      if (was_closed && gap > 0.0)
        out.intact = false; // failed in tension (or had no tensile strength)
      return out;           // open: no forces
    }
  }
  out.normal_force = normal_force;
  const double limit = std::max(0.0, std::max(normal_force, 0.0) * law.tan_friction +
                                         (out.intact ? law.cohesive_force : 0.0));
  const double previous_shear = was_closed ? start.shear_force : 0.0;
  const double trial = previous_shear + law.shear_stiffness * slip;
  const double with_dashpot = std::abs(trial + viscous_shear);
  if ((demand == DashpotDemand::total ? with_dashpot : std::min(std::abs(trial), with_dashpot)) <=
      limit)
  {
    out.state = ContactState::lock;
    out.shear_force = trial;
    return out;
  }
  out.state = ContactState::slide;
  out.intact = false;
  // The limit without cohesion, since sliding has destroyed it.
  const double residual = std::max(normal_force, 0.0) * law.tan_friction;
  out.shear_force = std::copysign(residual, trial + viscous_shear);
  return out;
}

bool exceeds_strength(const ContactLaw& law, double normal_force, double shear_force)
{
  const double shear_capacity = std::max(0.0, law.cohesive_force + normal_force * law.tan_friction);
  return -normal_force > law.tensile_capacity || std::abs(shear_force) > shear_capacity;
}

ContactForces iteration_trial(unsigned iteration, const ContactForces& previous,
                              const ContactForces& next)
{
  const bool reverses = previous.state == ContactState::slide &&
                        next.state == ContactState::slide && previous.shear_force != 0.0 &&
                        next.shear_force != 0.0 &&
                        std::signbit(previous.shear_force) != std::signbit(next.shear_force);
  if (iteration < 2 || !reverses)
    return next;
  ContactForces locked = next;
  locked.state = ContactState::lock;
  locked.shear_force = 0.0; // provisional: the law gives it from the next solution's slip
  return locked;
}

bool change_holds_iteration(unsigned iteration, const ContactForces& before,
                            const ContactForces& after, double negligible)
{
  const auto carries = [negligible](const ContactForces& f)
  { return std::max(std::abs(f.normal_force), std::abs(f.shear_force)) > negligible; };
  return iteration < 3 || carries(before) || carries(after);
}

bool state_changed(const ContactForces& a, const ContactForces& b)
{
  if (a.state != b.state)
    return true;
  // Sliding without friction has no direction.
  return a.state == ContactState::slide && a.shear_force != 0.0 && b.shear_force != 0.0 &&
         std::signbit(a.shear_force) != std::signbit(b.shear_force);
}

} // namespace ddafem::dda
