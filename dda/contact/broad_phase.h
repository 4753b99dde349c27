// Broad phase of contact detection: axis-aligned bounding boxes and the pairs whose boxes overlap.
#pragma once

#include "dda/types.h"

#include <cstddef>
#include <utility>
#include <vector>

namespace ddafem::dda
{
/// An axis-aligned box [x_min, x_max] x [y_min, y_max] [m].
struct BoundingBox
{
  double x_min, x_max, y_min, y_max;
};

/// The smallest box around `vertices`, inflated by `pad` [m] on every side (pad >= 0 is the
/// distance within which two polygons count as neighbours). Throws std::invalid_argument for no
/// vertices.
BoundingBox bounding_box(const std::vector<Point>& vertices, double pad);

/// Every pair (i, j), i < j, of boxes that overlap or touch (a shared side or corner counts),
/// sorted lexicographically. Sweep and prune along x: boxes sorted by x_min, and each box is
/// tested (in y) only against the boxes whose x_min lies in its x range. Cost O(n log n + m),
/// where m is the number of pairs whose x ranges overlap (m = k, the number of pairs returned,
/// when the boxes are spread in y no more than in x).
std::vector<std::pair<std::size_t, std::size_t>>
overlapping_pairs(const std::vector<BoundingBox>& boxes);

} // namespace ddafem::dda
