// The blocks' truncation (issue 55): the edges of the viscous boundaries (VB I, VB II, dashpots,
// free edges) with the incident wave's input force, and the static supports that hold those
// edges while a static stage finds the in-situ equilibrium (dda/viscous_boundary.h has the
// boundaries' laws). The System calls the hooks below in its step's phases; the sums they add
// to keep their order.
#pragma once

#include "dda/block.h"
#include "dda/element.h"
#include "dda/energy_ledger.h"
#include "dda/integrator.h"
#include "dda/joints.h"
#include "dda/model_description.h"
#include "dda/types.h"
#include "dda/viscous_boundary.h"

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <functional>
#include <vector>

namespace ddafem::dda
{
/// A static support of a viscous boundary: an end of a selected edge held by a normal and a
/// shear spring to `anchor` in static stages, with a force `load` [N] (global components) on
/// the block: the in-situ traction over half the edge at first, in dynamic stages the force
/// the support held when the static stage ended (a constant edge load).
struct Support
{
  MaterialPoint point;
  Eigen::Matrix2d stiffness; ///< p n n^T + p_s t t^T [N/m], n the edge's outward normal
  Vector2 load;              ///< [N]
  Point anchor;              ///< fixed ground [m], where the point was when the stage began
  /// Force on the block [N]: load + stiffness (anchor - position).
  Vector2 force() const { return load + stiffness * (anchor - point.position); }
};

/// Outward unit normal of a boundary edge in the configuration the step is linearised about
/// (the initial one if `small_displacement`).
Vector2 boundary_normal(const BoundaryEdge& e, const std::vector<Block>& blocks,
                        bool small_displacement);

struct BoundarySet
{
  /// What the boundaries read of the model and the step.
  struct StepInput
  {
    const ModelDescription& model;
    const std::vector<Block>& blocks;
    const ElementHost& host;
    bool is_static = false;    ///< a static stage: the supports hold the edges
    double t0 = 0.0, t1 = 0.0; ///< the step's start and end [s]
  };

  /// The edges each boundary of `model` selects (tolerance `tol` [m]); throws InputError for an
  /// edge that two boundaries select.
  void select(const ModelDescription& model, const std::vector<Block>& blocks,
              const std::vector<Joint>& joints, double tol);
  /// The supports of every edge of a boundary that is not free: springs like a bonded joint's
  /// at both ends (joints.default's, else `default_stiffness` [N/m] with a shear ratio of 0.4),
  /// preloaded with the in-situ traction over the edge.
  void set_up_supports(const ModelDescription& model, const std::vector<Block>& blocks,
                       double default_stiffness, bool small_displacement);
  /// A stage begins: what the supports hold at the end of a static stage stays as a constant
  /// load on the edges (`after_static`); a static stage anchors them where the edges are.
  void begin_stage(bool after_static, bool is_static);
  /// The incident wave's input force on edge e at time t [s] [N]: 2 (cn n n^T + ct t t^T) v_in.
  Vector2 input_force(const StepInput& in, const BoundaryEdge& e, double t) const;
  /// The boundaries' dashpots (dynamic stages; `start(block)`: its state at the step's start,
  /// `integration`'s beta and gamma) with their input force at t1, and the supports (springs in
  /// static stages, constant loads in dynamic ones); keeps each edge's step for add_work.
  void assemble(const StepInput& in, const IntegratorCoefficients& integration, double dt,
                const std::function<KinematicState(std::size_t)>& start, StepEquations& step,
                bool with_matrix);
  /// The step's work with the blocks' unknowns d [J]: the boundaries' -k T d + f on T d into
  /// ledger.boundaries; in dynamic stages the input forces (trapezoidal in time) and the
  /// supports' constant loads into ledger.loads. Before the points move.
  void add_work(const StepInput& in, const Eigen::VectorXd& d, EnergyLedger& ledger) const;
  /// The edges' midpoints and the supports move with their blocks by the unknowns d.
  void move_points(const ElementHost& host, const Eigen::VectorXd& d);
  /// Static stages' balance: add(block, |force| [N]) for each support.
  void add_loads(const std::function<void(std::size_t, double)>& add) const;

  std::vector<BoundaryEdge> edges;
  /// Each edge's stiffness and force in the current step (assemble), for its work (add_work).
  std::vector<BoundaryStep> steps;
  std::vector<Support> supports;         ///< two per edge of a vb1, vb2 or dashpot boundary
  double support_normal_stiffness = 0.0; ///< [N/m]
};

} // namespace ddafem::dda
