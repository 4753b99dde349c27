// The model's energies: kinetic, strain and spring energy, and the balance with the works done
// on it; the contacts' and joints' snapshot.
#include "dda/system.h"

#include "dda/submatrices.h"

namespace ddafem::dda
{
double System::stored_spring_energy() const
{
  double e = 0.0;
  for (const Joint& j : joints)
  {
    const JointMaterial& jm = model.joint_materials[j.joint_material];
    for (const JointPoint& p : j.points)
      e += joint_point_energy(p, jm);
  }
  for (const std::unique_ptr<ElementKind>& k : element_kinds)
    k->add_energy(e);
  for (const AttachedFixedPoint& f : fixed_points)
    e += 0.5 * f.stiffness * (f.point.position - f.target(current_time)).squaredNorm();
  contact_set.add_energy(e);
  return e;
}

double System::kinetic_energy(const Block& b) const
{
  return 0.5 * b.velocity.dot(mass_matrix(linearisation_moments(b), block_density(b)) * b.velocity);
}

EnergyBalance System::energy() const
{
  EnergyBalance e;
  for (const Block& b : blocks)
  {
    const PolygonMoments& g = linearisation_moments(b);
    e.kinetic += kinetic_energy(b);
    e.strain += 0.5 * g.area * b.stress.dot(compliance[b.material] * b.stress);
  }
  e.spring = stored_spring_energy();
  e.work_of_loads = work_of_loads;
  e.work_of_supports = work_of_supports;
  e.work_of_boundaries = work_of_boundaries;
  e.work_of_damping = work_of_damping;
  e.work_of_ties = tied_body ? tied_body->work_on_blocks() : 0.0;
  e.removed = removed_energy;
  e.initial = initial_energy;
  e.dissipated = e.initial + e.work_of_loads + e.work_of_supports + e.work_of_boundaries +
                 e.work_of_damping + e.work_of_ties - e.removed - e.stored();
  return e;
}

std::vector<ContactSnapshot> System::contact_snapshot() const
{
  std::vector<ContactSnapshot> out;
  out.reserve(contact_set.accepted.size() + 2 * joints.size());
  contact_set.add_snapshots(blocks, out);
  for (const Joint& j : joints)
    for (const JointPoint& p : j.points)
    {
      ContactSnapshot s;
      s.id = j.id;
      s.block_a = j.block_a;
      s.block_b = j.block_b;
      s.state = ContactPointState::bonded;
      s.position = p.on_a.position;
      s.normal = j.normal(small_displacement());
      s.normal_force = -p.normal_force;
      s.shear_force = p.shear_force;
      s.gap = s.normal.dot(p.on_b.position - p.on_a.position);
      out.push_back(s);
    }
  return out;
}
} // namespace ddafem::dda
