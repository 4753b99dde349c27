#include "app/studies/ensemble.h"

#include "app/run/run_support.h"
#include "app/scene/map_reader.h"
#include "app/scene/scene.h"
#include "app/scene/scene_text.h"
#include "app/schema/scene_schema.h"
#include "app/studies/child_runs.h"
#include "common/format.h"
#include "common/input_error.h"
#include "common/stopwatch.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <thread>

namespace ddafem
{
namespace
{
using scene_reading::child;
using scene_reading::split;
using statistics::Distribution;
using statistics::DistributionKind;

/// A number as a --set value that reads back to the same double (17 significant digits).
std::string exact_text(const double value)
{
  std::ostringstream s;
  s.precision(17);
  s << value;
  return s.str();
}

/// The scene file's YAML tree with the options' --set applied.
YAML::Node scene_root(const EnsembleOptions& o)
{
  YAML::Node root = scene_reading::load_yaml(o.scene);
  for (const std::string& s : o.settings)
    scene_reading::apply_override(root, parse_override(s));
  return root;
}

/// The schema's key at a dotted path of the scene `root` (named maps by their name, lists by
/// index, time functions by their `type`), if the path leads to one.
std::optional<schema::Key> schema_key_at(const YAML::Node& root, const std::string& path)
{
  using schema::ValueType;
  const schema::SceneSchema all;
  const schema::Section* section = &all.section(schema::SceneSchema::top_level);
  YAML::Node node = root;
  const std::vector<std::string> parts = split(path, '.');
  for (std::size_t i = 0; i < parts.size(); ++i)
  {
    const schema::Key* key = section->find(parts[i]);
    if (key == nullptr || i + 1 == parts.size())
      return key == nullptr ? std::nullopt : std::optional<schema::Key>(*key);
    YAML::Node next = node.IsMap() ? child(node, parts[i]) : YAML::Node();
    if (key->type == ValueType::section_map || key->type == ValueType::section_list)
    {
      ++i; // the name or index of the item
      const bool list = key->type == ValueType::section_list;
      const bool index = parts[i].find_first_not_of("0123456789") == std::string::npos;
      if (i + 1 == parts.size() || (list && !(index && next.IsSequence())) ||
          (!list && !next.IsMap()))
        return std::nullopt;
      const YAML::Node& items = next;
      next.reset(list ? items[std::stoul(parts[i])] : child(items, parts[i]));
    }
    if (key->type == ValueType::time_function)
    {
      const std::optional<schema::TimeFunctionType> type = value_of<schema::TimeFunctionType>(
          next.IsMap() && child(next, "type").IsScalar() ? child(next, "type").Scalar()
                                                         : std::string());
      if (!type)
        return std::nullopt;
      section = &all.section(schema::SceneSchema::time_function_section(*type));
    }
    else if (key->type == ValueType::section || key->type == ValueType::section_map ||
             key->type == ValueType::section_list)
      section = &all.section(key->section);
    else
      return std::nullopt; // a value on the way: the path goes below a leaf
    node.reset(next);
  }
  return std::nullopt;
}

/// A value well inside a distribution's support: its mean, median or middle.
double central_value(const Distribution& d)
{
  return d.kind == DistributionKind::uniform ? 0.5 * (d.parameters[0] + d.parameters[1])
         : d.kind == DistributionKind::truncnormal
             ? std::clamp(d.parameters[0], d.parameters[2], d.parameters[3])
             : d.parameters[0];
}

/// Whether every value the distribution can take is in the range (lognormal's 0 not taken).
bool support_within(const schema::Range& range, const Distribution& d)
{
  const statistics::Interval s = d.support();
  const bool open_low = d.kind == DistributionKind::lognormal;
  if (range.min &&
      (s.low < *range.min || (s.low == *range.min && !range.min_inclusive && !open_low)))
    return false;
  return !(range.max && (s.high > *range.max || (s.high == *range.max && !range.max_inclusive)));
}

/// The scene read with the options' --set and `extra`; an InputError is prefixed by `what`.
void read_with(const EnsembleOptions& o, const Override& extra, const std::string& what)
{
  std::vector<Override> overrides;
  for (const std::string& s : o.settings)
    overrides.push_back(parse_override(s));
  overrides.push_back(extra);
  try
  {
    read_scene(o.scene, overrides);
  }
  catch (const InputError& e)
  {
    throw InputError(what + ": " + e.what());
  }
}

/// A schema key's type must be a number for --vary and --roundoff.
void require_number(const std::optional<schema::Key>& key, const std::string& what)
{
  if (key && key->type != schema::ValueType::number)
    throw InputError(what + ": key '" + key->name + "' is of type " + name_of(key->type) +
                     ": expected a numeric key (type number)");
}

/// One --vary KEY=DIST, checked: the key is a number whose allowed range (schema) holds the
/// distribution's support, and the scene reads with it set to the distribution's centre (an
/// unknown key fails there) and to a finite support's ends.
VariedKey varied_key(const EnsembleOptions& o, const YAML::Node& root, const std::string& text)
{
  const std::string what = "--vary " + text;
  const std::size_t equals = text.find('=');
  if (equals == std::string::npos || equals == 0)
    throw InputError(what + ": expected KEY=DIST, e.g. "
                            "joint_materials.joint.friction_angle=normal(35,2)");
  VariedKey v{scene_reading::trim(text.substr(0, equals)), {}};
  try
  {
    v.distribution = statistics::parse_distribution(text.substr(equals + 1));
  }
  catch (const InputError& e)
  {
    throw InputError(what + ": " + e.what());
  }
  const std::optional<schema::Key> key = schema_key_at(root, v.key);
  require_number(key, what);
  read_with(o, {v.key, exact_text(central_value(v.distribution))}, what); // e.g. an unknown key
  const statistics::Interval s = v.distribution.support();
  if (key && !support_within(key->range, v.distribution))
    throw InputError(what + ": its values [" + format_number(s.low) + ", " + format_number(s.high) +
                     "] leave the range of key '" + v.key + "' (" + key->range.describe() +
                     "): expected a distribution inside it; truncate it, e.g. "
                     "truncnormal(mean,sd,low,high) or uniform(low,high)");
  for (const double end : {s.low, s.high})
    if (std::isfinite(end) && !(end == 0.0 && v.distribution.kind == DistributionKind::lognormal))
      read_with(o, {v.key, exact_text(end)}, what);
  return v;
}

/// Why the members' seeds change nothing, or "" if a joint set of a seeded section has a random
/// perturbation (spacing or position > 0).
std::string seed_warning(const YAML::Node& root, const std::vector<std::string>& seed_keys)
{
  if (seed_keys.empty())
    return "the scene has no rock_mass or tunnel section, so no seed to vary: the members differ "
           "only by --vary and --roundoff";
  for (const std::string& key : seed_keys)
  {
    const YAML::Node sets = scene_reading::nested(root, {split(key, '.')[0], "joint_sets"});
    for (std::size_t i = 0; sets.IsSequence() && i < sets.size(); ++i)
      for (const char* amount : {"spacing", "position"})
      {
        const std::optional<double> value =
            scene_reading::parse_double(scene_reading::nested(sets[i], {"perturbation", amount}));
        if (value && *value > 0.0)
          return "";
      }
  }
  return "no joint set has a random perturbation (perturbation.spacing or .position > 0), so "
         "the members' seeds (" +
         scene_reading::join(seed_keys, ", ") + ") change nothing";
}

/// The --roundoff key (the default in tunnel scenes) and its value in the scene.
void plan_roundoff(const EnsembleOptions& o, const YAML::Node& root, EnsemblePlan& plan)
{
  plan.roundoff_key = *o.roundoff;
  if (plan.roundoff_key.empty())
  {
    if (!child(root, "tunnel").IsDefined())
      throw InputError("--roundoff: the scene has no tunnel section, so no default key: expected "
                       "--roundoff KEY, a numeric key of the scene");
    plan.roundoff_key = "tunnel.wave.velocity.amplitude";
  }
  const std::string what = "--roundoff " + plan.roundoff_key;
  for (const VariedKey& v : plan.varied)
    if (v.key == plan.roundoff_key)
      throw InputError(what + ": the key is also drawn by --vary: expected one or the other");
  require_number(schema_key_at(root, plan.roundoff_key), what);
  const std::optional<double> value =
      child_runs::scene_value(o.scene, o.settings, plan.roundoff_key);
  if (!value || *value == 0.0)
    throw InputError(what + ": the scene (with its --set) has no number other than 0 at this "
                            "key: expected a numeric key that the scene gives");
  plan.roundoff_value = *value;
}
} // namespace

EnsemblePlan plan_ensemble(const EnsembleOptions& o)
{
  if (o.members == 0)
    throw InputError("ensemble: -n " + std::to_string(o.members) + ": expected at least 1 member");
  const YAML::Node root = scene_root(o);
  EnsemblePlan plan;
  for (const std::string& text : o.vary)
  {
    plan.varied.push_back(varied_key(o, root, text));
    for (std::size_t i = 0; i + 1 < plan.varied.size(); ++i)
      if (plan.varied[i].key == plan.varied.back().key)
        throw InputError("--vary " + text + ": key '" + plan.varied[i].key +
                         "' is varied twice: expected each key once");
  }
  if (o.roundoff)
    plan_roundoff(o, root, plan);
  for (const char* section : {"rock_mass", "tunnel"})
    if (child(root, section).IsDefined())
      plan.seed_keys.push_back(std::string(section) + ".seed");
  plan.seed_warning = seed_warning(root, plan.seed_keys);
  return plan;
}

Member plan_member(const EnsembleOptions& o, const EnsemblePlan& plan, const std::size_t index)
{
  Member m;
  m.index = index;
  // Below 2^31: the seed keys are integers, and any reader of member.json keeps them exactly.
  m.seed = statistics::mix_seed(statistics::mix_seed(o.seed, 0), index) % (1ULL << 31);
  m.settings = o.settings;
  for (const std::string& key : plan.seed_keys)
  {
    m.values.emplace_back(key, static_cast<double>(m.seed));
    m.settings.push_back(key + "=" + std::to_string(m.seed));
  }
  for (std::size_t i = 0; i < plan.varied.size(); ++i)
  {
    const double v = plan.varied[i].distribution.sample(statistics::mix_seed(o.seed, i + 1), index);
    m.values.emplace_back(plan.varied[i].key, v);
    m.settings.push_back(plan.varied[i].key + "=" + exact_text(v));
  }
  if (!plan.roundoff_key.empty())
  {
    const double v = plan.roundoff_value * (1.0 + static_cast<double>(index) * 1e-12);
    m.values.emplace_back(plan.roundoff_key, v);
    m.settings.push_back(plan.roundoff_key + "=" + exact_text(v));
  }
  if (!o.snapshots)
    m.settings.push_back("output.interval=0"); // snapshots of the first and last state only
  return m;
}

namespace
{
/// DIR/member_NNN.
std::filesystem::path member_directory(const EnsembleOptions& o, const std::size_t index)
{
  std::string number = std::to_string(index);
  number.insert(0, number.size() < 3 ? 3 - number.size() : 0, '0');
  return std::filesystem::path(o.directory) / ("member_" + number);
}

/// Writes the member's member.json and starts its `ddafem run`, output into DIR/member_NNN.log.
child_runs::Child start_member(const EnsembleOptions& o, const Member& m, unsigned threads)
{
  const std::filesystem::path dir = member_directory(o, m.index);
  run_support::create_output_directory(dir);
  nlohmann::json values = nlohmann::json::object();
  for (const auto& [key, value] : m.values)
    values[key] = value;
  run_support::write_text_file(
      dir / "member.json",
      nlohmann::json(
          {{"index", m.index}, {"seed", m.seed}, {"values", values}, {"settings", m.settings}})
              .dump(2) +
          "\n");
  std::vector<std::string> args = {"ddafem",     "run", o.scene,     "-o",
                                   dir.string(), "-q",  "--threads", std::to_string(threads)};
  if (o.max_wall_time > 0.0)
    args.insert(args.end(), {"--max-wall-time", exact_text(o.max_wall_time)});
  for (const std::string& s : m.settings)
    args.insert(args.end(), {"--set", s});
  return child_runs::start(args, dir.string() + ".log");
}

/// The outcome of a member that ended; a run refused as bad input throws.
MemberOutcome finish_member(const EnsembleOptions& o, const Member& m, const child_runs::Child& c)
{
  const std::filesystem::path dir = member_directory(o, m.index);
  if (c.exit_code == 2)
    throw InputError("ensemble: member " + std::to_string(m.index) +
                     " was refused: " + child_runs::file_text(dir.string() + ".log"));
  std::ifstream in(dir / "summary.json");
  nlohmann::json summary;
  if (in)
    summary = nlohmann::json::parse(in, nullptr, false);
  MemberOutcome outcome =
      member_outcome(m.index, c.exit_code, summary.is_discarded() ? nlohmann::json() : summary);
  outcome.wall_s = c.wall_s;
  return outcome;
}

/// Ids of the keyblocks with a verdict, for the progress line.
std::string ids_where(const MemberOutcome& m, bool KeyblockOutcome::*verdict)
{
  std::vector<std::string> ids;
  for (const KeyblockOutcome& k : m.keyblocks)
    if (k.*verdict)
      ids.push_back(std::to_string(k.id));
  return "[" + scene_reading::join(ids, ", ") + "]";
}

/// The progress line of a member that ended, written by one call: under mpirun every rank
/// writes to the same unbuffered stderr, and a line written piece by piece interleaves with
/// another rank's.
void log_member(const EnsembleOptions& o, const MemberOutcome& m, std::size_t n_done,
                std::ostream& log)
{
  if (o.quiet)
    return;
  std::ostringstream line;
  line << "ensemble: " << member_directory(o, m.index).filename().string() << ": "
       << (m.status.empty() ? "no summary (exit code " + std::to_string(m.exit_code) + ")"
                            : m.status)
       << ", fell " << ids_where(m, &KeyblockOutcome::fell) << ", loosened "
       << ids_where(m, &KeyblockOutcome::loosened) << ", " << format_significant(m.wall_s, 3)
       << " s; " << n_done << " of " << o.members << " done\n";
  log << line.str() << std::flush;
}

/// Writes ensemble.json and ensemble.md.
void write_report(const EnsembleOptions& o, const EnsemblePlan& plan,
                  const std::vector<Member>& members, const std::vector<MemberOutcome>& outcomes,
                  double wall_s)
{
  const nlohmann::json j = ensemble_json(o, plan, members, outcomes, wall_s);
  const std::filesystem::path dir(o.directory);
  run_support::write_text_file(dir / "ensemble.json", j.dump(2) + "\n");
  run_support::write_text_file(dir / "ensemble.md", ensemble_markdown(j));
}

/// The members that finished (completed or failed) in an earlier run of this ensemble into the
/// same directory, from its ensemble.json and their summary.json; none if there is none. A
/// larger -n extends the ensemble: member k draws the same values whatever -n is (its seed
/// mixes --seed and k alone), so the earlier members stand and only the new ones run. Throws
/// InputError if that was another ensemble (another scene, a smaller -n, --vary, --seed, --set,
/// --roundoff or --snapshots).
std::vector<MemberOutcome> earlier_outcomes(const EnsembleOptions& o, const EnsemblePlan& plan)
{
  const std::filesystem::path file = std::filesystem::path(o.directory) / "ensemble.json";
  std::ifstream in(file);
  if (!in)
    return {};
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object())
    throw InputError(file.string() + ": not an ensemble's report: expected an empty or new -o DIR");
  const std::size_t earlier_members = j.value("members_requested", std::size_t(0));
  if (o.members < earlier_members)
    throw InputError(file.string() + ": the ensemble in this directory has members_requested = " +
                     std::to_string(earlier_members) + ", not " + std::to_string(o.members) +
                     ": expected -n " + std::to_string(earlier_members) +
                     " or more to continue or extend it, or another -o DIR");
  const nlohmann::json now = {{"scene_path", scene_path(o.scene)},
                              {"vary", o.vary},
                              {"seed", o.seed},
                              {"settings", o.settings},
                              {"roundoff_key", plan.roundoff_key},
                              {"snapshots", o.snapshots}};
  for (const auto& [key, value] : now.items())
    if (j.value(key, nlohmann::json()) != value)
      throw InputError(file.string() + ": the ensemble in this directory has " + key + " = " +
                       j.value(key, nlohmann::json()).dump() + ", not " + value.dump() +
                       ": expected the same options to continue it (ddafem resume " + o.directory +
                       "), or another -o DIR");
  std::vector<MemberOutcome> outcomes;
  for (const nlohmann::json& m : j.value("members", nlohmann::json::array()))
  {
    const std::string status = m.value("status", "");
    if (!m.value("finished", false) || (status != "completed" && status != "failed"))
      continue; // not run, stopped at a budget, or without a summary: run again
    std::ifstream summary_in(std::filesystem::path(o.directory) / m.value("directory", "") /
                             "summary.json");
    const nlohmann::json summary = nlohmann::json::parse(summary_in, nullptr, false);
    if (summary.is_discarded())
      continue;
    outcomes.push_back(member_outcome(m["index"], m.value("exit_code", -1), summary));
    outcomes.back().wall_s = m.value("wall_s", 0.0);
  }
  return outcomes;
}

/// Which members this process runs: all, or under mpirun with N ranks member k on rank k mod N
/// (each a child run of its own, app/studies/child_runs.h).
struct RankShare
{
  std::optional<run_support::MpiJob> job;
  bool runs(const std::size_t index) const { return !job || index % job->size == job->rank; }
  /// Whether this process writes the report: rank 0, or the only process.
  bool leads() const { return !job || job->rank == 0; }
};

RankShare rank_share()
{
  return {run_support::mpi_job_from_environment()};
}

/// DIR/rank_NNN.json: the members rank r ran (index, exit code, wall time), written when it is
/// done (or failed: `error`); rank 0 waits for it.
std::filesystem::path rank_marker(const EnsembleOptions& o, const unsigned int rank)
{
  return std::filesystem::path(o.directory) / ("rank_" + std::to_string(rank) + ".json");
}

/// Runs this rank's members by `run`; on a rank other than 0 of several, then writes its marker
/// with the members it ran (not those of `earlier`), or with the error that ended it.
std::vector<MemberOutcome> run_rank_members(const EnsembleOptions& o, const RankShare& share,
                                            const std::vector<MemberOutcome>& earlier,
                                            const std::function<std::vector<MemberOutcome>()>& run)
{
  if (share.leads() || share.job->size < 2)
    return run();
  nlohmann::json marker = {{"job", share.job->name}, {"rank", share.job->rank}};
  try
  {
    const std::vector<MemberOutcome> outcomes = run();
    nlohmann::json list = nlohmann::json::array();
    for (std::size_t i = earlier.size(); i < outcomes.size(); ++i)
      list.push_back({{"index", outcomes[i].index},
                      {"exit_code", outcomes[i].exit_code},
                      {"wall_s", outcomes[i].wall_s}});
    marker["members"] = list;
    run_support::write_text_file(rank_marker(o, share.job->rank), marker.dump(2) + "\n");
    return outcomes;
  }
  catch (const std::exception& e)
  {
    marker["error"] = e.what();
    marker["input_error"] = dynamic_cast<const InputError*>(&e) != nullptr;
    run_support::write_text_file(rank_marker(o, share.job->rank), marker.dump(2) + "\n");
    throw;
  }
}

/// On rank 0 of several: waits for every other rank's marker of this job (polling DIR), adds
/// the outcomes of the members they ran from their summary.json, and removes the markers. A
/// rank's error is thrown here (InputError if it was bad input).
std::vector<MemberOutcome> gather_ranks(const EnsembleOptions& o, const RankShare& share,
                                        std::vector<MemberOutcome> outcomes)
{
  for (unsigned int r = 1; share.job && r < share.job->size; ++r)
  {
    nlohmann::json marker;
    while (true)
    {
      std::ifstream in(rank_marker(o, r));
      marker = in ? nlohmann::json::parse(in, nullptr, false) : nlohmann::json();
      if (marker.is_object() && marker.value("job", "") == share.job->name)
        break; // not another job's stale marker
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    std::filesystem::remove(rank_marker(o, r));
    if (marker.contains("error"))
    {
      const std::string what =
          "ensemble: rank " + std::to_string(r) + ": " + marker["error"].get<std::string>();
      if (marker.value("input_error", false))
        throw InputError(what);
      throw std::runtime_error(what);
    }
    for (const nlohmann::json& m : marker["members"])
    {
      std::ifstream in(member_directory(o, m["index"]) / "summary.json");
      const nlohmann::json summary = nlohmann::json::parse(in, nullptr, false);
      outcomes.push_back(member_outcome(m["index"], m["exit_code"],
                                        summary.is_discarded() ? nlohmann::json() : summary));
      outcomes.back().wall_s = m["wall_s"];
    }
  }
  return outcomes;
}

/// Runs the members of this rank (all without mpirun) without an outcome in `outcomes` (those
/// of an earlier, interrupted run of the ensemble), `jobs` at a time, each with `threads`
/// threads; after each, `after_each`.
std::vector<MemberOutcome>
run_members(const EnsembleOptions& o, const std::vector<Member>& members, unsigned jobs,
            unsigned threads, std::vector<MemberOutcome> outcomes, const RankShare& share,
            std::ostream& log,
            const std::function<void(const std::vector<MemberOutcome>&)>& after_each)
{
  std::vector<child_runs::Child> children(members.size());
  std::vector<std::size_t> to_run, running; // indices into members
  for (const Member& m : members)
    if (share.runs(m.index) &&
        std::none_of(outcomes.begin(), outcomes.end(),
                     [&](const MemberOutcome& done) { return done.index == m.index; }))
      to_run.push_back(m.index);
  std::size_t next = 0;
  try
  {
    while (next < to_run.size() || !running.empty())
    {
      for (; running.size() < jobs && next < to_run.size(); ++next)
      {
        children[to_run[next]] = start_member(o, members[to_run[next]], threads);
        running.push_back(to_run[next]);
      }
      std::vector<child_runs::Child*> waiting;
      for (const std::size_t i : running)
        waiting.push_back(&children[i]);
      const std::size_t k = child_runs::wait_for_any(waiting);
      const std::size_t i = running[k];
      running.erase(running.begin() + static_cast<std::ptrdiff_t>(k));
      outcomes.push_back(finish_member(o, members[i], children[i]));
      log_member(o, outcomes.back(), outcomes.size(), log);
      after_each(outcomes);
    }
  }
  catch (...)
  {
    for (const std::size_t i : running)
      child_runs::stop(children[i]);
    throw;
  }
  return outcomes;
}
} // namespace

int run_ensemble(const EnsembleOptions& o, std::ostream& log)
{
  return run_ensemble_members(o, log).exit_code;
}

EnsembleResult run_ensemble_members(const EnsembleOptions& o, std::ostream& log)
{
  const auto wall_start = std::chrono::steady_clock::now();
  const EnsemblePlan plan = plan_ensemble(o);
  const RankShare share = rank_share();
  if (!plan.seed_warning.empty() && share.leads())
    log << "ensemble: warning: " << plan.seed_warning << std::endl;
  std::vector<Member> members;
  for (std::size_t k = 0; k < o.members; ++k)
    members.push_back(plan_member(o, plan, k));
  // Under mpirun one run at a time per rank unless -j says otherwise: the ranks are the cores.
  // (Not a structured binding: the lambda below captures them, which C++17 does not allow.)
  const std::pair<unsigned, unsigned> jobs_threads =
      child_runs::jobs_and_threads(share.job && o.jobs == 0 ? 1 : o.jobs, o.threads);
  const unsigned jobs = jobs_threads.first, threads = jobs_threads.second;
  const std::vector<MemberOutcome> earlier = earlier_outcomes(o, plan);
  if (!earlier.empty() && !o.quiet && share.leads())
    log << "ensemble: continuing in " << o.directory << ": " << earlier.size() << " of "
        << o.members << " members finished earlier" << std::endl;
  run_support::create_output_directory(o.directory);
  if (share.leads())
    write_report(o, plan, members, earlier, 0.0);
  std::vector<MemberOutcome> outcomes = run_rank_members(
      o, share, earlier,
      [&]
      {
        return run_members(o, members, jobs, threads, earlier, share, log,
                           [&](const std::vector<MemberOutcome>& done)
                           {
                             if (share.leads())
                               write_report(o, plan, members, done, seconds_since(wall_start));
                           });
      });
  if (!share.leads())
    return {0, outcomes}; // rank 0 reports
  if (share.job && share.job->size > 1)
  {
    outcomes = gather_ranks(o, share, std::move(outcomes));
    write_report(o, plan, members, outcomes, seconds_since(wall_start));
  }
  const nlohmann::json j = ensemble_json(o, plan, members, outcomes, seconds_since(wall_start));
  log << "ensemble: " << j["answer"].get<std::string>() << " ("
      << (std::filesystem::path(o.directory) / "ensemble.md").string() << ", "
      << format_significant(seconds_since(wall_start), 3) << " s)" << std::endl;
  return {!j["failed"].empty() ? 1 : j["stopped"].empty() ? 0 : 3, outcomes};
}

int resume_ensemble(const std::string& directory, const bool quiet, const unsigned threads,
                    std::ostream& log)
{
  const std::filesystem::path file = std::filesystem::path(directory) / "ensemble.json";
  std::ifstream in(file);
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (!in || j.is_discarded() || !j.is_object())
    throw InputError(file.string() + ": cannot be read: expected the report of an ensemble");
  EnsembleOptions o;
  o.scene = j.value("scene_path", ""); // absolute: resume may run from another directory
  o.members = j.value("members_requested", std::size_t(0));
  o.settings = j.value("settings", std::vector<std::string>());
  o.vary = j.value("vary", std::vector<std::string>());
  o.seed = j.value("seed", std::uint64_t(1));
  o.snapshots = j.value("snapshots", false);
  if (const std::string key = j.value("roundoff_key", ""); !key.empty())
    o.roundoff = key;
  o.directory = directory;
  o.quiet = quiet;
  o.threads = threads;
  return run_ensemble(o, log);
}

} // namespace ddafem
