#include "coupling/interface_impedance.h"

#include "dda/jointed_block_modulus.h"

#include <cmath>
#include <map>

namespace ddafem::coupling
{
InterfaceImpedance impedance_contrast(double blocks_modulus, double far_field_modulus)
{
  InterfaceImpedance z;
  z.blocks_modulus = blocks_modulus;
  z.far_field_modulus = far_field_modulus;
  const double ratio = std::sqrt(z.blocks_modulus / z.far_field_modulus);
  z.reflection = std::abs(1.0 - ratio) / (1.0 + ratio);
  return z;
}

std::optional<InterfaceImpedance> interface_impedance(const dda::ModelDescription& m,
                                                      const dda::System& system,
                                                      const FarFieldTies& ties,
                                                      double far_field_modulus)
{
  if (m.default_joint_material >= m.joint_materials.size())
    return std::nullopt;
  const double p = m.joint_materials[m.default_joint_material].normal_stiffness;
  // The tied length of each tied block.
  std::map<std::size_t, double> tied_length;
  for (const Tie& t : ties.get_ties())
    tied_length[t.block] += t.length;
  double sum = 0.0, weight = 0.0;
  for (const auto& [block, length] : tied_length)
  {
    const dda::Block& b = system.blocks().list[block];
    sum += length * dda::jointed_block_modulus(m.materials[b.material].youngs_modulus, p,
                                               b.moments.area, length);
    weight += length;
  }
  return impedance_contrast(sum / weight, far_field_modulus);
}

} // namespace ddafem::coupling
