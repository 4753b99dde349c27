#include "dda/contact/narrow_phase.h"

#include "dda/geometry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace ddafem::dda
{
namespace
{
double cross(const Vector2& u, const Vector2& v)
{
  return u.x() * v.y() - u.y() * v.x();
}

std::size_t next(std::size_t k, std::size_t n)
{
  return (k + 1) % n;
}

std::size_t previous(std::size_t k, std::size_t n)
{
  return (k + n - 1) % n;
}

PolygonEdge edge_of(const std::vector<Point>& polygon, std::size_t k)
{
  const Vector2 along = polygon[next(k, polygon.size())] - polygon[k];
  const double length = along.norm();
  const Vector2 t = along / length;
  return {polygon[k], t, length, Vector2(t.y(), -t.x())};
}

/// Unit legs of the polygon at vertex k: towards its previous and its next vertex.
std::array<Vector2, 2> legs_at(const std::vector<Point>& polygon, std::size_t k)
{
  const std::size_t n = polygon.size();
  return {(polygon[previous(k, n)] - polygon[k]).normalized(),
          (polygon[next(k, n)] - polygon[k]).normalized()};
}

VertexShape vertex_shape(const std::vector<Point>& polygon, std::size_t k, double angle_tolerance)
{
  const double angle = interior_angle(polygon, k);
  if (angle < M_PI - angle_tolerance)
    return VertexShape::convex;
  if (angle > M_PI + angle_tolerance)
    return VertexShape::concave;
  return VertexShape::straight;
}

/// The features of two polygons and the tolerances of one search.
class PairSearch
{
public:
  PairSearch(const PolygonFeatures& a, const PolygonFeatures& b, double search_distance,
             NarrowPhaseWorkspace& work)
      : polygons{&a, &b}, near(work.near), d0(search_distance), reach(d0 * (1.0 + 1e-9)),
        sin_tolerance(std::sin(a.angle_tolerance))
  {
    for (std::size_t s = 0; s < 2; ++s)
      find_near_vertices(*polygons[s], *polygons[1 - s], near[s]);
  }

  /// Rules 3 and 4, in any order (the caller sorts). Only vertices near the other polygon's
  /// bounding box are visited: a vertex farther than d0 from it is farther than d0 from every
  /// edge and vertex of the other polygon and pairs with none.
  void find(std::vector<VertexEdgePair>& pairs) const
  {
    pairs.clear();
    for (std::size_t s = 0; s < 2; ++s)
      for (const std::size_t v : near[s])
        if (shape(s, v) == VertexShape::convex)
          add_vertex_edge_pairs(s, v, pairs);

    const std::vector<Point>& a = polygons[0]->vertices;
    const std::vector<Point>& b = polygons[1]->vertices;
    for (const std::size_t i : near[0])
      for (const std::size_t j : near[1])
      {
        if (!near_box(a[i], b[j], b[j]) || (a[i] - b[j]).norm() > d0)
          continue;
        if (shape(0, i) == VertexShape::convex && shape(1, j) == VertexShape::convex)
          pairs.push_back(entrance_pair(i, j));
        else if (shape(0, i) == VertexShape::convex)
          add_corner_pairs(0, i, j, pairs);
        else if (shape(1, j) == VertexShape::convex)
          add_corner_pairs(1, j, i, pairs);
      }
  }

private:
  /// Vertex v of polygon s against edge e of the other polygon, with ratio and signed distance.
  VertexEdgePair pair_of(std::size_t s, std::size_t v, std::size_t e, ContactKind kind) const
  {
    const PolygonEdge& edge = polygons[1 - s]->edges[e];
    const Vector2 from_start = polygons[s]->vertices[v] - edge.start;
    return {s,
            v,
            e,
            std::clamp(from_start.dot(edge.tangent) / edge.length, 0.0, 1.0),
            from_start.dot(edge.normal),
            kind};
  }

  /// Rule 2: both legs of polygon s at v lie on the outer side of edge e's line (within the
  /// angle tolerance).
  bool enters(std::size_t s, std::size_t v, std::size_t e) const
  {
    const Vector2& n = polygons[1 - s]->edges[e].normal;
    const std::array<Vector2, 2>& legs = polygons[s]->legs[v];
    return legs[0].dot(n) >= -sin_tolerance && legs[1].dot(n) >= -sin_tolerance;
  }

  /// Vertex v of polygon s, behind edge e's line (the penetrating side), did not enter the
  /// other polygon through e when, at a convex end of e, it lies
  /// - in front of the adjacent edge's line: outside the polygon, beside that end, so its
  ///   distance to e's line is no penetration. Near an acute end (a wedge of 28 deg) a vertex
  ///   just beyond d0 from it would otherwise be taken as millimetres deep in a block it does
  ///   not touch;
  /// - or behind the adjacent edge's line by less than behind e's, and entering that edge (rule
  ///   2): inside the corner, it entered through the adjacent edge (that pair is the contact).
  ///   Two blocks whose corners overlap along a joint by just beyond d0 (a vertex 0.23 mm
  ///   behind the joint's edge and 5.9 mm along it from the corner) would otherwise pair the
  ///   vertex with the corner's other edge, 5.9 mm deep.
  /// `edge` is edge e of the other polygon (the caller has it).
  bool not_entered_through(std::size_t s, std::size_t v, std::size_t e,
                           const PolygonEdge& edge) const
  {
    const Point& p = polygons[s]->vertices[v];
    const double depth = -(p - edge.start).dot(edge.normal);
    if (depth <= 0.0)
      return false;
    // The edge before e meets it at e's start, the edge after at its end; a concave end does
    // not bound the polygon by its other edge.
    const PolygonFeatures& other = *polygons[1 - s];
    const std::size_t n = other.vertices.size();
    for (const auto& [adjacent, shared] : {std::pair{previous(e, n), e}, {next(e, n), next(e, n)}})
    {
      if (shape(1 - s, shared) != VertexShape::convex)
        continue;
      const PolygonEdge& side = other.edges[adjacent];
      const double side_depth = -(p - side.start).dot(side.normal);
      if (side_depth < 0.0 || (side_depth < depth && enters(s, v, adjacent)))
        return true;
    }
    return false;
  }

  /// Rule 3: convex vertex v of polygon s near the inside of the other polygon's edges.
  void add_vertex_edge_pairs(std::size_t s, std::size_t v, std::vector<VertexEdgePair>& pairs) const
  {
    const Point& p = polygons[s]->vertices[v];
    const std::vector<Point>& other = polygons[1 - s]->vertices;
    const std::array<Vector2, 2>& legs = polygons[s]->legs[v];
    for (std::size_t e = 0; e < other.size(); ++e)
    {
      if (!near_box(p, other[e], other[next(e, other.size())]))
        continue; // farther than d0 from the edge and its ends
      if ((p - other[e]).norm() <= d0 || (p - other[next(e, other.size())]).norm() <= d0)
        continue; // a vertex-vertex contact (rule 4)
      const PolygonEdge& edge = polygons[1 - s]->edges[e];
      const double along = std::clamp((p - edge.start).dot(edge.tangent), 0.0, edge.length);
      if ((p - (edge.start + along * edge.tangent)).norm() > d0 || !enters(s, v, e) ||
          not_entered_through(s, v, e, edge))
        continue;
      const bool parallel_leg = std::abs(legs[0].dot(edge.normal)) <= sin_tolerance ||
                                std::abs(legs[1].dot(edge.normal)) <= sin_tolerance;
      pairs.push_back(
          pair_of(s, v, e, parallel_leg ? ContactKind::edge_edge : ContactKind::vertex_edge));
    }
  }

  /// Rule 4 for convex vertex v of polygon s near a concave or straight vertex w of the other.
  void add_corner_pairs(std::size_t s, std::size_t v, std::size_t w,
                        std::vector<VertexEdgePair>& pairs) const
  {
    const std::size_t n_other = polygons[1 - s]->vertices.size();
    std::array<std::size_t, 2> edges{previous(w, n_other), w};
    std::sort(edges.begin(), edges.end());
    std::array<VertexEdgePair, 2> entered;
    std::size_t n_entered = 0;
    for (const std::size_t e : edges)
      if (enters(s, v, e))
        entered[n_entered++] = pair_of(s, v, e, ContactKind::vertex_vertex);

    if (shape(1 - s, w) == VertexShape::concave || n_entered < 2)
    {
      pairs.insert(pairs.end(), entered.begin(), entered.begin() + n_entered);
      return;
    }
    // Straight w, both edges entered: the one on which v projects farther from the ends.
    const auto inset = [](const VertexEdgePair& p) { return std::min(p.ratio, 1.0 - p.ratio); };
    pairs.push_back(inset(entered[1]) > inset(entered[0]) ? entered[1] : entered[0]);
  }

  /// Rule 4 for convex vertex i of a near convex vertex j of b: Shi's entrance line.
  VertexEdgePair entrance_pair(std::size_t i, std::size_t j) const
  {
    // Candidates in (vertex_polygon, vertex, edge) order: i on b's edges at j, j on a's at i.
    std::array<VertexEdgePair, 4> candidates;
    std::array<bool, 4> valid;
    const std::array<std::size_t, 2> touching{i, j}; // the vertex of a and the vertex of b
    std::size_t n = 0;
    for (std::size_t s = 0; s < 2; ++s)
    {
      const std::size_t v = touching[s], w = touching[1 - s];
      const std::size_t n_other = polygons[1 - s]->vertices.size();
      std::array<std::size_t, 2> edges{previous(w, n_other), w};
      std::sort(edges.begin(), edges.end());
      for (const std::size_t e : edges)
      {
        candidates[n] = pair_of(s, v, e, ContactKind::vertex_vertex);
        valid[n++] = enters(s, v, e);
      }
    }
    // Interlocked wedges (no valid candidate): every candidate competes.
    if (std::find(valid.begin(), valid.end(), true) == valid.end())
      valid.fill(true);
    double largest = -std::numeric_limits<double>::infinity();
    for (std::size_t c = 0; c < candidates.size(); ++c)
      if (valid[c])
        largest = std::max(largest, candidates[c].distance);
    // The first valid candidate within the tie tolerance of the largest distance.
    const double tie = 1e-12 * d0;
    std::size_t c = 0;
    while (!(valid[c] && candidates[c].distance >= largest - tie))
      ++c;
    return candidates[c];
  }

  /// Whether p lies within `reach` (d0 and a margin of 1e-9 d0 for rounding) of the box of q0
  /// and q1 along both axes: if not, p is farther than d0 from the segment [q0, q1] and its ends
  /// (a Euclidean distance is at least either axis' distance), so the exact tests that follow
  /// would reject it; it saves their square roots for the edges far from p.
  bool near_box(const Point& p, const Point& q0, const Point& q1) const
  {
    return p.x() >= std::min(q0.x(), q1.x()) - reach && p.x() <= std::max(q0.x(), q1.x()) + reach &&
           p.y() >= std::min(q0.y(), q1.y()) - reach && p.y() <= std::max(q0.y(), q1.y()) + reach;
  }

  /// The shape of vertex k of polygon s.
  VertexShape shape(std::size_t s, std::size_t k) const { return polygons[s]->shapes[k]; }

  /// The vertices of p within d0 of q's bounding box (a conservative margin of 1e-9 d0 covers
  /// rounding), in ascending order.
  void find_near_vertices(const PolygonFeatures& p, const PolygonFeatures& q,
                          std::vector<std::size_t>& vertices) const
  {
    vertices.clear();
    for (std::size_t k = 0; k < p.vertices.size(); ++k)
    {
      const Point& x = p.vertices[k];
      if (x.x() >= q.lower.x() - reach && x.x() <= q.upper.x() + reach &&
          x.y() >= q.lower.y() - reach && x.y() <= q.upper.y() + reach)
        vertices.push_back(k);
    }
  }

  std::array<const PolygonFeatures*, 2> polygons;
  std::array<std::vector<std::size_t>, 2>& near; ///< vertices near the other's box
  double d0;                                     ///< search distance [m]
  double reach;                                  ///< d0 with a margin for rounding [m]
  double sin_tolerance;                          ///< sine of the angle tolerance [-]
};

void check_polygon(const std::vector<Point>& polygon)
{
  const double area = polygon.size() < 3 ? 0.0 : signed_area(polygon);
  if (!(area > 0.0))
    throw std::invalid_argument("find_vertex_edge_pairs: a polygon has " +
                                std::to_string(polygon.size()) + " vertices and signed area " +
                                std::to_string(area) +
                                " m^2, expected at least 3 vertices in anticlockwise order");
}
} // namespace

double interior_angle(const std::vector<Point>& polygon, std::size_t k)
{
  // pi minus the turn from the incoming to the outgoing edge (positive left, anticlockwise).
  const std::size_t n = polygon.size();
  const Vector2 incoming = polygon[k] - polygon[previous(k, n)];
  const Vector2 outgoing = polygon[next(k, n)] - polygon[k];
  return M_PI - std::atan2(cross(incoming, outgoing), incoming.dot(outgoing));
}

void compute_polygon_features(const std::vector<Point>& polygon, double angle_tolerance,
                              PolygonFeatures& features)
{
  check_polygon(polygon);
  if (!(angle_tolerance >= 0.0 && angle_tolerance < M_PI / 2))
    throw std::invalid_argument("find_vertex_edge_pairs: angle tolerance " +
                                std::to_string(angle_tolerance) + " rad, expected in [0, pi/2)");
  const std::size_t n = polygon.size();
  features.vertices = polygon;
  features.angle_tolerance = angle_tolerance;
  features.shapes.resize(n);
  features.legs.resize(n);
  features.edges.resize(n);
  features.lower = features.upper = polygon.front();
  for (std::size_t k = 0; k < n; ++k)
  {
    features.shapes[k] = vertex_shape(polygon, k, angle_tolerance);
    features.legs[k] = legs_at(polygon, k);
    features.edges[k] = edge_of(polygon, k);
    features.lower = features.lower.cwiseMin(polygon[k]);
    features.upper = features.upper.cwiseMax(polygon[k]);
  }
}

std::vector<VertexEdgePair> find_vertex_edge_pairs(const std::vector<Point>& a,
                                                   const std::vector<Point>& b,
                                                   double search_distance, double angle_tolerance)
{
  NarrowPhaseWorkspace work;
  find_vertex_edge_pairs(a, b, search_distance, angle_tolerance, work);
  return std::move(work.pairs);
}

void find_vertex_edge_pairs(const std::vector<Point>& a, const std::vector<Point>& b,
                            double search_distance, double angle_tolerance,
                            NarrowPhaseWorkspace& work)
{
  compute_polygon_features(a, angle_tolerance, work.features[0]);
  compute_polygon_features(b, angle_tolerance, work.features[1]);
  find_vertex_edge_pairs(work.features[0], work.features[1], search_distance, work);
}

void find_vertex_edge_pairs(const PolygonFeatures& a, const PolygonFeatures& b,
                            double search_distance, NarrowPhaseWorkspace& work)
{
  if (!(search_distance > 0.0))
    throw std::invalid_argument("find_vertex_edge_pairs: search distance " +
                                std::to_string(search_distance) + " m, expected > 0");
  if (a.angle_tolerance != b.angle_tolerance)
    throw std::invalid_argument("find_vertex_edge_pairs: the polygons' features were computed "
                                "with angle tolerances " +
                                std::to_string(a.angle_tolerance) + " and " +
                                std::to_string(b.angle_tolerance) + " rad, expected the same");
  std::vector<VertexEdgePair>& pairs = work.pairs;
  PairSearch(a, b, search_distance, work).find(pairs);
  // A stable sort by key (insertion: a pair of polygons has a few pairs), then one of each key.
  const auto key = [](const VertexEdgePair& p) {
    return std::array<std::size_t, 3>{p.vertex_polygon, p.vertex, p.edge};
  };
  for (std::size_t k = 1; k < pairs.size(); ++k)
    for (std::size_t m = k; m > 0 && key(pairs[m]) < key(pairs[m - 1]); --m)
      std::swap(pairs[m], pairs[m - 1]);
  pairs.erase(std::unique(pairs.begin(), pairs.end(),
                          [&](const VertexEdgePair& p, const VertexEdgePair& q)
                          { return key(p) == key(q); }),
              pairs.end());
}

} // namespace ddafem::dda
