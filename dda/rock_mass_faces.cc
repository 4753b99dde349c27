// The faces of the rock mass arrangement: which are blocks (a walk from the unbounded face), the
// boundary loops of a face without its dangling traces, and the vertical cuts that leave no
// block around an island (dda/rock_mass_arrangement.h).
#include "dda/rock_mass_arrangement.h"

#include "dda/exact_area.h"

#include <algorithm>
#include <map>
#include <optional>
#include <utility>

namespace ddafem::dda::rock_mass_internal
{
namespace
{
/// Marks every face as a block or not by a walk over the faces from the unbounded one: crossing
/// an edge of the region's boundary toggles `in_region`, crossing an opening's boundary toggles
/// that opening's flag. Exact and independent of how the faces are shaped.
void classify_faces(Arrangement& arrangement, std::size_t n_openings)
{
  std::size_t index = 0;
  for (auto f = arrangement.faces_begin(); f != arrangement.faces_end(); ++f)
  {
    f->data() = FaceInfo{};
    f->data().index = index++;
  }
  Face start = arrangement.unbounded_face();
  start->data().visited = true;
  start->data().in_opening.assign(n_openings, false);
  std::vector<Face> stack{start};
  while (!stack.empty())
  {
    const Face f = stack.back();
    stack.pop_back();
    for_each_halfedge(f,
                      [&](Halfedge h)
                      {
                        const Face g = h->twin()->face();
                        if (g->data().visited)
                          return;
                        FaceInfo info = f->data();
                        info.index = g->data().index;
                        for (const CurveSource& s : h->curve().data())
                          if (s.kind == CurveSource::Kind::region)
                            info.in_region = !info.in_region;
                          else if (s.kind == CurveSource::Kind::opening)
                            info.in_opening[s.index] = !info.in_opening[s.index];
                        info.block = info.in_region &&
                                     std::none_of(info.in_opening.begin(), info.in_opening.end(),
                                                  [](bool b) { return b; });
                        g->data() = info;
                        stack.push_back(g);
                      });
  }
}

/// Area of the region a boundary encloses [m^2], exact: positive for an outer boundary, negative
/// for an inner one; dangling edges, walked both ways, add nothing.
Kernel::FT ccb_area(Ccb first)
{
  std::vector<ExactPoint> points;
  Ccb h = first;
  do
    points.push_back(h->source()->point());
  while (++h != first);
  return polygon_area(points.begin(), points.end(), Kernel());
}

/// Whether h (with f on its left) separates f from another face. Dangling joint traces
/// (antennae) and traces that connect f's boundary to an island inside f (bridges) have f on
/// both sides.
bool separates(Halfedge h, Face f)
{
  return h->twin()->face() != f;
}

/// A closed chain of halfedges split into simple loops where it passes a vertex again.
std::vector<std::vector<Halfedge>> simple_loops(const std::vector<Halfedge>& cycle)
{
  std::vector<std::vector<Halfedge>> loops;
  std::vector<Halfedge> path;
  std::map<Arrangement::Vertex_handle, std::size_t> position; // in path, by source vertex
  for (const Halfedge h : cycle)
  {
    const auto again = position.find(h->source());
    if (again != position.end())
    {
      const std::size_t start = again->second;
      loops.emplace_back(path.begin() + static_cast<std::ptrdiff_t>(start), path.end());
      for (std::size_t k = start; k < path.size(); ++k)
        position.erase(path[k]->source());
      path.resize(start);
    }
    position[h->source()] = path.size();
    path.push_back(h);
  }
  loops.push_back(path);
  return loops;
}

Kernel::FT loop_area(const std::vector<Halfedge>& loop)
{
  std::vector<ExactPoint> points;
  for (const Halfedge h : loop)
    points.push_back(h->source()->point());
  return polygon_area(points.begin(), points.end(), Kernel());
}

/// The point nearest to v where a vertical ray from v (up: dy = +1, down: dy = -1) meets an edge
/// between f and another face. v lies on f's boundary and f is bounded, so there is one.
ExactPoint first_hit(Face f, const ExactPoint& v, int dy)
{
  const Kernel::Ray_2 ray(v, Kernel::Direction_2(0, dy));
  std::optional<ExactPoint> best;
  const auto consider = [&](const ExactPoint& p)
  {
    if (p != v && (!best || CGAL::compare_distance_to_point(v, p, *best) == CGAL::SMALLER))
      best = p;
  };
  for_each_halfedge(f,
                    [&](Halfedge h)
                    {
                      if (!separates(h, f))
                        return;
                      const Segment edge(h->source()->point(), h->target()->point());
                      const auto hit = CGAL::intersection(ray, edge);
                      if (!hit)
                        return;
                      if (const ExactPoint* p = boost::get<ExactPoint>(&*hit))
                        consider(*p);
                      else if (const Segment* s = boost::get<Segment>(&*hit))
                      {
                        consider(s->source());
                        consider(s->target());
                      }
                    });
  return *best;
}

/// A block must be a simple polygon, but a block face may enclose islands: an opening no joint
/// reaches (or only a trace that ends on it), blocks inside a closed ring of joints, or a block
/// that the face surrounds but touches at one vertex. They show as clockwise boundary loops of
/// the face. Each island gets two vertical cuts, up from its top vertex and down from its
/// bottom vertex to the nearest edge of the face, which split the face in two; no cut starts
/// where the island touches another loop (it is attached there already, and the vertical from
/// there may leave the face). Returns the number of cuts inserted (0: every block face is
/// simple); the faces must be classified again after a cut.
std::size_t cut_islands(Arrangement& arrangement)
{
  std::vector<Traits::Curve_2> cuts;
  const CurveSource source{CurveSource::Kind::island_cut, 0};
  for (auto f = arrangement.faces_begin(); f != arrangement.faces_end(); ++f)
  {
    if (!f->data().block)
      continue;
    const std::vector<std::vector<Halfedge>> loops = boundary_loops(f);
    std::map<Arrangement::Vertex_handle, int> n_visits;
    for (const std::vector<Halfedge>& loop : loops)
      for (const Halfedge h : loop)
        ++n_visits[h->source()];
    for (const std::vector<Halfedge>& loop : loops)
    {
      if (loop_area(loop) > 0)
        continue; // the outer loop
      // Top: largest (y, x); bottom: smallest (y, x).
      const auto above = [](const ExactPoint& a, const ExactPoint& b)
      { return CGAL::compare_yx(a, b) == CGAL::LARGER; };
      Arrangement::Vertex_handle top = loop.front()->source(), bottom = top;
      for (const Halfedge h : loop)
      {
        if (above(h->source()->point(), top->point()))
          top = h->source();
        if (above(bottom->point(), h->source()->point()))
          bottom = h->source();
      }
      if (n_visits[top] == 1)
        cuts.emplace_back(Segment(top->point(), first_hit(f, top->point(), +1)), source);
      if (n_visits[bottom] == 1)
        cuts.emplace_back(Segment(bottom->point(), first_hit(f, bottom->point(), -1)), source);
    }
  }
  if (!cuts.empty())
    CGAL::insert(arrangement, cuts.begin(), cuts.end());
  return cuts.size();
}

} // namespace

/// Area of a face [m^2], exact: its outer boundary minus what its inner boundaries enclose.
Kernel::FT face_area(Face f)
{
  Kernel::FT area = f->has_outer_ccb() ? ccb_area(f->outer_ccb()) : Kernel::FT(0);
  for (auto inner = f->inner_ccbs_begin(); inner != f->inner_ccbs_end(); ++inner)
    area += ccb_area(*inner);
  return area;
}

/// The halfedges on f's boundaries that separate it from other faces.
std::vector<Halfedge> separating_halfedges(Face f)
{
  std::vector<Halfedge> halfedges;
  for_each_halfedge(f,
                    [&](Halfedge h)
                    {
                      if (separates(h, f))
                        halfedges.push_back(h);
                    });
  return halfedges;
}

/// The boundary of f as simple loops of separating halfedges: the outer loop (anticlockwise)
/// and a loop around each island (clockwise). From each halfedge the boundary turns, around
/// its target vertex, to the next halfedge that separates f from another face, so antennae and
/// bridges are passed over; where f touches itself at a vertex the loops are split there.
std::vector<std::vector<Halfedge>> boundary_loops(Face f)
{
  const std::vector<Halfedge> halfedges = separating_halfedges(f);
  std::map<Halfedge, bool> used;
  for (const Halfedge h : halfedges)
    used[h] = false;
  std::vector<std::vector<Halfedge>> loops;
  for (const Halfedge start : halfedges)
  {
    if (used[start])
      continue;
    std::vector<Halfedge> cycle;
    for (Halfedge h = start; !used[h];)
    {
      used[h] = true;
      cycle.push_back(h);
      h = h->next();
      while (!separates(h, f))
        h = h->twin()->next();
    }
    for (std::vector<Halfedge>& loop : simple_loops(cycle))
      loops.push_back(std::move(loop));
  }
  return loops;
}

/// Classifies the faces and cuts islands until every block face is simple; returns the cuts.
std::size_t settle(Arrangement& arrangement, std::size_t n_openings)
{
  std::size_t n_cuts = 0;
  classify_faces(arrangement, n_openings);
  while (const std::size_t n = cut_islands(arrangement))
  {
    n_cuts += n;
    classify_faces(arrangement, n_openings);
  }
  return n_cuts;
}

} // namespace ddafem::dda::rock_mass_internal
