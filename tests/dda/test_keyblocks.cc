// The openings of a set of blocks and their keyblocks (dda/keyblocks.h) on grids of unit
// squares with holes, whose answers can be counted by hand, and on the keyblock example's blocks.
#include "dda/keyblocks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

using namespace ddafem::dda;

namespace
{
/// Unit squares of an n x n grid from (0, 0), row by row, leaving out the cells in `holes`
/// (cell index iy n + ix); every other square is given clockwise (either orientation is valid).
std::vector<std::vector<Point>> grid(int n, const std::set<int>& holes)
{
  std::vector<std::vector<Point>> blocks;
  for (int iy = 0; iy < n; ++iy)
    for (int ix = 0; ix < n; ++ix)
      if (holes.count(iy * n + ix) == 0)
      {
        std::vector<Point> square = {{ix, iy}, {ix + 1, iy}, {ix + 1, iy + 1}, {ix, iy + 1}};
        if (blocks.size() % 2 == 1)
          std::reverse(square.begin(), square.end());
        blocks.push_back(square);
      }
  return blocks;
}

/// The keyblock example's blocks: base, left abutment, key, right abutment around a 1 m x
/// 0.5 m void (examples/keyblock/keyblock.yaml). The base's top edge is shared with both
/// abutments only in part: the void's floor is the middle of that edge.
std::vector<std::vector<Point>> keyblock_example()
{
  return {{{-3, -1}, {3, -1}, {3, 0}, {-3, 0}},
          {{-1.5, 0}, {-0.5, 0}, {-0.5, 1}, {-1.5, 1}},
          {{-0.5, 0.5}, {0.5, 0.5}, {0.5, 1.5}, {-0.5, 1.5}},
          {{0.5, 0}, {1.5, 0}, {1.5, 1}, {0.5, 1}}};
}
} // namespace

TEST(Keyblocks, AreTheEightBlocksAroundTheHoleOfAGrid)
{
  // 5 x 5 squares without the middle one (cell 12): its four edge neighbours (7, 11, 13, 17)
  // and four corner neighbours (6, 8, 16, 18) touch it; block indices skip the hole.
  const KeyblockGeometry k = find_keyblocks(grid(5, {12}), 1e-9);
  ASSERT_EQ(k.openings.size(), 1u);
  EXPECT_NEAR(k.openings[0].area, 1.0, 1e-12);
  EXPECT_NEAR(k.openings[0].size(), 1.0, 1e-12);
  EXPECT_EQ(k.openings[0].lower, Point(2, 2));
  EXPECT_EQ(k.openings[0].upper, Point(3, 3));
  EXPECT_EQ(k.blocks, (std::vector<std::size_t>{6, 7, 8, 11, 12, 15, 16, 17}));
  EXPECT_EQ(k.opening_of, std::vector<std::size_t>(8, 0));
}

TEST(Keyblocks, NoneWithoutAHole)
{
  // A full grid and a notch open to the outside have only an outer boundary.
  EXPECT_TRUE(find_keyblocks(grid(3, {}), 1e-9).blocks.empty());
  const KeyblockGeometry notch = find_keyblocks(grid(3, {4, 7}), 1e-9);
  EXPECT_TRUE(notch.openings.empty());
  EXPECT_TRUE(notch.blocks.empty());
}

TEST(Keyblocks, TwoHolesAreTwoOpenings)
{
  // 5 x 5 squares without cells 6 and 18: bottom-left opening first.
  const KeyblockGeometry k = find_keyblocks(grid(5, {18, 6}), 1e-9);
  ASSERT_EQ(k.openings.size(), 2u);
  EXPECT_EQ(k.openings[0].lower, Point(1, 1));
  EXPECT_EQ(k.openings[1].lower, Point(3, 3));
  // 8 around each; block 11 (cell 12) touches both (first: the lower one).
  EXPECT_EQ(k.blocks.size(), 15u);
  const auto at = std::find(k.blocks.begin(), k.blocks.end(), 11u) - k.blocks.begin();
  EXPECT_EQ(k.opening_of[static_cast<std::size_t>(at)], 0u);
}

TEST(Keyblocks, AnEdgeSharedInPartBoundsTheVoidWithItsMiddle)
{
  const KeyblockGeometry k = find_keyblocks(keyblock_example(), 1e-9);
  ASSERT_EQ(k.openings.size(), 1u);
  EXPECT_NEAR(k.openings[0].area, 0.5, 1e-12);
  EXPECT_NEAR(k.openings[0].size(), 1.0, 1e-12);
  EXPECT_EQ(k.blocks, (std::vector<std::size_t>{0, 1, 2, 3}));
}

TEST(Keyblocks, DistanceToTheOpeningsBoundary)
{
  // The hole of the 5 x 5 grid is the square [2, 3] x [2, 3]: its centre is 0.5 m from every
  // side, a point beyond a corner is as far as that corner.
  const KeyblockGeometry k = find_keyblocks(grid(5, {12}), 1e-9);
  ASSERT_EQ(k.openings.size(), 1u);
  EXPECT_NEAR(distance_to_boundary(k.openings[0], Point(2.5, 2.5)), 0.5, 1e-12);
  EXPECT_NEAR(distance_to_boundary(k.openings[0], Point(2.5, 2.0)), 0.0, 1e-12);
  EXPECT_NEAR(distance_to_boundary(k.openings[0], Point(0.0, 6.0)), std::hypot(2.0, 3.0), 1e-12);
}

// keyblock_fell with a 6 cm threshold (1 % of a 6 m opening) under g = 9.81 m/s^2 downwards:
// the fall speed is sqrt(2 x 9.81 x 0.06) = 1.085 m/s.
TEST(Keyblocks, FallVerdicts)
{
  const Vector2 down(0.0, -1.0);
  const double threshold = 0.06, g = 9.81;
  const auto verdict = [&](Vector2 u, Vector2 relative, Vector2 v, bool held) {
    return keyblock_fell({u, relative, v, held}, down, threshold, g);
  };
  const Vector2 zero = Vector2::Zero();
  // Dropped 6.1 cm, held or not, whatever the rock did.
  EXPECT_EQ(verdict({0.0, -0.061}, zero, zero, true), FallVerdict::dropped);
  // 5.9 cm down and held: no (friction caught it above the threshold).
  EXPECT_EQ(verdict({0.0, -0.059}, {0.0, -0.059}, zero, true), FallVerdict::no);
  // Detached, 1 cm down but faster than the fall speed: falling; just slower: no.
  EXPECT_EQ(verdict({0.0, -0.01}, {0.0, -0.01}, {0.0, -1.09}, false), FallVerdict::falling);
  EXPECT_EQ(verdict({0.0, -0.01}, {0.0, -0.01}, {0.0, -1.08}, false), FallVerdict::no);
  // Thrown sideways 0.8 m and up 0.15 m, detached (block 50 of the default tunnel at 2.44 m/s):
  // thrown out; the same displacement held (lying on the floor of the opening): no.
  EXPECT_EQ(verdict({0.8, 0.15}, {0.8, 0.15}, {2.2, 0.0}, false), FallVerdict::thrown_out);
  EXPECT_EQ(verdict({0.8, 0.15}, {0.8, 0.15}, zero, true), FallVerdict::no);
  // Detached but within the threshold of its place relative to the rock, although the rock
  // carried it 0.2 m: no (the free field moves it, not a fall).
  EXPECT_EQ(verdict({0.2, 0.0}, {0.05, 0.0}, zero, false), FallVerdict::no);
}

// A 0.45 m x 0.35 m block (keyblock 50 of the default tunnel, in the invert): it has left its
// place once it has moved its own width along its motion, 0.45 m sideways, 0.35 m up, or
// 0.45 + 0.35 = 0.8 m along the diagonal (the extent of a rectangle along (1, 1)/sqrt(2) is
// (0.45 + 0.35)/sqrt(2), and the move's length along it is |d| = sqrt(2) d).
TEST(Keyblocks, LeftItsPlace)
{
  const std::vector<Point> block = {{-1.48, -2.94}, {-1.03, -2.94}, {-1.03, -2.59}, {-1.48, -2.59}};
  EXPECT_FALSE(left_its_place(block, {0.449, 0.0}));
  EXPECT_TRUE(left_its_place(block, {0.451, 0.0}));
  EXPECT_FALSE(left_its_place(block, {0.0, 0.349}));
  EXPECT_TRUE(left_its_place(block, {0.0, -0.351}));
  EXPECT_FALSE(left_its_place(block, {0.399, 0.399}));
  EXPECT_TRUE(left_its_place(block, {0.401, 0.401}));
  EXPECT_FALSE(left_its_place(block, {0.0, 0.0}));
}
