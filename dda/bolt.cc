#include "dda/bolt.h"

#include <algorithm>
#include <cmath>

namespace ddafem::dda
{
BoltLaw make_bolt_law(const Point& head, const Point& anchor, double youngs_modulus, double area,
                      double pretension, double yield_force, double rupture_strain)
{
  BoltLaw law;
  law.free_length = (anchor - head).norm();
  law.stiffness = youngs_modulus * area / law.free_length;
  law.pretension = pretension;
  law.yield_force = yield_force;
  law.rupture_elongation = rupture_strain * law.free_length;
  return law;
}

BoltForces evaluate_bolt(const BoltLaw& law, const BoltForces& start, double length)
{
  BoltForces out;
  out.plastic_elongation = start.plastic_elongation;
  const double elongation = length - law.free_length;
  if (start.state == BoltState::ruptured || elongation > law.rupture_elongation)
  {
    out.state = BoltState::ruptured;
    return out;
  }
  const double trial = law.pretension + law.stiffness * (elongation - start.plastic_elongation);
  if (trial > law.yield_force)
  {
    out.state = BoltState::yielding;
    out.axial_force = law.yield_force;
    out.plastic_elongation = elongation - (law.yield_force - law.pretension) / law.stiffness;
  }
  else if (trial < 0.0)
    out.state = BoltState::slack;
  else
  {
    out.state = BoltState::elastic;
    out.axial_force = trial;
  }
  return out;
}

double bolt_tangent_stiffness(const BoltLaw& law, const BoltForces& forces)
{
  return forces.state == BoltState::elastic ? law.stiffness : 0.0;
}

double bolt_energy(const BoltLaw& law, const BoltForces& forces)
{
  return 0.5 * forces.axial_force * forces.axial_force / law.stiffness;
}

BoltRecord record_bolt(const BoltRecord& before, const BoltForces& forces, double elongation,
                       double t)
{
  if (!std::isnan(before.rupture_time))
    return before; // a broken bolt's ends move apart freely: its record ends at the rupture
  BoltRecord out = before;
  out.max_force = std::max(out.max_force, forces.axial_force);
  out.max_elongation = std::max(out.max_elongation, elongation);
  if (forces.state == BoltState::yielding && std::isnan(out.yield_time))
    out.yield_time = t;
  if (forces.state == BoltState::ruptured && std::isnan(out.rupture_time))
    out.rupture_time = t;
  return out;
}

double Bolt::length(bool initial) const
{
  return initial ? (anchor.initial - head.initial).norm()
                 : (anchor.position - head.position).norm();
}

Vector2 Bolt::direction(bool initial) const
{
  return initial ? (anchor.initial - head.initial).normalized()
                 : (anchor.position - head.position).normalized();
}

} // namespace ddafem::dda
