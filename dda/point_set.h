// The blocks' point elements (issue 55): point loads, fixed points (penalty springs to a target
// that may move with time) and monitors, each a material point that moves with its block. The
// System calls the hooks below in its step's phases; the sums they add to keep their order.
#pragma once

#include "dda/block.h"
#include "dda/element.h"
#include "dda/energy_ledger.h"
#include "dda/model_description.h"
#include "dda/types.h"

#include <Eigen/Core>

#include <cstddef>
#include <functional>
#include <vector>

namespace ddafem::dda
{
struct AttachedLoad
{
  MaterialPoint point;
  Vector2 force; ///< [N], times `function`
  TimeFunction function;
};

struct AttachedFixedPoint
{
  MaterialPoint point;
  double stiffness; ///< [N/m]
  TimeFunction displacement_x, displacement_y;
  /// Where the spring pulls the point at time t [s]: its initial position moved by the
  /// prescribed displacement [m].
  Point target(double t) const;
};

/// The fixed points' default penalty [N/m]: 10 x the stiffest joint or block (E x 1 m).
double default_fixed_stiffness(const ModelDescription& model);

struct PointSet
{
  /// The model's point loads, fixed points (without a stiffness: default_stiffness) and
  /// monitors on the blocks that contain them (host.attach: InputError for a point outside).
  void attach(const ModelDescription& model, const ElementHost& host);
  /// Loads at the step's end time t1 [s] on the right-hand side; fixed points' springs
  /// k |x + T d - X(t1)|^2 / 2 (their stiffness into the matrix if `with_matrix`).
  void assemble(const ElementHost& host, StepEquations& step, double t1, bool with_matrix) const;
  /// The step's work from t0 to t1 [s] with the blocks' unknowns d [J]: the loads' (trapezoidal
  /// in time) into ledger.loads, the moving fixed points' -k (x - X)_mid . dX into
  /// ledger.supports; before the points move.
  void add_work(const ElementHost& host, const Eigen::VectorXd& d, double t0, double t1,
                EnergyLedger& ledger) const;
  /// The points move with their blocks by the accepted step's unknowns d.
  void move_points(const ElementHost& host, const Eigen::VectorXd& d);
  /// Static stages' balance at time t [s]: add(block, |force| [N]) for each load and spring.
  void add_loads(const std::function<void(std::size_t, double)>& add, double t) const;
  /// The fixed points' spring energy at time t [s] [J], added to `energy`.
  void add_energy(double& energy, double t) const;
  /// A dynamic stage after a static one measures the monitors' displacements from here.
  void measure_from_here();

  double default_stiffness = 0.0; ///< of fixed points without their own [N/m]
  std::vector<AttachedLoad> loads;
  std::vector<AttachedFixedPoint> fixed_points;
  std::vector<MaterialPoint> monitors;
  std::vector<Point> monitor_origins; ///< where each monitor's displacement is measured from
};

} // namespace ddafem::dda
