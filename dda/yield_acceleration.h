// Newmark's yield acceleration of a keyblock: the smallest pseudo-static ground acceleration
// at which the block, rigid on its joints, starts to move (Goodman & Shi's block theory in 2D:
// lift-off or sliding on one face, translations only). Pure functions of the geometry.
#pragma once

#include "dda/types.h"

#include <cstddef>
#include <limits>
#include <vector>

namespace ddafem::dda
{
/// A face on which a block rests against a neighbour: an edge of the block's polygon that is not
/// on an opening.
struct BlockFace
{
  std::size_t edge = 0;              ///< edge k runs from vertex k to vertex k + 1
  Vector2 normal = Vector2::Zero();  ///< unit normal into the block (away from the neighbour)
  Vector2 tangent = Vector2::Zero(); ///< unit tangent along the edge
  double tan_friction = 0.0;         ///< tan(phi) of the joint there
};

/// How a block yields.
enum class YieldMode
{
  none,     ///< no translation that this shaking can start leaves its neighbours
  lift_off, ///< leaves every face (falls or is thrown out)
  slide     ///< slides on one face, leaving the others
};

struct YieldAcceleration
{
  /// Smallest |a| [m/s^2] of the ground acceleration a d at which it moves; 0 if gravity alone
  /// moves it; infinity if shaking along d alone cannot move it (mode none: e.g. a block whose
  /// only way out is up, shaken horizontally; rotations are not considered).
  double a_y = std::numeric_limits<double>::infinity();
  double sign = 1.0; ///< the ground accelerates along +d (1) or -d (-1) at a_y
  YieldMode mode = YieldMode::none;
  std::size_t edge = 0; ///< the edge of the face it slides on (mode slide)
};

/// The faces of a polygon (anticlockwise, [m]) whose edges are not on an opening: an edge is on
/// an opening if its midpoint is within `tol` [m] of one of `opening_segments`. tan_friction per
/// edge.
std::vector<BlockFace> block_faces(const std::vector<Point>& polygon,
                                   const std::vector<std::pair<Point, Point>>& opening_segments,
                                   const std::vector<double>& tan_friction, double tol);

/// The yield acceleration of a rigid block on `faces` under gravity `g` [m/s^2] and a ground
/// acceleration a d (d a unit direction: horizontal for an SV wave, vertical for a P wave). The
/// block feels g - a d per unit mass. Lift-off: (g - a d) . n_j >= 0 on every face. Sliding on
/// face i along s = +-t_i, with s . n_j >= 0 on the others: the face pushed, N = -(g - a d) . n_i
/// >= 0, and (g - a d) . s >= tan(phi_i) N. No cohesion, no tensile strength and no clamping by
/// the in-situ stress: a lower bound of what holds the block.
YieldAcceleration yield_acceleration(const std::vector<BlockFace>& faces, const Vector2& g,
                                     const Vector2& d);

} // namespace ddafem::dda
