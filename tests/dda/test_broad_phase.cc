// Broad phase: bounding boxes and sweep and prune against hand-computed cases and brute force.
#include "dda/contact/broad_phase.h"

#include <gtest/gtest.h>

#include <random>

using namespace ddafem::dda;

namespace
{
using IndexPairs = std::vector<std::pair<std::size_t, std::size_t>>;

BoundingBox box(double x_min, double x_max, double y_min, double y_max)
{
  return {x_min, x_max, y_min, y_max};
}
} // namespace

TEST(BroadPhase, BoundingBoxOfConcavePolygonWithPad)
{
  // L-shape spanning [0, 2] x [0, 2]; a pad of 0.25 m moves every side out by 0.25 m.
  const BoundingBox b = bounding_box({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}, 0.25);
  EXPECT_DOUBLE_EQ(b.x_min, -0.25);
  EXPECT_DOUBLE_EQ(b.x_max, 2.25);
  EXPECT_DOUBLE_EQ(b.y_min, -0.25);
  EXPECT_DOUBLE_EQ(b.y_max, 2.25);
}

TEST(BroadPhase, BoundingBoxRejectsNoVertices)
{
  EXPECT_THROW(bounding_box({}, 0.0), std::invalid_argument);
}

TEST(BroadPhase, TouchingBoxesPairAndSeparatedOnesDoNot)
{
  const std::vector<BoundingBox> boxes{
      box(0, 1, 0, 1),       // 0
      box(1, 2, 0, 1),       // 1: shares the side x = 1 with 0
      box(2, 3, 1, 2),       // 2: touches 1 at the corner (2, 1) only
      box(0, 1, 1.5, 2),     // 3: overlaps 0 in x but is 0.5 above it
      box(0.5, 0.6, -5, 5),  // 4: tall sliver through 0 and 3, right of nothing else
      box(10, 11, 0, 1),     // 5: far away
      box(-1, 0, -1, -1e-9), // 6: just below the corner (0, 0) of box 0
  };
  const IndexPairs expected{{0, 1}, {0, 4}, {1, 2}, {3, 4}};
  EXPECT_EQ(overlapping_pairs(boxes), expected);
}

TEST(BroadPhase, NoBoxesOrOneBoxGiveNoPairs)
{
  EXPECT_TRUE(overlapping_pairs({}).empty());
  EXPECT_TRUE(overlapping_pairs({box(0, 1, 0, 1)}).empty());
}

TEST(BroadPhase, MatchesAllPairsOnRandomBoxes)
{
  // 500 boxes of side 0.1 to 3 m in a 50 m x 50 m square (a few thousand pairs), plus the
  // first 50 repeated exactly (coincident x_min, identical boxes).
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> position(0.0, 50.0);
  std::uniform_real_distribution<double> size(0.1, 3.0);
  std::vector<BoundingBox> boxes;
  for (int i = 0; i < 450; ++i)
  {
    const double x = position(rng), y = position(rng);
    boxes.push_back(box(x, x + size(rng), y, y + size(rng)));
  }
  for (std::size_t i = 0; i < 50; ++i)
    boxes.push_back(boxes[i]);

  IndexPairs expected;
  for (std::size_t i = 0; i < boxes.size(); ++i)
    for (std::size_t j = i + 1; j < boxes.size(); ++j)
      if (boxes[i].x_min <= boxes[j].x_max && boxes[j].x_min <= boxes[i].x_max &&
          boxes[i].y_min <= boxes[j].y_max && boxes[j].y_min <= boxes[i].y_max)
        expected.emplace_back(i, j);
  ASSERT_GT(expected.size(), 500u); // enough pairs for the comparison to mean something
  EXPECT_EQ(overlapping_pairs(boxes), expected);
}
