// `ddafem ensemble`: answers as probabilities (issue 53). It runs a scene N times as separate
// `ddafem run` processes (app/studies/child_runs.h), the members differing by the seeds of the
// joint sets' random perturbations, by values drawn for numeric keys (--vary KEY=DIST) and by a
// round-off perturbation of one key (--roundoff: member k's value x (1 + k 1e-12)), and reports
// per keyblock P(fell) and P(loosened) with Wilson intervals and the spread of its residual
// displacement. docs/ensemble.md.
#pragma once

#include "common/statistics.h"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace ddafem
{
/// What `ddafem ensemble` was asked.
struct EnsembleOptions
{
  std::string scene;
  std::size_t members = 0;           ///< -n: members to run
  std::vector<std::string> settings; ///< --set KEY=VALUE for every member
  std::vector<std::string>
      vary; ///< --vary KEY=DIST, e.g. "joint_materials.j.friction_angle=normal(35,2)"
  /// --roundoff [KEY]: the key whose value member k takes x (1 + k 1e-12); "" asks for the
  /// default (tunnel.wave.velocity.amplitude in tunnel scenes); none: no round-off.
  std::optional<std::string> roundoff;
  std::uint64_t seed = 1;     ///< --seed: of the members' seeds and of every draw
  unsigned jobs = 0;          ///< runs at a time; 0: the cores
  unsigned threads = 0;       ///< threads of each run; 0: the cores shared by the runs
  double max_wall_time = 0.0; ///< [s] budget of each member; 0: none
  bool snapshots = false;     ///< VTU snapshots during the run (else first and last only)
  double sector_deg = 10.0;   ///< width of the sectors of an opening's perimeter [deg]
  bool quiet = false;
  std::string directory;
};

/// A key drawn from a distribution for every member.
struct VariedKey
{
  std::string key;
  statistics::Distribution distribution;
};

/// What the ensemble runs, checked against the scene before the first member.
struct EnsemblePlan
{
  std::vector<VariedKey> varied;
  std::string roundoff_key;           ///< empty: no round-off
  double roundoff_value = 0.0;        ///< the key's value in the scene (with --set)
  std::vector<std::string> seed_keys; ///< the scene's seed keys (rock_mass.seed, tunnel.seed)
  /// Why the seeds change nothing (no joint set with a random perturbation); empty if they do.
  std::string seed_warning;
};

/// Member `index` of an ensemble: its seed, the values drawn or set for it (key -> value) and
/// the --set arguments of its run.
struct Member
{
  std::size_t index = 0;
  std::uint64_t seed = 0;
  std::vector<std::pair<std::string, double>> values;
  std::vector<std::string> settings;
};

/// Checks the options against the scene and returns the plan; throws InputError naming the
/// option, key and value and what was expected: a --vary text that is not KEY=DIST, an unknown
/// or non-numeric key, an unknown distribution, a spread <= 0, a distribution whose support
/// leaves the key's allowed range (schema), a --roundoff key without a number.
EnsemblePlan plan_ensemble(const EnsembleOptions& options);

/// Member `index`: its seed mix_seed(mix_seed(seed, 0), index) mod 2^31 on every seed key, each
/// varied key i drawn with seed mix_seed(seed, i + 1), the round-off key x (1 + index 1e-12),
/// output.interval 0 unless --snapshots; the options' --set first.
Member plan_member(const EnsembleOptions& options, const EnsemblePlan& plan, std::size_t index);

/// A keyblock's verdict in one member (summary.json keyblocks.blocks[]).
struct KeyblockOutcome
{
  std::size_t id = 0;
  std::size_t opening = 0;
  bool fell = false, loosened = false, released = false;
  double residual_relative_m = 0.0; ///< residual displacement relative to the rock [m]
  /// Where on the opening's perimeter: from straight up, clockwise [deg]; NaN if not given.
  double angle_deg = 0.0;
};

/// What one member said.
struct MemberOutcome
{
  std::size_t index = 0;
  int exit_code = -1;
  std::string status; ///< summary.json's status: completed, failed, stopped; "" if none
  double wall_s = 0.0;
  std::vector<KeyblockOutcome> keyblocks;
  /// per opening: area of the blocks fallen that no static stage released [m^2 = m^3/m]
  std::vector<double> fallen_area_m2;
  /// per opening: area of the fallen blocks a static stage (the excavation) released [m^2]
  std::vector<double> released_area_m2;
  /// the summary kept the released area apart (summaries before it did not: their fallen area
  /// includes the excavation's releases)
  bool released_area_known = true;
  /// PGV of the wave arriving at the near field's base [m/s] (summary.json's
  /// far_field.free_field_at_base; none without a free-field column)
  std::optional<double> pgv_at_base_m_s;
  /// Counted in the probabilities: the run completed (failed and stopped ones are not).
  bool counted() const { return status == "completed"; }
};

/// The outcome of a member from its summary.json (null: the run left none).
MemberOutcome member_outcome(std::size_t index, int exit_code, const nlohmann::json& summary);

/// The PGV arriving at the near field's base over the counted members that have one (the
/// quantiles of sample_json), null if none has.
nlohmann::json pgv_at_base_json(const std::vector<MemberOutcome>& outcomes);

/// The members' wall times summed [s] (of every member finished, counted or not).
double members_wall_s(const std::vector<MemberOutcome>& outcomes);

/// A count `k` of `n` as a probability: {"count", "p" = k / n, "wilson_95": [low, high]}.
nlohmann::json proportion_json(std::size_t k, std::size_t n);

/// "35 % [20, 52]" of a proportion_json: whole percent from 10 %, two digits below.
std::string percent_text(const nlohmann::json& p);

/// The scene file's absolute path without `.` and `..` (ensemble.json's scene_path: the same
/// file however it was named).
std::string scene_path(const std::string& scene);

/// ensemble.json: the question, each member and, over the completed members, per keyblock
/// P(fell) and P(loosened) with 95 % Wilson intervals and the median, 5-95 % and the median's
/// 95 % order-statistic interval of its residual relative displacement; per sector of each
/// opening's perimeter (options.sector_deg wide, from the crown clockwise) the probability that a
/// keyblock there fell or loosened, which holds where the members' blocks differ; per opening
/// the fallen area; `answer`, the sentence ensemble.md opens with.
nlohmann::json ensemble_json(const EnsembleOptions& options, const EnsemblePlan& plan,
                             const std::vector<Member>& members,
                             const std::vector<MemberOutcome>& outcomes, double wall_s);

/// ensemble.md from ensemble.json: the answer, the keyblock table, the openings, the members.
std::string ensemble_markdown(const nlohmann::json& ensemble);

/// Runs the ensemble into DIR (DIR/member_NNN with member.json, DIR/ensemble.json and .md
/// rewritten after each member). Returns the exit code: 0; 1 if a member failed numerically;
/// 3 if one stopped at a budget. Bad input throws InputError before any member runs. If DIR
/// holds the report of an earlier run of the same ensemble, the members that finished there
/// (completed or failed) are not run again; another ensemble's report (another scene, -n,
/// --vary, --seed, --set, --roundoff or --snapshots) is bad input.
int run_ensemble(const EnsembleOptions& options, std::ostream& log);

/// What run_ensemble ran: its exit code and the outcome of every member that finished (here or
/// in the earlier run it continued), in the order they finished.
struct EnsembleResult
{
  int exit_code = 0;
  std::vector<MemberOutcome> outcomes;
};

/// run_ensemble, returning the members' outcomes too (`ddafem fragility` runs one per level).
EnsembleResult run_ensemble_members(const EnsembleOptions& options, std::ostream& log);

/// `ddafem resume DIR` of an ensemble: run_ensemble with the options in DIR/ensemble.json.
int resume_ensemble(const std::string& directory, bool quiet, unsigned threads, std::ostream& log);

} // namespace ddafem
