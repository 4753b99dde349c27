// `ddafem ensemble` (app/studies/ensemble.h) without running members: its options checked against
// the roof-wedge tunnel (keys, distributions, ranges, the round-off key, the seeds), the members'
// values, and the report gathered from synthetic summaries against counts done by hand.
#include "app/studies/ensemble.h"

#include "common/input_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace
{
using namespace ddafem;

EnsembleOptions roof_wedge_options()
{
  EnsembleOptions o;
  o.scene = std::string(DDAFEM_SOURCE_DIR) + "/examples/tunnel/roof_wedge_sv.yaml";
  o.members = 8;
  o.settings = {"tunnel.settle.enabled=false"};
  return o;
}

/// The InputError message of plan_ensemble, or "no error".
std::string plan_error(const EnsembleOptions& o)
{
  try
  {
    plan_ensemble(o);
  }
  catch (const InputError& e)
  {
    return e.what();
  }
  return "no error";
}

TEST(Ensemble, BadVaryTextsAreRefusedNamingThem)
{
  EnsembleOptions o = roof_wedge_options();
  const auto error_of = [&](const std::string& vary)
  {
    o.vary = {vary};
    return plan_error(o);
  };
  // An unknown key: the scene reader's message, prefixed by the option.
  std::string e = error_of("joint_materials.clean.friction=normal(35,2)");
  EXPECT_NE(e.find("--vary joint_materials.clean.friction=normal(35,2)"), std::string::npos) << e;
  EXPECT_NE(e.find("friction"), std::string::npos) << e;
  // A key that is not a number.
  e = error_of("joint_materials.clean.bonded=uniform(0,1)");
  EXPECT_NE(e.find("of type boolean: expected a numeric key"), std::string::npos) << e;
  e = error_of("joint_materials.clean.friction_angle=gauss(35,2)");
  EXPECT_NE(e.find("unknown distribution 'gauss'"), std::string::npos) << e;
  e = error_of("joint_materials.clean.friction_angle=normal(35,-2)");
  EXPECT_NE(e.find("sd > 0, found -2"), std::string::npos) << e;
  // friction_angle is in [0, 90): a normal distribution leaves it, a truncated one does not.
  e = error_of("joint_materials.clean.friction_angle=normal(35,2)");
  EXPECT_NE(e.find("leave the range of key 'joint_materials.clean.friction_angle' ([0, 90))"),
            std::string::npos)
      << e;
  e = error_of("joint_materials.clean.friction_angle=uniform(30,90)"); // 90 excluded
  EXPECT_NE(e.find("leave the range"), std::string::npos) << e;
  e = error_of("joint_materials.clean.friction_angle");
  EXPECT_NE(e.find("expected KEY=DIST"), std::string::npos) << e;
  EXPECT_EQ(error_of("joint_materials.clean.friction_angle=truncnormal(35,2,30,40)"), "no error");
  // A spread of the incident wave, in a time function: lognormal stays above 0.
  EXPECT_EQ(error_of("tunnel.wave.velocity.amplitude=lognormal(0.1,0.3)"), "no error");
  o.vary = {"tunnel.k0=uniform(0.4,0.6)", "tunnel.k0=uniform(0.5,0.7)"};
  EXPECT_NE(plan_error(o).find("varied twice"), std::string::npos);
}

TEST(Ensemble, RoundoffKeyAndSeeds)
{
  EnsembleOptions o = roof_wedge_options();
  o.roundoff = "";
  const EnsemblePlan plan = plan_ensemble(o);
  EXPECT_EQ(plan.roundoff_key, "tunnel.wave.velocity.amplitude");
  EXPECT_EQ(plan.roundoff_value, 0.1);
  ASSERT_EQ(plan.seed_keys, std::vector<std::string>{"tunnel.seed"});
  // Its joint sets have no perturbation: the seeds change nothing, and it says so.
  EXPECT_NE(plan.seed_warning.find("change nothing"), std::string::npos);
  o.settings.push_back("tunnel.joint_sets.0.perturbation.spacing=0.2");
  EXPECT_EQ(plan_ensemble(o).seed_warning, "");
  o.roundoff = "tunnel.depth";
  EXPECT_EQ(plan_ensemble(o).roundoff_value, 50.0);
  o.roundoff = "tunnel.rock";
  EXPECT_NE(plan_error(o).find("of type string: expected a numeric key"), std::string::npos);
  o.roundoff = "tunnel.wave.velocity.start"; // a number with a default, absent from the scene
  EXPECT_NE(plan_error(o).find("no number other than 0"), std::string::npos);
  o.roundoff.reset();
  o.members = 0;
  EXPECT_NE(plan_error(o).find("expected at least 1 member"), std::string::npos);
}

TEST(Ensemble, MembersDrawDeterministicValues)
{
  EnsembleOptions o = roof_wedge_options();
  o.vary = {"joint_materials.clean.friction_angle=truncnormal(35,2,30,40)"};
  o.roundoff = "";
  const EnsemblePlan plan = plan_ensemble(o);
  std::set<std::uint64_t> seeds;
  for (std::size_t k = 0; k < 8; ++k)
  {
    const Member m = plan_member(o, plan, k);
    ASSERT_EQ(m.values.size(), 3u); // tunnel.seed, the friction angle, the amplitude
    EXPECT_EQ(m.values[0].first, "tunnel.seed");
    EXPECT_EQ(m.values[0].second, static_cast<double>(m.seed));
    EXPECT_LT(m.seed, 1ULL << 31);
    seeds.insert(m.seed);
    EXPECT_GE(m.values[1].second, 30.0);
    EXPECT_LE(m.values[1].second, 40.0);
    EXPECT_EQ(m.values[1].second,
              plan.varied[0].distribution.sample(statistics::mix_seed(1, 1), k));
    // The round-off: 0.1 (1 + k 1e-12), passed with 17 digits so that it reads back exactly.
    EXPECT_EQ(m.values[2].second, 0.1 * (1.0 + static_cast<double>(k) * 1e-12));
    EXPECT_EQ(m.settings.front(), "tunnel.settle.enabled=false");
    EXPECT_EQ(m.settings.back(), "output.interval=0");
    const std::string amplitude = m.settings[m.settings.size() - 2];
    EXPECT_EQ(std::stod(amplitude.substr(amplitude.find('=') + 1)), m.values[2].second);
    EXPECT_EQ(plan_member(o, plan, k).values, m.values); // the same member again
  }
  EXPECT_EQ(seeds.size(), 8u);
  o.snapshots = true;
  EXPECT_EQ(plan_member(o, plan, 0).settings.back().rfind("tunnel.wave.velocity.amplitude=", 0),
            0u);
}

/// A summary.json of a tunnel run: block 50 fell or not, block 47's residual [m] and whether it
/// loosened, block 60 released by the excavation (and fell), the fallen area of opening 0.
nlohmann::json summary(const std::string& status, bool fell_50, double residual_47,
                       bool loosened_47)
{
  // Block 47 at 355 deg (sector 35 of 10 deg), 50 at 5 (sector 0), 60 at 15 (sector 1).
  const auto block = [](std::size_t id, bool fell, bool loosened, bool released, double r)
  {
    return nlohmann::json{{"id", id},
                          {"opening", 0},
                          {"fell", fell},
                          {"loosened", loosened},
                          {"released", released},
                          {"residual_relative_m", r},
                          {"angle_deg", id == 47   ? 355.0
                                        : id == 50 ? 5.0
                                                   : 15.0}};
  };
  return {{"status", status},
          {"keyblocks",
           {{"blocks",
             {block(47, false, loosened_47, false, residual_47),
              block(50, fell_50, false, false, 0.5), block(60, true, false, true, 1.0)}},
            {"openings", {{{"fallen_area_m2", fell_50 ? 1.5 : 0.5}, {"released_area_m2", 0.5}}}}}}};
}

TEST(Ensemble, ReportCountsCompletedMembers)
{
  EnsembleOptions o = roof_wedge_options();
  o.members = 11;
  const EnsemblePlan plan = plan_ensemble(o);
  std::vector<Member> members;
  std::vector<MemberOutcome> outcomes;
  // Members 0-9 complete: block 50 falls in 0, 3, 6; block 47's residual is (k + 1) mm and it
  // loosens in the 6 members with k >= 4. Member 10 failed numerically with block 50 fallen.
  for (std::size_t k = 0; k < 11; ++k)
  {
    members.push_back(plan_member(o, plan, k));
    const bool failed = k == 10;
    outcomes.push_back(member_outcome(
        k, failed ? 1 : 0,
        summary(failed ? "failed" : "completed", k % 3 == 0, 1e-3 * (k + 1), k >= 4)));
  }
  const nlohmann::json j = ensemble_json(o, plan, members, outcomes, 12.0);
  EXPECT_EQ(j["n_counted"], 10);
  EXPECT_EQ(j["failed"], nlohmann::json({10}));
  ASSERT_EQ(j["keyblocks"].size(), 3u);
  const nlohmann::json& b47 = j["keyblocks"][0];
  const nlohmann::json& b50 = j["keyblocks"][1];
  EXPECT_EQ(b50["id"], 50);
  EXPECT_EQ(b50["n"], 10);
  // 4 of 10 fell (k = 0, 3, 6, 9): the failed member's fall is not counted.
  EXPECT_EQ(b50["fell"]["count"], 4);
  EXPECT_EQ(b50["fell"]["p"], 0.4);
  const statistics::Interval w = statistics::wilson_interval(4, 10);
  EXPECT_EQ(b50["fell"]["wilson_95"][0], w.low);
  EXPECT_EQ(b50["fell"]["wilson_95"][1], w.high);
  EXPECT_EQ(b47["loosened"]["count"], 6);
  // Residuals 1..10 mm: median 5.5 mm, 5 % at h = 0.45 -> 1.45 mm, 95 % at 9.55 mm; the
  // median's 95 % interval [x_(2), x_(9)] (n = 10, statistics tests) = [2, 9] mm.
  const nlohmann::json& r = b47["residual_relative_m"];
  EXPECT_NEAR(r["median"].get<double>(), 5.5e-3, 1e-15);
  EXPECT_NEAR(r["q05"].get<double>(), 1.45e-3, 1e-15);
  EXPECT_NEAR(r["q95"].get<double>(), 9.55e-3, 1e-15);
  EXPECT_EQ(r["median_95"][0], 1e-3 * 2); // order statistics: the samples themselves
  EXPECT_EQ(r["median_95"][1], 1e-3 * 9);
  EXPECT_EQ(j["keyblocks"][2]["released"], 10);
  // By sector: 0-10 deg (block 50) fell in 4 of 10; 10-20 (block 60) was released in 10, which
  // does not count as a fall there; 350-360 (block 47) loosened in 6.
  const nlohmann::json& sectors = j["sectors"];
  ASSERT_EQ(sectors.size(), 3u);
  EXPECT_EQ(sectors[0]["from_deg"], 0.0);
  EXPECT_EQ(sectors[0]["fell"]["count"], 4);
  EXPECT_EQ(sectors[1]["to_deg"], 20.0);
  EXPECT_EQ(sectors[1]["fell"]["count"], 0);
  EXPECT_EQ(sectors[1]["released"], 10);
  EXPECT_EQ(sectors[2]["from_deg"], 350.0);
  EXPECT_EQ(sectors[2]["loosened"]["count"], 6);
  EXPECT_EQ(sectors[2]["fell"]["count"], 0);
  EXPECT_EQ(sectors[2]["with_keyblock"], 10);
  // Opening 0 loses 1.5 m^2 in the 4 members where block 50 fell, else 0.5: block 60, which
  // the excavation released and which is counted apart (0.5 in every member), not as damage.
  const nlohmann::json& opening = j["openings"][0];
  EXPECT_EQ(opening["any_fell"]["count"], 4);
  EXPECT_NEAR(opening["fallen_area_mean_m2"].get<double>(), 0.4, 1e-15);
  EXPECT_EQ(opening["released_area_m2"]["median"].get<double>(), 0.5);
  // The answer quotes block 50 (block 60 falls only where released), as a percentage with its
  // interval rounded to two digits: 40 % [17, 69].
  const std::string answer = j["answer"];
  EXPECT_NE(answer.find("Over 10 completed runs (1 failed numerically, excluded), block 50 falls, "
                        "the excavation having left it in place, in 40 % [17, 69] (95 % Wilson)"),
            std::string::npos)
      << answer;
  EXPECT_NE(answer.find("1 of 3 keyblocks loosen in at least half of the runs"), std::string::npos)
      << answer;
  const std::string md = ensemble_markdown(j);
  EXPECT_NE(md.find("**" + answer + "**"), std::string::npos);
  EXPECT_NE(md.find("| 50 | 0 | 10 | 40 % [17, 69] |"), std::string::npos) << md;
}

TEST(Ensemble, SummariesBeforeTheReleasedAreaSayTheirAreaIncludesIt)
{
  // A summary.json without keyblocks.openings[].released_area_m2 (written before it existed):
  // its fallen area cannot be split, and the outcome says so instead of calling it damage.
  const nlohmann::json old = {
      {"status", "completed"},
      {"keyblocks",
       {{"blocks", nlohmann::json::array()}, {"openings", {{{"fallen_area_m2", 0.344}}}}}}};
  const MemberOutcome m = member_outcome(0, 0, old);
  EXPECT_FALSE(m.released_area_known);
  EXPECT_EQ(m.fallen_area_m2, std::vector<double>{0.344});
  nlohmann::json now = old;
  now["keyblocks"]["openings"][0]["released_area_m2"] = 0.344;
  const MemberOutcome n = member_outcome(0, 0, now);
  EXPECT_TRUE(n.released_area_known);
  EXPECT_EQ(n.fallen_area_m2, std::vector<double>{0.0});
}

TEST(Ensemble, ReportWithoutFallsGivesTheUpperBound)
{
  EnsembleOptions o = roof_wedge_options();
  o.members = 2;
  const EnsemblePlan plan = plan_ensemble(o);
  const std::vector<Member> members = {plan_member(o, plan, 0), plan_member(o, plan, 1)};
  nlohmann::json s = summary("completed", false, 1e-3, false);
  s["keyblocks"]["blocks"].erase(2); // no released block
  const nlohmann::json j = ensemble_json(o, plan, members, {member_outcome(0, 0, s)}, 1.0);
  // 0 of 1: the Wilson upper bound is z^2 / (1 + z^2) = 3.8416 / 4.8416 = 79 %.
  EXPECT_NE(j["answer"].get<std::string>().find("no keyblock the excavation left in place fell "
                                                "(at most 79 %, the 95 % Wilson bound of 0 in 1)"),
            std::string::npos)
      << j["answer"];
  EXPECT_EQ(j["members"][1]["finished"], false);
  EXPECT_EQ(ensemble_json(o, plan, members, {}, 0.0)["answer"],
            "No run of the 2 has completed yet.");
}
} // namespace

namespace
{
TEST(Ensemble, ReportBySectorWhereTheBlocksDiffer)
{
  // Two members whose crown keyblocks differ (47 at 5 deg, 48 at 7 deg): the answer goes by
  // sector, 0 to 10 deg, where a keyblock fell in 1 of 2. Wilson(1, 2): 0.5 -+ 1.96
  // sqrt(0.125 + 0.2401) / 2.9208 = [0.0945, 0.9055].
  EnsembleOptions o = roof_wedge_options();
  o.members = 2;
  const EnsemblePlan plan = plan_ensemble(o);
  const auto member = [](std::size_t id, double angle, bool fell)
  {
    return nlohmann::json{
        {"status", "completed"},
        {"keyblocks",
         {{"blocks", {{{"id", id}, {"opening", 0}, {"fell", fell}, {"angle_deg", angle}}}}}}};
  };
  const nlohmann::json j = ensemble_json(
      o, plan, {plan_member(o, plan, 0), plan_member(o, plan, 1)},
      {member_outcome(0, 0, member(47, 5.0, true)), member_outcome(1, 0, member(48, 7.0, false))},
      1.0);
  ASSERT_EQ(j["sectors"].size(), 1u);
  EXPECT_EQ(j["sectors"][0]["with_keyblock"], 2);
  EXPECT_NE(j["answer"].get<std::string>().find(
                "(the blocks differ between them: by location), a keyblock the excavation left in "
                "place falls between 0 and 10 deg from the crown (clockwise) of opening 0 in 50 % "
                "[9.5, 91] (95 % Wilson)"),
            std::string::npos)
      << j["answer"];
}
} // namespace
