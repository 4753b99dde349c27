// `ddafem sweep`: the critical shaking of a scene. It runs the scene with one key (e.g.
// tunnel.wave.velocity.amplitude or ...scale_to_pga) set to a sequence of values, as separate
// `ddafem run` processes in parallel, and narrows down the smallest value at which a keyblock
// falls (or its relative displacement exceeds a threshold). docs/sweep.md.
#pragma once

#include "common/enum_names.h"

#include <nlohmann/json.hpp>

#include <array>
#include <cstddef>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace ddafem
{
/// What the critical value is the smallest value of.
enum class SweepCriterion
{
  first_fall,  ///< a keyblock falls that the excavation did not already release
  displacement ///< a keyblock's residual displacement relative to the rock exceeds a threshold
};

constexpr std::array<EnumName<SweepCriterion>, 2> enum_names(SweepCriterion)
{
  return {
      {{SweepCriterion::first_fall, "first_fall"}, {SweepCriterion::displacement, "displacement"}}};
}

/// What one run said, by the criterion.
struct CaseVerdict
{
  bool exceeded = false;           ///< the criterion is met (or the run failed numerically)
  bool failed = false;             ///< status failed: counted as exceeded
  std::vector<std::size_t> fallen; ///< keyblocks that fell, not released by the excavation
  double max_relative_m = 0.0;     ///< largest residual relative displacement of those not
                                   ///< released [m]
  double keyblock_peak_m = 0.0;    ///< summary.json keyblocks.keyblock_peak_m
};

/// The verdict of a run's summary.json; `threshold` [m] for the displacement criterion.
CaseVerdict judge_case(const nlohmann::json& summary, SweepCriterion criterion, double threshold);

/// The search for the smallest value that exceeds, asynchronous: the caller asks for a value
/// whenever a core is free, giving the values still running. It brackets the value by doubling or
/// halving from `start` (or runs `low` and `high` first if given), then splits the widest part of
/// the bracket (largest value held, smallest exceeded], cut by the values still running, at its
/// middle, until the bracket's width is at most `tolerance` x its upper end. Values are > 0.
class CriticalValueSearch
{
public:
  CriticalValueSearch(double start, std::optional<double> low, std::optional<double> high,
                      double tolerance);

  /// The value to start next while `running` run; none when the search is over or no value
  /// would add to those running (the bounds of the bracketing reached).
  std::optional<double> next(const std::vector<double>& running) const;
  /// Whether a run of `value` can still narrow the bracket: false once the search is over, or a
  /// value at or below it exceeded, or one at or above it held.
  bool worth_running(double value) const;
  /// Records the verdict of a value.
  void add(double value, bool exceeded);

  /// Smallest value that exceeded, if any.
  std::optional<double> lowest_exceeding() const;
  /// Largest value below lowest_exceeding() that held (or the largest that held), if any.
  std::optional<double> highest_holding() const;
  /// Values that held above one that exceeded: the outcome is not monotonic in the value.
  std::vector<double> non_monotonic() const;
  /// Why the search ended: "bracketed", "never exceeded", "always exceeded", or "" if not over.
  std::string conclusion() const;

  /// The bracketing stops 2^10 times above or below the start.
  static constexpr double max_factor = 1024.0;

private:
  /// The next value while nothing is bracketed on one side: doubling up from the highest value
  /// held or running, or halving down from the lowest exceeded or running.
  std::optional<double> next_outward(const std::vector<double>& running) const;

  double start, tolerance;
  std::optional<double> low, high;
  std::vector<std::pair<double, bool>> cases;
};

/// What `ddafem sweep` was asked.
struct SweepOptions
{
  std::string scene;
  std::vector<std::string> settings; ///< --set key=value for every case
  std::string key;                   ///< the key swept
  SweepCriterion find = SweepCriterion::first_fall;
  double threshold = 0.0; ///< [m], displacement only
  std::optional<double> low, high;
  double tolerance = 0.05;
  unsigned jobs = 0; ///< runs at a time; 0: the cores
  std::string directory;
  bool quiet = false;
};

/// The line sweep.md and the log add when values held above one that exceeded (`held_above`,
/// CriticalValueSearch::non_monotonic()): the outcome is not monotonic in `key`, the critical
/// value a band; `ddafem fragility` gives the probability at each value.
std::string non_monotonic_note(const std::vector<double>& held_above, const std::string& key);

/// Runs the sweep; writes DIR/sweep.json and DIR/sweep.md, one DIR/case_NN per run. Returns the
/// exit code: 0, 1 if a run could not be judged (no summary.json), 2 for bad input (checked
/// before the first run: the scene with the key set to each starting value).
int run_sweep(const SweepOptions& options, std::ostream& log);

} // namespace ddafem
