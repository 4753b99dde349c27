// The blocks of the DDA model (issue 55): their geometry and state, their materials' constants,
// which of them are held or removed, and what the element kinds see of them (ElementHost): where
// a point lies, how a material point moves with its block, and each block's mass, density and
// kinetic energy in the configuration the step is linearised about (the initial one in a
// small-displacement analysis, the current one otherwise).
#pragma once

#include "dda/block.h"
#include "dda/block_materials.h"
#include "dda/element.h"
#include "dda/model_description.h"
#include "dda/snapshot.h"
#include "dda/step_scheme.h"
#include "dda/types.h"

#include <Eigen/Core>

#include <cstddef>
#include <string>
#include <vector>

namespace ddafem::dda
{
class BlockSet final : public ElementHost
{
public:
  /// The blocks of `model` with their initial velocity and stress, none held or removed.
  /// Throws InputError for a model without blocks. `model` must outlive the set.
  explicit BlockSet(const ModelDescription& model);

  MaterialPoint attach(const Point& p, const std::string& what) const override;
  /// T at a material point, in the configuration the step is linearised about.
  Matrix26 point_matrix(const MaterialPoint& p) const override;
  /// point_matrix(p) d [m] without forming T (displacement_at: the same bits).
  Vector2 point_displacement(const MaterialPoint& p, const Vector6& d) const override;
  bool small_displacement() const override
  {
    return model.geometry == GeometryMode::small_displacement;
  }

  /// Moments of the configuration the step is linearised about (current or initial).
  const PolygonMoments& linearisation_moments(const Block& b) const
  {
    return small_displacement() ? b.initial_moments : b.moments;
  }
  /// Density of the block in the configuration the step is linearised about [kg/m^3]: the
  /// material's, times initial over current area (mass conservation), so that M = rho
  /// integral of T^T T dA keeps the translational mass rho A0.
  double density(const Block& b) const;
  /// v^T M v / 2 of a block [J], with the mass matrix of its linearisation moments.
  double kinetic_energy(const Block& b) const;
  /// rho A0 [kg] of block i.
  double mass_of(std::size_t i) const { return block_mass(model, list[i]); }
  /// The largest displacement of a vertex [m] by the unknowns d (6 per block).
  double largest_vertex_displacement(const Eigen::VectorXd& d) const;
  /// Held until the next stage (hold_block) or removed for the rest of the run.
  bool is_held(std::size_t i) const { return held[i] || removed[i]; }
  bool is_removed(std::size_t i) const { return removed[i]; }
  std::size_t n_dofs() const { return 6 * list.size(); }
  /// Each block's state as written for ParaView.
  std::vector<BlockSnapshot> snapshot() const;
  /// Each block's velocity, acceleration and force at the end of the accepted step of dt [s]
  /// and unknowns d (6 per block), by the scheme's update with the mass matrices the step used
  /// (`masses`), then its geometry and stress. A removed block, held by a penalty, stays at
  /// rest: the little it moves is not motion to carry on.
  void advance_states(const Eigen::VectorXd& d, double dt, const std::vector<Matrix6>& masses,
                      StepScheme& scheme, bool dynamic);
  /// Zero velocity, acceleration and force of every block (static stages, start of a dynamic
  /// one).
  void set_at_rest();

  std::vector<Block> list;
  BlockMaterials materials;  ///< C and C^-1 per material
  std::vector<bool> held;    ///< per block: held until the next begin_stage
  std::vector<bool> removed; ///< per block: inert for the rest of the run

private:
  const ModelDescription& model;
};

/// The blocks' names for messages: each block's origin in the scene, else "block i".
std::vector<std::string> block_names(const ModelDescription& model);

} // namespace ddafem::dda
