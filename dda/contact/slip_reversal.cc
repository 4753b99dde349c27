#include "dda/contact/slip_reversal.h"

#include <cmath>

namespace ddafem::dda
{
double end_velocity(const IntegratorCoefficients& c, double dt, const TangentialMotion& m)
{
  return newmark_end(c, dt, m.slip, m.velocity, m.acceleration).second;
}

SlipReversal slip_reversal(const ContactForces& start, const ContactForces& end, double v0,
                           double v1)
{
  if (start.state != ContactState::slide || start.shear_force == 0.0 ||
      end.state == ContactState::open)
    return {};
  const double old_sign = std::copysign(1.0, start.shear_force);
  if (old_sign * v0 <= 0.0 || old_sign * v1 >= 0.0)
    return {};
  const double at = v0 / (v0 - v1);
  const bool keeps_direction = end.state == ContactState::slide && end.shear_force != 0.0 &&
                               std::signbit(end.shear_force) == std::signbit(start.shear_force);
  const double mistimed = keeps_direction ? 1.0 - at : at;
  return {at, mistimed, std::abs(v1 - v0) * mistimed};
}

} // namespace ddafem::dda
