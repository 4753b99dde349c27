// fragility.json and fragility.md of `ddafem fragility` (app/studies/fragility.h).
#include "app/studies/fragility.h"

#include "app/scene/scene_text.h"
#include "common/format.h"

#include <cmath>
#include <sstream>

namespace ddafem
{
namespace
{
/// HAZUS (FEMA, Table 7-9) bored or drilled rock tunnels, PGA at the site: median [g], beta.
struct HazusCurve
{
  const char* state;
  double pga_median_g;
  double beta;
};
constexpr std::array<HazusCurve, 2> hazus_bored_tunnels = {
    {{"slight", 0.6, 0.6}, {"moderate", 0.8, 0.6}}};

/// Bootstrap resamples of each fit.
constexpr std::size_t n_resamples = 1000;

nlohmann::json optional_json(const std::optional<double>& v)
{
  return v ? nlohmann::json(*v) : nlohmann::json();
}

/// Per level, the members counted (completed) and those reaching `state`.
std::vector<statistics::FragilityLevel> counts(const IntensityMeasure& im, const DamageState& state,
                                               const std::vector<FragilityLevelRun>& levels)
{
  std::vector<statistics::FragilityLevel> c;
  for (const FragilityLevelRun& l : levels)
    if (const statistics::FragilityLevel f = level_count(state, l, im.factor * l.value); f.n > 0)
      c.push_back(f);
  return c;
}

/// A damage state's fit: status, theta [IM] and beta with 90 % bootstrap bounds when resolved,
/// the bracket when separated or one-sided.
nlohmann::json fit_json(const std::vector<statistics::FragilityLevel>& c, std::uint64_t seed)
{
  const statistics::FragilityFit fit = statistics::fit_lognormal_fragility(c);
  nlohmann::json j = {{"status", name_of(fit.status)},
                      {"highest_none", optional_json(fit.highest_none)},
                      {"lowest_all", optional_json(fit.lowest_all)}};
  if (fit.status != statistics::FragilityFitStatus::resolved)
    return j;
  const statistics::FragilityBounds b = statistics::bootstrap_fragility(c, n_resamples, seed);
  j.update({{"theta", fit.theta},
            {"beta", fit.beta},
            {"log_likelihood", fit.log_likelihood},
            {"bootstrap",
             {{"theta_90", {b.theta.low, b.theta.high}},
              {"beta_90", {b.beta.low, b.beta.high}},
              {"n_resamples", b.n_resamples},
              {"n_unresolved", b.n_unresolved}}}});
  return j;
}

/// "1.62 m/s" of an IM value.
std::string im_text(const double v, const nlohmann::json& im)
{
  const std::string unit = im["unit"];
  return format_significant(v, 3) + (unit.empty() ? "" : " " + unit);
}

/// A bootstrap bound: "unbounded" where resamples drove it to infinity (JSON null).
std::string bound_text(const nlohmann::json& v, const int digits)
{
  if (!v.is_number() || !std::isfinite(v.get<double>()))
    return "unbounded";
  return format_significant(v.get<double>(), digits);
}

/// The sentence of one damage state: its median and beta, or what the data allow. `highest_im`:
/// the highest level run, beyond which a median is an extrapolation of the fit.
std::string state_sentence(const nlohmann::json& s, const nlohmann::json& im,
                           const double highest_im)
{
  const nlohmann::json& f = s["fit"];
  const std::string status = f["status"], name = im["name"];
  std::ostringstream t;
  if (status == "resolved")
  {
    const nlohmann::json& b = f["bootstrap"];
    t << "the median " << name << " at which " << s["name"].get<std::string>() << " is "
      << im_text(f["theta"], im) << " [" << bound_text(b["theta_90"][0], 3) << ", "
      << bound_text(b["theta_90"][1], 3) << "], beta "
      << format_significant(f["beta"].get<double>(), 2) << " [" << bound_text(b["beta_90"][0], 2)
      << ", " << bound_text(b["beta_90"][1], 2) << "] (90 % bootstrap)";
    if (f["theta"].get<double>() > highest_im)
      t << ", extrapolated beyond the highest level run (" << im_text(highest_im, im)
        << "): more levels above it would pin it down";
  }
  else if (status == "separated" && f["lowest_all"].is_null()) // none, then one level partly
    t << "no run had " << s["name"].get<std::string>() << " up to " << name << " "
      << im_text(f["highest_none"], im)
      << " and some runs above it: the runs separate, so beta is unresolved (smaller than the "
         "levels resolve) and the median lies above "
      << im_text(f["highest_none"], im) << " (more levels above would bound it)";
  else if (status == "separated" && f["highest_none"].is_null()) // one level partly, then all
    t << s["name"].get<std::string>() << " in every run from " << name << " "
      << im_text(f["lowest_all"], im)
      << " and in some runs below it: the runs separate, so beta is unresolved (smaller than "
         "the levels resolve) and the median lies below "
      << im_text(f["lowest_all"], im) << " (more levels below would bound it)";
  else if (status == "separated")
    t << s["name"].get<std::string>() << " between " << name << " "
      << im_text(f["highest_none"], im) << " (never) and " << im_text(f["lowest_all"], im)
      << " (always): the runs separate perfectly, so beta is unresolved (smaller than the "
         "levels resolve) and the median lies in that bracket";
  else if (!f["lowest_all"].is_null())
    t << s["name"].get<std::string>() << " in every run from " << name << " "
      << im_text(f["lowest_all"], im) << " (the median lies below the levels run)";
  else if (!f["highest_none"].is_null())
    t << "no run had " << s["name"].get<std::string>() << " up to " << name << " "
      << im_text(f["highest_none"], im) << " (the median lies above the levels run)";
  else
    t << s["name"].get<std::string>() << ": " << status << ", no curve from these levels";
  return t.str();
}

/// The sentence fragility.md opens with: the fall state's median and beta (or bracket), and the
/// level where its fraction is nearest one half, with its Wilson interval.
std::string answer_sentence(const nlohmann::json& j)
{
  if (j["levels"].empty())
    return "No level has run yet.";
  const nlohmann::json& fell = j["states"][1]; // any keyblock fell
  double highest_im = 0.0;
  for (const nlohmann::json& l : j["levels"])
    highest_im = std::max(highest_im, l["im"].get<double>());
  std::string s = state_sentence(fell, j["intensity_measure"], highest_im);
  s[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(s[0])));
  const nlohmann::json* nearest = nullptr;
  for (const nlohmann::json& l : j["levels"])
    if (l["n_counted"].get<std::size_t>() > 0 &&
        (nearest == nullptr || std::abs(l["states"][1]["p"].get<double>() - 0.5) <
                                   std::abs((*nearest)["states"][1]["p"].get<double>() - 0.5)))
      nearest = &l;
  if (nearest != nullptr)
    s += "; at " + im_text((*nearest)["im"], j["intensity_measure"]) + " a keyblock fell in " +
         percent_text((*nearest)["states"][1]) + " of " +
         std::to_string((*nearest)["n_counted"].get<std::size_t>()) + " runs (95 % Wilson)";
  return s + "; " + state_sentence(j["states"][0], j["intensity_measure"], highest_im) + ".";
}

/// The levels: key value, IM, members, and per damage state its proportion.
nlohmann::json levels_json(const IntensityMeasure& im, const std::vector<DamageState>& states,
                           const std::vector<FragilityLevelRun>& levels)
{
  nlohmann::json list = nlohmann::json::array();
  for (const FragilityLevelRun& l : levels)
  {
    std::size_t n = 0, n_failed = 0;
    for (const MemberOutcome& m : l.outcomes)
    {
      n += m.counted() ? 1 : 0;
      n_failed += m.status == "failed" ? 1 : 0;
    }
    nlohmann::json reached_json = nlohmann::json::array();
    for (const DamageState& s : states)
      reached_json.push_back(proportion_json(level_count(s, l, l.value).exceeded, n));
    list.push_back({{"value", l.value},
                    {"im", im.factor * l.value},
                    {"directory", l.directory},
                    {"n_finished", l.outcomes.size()},
                    {"n_counted", n},
                    {"n_failed", n_failed},
                    {"pgv_at_base_m_s", pgv_at_base_json(l.outcomes)},
                    {"states", reached_json}});
  }
  return list;
}
} // namespace

nlohmann::json fragility_json(const FragilityOptions& o, const IntensityMeasure& im,
                              const std::vector<DamageState>& states,
                              const std::vector<FragilityLevelRun>& levels, const double wall_s)
{
  nlohmann::json state_list = nlohmann::json::array();
  for (std::size_t i = 0; i < states.size(); ++i)
    state_list.push_back({{"name", states[i].name},
                          {"kind", name_of(states[i].kind)},
                          {"fit", fit_json(counts(im, states[i], levels),
                                           statistics::mix_seed(o.ensemble.seed, i))}});
  double members_wall = 0.0;
  for (const FragilityLevelRun& l : levels)
    members_wall += members_wall_s(l.outcomes);
  nlohmann::json hazus = nlohmann::json::array();
  for (const HazusCurve& h : hazus_bored_tunnels)
    hazus.push_back(
        {{"state", h.state},
         {"pga_median_g", h.pga_median_g},
         {"beta", h.beta},
         {"im_median",
          im.pga_g_per_im ? nlohmann::json(h.pga_median_g / *im.pga_g_per_im) : nlohmann::json()}});
  nlohmann::json j = {{"scene", o.ensemble.scene},
                      {"scene_path", scene_path(o.ensemble.scene)},
                      {"key", o.key},
                      {"settings", o.ensemble.settings},
                      {"vary", o.ensemble.vary},
                      {"roundoff_key", o.ensemble.roundoff.value_or("")},
                      {"seed", o.ensemble.seed},
                      {"members_per_level", o.ensemble.members},
                      {"intensity_measure",
                       {{"name", im.name},
                        {"unit", im.unit},
                        {"factor", im.factor},
                        {"definition", im.definition},
                        {"pga_g_per_im", optional_json(im.pga_g_per_im)}}},
                      {"levels", levels_json(im, states, levels)},
                      {"states", state_list},
                      {"hazus_bored_tunnels", hazus},
                      {"wall_s", wall_s},
                      {"members_wall_s", members_wall}};
  j["answer"] = answer_sentence(j);
  return j;
}

std::string fragility_markdown(const nlohmann::json& j)
{
  const nlohmann::json& im = j["intensity_measure"];
  std::ostringstream md;
  md << "# Fragility of `" << j["scene"].get<std::string>() << "`\n\n"
     << "**" << j["answer"].get<std::string>() << "**\n\nIntensity measure: **"
     << im["name"].get<std::string>() << "** [" << im["unit"].get<std::string>() << "], "
     << im["definition"].get<std::string>() << ". " << j["levels"].size() << " levels of "
     << j["members_per_level"] << " members (" << j["key"].get<std::string>() << "), "
     << format_significant(j["wall_s"].get<double>(), 3)
     << " s (this call; the members' wall times sum to "
     << format_significant(j.value("members_wall_s", 0.0), 3)
     << " s). Lognormal fit P = Phi(ln(IM / theta) / beta) by maximum likelihood (Baker 2015), "
        "bounds from 1000 bootstrap resamples of the members within each level (5-95 %).\n\n"
     << "| damage state | fit | median theta [" << im["unit"].get<std::string>()
     << "] | theta 90 % | beta | beta 90 % |\n|---|---|---|---|---|---|\n";
  for (const nlohmann::json& s : j["states"])
  {
    const nlohmann::json& f = s["fit"];
    const bool resolved = f["status"] == "resolved";
    const auto pair = [](const nlohmann::json& p)
    { return "[" + bound_text(p[0], 3) + ", " + bound_text(p[1], 3) + "]"; };
    const std::string bracket =
        "(" +
        (f["highest_none"].is_null() ? std::string("-")
                                     : format_significant(f["highest_none"], 3)) +
        ", " +
        (f["lowest_all"].is_null() ? std::string("-") : format_significant(f["lowest_all"], 3)) +
        "]";
    md << "| " << s["name"].get<std::string>() << " | " << f["status"].get<std::string>() << " | "
       << (resolved ? format_significant(f["theta"], 3) : "in " + bracket) << " | "
       << (resolved ? pair(f["bootstrap"]["theta_90"]) : "") << " | "
       << (resolved ? format_significant(f["beta"], 2) : "unresolved") << " | "
       << (resolved ? pair(f["bootstrap"]["beta_90"]) : "") << " |\n";
  }
  md << "\n| " << j["key"].get<std::string>() << " | " << im["name"].get<std::string>()
     << " | PGV at the near field's base [m/s] | counted |";
  for (const nlohmann::json& s : j["states"])
    md << " " << s["name"].get<std::string>() << " |";
  md << "\n|---|---|---|---|"
     << scene_reading::join(std::vector<std::string>(j["states"].size(), "---"), "|") << "|\n";
  for (const nlohmann::json& l : j["levels"])
  {
    md << "| " << format_significant(l["value"], 6) << " | " << format_significant(l["im"], 4)
       << " | "
       << (l["pgv_at_base_m_s"].is_null()
               ? std::string("-")
               : format_significant(l["pgv_at_base_m_s"]["median"].get<double>(), 3))
       << " | " << l["n_counted"] << " of " << l["n_finished"] << " |";
    for (const nlohmann::json& p : l["states"])
      md << " " << p["count"] << ": " << percent_text(p) << " |";
    md << "\n";
  }
  md << "\nFor context, HAZUS (FEMA, Table 7-9) bored or drilled rock tunnels: median PGA 0.6 g "
        "(slight) and 0.8 g (moderate), beta 0.6";
  if (!im["pga_g_per_im"].is_null())
    md << "; here " << im["name"].get<std::string>() << " "
       << format_significant(j["hazus_bored_tunnels"][0]["im_median"], 3) << " and "
       << format_significant(j["hazus_bored_tunnels"][1]["im_median"], 3) << " "
       << im["unit"].get<std::string>() << " by the input's PGA/PGV relation";
  md << ". The chart: `python3 tools/plot_fragility.py DIR` writes DIR/fragility.png.\n";
  return md.str();
}

} // namespace ddafem
