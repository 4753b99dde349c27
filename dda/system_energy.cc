// The model's energies: kinetic, strain and spring energy, and the balance with the works done
// on it; the contacts' and joints' snapshot.
#include "dda/system.h"

#include "dda/submatrices.h"

namespace ddafem::dda
{
EnergyBalance System::energy() const
{
  EnergyBalance e;
  for (const Block& b : block_set.list)
  {
    const PolygonMoments& g = block_set.linearisation_moments(b);
    e.kinetic += block_set.kinetic_energy(b);
    e.strain += 0.5 * g.area * b.stress.dot(block_set.materials.compliance[b.material] * b.stress);
  }
  // Joints' and elements' springs, fixed points' penalty springs and contacts' springs.
  double spring = 0.0;
  bonded.add_energy(model, spring);
  for (const std::unique_ptr<ElementKind>& k : element_kinds)
    k->add_energy(spring);
  point_set.add_energy(spring, current_time);
  contact_set.add_energy(spring);
  e.spring = spring;
  ledger.fill(e);
  e.work_of_ties = tie_set.has_body() ? tie_set.body->work_on_blocks() : 0.0;
  e.dissipated = e.initial + e.work_of_loads + e.work_of_supports + e.work_of_boundaries +
                 e.work_of_damping + e.work_of_ties - e.removed - e.stored();
  return e;
}

std::vector<ContactSnapshot> contact_snapshot(const System& system)
{
  const ContactSet& contacts = system.contacts();
  const BondedJoints& bonded = system.bonded_joints();
  std::vector<ContactSnapshot> out;
  out.reserve(contacts.accepted.size() + 2 * bonded.list.size());
  contacts.add_snapshots(system.blocks().list, out);
  bonded.add_snapshots(system.blocks().small_displacement(), out);
  return out;
}
} // namespace ddafem::dda
