// The critical-value search of `ddafem sweep` (app/sweep.h) against oracles with a known
// threshold, and the verdict it reads from a run's summary.json.
#include "app/sweep.h"

#include <gtest/gtest.h>

#include <functional>

namespace
{
using ddafem::CriticalValueSearch;

/// Runs the search against `exceeds` to its end; returns the number of rounds.
int search_to_end(CriticalValueSearch& search, const std::function<bool(double)>& exceeds)
{
  int rounds = 0;
  for (std::vector<double> values = search.next(); !values.empty(); values = search.next())
  {
    ++rounds;
    for (const double v : values)
      search.add(v, exceeds(v));
    EXPECT_LT(rounds, 100) << "the search does not end";
    if (rounds >= 100)
      break;
  }
  return rounds;
}

TEST(CriticalValueSearch, BracketsAThresholdAboveTheStartWithinTheTolerance)
{
  // Two runs a round: doubling from 0.5 brackets 3.7 in (2, 4] after 2 rounds; each round then
  // cuts the bracket into 3, and 2 / 3^k <= 0.05 x 4 after k = 3 more.
  CriticalValueSearch search(0.5, std::nullopt, std::nullopt, 0.05, 2);
  const int rounds = search_to_end(search, [](double v) { return v >= 3.7; });
  EXPECT_EQ(search.conclusion(), "bracketed");
  ASSERT_TRUE(search.lowest_exceeding() && search.highest_holding());
  EXPECT_GE(*search.lowest_exceeding(), 3.7);
  EXPECT_LT(*search.highest_holding(), 3.7);
  EXPECT_LE(*search.lowest_exceeding() - *search.highest_holding(),
            0.05 * *search.lowest_exceeding());
  EXPECT_LE(rounds, 6);
  EXPECT_TRUE(search.non_monotonic().empty());
}

TEST(CriticalValueSearch, BracketsAThresholdBelowTheStart)
{
  CriticalValueSearch search(0.5, std::nullopt, std::nullopt, 0.02, 3);
  search_to_end(search, [](double v) { return v > 0.061; });
  EXPECT_EQ(search.conclusion(), "bracketed");
  EXPECT_GT(*search.lowest_exceeding(), 0.061);
  EXPECT_LE(*search.highest_holding(), 0.061);
}

TEST(CriticalValueSearch, GivenLowAndHighAreRunFirstAndBoundTheSearch)
{
  CriticalValueSearch search(0.5, 0.1, 0.8, 0.05, 2);
  EXPECT_EQ(search.next(), (std::vector<double>{0.1, 0.8}));
  search_to_end(search, [](double) { return false; });
  EXPECT_EQ(search.conclusion(), "never exceeded");
  EXPECT_EQ(*search.highest_holding(), 0.8);

  CriticalValueSearch always(0.5, 0.1, 0.8, 0.05, 2);
  search_to_end(always, [](double) { return true; });
  EXPECT_EQ(always.conclusion(), "always exceeded");
  EXPECT_EQ(*always.lowest_exceeding(), 0.1);
}

TEST(CriticalValueSearch, WithoutBoundsItStopsAThousandTimesAwayFromTheStart)
{
  CriticalValueSearch search(1.0, std::nullopt, std::nullopt, 0.05, 2);
  search_to_end(search, [](double) { return false; });
  EXPECT_EQ(search.conclusion(), "never exceeded");
  EXPECT_EQ(*search.highest_holding(), CriticalValueSearch::max_factor);
}

TEST(CriticalValueSearch, AValueThatHoldsAboveOneThatExceededIsReported)
{
  CriticalValueSearch search(1.0, std::nullopt, std::nullopt, 0.05, 2);
  search.add(1.0, false);
  search.add(2.0, true);
  search.add(3.0, false);
  EXPECT_EQ(search.non_monotonic(), (std::vector<double>{3.0}));
  EXPECT_EQ(*search.highest_holding(), 1.0); // below the lowest that exceeded
}

TEST(SweepVerdict, ReleasedBlocksDoNotCountAndAFailedRunExceeds)
{
  const nlohmann::json summary = nlohmann::json::parse(R"({"status": "completed",
    "keyblocks": {"keyblock_peak_m": 2.0, "blocks": [
      {"id": 60, "released": true, "fell": true, "residual_relative_m": 2.0},
      {"id": 12, "released": false, "fell": false, "residual_relative_m": 0.004},
      {"id": 13, "released": false, "fell": false, "residual_relative_m": 0.001}]}})");
  const ddafem::CaseVerdict fall =
      ddafem::judge_case(summary, ddafem::SweepCriterion::first_fall, 0.0);
  EXPECT_FALSE(fall.exceeded);
  EXPECT_TRUE(fall.fallen.empty());
  EXPECT_DOUBLE_EQ(fall.max_relative_m, 0.004);
  EXPECT_TRUE(ddafem::judge_case(summary, ddafem::SweepCriterion::displacement, 0.003).exceeded);
  EXPECT_FALSE(ddafem::judge_case(summary, ddafem::SweepCriterion::displacement, 0.005).exceeded);

  nlohmann::json fell = summary;
  fell["keyblocks"]["blocks"][2]["fell"] = true;
  EXPECT_EQ(ddafem::judge_case(fell, ddafem::SweepCriterion::first_fall, 0.0).fallen,
            (std::vector<std::size_t>{13}));
  nlohmann::json failed = summary;
  failed["status"] = "failed";
  const ddafem::CaseVerdict f = ddafem::judge_case(failed, ddafem::SweepCriterion::first_fall, 0.0);
  EXPECT_TRUE(f.exceeded && f.failed);
}
} // namespace
