#include "dda/contact/broad_phase.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace ddafem::dda
{
namespace
{
using IndexPair = std::pair<std::size_t, std::size_t>;

/// Stable counting sort of `pairs` by key(pair), a value in [0, n): O(n + pairs.size()).
template <typename Key>
void stable_sort_by(std::vector<IndexPair>& pairs, std::size_t n, Key key)
{
  std::vector<std::size_t> start(n + 1, 0);
  for (const IndexPair& p : pairs)
    ++start[key(p) + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<IndexPair> sorted(pairs.size());
  for (const IndexPair& p : pairs)
    sorted[start[key(p)]++] = p;
  pairs.swap(sorted);
}
} // namespace

BoundingBox bounding_box(const std::vector<Point>& vertices, double pad)
{
  if (vertices.empty())
    throw std::invalid_argument("bounding_box: no vertices, expected at least one");
  BoundingBox b{vertices[0].x(), vertices[0].x(), vertices[0].y(), vertices[0].y()};
  for (const Point& v : vertices)
  {
    b.x_min = std::min(b.x_min, v.x());
    b.x_max = std::max(b.x_max, v.x());
    b.y_min = std::min(b.y_min, v.y());
    b.y_max = std::max(b.y_max, v.y());
  }
  b.x_min -= pad;
  b.y_min -= pad;
  b.x_max += pad;
  b.y_max += pad;
  return b;
}

std::vector<std::pair<std::size_t, std::size_t>>
overlapping_pairs(const std::vector<BoundingBox>& boxes)
{
  const std::size_t n_boxes = boxes.size();
  std::vector<std::size_t> order(n_boxes);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](std::size_t i, std::size_t j) {
              return boxes[i].x_min < boxes[j].x_min || (boxes[i].x_min == boxes[j].x_min && i < j);
            });

  std::vector<IndexPair> pairs;
  for (std::size_t oi = 0; oi < n_boxes; ++oi)
  {
    const BoundingBox& bi = boxes[order[oi]];
    for (std::size_t oj = oi + 1; oj < n_boxes; ++oj)
    {
      const BoundingBox& bj = boxes[order[oj]];
      if (bj.x_min > bi.x_max)
        break; // this and every later box start right of bi
      if (bj.y_min > bi.y_max || bj.y_max < bi.y_min)
        continue;
      pairs.emplace_back(std::min(order[oi], order[oj]), std::max(order[oi], order[oj]));
    }
  }
  // Lexicographic order in O(n + k): by the second index, then stably by the first.
  stable_sort_by(pairs, n_boxes, [](const IndexPair& p) { return p.second; });
  stable_sort_by(pairs, n_boxes, [](const IndexPair& p) { return p.first; });
  return pairs;
}

} // namespace ddafem::dda
