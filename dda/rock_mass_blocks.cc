// The blocks of the rock mass: a block face of the arrangement as a RockMassBlock, its vertices
// without the straight ones, its edges' joints, the joints and boundaries it touches
// (dda/rock_mass_arrangement.h).
#include "common/input_error.h"
#include "dda/rock_mass_arrangement.h"

#include "dda/exact_area.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

namespace ddafem::dda::rock_mass_internal
{
namespace
{
/// Drops vertices between two collinear edges (where a neighbour's vertex or a dangling trace
/// met the edge): exactly collinear, or within `tolerance` [m] of the line through the vertices
/// on either side and between them. The tolerance is of the order of rounding: a vertex that
/// tidy() moved by a rounding error (onto a corner of an opening that a joint missed by 1e-16
/// m) bends the joints through it by as much, and the vertex is straight to rounding in the
/// blocks on the outer side of the bend (their neighbours keep it, as where a joint ends on
/// an edge).
std::vector<ExactPoint> without_collinear_vertices(std::vector<ExactPoint> points, double tolerance)
{
  const auto straight = [&](const ExactPoint& a, const ExactPoint& v, const ExactPoint& b)
  {
    if (CGAL::collinear(a, v, b))
      return true;
    const Point pa = approximate(a), pv = approximate(v), pb = approximate(b);
    const Vector2 chord = pb - pa, leg = pv - pa;
    return leg.dot(chord) > 0.0 && (pb - pv).dot(chord) > 0.0 &&
           std::abs(chord.x() * leg.y() - chord.y() * leg.x()) <= tolerance * chord.norm();
  };
  for (bool changed = true; changed && points.size() > 3;)
  {
    changed = false;
    for (std::size_t i = 0; i < points.size() && points.size() > 3;)
    {
      const std::size_t n = points.size();
      if (straight(points[(i + n - 1) % n], points[i], points[(i + 1) % n]))
      {
        points.erase(points.begin() + static_cast<std::ptrdiff_t>(i));
        changed = true;
      }
      else
        ++i;
    }
  }
  return points;
}

/// The joint a piece of a block's boundary lies on (explicit joints before sets, lower index
/// first, where joints overlap); none on the region's or an opening's boundary.
EdgeJoint piece_joint(Halfedge h)
{
  if (on_boundary(h))
    return {};
  // (0 for an explicit joint, 1 for a set; index): the smallest wins.
  std::optional<std::pair<int, std::size_t>> best;
  for (const CurveSource& s : h->curve().data())
    if (s.kind == CurveSource::Kind::explicit_joint || s.kind == CurveSource::Kind::joint_set)
    {
      const std::pair<int, std::size_t> rank(s.kind == CurveSource::Kind::joint_set, s.index);
      best = best ? std::min(*best, rank) : rank;
    }
  if (!best)
    return {};
  return {best->first == 0 ? EdgeJoint::Kind::explicit_joint : EdgeJoint::Kind::joint_set,
          best->second};
}

/// The joints of a block's edges (RockMassBlock::edge_joints): `boundary` is its loop of
/// halfedges, `kept` its vertices after the straight ones were dropped, in the loop's order.
std::vector<EdgeJoint> edge_joints(const std::vector<Halfedge>& boundary,
                                   const std::vector<ExactPoint>& kept)
{
  // The length [m] of each edge's pieces on each joint.
  std::vector<std::vector<std::pair<EdgeJoint, double>>> pieces(kept.size());
  const auto first = std::find_if(boundary.begin(), boundary.end(),
                                  [&](Halfedge h) { return h->source()->point() == kept.front(); });
  std::size_t edge = 0;
  for (std::size_t i = 0; i < boundary.size(); ++i)
  {
    const Halfedge h =
        boundary[(static_cast<std::size_t>(first - boundary.begin()) + i) % boundary.size()];
    if (edge + 1 < kept.size() && h->source()->point() == kept[edge + 1])
      ++edge;
    const EdgeJoint joint = piece_joint(h);
    auto it = std::find_if(pieces[edge].begin(), pieces[edge].end(),
                           [&](const auto& p) { return p.first == joint; });
    if (it == pieces[edge].end())
      it = pieces[edge].insert(it, {joint, 0.0});
    it->second += length(h);
  }
  std::vector<EdgeJoint> joints;
  for (const auto& on_joints : pieces)
    joints.push_back(std::max_element(on_joints.begin(), on_joints.end(),
                                      [](const auto& a, const auto& b)
                                      { return a.second < b.second; })
                         ->first);
  return joints;
}

} // namespace

/// The block of a block face whose boundary is one simple loop (as settle() leaves them).
RockMassBlock make_block(Face f, double straight_tolerance)
{
  const std::vector<std::vector<Halfedge>> loops = boundary_loops(f);
  if (loops.size() != 1)
  {
    const Point near = rounded(loops.front().front()->source()->point());
    throw InputError("a block near " + format_point(near.x(), near.y()) +
                     " m is not a simple polygon: it touches itself or an island at vertices "
                     "that no vertical cut can separate; expected openings and joints that meet "
                     "the rest of the boundary along edges or not at all");
  }
  const std::vector<Halfedge>& boundary = loops.front();
  std::vector<ExactPoint> points;
  for (const Halfedge h : boundary)
    points.push_back(h->source()->point());

  RockMassBlock block;
  for (const Halfedge h : boundary)
    for (const CurveSource& s : h->curve().data())
      switch (s.kind)
      {
      case CurveSource::Kind::region:
        block.region_boundary = true;
        break;
      case CurveSource::Kind::opening:
        block.openings.push_back(s.index);
        break;
      case CurveSource::Kind::joint_set:
        block.joint_sets.push_back(s.index);
        break;
      case CurveSource::Kind::explicit_joint:
        block.explicit_joint = true;
        break;
      case CurveSource::Kind::island_cut:
        break;
      }
  for (std::vector<std::size_t>* list : {&block.openings, &block.joint_sets})
  {
    std::sort(list->begin(), list->end());
    list->erase(std::unique(list->begin(), list->end()), list->end());
  }

  points = without_collinear_vertices(std::move(points), straight_tolerance);
  // Start at the lowest vertex (smallest y, then x).
  std::rotate(points.begin(),
              std::min_element(points.begin(), points.end(),
                               [](const ExactPoint& a, const ExactPoint& b)
                               { return CGAL::compare_yx(a, b) == CGAL::SMALLER; }),
              points.end());
  block.edge_joints = edge_joints(boundary, points);
  block.area = CGAL::to_double(polygon_area(points.begin(), points.end(), Kernel()));
  for (const ExactPoint& p : points)
    block.vertices.push_back(rounded(p));
  return block;
}

} // namespace ddafem::dda::rock_mass_internal
