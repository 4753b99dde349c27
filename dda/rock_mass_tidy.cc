// Short edges and straight vertices of the rock mass arrangement (tidy in
// dda/rock_mass_arrangement.h). A vertex is shared by every face around it, so each change is
// the same for all of them: no gap, no overlap. Only the edges that change are taken out and put
// in again, exactly: a crossing that a move makes becomes a vertex, a face folded over becomes a
// small face that the next call or the sliver merge removes.
//
// 1. Dangling edges are removed (they bound no block).
// 2. Each edge shorter than min_length with a block on one side, shortest first, joins its two
//    vertices' clusters (union-find) unless their pins contradict (see Pin). Every vertex of a
//    cluster moves to the member that satisfies the cluster's pin and is nearest to all the
//    others. The region's and the openings' boundaries keep their shape: their corners stay,
//    and vertices on them move along them.
// 3. A free vertex with two edges whose angle is within straight_angle of 180 degrees is
//    removed (both faces agree: it is straight on both sides); its two edges become one.
#include "dda/rock_mass_arrangement.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <utility>

namespace ddafem::dda::rock_mass_internal
{
namespace
{
using Vertex = Arrangement::Vertex_handle;

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

/// The arrangement as a graph: its vertices by index and its edges between them.
struct VertexGraph
{
  std::vector<Vertex> vertices;
  std::vector<ExactPoint> points; ///< the vertices, exact [m]
  /// Exact for the ends of short edges (see pin_short_edge_ends); else free or not (kind point).
  std::vector<Pin> pins;
  std::vector<GraphEdge> edges;
  std::vector<Point> near; ///< the vertices in double [m]

  /// Squared distance between vertices a and b, in double [m^2].
  double squared_length(std::size_t a, std::size_t b) const
  {
    return (near[a] - near[b]).squaredNorm();
  }
};

/// The graph of the arrangement's vertices and edges; a vertex on a boundary gets the pin kind
/// point until pin_short_edge_ends finds its exact pin.
VertexGraph vertex_graph(Arrangement& arrangement)
{
  VertexGraph graph;
  std::map<Vertex, std::size_t> index;
  for (auto v = arrangement.vertices_begin(); v != arrangement.vertices_end(); ++v)
  {
    index[v] = graph.points.size();
    graph.vertices.push_back(v);
    graph.points.push_back(v->point());
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
    graph.pins.push_back(pin);
  }
  for (auto e = arrangement.edges_begin(); e != arrangement.edges_end(); ++e)
  {
    const Face f = e->face(), g = e->twin()->face();
    graph.edges.push_back({index[e->source()], index[e->target()], e,
                           f != g && (f->data().block || g->data().block)});
  }
  for (const ExactPoint& p : graph.points)
    graph.near.push_back(approximate(p));
  return graph;
}

/// (squared length [m^2], index into VertexGraph::edges) of each short edge, shortest first.
using ShortEdges = std::vector<std::pair<double, std::size_t>>;

/// The edges shorter than min_length [m] with a block on one side.
ShortEdges short_edges(const VertexGraph& graph, double min_length)
{
  const double min_squared = min_length * min_length;
  ShortEdges short_edges;
  for (std::size_t e = 0; e < graph.edges.size(); ++e)
  {
    const double l2 = graph.squared_length(graph.edges[e].a, graph.edges[e].b);
    if (graph.edges[e].at_block && l2 < min_squared)
      short_edges.emplace_back(l2, e);
  }
  std::sort(short_edges.begin(), short_edges.end());
  return short_edges;
}

/// Gives the ends of the short edges that lie on a boundary their exact pin (pin_of).
void pin_short_edge_ends(VertexGraph& graph, const ShortEdges& short_edges)
{
  std::vector<bool> pinned_exactly(graph.points.size(), false);
  for (const auto& [l2, e] : short_edges)
    for (const std::size_t i : {graph.edges[e].a, graph.edges[e].b})
      if (graph.pins[i].kind != Pin::Kind::free && !pinned_exactly[i])
      {
        graph.pins[i] = pin_of(graph.vertices[i]);
        pinned_exactly[i] = true;
      }
}

/// Vertices joined into clusters (union-find) and the pin of each cluster.
class Clusters
{
public:
  explicit Clusters(const std::vector<Pin>& pins) : parent(pins.size()), cluster_pin(pins)
  {
    for (std::size_t i = 0; i < parent.size(); ++i)
      parent[i] = i;
  }

  /// The cluster of vertex i, by the index of its root vertex.
  std::size_t root(std::size_t i)
  {
    while (parent[i] != i)
      i = parent[i] = parent[parent[i]];
    return i;
  }

  /// Joins the clusters of vertices a and b unless they are one already or their pins
  /// contradict; whether it did.
  bool join(std::size_t a, std::size_t b)
  {
    a = root(a);
    b = root(b);
    if (a == b)
      return false;
    const std::optional<Pin> pin = combine(cluster_pin[a], cluster_pin[b]);
    if (!pin)
      return false; // stays short: RockMassStatistics::n_short_edges
    parent[b] = a;
    cluster_pin[a] = *pin;
    return true;
  }

  /// The pin of the cluster whose root is r.
  const Pin& pin(std::size_t r) const { return cluster_pin[r]; }

private:
  std::vector<std::size_t> parent;
  std::vector<Pin> cluster_pin; ///< valid at the roots
};

/// The member of a cluster with pin `pin` that all its vertices move to: one with the cluster's
/// pin kind, nearest to all the others (r if none is).
std::size_t meeting_vertex(const VertexGraph& graph, const std::vector<std::size_t>& members,
                           const Pin& pin, std::size_t r)
{
  double best_reach = std::numeric_limits<double>::infinity();
  std::size_t best = r;
  for (const std::size_t m : members)
  {
    if (graph.pins[m].kind != pin.kind)
      continue; // a free member of a pinned cluster, or a line member of a cornered one
    double reach = 0.0;
    for (const std::size_t other : members)
      reach = std::max(reach, graph.squared_length(m, other));
    if (reach < best_reach)
    {
      best_reach = reach;
      best = m;
    }
  }
  return best;
}

/// Where each vertex moves (the index of a vertex): each cluster to its meeting vertex.
std::vector<std::size_t> targets(const VertexGraph& graph, Clusters& clusters)
{
  std::vector<std::size_t> target(graph.points.size());
  std::map<std::size_t, std::vector<std::size_t>> members;
  for (std::size_t i = 0; i < graph.points.size(); ++i)
  {
    target[i] = i;
    members[clusters.root(i)].push_back(i);
  }
  for (const auto& [r, cluster] : members)
  {
    if (cluster.size() == 1)
      continue;
    const std::size_t best = meeting_vertex(graph, cluster, clusters.pin(r), r);
    for (const std::size_t m : cluster)
      target[m] = best;
  }
  return target;
}

/// An edge by its two vertices, the lower index first.
using Key = std::pair<std::size_t, std::size_t>;

Key key(std::size_t a, std::size_t b)
{
  return Key(std::min(a, b), std::max(a, b));
}

/// The edges after the moves, by their vertices, and each vertex's neighbours along them.
struct MovedEdges
{
  std::map<Key, MovedEdge> edges;
  std::vector<std::vector<std::size_t>> neighbours;

  /// The edge from a to b, made if there is none, with `from` added to its sources.
  MovedEdge& link(std::size_t a, std::size_t b, const std::vector<CurveSource>& from)
  {
    const auto [it, inserted] = edges.try_emplace(key(a, b));
    add_sources(it->second.sources, from);
    if (inserted)
    {
      neighbours[a].push_back(b);
      neighbours[b].push_back(a);
    }
    return it->second;
  }

  /// Takes b from a's neighbours.
  void unlink(std::size_t a, std::size_t b)
  {
    std::vector<std::size_t>& n = neighbours[a];
    n.erase(std::find(n.begin(), n.end(), b));
  }
};

/// The edges after each vertex moved to its target; edges that now join the same two vertices
/// become one.
MovedEdges moved_edges(const VertexGraph& graph, const std::vector<std::size_t>& target)
{
  MovedEdges moved;
  moved.neighbours.resize(graph.points.size());
  for (const GraphEdge& edge : graph.edges)
  {
    const std::size_t a = target[edge.a], b = target[edge.b];
    if (a == b)
      continue;
    MovedEdge& m = moved.link(a, b, sources(edge.h));
    if (a == edge.a && b == edge.b)
      m.unchanged = edge.h;
  }
  return moved;
}

/// Removes the free vertices with two edges whose angle is within straight_angle [rad] of 180
/// degrees: their two edges become one. Returns how many.
std::size_t remove_straight_vertices(const VertexGraph& graph, double straight_angle,
                                     MovedEdges& moved)
{
  const double sin_straight = std::sin(straight_angle);
  std::vector<std::size_t> candidates(graph.points.size());
  for (std::size_t i = 0; i < candidates.size(); ++i)
    candidates[i] = i;
  std::size_t n_straight = 0;
  while (!candidates.empty())
  {
    const std::size_t v = candidates.back();
    candidates.pop_back();
    if (graph.pins[v].kind != Pin::Kind::free || moved.neighbours[v].size() != 2)
      continue;
    const std::size_t a = moved.neighbours[v][0], b = moved.neighbours[v][1];
    const Vector2 in = graph.near[v] - graph.near[a], out = graph.near[b] - graph.near[v];
    const double sine = in.x() * out.y() - in.y() * out.x();
    if (in.dot(out) <= 0.0 || std::abs(sine) > sin_straight * in.norm() * out.norm())
      continue;
    std::vector<CurveSource> joined = moved.edges[key(a, v)].sources;
    add_sources(joined, moved.edges[key(v, b)].sources);
    moved.edges.erase(key(a, v));
    moved.edges.erase(key(v, b));
    moved.unlink(a, v);
    moved.unlink(b, v);
    moved.neighbours[v].clear();
    moved.link(a, b, joined);
    candidates.push_back(a); // their angles changed
    candidates.push_back(b);
    ++n_straight;
  }
  return n_straight;
}

/// Out with the edges that changed, in with what replaces them (an unchanged edge that a moved
/// one now runs along only gains its sources).
void replace_changed_edges(Arrangement& arrangement, const VertexGraph& graph,
                           const std::map<Key, MovedEdge>& moved)
{
  std::vector<Traits::Curve_2> curves;
  std::set<Halfedge> kept;
  for (const auto& [ab, edge] : moved)
  {
    const Segment segment(graph.points[ab.first], graph.points[ab.second]);
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
  for (const GraphEdge& edge : graph.edges)
    if (!kept.count(edge.h))
      arrangement.remove_edge(edge.h);
  // One at a time (a walk through the faces each curve crosses) unless they are many: the
  // aggregated insertion sweeps the whole arrangement.
  if (10 * curves.size() < arrangement.number_of_edges())
    for (const Traits::Curve_2& c : curves)
      CGAL::insert(arrangement, c);
  else
    CGAL::insert(arrangement, curves.begin(), curves.end());
}

} // namespace

TidyCounts tidy(Arrangement& arrangement, const EdgeCriteria& criteria)
{
  remove_dangling_edges(arrangement);
  VertexGraph graph = vertex_graph(arrangement);
  const ShortEdges short_ones = short_edges(graph, criteria.min_length);
  pin_short_edge_ends(graph, short_ones);
  TidyCounts counts;
  Clusters clusters(graph.pins);
  for (const auto& [l2, e] : short_ones)
    counts.n_collapsed += clusters.join(graph.edges[e].a, graph.edges[e].b);
  MovedEdges moved = moved_edges(graph, targets(graph, clusters));
  counts.n_straight = remove_straight_vertices(graph, criteria.straight_angle, moved);
  if (counts.changed())
    replace_changed_edges(arrangement, graph, moved.edges);
  return counts;
}

} // namespace ddafem::dda::rock_mass_internal
