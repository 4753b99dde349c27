// Narrow phase: Shi's vertex-edge pairs between two polygons against hand-computed cases.
//
// Coordinates are of order 1 m and each expected ratio or distance comes from a few subtractions
// and at most one normalization, so rounding errors are a few 1e-16 m; 1e-12 leaves a wide margin
// while still catching any wrong vertex, edge or formula (the smallest expected distance is
// 1e-3 m).
#include "dda/contact/narrow_phase.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>

using namespace ddafem::dda;

namespace
{
constexpr double tol = 1e-12;

std::vector<Point> rectangle(double x0, double y0, double w, double h)
{
  return {{x0, y0}, {x0 + w, y0}, {x0 + w, y0 + h}, {x0, y0 + h}};
}

/// L-shape: 2 x 2 square minus its upper-right 1 x 1 quarter; vertex 3 = (1, 1) is concave,
/// edge 2 runs (2, 1) -> (1, 1) (normal +y), edge 3 runs (1, 1) -> (1, 2) (normal +x).
std::vector<Point> l_shape()
{
  return {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
}

struct Expected
{
  std::size_t vertex_polygon, vertex, edge;
  double ratio, distance;
  ContactKind kind;
};

void expect_pairs(const std::vector<VertexEdgePair>& found, const std::vector<Expected>& expected)
{
  ASSERT_EQ(found.size(), expected.size());
  for (std::size_t k = 0; k < found.size(); ++k)
  {
    SCOPED_TRACE("pair " + std::to_string(k));
    EXPECT_EQ(found[k].vertex_polygon, expected[k].vertex_polygon);
    EXPECT_EQ(found[k].vertex, expected[k].vertex);
    EXPECT_EQ(found[k].edge, expected[k].edge);
    EXPECT_NEAR(found[k].ratio, expected[k].ratio, tol);
    EXPECT_NEAR(found[k].distance, expected[k].distance, tol);
    EXPECT_EQ(found[k].kind, expected[k].kind);
  }
}

/// The pairs of (b, a) as pairs of (a, b): vertex_polygon swapped, sorted again.
std::vector<VertexEdgePair> mirrored(std::vector<VertexEdgePair> pairs)
{
  for (VertexEdgePair& p : pairs)
    p.vertex_polygon = 1 - p.vertex_polygon;
  std::sort(pairs.begin(), pairs.end(),
            [](const VertexEdgePair& p, const VertexEdgePair& q)
            {
              return std::tie(p.vertex_polygon, p.vertex, p.edge) <
                     std::tie(q.vertex_polygon, q.vertex, q.edge);
            });
  return pairs;
}

/// Checks the pairs of (a, b) and that (b, a) gives the same pairs mirrored.
void expect_pairs_both_ways(const std::vector<Point>& a, const std::vector<Point>& b, double d0,
                            double angle_tolerance, const std::vector<Expected>& expected)
{
  expect_pairs(find_vertex_edge_pairs(a, b, d0, angle_tolerance), expected);
  SCOPED_TRACE("a and b swapped");
  expect_pairs(mirrored(find_vertex_edge_pairs(b, a, d0, angle_tolerance)), expected);
}
} // namespace

TEST(NarrowPhase, InteriorAngles)
{
  for (std::size_t k = 0; k < 4; ++k)
    EXPECT_NEAR(interior_angle(rectangle(3, -2, 2, 1), k), M_PI / 2, tol);
  const std::vector<Point> l = l_shape();
  for (std::size_t k : {0, 1, 2, 4, 5})
    EXPECT_NEAR(interior_angle(l, k), M_PI / 2, tol);
  EXPECT_NEAR(interior_angle(l, 3), 3 * M_PI / 2, tol);
  // Right isosceles triangle: pi/2 at the right angle, pi/4 at the others.
  const std::vector<Point> triangle{{0, 0}, {1, 0}, {0, 1}};
  EXPECT_NEAR(interior_angle(triangle, 0), M_PI / 2, tol);
  EXPECT_NEAR(interior_angle(triangle, 1), M_PI / 4, tol);
  EXPECT_NEAR(interior_angle(triangle, 2), M_PI / 4, tol);
  // A vertex in the middle of a straight side.
  EXPECT_NEAR(interior_angle({{0, 0}, {1, 0}, {2, 0}, {1, 1}}, 1), M_PI, tol);
}

TEST(NarrowPhase, SeparatedPolygonsGiveNoPairs)
{
  // Gap 0.021 m > d0 = 0.02 m: above, to the side and across a corner.
  const std::vector<Point> a = rectangle(0, 0, 1, 1);
  EXPECT_TRUE(find_vertex_edge_pairs(a, rectangle(0, 1.021, 1, 1), 0.02, 0.01).empty());
  EXPECT_TRUE(find_vertex_edge_pairs(a, rectangle(1.021, 0.3, 1, 1), 0.02, 0.01).empty());
  EXPECT_TRUE(find_vertex_edge_pairs(a, rectangle(1.015, 1.015, 1, 1), 0.02, 0.01).empty());
}

TEST(NarrowPhase, TriangleTipAboveEdgeMiddle)
{
  // Square a = [0, 1]^2; triangle b with its tip (vertex 0) 0.01 m above the middle of a's top
  // edge 2, (1, 1) -> (0, 1): ratio = (1 - 0.5) / 1 = 0.5, distance = 1.01 - 1 = +0.01. The
  // tip's legs (+-1, 1)/sqrt(2) are 45 degrees off the edge: vertex_edge.
  const std::vector<Point> tip{{0.5, 1.01}, {1.0, 1.51}, {0.0, 1.51}};
  expect_pairs_both_ways(rectangle(0, 0, 1, 1), tip, 0.02, 0.01,
                         {{1, 0, 2, 0.5, 0.01, ContactKind::vertex_edge}});
}

TEST(NarrowPhase, TriangleTipPenetratingEdge)
{
  // The same tip 0.005 m below the top edge: distance = 0.995 - 1 = -0.005.
  const std::vector<Point> tip{{0.5, 0.995}, {1.0, 1.495}, {0.0, 1.495}};
  expect_pairs_both_ways(rectangle(0, 0, 1, 1), tip, 0.02, 0.01,
                         {{1, 0, 2, 0.5, -0.005, ContactKind::vertex_edge}});
}

TEST(NarrowPhase, WedgePointingIntoTheEdgesPolygonGivesNoPair)
{
  // Triangle tip 0.005 m above a's top edge (within d0) but its legs (-+0.2, -0.505) point down,
  // into the square: the wedge condition fails, so the tip is no contact. Every other vertex is
  // at least 0.3 m from the other polygon.
  const std::vector<Point> inside_out{{0.5, 1.005}, {0.3, 0.5}, {0.7, 0.5}};
  EXPECT_TRUE(find_vertex_edge_pairs(rectangle(0, 0, 1, 1), inside_out, 0.01, 0.01).empty());
  EXPECT_TRUE(find_vertex_edge_pairs(inside_out, rectangle(0, 0, 1, 1), 0.01, 0.01).empty());
}

TEST(NarrowPhase, VertexBesideAnAcuteEndIsNoPenetrationOfThatEdge)
{
  // b: a triangle with a 26.6 deg corner at (0, 0): edge 0 (0, 0) -> (1, 0) (normal -y), edge 2
  // (1, 0.5) -> (0, 0) (normal (-1, 2) / sqrt(5)). a's tip p = (0.006, 0.0035) is 6.95 mm from
  // the corner (beyond d0 = 6 mm), 3.5 mm behind edge 0's line, but 0.5 mm / sqrt(1.25) =
  // 0.447 mm in front of edge 2's: outside b, whose edge 2 it faces. Its legs (-1, -0.1) and
  // (-1, -0.4) keep a above edge 2's line. The one pair: p on edge 2, ratio (0.994 + 0.24825) /
  // 1.25 = 0.9938, distance 0.001 / sqrt(5); p on edge 0 at -3.5 mm (a tunnel's falling block
  // met it: a new contact 3.8 mm deep between blocks 0.3 mm apart) is none.
  const Point p(0.006, 0.0035);
  const std::vector<Point> a{p, p + Vector2(-1.0, -0.1), p + Vector2(-1.0, -0.4)};
  const std::vector<Point> b{{0, 0}, {1, 0}, {1, 0.5}};
  expect_pairs_both_ways(a, b, 0.006, 0.01,
                         {{0, 0, 2, 0.9938, 0.001 / std::sqrt(5.0), ContactKind::vertex_edge}});
}

TEST(NarrowPhase, CornersOverlappingAlongAJointPairOnlyWithTheJointsEdges)
{
  // b = [0, 1] x [-1, 0], its corner w = (0, 0) between top edge 2, (1, 0) -> (0, 0) (normal
  // +y), and left edge 3, (0, 0) -> (0, -1) (normal -x). a = [-0.994, 0.006] x [-0.0005, 0.9995]
  // on top of it, their corners overlapping along the joint y = 0 by 6 mm: a's corner p =
  // (0.006, -0.0005) is 0.5 mm behind edge 2, 6 mm behind edge 3's line and 6.02 mm from w
  // (beyond d0 = 6.01 mm, so no vertex-vertex pair). It entered through edge 2: ratio 0.994,
  // distance -0.5 mm, a leg along it (edge_edge). On edge 3 it would be 6 mm deep (a tunnel's
  // pair of blocks, cornered so at 4.95 m/s, failed with such a contact at dt_min). Likewise w
  // on a's bottom edge 0 only, not on a's right edge 1.
  const std::vector<Point> a = rectangle(-0.994, -0.0005, 1, 1);
  const std::vector<Point> b = rectangle(0, -1, 1, 1);
  expect_pairs_both_ways(a, b, 0.00601, 0.01,
                         {{0, 1, 2, 0.994, -0.0005, ContactKind::edge_edge},
                          {1, 3, 0, 0.994, -0.0005, ContactKind::edge_edge}});
}

TEST(NarrowPhase, AlignedStackedSquaresGiveOnePairPerCorner)
{
  // a = [0, 1]^2, b = [0, 1] x [1.004, 2.004]: corners a2 = (1, 1) ~ b1 and a3 = (0, 1) ~ b0,
  // 0.004 m apart, all convex. For (a2, b1): a2 enters b's edge 0 (normal -y, distance 0.004) and
  // b1 enters a's edge 2 (normal +y, distance 0.004); the side edges fail the wedge condition
  // (a2's leg (-1, 0) against normal +x). Exact tie, so a's vertex wins: a2 on b's edge 0,
  // (0, 1.004) -> (1, 1.004), ratio 1. Likewise a3 on b's edge 0 with ratio 0. Vertex-edge
  // pairs are excluded because every vertex is within d0 of the ends of the nearby edges.
  const std::vector<Point> a = rectangle(0, 0, 1, 1);
  const std::vector<Point> b = rectangle(0, 1.004, 1, 1);
  expect_pairs(find_vertex_edge_pairs(a, b, 0.01, 0.01),
               {{0, 2, 0, 1.0, 0.004, ContactKind::vertex_vertex},
                {0, 3, 0, 0.0, 0.004, ContactKind::vertex_vertex}});
  // Swapped, the tie goes to b's corners on a's top edge 2, (1, 1) -> (0, 1): the same contact
  // line, not the mirror image (see find_vertex_edge_pairs).
  expect_pairs(find_vertex_edge_pairs(b, a, 0.01, 0.01),
               {{0, 0, 2, 1.0, 0.004, ContactKind::vertex_vertex},
                {0, 1, 2, 0.0, 0.004, ContactKind::vertex_vertex}});
}

TEST(NarrowPhase, BrickOffsetByHalfGivesTwoEdgeToEdgePairs)
{
  // Brick b = [0.5, 1.5] x [1, 2] on a = [0, 1]^2: b0 = (0.5, 1) lies on a's top edge 2,
  // (1, 1) -> (0, 1), ratio (1 - 0.5) / 1 = 0.5; a2 = (1, 1) lies on b's bottom edge 0,
  // (0.5, 1) -> (1.5, 1), ratio 0.5. Both distances 0; each corner has a leg along the edge.
  expect_pairs_both_ways(
      rectangle(0, 0, 1, 1), rectangle(0.5, 1, 1, 1), 0.01, 0.01,
      {{0, 2, 0, 0.5, 0.0, ContactKind::edge_edge}, {1, 0, 2, 0.5, 0.0, ContactKind::edge_edge}});
}

TEST(NarrowPhase, AngleToleranceDecidesEdgeToEdge)
{
  // The brick of the previous test turned by theta = 0.002 rad about its corner b0 = (0.5, 1).
  // a2 = (1, 1) is then 0.5 sin(theta) outside b's bottom edge at ratio 0.5 cos(theta), and its
  // leg (-1, 0) has component -sin(theta) = -0.002 along that edge's normal (sin theta, -cos
  // theta); b0's leg (cos theta, sin theta) makes angle theta with a's top edge.
  const double theta = 0.002;
  const Point b0(0.5, 1);
  const Vector2 t(std::cos(theta), std::sin(theta)), up(-std::sin(theta), std::cos(theta));
  const std::vector<Point> a = rectangle(0, 0, 1, 1);
  const std::vector<Point> b{b0, b0 + t, b0 + t + up, b0 + up};
  // Tolerance 0.01 rad > theta: both corners pair, edge to edge.
  expect_pairs_both_ways(
      a, b, 0.01, 0.01,
      {{0, 2, 0, 0.5 * std::cos(theta), 0.5 * std::sin(theta), ContactKind::edge_edge},
       {1, 0, 2, 0.5, 0.0, ContactKind::edge_edge}});
  // Tolerance 0.001 rad < theta: a2's wedge dips into b's edge line (fails), b0 is a plain
  // vertex on a's edge.
  expect_pairs_both_ways(a, b, 0.01, 0.001, {{1, 0, 2, 0.5, 0.0, ContactKind::vertex_edge}});
}

TEST(NarrowPhase, SquareCornerInConcaveCornerPairsWithBothFaces)
{
  // Square b = [0.998, 1.498] x [0.999, 1.499] pushed into the L's concave corner (1, 1): it
  // penetrates the face y = 1 (a's edge 2, (2, 1) -> (1, 1)) by 0.001 m and the face x = 1
  // (a's edge 3, (1, 1) -> (1, 2)) by 0.002 m.
  // - b0 = (0.998, 0.999) is 0.0022 m from the concave vertex: one pair per face,
  //   on edge 2 ratio (2 - 0.998) / 1 = 1.002 -> 1, distance -0.001;
  //   on edge 3 ratio (0.999 - 1) / 1 -> 0, distance -0.002.
  // - b1 = (1.498, 0.999) on edge 2: ratio 2 - 1.498 = 0.502, distance -0.001, leg along it.
  // - b3 = (0.998, 1.499) on edge 3: ratio 1.499 - 1 = 0.499, distance -0.002, leg along it.
  expect_pairs_both_ways(l_shape(), rectangle(0.998, 0.999, 0.5, 0.5), 0.01, 0.01,
                         {{1, 0, 2, 1.0, -0.001, ContactKind::vertex_vertex},
                          {1, 0, 3, 0.0, -0.002, ContactKind::vertex_vertex},
                          {1, 1, 2, 0.502, -0.001, ContactKind::edge_edge},
                          {1, 3, 3, 0.499, -0.002, ContactKind::edge_edge}});
}

TEST(NarrowPhase, ConvexVertexAtStraightVertexTakesTheEdgeBelowIt)
{
  // a: unit square with an extra vertex (0.5, 1) in its top side (straight), splitting it into
  // edge 2, (1, 1) -> (0.5, 1), and edge 3, (0.5, 1) -> (0, 1), both of length 0.5. b's tip
  // (0.503, 1.004) is 0.005 m from the straight vertex and projects onto edge 2 at ratio
  // (1 - 0.503) / 0.5 = 0.994 (onto edge 3 at -0.006, clamped 0): the pair is on edge 2,
  // distance 0.004.
  const std::vector<Point> a{{0, 0}, {1, 0}, {1, 1}, {0.5, 1}, {0, 1}};
  const std::vector<Point> tip{{0.503, 1.004}, {1.003, 1.504}, {0.003, 1.504}};
  expect_pairs_both_ways(a, tip, 0.01, 0.01, {{1, 0, 2, 0.994, 0.004, ContactKind::vertex_vertex}});
}

TEST(NarrowPhase, DiamondTipsTouchingGiveOneEntrancePair)
{
  // a: rhombus with the sharp tip a1 = (1, 0), legs (-1, -+0.5)/sqrt(1.25); b: square diamond
  // with its tip b3 = (1.006, 0.002), legs (1, +-1)/sqrt(2). Candidate entrance lines:
  // - a1 on b's edge 2 (normal (-1, 1)/sqrt(2)): distance (0.006 - 0.002)/sqrt(2), wedge holds;
  // - a1 on b's edge 3 (normal (-1, -1)/sqrt(2)): distance (0.006 + 0.002)/sqrt(2), holds;
  // - b3 on a's edges 0 and 1 (normals (0.5, -+1)/sqrt(1.25)): b's blunt wedge has a leg
  //   -0.5/sqrt(2.5) below both lines, so the wedge condition fails.
  // The largest valid distance: a1 on b's edge 3, (1.006, 0.002) -> (2.006, -0.998), ratio
  // (-0.006 + 0.002)/2 -> 0.
  const std::vector<Point> a{{0, -0.5}, {1, 0}, {0, 0.5}, {-1, 0}};
  const std::vector<Point> b{{2.006, -0.998}, {3.006, 0.002}, {2.006, 1.002}, {1.006, 0.002}};
  expect_pairs_both_ways(a, b, 0.01, 0.01,
                         {{0, 1, 3, 0.0, 0.008 / std::sqrt(2.0), ContactKind::vertex_vertex}});
}

TEST(NarrowPhase, EqualDiamondsTieGoesToVertexOfA)
{
  // Point-symmetric tips a1 = (1, 0) and b3 = (1.004, 0): all four candidate lines are entered
  // at distance 0.004/sqrt(2). The tie goes to a's vertex and then the smaller edge: a1 on b's
  // edge 2, (2.004, 1) -> (1.004, 0), ratio (2 + 0.004)/2 -> 1.
  const std::vector<Point> a{{0, -1}, {1, 0}, {0, 1}, {-1, 0}};
  const std::vector<Point> b{{2.004, -1}, {3.004, 0}, {2.004, 1}, {1.004, 0}};
  expect_pairs(find_vertex_edge_pairs(a, b, 0.01, 0.01),
               {{0, 1, 2, 1.0, 0.004 / std::sqrt(2.0), ContactKind::vertex_vertex}});
}

TEST(NarrowPhase, InterlockedWedgesStillGiveOnePair)
{
  // b's tip b0 = (1.002, 1.001) sits just outside a's corner a2 = (1, 1) with legs
  // (-1, 0.3) and (0.3, -1) (normalized), so a's corner lies inside b's wedge: no candidate
  // passes the wedge condition (a2 against b's edges: legs below the lines by 0.96 and 0.29;
  // b0 against a's edges 1 and 2: a leg 0.958 below each). The largest signed distance wins:
  // b0 on a's edge 1, (1, 0) -> (1, 1), distance 1.002 - 1 = 0.002, ratio 1.001 -> 1
  // (the other lines: b0 from a's edge 2 0.001; a2 from b's edges -0.0016 and -0.0022).
  const std::vector<Point> b{{1.002, 1.001}, {0.002, 1.301}, {1.302, 0.001}};
  expect_pairs_both_ways(rectangle(0, 0, 1, 1), b, 0.01, 0.01,
                         {{1, 0, 1, 1.0, 0.002, ContactKind::vertex_vertex}});
}

TEST(NarrowPhase, RejectsBadInput)
{
  const std::vector<Point> square = rectangle(0, 0, 1, 1);
  std::vector<Point> clockwise = square;
  std::reverse(clockwise.begin(), clockwise.end());
  EXPECT_THROW(find_vertex_edge_pairs(clockwise, square, 0.01, 0.01), std::invalid_argument);
  EXPECT_THROW(find_vertex_edge_pairs(square, {{0, 0}, {1, 0}}, 0.01, 0.01), std::invalid_argument);
  EXPECT_THROW(find_vertex_edge_pairs(square, square, 0.0, 0.01), std::invalid_argument);
  EXPECT_THROW(find_vertex_edge_pairs(square, square, 0.01, -0.01), std::invalid_argument);
}

TEST(NarrowPhase, FeaturesServeEveryPairOfABlock)
{
  // Each block's features are computed once per step and serve all its pairs: the pairs found
  // from them are those of the search on the polygons, bit for bit, in any order of pairs.
  const double d0 = 0.01, angle_tolerance = 0.01;
  const std::vector<std::vector<Point>> polygons{
      rectangle(0, 0, 1, 1),
      {{1.005, 0.2}, {3.005, 0.2}, {3.005, 1.2}, {2.005, 1.2}, {2.005, 2.2}, {1.005, 2.2}},
      {{0.3, 1.004}, {0.9, 1.004}, {0.6, 1.5}}};
  std::vector<PolygonFeatures> features(polygons.size());
  for (std::size_t k = 0; k < polygons.size(); ++k)
    compute_polygon_features(polygons[k], angle_tolerance, features[k]);
  NarrowPhaseWorkspace work;
  std::size_t n_found = 0;
  for (const auto& [i, j] : {std::pair{0, 1}, {0, 2}, {1, 2}, {1, 0}})
  {
    SCOPED_TRACE("polygons " + std::to_string(i) + " and " + std::to_string(j));
    const std::vector<VertexEdgePair> expected =
        find_vertex_edge_pairs(polygons[i], polygons[j], d0, angle_tolerance);
    find_vertex_edge_pairs(features[i], features[j], d0, work);
    ASSERT_EQ(work.pairs.size(), expected.size());
    for (std::size_t k = 0; k < expected.size(); ++k)
    {
      EXPECT_EQ(work.pairs[k].vertex_polygon, expected[k].vertex_polygon);
      EXPECT_EQ(work.pairs[k].vertex, expected[k].vertex);
      EXPECT_EQ(work.pairs[k].edge, expected[k].edge);
      EXPECT_EQ(work.pairs[k].ratio, expected[k].ratio);
      EXPECT_EQ(work.pairs[k].distance, expected[k].distance);
      EXPECT_EQ(work.pairs[k].kind, expected[k].kind);
    }
    n_found += expected.size();
  }
  EXPECT_GE(n_found, 4U); // the square meets the L-shape and the triangle on both sides

  // The L-shape's features: one concave vertex, the outward normals, the box.
  const PolygonFeatures& l = features[1];
  for (std::size_t k = 0; k < 6; ++k)
    EXPECT_EQ(l.shapes[k], k == 3 ? VertexShape::concave : VertexShape::convex) << k;
  EXPECT_NEAR(l.edges[2].normal.y(), 1.0, tol);
  EXPECT_NEAR(l.edges[3].normal.x(), 1.0, tol);
  EXPECT_NEAR(l.edges[0].length, 2.0, tol);
  EXPECT_NEAR(l.legs[0][1].x(), 1.0, tol);
  EXPECT_EQ(l.lower, Point(1.005, 0.2));
  EXPECT_EQ(l.upper, Point(3.005, 2.2));

  // Features of another angle tolerance do not mix.
  PolygonFeatures other;
  compute_polygon_features(polygons[0], 0.02, other);
  EXPECT_THROW(find_vertex_edge_pairs(other, features[1], d0, work), std::invalid_argument);
  EXPECT_THROW(compute_polygon_features({{0, 0}, {1, 0}}, angle_tolerance, other),
               std::invalid_argument);
}

TEST(NarrowPhase, PairsAtExactlyTheSearchDistance)
{
  // A triangle's apex exactly d0 = 0.25 m above the square's top edge (binary fractions: the
  // distance is exact) pairs with it; one ulp less of d0 and it does not. The search skips edges
  // whose box the vertex is beyond by more than d0 before it computes distances: that
  // shortcut must not move the boundary.
  const std::vector<Point> square = rectangle(0, 0, 1, 1);
  const std::vector<Point> triangle{{0.5, 1.25}, {1.0, 2.0}, {0.0, 2.0}};
  expect_pairs_both_ways(square, triangle, 0.25, 0.01,
                         {{1, 0, 2, 0.5, 0.25, ContactKind::vertex_edge}});
  EXPECT_TRUE(find_vertex_edge_pairs(square, triangle, std::nextafter(0.25, 0.0), 0.01).empty());
}
