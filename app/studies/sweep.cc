#include "app/studies/sweep.h"

#include "app/run/run_support.h"
#include "app/scene/scene.h"
#include "app/studies/child_runs.h"
#include "common/format.h"
#include "common/input_error.h"
#include "common/stopwatch.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

namespace ddafem
{
CaseVerdict judge_case(const nlohmann::json& summary, SweepCriterion criterion, double threshold)
{
  CaseVerdict v;
  v.failed = summary.value("status", "") == "failed";
  const nlohmann::json& keyblocks = summary.value("keyblocks", nlohmann::json());
  if (keyblocks.is_object())
  {
    v.keyblock_peak_m = keyblocks.value("keyblock_peak_m", 0.0);
    for (const nlohmann::json& b : keyblocks.value("blocks", nlohmann::json::array()))
    {
      if (b.value("released", false))
        continue;
      if (b.value("fell", false))
        v.fallen.push_back(b.value("id", std::size_t(0)));
      v.max_relative_m = std::max(v.max_relative_m, b.value("residual_relative_m", 0.0));
    }
  }
  const bool met =
      criterion == SweepCriterion::first_fall ? !v.fallen.empty() : v.max_relative_m > threshold;
  v.exceeded = met || v.failed;
  return v;
}

CriticalValueSearch::CriticalValueSearch(double start_, std::optional<double> low_,
                                         std::optional<double> high_, double tolerance_)
    : start(start_), tolerance(tolerance_), low(low_), high(high_)
{
}

void CriticalValueSearch::add(double value, bool exceeded)
{
  cases.emplace_back(value, exceeded);
}

std::optional<double> CriticalValueSearch::lowest_exceeding() const
{
  std::optional<double> v;
  for (const auto& [value, exceeded] : cases)
    if (exceeded && (!v || value < *v))
      v = value;
  return v;
}

std::optional<double> CriticalValueSearch::highest_holding() const
{
  const std::optional<double> exceeding = lowest_exceeding();
  std::optional<double> v;
  for (const auto& [value, exceeded] : cases)
    if (!exceeded && (!exceeding || value < *exceeding) && (!v || value > *v))
      v = value;
  return v;
}

std::vector<double> CriticalValueSearch::non_monotonic() const
{
  const std::optional<double> exceeding = lowest_exceeding();
  std::vector<double> v;
  for (const auto& [value, exceeded] : cases)
    if (!exceeded && exceeding && value > *exceeding)
      v.push_back(value);
  std::sort(v.begin(), v.end());
  return v;
}

std::string CriticalValueSearch::conclusion() const
{
  const std::optional<double> exceeding = lowest_exceeding(), holding = highest_holding();
  if (exceeding && holding && *exceeding - *holding <= tolerance * *exceeding)
    return "bracketed";
  const double top = high.value_or(start * max_factor);
  const double bottom = low.value_or(start / max_factor);
  if (!exceeding && holding && *holding >= top * (1.0 - 1e-12))
    return "never exceeded";
  if (exceeding && !holding && *exceeding <= bottom * (1.0 + 1e-12))
    return "always exceeded";
  return "";
}

bool CriticalValueSearch::worth_running(double value) const
{
  const std::optional<double> exceeding = lowest_exceeding(), holding = highest_holding();
  return conclusion().empty() && !(exceeding && value >= *exceeding) &&
         !(holding && value <= *holding);
}

std::optional<double> CriticalValueSearch::next(const std::vector<double>& running) const
{
  if (!conclusion().empty())
    return std::nullopt;
  const auto known = [&](double v)
  {
    return std::find(running.begin(), running.end(), v) != running.end() ||
           std::any_of(cases.begin(), cases.end(), [v](const auto& c) { return c.first == v; });
  };
  for (const std::optional<double>& bound : {low, high}) // given bounds are run first
    if (bound && !known(*bound))
      return bound;
  // The bracket (a, b]: a held (or is the given low), b exceeded (or is the given high).
  const std::optional<double> a = highest_holding() ? highest_holding() : low;
  const std::optional<double> b = lowest_exceeding() ? lowest_exceeding() : high;
  if (!a || !b)
    return next_outward(running);
  std::vector<double> points = {*a, *b}; // cut by the values running inside it
  for (const double v : running)
    if (v > *a && v < *b)
      points.push_back(v);
  std::sort(points.begin(), points.end());
  // The widest part relative to its upper end, as the tolerance measures; of equal parts the
  // upper one, whose run is the likelier to exceed and so to end early.
  std::size_t widest = 1;
  for (std::size_t i = 1; i < points.size(); ++i)
    if ((points[i] - points[i - 1]) / points[i] >=
        (points[widest] - points[widest - 1]) / points[widest] * (1.0 - 1e-12))
      widest = i;
  return 0.5 * (points[widest - 1] + points[widest]);
}

std::optional<double> CriticalValueSearch::next_outward(const std::vector<double>& running) const
{
  const std::optional<double> exceeding = lowest_exceeding(), holding = highest_holding();
  if (!exceeding) // nothing exceeded yet: up by doubling, to the top
  {
    const double top = high.value_or(start * max_factor);
    double from = holding.value_or(0.0);
    for (const double v : running)
      from = std::max(from, v);
    if (from == 0.0)
      return start;
    if (from >= top * (1.0 - 1e-12))
      return std::nullopt;
    return std::min(2.0 * from, top);
  }
  // nothing held below the lowest that exceeded: down by halving, to the bottom
  const double bottom = low.value_or(start / max_factor);
  double from = *exceeding;
  for (const double v : running)
    from = std::min(from, v);
  if (from <= bottom * (1.0 + 1e-12))
    return std::nullopt;
  return std::max(0.5 * from, bottom);
}

namespace
{
std::string value_text(double value)
{
  std::ostringstream s;
  s.precision(6);
  s << value;
  return s.str();
}

/// One run of the sweep.
struct Case
{
  double value = 0.0;
  std::filesystem::path directory;
  child_runs::Child child;
  bool cancelled = false; ///< stopped once its verdict could no longer narrow the bracket
  std::string status;
  CaseVerdict verdict;
};

/// Starts `ddafem run` on the scene with the key at the case's value; its output goes to
/// DIR/case_NN.log.
child_runs::Child start_case(const SweepOptions& o, const Case& c, unsigned threads)
{
  std::vector<std::string> args = {"ddafem",
                                   "run",
                                   o.scene,
                                   "-o",
                                   c.directory.string(),
                                   "-q",
                                   "--threads",
                                   std::to_string(threads)};
  if (o.find == SweepCriterion::first_fall)
    args.push_back("--stop-at-first-fall"); // the verdict is known once a block has fallen
  for (const std::string& s : o.settings)
    args.insert(args.end(), {"--set", s});
  args.insert(args.end(), {"--set", o.key + "=" + value_text(c.value)});
  return child_runs::start(args, c.directory.string() + ".log");
}

/// Reads a finished case's summary.json and judges it; a run refused as bad input throws.
void finish_case(const SweepOptions& o, Case& c)
{
  const std::filesystem::path summary_file = c.directory / "summary.json";
  const int exit_code = c.child.exit_code;
  if (exit_code == 2)
    throw InputError("the run with " + o.key + " = " + value_text(c.value) +
                     " was refused: " + child_runs::file_text(c.directory.string() + ".log"));
  // 0 completed, 1 failed numerically, 3 stopped (--stop-at-first-fall): judged by summary.json.
  // Anything else (killed, an output error) says nothing about the shaking.
  std::ifstream in(summary_file);
  if (!in || (exit_code != 0 && exit_code != 1 && exit_code != 3))
    throw std::runtime_error(
        "the run with " + o.key + " = " + value_text(c.value) + " ended with exit code " +
        std::to_string(exit_code) + " (128 + n: killed by signal n), its summary " +
        summary_file.string() + " cannot judge it: see " + c.directory.string() + ".log");
  const nlohmann::json summary = nlohmann::json::parse(in);
  c.status = summary.value("status", "");
  c.verdict = judge_case(summary, o.find, o.threshold);
}

/// Ends the runs still going (a sweep that stops on an error leaves none behind).
void stop_running(std::vector<Case>& cases)
{
  for (Case& c : cases)
    child_runs::stop(c.child);
}

/// The progress line of a case that ended.
void log_case(const SweepOptions& o, const Case& c, std::ostream& log)
{
  if (o.quiet)
    return;
  log << "sweep: " << o.key << " = " << value_text(c.value) << ": ";
  if (c.cancelled)
    log << "stopped, no longer able to narrow the bracket";
  else
    log << (c.verdict.failed ? "failed (counted as exceeded)"
            : c.verdict.exceeded
                ? (o.find == SweepCriterion::first_fall ? "a keyblock fell" : "exceeded")
                : "held")
        << ", largest relative residual " << format_significant(1e3 * c.verdict.max_relative_m, 3)
        << " mm";
  log << ", " << format_significant(c.child.wall_s, 3) << " s (" << c.directory.filename().string()
      << ")" << std::endl;
}

/// Starts values of the search while fewer than `jobs` run; `running` indexes `cases`.
void start_cases(const SweepOptions& o, const CriticalValueSearch& search, unsigned jobs,
                 unsigned threads, std::vector<Case>& cases, std::vector<std::size_t>& running)
{
  while (running.size() < jobs)
  {
    std::vector<double> values;
    for (const std::size_t i : running)
      values.push_back(cases[i].value);
    const std::optional<double> v = search.next(values);
    if (!v)
      return;
    Case c;
    c.value = std::stod(value_text(*v)); // the value the run is given
    const std::string number = std::to_string(cases.size() + 1);
    c.directory = std::filesystem::path(o.directory) /
                  ("case_" + std::string(number.size() < 2 ? 1 : 0, '0') + number);
    c.child = start_case(o, c, threads);
    running.push_back(cases.size());
    cases.push_back(c);
  }
}

/// Waits for one of the running cases to end; returns its index in `cases`.
std::size_t wait_for_case(std::vector<Case>& cases, std::vector<std::size_t>& running)
{
  std::vector<child_runs::Child*> children;
  for (const std::size_t i : running)
    children.push_back(&cases[i].child);
  const std::size_t k = child_runs::wait_for_any(children);
  const std::size_t index = running[k];
  running.erase(running.begin() + static_cast<std::ptrdiff_t>(k));
  return index;
}

/// Stops the running cases whose verdict can no longer narrow the bracket.
void cancel_cases(const SweepOptions& o, const CriticalValueSearch& search,
                  std::vector<Case>& cases, std::vector<std::size_t>& running, std::ostream& log)
{
  for (auto it = running.begin(); it != running.end();)
  {
    Case& c = cases[*it];
    if (search.worth_running(c.value))
    {
      ++it;
      continue;
    }
    child_runs::stop(c.child);
    c.cancelled = true;
    log_case(o, c, log);
    it = running.erase(it);
  }
}

/// Runs the search to its end, `jobs` runs at a time, each with `threads` threads: a run that
/// ends frees its core for the next value at once, and runs that can no longer narrow the
/// bracket are stopped. After every run, `after_each` (which writes sweep.json and sweep.md).
void run_search(const SweepOptions& o, CriticalValueSearch& search, unsigned jobs, unsigned threads,
                std::vector<Case>& cases, std::ostream& log,
                const std::function<void()>& after_each)
{
  std::vector<std::size_t> running;
  try
  {
    for (start_cases(o, search, jobs, threads, cases, running); !running.empty();
         start_cases(o, search, jobs, threads, cases, running))
    {
      Case& c = cases[wait_for_case(cases, running)];
      finish_case(o, c);
      search.add(c.value, c.verdict.exceeded);
      log_case(o, c, log);
      cancel_cases(o, search, cases, running, log);
      after_each();
    }
  }
  catch (...)
  {
    stop_running(cases);
    throw;
  }
}

/// sweep.json: the question, every case and the answer.
nlohmann::json sweep_json(const SweepOptions& o, const std::vector<Case>& cases,
                          const CriticalValueSearch& search,
                          std::chrono::steady_clock::time_point sweep_start)
{
  nlohmann::json list = nlohmann::json::array();
  for (const Case& c : cases)
    list.push_back(
        {{"value", c.value},
         {"directory", c.directory.filename().string()},
         {"exit_code", c.child.exit_code},
         {"cancelled", c.cancelled},
         {"status", c.status},
         {"exceeded", c.verdict.exceeded},
         {"failed", c.verdict.failed},
         {"fallen_keyblocks", c.verdict.fallen},
         {"max_relative_residual_m", c.verdict.max_relative_m},
         {"keyblock_peak_m", c.verdict.keyblock_peak_m},
         {"started_s", std::chrono::duration<double>(c.child.started - sweep_start).count()},
         {"wall_s", c.child.wall_s}});
  const auto optional = [](std::optional<double> v)
  { return v ? nlohmann::json(*v) : nlohmann::json(); };
  return {{"scene", o.scene},
          {"settings", o.settings},
          {"key", o.key},
          {"find", name_of(o.find)},
          {"threshold_m", o.threshold},
          {"tolerance", o.tolerance},
          {"cases", list},
          {"conclusion", search.conclusion()},
          {"highest_holding", optional(search.highest_holding())},
          {"lowest_exceeding", optional(search.lowest_exceeding())},
          {"non_monotonic", search.non_monotonic()},
          {"wall_s", seconds_since(sweep_start)}};
}

/// sweep.md: the answer, then the cases in the order of their values.
std::string sweep_markdown(const nlohmann::json& j)
{
  std::ostringstream md;
  md << "# Sweep of " << j["key"].get<std::string>() << ": " << j["find"].get<std::string>()
     << "\n\nScene `" << j["scene"].get<std::string>() << "`, " << j["cases"].size() << " runs in "
     << format_significant(j["wall_s"].get<double>(), 3) << " s. ";
  const std::string conclusion = j["conclusion"];
  if (conclusion == "bracketed")
    md << "**The critical value lies above " << j["highest_holding"].get<double>()
       << " and at most " << j["lowest_exceeding"].get<double>() << "** (within "
       << 100.0 * j["tolerance"].get<double>() << " %).";
  else if (!conclusion.empty())
    md << "**" << conclusion << "** over the values run.";
  else
    md << "Still searching (the sweep was stopped, or is running)"
       << (j["highest_holding"].is_null() || j["lowest_exceeding"].is_null()
               ? std::string(".")
               : ": the critical value lies above " +
                     format_significant(j["highest_holding"].get<double>(), 6) + " and at most " +
                     format_significant(j["lowest_exceeding"].get<double>(), 6) + " so far.");
  if (!j["non_monotonic"].empty())
    md << " " << non_monotonic_note(j["non_monotonic"], j["key"]);
  md << "\n\n| " << j["key"].get<std::string>()
     << " | verdict | fallen keyblocks | largest relative residual [mm] | keyblock peak [mm] | "
        "status | wall [s] | run |\n|---|---|---|---|---|---|---|---|\n";
  std::vector<nlohmann::json> cases(j["cases"].begin(), j["cases"].end());
  std::sort(cases.begin(), cases.end(),
            [](const auto& a, const auto& b) { return a["value"] < b["value"]; });
  for (const nlohmann::json& c : cases)
    md << "| " << c["value"].get<double>() << " | "
       << (c["cancelled"].get<bool>()  ? "stopped: no longer needed"
           : c["exceeded"].get<bool>() ? "**exceeded**"
                                       : "held")
       << " | " << c["fallen_keyblocks"].dump() << " | "
       << format_significant(1e3 * c["max_relative_residual_m"].get<double>(), 3) << " | "
       << format_significant(1e3 * c["keyblock_peak_m"].get<double>(), 3) << " | "
       << c["status"].get<std::string>() << " | "
       << format_significant(c["wall_s"].get<double>(), 3) << " | "
       << c["directory"].get<std::string>() << " |\n";
  return md.str();
}
} // namespace

std::string non_monotonic_note(const std::vector<double>& held_above, const std::string& key)
{
  std::ostringstream note;
  note << "Not monotonic: held at " << nlohmann::json(held_above).dump()
       << ", above the lowest value that exceeded. The critical value is a band, not a value: "
          "`ddafem fragility SCENE --key "
       << key << "` gives the probability of a fall at each value (docs/fragility.md).";
  return note.str();
}

int run_sweep(const SweepOptions& o, std::ostream& log)
{
  const auto wall_start = std::chrono::steady_clock::now();
  std::vector<Override> overrides;
  for (const std::string& s : o.settings)
    overrides.push_back(parse_override(s));
  const std::optional<double> given = child_runs::scene_value(o.scene, o.settings, o.key);
  if (!o.low != !o.high)
    throw InputError("sweep: expected both --low and --high, or neither (then it starts from the "
                     "scene's " +
                     o.key + ")");
  if (o.low && !(*o.low > 0.0 && *o.high > *o.low))
    throw InputError("sweep: expected 0 < --low < --high");
  if (!o.low && !(given && *given > 0.0))
    throw InputError(o.scene + ": key '" + o.key +
                     "' has no number > 0 to start the sweep from: "
                     "expected it in the scene (or a --set), or --low and --high");
  const double start = given.value_or(*o.low);
  // Bad input fails here, within seconds, not in a run.
  for (const double v : {start, o.low.value_or(start), o.high.value_or(start)})
  {
    std::vector<Override> with = overrides;
    with.push_back({o.key, value_text(v)});
    read_scene(o.scene, with);
  }
  const auto [jobs, threads] = child_runs::jobs_and_threads(o.jobs);
  run_support::create_output_directory(o.directory);
  CriticalValueSearch search(start, o.low, o.high, o.tolerance);
  std::vector<Case> cases;
  run_search(o, search, jobs, threads, cases, log,
             [&]
             {
               const nlohmann::json j = sweep_json(o, cases, search, wall_start);
               run_support::write_text_file(std::filesystem::path(o.directory) / "sweep.json",
                                            j.dump(2) + "\n");
               run_support::write_text_file(std::filesystem::path(o.directory) / "sweep.md",
                                            sweep_markdown(j));
             });
  log << "sweep: " << search.conclusion();
  if (search.conclusion() == "bracketed")
    log << ": the critical " << o.key << " lies above " << *search.highest_holding()
        << " and at most " << *search.lowest_exceeding();
  log << "; " << cases.size() << " runs in " << format_significant(seconds_since(wall_start), 3)
      << " s; " << (std::filesystem::path(o.directory) / "sweep.md").string() << "\n";
  if (!search.non_monotonic().empty())
    log << "sweep: " << non_monotonic_note(search.non_monotonic(), o.key) << "\n";
  return 0;
}

} // namespace ddafem
