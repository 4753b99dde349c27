// Parallel (common/parallel.h): every index once, and sums that are the same bits on any
// number of threads.
#include "common/parallel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

namespace ddafem
{
namespace
{
TEST(Parallel, VisitsEveryIndexOnceInFixedChunks)
{
  for (const unsigned threads : {1u, 2u, 3u})
  {
    const Parallel parallel(threads);
    std::vector<int> visits(1000, 0);
    std::vector<std::size_t> chunk_of(1000, 0);
    parallel.for_chunks(1000, 64,
                        [&](std::size_t begin, std::size_t end)
                        {
                          EXPECT_EQ(begin % 64, 0u);
                          EXPECT_EQ(end, std::min<std::size_t>(begin + 64, 1000));
                          for (std::size_t i = begin; i < end; ++i)
                            ++visits[i];
                        });
    EXPECT_EQ(visits, std::vector<int>(1000, 1)) << threads << " threads";
  }
  EXPECT_GE(Parallel(0).n_threads(), 1u); // all cores
}

TEST(Parallel, SumsAreTheSameBitsOnAnyThreadCount)
{
  // Magnitudes from 1e-12 to 1e12 with alternating signs: any other order of the additions
  // gives other bits.
  std::vector<double> values(5000);
  for (std::size_t i = 0; i < values.size(); ++i)
    values[i] = std::pow(10.0, static_cast<double>(i % 25) - 12.0) * (i % 3 == 0 ? -1.0 : 1.0) /
                static_cast<double>(i + 1);
  const auto sum = [&](const Parallel& parallel)
  {
    return parallel.sum_chunks(values.size(), 64,
                               [&](std::size_t begin, std::size_t end)
                               {
                                 double s = 0.0;
                                 for (std::size_t i = begin; i < end; ++i)
                                   s += values[i];
                                 return s;
                               });
  };
  const double one = sum(Parallel(1));
  for (const unsigned threads : {2u, 3u, 8u})
  {
    const double many = sum(Parallel(threads));
    EXPECT_EQ(std::memcmp(&one, &many, sizeof one), 0) << threads << " threads";
  }
}

} // namespace
} // namespace ddafem
