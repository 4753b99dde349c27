// A DDA block: its current geometry and its dynamic state.
#pragma once

#include "dda/geometry.h"
#include "dda/types.h"

#include <cstddef>
#include <vector>

namespace ddafem::dda
{
/// One block. The reference point of its unknowns is the current centroid.
struct Block
{
  std::size_t material = 0;
  std::vector<Point> vertices; ///< current vertices [m], anticlockwise
  /// Of the current vertices. In a small-displacement analysis only the centroid follows the
  /// block; area and second moments stay those of t = 0, the configuration it is linear about.
  PolygonMoments moments;
  std::vector<Point> initial_vertices;    ///< vertices at t = 0 [m]
  PolygonMoments initial_moments;         ///< of the vertices at t = 0
  Point initial_centroid = Point::Zero(); ///< centroid at t = 0 [m]
  Vector6 velocity = Vector6::Zero();     ///< d/dt of the unknowns (m/s, rad/s, 1/s)
  Vector6 acceleration = Vector6::Zero(); ///< d2/dt2 of the unknowns (used by Newmark)
  /// The non-inertial generalised force on the block at the end of the last step [N, N m]
  /// (generalized-alpha's r_n, see dda/integrator.h)
  Vector6 force = Vector6::Zero();
  Voigt stress = Voigt::Zero(); ///< accumulated (sxx, syy, sxy) [Pa], tension positive
  Voigt strain = Voigt::Zero(); ///< accumulated (exx, eyy, gxy) [-]

  Block(std::size_t material, std::vector<Point> vertices);

  /// Moves the vertices by T(x) d, updates the moments and accumulates the strain and stress
  /// of the step (stress += C * strain increment). With `about_initial`, T is evaluated at the
  /// initial vertices about the initial centroid (small-displacement analysis), else at the
  /// current ones (Shi's updated geometry).
  void apply_increment(const Vector6& d, const Eigen::Matrix3d& elasticity, bool about_initial);

  /// Centroid displacement since t = 0 [m].
  Vector2 displacement() const { return moments.centroid - initial_centroid; }
};

/// A point attached to a block (load, monitor, fixed point, joint end): it moves with the block.
struct MaterialPoint
{
  std::size_t block = 0;
  Point position = Point::Zero(); ///< current position [m]
  Point initial = Point::Zero();  ///< position at t = 0 [m]
};

} // namespace ddafem::dda
