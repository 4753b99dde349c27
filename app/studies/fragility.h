// `ddafem fragility`: the probability of a damage state given the shaking (issue 53). It runs an
// ensemble (app/studies/ensemble.h) at each of several values of one key (the intensity levels),
// counts per level the members that reached each damage state, and fits a lognormal fragility curve
// P(DS | IM) = Phi(ln(IM / theta) / beta) by maximum likelihood with bootstrap bounds
// (common/statistics.h). The levels are given, or chosen: a `ddafem sweep` brackets the critical
// value, and the levels spread across the band where the runs' outcomes change.
// docs/fragility.md.
#pragma once

#include "app/studies/ensemble.h"
#include "app/studies/sweep.h"
#include "common/statistics.h"

#include <nlohmann/json.hpp>

#include <array>
#include <cstddef>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace ddafem
{
/// What `ddafem fragility` was asked.
struct FragilityOptions
{
  /// The ensemble run at each level: its members (--members), --set, --vary, --roundoff, --seed,
  /// -j, --threads, --max-wall-time, --snapshots, --quiet; its directory is the fragility's.
  EnsembleOptions ensemble;
  std::string key;                   ///< the key whose value is the intensity
  std::vector<double> levels;        ///< --levels; empty: chosen
  std::size_t n_levels = 6;          ///< levels to choose
  std::optional<double> low, high;   ///< bounds of the bracketing, as `sweep`'s
  std::optional<double> fallen_area; ///< --fallen-area [m^2]: the fallen-area damage state
  std::vector<std::string> states;   ///< --state block:ID:fell|loosened
};

/// The kinds of damage state a member can reach.
enum class DamageKind
{
  any_loosened,  ///< a keyblock loosened (the keyblock report's threshold)
  any_fell,      ///< a keyblock fell that the excavation had not released
  fallen_area,   ///< the area of the blocks fallen, over every opening, above a value
  block_fell,    ///< keyblock `block` fell, not released by the excavation
  block_loosened ///< keyblock `block` loosened
};

constexpr std::array<EnumName<DamageKind>, 5> enum_names(DamageKind)
{
  return {{{DamageKind::any_loosened, "any_loosened"},
           {DamageKind::any_fell, "any_fell"},
           {DamageKind::fallen_area, "fallen_area"},
           {DamageKind::block_fell, "block_fell"},
           {DamageKind::block_loosened, "block_loosened"}}};
}

/// A damage state: its kind, its name in the reports and its parameter.
struct DamageState
{
  DamageKind kind = DamageKind::any_fell;
  std::string name;      ///< e.g. "a keyblock fell", "block 50 fell"
  double area_m2 = 0.0;  ///< fallen_area: exceeded when the fallen area is above it [m^2]
  std::size_t block = 0; ///< block_*: the keyblock's id
};

/// The damage states of the options: any keyblock loosened, any fell, the fallen area above
/// --fallen-area if given, and each --state block:ID:fell|loosened. Throws InputError naming a
/// --state that is not of that form or a --fallen-area <= 0.
std::vector<DamageState> damage_states(const FragilityOptions& options);

/// Whether a member reached the damage state.
bool reached(const DamageState& state, const MemberOutcome& member);

/// `n` levels (n >= 2) spread evenly in ln IM across the band [band_low, band_high] where the
/// outcome changes, widened about its geometric centre to at least the 10-90 % band of a
/// lognormal curve with beta = min_beta (ln(high / low) >= 2 x 1.2816 min_beta): the ends are
/// the band's, so the curve's 10 % and 90 % points are sampled.
std::vector<double> spread_levels(double band_low, double band_high, std::size_t n,
                                  double min_beta = 0.1);

/// The band where the outcome changes, from a sweep's verdicts (value, exceeded): from the
/// lowest value that exceeded to the highest that held, if the latter is above (not monotonic);
/// else the bracket [highest held, lowest exceeded]. None without both verdicts.
std::optional<std::pair<double, double>>
outcome_band(const std::vector<std::pair<double, bool>>& verdicts);

/// The intensity measure a key's value stands for, derived from the scene.
struct IntensityMeasure
{
  std::string name;       ///< e.g. "PGV (outcrop)"
  std::string unit;       ///< e.g. "m/s"
  double factor = 1.0;    ///< IM = factor x the key's value (2: the outcrop doubles the incident)
  std::string definition; ///< how it follows from the input, for the report
  /// PGA at the outcrop [g] per unit IM, if the input's time function gives it (a sine pulse of
  /// frequency f: PGA = 2 pi f PGV / g); none otherwise.
  std::optional<double> pga_g_per_im;
};

/// The intensity measure of `key` in the scene with `settings`: the incident wave's amplitude
/// (tunnel.wave.velocity.amplitude) or a record's scale_to_pgv is the incident PGV, and the
/// outcrop's is twice it; a record's scale_to_pga likewise for PGA; any other key is its value.
IntensityMeasure intensity_measure(const std::string& scene,
                                   const std::vector<std::string>& settings,
                                   const std::string& key);

/// PGA [g] per PGV [m/s] of the record a run's summary.json reports (its first `records[]`
/// entry, pga_g / pgv_m_s, of the record as scaled and corrected): for an IM that scales a
/// record, the ratio holds at every level. None without a record.
std::optional<double> record_pga_g_per_pgv(const nlohmann::json& summary);

/// One level's members.
struct FragilityLevelRun
{
  double value = 0.0; ///< the key's value
  std::string directory;
  std::vector<MemberOutcome> outcomes;
};

/// The members of `level` counted (completed) and those of them reaching `state`, at intensity
/// `im` (the level's value in the intensity measure).
statistics::FragilityLevel level_count(const DamageState& state, const FragilityLevelRun& level,
                                       double im);

/// sweep.json of an earlier call's bracketing in `sweep.directory`, if it ran to a conclusion
/// for the same scene, key and --set, and ran --low and --high when they are given (a fragility
/// run again into the same directory resumes with the same levels); else null.
nlohmann::json earlier_bracket(const SweepOptions& sweep);

/// Chosen levels are spread over the band that single runs bracketed, and the curve's 10-90 %
/// band of a keyblock falling can lie beyond it (a perturbed model may fall less often than the
/// bracket's unperturbed run): the level to add after `runs` (in the order run, the o.n_levels
/// chosen first), a step of half the chosen levels' span in ln IM (sqrt(last / first)) above
/// the highest while fewer than 90 % of its completed members had a keyblock fall, else below the
/// lowest while more than 10 % had; none once covered, after o.n_levels levels added, before
/// the chosen levels have run, or when the levels were given.
std::optional<double> level_beyond(const FragilityOptions& o,
                                   const std::vector<DamageState>& states,
                                   const std::vector<FragilityLevelRun>& runs);

/// fragility.json: the question, the intensity measure, per level and damage state the count
/// with its Wilson interval, per damage state the fit (theta in IM, beta, status and bracket)
/// and its bootstrap bounds, the HAZUS bored-tunnel curves for context, and `answer`.
nlohmann::json fragility_json(const FragilityOptions& options, const IntensityMeasure& im,
                              const std::vector<DamageState>& states,
                              const std::vector<FragilityLevelRun>& levels, double wall_s);

/// fragility.md from fragility.json: the answer, the fits, the counts per level.
std::string fragility_markdown(const nlohmann::json& fragility);

/// Runs the fragility analysis into DIR: DIR/bracket (the sweep, when the levels are chosen),
/// DIR/level_NN (an ensemble each), DIR/fragility.json and .md rewritten after each level.
/// Returns the exit code: 0; 1 if a member failed numerically; 3 if one stopped at a budget.
/// Bad input throws InputError before any member runs.
int run_fragility(const FragilityOptions& options, std::ostream& log);

} // namespace ddafem
