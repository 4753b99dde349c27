// Constants of the blocks' materials that the step uses, computed once from the model.
#pragma once

#include "dda/block.h"
#include "dda/model_description.h"
#include "dda/submatrices.h"

#include <Eigen/Core>
#include <Eigen/LU>

#include <vector>

namespace ddafem::dda
{
struct BlockMaterials
{
  std::vector<Eigen::Matrix3d> elasticity; ///< C per material [Pa] (Voigt: xx, yy, xy)
  std::vector<Eigen::Matrix3d> compliance; ///< C^-1 per material [1/Pa]
  bool damped = false; ///< a material or joint material has damping (dda/damping.h)
};

/// The constants of `model`'s materials (its plane mode's C).
inline BlockMaterials block_materials(const ModelDescription& model)
{
  BlockMaterials out;
  for (const Material& m : model.materials)
  {
    out.elasticity.push_back(
        elasticity_matrix(m.youngs_modulus, m.poisson_ratio, model.plane_mode));
    out.compliance.push_back(out.elasticity.back().inverse());
  }
  for (const Material& m : model.materials)
    out.damped = out.damped || m.damping.active();
  for (const JointMaterial& jm : model.joint_materials)
    out.damped = out.damped || jm.damping.active();
  return out;
}

/// rho A0 [kg]: the mass stays that of t = 0 while the block's area changes with its strain.
inline double block_mass(const ModelDescription& model, const Block& b)
{
  return model.materials[b.material].density * b.initial_moments.area;
}

} // namespace ddafem::dda
