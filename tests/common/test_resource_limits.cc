// The memory limit a scene is read against, and the far field's DOF estimate (issue 20).
#include "common/input_error.h"
#include "common/resource_limits.h"

#include <gtest/gtest.h>

namespace ddafem
{
namespace
{
TEST(ResourceLimits, GivenSizesWithUnits)
{
  EXPECT_DOUBLE_EQ(ResourceLimits::given("8G").memory, 8e9);
  EXPECT_DOUBLE_EQ(ResourceLimits::given("500M").memory, 5e8);
  EXPECT_DOUBLE_EQ(ResourceLimits::given("2e9").memory, 2e9);
  EXPECT_TRUE(ResourceLimits::given("1G").fits(0.9e9));
  EXPECT_FALSE(ResourceLimits::given("1G").fits(1.1e9));
  for (const char* bad : {"20X", "-1G", "0", "G", "", "1e999"})
    EXPECT_THROW(ResourceLimits::given(bad), InputError) << bad;
}

TEST(ResourceLimits, ThisMachineHasALimit)
{
  const ResourceLimits limits = ResourceLimits::of_this_machine();
  EXPECT_GT(limits.memory, 1e8); // a Linux machine with /proc/meminfo
  EXPECT_NE(limits.source.find("available on this machine"), std::string::npos);
  EXPECT_NE(limits.too_much(1e15).find("--max-memory sets another limit"), std::string::npos);
}

TEST(ResourceLimits, FarFieldDofsOfARectangle)
{
  // 400 m x 40 m of 1 m FE_Q(2) elements: 16,000 cells, 8 DOFs each (the mesh has 129,762:
  // the estimate leaves out the nodes of one row and one column).
  EXPECT_DOUBLE_EQ(estimate_far_field_dofs(16000.0, 1.0, 0.0, 0.0, 1.3, 2), 128000.0);
  // Half the element size, four times the DOFs.
  EXPECT_DOUBLE_EQ(estimate_far_field_dofs(16000.0, 0.5, 0.0, 0.0, 1.3, 2), 512000.0);
  // A hole of perimeter 62.8 m refined to 1 m, growing by 1.3 up to 27 m: the ring adds
  // 6 x 62.8 / 0.3 x (1 - 1/27) cells.
  const double with_hole = estimate_far_field_dofs(30000.0, 27.0, 62.8, 1.0, 1.3, 2);
  EXPECT_NEAR(with_hole, 8.0 * (30000.0 / 729.0 + 6.0 * 62.8 / 0.3 * (1.0 - 1.0 / 27.0)), 1e-6);
}

} // namespace
} // namespace ddafem
