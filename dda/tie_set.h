// The blocks' ties to a tied body (issue 55): the far field that the System steps with itself
// (dda/tied_body.h). The tie points move with their blocks; each step the body gets their
// displacements since the origins (t = 0, then the static equilibrium reached) and gives back its
// condensed stiffness H (2m x 2m) and force g (2m) on them, which enter the blocks' equations as
// T^T H T and T^T g (T of each point at the step's start); the body then takes the increments
// T d of the solution. Without a body the set is empty and every hook does nothing.
#pragma once

#include "common/parallel.h"
#include "dda/block.h"
#include "dda/element.h"
#include "dda/linear_solver.h"
#include "dda/tie_terms.h"
#include "dda/tied_body.h"
#include "dda/types.h"

#include <Eigen/Core>

#include <cstddef>
#include <functional>
#include <future>
#include <utility>
#include <vector>

namespace ddafem::dda
{
struct TieSet
{
  /// Ties `points_` (each on the boundary of its block, points of one block together) to
  /// `body_`; throws InputError for a point off its block's boundary (within `tolerance` [m]).
  void attach(TiedBody& body_, const std::vector<MaterialPoint>& points_,
              const std::vector<Block>& blocks, double tolerance);
  bool has_body() const { return body != nullptr; }
  std::size_t size() const { return points.size(); }
  /// Every pair (i < j) of blocks with tie points, sorted: H is dense over them.
  std::vector<std::pair<std::size_t, std::size_t>> block_pairs() const;
  /// A dynamic stage after a static one measures the ties' displacements from here.
  void measure_from_here();
  /// Each point's T at the step's start (host.point_matrix) and the body's step begun with
  /// the points' displacements since their origins, on another thread if the body allows it
  /// (deferred otherwise); its time adds to `seconds`. No future without a body.
  std::future<StepResult> begin_step(double dt, const ElementHost& host, double& seconds);
  /// Adds T^T H T to the matrix and T^T g to the right-hand side (step.coupling_of between
  /// blocks, host.small_displacement for the pair terms' geometry).
  void add_terms(StepEquations& step, const ElementHost& host, const std::vector<Block>& blocks,
                 const Parallel& parallel);
  /// The points' displacement increments T d (2m) of the blocks' unknowns d (6 per block).
  Eigen::VectorXd increments(const Eigen::VectorXd& d) const;
  /// The points move with their blocks by the accepted step's unknowns d.
  void move_points(const ElementHost& host, const Eigen::VectorXd& d);
  /// Static stages' balance: add(block, |g_k| [N]) for each tie point.
  void add_loads(const std::function<void(std::size_t, double)>& add) const;

  TiedBody* body = nullptr;
  std::vector<MaterialPoint> points; ///< the tie points, at their current positions [m]
  /// Where each point's displacement is measured from: t = 0, then the static equilibrium.
  std::vector<Point> origins;
  std::vector<Matrix26> matrices;  ///< T of each point at the step's start
  std::vector<std::size_t> blocks; ///< blocks with tie points, sorted
  TieTerms pairs;                  ///< T^T H T of the body, pair by pair of its runs of points
  /// The step's matrix without contacts but with the ties' terms, and its right-hand side:
  /// where each open-close iteration starts while the ties keep their states.
  BlockSparseMatrix matrix{0, {}};
  Eigen::VectorXd rhs;
};

} // namespace ddafem::dda
