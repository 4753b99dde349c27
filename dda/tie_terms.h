// A tied body's stiffness in the blocks' equations: T^T H T over runs of tie points on one
// block (TieSet::add_terms), kept per H and turned with the blocks instead of recomputed
// each step.
#pragma once

#include "common/parallel.h"
#include "common/recent_cache.h"
#include "dda/block.h"
#include "dda/types.h"

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace ddafem::dda
{
/// Consecutive tie points on one block: points first .. first + count - 1.
struct TieRun
{
  std::size_t block = 0;
  Eigen::Index first = 0, count = 0;
};

/// The rotation R (6 x 6) with T(x) = T(x0) R for every point x of a block whose points x0
/// (offsets from its centroid, `reference`) moved to x (`current`) by one linear map F: DDA
/// moves a block's vertices and material points by the same affine map each step. R is the
/// identity on (u0, v0) and maps (r0, ex, ey, gxy) by the Q with L(Q d) = L(d) F, L(d) the 2 x 2
/// gradient [[ex, gxy/2 - r0], [gxy/2 + r0, ey]] of T's last four columns. F is fitted to the
/// vertices by least squares (exact but for round-off: they move affinely).
Matrix6 block_turn(const std::vector<Point>& reference, const Point& reference_centroid,
                   const std::vector<Point>& current, const Point& current_centroid);

/// The pair terms X_ab = T_a^T H(points of a, points of b) T_b of a tied body's H (2m x 2m) for
/// the runs a <= b of its m tie points. Computed directly (Y = H T run by run, then T_a^T Y), or,
/// when the body names H's contents by an id (the ties' condensation for one dt), once per id
/// at the blocks' initial geometry, X0, and each step R_a^T X0_ab R_b with each block's turn R
/// since t = 0 (block_turn): about a tenth of the products. Each pair is computed alone, so the
/// bits do not depend on the threads.
class TieTerms
{
public:
  /// The runs of `points` (points of one block together).
  void set_points(const std::vector<MaterialPoint>& points);
  const std::vector<TieRun>& runs() const { return tie_runs; }
  /// Computes the pair terms for H = `h` with the points' T now (`t`, one per point); `id`
  /// names H's contents when they repeat. `small_displacement`: T stays at the initial
  /// geometry.
  void compute(const Eigen::MatrixXd& h, std::optional<std::uint64_t> id,
               const std::vector<Matrix26>& t, const std::vector<MaterialPoint>& points,
               const std::vector<Block>& blocks, bool small_displacement, const Parallel& parallel);
  /// X_ab of the last compute(), a <= b.
  const Matrix6& pair(std::size_t a, std::size_t b) const { return pairs[pair_start[a] + b - a]; }
  /// T_a^T g(points of a) [N] with the points' T of the last compute().
  Vector6 force(std::size_t a, const Eigen::VectorXd& g) const;
  /// Initial-geometry pair terms built (one per id kept, rebuilds after the cache dropped one).
  std::size_t n_initial_builds() const { return initial_builds; }

private:
  /// X_ab = T_a^T H T_b for all pairs into `out`, T of the runs in `stacks`.
  void direct(const Eigen::MatrixXd& h,
              const std::vector<Eigen::Matrix<double, Eigen::Dynamic, 6>>& stacks,
              std::vector<Matrix6>& out, const Parallel& parallel);
  void stack(const std::vector<Matrix26>& t,
             std::vector<Eigen::Matrix<double, Eigen::Dynamic, 6>>& stacks) const;

  std::vector<TieRun> tie_runs;
  std::vector<std::size_t> pair_start; ///< pair (a, b) at pair_start[a] + b - a
  std::vector<Matrix6> pairs;
  /// T of each run's points stacked (2 count x 6), now and at the initial geometry
  std::vector<Eigen::Matrix<double, Eigen::Dynamic, 6>> stacks, initial_stacks;
  Eigen::MatrixXd products; ///< Y = H T: 2m rows, 6 columns per run
  /// X0 by H's id: the pair terms at the initial geometry (a coupled run's dt levels)
  RecentCache<std::uint64_t, std::vector<Matrix6>> initial_pairs{16};
  std::vector<Matrix6> turns; ///< R of each run's block
  std::size_t initial_builds = 0;
};

} // namespace ddafem::dda
