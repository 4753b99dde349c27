#include "app/studies/fragility.h"

#include "app/run/run_support.h"
#include "app/scene/map_reader.h"
#include "app/scene/scene.h"
#include "app/scene/scene_text.h"
#include "app/studies/child_runs.h"
#include "app/studies/sweep.h"
#include "common/format.h"
#include "common/ground_motion.h"
#include "common/input_error.h"
#include "common/stopwatch.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

namespace ddafem
{
std::vector<DamageState> damage_states(const FragilityOptions& o)
{
  std::vector<DamageState> states = {{DamageKind::any_loosened, "a keyblock loosened", 0.0, 0},
                                     {DamageKind::any_fell, "a keyblock fell", 0.0, 0}};
  if (o.fallen_area)
  {
    if (!(*o.fallen_area > 0.0))
      throw InputError("--fallen-area " + format_number(*o.fallen_area) +
                       ": expected an area > 0 [m^2]");
    states.push_back({DamageKind::fallen_area,
                      "fallen area above " + format_number(*o.fallen_area) + " m^2", *o.fallen_area,
                      0});
  }
  for (const std::string& text : o.states)
  {
    const std::vector<std::string> parts = scene_reading::split(text, ':');
    const bool id = parts.size() == 3 && !parts[1].empty() &&
                    parts[1].find_first_not_of("0123456789") == std::string::npos;
    if (!id || parts[0] != "block" || (parts[2] != "fell" && parts[2] != "loosened"))
      throw InputError("--state " + text +
                       ": expected block:ID:fell or block:ID:loosened, e.g. block:50:fell");
    const bool fell = parts[2] == "fell";
    states.push_back({fell ? DamageKind::block_fell : DamageKind::block_loosened,
                      "block " + parts[1] + " " + parts[2], 0.0, std::stoul(parts[1])});
  }
  return states;
}

bool reached(const DamageState& state, const MemberOutcome& member)
{
  const auto any = [&](auto predicate)
  { return std::any_of(member.keyblocks.begin(), member.keyblocks.end(), predicate); };
  switch (state.kind)
  {
  case DamageKind::any_loosened:
    return any([](const KeyblockOutcome& k) { return k.loosened; });
  case DamageKind::any_fell:
    return any([](const KeyblockOutcome& k) { return k.fell && !k.released; });
  case DamageKind::fallen_area:
  {
    double area = 0.0; // [m^2] over every opening
    for (const double a : member.fallen_area_m2)
      area += a;
    return area > state.area_m2;
  }
  case DamageKind::block_fell:
    return any([&](const KeyblockOutcome& k)
               { return k.id == state.block && k.fell && !k.released; });
  case DamageKind::block_loosened:
    return any([&](const KeyblockOutcome& k) { return k.id == state.block && k.loosened; });
  }
  return false;
}

std::vector<double> spread_levels(const double band_low, const double band_high,
                                  const std::size_t n, const double min_beta)
{
  const double z90 = statistics::normal_quantile(0.9); // 1.2816
  const double centre = 0.5 * (std::log(band_low) + std::log(band_high));
  const double half = std::max(0.5 * std::log(band_high / band_low), z90 * min_beta);
  std::vector<double> levels;
  for (std::size_t i = 0; i < n; ++i)
    levels.push_back(
        std::exp(centre - half + 2.0 * half * static_cast<double>(i) / static_cast<double>(n - 1)));
  return levels;
}

std::optional<std::pair<double, double>>
outcome_band(const std::vector<std::pair<double, bool>>& verdicts)
{
  std::optional<double> lowest_exceeded, highest_held, highest_held_below;
  for (const auto& [value, exceeded] : verdicts)
    if (exceeded)
      lowest_exceeded = std::min(value, lowest_exceeded.value_or(value));
    else
      highest_held = std::max(value, highest_held.value_or(value));
  if (!lowest_exceeded || !highest_held)
    return std::nullopt;
  if (*highest_held > *lowest_exceeded)
    return std::make_pair(*lowest_exceeded, *highest_held); // not monotonic
  return std::make_pair(*highest_held, *lowest_exceeded);
}

IntensityMeasure intensity_measure(const std::string& scene,
                                   const std::vector<std::string>& settings, const std::string& key)
{
  const auto ends_with = [&](const std::string& tail)
  {
    return key.size() >= tail.size() &&
           key.compare(key.size() - tail.size(), tail.size(), tail) == 0;
  };
  IntensityMeasure im;
  if (key == "tunnel.wave.velocity.amplitude")
  {
    im = {"PGV (outcrop)", "m/s", 2.0,
          "twice the incident wave's peak velocity (tunnel.wave.velocity.amplitude): a vertically "
          "incident wave doubles at a free surface",
          std::nullopt};
    YAML::Node root = scene_reading::load_yaml(scene);
    for (const std::string& s : settings)
      scene_reading::apply_override(root, parse_override(s));
    const YAML::Node type = scene_reading::nested(root, {"tunnel", "wave", "velocity", "type"});
    const std::optional<double> f =
        child_runs::scene_value(scene, settings, "tunnel.wave.velocity.frequency");
    if (type.IsScalar() && type.Scalar() == "sine_pulse" && f)
    {
      // v(t) = A sin(2 pi f t): the peak acceleration is 2 pi f A, at the outcrop as the velocity.
      im.pga_g_per_im = 2.0 * M_PI * *f / standard_gravity;
      im.definition += "; PGA (outcrop) = 2 pi f PGV, f = " + format_number(*f) +
                       " Hz, the sine pulse's frequency";
    }
  }
  else if (ends_with(".scale_to_pgv"))
    im = {"PGV (record)", "m/s", 1.0,
          "the record's peak velocity (" + key + "), at the record's `motion` (within or outcrop)",
          std::nullopt};
  else if (ends_with(".scale_to_pga"))
    im = {"PGA (record)", "m/s^2", 1.0,
          "the record's peak acceleration (" + key + "), at the record's `motion`",
          1.0 / standard_gravity};
  else
    im = {key, "", 1.0, "the value of " + key, std::nullopt};
  return im;
}

std::optional<double> record_pga_g_per_pgv(const nlohmann::json& summary)
{
  const nlohmann::json records = summary.value("records", nlohmann::json::array());
  if (!records.is_array() || records.empty())
    return std::nullopt;
  const double pga_g = records[0].value("pga_g", 0.0), pgv = records[0].value("pgv_m_s", 0.0);
  return pga_g > 0.0 && pgv > 0.0 ? std::optional<double>(pga_g / pgv) : std::nullopt;
}

namespace
{
const DamageState& fall_state(const std::vector<DamageState>& states)
{
  return *std::find_if(states.begin(), states.end(),
                       [](const DamageState& s) { return s.kind == DamageKind::any_fell; });
}

/// The share of a level's completed members reaching `state` (0 when none completed).
double share_reached(const DamageState& state, const FragilityLevelRun& level)
{
  const statistics::FragilityLevel c = level_count(state, level, level.value);
  return c.n > 0 ? static_cast<double>(c.exceeded) / static_cast<double>(c.n) : 0.0;
}
} // namespace

statistics::FragilityLevel level_count(const DamageState& state, const FragilityLevelRun& level,
                                       const double im)
{
  statistics::FragilityLevel c{im, 0, 0};
  for (const MemberOutcome& m : level.outcomes)
    if (m.counted())
    {
      ++c.n;
      c.exceeded += reached(state, m) ? 1 : 0;
    }
  return c;
}

nlohmann::json earlier_bracket(const SweepOptions& s)
{
  std::ifstream in(std::filesystem::path(s.directory) / "sweep.json");
  if (!in)
    return nullptr;
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (!j.is_object() || j.value("conclusion", std::string()).empty() ||
      j.value("scene", std::string()) != s.scene || j.value("key", std::string()) != s.key ||
      j.value("settings", std::vector<std::string>()) != s.settings)
    return nullptr;
  const auto ran = [&](const std::optional<double>& v)
  {
    const nlohmann::json& cases = j.value("cases", nlohmann::json::array());
    return !v || std::any_of(cases.begin(), cases.end(),
                             [&](const nlohmann::json& c) { return c.value("value", 0.0) == *v; });
  };
  return ran(s.low) && ran(s.high) ? j : nlohmann::json();
}

std::optional<double> level_beyond(const FragilityOptions& o,
                                   const std::vector<DamageState>& states,
                                   const std::vector<FragilityLevelRun>& runs)
{
  const DamageState& fall = fall_state(states);
  if (!o.levels.empty() || o.n_levels < 2 || runs.size() < o.n_levels ||
      runs.size() >= 2 * o.n_levels)
    return std::nullopt;
  const auto by_value = [](const FragilityLevelRun& a, const FragilityLevelRun& b)
  { return a.value < b.value; };
  const FragilityLevelRun& lowest = *std::min_element(runs.begin(), runs.end(), by_value);
  const FragilityLevelRun& highest = *std::max_element(runs.begin(), runs.end(), by_value);
  // Half the chosen levels' span in ln IM: they are spread densely over a bracket that may sit
  // well inside the band sought; one of their spacings at a time would creep.
  const double ratio = std::sqrt(runs[o.n_levels - 1].value / runs[0].value);
  if (share_reached(fall, highest) < 0.9)
    return std::stod(format_significant(highest.value * ratio, 4));
  if (share_reached(fall, lowest) > 0.1)
    return std::stod(format_significant(lowest.value / ratio, 4));
  return std::nullopt;
}

namespace
{
/// DIR/level_NN, 1-based.
std::filesystem::path level_directory(const FragilityOptions& o, const std::size_t index)
{
  std::string number = std::to_string(index + 1);
  number.insert(0, number.size() < 2 ? 2 - number.size() : 0, '0');
  return std::filesystem::path(o.ensemble.directory) / ("level_" + number);
}

/// A record's PGA [g] per PGV [m/s] from the summary.json of a member in `level` that has one
/// (scaling the record keeps the ratio); none if no member reports a record.
std::optional<double> member_pga_g_per_pgv(const std::filesystem::path& level)
{
  for (const std::filesystem::directory_entry& member : std::filesystem::directory_iterator(level))
  {
    std::ifstream in(member.path() / "summary.json");
    const nlohmann::json summary =
        in ? nlohmann::json::parse(in, nullptr, false) : nlohmann::json();
    if (summary.is_object())
      if (const std::optional<double> ratio = record_pga_g_per_pgv(summary))
        return ratio;
  }
  return std::nullopt;
}

/// Bad input found before any run: the options, the scene at each given level, the ensemble's
/// --vary and --roundoff.
void check_options(const FragilityOptions& o)
{
  if (o.key.empty())
    throw InputError("fragility: --key: expected the scene key whose value is the intensity, "
                     "e.g. tunnel.wave.velocity.amplitude");
  if (!o.low != !o.high)
    throw InputError("fragility: expected both --low and --high, or neither");
  if (o.low && !(*o.low > 0.0 && *o.high > *o.low))
    throw InputError("fragility: --low " + format_number(*o.low) + " --high " +
                     format_number(*o.high) + ": expected 0 < --low < --high");
  if (o.levels.empty() && o.n_levels < 2)
    throw InputError("fragility: --n-levels " + std::to_string(o.n_levels) +
                     ": expected at least 2");
  for (const double v : o.levels)
    if (!(v > 0.0))
      throw InputError("fragility: --levels " + format_number(v) +
                       ": expected intensity levels > 0");
  for (const double v : o.levels)
  {
    std::vector<Override> overrides;
    for (const std::string& s : o.ensemble.settings)
      overrides.push_back(parse_override(s));
    overrides.push_back({o.key, format_significant(v, 17)});
    try
    {
      read_scene(o.ensemble.scene, overrides);
    }
    catch (const InputError& e)
    {
      throw InputError("fragility: --key " + o.key + " = " + format_number(v) + ": " + e.what());
    }
  }
  EnsembleOptions first = o.ensemble; // at the first level given, else at the scene's value
  if (!o.levels.empty())
    first.settings.push_back(o.key + "=" + format_significant(o.levels[0], 17));
  plan_ensemble(first);
}

/// The levels: given, or spread across the band where a sweep's single runs change outcome.
std::vector<double> choose_levels(const FragilityOptions& o, std::ostream& log)
{
  if (!o.levels.empty())
  {
    std::vector<double> levels = o.levels;
    std::sort(levels.begin(), levels.end());
    return levels;
  }
  SweepOptions s;
  s.scene = o.ensemble.scene;
  s.settings = o.ensemble.settings;
  s.key = o.key;
  s.low = o.low;
  s.high = o.high;
  s.tolerance = 0.1;
  s.jobs = o.ensemble.jobs;
  s.directory = (std::filesystem::path(o.ensemble.directory) / "bracket").string();
  s.quiet = o.ensemble.quiet;
  nlohmann::json sweep = earlier_bracket(s);
  if (sweep.is_object())
    log << "fragility: the bracketing in " << s.directory
        << " is reused (the same scene, key and --set; delete it to bracket again)" << std::endl;
  else
  {
    run_sweep(s, log);
    std::ifstream in(std::filesystem::path(s.directory) / "sweep.json");
    sweep = nlohmann::json::parse(in, nullptr, false);
  }
  std::vector<std::pair<double, bool>> verdicts;
  for (const nlohmann::json& c : sweep.value("cases", nlohmann::json::array()))
    if (!c.value("cancelled", false) && !c.value("status", "").empty())
      verdicts.emplace_back(c["value"].get<double>(), c["exceeded"].get<bool>());
  const std::optional<std::pair<double, double>> band = outcome_band(verdicts);
  if (!band)
    throw InputError("fragility: the bracketing of " + o.key + " (" + s.directory + ") ended '" +
                     sweep.value("conclusion", std::string()) +
                     "': expected --low and --high around the critical value, or --levels");
  std::vector<double> levels;
  for (const double v : spread_levels(band->first, band->second, o.n_levels))
    levels.push_back(std::stod(format_significant(v, 4)));
  log << "fragility: " << o.key << " changes outcome between " << band->first << " and "
      << band->second << "; levels " << nlohmann::json(levels).dump() << std::endl;
  return levels;
}
} // namespace

int run_fragility(const FragilityOptions& o, std::ostream& log)
{
  const auto wall_start = std::chrono::steady_clock::now();
  const std::vector<DamageState> states = damage_states(o);
  check_options(o);
  IntensityMeasure im = intensity_measure(o.ensemble.scene, o.ensemble.settings, o.key);
  run_support::create_output_directory(o.ensemble.directory);
  // Under mpirun every rank runs each level's ensemble (its share of the members, rank 0
  // gathering); the bracketing sweep runs on one process only, so the levels must be given.
  const std::optional<run_support::MpiJob> job = run_support::mpi_job_from_environment();
  const bool leads = !job || job->rank == 0;
  if (job && job->size > 1 && o.levels.empty())
    throw InputError("fragility under mpirun: expected --levels (the bracketing that chooses "
                     "them runs on one process: run it without mpirun, or give the levels)");
  std::vector<double> values = choose_levels(o, log);
  std::vector<FragilityLevelRun> levels;
  const auto write_report = [&]
  {
    std::vector<FragilityLevelRun> sorted = levels; // levels added beyond come last
    std::stable_sort(sorted.begin(), sorted.end(),
                     [](const auto& a, const auto& b) { return a.value < b.value; });
    const nlohmann::json j = fragility_json(o, im, states, sorted, seconds_since(wall_start));
    const std::filesystem::path dir(o.ensemble.directory);
    if (leads) // the other ranks know only their own members
    {
      run_support::write_text_file(dir / "fragility.json", j.dump(2) + "\n");
      run_support::write_text_file(dir / "fragility.md", fragility_markdown(j));
    }
    return j;
  };
  bool failed = false, stopped = false;
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    EnsembleOptions e = o.ensemble;
    e.settings.push_back(o.key + "=" + format_significant(values[i], 17));
    e.directory = level_directory(o, i).string();
    if (!o.ensemble.quiet && leads)
      log << "fragility: level " << i + 1 << " of " << values.size() << ": " << o.key << " = "
          << values[i] << " (" << im.name << " " << im.factor * values[i] << " " << im.unit << ")"
          << std::endl;
    EnsembleResult r = run_ensemble_members(e, log);
    failed = failed || r.exit_code == 1;
    stopped = stopped || r.exit_code == 3;
    levels.push_back({values[i], level_directory(o, i).filename().string(), std::move(r.outcomes)});
    if (!im.pga_g_per_im && im.name == "PGV (record)")
      im.pga_g_per_im = member_pga_g_per_pgv(level_directory(o, i));
    write_report();
    if (i + 1 == values.size())
      if (const std::optional<double> beyond = level_beyond(o, states, levels))
      {
        if (leads)
          log << "fragility: the chosen levels do not cover where 10 to 90 % of the runs drop a "
                 "keyblock: adding "
              << o.key << " = " << *beyond << std::endl;
        values.push_back(*beyond);
      }
  }
  const nlohmann::json j = write_report();
  if (!leads)
    return 0; // rank 0 reports
  log << "fragility: " << j["answer"].get<std::string>() << " ("
      << (std::filesystem::path(o.ensemble.directory) / "fragility.md").string() << ", "
      << format_significant(seconds_since(wall_start), 3) << " s)" << std::endl;
  return failed ? 1 : stopped ? 3 : 0;
}

} // namespace ddafem
