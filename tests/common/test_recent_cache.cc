// RecentCache: the most recently used value first, the least recently used dropped at capacity.
#include "common/recent_cache.h"

#include <gtest/gtest.h>

#include <memory>

namespace
{
using Cache = ddafem::RecentCache<double, int>;

TEST(RecentCache, KeepsTheMostRecentlyUsedFirstAndDropsTheLeastRecent)
{
  Cache cache(3);
  EXPECT_TRUE(cache.empty());
  EXPECT_EQ(cache.use(1e-3), nullptr);
  cache.insert(1e-3, std::make_unique<int>(1));
  cache.insert(5e-4, std::make_unique<int>(2));
  cache.insert(2.5e-4, std::make_unique<int>(3));
  ASSERT_NE(cache.use(1e-3), nullptr); // 1e-3 is the most recent now, 5e-4 the least
  EXPECT_EQ(cache.front_key(), 1e-3);
  EXPECT_EQ(cache.front(), 1);
  cache.insert(1.25e-4, std::make_unique<int>(4)); // drops 5e-4
  EXPECT_EQ(cache.size(), 3u);
  EXPECT_EQ(cache.use(5e-4), nullptr);
  ASSERT_NE(cache.use(2.5e-4), nullptr);
  EXPECT_EQ(*cache.use(2.5e-4), 3);
  EXPECT_EQ(*cache.use(1e-3), 1);
  EXPECT_EQ(*cache.use(1.25e-4), 4);
  cache.clear();
  EXPECT_TRUE(cache.empty());
}

TEST(RecentCache, AValueKeepsItsAddressWhileKept)
{
  Cache cache(2);
  int* first = &cache.insert(1.0, std::make_unique<int>(7));
  cache.insert(0.5, std::make_unique<int>(8));
  EXPECT_EQ(cache.use(1.0), first); // reordering moves the owner, not the value
}
} // namespace
