// What an ensemble reports (app/studies/ensemble.h): the members' summaries gathered into
// probabilities with Wilson intervals and sample quantiles (common/statistics.h), as
// ensemble.json and ensemble.md.
#include "app/studies/ensemble.h"

#include "app/scene/scene_text.h"
#include "common/format.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

namespace ddafem
{
MemberOutcome member_outcome(const std::size_t index, const int exit_code,
                             const nlohmann::json& summary)
{
  MemberOutcome m;
  m.index = index;
  m.exit_code = exit_code;
  if (!summary.is_object())
    return m;
  m.status = summary.value("status", "");
  const nlohmann::json::json_pointer base("/far_field/free_field_at_base/pgv_m_s");
  if (summary.contains(base) && summary[base].is_number())
    m.pgv_at_base_m_s = summary[base].get<double>();
  const nlohmann::json keyblocks = summary.value("keyblocks", nlohmann::json());
  if (!keyblocks.is_object())
    return m;
  for (const nlohmann::json& b : keyblocks.value("blocks", nlohmann::json::array()))
    m.keyblocks.push_back({b.value("id", std::size_t(0)), b.value("opening", std::size_t(0)),
                           b.value("fell", false), b.value("loosened", false),
                           b.value("released", false), b.value("residual_relative_m", 0.0),
                           b.value("angle_deg", std::nan(""))});
  for (const nlohmann::json& o : keyblocks.value("openings", nlohmann::json::array()))
  {
    // The blocks a static stage released (the excavation's) fall in every member alike: they
    // are counted apart, not as the member's damage.
    m.released_area_known = m.released_area_known && o.contains("released_area_m2");
    const double released = o.value("released_area_m2", 0.0);
    m.released_area_m2.push_back(released);
    m.fallen_area_m2.push_back(std::max(0.0, o.value("fallen_area_m2", 0.0) - released));
  }
  return m;
}

namespace
{
using statistics::Interval;

/// A keyblock's verdicts over the counted members in which it is a keyblock.
struct KeyblockTally
{
  std::size_t opening = 0, n = 0, n_fell = 0, n_loosened = 0, n_released = 0;
  std::size_t n_fell_in_place = 0; ///< fell where the excavation had not released it
  std::vector<double> residuals_m;
};

nlohmann::json interval_json(const Interval& i)
{
  return {i.low, i.high};
}

/// The 5 %, 50 %, 95 % quantiles of a sample and the median's 95 % interval (null if the
/// sample is too small for one).
nlohmann::json sample_json(const std::vector<double>& sample)
{
  const statistics::SampleSummary s = statistics::summarize(sample);
  if (s.n == 0)
    return nullptr;
  const statistics::MedianInterval& m = s.median_interval;
  return {{"n", s.n},
          {"median", s.median},
          {"q05", s.q05},
          {"q95", s.q95},
          {"median_95", m.available ? interval_json(m.interval) : nlohmann::json()},
          {"median_95_ranks",
           m.available ? nlohmann::json({m.rank, s.n + 1 - m.rank}) : nlohmann::json()},
          {"median_95_coverage", m.available ? nlohmann::json(m.coverage) : nlohmann::json()}};
}

} // namespace

double members_wall_s(const std::vector<MemberOutcome>& outcomes)
{
  double sum = 0.0;
  for (const MemberOutcome& m : outcomes)
    sum += m.wall_s;
  return sum;
}

nlohmann::json pgv_at_base_json(const std::vector<MemberOutcome>& outcomes)
{
  std::vector<double> pgv;
  for (const MemberOutcome& m : outcomes)
    if (m.counted() && m.pgv_at_base_m_s)
      pgv.push_back(*m.pgv_at_base_m_s);
  return sample_json(pgv);
}

nlohmann::json proportion_json(std::size_t k, std::size_t n)
{
  return {{"count", k},
          {"p", n > 0 ? static_cast<double>(k) / static_cast<double>(n) : 0.0},
          {"wilson_95", interval_json(statistics::wilson_interval(k, n))}};
}

namespace
{

/// Per keyblock id, its tally over the counted members.
std::map<std::size_t, KeyblockTally> tally_keyblocks(const std::vector<MemberOutcome>& outcomes)
{
  std::map<std::size_t, KeyblockTally> tallies;
  for (const MemberOutcome& m : outcomes)
    if (m.counted())
      for (const KeyblockOutcome& k : m.keyblocks)
      {
        KeyblockTally& t = tallies[k.id];
        t.opening = k.opening;
        ++t.n;
        t.n_fell += k.fell ? 1 : 0;
        t.n_fell_in_place += k.fell && !k.released ? 1 : 0;
        t.n_loosened += k.loosened ? 1 : 0;
        t.n_released += k.released ? 1 : 0;
        t.residuals_m.push_back(k.residual_relative_m);
      }
  return tallies;
}

nlohmann::json keyblocks_json(const std::vector<MemberOutcome>& outcomes)
{
  nlohmann::json list = nlohmann::json::array();
  for (const auto& [id, t] : tally_keyblocks(outcomes))
    list.push_back({{"id", id},
                    {"opening", t.opening},
                    {"n", t.n},
                    {"fell", proportion_json(t.n_fell, t.n)},
                    {"fell_in_place", proportion_json(t.n_fell_in_place, t.n)},
                    {"loosened", proportion_json(t.n_loosened, t.n)},
                    {"released", t.n_released},
                    {"residual_relative_m", sample_json(t.residuals_m)}});
  return list;
}

/// Per sector of each opening's perimeter (`width` degrees from the crown clockwise) in which
/// some member has a keyblock: in how many counted members a keyblock there fell (not one the
/// excavation released: that one falls whatever the shaking), loosened, was released.
nlohmann::json sectors_json(const std::vector<MemberOutcome>& outcomes, const double width)
{
  struct Counts
  {
    std::size_t with_keyblock = 0, fell = 0, loosened = 0, released = 0;
  };
  std::map<std::pair<std::size_t, long>, Counts> sectors; // (opening, sector)
  std::size_t n = 0;
  for (const MemberOutcome& m : outcomes)
  {
    if (!m.counted())
      continue;
    ++n;
    std::map<std::pair<std::size_t, long>, std::array<bool, 3>> seen; // fell, loosened, released
    for (const KeyblockOutcome& k : m.keyblocks)
      if (std::isfinite(k.angle_deg))
      {
        std::array<bool, 3>& s = seen[{k.opening, std::lround(std::floor(k.angle_deg / width))}];
        s = {s[0] || (k.fell && !k.released), s[1] || k.loosened, s[2] || k.released};
      }
    for (const auto& [where, s] : seen)
    {
      Counts& c = sectors[where];
      c.with_keyblock += 1;
      c.fell += s[0] ? 1 : 0;
      c.loosened += s[1] ? 1 : 0;
      c.released += s[2] ? 1 : 0;
    }
  }
  nlohmann::json list = nlohmann::json::array();
  for (const auto& [where, c] : sectors)
    list.push_back({{"opening", where.first},
                    {"from_deg", static_cast<double>(where.second) * width},
                    {"to_deg", static_cast<double>(where.second + 1) * width},
                    {"with_keyblock", c.with_keyblock},
                    {"fell", proportion_json(c.fell, n)},
                    {"loosened", proportion_json(c.loosened, n)},
                    {"released", c.released}});
  return list;
}

/// Per opening: the fallen area of the counted members and how often anything fell there.
nlohmann::json openings_json(const std::vector<MemberOutcome>& outcomes)
{
  std::vector<std::vector<double>> areas, released;
  bool released_known = true;
  for (const MemberOutcome& m : outcomes)
    if (m.counted())
    {
      released_known = released_known && m.released_area_known;
      for (std::size_t o = 0; o < m.fallen_area_m2.size(); ++o)
      {
        areas.resize(std::max(areas.size(), o + 1));
        released.resize(areas.size());
        areas[o].push_back(m.fallen_area_m2[o]);
        released[o].push_back(o < m.released_area_m2.size() ? m.released_area_m2[o] : 0.0);
      }
    }
  nlohmann::json list = nlohmann::json::array();
  for (std::size_t o = 0; o < areas.size(); ++o)
  {
    const std::size_t n_any = static_cast<std::size_t>(
        std::count_if(areas[o].begin(), areas[o].end(), [](double a) { return a > 0.0; }));
    double mean = 0.0;
    for (const double a : areas[o])
      mean += a / static_cast<double>(areas[o].size());
    list.push_back({{"opening", o},
                    {"any_fell", proportion_json(n_any, areas[o].size())},
                    {"fallen_area_m2", sample_json(areas[o])},
                    {"fallen_area_mean_m2", mean},
                    {"fallen_area_max_m2", *std::max_element(areas[o].begin(), areas[o].end())},
                    {"released_area_m2", sample_json(released[o])},
                    {"released_area_known", released_known}});
  }
  return list;
}

/// A fraction in percent: whole numbers from 10 %, two significant digits below ("4.2").
std::string percent(const double fraction)
{
  const double x = 100.0 * fraction;
  return x >= 9.95 ? std::to_string(std::lround(x)) : format_significant(x, 2);
}

} // namespace

std::string percent_text(const nlohmann::json& p)
{
  return percent(p["p"].get<double>()) + " % [" + percent(p["wilson_95"][0].get<double>()) + ", " +
         percent(p["wilson_95"][1].get<double>()) + "]";
}

namespace
{

/// The sentence an engineer can quote: the keyblock likeliest to fall, how many loosen, the
/// fallen area.
std::string answer_sentence(const nlohmann::json& j)
{
  const std::size_t n = j["n_counted"], n_total = j["members_requested"];
  std::ostringstream s;
  if (n == 0 && j["n_finished"] == 0)
    return "No run of the " + std::to_string(n_total) + " has completed yet.";
  if (n == 0)
    return "None of the " + j["n_finished"].dump() + " runs that ended (of " +
           std::to_string(n_total) + ") completed: " + std::to_string(j["failed"].size()) +
           " failed numerically or without a summary, " + std::to_string(j["stopped"].size()) +
           " stopped at a budget.";
  s << "Over " << n << " completed runs";
  if (!j["failed"].empty())
    s << " (" << j["failed"].size() << " failed numerically, excluded)";
  const nlohmann::json* likeliest = nullptr;
  std::size_t n_loosen_often = 0;
  for (const nlohmann::json& k : j["keyblocks"])
  {
    if (!likeliest ||
        k["fell_in_place"]["p"].get<double>() > (*likeliest)["fell_in_place"]["p"].get<double>())
      likeliest = &k;
    n_loosen_often += 2 * k["loosened"]["count"].get<std::size_t>() >= k["n"].get<std::size_t>();
  }
  const bool by_sector = std::any_of(j["keyblocks"].begin(), j["keyblocks"].end(),
                                     [&](const nlohmann::json& k) { return k["n"] != n; });
  const nlohmann::json* sector = nullptr; // the sector likeliest to lose a keyblock
  for (const nlohmann::json& x : j["sectors"])
    if (!sector || x["fell"]["p"].get<double>() > (*sector)["fell"]["p"].get<double>())
      sector = &x;
  if (j["keyblocks"].empty())
    s << ", the scene has no keyblocks";
  else if (by_sector && sector && (*sector)["fell"]["count"].get<std::size_t>() > 0)
    s << " (the blocks differ between them: by location), a keyblock the excavation left in "
         "place falls between "
      << (*sector)["from_deg"].get<double>() << " and " << (*sector)["to_deg"].get<double>()
      << " deg from the crown (clockwise) of opening " << (*sector)["opening"] << " in "
      << percent_text((*sector)["fell"]) << " (95 % Wilson)";
  else if (!by_sector && likeliest && (*likeliest)["fell_in_place"]["count"].get<std::size_t>() > 0)
    s << ", block " << (*likeliest)["id"] << " falls, the excavation having left it in place, in "
      << percent_text((*likeliest)["fell_in_place"]) << " (95 % Wilson)";
  else
    s << ", no keyblock the excavation left in place fell (at most "
      << percent(statistics::wilson_interval(0, n).high) << " %, the 95 % Wilson bound of 0 in "
      << n << ")";
  if (!j["keyblocks"].empty())
    s << "; " << n_loosen_often << " of " << j["keyblocks"].size()
      << " keyblocks loosen in at least half of the runs";
  for (const nlohmann::json& o : j["openings"])
    if (!o["fallen_area_m2"].is_null() && o["any_fell"]["count"].get<std::size_t>() > 0)
      s << "; opening " << o["opening"] << " loses a median "
        << format_significant(o["fallen_area_m2"]["median"].get<double>(), 3)
        << " m^3/m (5-95 %: " << format_significant(o["fallen_area_m2"]["q05"].get<double>(), 3)
        << " to " << format_significant(o["fallen_area_m2"]["q95"].get<double>(), 3)
        << (o.value("released_area_known", true)
                ? ") besides what the excavation released"
                : "), the blocks the excavation released included (these runs' summaries "
                  "predate keeping them apart)");
  s << ".";
  return s.str();
}

/// One member's entry: what it was given and what it said.
nlohmann::json member_json(const Member& m, const MemberOutcome* outcome)
{
  nlohmann::json values = nlohmann::json::object();
  for (const auto& [key, value] : m.values)
    values[key] = value;
  std::string number = std::to_string(m.index);
  number.insert(0, number.size() < 3 ? 3 - number.size() : 0, '0');
  nlohmann::json j = {{"index", m.index},
                      {"directory", "member_" + number},
                      {"seed", m.seed},
                      {"values", values},
                      {"finished", outcome != nullptr}};
  if (!outcome)
    return j;
  std::vector<std::size_t> fell, loosened, released;
  for (const KeyblockOutcome& k : outcome->keyblocks)
  {
    if (k.fell)
      fell.push_back(k.id);
    if (k.loosened)
      loosened.push_back(k.id);
    if (k.released)
      released.push_back(k.id);
  }
  j.update({{"exit_code", outcome->exit_code},
            {"status", outcome->status},
            {"counted", outcome->counted()},
            {"fell", fell},
            {"loosened", loosened},
            {"released", released},
            {"fallen_area_m2", outcome->fallen_area_m2},
            {"wall_s", outcome->wall_s}});
  return j;
}
} // namespace

std::string scene_path(const std::string& scene)
{
  return std::filesystem::weakly_canonical(std::filesystem::absolute(scene)).string();
}

nlohmann::json ensemble_json(const EnsembleOptions& o, const EnsemblePlan& plan,
                             const std::vector<Member>& members,
                             const std::vector<MemberOutcome>& outcomes, const double wall_s)
{
  std::vector<const MemberOutcome*> by_member(members.size(), nullptr);
  std::vector<std::size_t> failed, stopped;
  std::size_t n_counted = 0;
  for (const MemberOutcome& m : outcomes)
  {
    if (m.index < by_member.size())
      by_member[m.index] = &m;
    n_counted += m.counted() ? 1 : 0;
    if (m.status == "stopped")
      stopped.push_back(m.index);
    else if (!m.counted())
      failed.push_back(m.index); // failed numerically, or ended without a summary
  }
  std::sort(failed.begin(), failed.end());
  std::sort(stopped.begin(), stopped.end());
  nlohmann::json list = nlohmann::json::array(), varied = nlohmann::json::array();
  for (const Member& m : members)
    list.push_back(member_json(m, by_member[m.index]));
  for (const VariedKey& v : plan.varied)
    varied.push_back({{"key", v.key}, {"distribution", v.distribution.text}});
  nlohmann::json j = {{"scene", o.scene},
                      {"scene_path", scene_path(o.scene)},
                      {"settings", o.settings},
                      {"members_requested", o.members},
                      {"seed", o.seed},
                      {"vary", o.vary},
                      {"varied", varied},
                      {"roundoff_key", plan.roundoff_key},
                      {"seed_keys", plan.seed_keys},
                      {"seed_warning", plan.seed_warning},
                      {"snapshots", o.snapshots},
                      {"n_finished", outcomes.size()},
                      {"n_counted", n_counted},
                      {"failed", failed},
                      {"stopped", stopped},
                      {"keyblocks", keyblocks_json(outcomes)},
                      {"sector_deg", o.sector_deg},
                      {"sectors", sectors_json(outcomes, o.sector_deg)},
                      {"openings", openings_json(outcomes)},
                      {"pgv_at_base_m_s", pgv_at_base_json(outcomes)},
                      {"members", list},
                      {"wall_s", wall_s},
                      {"members_wall_s", members_wall_s(outcomes)}};
  j["answer"] = answer_sentence(j);
  return j;
}

namespace
{
/// "12.3 (5-95 %: 10.1 to 15.2)" of a sample_json in mm, or "-".
std::string residual_cells(const nlohmann::json& r)
{
  if (r.is_null())
    return "- | - | -";
  const auto mm = [](const nlohmann::json& x)
  { return format_significant(1e3 * x.get<double>(), 3); };
  return mm(r["median"]) + " | " + mm(r["q05"]) + " to " + mm(r["q95"]) + " | " +
         (r["median_95"].is_null() ? std::string("too few runs")
                                   : mm(r["median_95"][0]) + " to " + mm(r["median_95"][1]));
}

void keyblock_table(const nlohmann::json& j, std::ostringstream& md)
{
  md << "\n## Keyblocks\n\nOver the completed runs in which the block is a keyblock (n); "
        "probabilities with their 95 % Wilson intervals; the residual displacement relative to "
        "the rock around the opening [mm]: median, 5-95 % of the runs, and the median's 95 % "
        "interval from order statistics.\n\n"
        "| block | opening | n | P(fell) | P(loosened) | released by the excavation | residual "
        "median [mm] | 5-95 % [mm] | median's 95 % [mm] |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const nlohmann::json& k : j["keyblocks"])
    md << "| " << k["id"] << " | " << k["opening"] << " | " << k["n"] << " | "
       << percent_text(k["fell"]) << " | " << percent_text(k["loosened"]) << " | " << k["released"]
       << " | " << residual_cells(k["residual_relative_m"]) << " |\n";
}

void sector_table(const nlohmann::json& j, std::ostringstream& md)
{
  md << "\n## Sectors\n\nBy location, which holds where the members' blocks differ: sectors of "
     << j["sector_deg"] << " deg of each opening's perimeter, from the crown (0) clockwise (90 the "
     << "right wall, 180 the invert), by the keyblocks' centroids at the start. P: a keyblock in "
        "the sector fell (a block the excavation released not counted), loosened, over all "
        "completed runs, with its 95 % Wilson interval.\n\n"
        "| opening | sector [deg] | runs with a keyblock there | P(a keyblock fell) | "
        "P(a keyblock loosened) | runs in which the excavation released one |\n"
        "|---|---|---|---|---|---|\n";
  for (const nlohmann::json& s : j["sectors"])
    md << "| " << s["opening"] << " | " << s["from_deg"].get<double>() << " to "
       << s["to_deg"].get<double>() << " | " << s["with_keyblock"] << " | "
       << percent_text(s["fell"]) << " | " << percent_text(s["loosened"]) << " | " << s["released"]
       << " |\n";
}

void member_table(const nlohmann::json& j, std::ostringstream& md)
{
  md << "\n## Members\n\n| member | seed | values | status | fell | loosened | wall [s] |\n"
        "|---|---|---|---|---|---|---|\n";
  for (const nlohmann::json& m : j["members"])
  {
    std::vector<std::string> values;
    for (const auto& [key, value] : m["values"].items())
    {
      const double v = value.get<double>(); // a seed in full, other values to 6 digits
      values.push_back(key + " = " +
                       (v == std::floor(v) && std::abs(v) < 1e15 ? std::to_string(std::llround(v))
                                                                 : format_significant(v, 6)));
    }
    md << "| " << m["directory"].get<std::string>() << " | " << m["seed"] << " | "
       << scene_reading::join(values, ", ") << " | ";
    if (!m["finished"].get<bool>())
      md << "not run yet | | | |\n";
    else
      md << (m["status"].get<std::string>().empty()
                 ? "no summary, exit code " + m["exit_code"].dump()
                 : m["status"].get<std::string>())
         << " | " << m["fell"].dump() << " | " << m["loosened"].dump() << " | "
         << format_significant(m["wall_s"].get<double>(), 3) << " |\n";
  }
}
} // namespace

std::string ensemble_markdown(const nlohmann::json& j)
{
  std::ostringstream md;
  md << "# Ensemble of " << std::filesystem::path(j["scene"].get<std::string>()).filename().string()
     << "\n\n**" << j["answer"].get<std::string>() << "**\n\n"
     << "Scene `" << j["scene"].get<std::string>() << "`, " << j["n_finished"] << " of "
     << j["members_requested"] << " members run in "
     << format_significant(j["wall_s"].get<double>(), 3)
     << " s (this call; the members' wall times, of this call and any it resumed, sum to "
     << format_significant(j.value("members_wall_s", 0.0), 3) << " s), seed " << j["seed"] << ".";
  for (const nlohmann::json& v : j["varied"])
    md << " `" << v["key"].get<std::string>() << "` drawn from "
       << v["distribution"].get<std::string>() << ".";
  if (!j["roundoff_key"].get<std::string>().empty())
    md << " Member k's `" << j["roundoff_key"].get<std::string>() << "` x (1 + k 1e-12).";
  if (!j["seed_keys"].empty())
    md << " Each member's seed on " << j["seed_keys"].dump() << ".";
  if (!j["seed_warning"].get<std::string>().empty())
    md << " Warning: " << j["seed_warning"].get<std::string>() << ".";
  if (!j["failed"].empty())
    md << " Failed (not counted): members " << j["failed"].dump() << ".";
  if (!j["stopped"].empty())
    md << " Stopped at a budget (not counted): members " << j["stopped"].dump() << ".";
  md << "\n";
  keyblock_table(j, md);
  sector_table(j, md);
  md << "\n## Openings\n\nFallen area per opening [m^2, = m^3 per metre of tunnel] over the "
        "completed runs: the blocks that fell in the run, apart from those a static stage (the "
        "excavation) released, whose area is the last column (median).\n\n"
        "| opening | P(anything fell) | median | 5-95 % | mean | max | released [m^2] |\n"
        "|---|---|---|---|---|---|---|\n";
  for (const nlohmann::json& o : j["openings"])
  {
    const nlohmann::json& a = o["fallen_area_m2"];
    md << "| " << o["opening"] << " | " << percent_text(o["any_fell"]) << " | "
       << format_significant(a["median"].get<double>(), 3) << " | "
       << format_significant(a["q05"].get<double>(), 3) << " to "
       << format_significant(a["q95"].get<double>(), 3) << " | "
       << format_significant(o["fallen_area_mean_m2"].get<double>(), 3) << " | "
       << format_significant(o["fallen_area_max_m2"].get<double>(), 3) << " | "
       << format_significant(o["released_area_m2"]["median"].get<double>(), 3) << " |\n";
  }
  const nlohmann::json& pgv = j["pgv_at_base_m_s"];
  if (!pgv.is_null())
    md << "\nThe wave arriving at the near field's base (the free-field column's PGV there, "
          "damped on its way): median "
       << format_significant(pgv["median"].get<double>(), 3)
       << " m/s (5-95 %: " << format_significant(pgv["q05"].get<double>(), 3) << " to "
       << format_significant(pgv["q95"].get<double>(), 3) << ").\n";
  md << "\nThe picture: `python3 tools/plot_ensemble.py DIR` writes DIR/ensemble.png (the "
        "opening, each keyblock or sector coloured by its probability of falling and of "
        "loosening).\n";
  member_table(j, md);
  return md.str();
}

} // namespace ddafem
