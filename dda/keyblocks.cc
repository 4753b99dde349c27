#include "dda/keyblocks.h"

#include "dda/contact/broad_phase.h"
#include "dda/geometry.h"

#include <cmath>
#include <limits>
#include <numeric>

namespace ddafem::dda
{
namespace
{
constexpr std::size_t npos = std::numeric_limits<std::size_t>::max();

/// A piece of block edge that no other block shares, in the block's anticlockwise direction.
struct Piece
{
  Point from, to;
  std::size_t block;
};

/// The pieces of the blocks' edges (anticlockwise polygons) that no other block's edge runs
/// along.
std::vector<Piece> unshared_pieces(const std::vector<std::vector<Point>>& polygons, double tol)
{
  // Per block and edge: the stretches [s0, s1] (distance from the edge's start) shared.
  std::vector<std::vector<std::vector<std::pair<double, double>>>> shared(polygons.size());
  std::vector<BoundingBox> boxes;
  for (std::size_t b = 0; b < polygons.size(); ++b)
  {
    shared[b].resize(polygons[b].size());
    boxes.push_back(bounding_box(polygons[b], tol));
  }
  for (const auto& [i, j] : overlapping_pairs(boxes))
    for (const SharedSegment& s : shared_segments(polygons[i], polygons[j], tol))
    {
      // p and q run along i's edge, so against j's.
      const Point& a = polygons[i][s.a_edge];
      const Point& b = polygons[j][s.b_edge];
      shared[i][s.a_edge].emplace_back((s.p - a).norm(), (s.q - a).norm());
      shared[j][s.b_edge].emplace_back((s.q - b).norm(), (s.p - b).norm());
    }

  std::vector<Piece> pieces;
  for (std::size_t b = 0; b < polygons.size(); ++b)
  {
    const std::vector<Point>& v = polygons[b];
    for (std::size_t e = 0; e < v.size(); ++e)
    {
      const Point& a = v[e];
      const Vector2 edge = v[(e + 1) % v.size()] - a;
      const double length = edge.norm();
      const Vector2 t = edge / length;
      std::vector<std::pair<double, double>>& stretches = shared[b][e];
      std::sort(stretches.begin(), stretches.end());
      double covered = 0.0; // the edge is shared from its start up to here
      stretches.emplace_back(length, length);
      for (const auto& [s0, s1] : stretches)
      {
        if (s0 - covered > tol)
          pieces.push_back({a + covered * t, a + s0 * t, b});
        covered = std::max(covered, s1);
      }
    }
  }
  return pieces;
}

/// Groups the pieces into connected loops (pieces meeting at an end within tol); returns each
/// piece's loop number and the number of loops.
std::pair<std::vector<std::size_t>, std::size_t> loops_of(const std::vector<Piece>& pieces,
                                                          double tol)
{
  std::vector<std::size_t> parent(pieces.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](std::size_t k)
  {
    while (parent[k] != k)
      k = parent[k] = parent[parent[k]];
    return k;
  };
  // Ends sorted by x: each is compared only with those within tol in x.
  std::vector<std::pair<Point, std::size_t>> ends;
  for (std::size_t k = 0; k < pieces.size(); ++k)
  {
    ends.emplace_back(pieces[k].from, k);
    ends.emplace_back(pieces[k].to, k);
  }
  std::sort(ends.begin(), ends.end(),
            [](const auto& a, const auto& b) { return a.first.x() < b.first.x(); });
  for (std::size_t i = 0; i < ends.size(); ++i)
    for (std::size_t j = i + 1; j < ends.size() && ends[j].first.x() - ends[i].first.x() <= tol;
         ++j)
      if ((ends[j].first - ends[i].first).norm() <= tol)
        parent[root(ends[i].second)] = root(ends[j].second);

  std::vector<std::size_t> loop(pieces.size(), npos), number(pieces.size(), npos);
  std::size_t n_loops = 0;
  for (std::size_t k = 0; k < pieces.size(); ++k)
  {
    const std::size_t r = root(k);
    if (number[r] == npos)
      number[r] = n_loops++;
    loop[k] = number[r];
  }
  return {loop, n_loops};
}

/// Distance from p to the segment [a, b].
double distance_to_segment(const Point& p, const Point& a, const Point& b)
{
  const Vector2 ab = b - a;
  const double s = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + s * ab)).norm();
}

bool boxes_overlap(const OpeningOutline& o, const BoundingBox& b)
{
  return b.x_min <= o.upper.x() && b.x_max >= o.lower.x() && b.y_min <= o.upper.y() &&
         b.y_max >= o.lower.y();
}
} // namespace

KeyblockGeometry find_keyblocks(const std::vector<std::vector<Point>>& blocks, double tol)
{
  std::vector<std::vector<Point>> polygons = blocks;
  for (std::vector<Point>& p : polygons)
    if (signed_area(p) < 0.0)
      std::reverse(p.begin(), p.end());
  const std::vector<Piece> pieces = unshared_pieces(polygons, tol);
  const auto [loop, n_loops] = loops_of(pieces, tol);

  // Each loop's area by the shoelace formula over its directed pieces (no need to chain them),
  // about a common origin against cancellation: outer boundaries are anticlockwise (> 0).
  const Point origin = pieces.empty() ? Point::Zero() : pieces.front().from;
  std::vector<OpeningOutline> loops(n_loops);
  std::vector<bool> started(n_loops, false);
  for (std::size_t k = 0; k < pieces.size(); ++k)
  {
    OpeningOutline& o = loops[loop[k]];
    const Piece& p = pieces[k];
    o.segments.emplace_back(p.from, p.to);
    const Vector2 a = p.from - origin, b = p.to - origin;
    o.area -= 0.5 * (a.x() * b.y() - a.y() * b.x()); // clockwise: a hole's area > 0
    o.lower = started[loop[k]] ? o.lower.cwiseMin(p.from) : p.from;
    o.upper = started[loop[k]] ? o.upper.cwiseMax(p.from) : p.from;
    started[loop[k]] = true;
  }
  // The holes: clockwise loops wider than round-off (2 area / perimeter, half the width of a
  // strip, above 1000 tol: not a gap between edges that miss each other by a little more than
  // tol).
  KeyblockGeometry g;
  for (const OpeningOutline& o : loops)
  {
    double perimeter = 0.0;
    for (const auto& [from, to] : o.segments)
      perimeter += (to - from).norm();
    if (2.0 * o.area > 1e3 * tol * perimeter)
      g.openings.push_back(o);
  }
  std::sort(g.openings.begin(), g.openings.end(),
            [](const OpeningOutline& a, const OpeningOutline& b) {
              return std::make_pair(a.lower.y(), a.lower.x()) <
                     std::make_pair(b.lower.y(), b.lower.x());
            });

  // Keyblocks: blocks with a point of their boundary on an opening's (the blocks do not
  // overlap, so edges that do not cross are within tol where an end of one is).
  for (std::size_t b = 0; b < polygons.size(); ++b)
  {
    const std::vector<Point>& v = polygons[b];
    const BoundingBox box = bounding_box(v, tol);
    std::size_t found = npos;
    for (std::size_t o = 0; o < g.openings.size() && found == npos; ++o)
    {
      if (!boxes_overlap(g.openings[o], box))
        continue;
      for (std::size_t e = 0; e < v.size() && found == npos; ++e)
      {
        const Point& p = v[e];
        const Point& q = v[(e + 1) % v.size()];
        for (const auto& [from, to] : g.openings[o].segments)
          if (std::min({distance_to_segment(p, from, to), distance_to_segment(q, from, to),
                        distance_to_segment(from, p, q), distance_to_segment(to, p, q)}) <= tol)
            found = o;
      }
    }
    if (found != npos)
    {
      g.blocks.push_back(b);
      g.opening_of.push_back(found);
    }
  }
  return g;
}

double distance_to_boundary(const OpeningOutline& opening, const Point& p)
{
  double distance = std::numeric_limits<double>::infinity();
  for (const auto& [from, to] : opening.segments)
    distance = std::min(distance, distance_to_segment(p, from, to));
  return distance;
}

bool left_its_place(const std::vector<Point>& vertices, const Vector2& moved)
{
  if (vertices.empty() || moved.squaredNorm() == 0.0)
    return false;
  const Vector2 u = moved.normalized();
  double lowest = std::numeric_limits<double>::infinity(), highest = -lowest;
  for (const Point& x : vertices)
  {
    lowest = std::min(lowest, x.dot(u));
    highest = std::max(highest, x.dot(u));
  }
  return moved.norm() >= highest - lowest;
}

FallVerdict keyblock_fell(const KeyblockMotion& motion, const Vector2& down, double threshold,
                          double gravity)
{
  if (motion.displacement.dot(down) > threshold)
    return FallVerdict::dropped;
  if (!motion.held && motion.velocity.dot(down) > std::sqrt(2.0 * gravity * threshold))
    return FallVerdict::falling;
  if (!motion.held && motion.relative_displacement.norm() > threshold)
    return FallVerdict::thrown_out;
  return FallVerdict::no;
}

} // namespace ddafem::dda
