// Rock mass generation: areas, overlaps, joint spacing, persistence, openings, slivers, seeds,
// short edges and straight vertices.
#include "common/input_error.h"
#include "dda/geometry.h"
#include "dda/rock_mass.h"
#include "joint_sets.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <random>

using namespace ddafem::dda;

namespace
{
std::vector<Point> rectangle(double x0, double y0, double x1, double y1)
{
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

using test_models::persistent_set;

JointSet non_persistent_set(double dip, double spacing, double trace_length, double bridge)
{
  JointSet set = persistent_set(dip, spacing);
  set.trace_length = trace_length;
  set.bridge = bridge;
  return set;
}

Opening circle(const Point& center, double radius)
{
  Opening o;
  o.shape = Opening::Shape::circle;
  o.center = center;
  o.radius = radius;
  return o;
}

double mean_spacing(const RockMassDescription& d)
{
  double sum = 0.0;
  for (const JointSet& set : d.joint_sets)
    sum += set.spacing;
  return sum / static_cast<double>(d.joint_sets.size());
}

double sum_of_areas(const RockMassResult& r)
{
  double sum = 0.0;
  for (const RockMassBlock& b : r.blocks)
    sum += signed_area(b.vertices);
  return sum;
}

/// Extent of a polygon along a unit direction [m].
std::pair<double, double> extent(const std::vector<Point>& vertices, const Vector2& direction)
{
  double lo = vertices.front().dot(direction), hi = lo;
  for (const Point& v : vertices)
  {
    lo = std::min(lo, v.dot(direction));
    hi = std::max(hi, v.dot(direction));
  }
  return {lo, hi};
}

/// A 40 m x 40 m rock mass with two joint sets (one non-persistent) and three openings: a
/// circle, a horseshoe and a triangle.
RockMassDescription tunnel_scene()
{
  RockMassDescription d;
  d.region = rectangle(-20, -20, 20, 20);
  d.joint_sets = {persistent_set(30, 2.5, 0.3), non_persistent_set(110, 3.0, 8.0, 2.0)};
  d.joint_sets[0].perturbation.spacing = 0.2;
  d.joint_sets[1].perturbation.position = 0.3;
  d.seed = 7;
  Opening horseshoe;
  horseshoe.shape = Opening::Shape::horseshoe;
  horseshoe.center = {10, -12};
  horseshoe.width = 5;
  horseshoe.wall_height = 2;
  Opening triangle;
  triangle.shape = Opening::Shape::polygon;
  triangle.vertices = {{-15, 10}, {-9, 12}, {-14, 16}};
  d.openings = {circle({0, 0}, 4), horseshoe, triangle};
  return d;
}

/// Pairs of blocks whose bounding boxes overlap.
std::vector<std::pair<std::size_t, std::size_t>> nearby_pairs(const RockMassResult& r)
{
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < r.blocks.size(); ++i)
    for (std::size_t j = i + 1; j < r.blocks.size(); ++j)
    {
      const std::vector<Point>&a = r.blocks[i].vertices, &b = r.blocks[j].vertices;
      const auto [ax0, ax1] = extent(a, {1, 0});
      const auto [bx0, bx1] = extent(b, {1, 0});
      const auto [ay0, ay1] = extent(a, {0, 1});
      const auto [by0, by1] = extent(b, {0, 1});
      if (!(ax1 < bx0 || bx1 < ax0 || ay1 < by0 || by1 < ay0))
        pairs.emplace_back(i, j);
    }
  return pairs;
}

/// The blocks tile the region without the openings along matching edges: every stretch of every
/// block edge is shared (collinear, opposite direction, as dda::find_joints pairs them) with
/// another block's edge, the region's boundary or an opening's. With the areas adding up this
/// leaves no gap and no overlap.
void expect_matching_edges(const RockMassResult& r, const std::vector<Point>& region)
{
  const double tol = 1e-9;
  std::vector<Point> clockwise_region = region;
  if (signed_area(clockwise_region) > 0.0)
    std::reverse(clockwise_region.begin(), clockwise_region.end());
  std::vector<std::vector<double>> covered(r.blocks.size());
  for (std::size_t i = 0; i < r.blocks.size(); ++i)
  {
    covered[i].assign(r.blocks[i].vertices.size(), 0.0);
    const auto cover = [&](const std::vector<Point>& other)
    {
      for (const SharedSegment& s : shared_segments(r.blocks[i].vertices, other, tol))
        covered[i][s.a_edge] += (s.q - s.p).norm();
    };
    cover(clockwise_region);
    for (const std::vector<Point>& o : r.openings)
      cover(o);
  }
  for (const auto& [i, j] : nearby_pairs(r))
    for (const SharedSegment& s : shared_segments(r.blocks[i].vertices, r.blocks[j].vertices, tol))
    {
      covered[i][s.a_edge] += (s.q - s.p).norm();
      covered[j][s.b_edge] += (s.q - s.p).norm();
    }
  for (std::size_t i = 0; i < r.blocks.size(); ++i)
  {
    const std::vector<Point>& v = r.blocks[i].vertices;
    for (std::size_t k = 0; k < v.size(); ++k)
      EXPECT_NEAR(covered[i][k], (v[(k + 1) % v.size()] - v[k]).norm(), 1e-9)
          << "block " << i << " edge " << k << " from " << v[k].transpose();
  }
}

/// Shortest edge of any block [m].
double shortest_edge(const RockMassResult& r)
{
  double shortest = std::numeric_limits<double>::infinity();
  for (const RockMassBlock& b : r.blocks)
    for (std::size_t k = 0; k < b.vertices.size(); ++k)
      shortest =
          std::min(shortest, (b.vertices[(k + 1) % b.vertices.size()] - b.vertices[k]).norm());
  return shortest;
}

/// Largest overlap of two blocks, or of a block and an opening [m^2].
double largest_overlap(const RockMassResult& r)
{
  double largest = 0.0;
  for (const auto& [i, j] : nearby_pairs(r))
    largest = std::max(largest, overlap_area(r.blocks[i].vertices, r.blocks[j].vertices));
  for (const RockMassBlock& b : r.blocks)
    for (const std::vector<Point>& o : r.openings)
      largest = std::max(largest, overlap_area(b.vertices, o));
  return largest;
}

/// Vertices off the region's and the openings' boundaries where every block that has them is
/// straight within `degrees` of 180 (both blocks at a vertex only two blocks share): tidy()
/// removes them.
std::size_t n_straight_vertices(const RockMassResult& r, const std::vector<Point>& region,
                                double degrees)
{
  std::map<std::pair<double, double>, bool> all_straight; // by position
  for (const RockMassBlock& b : r.blocks)
  {
    const std::vector<Point>& v = b.vertices;
    for (std::size_t k = 0; k < v.size(); ++k)
    {
      const Vector2 in = v[k] - v[(k + v.size() - 1) % v.size()];
      const Vector2 out = v[(k + 1) % v.size()] - v[k];
      const double turn = std::atan2(in.x() * out.y() - in.y() * out.x(), in.dot(out));
      const auto [it, inserted] = all_straight.try_emplace({v[k].x(), v[k].y()}, true);
      it->second = it->second && std::abs(turn) <= degrees * M_PI / 180.0;
    }
  }
  std::size_t n = 0;
  for (const auto& [position, straight] : all_straight)
  {
    const Point p(position.first, position.second);
    bool on_boundary = locate_point(region, p, 1e-9) == PointLocation::on_boundary;
    for (const std::vector<Point>& o : r.openings)
      on_boundary = on_boundary || locate_point(o, p, 1e-9) == PointLocation::on_boundary;
    n += straight && !on_boundary;
  }
  return n;
}

/// Every block simple, anticlockwise and without a vertex between two collinear edges.
void expect_valid_polygons(const RockMassResult& r)
{
  for (std::size_t i = 0; i < r.blocks.size(); ++i)
  {
    const std::vector<Point>& v = r.blocks[i].vertices;
    EXPECT_TRUE(is_simple_polygon(v)) << "block " << i;
    EXPECT_GT(signed_area(v), 0.0) << "block " << i;
    // The exact area against the rounded vertices' (which differ by rounding, ~1e-15 m^2).
    EXPECT_NEAR(signed_area(v), r.blocks[i].area, 1e-12 * r.blocks[i].area + 1e-13)
        << "block " << i;
    for (std::size_t k = 0; k < v.size(); ++k)
    {
      const Vector2 a = v[k] - v[(k + v.size() - 1) % v.size()];
      const Vector2 b = v[(k + 1) % v.size()] - v[k];
      const double sine = (a.x() * b.y() - a.y() * b.x()) / (a.norm() * b.norm());
      EXPECT_GT(std::abs(sine), 1e-12) << "block " << i << " vertex " << k << " is straight";
    }
  }
}
} // namespace

TEST(RockMass, AreasAddUpToRegionMinusOpenings)
{
  const RockMassDescription d = tunnel_scene();
  const RockMassResult r = generate_blocks(d);
  ASSERT_EQ(r.openings.size(), 3u);
  double openings = 0.0;
  for (const std::vector<Point>& o : r.openings)
    openings += signed_area(o); // the polygons as excavated (anticlockwise: positive)
  const double expected = 40.0 * 40.0 - openings;
  const double sum = sum_of_areas(r);
  std::cout << r.statistics.n_blocks << " blocks, " << r.statistics.n_merged << " slivers merged, "
            << r.statistics.n_island_cuts << " island cuts; area error "
            << (sum - expected) / expected << " (relative)\n";
  EXPECT_NEAR(sum, expected, 1e-9 * expected);
  EXPECT_NEAR(r.statistics.total_area, expected, 1e-9 * expected);
  EXPECT_NEAR(r.statistics.region_area, 1600.0, 1e-12);
  EXPECT_NEAR(r.statistics.excavated_area, openings, 1e-9 * openings);
  EXPECT_GT(r.statistics.n_blocks, 150u);
  expect_valid_polygons(r);
}

TEST(RockMass, NoTwoBlocksOverlap)
{
  // The blocks are exact faces of the arrangement; only rounding their vertices to double can
  // make them overlap. A vertex moves by at most one ulp of 20 m (3.6e-15 m), and a vertex moved
  // across a neighbour's edge (at most 10 m long here) overlaps it by less than
  // 10 m x 3.6e-15 m = 3.6e-14 m^2.
  const double rounding = 10.0 * 20.0 * std::numeric_limits<double>::epsilon();
  const RockMassResult r = generate_blocks(tunnel_scene());
  std::size_t n_checked = 0, n_touching = 0;
  double largest = 0.0;
  for (const auto& [i, j] : nearby_pairs(r))
  {
    ++n_checked;
    const double overlap = overlap_area(r.blocks[i].vertices, r.blocks[j].vertices);
    n_touching += overlap > 0.0;
    largest = std::max(largest, overlap);
    EXPECT_LT(overlap, rounding) << "blocks " << i << " and " << j;
  }
  // Nor does any block reach into an opening.
  for (std::size_t i = 0; i < r.blocks.size(); ++i)
    for (const std::vector<Point>& o : r.openings)
    {
      const double overlap = overlap_area(r.blocks[i].vertices, o);
      largest = std::max(largest, overlap);
      EXPECT_LT(overlap, rounding) << "block " << i;
    }
  std::cout << n_checked << " pairs with overlapping bounding boxes; " << n_touching
            << " overlap by rounding, at most " << largest << " m^2 (bound " << rounding
            << " m^2)\n";
}

TEST(RockMass, SinglePersistentSetGivesStripsOfTheSpacing)
{
  // Dip 30 deg, s = 1.5 m across a 20 m square: every strip between two joints is s wide
  // (normal to the set); only the first and last strip, cut by the region's corners, are not.
  const double s = 1.5;
  RockMassDescription d;
  d.region = rectangle(0, 0, 20, 20);
  d.joint_sets = {persistent_set(30, s, 0.2)};
  d.slivers.min_area = 0.0; // keep the corner pieces
  const RockMassResult r = generate_blocks(d);
  const Vector2 normal(-std::sin(M_PI / 6), std::cos(M_PI / 6));
  const auto [lo, hi] = extent(d.region, normal);
  // Lines n.x = 0.2 + k s inside [lo, hi].
  const double n_lines = std::floor((hi - 0.2) / s) - std::ceil((lo - 0.2) / s) + 1;
  EXPECT_EQ(static_cast<double>(r.blocks.size()), n_lines + 1);
  std::size_t n_interior = 0;
  for (const RockMassBlock& b : r.blocks)
  {
    const auto [b_lo, b_hi] = extent(b.vertices, normal);
    if (std::abs(b_lo - lo) < 1e-9 || std::abs(b_hi - hi) < 1e-9)
      continue; // an edge strip
    ++n_interior;
    EXPECT_NEAR(b_hi - b_lo, s, 1e-9);
    EXPECT_EQ(b.joint_sets, std::vector<std::size_t>{0});
    EXPECT_TRUE(b.region_boundary);
  }
  EXPECT_EQ(n_interior, r.blocks.size() - 2);
}

TEST(RockMass, PerturbedSpacingKeepsTheMeanSpacing)
{
  // Strips of a set at dip 30 deg across a 400 m x 20 m region; gaps s (1 + a xi). The mean of
  // N gaps has the standard deviation s a / sqrt(3 N) (uniform xi in [-1, 1], variance 1/3) or
  // s a / sqrt(N) (normal, whose truncation at 1 + a xi < 0.1 is 7 standard deviations away for
  // a = 0.13 and negligible). 4 standard deviations: a false alarm once in 16000 seeds.
  const double s = 2.0;
  for (const Distribution distribution : {Distribution::uniform, Distribution::normal})
  {
    const double a = distribution == Distribution::uniform ? 0.3 : 0.13;
    RockMassDescription d;
    d.region = rectangle(0, 0, 400, 20);
    d.joint_sets = {persistent_set(30, s)};
    d.joint_sets[0].perturbation.spacing = a;
    d.joint_sets[0].perturbation.distribution = distribution;
    d.slivers.min_area = 0.0;
    d.seed = 2024;
    const RockMassResult r = generate_blocks(d);
    const Vector2 normal(-std::sin(M_PI / 6), std::cos(M_PI / 6));
    const auto [lo, hi] = extent(d.region, normal);
    std::vector<double> widths;
    for (const RockMassBlock& b : r.blocks)
    {
      const auto [b_lo, b_hi] = extent(b.vertices, normal);
      if (std::abs(b_lo - lo) > 1e-9 && std::abs(b_hi - hi) > 1e-9)
        widths.push_back(b_hi - b_lo);
    }
    const double n = static_cast<double>(widths.size());
    double mean = 0.0, variance = 0.0;
    for (const double w : widths)
      mean += w / n;
    for (const double w : widths)
      variance += (w - mean) * (w - mean) / (n - 1);
    const double sigma = distribution == Distribution::uniform ? s * a / std::sqrt(3.0) : s * a;
    std::cout << (distribution == Distribution::uniform ? "uniform" : "normal") << ": " << n
              << " gaps, mean " << mean << " m (expected " << s << " +- "
              << 4 * sigma / std::sqrt(n) << "), standard deviation " << std::sqrt(variance)
              << " m (expected " << sigma << ")\n";
    EXPECT_GT(n, 80.0);
    EXPECT_NEAR(mean, s, 4.0 * sigma / std::sqrt(n));
    // The sample standard deviation of n draws is within 25% of sigma (n > 80: its relative
    // standard error is about 1 / sqrt(2 n) < 8%).
    EXPECT_NEAR(std::sqrt(variance), sigma, 0.25 * sigma);
    if (distribution == Distribution::uniform)
    {
      for (const double w : widths)
        EXPECT_GE(w, s * (1 - a) - 1e-9);
    }
  }
}

TEST(RockMass, TwoOrthogonalPersistentSetsGiveTheGrid)
{
  // Joints every 1 m in x and y over a 10 m x 6 m region; the lines at y = 0 and y = 6 lie on
  // the boundary, so the blocks are the 10 x 6 unit squares.
  RockMassDescription d;
  d.region = rectangle(0, 0, 10, 6);
  d.joint_sets = {persistent_set(0, 1.0), persistent_set(90, 1.0)};
  const RockMassResult r = generate_blocks(d);
  ASSERT_EQ(r.blocks.size(), 60u);
  for (const RockMassBlock& b : r.blocks)
  {
    EXPECT_EQ(b.vertices.size(), 4u);
    EXPECT_NEAR(b.area, 1.0, 1e-12);
    // The lines x = 0, 10 and y = 0, 6 of the sets run along the region's boundary.
    EXPECT_EQ(b.joint_sets, (std::vector<std::size_t>{0, 1}));
  }
  // Bottom row first: block 0 is the square at the origin, block 12 is the third of row two.
  EXPECT_EQ(r.blocks[0].vertices, rectangle(0, 0, 1, 1));
  EXPECT_EQ(r.blocks[12].vertices, rectangle(2, 1, 3, 2));
  EXPECT_EQ(r.blocks[12].joint_sets, (std::vector<std::size_t>{0, 1}));
  EXPECT_FALSE(r.blocks[12].region_boundary);
  EXPECT_EQ(r.statistics.n_merged, 0u);
  EXPECT_TRUE(r.slivers.empty());

  // Offset by half a spacing: 11 x 7 blocks, the outer ones half or quarter squares.
  d.joint_sets = {persistent_set(0, 1.0, 0.5), persistent_set(90, 1.0, 0.5)};
  d.slivers.min_area = 0.0;
  EXPECT_EQ(generate_blocks(d).blocks.size(), 77u);
}

TEST(RockMass, NonPersistentJointsLeaveBridges)
{
  // One non-persistent set alone cuts nothing off: every trace ends in intact rock, so the
  // region stays one block, its polygon the rectangle without the dangling traces.
  RockMassDescription d;
  d.region = rectangle(0, 0, 12, 6);
  d.joint_sets = {non_persistent_set(0, 1.0, 3.0, 1.0)};
  d.joint_sets[0].offset = 0.5;
  RockMassResult r = generate_blocks(d);
  ASSERT_EQ(r.blocks.size(), 1u);
  EXPECT_EQ(r.blocks[0].vertices, rectangle(0, 0, 12, 6));
  EXPECT_TRUE(r.blocks[0].joint_sets.empty());

  // With a persistent cross set, bridges join what persistent joints would separate.
  d.joint_sets = {persistent_set(0, 1.0, 0.5), persistent_set(90, 1.5, 0.25)};
  const std::size_t n_persistent = generate_blocks(d).blocks.size();
  d.joint_sets[0].trace_length = 2.0;
  d.joint_sets[0].bridge = 1.0; // persistence 2/3
  r = generate_blocks(d);
  std::cout << "persistent: " << n_persistent << " blocks; persistence 2/3: " << r.blocks.size()
            << " blocks\n";
  EXPECT_LT(r.blocks.size(), n_persistent);
  EXPECT_GT(r.blocks.size(), 1u);
  expect_valid_polygons(r);
  EXPECT_NEAR(sum_of_areas(r), 72.0, 1e-9 * 72.0);
}

TEST(RockMass, ExplicitJoints)
{
  RockMassDescription d;
  d.region = rectangle(0, 0, 4, 2);
  d.joints = {{{2, -1}, {2, 3}}, {{0, 1}, {1, 1}}}; // a cut across, and a crack from the side
  const RockMassResult r = generate_blocks(d);
  ASSERT_EQ(r.blocks.size(), 2u);
  EXPECT_EQ(r.blocks[0].vertices, rectangle(0, 0, 2, 2));
  EXPECT_EQ(r.blocks[1].vertices, rectangle(2, 0, 4, 2));
  EXPECT_TRUE(r.blocks[0].explicit_joint);
}

TEST(RockMass, CircularOpeningLosesAreaWithinTheChordError)
{
  // The inscribed N-gon misses the circle by less than its perimeter times the chord error.
  const double radius = 3.0, tolerance = 0.01;
  RockMassDescription d;
  d.region = rectangle(-10, -10, 10, 10);
  d.joint_sets = {persistent_set(45, 2.0), persistent_set(-30, 2.5)};
  d.openings = {circle({0.3, -0.2}, radius)};
  d.chord_tolerance = tolerance;
  const RockMassResult r = generate_blocks(d);
  const std::size_t n = r.openings[0].size();
  EXPECT_LE(radius * (1 - std::cos(M_PI / n)), tolerance);
  EXPECT_GT(radius * (1 - std::cos(M_PI / (n - 1))), tolerance); // the fewest sides
  const double loss = 400.0 - sum_of_areas(r);
  const double circle_area = M_PI * radius * radius;
  std::cout << n << " sides; excavated " << loss << " m^2, circle " << circle_area << " m^2, bound "
            << 2 * M_PI * radius * tolerance << " m^2\n";
  EXPECT_LT(loss, circle_area);
  EXPECT_GT(loss, circle_area - 2 * M_PI * radius * tolerance);
  for (const RockMassBlock& b : r.blocks)
    for (const Point& v : b.vertices)
      EXPECT_GE((v - Point(0.3, -0.2)).norm(), radius - tolerance - 1e-12);
  expect_valid_polygons(r);
  const auto around = std::count_if(r.blocks.begin(), r.blocks.end(),
                                    [](const RockMassBlock& b)
                                    { return b.openings == std::vector<std::size_t>{0}; });
  EXPECT_GE(around, 8);
}

TEST(RockMass, OpeningNoJointReachesIsCutOut)
{
  // An opening inside one block would make it a polygon with a hole: two vertical cuts from the
  // opening's top and bottom split it into two simple blocks.
  RockMassDescription d;
  d.region = rectangle(0, 0, 10, 8);
  d.openings = {circle({5, 4}, 2)};
  const RockMassResult r = generate_blocks(d);
  ASSERT_EQ(r.blocks.size(), 2u);
  EXPECT_EQ(r.statistics.n_island_cuts, 2u);
  expect_valid_polygons(r);
  EXPECT_NEAR(sum_of_areas(r), 80.0 - signed_area(r.openings[0]), 1e-12 * 80.0);
  // With 32 sides the circle's top and bottom vertices lie on x = 5: two mirror halves.
  EXPECT_EQ(r.openings[0].size(), 32u);
  for (const RockMassBlock& b : r.blocks)
    EXPECT_NEAR(b.area, 0.5 * (80.0 - signed_area(r.openings[0])), 1e-9);
}

TEST(RockMass, HorseshoeOpening)
{
  Opening o;
  o.shape = Opening::Shape::horseshoe;
  o.center = {1, -2}; // middle of the floor
  o.width = 6;
  o.wall_height = 2.5;
  const double tolerance = 0.005;
  const std::vector<Point> polygon = opening_polygon(o, tolerance);
  EXPECT_GT(signed_area(polygon), 0.0);
  EXPECT_TRUE(is_simple_polygon(polygon));
  // Walls and floor exact; the roof within the chord error of its semicircle.
  const double exact_area = 6 * 2.5 + 0.5 * M_PI * 9;
  EXPECT_LT(signed_area(polygon), exact_area);
  EXPECT_GT(signed_area(polygon), exact_area - M_PI * 3 * tolerance);
  EXPECT_EQ(polygon[0], Point(-2, -2));
  EXPECT_EQ(polygon[1], Point(4, -2));
  EXPECT_EQ(polygon[2], Point(4, 0.5));
  EXPECT_EQ(polygon.back(), Point(-2, 0.5));

  RockMassDescription d;
  d.region = rectangle(-10, -10, 10, 10);
  d.joint_sets = {persistent_set(20, 1.7), persistent_set(100, 2.1)};
  d.openings = {o};
  d.chord_tolerance = tolerance;
  const RockMassResult r = generate_blocks(d);
  EXPECT_NEAR(sum_of_areas(r), 400.0 - signed_area(polygon), 1e-9 * 400.0);
  expect_valid_polygons(r);
}

TEST(RockMass, SameSeedSameBlocksOtherSeedOtherBlocks)
{
  RockMassDescription d = tunnel_scene();
  d.joint_sets[0].perturbation.position = 0.2;
  d.joint_sets[1].perturbation.spacing = 0.25;
  d.joint_sets[1].perturbation.distribution = Distribution::normal;
  const RockMassResult a = generate_blocks(d);
  const RockMassResult b = generate_blocks(d);
  ASSERT_EQ(a.blocks.size(), b.blocks.size());
  for (std::size_t i = 0; i < a.blocks.size(); ++i)
    EXPECT_EQ(a.blocks[i].vertices, b.blocks[i].vertices) << "block " << i;
  d.seed += 1;
  const RockMassResult c = generate_blocks(d);
  bool differ = c.blocks.size() != a.blocks.size();
  for (std::size_t i = 0; !differ && i < a.blocks.size(); ++i)
    differ = a.blocks[i].vertices != c.blocks[i].vertices;
  EXPECT_TRUE(differ);
}

TEST(RockMass, SliversAreMergedOrReported)
{
  // Two sets 8 degrees apart make thin wedges where their traces cross.
  RockMassDescription d;
  d.region = rectangle(0, 0, 30, 20);
  d.joint_sets = {persistent_set(0, 2.0, 0.1), persistent_set(8, 2.3)};
  d.joint_sets.push_back(persistent_set(95, 3.0));
  d.slivers.min_area = 0.2;
  d.slivers.min_inscribed_radius = 0.1;
  d.slivers.action = SliverAction::report;
  const RockMassResult reported = generate_blocks(d);
  d.slivers.action = SliverAction::merge;
  const RockMassResult merged = generate_blocks(d);
  std::cout << "report: " << reported.blocks.size() << " blocks, " << reported.slivers.size()
            << " slivers; merge: " << merged.blocks.size() << " blocks, "
            << merged.statistics.n_merged << " merges, " << merged.slivers.size()
            << " slivers left\n";
  ASSERT_GT(reported.slivers.size(), 5u);
  EXPECT_EQ(reported.statistics.n_merged, 0u);
  EXPECT_EQ(reported.statistics.n_reported, reported.slivers.size());
  for (const Sliver& s : reported.slivers)
  {
    const RockMassBlock& b = reported.blocks[s.block];
    EXPECT_TRUE(b.area < 0.2 || s.inscribed_radius < 0.1);
    EXPECT_DOUBLE_EQ(s.area, b.area);
    EXPECT_NEAR((s.centroid - polygon_moments(b.vertices).centroid).norm(), 0.0, 1e-12);
  }
  EXPECT_EQ(merged.blocks.size(), reported.blocks.size() - merged.statistics.n_merged);
  EXPECT_GE(merged.statistics.n_merged, reported.slivers.size() / 2);
  EXPECT_TRUE(merged.slivers.empty());
  EXPECT_NEAR(sum_of_areas(merged), 600.0, 1e-9 * 600.0);
  EXPECT_NEAR(sum_of_areas(reported), 600.0, 1e-9 * 600.0);
  expect_valid_polygons(merged);
  for (const RockMassBlock& b : merged.blocks)
    EXPECT_GE(b.area, 0.2);
}

TEST(RockMass, DefaultSliverThresholdIsOnePercentOfTheMeanSpacingSquared)
{
  RockMassDescription d;
  d.region = rectangle(0, 0, 10, 10);
  d.joint_sets = {persistent_set(10, 1.0), persistent_set(70, 3.0)};
  const RockMassResult r = generate_blocks(d);
  EXPECT_DOUBLE_EQ(r.statistics.min_area, 0.01 * 2.0 * 2.0);
  EXPECT_GE(r.statistics.smallest_area, 0.04);
}

TEST(RockMass, BadDescriptionsAreInputErrors)
{
  RockMassDescription d;
  d.region = rectangle(0, 0, 10, 10);
  d.joint_sets = {persistent_set(10, 0.0)};
  EXPECT_THROW(generate_blocks(d), ddafem::InputError);
  d.joint_sets = {non_persistent_set(10, 1.0, std::numeric_limits<double>::infinity(), 1.0)};
  EXPECT_THROW(generate_blocks(d), ddafem::InputError);
  d.joint_sets.clear();
  d.region = {{0, 0}, {1, 1}, {1, 0}, {0, 1}}; // bow tie
  EXPECT_THROW(generate_blocks(d), ddafem::InputError);
}

TEST(RockMass, TwoThousandBlocks)
{
  // Timing: a 100 m x 100 m region with two perturbed sets and a circular opening.
  RockMassDescription d;
  d.region = rectangle(-50, -50, 50, 50);
  d.joint_sets = {persistent_set(35, 2.1), persistent_set(-50, 2.4)};
  d.joint_sets[0].perturbation.spacing = 0.2;
  d.joint_sets[1].perturbation.spacing = 0.2;
  d.openings = {circle({0, 0}, 5)};
  const auto start = std::chrono::steady_clock::now();
  const RockMassResult r = generate_blocks(d);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << r.statistics.n_blocks << " blocks from " << r.statistics.n_traces << " traces in "
            << seconds << " s; smallest " << r.statistics.smallest_area << " m^2, mean "
            << r.statistics.mean_area << " m^2, " << r.statistics.n_merged << " merged\n";
  EXPECT_GT(r.blocks.size(), 1800u);
  EXPECT_LT(r.blocks.size(), 2200u);
  EXPECT_NEAR(sum_of_areas(r), 1e4 - signed_area(r.openings[0]), 1e-9 * 1e4);
}

TEST(RockMass, RandomRockMassesGiveValidBlocks)
{
  // Robustness: star-shaped regions, one to three sets of random dip (0, 90 and repeated sets
  // included, so that traces overlap one another and the region's edges), persistence and
  // perturbation, explicit joints, and up to two circular openings inside the region. Blocks
  // may enclose openings or touch themselves at a crossing (and are cut), and in report mode
  // slivers of any size stay.
  std::mt19937_64 random(12345);
  const auto uniform = [&](double lo, double hi)
  { return std::uniform_real_distribution<double>(lo, hi)(random); };
  std::size_t n_blocks = 0, n_cuts = 0, n_merged = 0, n_collapsed = 0, n_straight = 0;
  double seconds = 0.0, largest = 0.0;
  double shortest_ratio = std::numeric_limits<double>::infinity();
  for (int trial = 0; trial < 40; ++trial)
  {
    SCOPED_TRACE("trial " + std::to_string(trial));
    RockMassDescription d;
    const double r_min = 8.0;
    const int n_corners = trial % 3 == 0 ? 4 : 5 + trial % 5;
    for (int k = 0; k < n_corners; ++k)
    {
      const double a = 2 * M_PI * (k + (trial % 3 == 0 ? 0.5 : uniform(0.1, 0.9))) / n_corners;
      const double r = trial % 3 == 0 ? r_min * std::sqrt(2.0) : uniform(r_min, 14.0);
      d.region.emplace_back(r * std::cos(a), r * std::sin(a));
    }
    const double dips[] = {0.0, 90.0, 45.0, uniform(-180, 180), uniform(-180, 180)};
    for (int s = 0; s < 1 + trial % 3; ++s)
    {
      JointSet set = persistent_set(dips[(trial + 2 * s) % 5], uniform(0.8, 3.0), uniform(-2, 2));
      if (uniform(0, 1) < 0.4)
      {
        set.trace_length = uniform(1.0, 8.0);
        set.bridge = uniform(0.3, 3.0);
      }
      set.perturbation.spacing = uniform(0, 1) < 0.5 ? uniform(0, 0.4) : 0.0;
      set.perturbation.position = uniform(0, 0.5);
      set.perturbation.distribution = s % 2 ? Distribution::normal : Distribution::uniform;
      d.joint_sets.push_back(set);
    }
    if (trial % 4 == 1)
    {
      // The same traces twice (an unperturbed persistent set; a perturbed one would draw other
      // numbers and give other traces).
      d.joint_sets.front().bridge = 0.0;
      d.joint_sets.front().perturbation = JointPerturbation();
      d.joint_sets.push_back(d.joint_sets.front());
    }
    if (trial % 2 == 0)
      d.joints = {{{uniform(-10, 10), uniform(-10, 10)}, {uniform(-10, 10), uniform(-10, 10)}}};
    if (trial % 3 != 2)
      d.openings.push_back(circle({uniform(-2, 2), uniform(-2, 2)}, uniform(0.5, 1.8)));
    if (trial % 5 == 0)
      d.openings.push_back(circle({6, 0}, 0.8)); // clear of the first (within 4.6 m of 0)
    d.slivers.action = trial % 2 ? SliverAction::merge : SliverAction::report;
    d.seed = static_cast<std::uint64_t>(trial);

    const auto start = std::chrono::steady_clock::now();
    const RockMassResult r = generate_blocks(d);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // Openings may reach out of a star-shaped region: only what lies inside is excavated.
    double expected = std::abs(signed_area(d.region));
    for (const std::vector<Point>& o : r.openings)
      expected -= overlap_area(o, d.region);
    EXPECT_NEAR(sum_of_areas(r), expected, 1e-9 * expected);
    expect_valid_polygons(r);
    expect_matching_edges(r, d.region);
    // Rounding only: a vertex moves by an ulp of 14 m across an edge at most 30 m long.
    const double overlap = largest_overlap(r);
    EXPECT_LT(overlap, 30.0 * 14.0 * std::numeric_limits<double>::epsilon());
    const RockMassStatistics& s = r.statistics;
    EXPECT_DOUBLE_EQ(s.min_edge_length, 0.01 * mean_spacing(d));
    EXPECT_GE(s.shortest_edge, s.min_edge_length);
    EXPECT_EQ(s.shortest_edge, shortest_edge(r));
    EXPECT_EQ(s.n_short_edges, 0u);
    EXPECT_EQ(n_straight_vertices(r, d.region, d.straight_angle), 0u);
    n_blocks += r.blocks.size();
    n_cuts += r.statistics.n_island_cuts;
    n_merged += r.statistics.n_merged;
    n_collapsed += s.n_collapsed_edges;
    n_straight += s.n_straight_vertices;
    shortest_ratio = std::min(shortest_ratio, s.shortest_edge / s.min_edge_length);
    largest = std::max(largest, overlap);
  }
  std::cout << "40 random rock masses in " << seconds << " s: " << n_blocks << " blocks, "
            << n_merged << " merges, " << n_cuts << " island cuts, " << n_collapsed
            << " short edges collapsed, " << n_straight
            << " straight vertices removed; shortest edge / min_edge_length " << shortest_ratio
            << "; largest overlap " << largest << " m^2\n";
}

TEST(RockMass, JointThroughAnOpeningsCornerLeavesNoRoundingEdge)
{
  // A set at dip 120 through the centre of an 18-gon (chord_tolerance 0.05 m, radius 3 m) passes
  // its corners at 120 and 300 degrees in real numbers; rounded apart, the trace crossed a chord
  // 2e-16 m from the corner (a 2.2e-16 m edge). The corner and the crossing are now one vertex,
  // and no edge is shorter than 1% of the spacing.
  RockMassDescription d;
  d.region = rectangle(-12, -12, 12, 12);
  d.joint_sets = {persistent_set(30, 3, 0.5), non_persistent_set(120, 3, 9, 2)};
  d.openings = {circle({0, 0}, 3)};
  d.chord_tolerance = 0.05;
  const auto start = std::chrono::steady_clock::now();
  const RockMassResult r = generate_blocks(d);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const RockMassStatistics& s = r.statistics;
  std::cout << s.n_blocks << " blocks in " << seconds << " s; shortest edge " << s.shortest_edge
            << " m (threshold " << s.min_edge_length << " m), " << s.n_collapsed_edges
            << " short edges collapsed, " << s.n_straight_vertices << " straight vertices removed, "
            << s.n_merged << " slivers merged\n";
  ASSERT_EQ(r.openings[0].size(), 18u);
  EXPECT_DOUBLE_EQ(s.min_edge_length, 0.03);
  EXPECT_GE(s.shortest_edge, 0.03);
  EXPECT_EQ(s.shortest_edge, shortest_edge(r));
  EXPECT_EQ(s.n_short_edges, 0u);
  EXPECT_GE(s.n_collapsed_edges, 2u);
  const double expected = 24.0 * 24.0 - signed_area(r.openings[0]);
  EXPECT_NEAR(sum_of_areas(r), expected, 1e-12 * expected);
  EXPECT_NEAR(s.total_area, expected, 1e-12 * expected);
  expect_valid_polygons(r);
  expect_matching_edges(r, d.region);
  EXPECT_LT(largest_overlap(r), 10.0 * 12.0 * std::numeric_limits<double>::epsilon());
  // The opening's corners stay where they were: the trace was moved onto them.
  for (const Point& corner : r.openings[0])
    EXPECT_NEAR((corner - Point(0, 0)).norm(), 3.0, 1e-15);
}

TEST(RockMass, CloseCrossingsAndNearDuplicateTracesAreTidied)
{
  // Two sets 0.01 degrees apart from one line 0: their traces cross at the origin and stay
  // within 4 mm of each other across the region, crossing every trace of the third set and
  // the region's boundary up to 4 mm apart; merging the thin wedges between them leaves
  // vertices within 0.01 degrees of straight. Explicit joints cross each other 2 mm apart and
  // end 1 mm from a corner.
  RockMassDescription d;
  d.region = rectangle(-10, -10, 10, 10);
  d.joint_sets = {persistent_set(30, 2.0), persistent_set(30.01, 2.0), persistent_set(100, 2.5)};
  d.joints = {{{-10.001, -3}, {4, 10.001}}, {{-9.998, -3}, {4, 9.999}}, {{-10, 9.999}, {3, 0}}};
  // Thresholds 0: only edges below 1e-9 of the region's extent (rounding) are collapsed.
  const RockMassDescription untreated = [&]
  {
    RockMassDescription u = d;
    u.min_edge_length = 0.0;
    u.straight_angle = 0.0;
    return u;
  }();
  const RockMassResult before = generate_blocks(untreated);
  const RockMassResult r = generate_blocks(d);
  const RockMassStatistics& s = r.statistics;
  std::cout << "untreated: " << before.blocks.size() << " blocks, shortest edge "
            << before.statistics.shortest_edge << " m, "
            << n_straight_vertices(before, d.region, 1.0)
            << " straight vertices; treated: " << r.blocks.size() << " blocks, shortest edge "
            << s.shortest_edge << " m (threshold " << s.min_edge_length << " m), "
            << s.n_collapsed_edges << " collapsed, " << s.n_straight_vertices
            << " straight vertices removed\n";
  EXPECT_LT(before.statistics.shortest_edge, 0.005);
  EXPECT_GT(n_straight_vertices(before, d.region, 1.0), 0u);
  EXPECT_NEAR(s.min_edge_length, 0.01 * (2.0 + 2.0 + 2.5) / 3.0, 1e-15);
  EXPECT_GE(s.shortest_edge, s.min_edge_length);
  EXPECT_EQ(n_straight_vertices(r, d.region, 1.0), 0u);
  EXPECT_NEAR(sum_of_areas(r), 400.0, 1e-12 * 400.0);
  expect_valid_polygons(r);
  expect_matching_edges(r, d.region);
  EXPECT_LT(largest_overlap(r), 30.0 * 10.0 * std::numeric_limits<double>::epsilon());

  // An explicit threshold; without joint sets the default is the chord tolerance.
  d.min_edge_length = 0.2;
  EXPECT_GE(generate_blocks(d).statistics.shortest_edge, 0.2);
  d.joint_sets.clear();
  d.min_edge_length.reset();
  d.chord_tolerance = 0.02;
  EXPECT_DOUBLE_EQ(generate_blocks(d).statistics.min_edge_length, 0.02);
  d.min_edge_length = -1.0;
  EXPECT_THROW(generate_blocks(d), ddafem::InputError);
}
