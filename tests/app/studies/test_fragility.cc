// `ddafem fragility` (app/studies/fragility.h) without running members: the choice of levels
// against closed forms, the damage states parsed and counted on synthetic members, the report's
// counts recomputed here and its fits against common/statistics' own, and the intensity measure of
// the roof-wedge tunnel (a sine pulse: PGA = 2 pi f PGV).
#include "app/studies/fragility.h"

#include "common/input_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace
{
using namespace ddafem;

const std::string roof_wedge =
    std::string(DDAFEM_SOURCE_DIR) + "/examples/tunnel/roof_wedge_sv.yaml";

/// The InputError message of damage_states, or "no error".
std::string states_error(const FragilityOptions& o)
{
  try
  {
    damage_states(o);
  }
  catch (const InputError& e)
  {
    return e.what();
  }
  return "no error";
}

/// A member that completed with the given keyblock verdicts and fallen area.
MemberOutcome member(std::vector<KeyblockOutcome> keyblocks, double fallen_area_m2 = 0.0,
                     const std::string& status = "completed")
{
  MemberOutcome m;
  m.status = status;
  m.keyblocks = std::move(keyblocks);
  m.fallen_area_m2 = {fallen_area_m2};
  return m;
}

TEST(Fragility, LevelsSpreadEvenlyInLogAcrossTheBand)
{
  // ln(4 / 1) / 2 = 0.693 > 1.2816 x 0.1: the band as given, 5 levels a factor sqrt 2 apart.
  const std::vector<double> wide = spread_levels(1.0, 4.0, 5);
  ASSERT_EQ(wide.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i)
    EXPECT_NEAR(wide[i], std::pow(2.0, 0.5 * static_cast<double>(i)), 1e-12) << i;
  // A band narrower than the 10-90 % band of beta 0.1: widened about its geometric centre to
  // exp(+-z90 0.1), z90 = Phi^-1(0.9) = 1.2815515655446004.
  const std::vector<double> narrow = spread_levels(1.6, 1.7, 3, 0.1);
  const double centre = std::sqrt(1.6 * 1.7), half = 1.2815515655446004 * 0.1;
  EXPECT_NEAR(narrow[0], centre * std::exp(-half), 1e-12);
  EXPECT_NEAR(narrow[1], centre, 1e-12);
  EXPECT_NEAR(narrow[2], centre * std::exp(half), 1e-12);
}

TEST(Fragility, OutcomeBandFromASweepsVerdicts)
{
  // Monotonic: the bracket [highest held, lowest exceeded].
  const auto bracket = outcome_band({{1.0, false}, {2.0, true}, {1.5, false}, {4.0, true}});
  ASSERT_TRUE(bracket);
  EXPECT_EQ(bracket->first, 1.5);
  EXPECT_EQ(bracket->second, 2.0);
  // Not monotonic (docs/sweep.md's 1.531 fell, 1.667 held): from the lowest that exceeded to the
  // highest that held.
  const auto band =
      outcome_band({{1.0, false}, {1.531, true}, {1.667, false}, {1.625, true}, {2.0, true}});
  ASSERT_TRUE(band);
  EXPECT_EQ(band->first, 1.531);
  EXPECT_EQ(band->second, 1.667);
  EXPECT_FALSE(outcome_band({{1.0, false}, {2.0, false}}));
  EXPECT_FALSE(outcome_band({{1.0, true}}));
}

TEST(Fragility, DamageStatesParsedAndBadOnesNamed)
{
  FragilityOptions o;
  ASSERT_EQ(damage_states(o).size(), 2u);
  EXPECT_EQ(damage_states(o)[0].kind, DamageKind::any_loosened);
  EXPECT_EQ(damage_states(o)[1].kind, DamageKind::any_fell);
  o.fallen_area = 0.5;
  o.states = {"block:50:fell", "block:7:loosened"};
  const std::vector<DamageState> s = damage_states(o);
  ASSERT_EQ(s.size(), 5u);
  EXPECT_EQ(s[2].kind, DamageKind::fallen_area);
  EXPECT_EQ(s[2].area_m2, 0.5);
  EXPECT_EQ(s[3].kind, DamageKind::block_fell);
  EXPECT_EQ(s[3].block, 50u);
  EXPECT_EQ(s[4].kind, DamageKind::block_loosened);
  EXPECT_EQ(s[4].name, "block 7 loosened");
  for (const std::string bad : {"block:x:fell", "rock:5:fell", "block:5:moved", "block:5"})
  {
    o.states = {bad};
    EXPECT_NE(states_error(o).find("--state " + bad + ": expected block:ID:fell"),
              std::string::npos)
        << states_error(o);
  }
  o.states.clear();
  o.fallen_area = -1.0;
  EXPECT_NE(states_error(o).find("--fallen-area -1: expected an area > 0"), std::string::npos);
}

TEST(Fragility, DamageStatesReachedByAMember)
{
  FragilityOptions o;
  o.fallen_area = 1.0;
  o.states = {"block:50:fell", "block:50:loosened"};
  const std::vector<DamageState> s = damage_states(o);
  // Block 3 fell where the excavation had released it: not a fall of the shaking.
  const MemberOutcome released = member({{3, 0, true, true, true, 0.1, 0.0}}, 1.5);
  EXPECT_TRUE(reached(s[0], released));  // loosened
  EXPECT_FALSE(reached(s[1], released)); // no fall the excavation left in place
  EXPECT_TRUE(reached(s[2], released));  // 1.5 m^2 > 1 m^2
  EXPECT_FALSE(reached(s[3], released));
  const MemberOutcome fifty = member({{50, 0, true, false, false, 0.2, 0.0}}, 1.0);
  EXPECT_FALSE(reached(s[0], fifty));
  EXPECT_TRUE(reached(s[1], fifty));
  EXPECT_FALSE(reached(s[2], fifty)); // 1 m^2 is not above 1 m^2
  EXPECT_TRUE(reached(s[3], fifty));
  EXPECT_FALSE(reached(s[4], fifty));
}

/// Level j of `n_fell`: n members, the first n_fell[j] with block 50 fallen, one more failed.
std::vector<FragilityLevelRun> synthetic_levels(const std::vector<double>& values,
                                                const std::vector<std::size_t>& n_fell,
                                                std::size_t n)
{
  std::vector<FragilityLevelRun> levels;
  for (std::size_t j = 0; j < values.size(); ++j)
  {
    FragilityLevelRun l{values[j], "level_0" + std::to_string(j + 1), {}};
    for (std::size_t i = 0; i < n; ++i)
      l.outcomes.push_back(member({{50, 0, i < n_fell[j], i < n_fell[j] + 1, false, 0.0, 0.0}}));
    l.outcomes.push_back(member({{50, 0, true, true, false, 0.0, 0.0}}, 0.0, "failed"));
    levels.push_back(l);
  }
  return levels;
}

TEST(Fragility, ReportCountsTheMembersAndFitsByMaximumLikelihood)
{
  FragilityOptions o;
  o.ensemble.scene = roof_wedge;
  o.ensemble.members = 9;
  o.key = "tunnel.wave.velocity.amplitude";
  const IntensityMeasure im{"PGV (outcrop)", "m/s", 2.0, "", std::nullopt};
  const std::vector<double> values = {0.5, 1.0, 1.5, 2.0};
  const std::vector<std::size_t> n_fell = {1, 3, 5, 7};
  const std::vector<DamageState> states = damage_states(o);
  const nlohmann::json j = fragility_json(o, im, states, synthetic_levels(values, n_fell, 8), 1.0);
  std::vector<statistics::FragilityLevel> fell;
  for (std::size_t l = 0; l < values.size(); ++l)
  {
    const nlohmann::json& level = j["levels"][l];
    EXPECT_EQ(level["im"].get<double>(), 2.0 * values[l]);
    EXPECT_EQ(level["n_counted"], 8u); // the failed member is not counted
    EXPECT_EQ(level["n_failed"], 1u);
    EXPECT_EQ(level["states"][1]["count"], n_fell[l]);
    EXPECT_EQ(level["states"][0]["count"], n_fell[l] + 1);
    const statistics::Interval w = statistics::wilson_interval(n_fell[l], 8);
    EXPECT_EQ(level["states"][1]["wilson_95"][0].get<double>(), w.low);
    fell.push_back({2.0 * values[l], 8, n_fell[l]});
  }
  const statistics::FragilityFit fit = statistics::fit_lognormal_fragility(fell);
  ASSERT_EQ(fit.status, statistics::FragilityFitStatus::resolved);
  const nlohmann::json& f = j["states"][1]["fit"];
  EXPECT_EQ(f["status"], "resolved");
  EXPECT_EQ(f["theta"].get<double>(), fit.theta);
  EXPECT_EQ(f["beta"].get<double>(), fit.beta);
  EXPECT_LT(f["bootstrap"]["theta_90"][0].get<double>(), fit.theta);
  EXPECT_GT(f["bootstrap"]["theta_90"][1].get<double>(), fit.theta);
  EXPECT_EQ(j["answer"].get<std::string>().rfind(
                "The median PGV (outcrop) at which a keyblock fell is", 0),
            0u)
      << j["answer"];
  // 3 of 8 at 1 (PGV 2 m/s) and 5 of 8 at 1.5 are as near one half: the lower is quoted, with
  // its Wilson interval [13.7, 69.4] %.
  EXPECT_NE(j["answer"].get<std::string>().find("at 2 m/s a keyblock fell in 38 % [14, 69] of 8"),
            std::string::npos)
      << j["answer"];
}

TEST(Fragility, SeparatedDataLeaveBetaUnresolvedWithTheBracket)
{
  FragilityOptions o;
  o.ensemble.scene = roof_wedge;
  o.key = "tunnel.wave.velocity.amplitude";
  const IntensityMeasure im{"PGV (outcrop)", "m/s", 2.0, "", std::nullopt};
  const nlohmann::json j = fragility_json(
      o, im, damage_states(o), synthetic_levels({0.5, 1.0, 1.5, 2.0}, {0, 0, 4, 4}, 4), 1.0);
  const nlohmann::json& f = j["states"][1]["fit"];
  EXPECT_EQ(f["status"], "separated");
  EXPECT_EQ(f["highest_none"].get<double>(), 2.0);
  EXPECT_EQ(f["lowest_all"].get<double>(), 3.0);
  EXPECT_NE(j["answer"].get<std::string>().find("between PGV (outcrop) 2 m/s (never) and 3 m/s "
                                                "(always): the runs separate perfectly, so beta "
                                                "is unresolved"),
            std::string::npos)
      << j["answer"];
  EXPECT_NE(fragility_markdown(j).find("| a keyblock fell | separated | in (2, 3] |"),
            std::string::npos);
}

TEST(Fragility, SeparationWithOnePartialLevelAtAnEndGivesTheBoundItHas)
{
  // None at the lower level, some at the upper and no level where all fell: separated without a
  // level of all (it crashed the report on JSON null before).
  FragilityOptions o;
  o.ensemble.scene = roof_wedge;
  o.key = "tunnel.wave.velocity.amplitude";
  const IntensityMeasure im{"PGV (outcrop)", "m/s", 2.0, "", std::nullopt};
  const nlohmann::json up =
      fragility_json(o, im, damage_states(o), synthetic_levels({0.5, 1.0}, {0, 2}, 4), 1.0);
  EXPECT_EQ(up["states"][1]["fit"]["status"], "separated");
  EXPECT_NE(up["answer"].get<std::string>().find(
                "No run had a keyblock fell up to PGV (outcrop) 1 m/s and some runs above it"),
            std::string::npos)
      << up["answer"];
  EXPECT_NE(fragility_markdown(up).find("| a keyblock fell | separated | in (1, -] |"),
            std::string::npos);
  const nlohmann::json down =
      fragility_json(o, im, damage_states(o), synthetic_levels({0.5, 1.0}, {2, 4}, 4), 1.0);
  EXPECT_NE(down["answer"].get<std::string>().find(
                "A keyblock fell in every run from PGV (outcrop) 2 m/s and in some runs below it"),
            std::string::npos)
      << down["answer"];
}

TEST(Fragility, ChosenLevelsExtendUntilTheFallsTenToNinetyPercentBandIsCovered)
{
  FragilityOptions o;
  o.n_levels = 2; // chosen: 1 and 4, a step of sqrt(4 / 1) = 2 beyond
  const std::vector<DamageState> states = damage_states(o);
  const auto beyond = [&](const std::vector<double>& values, const std::vector<std::size_t>& fell)
  { return level_beyond(o, states, synthetic_levels(values, fell, 8)); };
  // Half of the highest level's runs dropped a keyblock: a step above it.
  EXPECT_EQ(beyond({1.0, 4.0}, {0, 4}), std::optional<double>(8.0));
  EXPECT_EQ(beyond({1.0, 4.0}, {0, 7}), std::optional<double>(8.0)); // 7 / 8 < 0.9
  EXPECT_EQ(beyond({1.0, 4.0}, {0, 8}), std::nullopt);               // 0 and 1: covered
  // The top covered, the lowest level's 2 of 8 (> 0.1) is not: a step below it, also after a
  // level was added above (the levels in the order run).
  EXPECT_EQ(beyond({1.0, 4.0}, {2, 8}), std::optional<double>(0.5));
  EXPECT_EQ(beyond({1.0, 4.0, 8.0}, {1, 4, 8}), std::optional<double>(0.5));
  EXPECT_EQ(beyond({1.0, 4.0, 8.0}, {0, 4, 8}), std::nullopt);
  // At most n_levels added; none before the chosen levels ran, none to levels given.
  EXPECT_EQ(beyond({1.0, 4.0, 8.0, 16.0}, {0, 1, 2, 3}), std::nullopt);
  o.n_levels = 3;
  EXPECT_EQ(beyond({1.0, 4.0}, {0, 4}), std::nullopt);
  o.n_levels = 2;
  o.levels = {1.0, 4.0};
  EXPECT_EQ(beyond({1.0, 4.0}, {0, 4}), std::nullopt);
}

TEST(Fragility, AnEarlierBracketIsReusedOnlyForTheSameQuestion)
{
  // A sweep.json as run_sweep writes it (the fields earlier_bracket reads): the roof-wedge
  // tunnel's amplitude bracketed with one --set, cases at 0.1 and 0.4 m/s.
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "ddafem_test_fragility_bracket";
  std::filesystem::create_directories(dir);
  const nlohmann::json sweep = {
      {"scene", roof_wedge},
      {"key", "tunnel.wave.velocity.amplitude"},
      {"settings", {"tunnel.settle.enabled=false"}},
      {"conclusion", "critical value between 0.1 and 0.4"},
      {"cases", {{{"value", 0.1}, {"exceeded", false}}, {{"value", 0.4}, {"exceeded", true}}}}};
  std::ofstream(dir / "sweep.json") << sweep.dump();
  SweepOptions s;
  s.scene = roof_wedge;
  s.key = "tunnel.wave.velocity.amplitude";
  s.settings = {"tunnel.settle.enabled=false"};
  s.directory = dir.string();
  EXPECT_EQ(earlier_bracket(s), sweep);
  s.low = 0.1;
  s.high = 0.4;
  EXPECT_EQ(earlier_bracket(s), sweep) << "--low and --high among its cases";
  s.high = 0.5;
  EXPECT_TRUE(earlier_bracket(s).is_null()) << "--high 0.5 was not run";
  s.high.reset();
  s.settings = {"tunnel.settle.enabled=true"};
  EXPECT_TRUE(earlier_bracket(s).is_null()) << "another --set";
  s.settings = {"tunnel.settle.enabled=false"};
  s.key = "tunnel.wave.velocity.frequency";
  EXPECT_TRUE(earlier_bracket(s).is_null()) << "another key";
  s.key = "tunnel.wave.velocity.amplitude";
  nlohmann::json unfinished = sweep;
  unfinished.erase("conclusion");
  std::ofstream(dir / "sweep.json") << unfinished.dump();
  EXPECT_TRUE(earlier_bracket(s).is_null()) << "a sweep that did not conclude";
  std::filesystem::remove_all(dir);
  EXPECT_TRUE(earlier_bracket(s).is_null()) << "no sweep.json";
}

TEST(Fragility, IntensityMeasureOfTheTunnelsSinePulse)
{
  const double g = 9.80665;
  const IntensityMeasure pgv = intensity_measure(roof_wedge, {}, "tunnel.wave.velocity.amplitude");
  EXPECT_EQ(pgv.name, "PGV (outcrop)");
  EXPECT_EQ(pgv.factor, 2.0);
  ASSERT_TRUE(pgv.pga_g_per_im);
  EXPECT_NEAR(*pgv.pga_g_per_im, 2.0 * M_PI * 25.0 / g, 1e-12); // the scene's 25 Hz pulse
  const IntensityMeasure at_10_hz = intensity_measure(
      roof_wedge, {"tunnel.wave.velocity.frequency=10"}, "tunnel.wave.velocity.amplitude");
  EXPECT_NEAR(*at_10_hz.pga_g_per_im, 2.0 * M_PI * 10.0 / g, 1e-12);
  const IntensityMeasure other = intensity_measure(roof_wedge, {}, "rock_mass.friction_angle");
  EXPECT_EQ(other.factor, 1.0);
  EXPECT_EQ(other.name, "rock_mass.friction_angle");
  EXPECT_FALSE(other.pga_g_per_im);
}

TEST(Fragility, RecordsPgaPerPgvFromASummary)
{
  // summary.json's records[0] (app/run/run_summary.cc): PGA 0.4 g with PGV 0.25 m/s: 1.6 g per m/s.
  const nlohmann::json summary = {
      {"records", {{{"where", "far_field.incident.velocity"}, {"pga_g", 0.4}, {"pgv_m_s", 0.25}}}}};
  ASSERT_TRUE(record_pga_g_per_pgv(summary));
  EXPECT_DOUBLE_EQ(*record_pga_g_per_pgv(summary), 1.6);
  EXPECT_FALSE(record_pga_g_per_pgv(nlohmann::json{{"records", nlohmann::json::array()}}));
  EXPECT_FALSE(record_pga_g_per_pgv(nlohmann::json{{"status", "completed"}}));
}

} // namespace
