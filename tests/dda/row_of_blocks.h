// Shared test model: the paper's bar material and bonded joints on a row of unit blocks.
#pragma once

#include "dda/model_description.h"

#include <cstddef>

namespace ddafem::dda::test_models
{
/// Bao et al. (2012)'s rock: rho 2650 kg/m^3, E 50 GPa, nu 0.25.
constexpr double rho = 2650.0, young = 50e9, nu = 0.25;

/// n unit square blocks in a row from x = 0 (plane stress), bonded by joints with normal springs
/// p [N/m], shear ratio 0.4, phi 45 deg, c 20 MPa, tensile strength 10 MPa.
inline ModelDescription row_of_blocks(std::size_t n, double p)
{
  ModelDescription m;
  m.materials.push_back({"rock", rho, young, nu});
  m.joint_materials.push_back({"bond", p, 0.4, 45.0, 20e6, 10e6, true});
  m.default_joint_material = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    const double x = static_cast<double>(i);
    BlockDescription b;
    b.vertices = {{x, 0}, {x + 1, 0}, {x + 1, 1}, {x, 1}};
    m.blocks.push_back(b);
  }
  return m;
}
} // namespace ddafem::dda::test_models
