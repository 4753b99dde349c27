// The openings of a set of blocks and the keyblocks around them, from the blocks' geometry
// alone (issue 7): a tunnel cut by `rock_mass` and a void enclosed by hand-made blocks alike;
// and when a keyblock counts as fallen.
#pragma once

#include "common/enum_names.h"
#include "dda/types.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <utility>
#include <vector>

namespace ddafem::dda
{
/// An opening as the blocks see it: a hole in the union of the blocks, bounded by block edges
/// (or parts of edges) that no other block shares.
struct OpeningOutline
{
  /// Its boundary's pieces [m], each in the direction of its block's anticlockwise edge (so
  /// clockwise around the hole).
  std::vector<std::pair<Point, Point>> segments;
  Point lower = Point::Zero(); ///< bounding box [m]
  Point upper = Point::Zero();
  double area = 0.0; ///< enclosed area [m^2]

  /// The largest side of the bounding box [m]: the diameter of a circular opening.
  double size() const { return std::max(upper.x() - lower.x(), upper.y() - lower.y()); }
};

/// The openings of a set of blocks and the blocks around them.
struct KeyblockGeometry
{
  /// Ordered by the lower corner of their bounding box: bottom first, then by x.
  std::vector<OpeningOutline> openings;
  /// The keyblocks: blocks with an edge, part of an edge or a point on an opening's boundary;
  /// indices into the blocks, ascending.
  std::vector<std::size_t> blocks;
  std::vector<std::size_t> opening_of; ///< per keyblock: the (first) opening it borders
};

/// Finds the openings of `blocks` (simple polygons, either orientation [m]) and their
/// keyblocks. Edges count as shared where another block's edge runs along them (collinear within
/// `tol` [m], opposite direction, see shared_segments); the unshared pieces form closed
/// loops, the union's outer boundary (anticlockwise) and its holes (clockwise, negative area):
/// the holes wider than 1000 tol (2 area / perimeter) are the openings. A tunnel cut by
/// `rock_mass` is one; so is a void enclosed by hand-made blocks. A boundary tied to a far field
/// is outer: no keyblocks there.
KeyblockGeometry find_keyblocks(const std::vector<std::vector<Point>>& blocks, double tol);

/// Distance [m] from `p` to the nearest piece of the opening's boundary.
double distance_to_boundary(const OpeningOutline& opening, const Point& p);

/// When a keyblock counts as fallen (keyblock_fell): its residual (final) displacement along
/// gravity exceeds `fall_fraction` times the size of its opening; or it is detached and still
/// moves along gravity faster than a free fall over that distance would make it,
/// sqrt(2 g threshold), with g = |gravity| (9.81 m/s^2 for a scene without gravity); or it is
/// detached and its displacement relative to the rock around the opening exceeds the threshold
/// in any direction (thrown out of its place, e.g. a wall block ejected sideways).
struct FallCriterion
{
  double fall_fraction = 0.01; ///< [-] of OpeningOutline::size()
  /// A keyblock that did not fall is loosened when its residual displacement relative to the
  /// rock around the opening exceeds this fraction of the opening's size [-]: 0.6 mm for a 6 m
  /// tunnel, about a hundred times the elastic closure of its joints under the in-situ stress
  /// (sigma L / k_n = 1.3 MPa x 1 m / 2e11 N/m = 6.5 um in the default scene), a tenth of a
  /// percent of the fall threshold's way.
  double loosen_fraction = 1e-4;
};

/// Whether a block translated by `moved` [m] from its place has left it: along the direction it
/// moved it has travelled at least its own width (the extent of `vertices` [m] along it), so
/// that no part of it is still where it was. Rotation is ignored.
bool left_its_place(const std::vector<Point>& vertices, const Vector2& moved);

/// The state of a keyblock that keyblock_fell judges, in SI units.
struct KeyblockMotion
{
  Vector2 displacement = Vector2::Zero();          ///< of its centroid since the reference [m]
  Vector2 relative_displacement = Vector2::Zero(); ///< the same less the surrounding rock's [m]
  Vector2 velocity = Vector2::Zero();              ///< of its centroid [m/s]
  bool held = true; ///< held by a joint, a closed contact or a bolt (else detached)
};

/// How a keyblock fell, or `no` (FallCriterion): `dropped` by the threshold along gravity,
/// `falling` (detached, along gravity faster than the fall speed), `thrown_out` (detached, its
/// relative displacement beyond the threshold). `down`: unit vector along gravity; `threshold`
/// [m]; `gravity` = |g| [m/s^2].
enum class FallVerdict
{
  no,
  dropped,
  falling,
  thrown_out
};

constexpr std::array<EnumName<FallVerdict>, 4> enum_names(FallVerdict)
{
  return {{{FallVerdict::no, "no"},
           {FallVerdict::dropped, "dropped"},
           {FallVerdict::falling, "falling"},
           {FallVerdict::thrown_out, "thrown_out"}}};
}

FallVerdict keyblock_fell(const KeyblockMotion& motion, const Vector2& down, double threshold,
                          double gravity);

} // namespace ddafem::dda
