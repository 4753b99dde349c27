// A block and the joint behind one of its boundaries as one continuum normal to that boundary:
// the rock mass's effective modulus used by the tunnel plan and the interface impedance.
#pragma once

namespace ddafem::dda
{
/// E_eff = 1 / (1/E + L / (2 p d)) [Pa] of a block of modulus E [Pa] and area [m^2] with a
/// boundary of `length` L [m] on a line, d = area / L its depth behind it, and a joint of
/// springs p [N/m] at both ends of that edge behind it: the block and its joint as one
/// continuum normal to the line.
inline double jointed_block_modulus(double youngs_modulus, double normal_stiffness, double area,
                                    double length)
{
  const double depth = area / length;
  return 1.0 / (1.0 / youngs_modulus + length / (2.0 * normal_stiffness * depth));
}

} // namespace ddafem::dda
