// Narrow phase of contact detection: Shi's vertex-edge contact geometry between two polygons.
//
// Polygons are simple, anticlockwise and not closed (the last vertex is not repeated), convex or
// concave. Edge k runs from vertex k to vertex k + 1 (cyclic); with unit tangent t its outward
// unit normal is n = (t_y, -t_x). A contact is a convex vertex of one polygon against an edge of
// the other (Shi 1988, Discontinuous deformation analysis, ch. 4): the vertex-edge pairs found
// here become the normal and shear springs of the open-close iteration.
#pragma once

#include "dda/types.h"

#include <array>
#include <cstddef>
#include <vector>

namespace ddafem::dda
{
/// How a vertex-edge pair arose (Shi 1988, ch. 4).
enum class ContactKind
{
  vertex_edge,   ///< a convex vertex near the inside of an edge
  vertex_vertex, ///< a convex vertex near a vertex of the other polygon
  edge_edge      ///< a convex vertex near the inside of an edge, one of its legs along that edge
};

/// A convex vertex of one polygon against an edge of the other.
struct VertexEdgePair
{
  /// 0: vertex of `a` on an edge of `b`; 1: vertex of `b` on an edge of `a`
  std::size_t vertex_polygon;
  std::size_t vertex; ///< vertex index in its polygon
  std::size_t edge;   ///< edge index in the other polygon
  /// Projection of the vertex along the edge: 0 at its start, 1 at its end (clamped to [0, 1]).
  double ratio;
  /// Signed normal distance from the edge's line [m]: positive outside the edge's polygon,
  /// negative when penetrating.
  double distance;
  ContactKind kind;
};

/// Interior angle at vertex k [rad], in (0, 2 pi): below pi at a convex vertex, above pi at a
/// concave one. Requires an anticlockwise polygon without repeated consecutive vertices.
double interior_angle(const std::vector<Point>& polygon, std::size_t k);

/// The vertex-edge pairs of polygons a and b, sorted by (vertex_polygon, vertex, edge), without
/// duplicates. `search_distance` d0 [m] is how near a vertex must come to an edge or vertex to
/// pair; `angle_tolerance` [rad] (e.g. 1e-3 to 0.05) decides when a vertex counts as straight and
/// when a vertex's leg counts as parallel to an edge. Rules:
/// 1. Only convex vertices (interior angle < pi - angle_tolerance) are the vertex of a pair.
/// 2. Wedge ("entrance") condition for vertex v of P against edge e of Q with outward normal n:
///    both unit legs of P at v (towards its previous and next vertex) satisfy
///    leg . n >= -sin(angle_tolerance), i.e. P lies locally on the outer side of e's line.
/// 3. Vertex-edge: convex v within d0 of segment e (hence |distance| <= d0), the wedge condition
///    holds and v is farther than d0 from both end vertices of e: kind edge_edge when a leg of v
///    is parallel to e (|leg . n| <= sin(angle_tolerance)), else vertex_edge.
/// 4. Vertex-vertex: convex v of P within d0 of vertex w of Q, each such (v, w) resolved once
///    (kind vertex_vertex):
///    - w concave: v pairs with each of Q's two edges at w that passes the wedge condition;
///    - w straight: v pairs with the one of Q's two edges at w that passes the wedge condition (if
///      both do, the one on which v's ratio lies farther from the edge's ends);
///    - w convex: of the four candidate entrance lines (Q's edges at w for v, P's edges at v for
///      w), those whose entering vertex passes the wedge condition (all four if none does), the
///      one with the largest signed distance: the line the other vertex is most outside of.
///      Ties within 1e-12 d0 go to the smallest (vertex_polygon, vertex, edge), so a vertex of
///      `a` wins an exact tie: swapping a and b mirrors the result except for exact ties, e.g.
///      two aligned stacked squares, where both choices give the same contact line.
/// Pure and deterministic; cost O(n_a n_b). Throws std::invalid_argument for a polygon with
/// fewer than 3 vertices or non-positive signed area, d0 <= 0, or an angle tolerance outside
/// [0, pi/2).
std::vector<VertexEdgePair> find_vertex_edge_pairs(const std::vector<Point>& a,
                                                   const std::vector<Point>& b,
                                                   double search_distance, double angle_tolerance);

/// Whether the interior angle at a vertex is below, about or above pi (within the angle
/// tolerance).
enum class VertexShape : signed char
{
  convex,
  straight,
  concave
};

/// Edge k of a polygon: from vertex k, unit tangent t, length [m], outward unit normal
/// n = (t_y, -t_x).
struct PolygonEdge
{
  Point start;
  Vector2 tangent;
  double length;
  Vector2 normal;
};

/// What the search needs of one polygon, computed once per configuration: a block's features
/// serve every pair it is in (a block of a wall is in about six), where the search would
/// otherwise compute each vertex's shape, legs and edges again for each.
struct PolygonFeatures
{
  std::vector<Point> vertices;
  double angle_tolerance = 0.0;             ///< [rad] that decided the shapes
  std::vector<VertexShape> shapes;          ///< per vertex
  std::vector<std::array<Vector2, 2>> legs; ///< per vertex: unit legs to previous and next
  std::vector<PolygonEdge> edges;           ///< per edge
  Point lower = Point::Zero(), upper = Point::Zero(); ///< bounding box [m]
};

/// The features of `polygon` under `angle_tolerance` [rad], into `features` (its vectors reused).
/// Throws std::invalid_argument for fewer than 3 vertices or non-positive signed area, or an
/// angle tolerance outside [0, pi/2).
void compute_polygon_features(const std::vector<Point>& polygon, double angle_tolerance,
                              PolygonFeatures& features);

/// Scratch of find_vertex_edge_pairs, kept between calls (one per thread) so that a search
/// allocates nothing once the vectors have grown; `pairs` holds the last search's result.
struct NarrowPhaseWorkspace
{
  std::array<PolygonFeatures, 2> features;      ///< of a and b (the search on polygons)
  std::array<std::vector<std::size_t>, 2> near; ///< vertices near the other's bounding box
  std::vector<VertexEdgePair> pairs;
};

/// The same search, its result in `work.pairs` (the same pairs in the same order).
void find_vertex_edge_pairs(const std::vector<Point>& a, const std::vector<Point>& b,
                            double search_distance, double angle_tolerance,
                            NarrowPhaseWorkspace& work);

/// The same search on features computed beforehand (with the same angle tolerance, else
/// std::invalid_argument), its result in `work.pairs`: the same bits as the search on the
/// polygons.
void find_vertex_edge_pairs(const PolygonFeatures& a, const PolygonFeatures& b,
                            double search_distance, NarrowPhaseWorkspace& work);

} // namespace ddafem::dda
