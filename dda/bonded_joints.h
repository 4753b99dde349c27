// The blocks' bonded joints (issue 55): where two blocks share an edge through a bonded joint
// material, two end springs hold the gap with the in-situ preloads until the joint exceeds its
// strength; then it is gone and the blocks meet through contacts (dda/joints.h has the joint's
// springs and law). The System calls the hooks below in its step's phases; the sums they add to
// keep their order.
#pragma once

#include "dda/block.h"
#include "dda/damping.h"
#include "dda/element.h"
#include "dda/joints.h"
#include "dda/model_description.h"
#include "dda/snapshot.h"
#include "dda/types.h"

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace ddafem::dda
{
struct BondedJoints
{
  using BlockPairs = std::vector<std::pair<std::size_t, std::size_t>>;

  /// The bonded joints among the joints where blocks share an edge (find_joints within `tol`
  /// [m]; `names` of the blocks for messages). A small-displacement analysis cannot follow
  /// contacts: there a frictional joint throws InputError.
  void find(const ModelDescription& model, const std::vector<Block>& blocks,
            const std::vector<std::string>& names, double tol, bool small_displacement);
  /// The in-situ traction on block a (n out of a), what b puts on a across the joint in the
  /// rock mass at rest, as the end springs' preloads and forces.
  void apply_in_situ_stress(const InSituStress& in_situ);
  /// (block_a, block_b) of every intact joint and the blocks of every element of `kinds`
  /// between two blocks (lower first), sorted: the matrix couples them. Rebuilt once per
  /// revision.
  const BlockPairs& joined(const std::vector<std::unique_ptr<ElementKind>>& kinds);
  /// Each joint's coupling block in the step's matrix (StepEquations::coupling_of), looked up again
  /// when the matrix structure changed or the joints did.
  void find_couplings(const StepEquations& equations, bool structure_changed);
  /// Springs K_s on the gap g + T_b d_b - T_a d_a (g = x_b - x_a) with the preloads; with a
  /// dashpot (dda/damping.h) (1 + c_v beta) K_s and beta K_s on the velocity offsets.
  void assemble(const ElementHost& host, const ModelDescription& model,
                const StepDashpots& dashpots, StepEquations& step, bool with_matrix) const;
  /// The dashpots' work -C v . du over the step [J] (`mean`: each block's mean velocity), added
  /// to `work`.
  void add_work_of_damping(const ElementHost& host, const ModelDescription& model,
                           const StepDashpots& dashpots, const std::vector<Vector6>& mean,
                           const Eigen::VectorXd& d, double& work) const;
  /// The joint ends move with their blocks by the accepted step's unknowns d.
  void move_points(const ElementHost& host, const Eigen::VectorXd& d);
  /// The springs' forces at the gaps of the moved joint ends.
  void update_forces(const ModelDescription& model, bool small_displacement);
  /// Joints beyond their strength (Mohr-Coulomb with cohesion and tension over the half length
  /// each end carries, `tan_friction` per joint material) are removed, in order. Returns the
  /// message of a failure at time t [s] if `small_displacement` cannot follow it, else empty.
  std::string break_beyond_strength(const ModelDescription& model,
                                    const std::vector<double>& tan_friction,
                                    bool small_displacement, double t);
  /// Block i is removed from the model: its joints go.
  void remove_block(std::size_t i);
  /// The springs' energy [J], added to `energy`.
  void add_energy(const ModelDescription& model, double& energy) const;
  /// Static stages' balance: add(block, |force| [N]) for each end on each of its blocks.
  void add_loads(const std::function<void(std::size_t, double)>& add) const;
  /// Each end as a bonded contact point.
  void add_snapshots(bool small_displacement, std::vector<ContactSnapshot>& out) const;

  std::vector<Joint> list;  ///< the intact joints, in the order found
  std::size_t n_broken = 0; ///< joints broken since t = 0
  /// Counts the changes of the intact joints (a joint broke, a block was removed).
  std::uint64_t revision = 0;
  /// joined(): its pairs and the revision they are of.
  struct Lists
  {
    std::uint64_t revision = std::numeric_limits<std::uint64_t>::max();
    BlockPairs joined;
  } lists;
  /// The revision when the joints' couplings were last looked up (find_couplings).
  std::uint64_t couplings_revision = std::numeric_limits<std::uint64_t>::max();
};

} // namespace ddafem::dda
