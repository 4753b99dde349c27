// The critical-value search of `ddafem sweep` (app/studies/sweep.h) against oracles with a known
// threshold, and the verdict it reads from a run's summary.json.
#include "app/studies/sweep.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <optional>

namespace
{
using ddafem::CriticalValueSearch;

/// What a simulated sweep did.
struct Outcome
{
  int runs = 0;      ///< runs started
  double time = 0.0; ///< when the last ended
};

/// Runs the search against `exceeds` to its end as `ddafem sweep` does, `jobs` runs at a time on
/// a simulated clock: a run that holds takes `held` time units, one that exceeds 1 (it stops at
/// the first fall); runs the search no longer needs are stopped.
Outcome search_to_end(CriticalValueSearch& search, const std::function<bool(double)>& exceeds,
                      unsigned jobs, double held = 3.0)
{
  Outcome outcome;
  std::vector<std::pair<double, double>> running; // value, time it ends
  while (true)
  {
    while (running.size() < jobs)
    {
      std::vector<double> values;
      for (const auto& r : running)
        values.push_back(r.first);
      const std::optional<double> v = search.next(values);
      if (!v)
        break;
      EXPECT_EQ(std::count(values.begin(), values.end(), *v), 0) << *v << " is running already";
      running.emplace_back(*v, outcome.time + (exceeds(*v) ? 1.0 : held));
      if (++outcome.runs >= 100)
      {
        ADD_FAILURE() << "the search does not end";
        return outcome;
      }
    }
    if (running.empty())
      return outcome;
    const auto first = std::min_element(running.begin(), running.end(),
                                        [](auto& a, auto& b) { return a.second < b.second; });
    const double value = first->first;
    outcome.time = first->second;
    running.erase(first);
    search.add(value, exceeds(value));
    running.erase(std::remove_if(running.begin(), running.end(),
                                 [&](const auto& r) { return !search.worth_running(r.first); }),
                  running.end());
  }
}

TEST(CriticalValueSearch, BracketsAThresholdAboveTheStartWithinTheTolerance)
{
  // Two at a time: doubling from 0.5 brackets 3.7 in (2, 4]; splitting the widest part then
  // narrows it to 5 % of its upper end. Rounds of two (the sweep before issue 21's last step)
  // needed 5 rounds, up to 15 time units (a round lasts 3 units when one of its runs holds).
  CriticalValueSearch search(0.5, std::nullopt, std::nullopt, 0.05);
  const Outcome outcome = search_to_end(
      search, [](double v) { return v >= 3.7; }, 2);
  EXPECT_EQ(search.conclusion(), "bracketed");
  ASSERT_TRUE(search.lowest_exceeding() && search.highest_holding());
  EXPECT_GE(*search.lowest_exceeding(), 3.7);
  EXPECT_LT(*search.highest_holding(), 3.7);
  EXPECT_LE(*search.lowest_exceeding() - *search.highest_holding(),
            0.05 * *search.lowest_exceeding());
  EXPECT_LT(outcome.time, 15.0);
  EXPECT_TRUE(search.non_monotonic().empty());
}

TEST(CriticalValueSearch, BracketsAThresholdBelowTheStart)
{
  CriticalValueSearch search(0.5, std::nullopt, std::nullopt, 0.02);
  search_to_end(
      search, [](double v) { return v > 0.061; }, 3);
  EXPECT_EQ(search.conclusion(), "bracketed");
  EXPECT_GT(*search.lowest_exceeding(), 0.061);
  EXPECT_LE(*search.highest_holding(), 0.061);
  EXPECT_LE(*search.lowest_exceeding() - *search.highest_holding(),
            0.02 * *search.lowest_exceeding());
}

TEST(CriticalValueSearch, OneRunAtATimeIsABisection)
{
  // From (1, 2]: each run halves the bracket, 1 / 2^k <= 0.05 x 2 after k = 4 more runs.
  CriticalValueSearch search(1.0, std::nullopt, std::nullopt, 0.05);
  const Outcome outcome = search_to_end(
      search, [](double v) { return v > 1.3; }, 1);
  EXPECT_EQ(search.conclusion(), "bracketed");
  EXPECT_EQ(outcome.runs, 2 + 4);
  EXPECT_DOUBLE_EQ(*search.highest_holding(), 1.25);
  EXPECT_DOUBLE_EQ(*search.lowest_exceeding(), 1.3125);
}

TEST(CriticalValueSearch, AFreedCoreSplitsTheWidestPartLeftByTheRunningValues)
{
  CriticalValueSearch search(1.0, std::nullopt, std::nullopt, 0.05);
  EXPECT_EQ(search.next({}), 1.0);
  EXPECT_EQ(search.next({1.0}), 2.0); // doubling from the highest running
  search.add(1.0, false);
  EXPECT_EQ(search.next({2.0}), 4.0);
  search.add(4.0, true); // (1, 4] with 2 running: of equal parts, the upper one
  EXPECT_EQ(search.next({2.0}), 3.0);
  EXPECT_TRUE(search.worth_running(2.0));
  search.add(2.0, true); // (1, 2]: a run of 3 can no longer narrow it
  EXPECT_FALSE(search.worth_running(3.0));
  EXPECT_FALSE(search.worth_running(0.8));
  EXPECT_EQ(search.next({}), 1.5);
  EXPECT_EQ(search.next({1.5}), 1.25); // (1, 1.5) is a third of its end, (1.5, 2] a quarter
}

TEST(CriticalValueSearch, GivenLowAndHighAreRunFirstAndBoundTheSearch)
{
  CriticalValueSearch search(0.5, 0.1, 0.8, 0.05);
  EXPECT_EQ(search.next({}), 0.1);
  EXPECT_EQ(search.next({0.1}), 0.8);
  EXPECT_EQ(search.next({0.1, 0.8}), 0.45);
  search_to_end(
      search, [](double) { return false; }, 2);
  EXPECT_EQ(search.conclusion(), "never exceeded");
  EXPECT_EQ(*search.highest_holding(), 0.8);

  CriticalValueSearch always(0.5, 0.1, 0.8, 0.05);
  search_to_end(
      always, [](double) { return true; }, 2);
  EXPECT_EQ(always.conclusion(), "always exceeded");
  EXPECT_EQ(*always.lowest_exceeding(), 0.1);
}

TEST(CriticalValueSearch, WithoutBoundsItStopsAThousandTimesAwayFromTheStart)
{
  CriticalValueSearch search(1.0, std::nullopt, std::nullopt, 0.05);
  search_to_end(
      search, [](double) { return false; }, 2);
  EXPECT_EQ(search.conclusion(), "never exceeded");
  EXPECT_EQ(*search.highest_holding(), CriticalValueSearch::max_factor);
  EXPECT_FALSE(search.next({}));
}

TEST(CriticalValueSearch, AValueThatHoldsAboveOneThatExceededIsReported)
{
  CriticalValueSearch search(1.0, std::nullopt, std::nullopt, 0.05);
  search.add(1.0, false);
  search.add(2.0, true);
  search.add(3.0, false);
  EXPECT_EQ(search.non_monotonic(), (std::vector<double>{3.0}));
  EXPECT_EQ(*search.highest_holding(), 1.0); // below the lowest that exceeded
  EXPECT_EQ(ddafem::non_monotonic_note(search.non_monotonic(), "tunnel.wave.velocity.amplitude"),
            "Not monotonic: held at [3.0], above the lowest value that exceeded. The critical "
            "value is a band, not a value: `ddafem fragility SCENE --key "
            "tunnel.wave.velocity.amplitude` gives the probability of a fall at each value "
            "(docs/fragility.md).");
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
