#include "dda/rock_mass.h"

#include "common/input_error.h"
#include "dda/geometry.h"

#include <CGAL/Arr_consolidated_curve_data_traits_2.h>
#include <CGAL/Arr_extended_dcel.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <utility>

namespace ddafem::dda
{
namespace
{
using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using ExactPoint = Kernel::Point_2;
using Segment = Kernel::Segment_2;

/// What an arrangement edge lies on. Where curves overlap (a joint along the region's boundary,
/// an opening touching a joint), the edge carries all of them.
struct CurveSource
{
  enum class Kind
  {
    region,
    opening,
    joint_set,
    explicit_joint,
    island_cut ///< added so that no block encloses an island (see cut_islands)
  };
  Kind kind = Kind::region;
  std::size_t index = 0; ///< of the opening, joint set or explicit joint

  bool operator==(const CurveSource& other) const
  {
    return kind == other.kind && index == other.index;
  }
};

/// Classification of a face by the walk in classify_faces.
struct FaceInfo
{
  bool visited = false;
  bool in_region = false;
  std::vector<bool> in_opening; ///< one flag per opening
  bool block = false;           ///< in the region and in no opening
  std::size_t index = 0;        ///< position in the arrangement's face list (tie breaks)
};

using SegmentTraits = CGAL::Arr_segment_traits_2<Kernel>;
using Traits = CGAL::Arr_consolidated_curve_data_traits_2<SegmentTraits, CurveSource>;
using Arrangement = CGAL::Arrangement_2<Traits, CGAL::Arr_face_extended_dcel<Traits, FaceInfo>>;
using Face = Arrangement::Face_handle;
using Halfedge = Arrangement::Halfedge_handle;
using Ccb = Arrangement::Ccb_halfedge_circulator;

std::string format_number(double v)
{
  std::ostringstream s;
  s << v;
  return s.str();
}

std::string format_point(const Point& p)
{
  return "(" + format_number(p.x()) + ", " + format_number(p.y()) + ")";
}

ExactPoint exact_point(const Point& p)
{
  return ExactPoint(p.x(), p.y());
}

/// The point in double (within an ulp); blocks that share a vertex get the same one.
Point rounded(const ExactPoint& p)
{
  const auto& e = CGAL::exact(p);
  return Point(CGAL::to_double(e.x()), CGAL::to_double(e.y()));
}

/// The point in double from its interval approximation, without computing it exactly: for
/// tolerances far above rounding.
Point approximate(const ExactPoint& p)
{
  return Point(CGAL::to_double(p.x()), CGAL::to_double(p.y()));
}

/// Unit vector at `degrees` from +x, exact for multiples of 90 degrees (so that sets at 0 and
/// 90 degrees give exactly rectangular blocks).
Vector2 unit_vector(double degrees)
{
  const double quarter_turns = degrees / 90.0;
  if (quarter_turns == std::round(quarter_turns))
  {
    const long q = ((static_cast<long>(quarter_turns) % 4) + 4) % 4;
    const Vector2 axes[] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
    return axes[q];
  }
  const double radians = degrees * M_PI / 180.0;
  return Vector2(std::cos(radians), std::sin(radians));
}

// ---- Random perturbations ----------------------------------------------------------------------

/// Draws of xi for one joint set and direction. The engine and std::seed_seq are specified by
/// the standard, the std:: distributions are not (they differ between standard libraries), so
/// the draws are made here: a seed gives the same joints with any standard library (up to the
/// last bit of std::log and std::cos for normal draws).
class Draws
{
public:
  Draws(std::uint64_t seed, std::size_t set, unsigned stream)
  {
    std::seed_seq sequence{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                           static_cast<std::uint32_t>(set), stream};
    engine.seed(sequence);
  }

  double xi(Distribution distribution)
  {
    if (distribution == Distribution::uniform)
      return 2.0 * unit() - 1.0;
    // Box-Muller: u1 in (0, 1] keeps the logarithm finite.
    const double u1 = 1.0 - unit();
    const double u2 = unit();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  }

private:
  double unit() { return static_cast<double>(engine() >> 11) * 0x1.0p-53; } ///< [0, 1)
  std::mt19937_64 engine;
};

// ---- Joint traces ------------------------------------------------------------------------------

/// One joint line of a set: its normal position c [m] (n.x = c) and the shift of its trace
/// pattern along the line [m].
struct JointLine
{
  double c = 0.0;
  double phase = 0.0;
};

/// The lines of a set that meet the normal interval [n_lo, n_hi] [m]. Lines are generated from
/// line 0 outwards, one random stream per direction, each line drawing its gap to the next line
/// and its phase: enlarging the region adds lines but keeps the ones it had.
std::vector<JointLine> joint_lines(const JointSet& set, std::size_t set_index, std::uint64_t seed,
                                   double n_lo, double n_hi)
{
  const double walk = std::max(std::abs(n_hi - set.offset), std::abs(set.offset - n_lo));
  if (walk / set.spacing > 1e7)
    throw InputError("joint set " + std::to_string(set_index) + ": line 0 (offset " +
                     format_number(set.offset) + " m) is " + format_number(walk / set.spacing) +
                     " spacings from the far side of the region: expected an offset within 10^7 "
                     "spacings of the region");
  const JointPerturbation& p = set.perturbation;
  const double period = set.persistent() ? 0.0 : set.trace_length + set.bridge;
  std::vector<JointLine> lines;
  for (const int direction : {+1, -1})
  {
    Draws draws(seed, set_index, direction > 0 ? 0 : 1);
    double c = set.offset;
    long k = 0;
    const auto gap = [&]
    {
      double xi = draws.xi(p.distribution);
      while (1.0 + p.spacing * xi < 0.1)
        xi = draws.xi(p.distribution);
      return set.spacing * (1.0 + p.spacing * xi);
    };
    if (direction < 0)
    {
      c -= gap();
      k = -1;
    }
    while (direction > 0 ? c <= n_hi : c >= n_lo)
    {
      const double stagger = (k % 2 == 0) ? 0.0 : 0.5 * period;
      const double phase = stagger + p.position * period * draws.xi(p.distribution);
      if (c >= n_lo && c <= n_hi)
        lines.push_back({c, phase});
      c += direction * gap();
      k += direction;
    }
  }
  return lines;
}

/// Appends the segment from a to b clipped to the box (nothing if they do not cross it).
void append_clipped(const ExactPoint& a, const ExactPoint& b, const Kernel::Iso_rectangle_2& box,
                    CurveSource source, std::vector<Traits::Curve_2>& curves)
{
  const auto clipped = CGAL::intersection(Segment(a, b), box);
  if (!clipped)
    return;
  // CGAL 5 returns a boost::variant: a point where the segment only touches the box.
  if (const Segment* s = boost::get<Segment>(&*clipped))
    if (!s->is_degenerate())
      curves.emplace_back(*s, source);
}

/// Every trace of every joint set and every explicit joint, clipped to the region's bounding
/// box. (Pieces inside the box but outside a polygonal region bound only faces outside it.)
/// The points of a joint line are exact, x = c n + t d in rationals: every trace of the line
/// lies exactly on it (n.d = 0 holds exactly for n = (-d_y, d_x)), and lines meant to pass
/// through one point (offsets 0 through the origin, a corner of the region) do.
std::vector<Traits::Curve_2> joint_curves(const RockMassDescription& d)
{
  Point lower = d.region.front(), upper = d.region.front();
  for (const Point& v : d.region)
  {
    lower = lower.cwiseMin(v);
    upper = upper.cwiseMax(v);
  }
  const Kernel::Iso_rectangle_2 box(exact_point(lower), exact_point(upper));
  const Point corners[] = {lower, {upper.x(), lower.y()}, upper, {lower.x(), upper.y()}};
  const double margin = (upper - lower).norm(); // makes persistent traces reach past the box

  std::vector<Traits::Curve_2> curves;
  for (std::size_t s = 0; s < d.joint_sets.size(); ++s)
  {
    const JointSet& set = d.joint_sets[s];
    const Vector2 along = unit_vector(set.dip);
    const Vector2 normal(-along.y(), along.x());
    double n_lo = corners[0].dot(normal), n_hi = n_lo;
    double t_lo = corners[0].dot(along), t_hi = t_lo;
    for (const Point& corner : corners)
    {
      n_lo = std::min(n_lo, corner.dot(normal));
      n_hi = std::max(n_hi, corner.dot(normal));
      t_lo = std::min(t_lo, corner.dot(along));
      t_hi = std::max(t_hi, corner.dot(along));
    }
    const double n_traces =
        (n_hi - n_lo) / set.spacing *
        (set.persistent() ? 1.0 : (t_hi - t_lo) / (set.trace_length + set.bridge) + 1.0);
    if (n_traces > 1e6)
      throw InputError("joint set " + std::to_string(s) + ": about " + format_number(n_traces) +
                       " traces cross the region: expected at most 10^6 (is the spacing, " +
                       format_number(set.spacing) +
                       " m, or the period trace_length + bridge too small for the region?)");
    const CurveSource source{CurveSource::Kind::joint_set, s};
    for (const JointLine& line : joint_lines(set, s, d.seed, n_lo, n_hi))
    {
      const auto at = [&](double t)
      {
        const Kernel::FT c = line.c, tt = t;
        return ExactPoint(c * normal.x() + tt * along.x(), c * normal.y() + tt * along.y());
      };
      if (set.persistent())
      {
        append_clipped(at(t_lo - margin), at(t_hi + margin), box, source, curves);
        continue;
      }
      const double period = set.trace_length + set.bridge;
      // Traces j whose span [phase + j P, phase + j P + L] meets [t_lo, t_hi].
      const double j_first = std::floor((t_lo - line.phase - set.trace_length) / period);
      for (double j = j_first; line.phase + j * period <= t_hi; ++j)
      {
        const double t0 = line.phase + j * period;
        append_clipped(at(t0), at(t0 + set.trace_length), box, source, curves);
      }
    }
  }
  for (std::size_t i = 0; i < d.joints.size(); ++i)
    append_clipped(exact_point(d.joints[i].from), exact_point(d.joints[i].to), box,
                   {CurveSource::Kind::explicit_joint, i}, curves);
  return curves;
}

/// The closed polygon's edges as curves.
void append_polygon(const std::vector<Point>& polygon, CurveSource source,
                    std::vector<Traits::Curve_2>& curves)
{
  for (std::size_t i = 0; i < polygon.size(); ++i)
    curves.emplace_back(
        Segment(exact_point(polygon[i]), exact_point(polygon[(i + 1) % polygon.size()])), source);
}

// ---- Faces -------------------------------------------------------------------------------------

/// Calls visit(h) for every halfedge on the boundary of f (outer and inner boundaries), with
/// f on its left.
template <typename Visit>
void for_each_halfedge(Face f, Visit&& visit)
{
  const auto visit_ccb = [&](Ccb first)
  {
    Ccb h = first;
    do
      visit(Halfedge(h));
    while (++h != first);
  };
  if (f->has_outer_ccb())
    visit_ccb(f->outer_ccb());
  for (auto inner = f->inner_ccbs_begin(); inner != f->inner_ccbs_end(); ++inner)
    visit_ccb(*inner);
}

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
  return CGAL::polygon_area_2(points.begin(), points.end(), Kernel());
}

/// Area of a face [m^2], exact: its outer boundary minus what its inner boundaries enclose.
Kernel::FT face_area(Face f)
{
  Kernel::FT area = f->has_outer_ccb() ? ccb_area(f->outer_ccb()) : Kernel::FT(0);
  for (auto inner = f->inner_ccbs_begin(); inner != f->inner_ccbs_end(); ++inner)
    area += ccb_area(*inner);
  return area;
}

/// Whether h (with f on its left) separates f from another face. Dangling joint traces
/// (antennae) and traces that connect f's boundary to an island inside f (bridges) have f on
/// both sides.
bool separates(Halfedge h, Face f)
{
  return h->twin()->face() != f;
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

Kernel::FT loop_area(const std::vector<Halfedge>& loop)
{
  std::vector<ExactPoint> points;
  for (const Halfedge h : loop)
    points.push_back(h->source()->point());
  return CGAL::polygon_area_2(points.begin(), points.end(), Kernel());
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

// ---- Slivers -----------------------------------------------------------------------------------

/// The size criteria of a sliver.
struct SliverCriteria
{
  double min_area = 0.0;             ///< [m^2]
  double min_inscribed_radius = 0.0; ///< [m]

  bool is_sliver(double area, double perimeter) const
  {
    return area < min_area || 2.0 * area / perimeter < min_inscribed_radius;
  }
};

double length(Halfedge h)
{
  return std::sqrt(
      CGAL::to_double(CGAL::squared_distance(h->source()->point(), h->target()->point())));
}

/// One pass of merging: each sliver (smallest first) whose neighbouring block with the longest
/// shared boundary was not involved in a merge of this pass is joined to it by removing the
/// edges they share. Returns the number of merges.
std::size_t merge_pass(Arrangement& arrangement, const SliverCriteria& criteria)
{
  struct Candidate
  {
    Face face;
    std::size_t index = 0;
    double area = 0.0;
    std::size_t neighbour = 0; ///< face index of the block sharing the longest boundary
  };
  std::vector<Face> faces;
  std::vector<Candidate> slivers;
  for (auto f = arrangement.faces_begin(); f != arrangement.faces_end(); ++f)
  {
    faces.push_back(f);
    if (!f->data().block)
      continue;
    double perimeter = 0.0;
    std::vector<std::pair<std::size_t, double>> shared; // (face index, length [m])
    for (const Halfedge h : separating_halfedges(f))
    {
      const double l = length(h);
      perimeter += l;
      const FaceInfo& other = h->twin()->face()->data();
      if (!other.block)
        continue;
      const auto it = std::find_if(shared.begin(), shared.end(),
                                   [&](const auto& s) { return s.first == other.index; });
      if (it == shared.end())
        shared.emplace_back(other.index, l);
      else
        it->second += l;
    }
    const double area = CGAL::to_double(face_area(f));
    if (shared.empty() || !criteria.is_sliver(area, perimeter))
      continue;
    // Longest shared boundary; ties to the lower face index (deterministic).
    const auto best = std::min_element(shared.begin(), shared.end(),
                                       [](const auto& a, const auto& b) {
                                         return a.second > b.second ||
                                                (a.second == b.second && a.first < b.first);
                                       });
    slivers.push_back({f, f->data().index, area, best->first});
  }
  std::sort(slivers.begin(), slivers.end(),
            [](const Candidate& a, const Candidate& b)
            { return a.area < b.area || (a.area == b.area && a.index < b.index); });

  // Faces deleted or grown by a merge are not looked at again in this pass.
  std::vector<bool> touched(faces.size(), false);
  std::size_t n_merged = 0;
  for (const Candidate& s : slivers)
  {
    if (touched[s.index] || touched[s.neighbour])
      continue;
    touched[s.index] = touched[s.neighbour] = true;
    const Face neighbour = faces[s.neighbour];
    std::vector<Halfedge> shared;
    for (const Halfedge h : separating_halfedges(s.face))
      if (h->twin()->face() == neighbour)
        shared.push_back(h);
    for (const Halfedge h : shared)
      arrangement.remove_edge(h);
    ++n_merged;
  }
  return n_merged;
}

// ---- Short edges and straight vertices ---------------------------------------------------------

/// The thresholds of tidy().
struct EdgeCriteria
{
  double min_length = 0.0;     ///< edges shorter than this are collapsed [m]
  double straight_angle = 0.0; ///< vertices within this of 180 degrees are straight [rad]
};

/// What one tidy() did.
struct TidyCounts
{
  std::size_t n_collapsed = 0; ///< short edges collapsed
  std::size_t n_straight = 0;  ///< straight vertices removed
  bool changed() const { return n_collapsed + n_straight > 0; }
};

/// Whether an edge lies on the region's or an opening's boundary: those stay where they are.
bool on_boundary(Halfedge h)
{
  return std::any_of(h->curve().data().begin(), h->curve().data().end(),
                     [](const CurveSource& s) {
                       return s.kind == CurveSource::Kind::region ||
                              s.kind == CurveSource::Kind::opening;
                     });
}

/// Where a vertex may move so that the region's and the openings' boundaries keep their shape:
/// anywhere (free), along the one boundary line it lies on (line through p and q), or nowhere
/// (point p: a corner of the region or an opening, or where two boundaries cross).
struct Pin
{
  enum class Kind
  {
    free,
    line,
    point
  };
  Kind kind = Kind::free;
  ExactPoint p, q;

  bool holds(const ExactPoint& x) const { return CGAL::collinear(p, q, x); }
};

/// The pin of a vertex, from the boundary edges at it.
Pin pin_of(Arrangement::Vertex_handle v)
{
  Pin pin;
  if (v->is_isolated())
    return pin;
  auto h = v->incident_halfedges();
  const auto first = h;
  do
  {
    if (!on_boundary(h))
      continue;
    const ExactPoint& other = h->source()->point();
    if (pin.kind == Pin::Kind::free)
      pin = {Pin::Kind::line, v->point(), other};
    else if (pin.kind == Pin::Kind::line && !pin.holds(other))
      pin = {Pin::Kind::point, v->point(), v->point()};
  } while (++h != first);
  return pin;
}

/// The pin of a set of vertices merged into one: the stricter of the two, or none if they
/// contradict (two corners, two different lines, a corner off the other's line).
std::optional<Pin> combine(const Pin& a, const Pin& b)
{
  if (a.kind == Pin::Kind::free)
    return b;
  if (b.kind == Pin::Kind::free)
    return a;
  if (a.kind == Pin::Kind::point && b.kind == Pin::Kind::point)
    return std::nullopt;
  if (a.kind == Pin::Kind::point)
    return b.holds(a.p) ? std::optional<Pin>(a) : std::nullopt;
  if (b.kind == Pin::Kind::point)
    return a.holds(b.p) ? std::optional<Pin>(b) : std::nullopt;
  return a.holds(b.p) && a.holds(b.q) ? std::optional<Pin>(a) : std::nullopt;
}

/// An edge of the arrangement, by the indices of its vertices.
struct GraphEdge
{
  std::size_t a = 0, b = 0;
  Halfedge h;
  bool at_block = false; ///< a block on one side
};

/// An edge after the moves: the arrangement's edge it still is (if any) and what it lies on.
struct MovedEdge
{
  std::optional<Halfedge> unchanged;
  std::vector<CurveSource> sources;
};

void add_sources(std::vector<CurveSource>& to, const std::vector<CurveSource>& from)
{
  for (const CurveSource& s : from)
    if (std::find(to.begin(), to.end(), s) == to.end())
      to.push_back(s);
}

std::vector<CurveSource> sources(Halfedge h)
{
  return {h->curve().data().begin(), h->curve().data().end()};
}

/// Removes the edges with one face on both sides that lie on no boundary: dangling traces, and
/// traces that join an island to the face around it. They bound no block.
void remove_dangling_edges(Arrangement& arrangement)
{
  std::vector<Halfedge> dangling;
  for (auto e = arrangement.edges_begin(); e != arrangement.edges_end(); ++e)
    if (e->face() == e->twin()->face() && !on_boundary(e))
      dangling.push_back(e);
  for (const Halfedge h : dangling)
    arrangement.remove_edge(h);
}

/// Moves vertices of the arrangement so that no block edge is shorter than min_length, and
/// removes the straight vertices where only two faces meet. A vertex is shared by every face
/// around it, so each change is the same for all of them: no gap, no overlap. Only the edges
/// that change are taken out and put in again, exactly: a crossing that a move makes becomes a
/// vertex, a face folded over becomes a small face that the next call or the sliver merge
/// removes. The faces must be classified; they must be again if anything changed.
///
/// 1. Dangling edges are removed (they bound no block).
/// 2. Each edge shorter than min_length with a block on one side, shortest first, joins its two
///    vertices' clusters (union-find) unless their pins contradict (see Pin). Every vertex of a
///    cluster moves to the member that satisfies the cluster's pin and is nearest to all the
///    others. The region's and the openings' boundaries keep their shape: their corners stay,
///    and vertices on them move along them.
/// 3. A free vertex with two edges whose angle is within straight_angle of 180 degrees is
///    removed (both faces agree: it is straight on both sides); its two edges become one.
TidyCounts tidy(Arrangement& arrangement, const EdgeCriteria& criteria)
{
  remove_dangling_edges(arrangement);

  using Vertex = Arrangement::Vertex_handle;
  std::map<Vertex, std::size_t> index;
  std::vector<ExactPoint> points;
  std::vector<Vertex> vertices;
  std::vector<Pin> pins; // exact for the ends of short edges; else free or not (kind point)
  for (auto v = arrangement.vertices_begin(); v != arrangement.vertices_end(); ++v)
  {
    index[v] = points.size();
    vertices.push_back(v);
    points.push_back(v->point());
    Pin pin;
    if (!v->is_isolated())
    {
      auto h = v->incident_halfedges();
      const auto first = h;
      do
        if (on_boundary(h))
          pin.kind = Pin::Kind::point;
      while (++h != first);
    }
    pins.push_back(pin);
  }
  std::vector<GraphEdge> edges;
  for (auto e = arrangement.edges_begin(); e != arrangement.edges_end(); ++e)
  {
    const Face f = e->face(), g = e->twin()->face();
    edges.push_back({index[e->source()], index[e->target()], e,
                     f != g && (f->data().block || g->data().block)});
  }

  // 2. Clusters of the short edges' vertices.
  std::vector<Point> near; // the vertices in double
  for (const ExactPoint& p : points)
    near.push_back(approximate(p));
  const double min_squared = criteria.min_length * criteria.min_length;
  const auto squared_length = [&](std::size_t a, std::size_t b)
  { return (near[a] - near[b]).squaredNorm(); };
  std::vector<std::pair<double, std::size_t>> short_edges; // (squared length, edge)
  for (std::size_t e = 0; e < edges.size(); ++e)
  {
    const double l2 = squared_length(edges[e].a, edges[e].b);
    if (edges[e].at_block && l2 < min_squared)
      short_edges.emplace_back(l2, e);
  }
  std::sort(short_edges.begin(), short_edges.end());
  std::vector<bool> pinned_exactly(points.size(), false);
  for (const auto& [l2, e] : short_edges)
    for (const std::size_t i : {edges[e].a, edges[e].b})
      if (pins[i].kind != Pin::Kind::free && !pinned_exactly[i])
      {
        pins[i] = pin_of(vertices[i]);
        pinned_exactly[i] = true;
      }
  std::vector<std::size_t> parent(points.size());
  for (std::size_t i = 0; i < parent.size(); ++i)
    parent[i] = i;
  std::vector<Pin> cluster_pin = pins; // valid at the roots
  const auto root = [&](std::size_t i)
  {
    while (parent[i] != i)
      i = parent[i] = parent[parent[i]];
    return i;
  };
  TidyCounts counts;
  for (const auto& [l2, e] : short_edges)
  {
    const std::size_t a = root(edges[e].a), b = root(edges[e].b);
    if (a == b)
      continue;
    const std::optional<Pin> pin = combine(cluster_pin[a], cluster_pin[b]);
    if (!pin)
      continue; // stays short: RockMassStatistics::n_short_edges
    parent[b] = a;
    cluster_pin[a] = *pin;
    ++counts.n_collapsed;
  }
  // Each cluster moves to the member that satisfies its pin and is nearest to all the others.
  std::vector<std::size_t> target(points.size());
  std::map<std::size_t, std::vector<std::size_t>> clusters;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    target[i] = i;
    clusters[root(i)].push_back(i);
  }
  for (const auto& [r, members] : clusters)
  {
    if (members.size() == 1)
      continue;
    const Pin& pin = cluster_pin[r];
    double best_reach = std::numeric_limits<double>::infinity();
    std::size_t best = r;
    for (const std::size_t m : members)
    {
      if (pins[m].kind != pin.kind)
        continue; // a free member of a pinned cluster, or a line member of a cornered one
      double reach = 0.0;
      for (const std::size_t other : members)
        reach = std::max(reach, squared_length(m, other));
      if (reach < best_reach)
      {
        best_reach = reach;
        best = m;
      }
    }
    for (const std::size_t m : members)
      target[m] = best;
  }

  // The edges after the moves; edges that now join the same two vertices become one.
  using Key = std::pair<std::size_t, std::size_t>;
  const auto key = [](std::size_t a, std::size_t b) { return Key(std::min(a, b), std::max(a, b)); };
  std::map<Key, MovedEdge> moved;
  std::vector<std::vector<std::size_t>> neighbours(points.size());
  for (const GraphEdge& edge : edges)
  {
    const std::size_t a = target[edge.a], b = target[edge.b];
    if (a == b)
      continue;
    const auto [it, inserted] = moved.try_emplace(key(a, b));
    add_sources(it->second.sources, sources(edge.h));
    if (a == edge.a && b == edge.b)
      it->second.unchanged = edge.h;
    if (inserted)
    {
      neighbours[a].push_back(b);
      neighbours[b].push_back(a);
    }
  }

  // 3. Straight free vertices between two edges.
  const double sin_straight = std::sin(criteria.straight_angle);
  const auto unlink = [&](std::size_t a, std::size_t b)
  {
    std::vector<std::size_t>& n = neighbours[a];
    n.erase(std::find(n.begin(), n.end(), b));
  };
  std::vector<std::size_t> candidates(points.size());
  for (std::size_t i = 0; i < candidates.size(); ++i)
    candidates[i] = i;
  while (!candidates.empty())
  {
    const std::size_t v = candidates.back();
    candidates.pop_back();
    if (pins[v].kind != Pin::Kind::free || neighbours[v].size() != 2)
      continue;
    const std::size_t a = neighbours[v][0], b = neighbours[v][1];
    const Vector2 in = near[v] - near[a], out = near[b] - near[v];
    const double sine = in.x() * out.y() - in.y() * out.x();
    if (in.dot(out) <= 0.0 || std::abs(sine) > sin_straight * in.norm() * out.norm())
      continue;
    std::vector<CurveSource> joined = moved[key(a, v)].sources;
    add_sources(joined, moved[key(v, b)].sources);
    moved.erase(key(a, v));
    moved.erase(key(v, b));
    unlink(a, v);
    unlink(b, v);
    neighbours[v].clear();
    const auto [it, inserted] = moved.try_emplace(key(a, b));
    add_sources(it->second.sources, joined);
    if (inserted)
    {
      neighbours[a].push_back(b);
      neighbours[b].push_back(a);
    }
    candidates.push_back(a); // their angles changed
    candidates.push_back(b);
    ++counts.n_straight;
  }
  if (!counts.changed())
    return counts;

  // Out with the edges that changed, in with what replaces them (an unchanged edge that a
  // moved one now runs along only gains its sources).
  std::vector<Traits::Curve_2> curves;
  std::set<Halfedge> kept;
  for (const auto& [ab, edge] : moved)
  {
    const Segment segment(points[ab.first], points[ab.second]);
    std::vector<CurveSource> add = edge.sources;
    if (edge.unchanged)
    {
      kept.insert(*edge.unchanged);
      const std::vector<CurveSource> has = sources(*edge.unchanged);
      add.erase(std::remove_if(add.begin(), add.end(),
                               [&](const CurveSource& s)
                               { return std::find(has.begin(), has.end(), s) != has.end(); }),
                add.end());
    }
    for (const CurveSource& s : add)
      curves.emplace_back(segment, s);
  }
  for (const GraphEdge& edge : edges)
    if (!kept.count(edge.h))
      arrangement.remove_edge(edge.h);
  // One at a time (a walk through the faces each curve crosses) unless they are many: the
  // aggregated insertion sweeps the whole arrangement.
  if (10 * curves.size() < arrangement.number_of_edges())
    for (const Traits::Curve_2& c : curves)
      CGAL::insert(arrangement, c);
  else
    CGAL::insert(arrangement, curves.begin(), curves.end());
  return counts;
}

// ---- Blocks ------------------------------------------------------------------------------------

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

/// The block of a block face whose boundary is one simple loop (as settle() leaves them).
RockMassBlock make_block(Face f, double straight_tolerance)
{
  const std::vector<std::vector<Halfedge>> loops = boundary_loops(f);
  if (loops.size() != 1)
    throw InputError("a block near " +
                     format_point(rounded(loops.front().front()->source()->point())) +
                     " m is not a simple polygon: it touches itself or an island at vertices "
                     "that no vertical cut can separate; expected openings and joints that meet "
                     "the rest of the boundary along edges or not at all");
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
  block.area = CGAL::to_double(CGAL::polygon_area_2(points.begin(), points.end(), Kernel()));
  for (const ExactPoint& p : points)
    block.vertices.push_back(rounded(p));
  return block;
}

double perimeter(const std::vector<Point>& vertices)
{
  double p = 0.0;
  for (std::size_t i = 0; i < vertices.size(); ++i)
    p += (vertices[(i + 1) % vertices.size()] - vertices[i]).norm();
  return p;
}

/// Input problems the generator cannot work around.
void check_description(const RockMassDescription& d)
{
  const auto expect = [](bool ok, const std::string& what)
  {
    if (!ok)
      throw InputError("rock mass: " + what);
  };
  expect(is_simple_polygon(anticlockwise(d.region)),
         "the region is not a simple polygon: expected at least 3 vertices, no self-intersection "
         "and a non-zero area");
  for (std::size_t s = 0; s < d.joint_sets.size(); ++s)
  {
    const JointSet& set = d.joint_sets[s];
    const std::string name = "joint set " + std::to_string(s) + ": ";
    expect(std::isfinite(set.dip),
           name + "dip = " + format_number(set.dip) + ": expected a number");
    expect(set.spacing > 0.0 && std::isfinite(set.spacing),
           name + "spacing = " + format_number(set.spacing) + " m: expected > 0");
    expect(set.bridge >= 0.0 && std::isfinite(set.bridge),
           name + "bridge = " + format_number(set.bridge) + " m: expected >= 0");
    expect(set.persistent() || (set.trace_length > 0.0 && std::isfinite(set.trace_length)),
           name + "trace_length = " + format_number(set.trace_length) +
               " m with a bridge: expected a finite length > 0");
    expect(set.perturbation.spacing >= 0.0 && set.perturbation.spacing < 1.0,
           name + "spacing perturbation = " + format_number(set.perturbation.spacing) +
               ": expected a fraction in [0, 1)");
    expect(set.perturbation.position >= 0.0 && std::isfinite(set.perturbation.position),
           name + "position perturbation = " + format_number(set.perturbation.position) +
               ": expected a fraction >= 0");
  }
  for (std::size_t j = 0; j < d.joints.size(); ++j)
    expect(d.joints[j].from != d.joints[j].to,
           "joint " + std::to_string(j) + " starts and ends at " + format_point(d.joints[j].from) +
               ": expected two different points");
  if (d.min_edge_length)
    expect(*d.min_edge_length >= 0.0 && std::isfinite(*d.min_edge_length),
           "min_edge_length = " + format_number(*d.min_edge_length) + " m: expected >= 0");
  expect(d.straight_angle >= 0.0 && d.straight_angle < 90.0,
         "straight_angle = " + format_number(d.straight_angle) +
             " deg: expected an angle in [0, 90)");
  expect(d.chord_tolerance > 0.0,
         "chord_tolerance = " + format_number(d.chord_tolerance) + " m: expected > 0");
  for (std::size_t k = 0; k < d.openings.size(); ++k)
  {
    const Opening& o = d.openings[k];
    const std::string name = "opening " + std::to_string(k) + ": ";
    if (o.shape == Opening::Shape::circle)
      expect(o.radius > 0.0, name + "radius = " + format_number(o.radius) + " m: expected > 0");
    if (o.shape == Opening::Shape::horseshoe)
      expect(o.width > 0.0 && o.wall_height >= 0.0,
             name + "width = " + format_number(o.width) + " m, wall_height = " +
                 format_number(o.wall_height) + " m: expected width > 0 and wall_height >= 0");
    expect(is_simple_polygon(opening_polygon(o, d.chord_tolerance)),
           name + "not a simple polygon: expected at least 3 vertices, no self-intersection and "
                  "a non-zero area");
  }
}

/// Rounds of tidy() and sliver merging at most (two or three are usual).
constexpr std::size_t max_tidy_rounds = 16;

/// The region's extent in x or y, the larger [m].
double extent(const std::vector<Point>& region)
{
  Point lower = region.front(), upper = region.front();
  for (const Point& v : region)
  {
    lower = lower.cwiseMin(v);
    upper = upper.cwiseMax(v);
  }
  return (upper - lower).maxCoeff();
}

/// A few hundred rounding errors of the region's coordinates [m]: a vertex this close to the
/// line between its neighbours is straight (see without_collinear_vertices).
double rounding_tolerance(const RockMassDescription& d)
{
  return 1e-14 * extent(d.region);
}

/// The shortest block edge [m] (see RockMassDescription::min_edge_length).
double min_edge_length(const RockMassDescription& d, double mean_spacing)
{
  const double wanted =
      d.min_edge_length.value_or(d.joint_sets.empty() ? d.chord_tolerance : 0.01 * mean_spacing);
  return std::max(wanted, 1e-9 * extent(d.region));
}

} // namespace

RockMassResult generate_blocks(const RockMassDescription& d)
{
  check_description(d);
  RockMassResult result;
  RockMassStatistics& stats = result.statistics;
  const std::vector<Point> region = anticlockwise(d.region);
  const std::size_t n_openings = d.openings.size();

  std::vector<Traits::Curve_2> curves = joint_curves(d);
  stats.n_traces = curves.size();
  append_polygon(region, {CurveSource::Kind::region, 0}, curves);
  for (std::size_t k = 0; k < n_openings; ++k)
  {
    result.openings.push_back(opening_polygon(d.openings[k], d.chord_tolerance));
    append_polygon(result.openings.back(), {CurveSource::Kind::opening, k}, curves);
  }
  Arrangement arrangement;
  CGAL::insert(arrangement, curves.begin(), curves.end()); // sweep line, exact
  stats.n_island_cuts = settle(arrangement, n_openings);

  double mean_spacing = 0.0;
  for (const JointSet& set : d.joint_sets)
    mean_spacing += set.spacing / static_cast<double>(d.joint_sets.size());
  const SliverCriteria criteria{
      d.slivers.min_area.value_or(d.slivers.min_area_fraction * mean_spacing * mean_spacing),
      d.slivers.min_inscribed_radius};
  stats.min_area = criteria.min_area;
  const EdgeCriteria edge_criteria{min_edge_length(d, mean_spacing),
                                   d.straight_angle * M_PI / 180.0};
  stats.min_edge_length = edge_criteria.min_length;
  // Short edges and slivers, until neither changes anything: a collapse may fold a small face
  // over, a merge may leave a straight vertex.
  for (std::size_t round = 0; round < max_tidy_rounds; ++round)
  {
    const TidyCounts tidied = tidy(arrangement, edge_criteria);
    stats.n_collapsed_edges += tidied.n_collapsed;
    stats.n_straight_vertices += tidied.n_straight;
    if (tidied.changed())
      stats.n_island_cuts += settle(arrangement, n_openings);
    std::size_t n_merged = 0;
    if (d.slivers.action == SliverAction::merge)
      while (const std::size_t n = merge_pass(arrangement, criteria))
      {
        n_merged += n;
        stats.n_island_cuts += settle(arrangement, n_openings);
      }
    stats.n_merged += n_merged;
    if (!tidied.changed() && n_merged == 0)
      break;
  }

  Kernel::FT excavated = 0;
  for (auto f = arrangement.faces_begin(); f != arrangement.faces_end(); ++f)
    if (f->data().block)
      result.blocks.push_back(make_block(f, rounding_tolerance(d)));
    else if (f->data().in_region)
      excavated += face_area(f);
  std::vector<ExactPoint> exact_region;
  for (const Point& v : region)
    exact_region.push_back(exact_point(v));
  stats.region_area =
      CGAL::to_double(CGAL::polygon_area_2(exact_region.begin(), exact_region.end(), Kernel()));
  stats.excavated_area = CGAL::to_double(excavated);

  // Bottom row first: by centroid y, then x.
  std::vector<std::pair<Point, RockMassBlock>> by_centroid;
  for (RockMassBlock& b : result.blocks)
    by_centroid.emplace_back(polygon_moments(b.vertices).centroid, std::move(b));
  std::sort(by_centroid.begin(), by_centroid.end(),
            [](const auto& a, const auto& b) {
              return a.first.y() < b.first.y() ||
                     (a.first.y() == b.first.y() && a.first.x() < b.first.x());
            });
  result.blocks.clear();
  for (auto& [centroid, block] : by_centroid)
  {
    const double p = perimeter(block.vertices);
    if (criteria.is_sliver(block.area, p))
      result.slivers.push_back({result.blocks.size(), centroid, block.area, 2.0 * block.area / p});
    result.blocks.push_back(std::move(block));
  }

  stats.n_blocks = result.blocks.size();
  stats.n_reported = result.slivers.size();
  if (!result.blocks.empty())
  {
    stats.smallest_area = result.blocks.front().area;
    for (const RockMassBlock& b : result.blocks)
    {
      stats.smallest_area = std::min(stats.smallest_area, b.area);
      stats.total_area += b.area;
    }
    stats.mean_area = stats.total_area / static_cast<double>(stats.n_blocks);
    stats.shortest_edge = std::numeric_limits<double>::infinity();
    for (const RockMassBlock& b : result.blocks)
      for (std::size_t k = 0; k < b.vertices.size(); ++k)
      {
        const double l = (b.vertices[(k + 1) % b.vertices.size()] - b.vertices[k]).norm();
        stats.shortest_edge = std::min(stats.shortest_edge, l);
        stats.n_short_edges += l < stats.min_edge_length;
      }
  }
  return result;
}

} // namespace ddafem::dda
