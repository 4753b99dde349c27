// Element kinds of the blocks' model (issue 55): a kind is one module that holds every element of
// its sort a scene has (e.g. its end-anchored bolts) and takes part in the System's step through
// the hooks below, which the System calls over its kinds in a fixed order (make_element_kinds)
// without naming any of them. A new kind is its law, one class with these hooks, one line in
// make_element_kinds, its scene reader and its outputs.
#pragma once

#include "common/checkpoint_fwd.h"
#include "dda/block.h"

#include <Eigen/Core>

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace ddafem::dda
{
struct ModelDescription;
struct StepEquations;

/// What an element kind sees of the blocks (the System): where a point lies and how a material
/// point moves with its block in the configuration the step is linearised about.
class ElementHost
{
public:
  /// The material point of the block containing p [m]; throws InputError naming `what` if no
  /// block contains it.
  virtual MaterialPoint attach(const Point& p, const std::string& what) const = 0;
  /// T at a material point: its displacement [m] is T d for its block's 6 unknowns d.
  virtual Matrix26 point_matrix(const MaterialPoint& p) const = 0;
  /// point_matrix(p) d [m] for the block's unknowns d (the same bits, without forming T).
  virtual Vector2 point_displacement(const MaterialPoint& p, const Vector6& d) const = 0;
  /// Whether the step is linearised about the initial configuration (small displacement).
  virtual bool small_displacement() const = 0;
  /// Moves a material point with its block by the accepted step's unknowns d (6 per block).
  void move_with_block(MaterialPoint& p, const Eigen::VectorXd& d) const
  {
    p.position += point_displacement(p, d.segment<6>(6 * p.block));
  }

protected:
  ~ElementHost() = default;
};

/// One kind of element on the blocks. The System calls each hook over its kinds in the order of
/// make_element_kinds; within a kind the elements go in scene order, so that sums keep their bits.
class ElementKind
{
public:
  virtual ~ElementKind() = default;

  /// Stage `stage` (0: the first) begins at time t [s]: elements installed later start here.
  virtual void begin_stage(std::size_t /*stage*/, double /*t*/) {}
  /// Appends the block pairs (lower first) its elements couple in the step's matrix.
  virtual void add_couplings(std::vector<std::pair<std::size_t, std::size_t>>& pairs) const = 0;
  /// Whether its stiffness changes with its state, so that the matrix is assembled every step.
  virtual bool changes_stiffness() const = 0;
  /// Adds its forces at the step's start to the right-hand side and, `with_matrix`, its
  /// stiffness to the matrix.
  virtual void assemble(const ElementHost& host, StepEquations& step, bool with_matrix) const = 0;
  /// Static stages' balance: calls add(block, |force| [N]) for each force it puts on a block.
  virtual void add_loads(const std::function<void(std::size_t, double)>& add) const = 0;
  /// Its material points move with their blocks by the accepted step's unknowns d (6 per block).
  virtual void move_points(const ElementHost& host, const Eigen::VectorXd& d) = 0;
  /// Its state, forces and records after an accepted step ending at time t [s].
  virtual void update(const ElementHost& host, double t) = 0;
  /// Calls hold(block) for each block one of its elements still ties to another (not broken
  /// or ruptured): a keyblock so held hangs on its support (KeyblockRecorder::held_keyblocks).
  virtual void add_held_blocks(const std::function<void(std::size_t)>& hold) const = 0;
  /// Adds its elastic energy [J], element by element, to `energy`.
  virtual void add_energy(double& energy) const = 0;
  /// Checkpoints: its state between accepted steps (load: of a kind built from the same model;
  /// std::runtime_error otherwise).
  virtual void save(CheckpointOut& archive) const = 0;
  virtual void load(CheckpointIn& archive) = 0;
};

/// The model's element kinds in the order the step takes them (dda/element_kinds.cc; every
/// kind, with no elements if the scene has none). Attaches their points
/// through `host`; throws InputError for an element the blocks cannot carry.
std::vector<std::unique_ptr<ElementKind>> make_element_kinds(const ModelDescription& model,
                                                             const ElementHost& host);

} // namespace ddafem::dda
