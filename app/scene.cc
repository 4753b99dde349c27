#include "app/scene.h"

#include "app/rock_mass_scene.h"
#include "app/scene_schema.h"
#include "app/tunnel_scene.h"
#include "common/input_error.h"
#include "dda/geometry.h"
#include "dda/rock_mass.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <utility>

namespace ddafem
{
namespace
{
using dda::Point;
using dda::Vector2;
using dda::Voigt;
using schema::Key;
using schema::SceneSchema;
using schema::Section;
using schema::ValueType;

// ---- Text helpers ---------------------------------------------------------------------------

std::string trim(const std::string& s)
{
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos)
    return "";
  const auto last = s.find_last_not_of(" \t\r\n");
  return s.substr(first, last - first + 1);
}

std::vector<std::string> split(const std::string& s, char separator)
{
  std::vector<std::string> parts;
  std::string::size_type begin = 0;
  while (true)
  {
    const auto end = s.find(separator, begin);
    parts.push_back(s.substr(begin, end == std::string::npos ? std::string::npos : end - begin));
    if (end == std::string::npos)
      return parts;
    begin = end + 1;
  }
}

std::string join(const std::vector<std::string>& items, const std::string& separator)
{
  std::string s;
  for (std::size_t i = 0; i < items.size(); ++i)
    s += (i == 0 ? "" : separator) + items[i];
  return s;
}

std::string format_number(double v)
{
  std::ostringstream s;
  s << v;
  return s.str();
}

std::string format_point(const Point& p)
{
  return "[" + format_number(p.x()) + ", " + format_number(p.y()) + "]";
}

/// Levenshtein distance (insertions, deletions, substitutions).
std::size_t edit_distance(const std::string& a, const std::string& b)
{
  std::vector<std::size_t> previous(b.size() + 1), current(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    previous[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
  {
    current[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
      current[j] = std::min(
          {previous[j] + 1, current[j - 1] + 1, previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
    std::swap(previous, current);
  }
  return previous[b.size()];
}

/// "; did you mean 'X'?" for the candidate closest to `name`, if it is close; else "".
std::string suggestion(const std::string& name, const std::vector<std::string>& candidates)
{
  const std::size_t threshold = std::max<std::size_t>(2, name.size() / 3);
  std::optional<std::string> best;
  std::size_t best_distance = 0;
  for (const std::string& c : candidates)
  {
    const std::size_t d = edit_distance(name, c);
    if (d <= threshold && d < std::max(name.size(), c.size()) && (!best || d < best_distance))
    {
      best = c;
      best_distance = d;
    }
  }
  return best ? "; did you mean '" + *best + "'?" : "";
}

/// A node as it would be written in flow style, shortened for messages.
std::string yaml_text(const YAML::Node& node)
{
  if (!node.IsDefined() || node.IsNull())
    return "";
  std::string text;
  if (node.IsScalar())
    text = node.Scalar();
  else
  {
    YAML::Emitter emitter;
    emitter << YAML::Flow << node;
    text = emitter.c_str();
  }
  if (text.size() > 80)
    text = text.substr(0, 77) + "...";
  return text;
}

std::optional<double> parse_double(const std::string& text)
{
  const std::string t = trim(text);
  if (t.empty())
    return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(t.c_str(), &end);
  if (end != t.c_str() + t.size() || errno == ERANGE || !std::isfinite(v))
    return std::nullopt;
  return v;
}

std::optional<double> parse_double(const YAML::Node& node)
{
  if (!node.IsDefined() || !node.IsScalar())
    return std::nullopt;
  return parse_double(node.Scalar());
}

std::optional<long long> parse_integer(const YAML::Node& node)
{
  if (!node.IsDefined() || !node.IsScalar())
    return std::nullopt;
  const std::string t = trim(node.Scalar());
  if (t.empty())
    return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(t.c_str(), &end, 10);
  if (end != t.c_str() + t.size() || errno == ERANGE)
    return std::nullopt;
  return v;
}

/// The child of a map (without the side effects of non-const operator[]).
YAML::Node child(const YAML::Node& map, const std::string& key)
{
  const YAML::Node& const_map = map;
  return const_map[key];
}

// ---- What a key expects, in words -----------------------------------------------------------

std::string unit_suffix(const Key& key)
{
  return key.unit.empty() ? "" : " [" + key.unit + "]";
}

std::string range_text(const Key& key, bool each)
{
  const std::string r = key.range.describe();
  if (r.empty())
    return "";
  const bool interval = key.range.min && key.range.max;
  return std::string(each ? " each" : "") + (interval ? " in " : " ") + r;
}

std::string quoted_list(const std::vector<std::string>& names)
{
  std::vector<std::string> q;
  for (const std::string& n : names)
    q.push_back("'" + n + "'");
  return join(q, ", ");
}

/// "a number > 0 [kg/m^3]", "one of 'stress', 'strain'", ...
std::string expected_text(const Key& key, const SceneSchema& schema)
{
  switch (key.type)
  {
  case ValueType::string:
    return "a string";
  case ValueType::number:
    return "a number" + range_text(key, false) + unit_suffix(key);
  case ValueType::integer:
    return "an integer" + range_text(key, false);
  case ValueType::boolean:
    return "true or false";
  case ValueType::choice:
    return "one of " + quoted_list(key.choices);
  case ValueType::vector2:
    return "[x, y]: a list of 2 numbers" + range_text(key, true) + unit_suffix(key);
  case ValueType::integer_pair:
    return "a list of 2 integers" + range_text(key, true);
  case ValueType::integer_pair_list:
    return "a non-empty list of [integer, integer] pairs" + range_text(key, true);
  case ValueType::name_pair:
    return "a list of 2 names";
  case ValueType::voigt:
    return "[xx, yy, xy]: a list of 3 numbers" + unit_suffix(key);
  case ValueType::point_list:
    return "a list of [x, y] points" + unit_suffix(key);
  case ValueType::table:
    return "a list of [t, value] pairs with strictly increasing t";
  case ValueType::section:
    return "a map with keys " + quoted_list(schema.section(key.section).key_names());
  case ValueType::section_map:
    return "a map from names to maps with keys " +
           quoted_list(schema.section(key.section).key_names());
  case ValueType::section_list:
    return "a list of maps with keys " + quoted_list(schema.section(key.section).key_names());
  case ValueType::time_function:
    return "a time function: a map with 'type' one of " + quoted_list(schema.time_function_types());
  }
  return "";
}

// ---- Where a problem is ---------------------------------------------------------------------

/// A --set override as applied: the key path it set (in message form, "blocks[0].material") and
/// the argument as typed.
struct AppliedOverride
{
  std::string key_path;
  std::string argument;
};

std::string command_line_location(const std::string& argument)
{
  return "command line --set " + argument;
}

bool is_within(const std::string& path, const std::string& prefix)
{
  if (path.compare(0, prefix.size(), prefix) != 0)
    return false;
  return path.size() == prefix.size() || path[prefix.size()] == '.' || path[prefix.size()] == '[';
}

/// Turns problems at YAML nodes into InputErrors naming the file and line, or the --set argument
/// that put the value there.
class Locator
{
public:
  explicit Locator(std::string file_) : file(std::move(file_)) {}

  void add_override(AppliedOverride o) { overrides.push_back(std::move(o)); }

  InputError error(const YAML::Node& node, const std::string& key_path, const std::string& value,
                   const std::string& expected) const
  {
    // A problem at or inside an overridden key, or at a key an override changed something in.
    for (auto o = overrides.rbegin(); o != overrides.rend(); ++o)
      if (is_within(key_path, o->key_path) ||
          (!key_path.empty() && is_within(o->key_path, key_path)))
        return InputError::at(command_line_location(o->argument), 0, key_path, value, expected);
    int line = 0;
    if (node.IsDefined() && !node.Mark().is_null())
      line = node.Mark().line + 1;
    return InputError::at(file, line, key_path, value, expected);
  }

  const std::string& scene_file() const { return file; }

private:
  std::string file;
  std::vector<AppliedOverride> overrides;
};

/// What every reader needs: the schema, where problems are, and where relative paths start.
struct Context
{
  const SceneSchema& schema;
  const Locator& locator;
  std::filesystem::path scene_directory;
};

// ---- Reading one map against its schema section ---------------------------------------------

/// A YAML map checked against a schema section: no unknown or duplicate keys, all required keys
/// present. Its getters convert and range-check one key each, using the schema's default when the
/// key is absent; asking for a key that is not in the section is a programming error.
class MapReader
{
public:
  MapReader(const YAML::Node& node_, const Section& section_, std::string path_,
            const Context& context_)
      : node(node_), section(&section_), path(std::move(path_)), context(&context_)
  {
    // A null value (`output:` with nothing after it) is an empty map.
    if (!node.IsMap() && !node.IsNull())
      throw context->locator.error(node, path, yaml_text(node),
                                   "expected a map with keys " + quoted_list(section->key_names()));
    std::vector<std::string> seen;
    for (auto it = node.begin(); node.IsMap() && it != node.end(); ++it)
    {
      const YAML::Node key_node = it->first;
      if (!key_node.IsScalar())
        throw context->locator.error(key_node, path, yaml_text(key_node),
                                     "expected a key name (a string)");
      const std::string name = key_node.Scalar();
      if (std::find(seen.begin(), seen.end(), name) != seen.end())
        throw context->locator.error(key_node, path_of(name), "", "duplicate key");
      seen.push_back(name);
      if (section->find(name) == nullptr)
      {
        const std::string hint = suggestion(name, section->key_names());
        throw context->locator.error(key_node, path_of(name), "",
                                     "unknown key" + (hint.empty() ? std::string(".") : hint) +
                                         " Allowed keys here: " + join(section->key_names(), ", "));
      }
    }
    for (const Key& k : section->keys)
      if (k.required && !has(k.name))
        throw context->locator.error(node, path_of(k.name), "",
                                     "missing required key: expected " +
                                         expected_text(k, context->schema));
  }

  bool has(const std::string& name) const { return child(node, name).IsDefined(); }

  const std::string& key_path() const { return path; }
  const YAML::Node& yaml() const { return node; }
  const Context& ctx() const { return *context; }

  /// Path of a key of this map: "materials.rock.density".
  std::string path_of(const std::string& name) const
  {
    return path.empty() ? name : path + "." + name;
  }

  /// An error about key `name` (at its line, or the map's if it is absent).
  InputError error(const std::string& name, const std::string& expected) const
  {
    const YAML::Node n = child(node, name);
    return context->locator.error(n.IsDefined() ? n : node, path_of(name), yaml_text(n), expected);
  }

  double number(const std::string& name) const
  {
    const Value v = value(name, ValueType::number);
    const std::optional<double> x = parse_double(v.node);
    if (!x || !v.key->range.contains(*x))
      throw mismatch(v);
    return *x;
  }

  long long integer(const std::string& name) const
  {
    const Value v = value(name, ValueType::integer);
    const std::optional<long long> x = parse_integer(v.node);
    if (!x || !v.key->range.contains(static_cast<double>(*x)))
      throw mismatch(v);
    return *x;
  }

  bool boolean(const std::string& name) const
  {
    const Value v = value(name, ValueType::boolean);
    bool b = false;
    if (!v.node.IsScalar() || !YAML::convert<bool>::decode(v.node, b))
      throw mismatch(v);
    return b;
  }

  std::string string(const std::string& name) const
  {
    const Value v = value(name, ValueType::string);
    if (!v.node.IsScalar())
      throw mismatch(v);
    return v.node.Scalar();
  }

  std::string choice(const std::string& name) const
  {
    const Value v = value(name, ValueType::choice);
    if (!v.node.IsScalar())
      throw mismatch(v);
    const std::string s = v.node.Scalar();
    if (std::find(v.key->choices.begin(), v.key->choices.end(), s) == v.key->choices.end())
      throw context->locator.error(v.node, v.path, s,
                                   "expected " + expected_text(*v.key, context->schema) +
                                       suggestion(s, v.key->choices));
    return s;
  }

  Vector2 vector2(const std::string& name) const
  {
    const Value v = value(name, ValueType::vector2);
    const std::vector<double> x = numbers(v, 2);
    return Vector2(x[0], x[1]);
  }

  Voigt voigt(const std::string& name) const
  {
    const Value v = value(name, ValueType::voigt);
    const std::vector<double> x = numbers(v, 3);
    return Voigt(x[0], x[1], x[2]);
  }

  std::array<long long, 2> integer_pair(const std::string& name) const
  {
    const Value v = value(name, ValueType::integer_pair);
    if (!v.node.IsSequence() || v.node.size() != 2)
      throw mismatch(v);
    std::array<long long, 2> result{};
    for (std::size_t i = 0; i < 2; ++i)
    {
      const std::optional<long long> x = parse_integer(v.node[i]);
      if (!x || !v.key->range.contains(static_cast<double>(*x)))
        throw mismatch(v);
      result[i] = *x;
    }
    return result;
  }

  /// A non-empty list of pairs of integers ([[block, edge], ...]).
  std::vector<std::array<long long, 2>> integer_pair_list(const std::string& name) const
  {
    const Value v = value(name, ValueType::integer_pair_list);
    if (!v.node.IsSequence() || v.node.size() == 0)
      throw mismatch(v);
    std::vector<std::array<long long, 2>> result;
    for (std::size_t i = 0; i < v.node.size(); ++i)
    {
      const YAML::Node item = v.node[i];
      std::optional<long long> a, b;
      if (item.IsSequence() && item.size() == 2)
      {
        a = parse_integer(item[0]);
        b = parse_integer(item[1]);
      }
      if (!a || !b || !v.key->range.contains(static_cast<double>(*a)) ||
          !v.key->range.contains(static_cast<double>(*b)))
        throw context->locator.error(item, v.path + "[" + std::to_string(i) + "]", yaml_text(item),
                                     "expected a pair of integers in " +
                                         expected_text(*v.key, context->schema));
      result.push_back({*a, *b});
    }
    return result;
  }

  /// An error about item `i` of the list at key `name` (at the item's line).
  InputError item_error(const std::string& name, std::size_t i, const std::string& expected) const
  {
    const YAML::Node list = child(node, name);
    const YAML::Node& const_list = list;
    const YAML::Node item = const_list[i];
    return context->locator.error(item, path_of(name) + "[" + std::to_string(i) + "]",
                                  yaml_text(item), expected);
  }

  std::array<std::string, 2> name_pair(const std::string& name) const
  {
    const Value v = value(name, ValueType::name_pair);
    if (!v.node.IsSequence() || v.node.size() != 2 || !v.node[0].IsScalar() ||
        !v.node[1].IsScalar())
      throw mismatch(v);
    return {v.node[0].Scalar(), v.node[1].Scalar()};
  }

  /// A list of pairs of numbers ([[x, y], ...] or [[t, value], ...]).
  std::vector<std::array<double, 2>> pair_list(const std::string& name) const
  {
    const Key& k = section->key(name);
    assert(k.type == ValueType::point_list || k.type == ValueType::table);
    const Value v = value(name, k.type);
    if (!v.node.IsSequence() || v.node.size() == 0)
      throw mismatch(v);
    std::vector<std::array<double, 2>> result;
    for (std::size_t i = 0; i < v.node.size(); ++i)
    {
      const YAML::Node item = v.node[i];
      std::optional<double> a, b;
      if (item.IsSequence() && item.size() == 2)
      {
        a = parse_double(item[0]);
        b = parse_double(item[1]);
      }
      if (!a || !b)
        throw context->locator.error(item, v.path + "[" + std::to_string(i) + "]", yaml_text(item),
                                     "expected a pair of numbers in " +
                                         expected_text(k, context->schema));
      result.push_back({*a, *b});
    }
    return result;
  }

  MapReader section_reader(const std::string& name) const
  {
    const Value v = value_or_empty(name, ValueType::section);
    return MapReader(v.node, context->schema.section(v.key->section), v.path, *context);
  }

  /// Entries of a map of named maps, in file order.
  std::vector<std::pair<std::string, MapReader>> section_map(const std::string& name) const
  {
    const Value v = value_or_empty(name, ValueType::section_map);
    if (v.node.IsNull())
      return {};
    if (!v.node.IsMap())
      throw mismatch(v);
    const Section& s = context->schema.section(v.key->section);
    std::vector<std::pair<std::string, MapReader>> entries;
    std::vector<std::string> seen;
    for (auto it = v.node.begin(); it != v.node.end(); ++it)
    {
      const YAML::Node key_node = it->first;
      if (!key_node.IsScalar() || trim(key_node.Scalar()).empty())
        throw context->locator.error(key_node, v.path, yaml_text(key_node),
                                     "expected a name (a non-empty string)");
      const std::string entry = key_node.Scalar();
      if (std::find(seen.begin(), seen.end(), entry) != seen.end())
        throw context->locator.error(key_node, v.path + "." + entry, "", "duplicate name");
      seen.push_back(entry);
      entries.emplace_back(entry, MapReader(it->second, s, v.path + "." + entry, *context));
    }
    return entries;
  }

  std::vector<MapReader> section_list(const std::string& name) const
  {
    const Value v = value_or_empty(name, ValueType::section_list);
    if (v.node.IsNull())
      return {};
    if (!v.node.IsSequence())
      throw mismatch(v);
    const Section& s = context->schema.section(v.key->section);
    std::vector<MapReader> items;
    for (std::size_t i = 0; i < v.node.size(); ++i)
      items.emplace_back(v.node[i], s, v.path + "[" + std::to_string(i) + "]", *context);
    return items;
  }

  /// The time function's map, checked against the section its `type` selects.
  MapReader time_function_reader(const std::string& name) const
  {
    const Value v = value(name, ValueType::time_function);
    const std::vector<std::string>& types = context->schema.time_function_types();
    if (!v.node.IsMap())
      throw mismatch(v);
    const YAML::Node type_node = child(v.node, "type");
    if (!type_node.IsDefined())
      throw context->locator.error(v.node, v.path + ".type", "",
                                   "missing required key: expected one of " + quoted_list(types));
    const std::string type = type_node.IsScalar() ? type_node.Scalar() : "";
    if (std::find(types.begin(), types.end(), type) == types.end())
      throw context->locator.error(type_node, v.path + ".type", yaml_text(type_node),
                                   "expected one of " + quoted_list(types) +
                                       suggestion(type, types));
    return MapReader(v.node, context->schema.section(SceneSchema::time_function_section(type)),
                     v.path, *context);
  }

private:
  /// A key's value node: the user's, or the schema default parsed as YAML.
  struct Value
  {
    YAML::Node node;
    std::string path;
    const Key* key = nullptr;
  };

  Value value(const std::string& name, ValueType type) const
  {
    const Key& k = section->key(name);
    assert(k.type == type && "the reader asked for a key with another type than the schema's");
    (void)type;
    const YAML::Node n = child(node, name);
    if (n.IsDefined())
      return {n, path_of(name), &k};
    assert(!k.default_yaml.empty() && "the reader asked for an absent key without default");
    return {YAML::Load(k.default_yaml), path_of(name), &k};
  }

  /// Like value(), for optional sections without a YAML default: absent means empty.
  Value value_or_empty(const std::string& name, ValueType type) const
  {
    const Key& k = section->key(name);
    const YAML::Node n = child(node, name);
    if (n.IsDefined() || !k.default_yaml.empty())
      return value(name, type);
    return {YAML::Node(), path_of(name), &k};
  }

  InputError mismatch(const Value& v) const
  {
    return context->locator.error(v.node, v.path, yaml_text(v.node),
                                  "expected " + expected_text(*v.key, context->schema));
  }

  std::vector<double> numbers(const Value& v, std::size_t n) const
  {
    if (!v.node.IsSequence() || v.node.size() != n)
      throw mismatch(v);
    std::vector<double> result;
    for (std::size_t i = 0; i < n; ++i)
    {
      const std::optional<double> x = parse_double(v.node[i]);
      if (!x || !v.key->range.contains(*x))
        throw mismatch(v);
      result.push_back(*x);
    }
    return result;
  }

  YAML::Node node;
  const Section* section;
  std::string path;
  const Context* context;
};

// ---- Time functions -------------------------------------------------------------------------

/// A table from a CSV file; every problem names the file, row and the scene key.
TimeFunction read_csv_table(const MapReader& r)
{
  const std::string file = r.string("file");
  const long long time_column = r.integer("time_column");
  const long long value_column = r.integer("value_column");
  const long long skip_rows = r.integer("skip_rows");
  std::filesystem::path csv_path(file);
  if (csv_path.is_relative())
    csv_path = r.ctx().scene_directory / csv_path;
  const std::string shown = csv_path.lexically_normal().string();

  std::error_code ec;
  std::ifstream in(csv_path);
  if (!std::filesystem::is_regular_file(csv_path, ec) || !in)
    throw r.error("file", "cannot open CSV file '" + shown + "'");

  std::vector<double> times, values;
  std::string line;
  long long row = 0;
  const std::size_t n_needed = static_cast<std::size_t>(std::max(time_column, value_column)) + 1;
  while (std::getline(in, line))
  {
    ++row;
    if (row <= skip_rows || trim(line).empty())
      continue;
    const std::vector<std::string> cells = split(line, ',');
    const std::string at_row = "CSV file '" + shown + "' row " + std::to_string(row) + ": ";
    if (cells.size() < n_needed)
      throw r.error("file", at_row + "found " + std::to_string(cells.size()) +
                                " column(s), expected at least " + std::to_string(n_needed));
    const auto cell = [&](long long column)
    {
      const std::string text = trim(cells[static_cast<std::size_t>(column)]);
      const std::optional<double> x = parse_double(text);
      if (!x)
        throw r.error("file", at_row + "column " + std::to_string(column) + " is '" + text +
                                  "', expected a number");
      return *x;
    };
    const double t = cell(time_column);
    const double v = cell(value_column);
    if (!times.empty() && t <= times.back())
      throw r.error("file", at_row + "time " + format_number(t) +
                                " does not increase strictly (previous " +
                                format_number(times.back()) + ")");
    times.push_back(t);
    values.push_back(v);
  }
  if (times.empty())
    throw r.error("file", "CSV file '" + shown + "' has no data rows (after skipping " +
                              std::to_string(skip_rows) + ")");
  return TimeFunction::table(std::move(times), std::move(values));
}

TimeFunction read_time_function(const MapReader& parent, const std::string& name)
{
  const MapReader r = parent.time_function_reader(name);
  const std::string type = r.choice("type");
  if (type == "constant")
    return TimeFunction::constant(r.number("value"));
  if (type == "sine_pulse")
    return TimeFunction::sine_pulse(r.number("amplitude"), r.number("frequency"),
                                    r.number("cycles"), r.number("start"));
  if (type == "table")
  {
    std::vector<double> times, values;
    for (const auto& [t, v] : r.pair_list("points"))
    {
      if (!times.empty() && t <= times.back())
        throw r.error("points", "expected strictly increasing times; found " + format_number(t) +
                                    " after " + format_number(times.back()));
      times.push_back(t);
      values.push_back(v);
    }
    return TimeFunction::table(std::move(times), std::move(values));
  }
  assert(type == "csv");
  return read_csv_table(r);
}

// ---- Names ----------------------------------------------------------------------------------

/// Index of `name` in `names`, or an error at key `key` of `r` listing the defined names.
std::size_t find_name(const MapReader& r, const std::string& key, const std::string& name,
                      const std::vector<std::string>& names, const std::string& what)
{
  const auto it = std::find(names.begin(), names.end(), name);
  if (it != names.end())
    return static_cast<std::size_t>(it - names.begin());
  const std::string defined = names.empty() ? "none is defined" : "defined: " + join(names, ", ");
  throw r.error(key, "unknown " + what + " '" + name + "'" + suggestion(name, names) + " (" +
                         defined + ")");
}

// ---- Blocks ---------------------------------------------------------------------------------

/// Where a block came from, for messages.
struct BlockSource
{
  YAML::Node node;
  std::string key_path;
  bool generated = false;      ///< by `rock_mass`: disjoint from the other generated blocks
  bool initial_stress = false; ///< has an explicit `initial_stress` (else the in-situ stress)
};

/// Drops a repeated closing vertex, checks that the polygon (at key `key` of r) is simple and
/// orders it anticlockwise.
std::vector<Point> clean_polygon(const MapReader& r, const std::string& key,
                                 std::vector<Point> vertices)
{
  if (vertices.size() > 1 && vertices.front() == vertices.back())
    vertices.pop_back();
  std::vector<Point> distinct;
  for (const Point& v : vertices)
    if (std::find(distinct.begin(), distinct.end(), v) == distinct.end())
      distinct.push_back(v);
  if (distinct.size() < 3)
    throw r.error(key, "polygon is not closed: needs at least 3 distinct vertices");
  if (!dda::is_simple_polygon(vertices))
    throw r.error(key, "polygon of " + r.key_path() +
                           " is self-intersecting (or repeats a vertex or has zero "
                           "area): expected a simple polygon");
  if (dda::signed_area(vertices) < 0.0)
    std::reverse(vertices.begin(), vertices.end());
  return vertices;
}

/// [[x, y], ...] as points [m].
std::vector<Point> points_of(const std::vector<std::array<double, 2>>& pairs)
{
  std::vector<Point> points;
  for (const auto& [x, y] : pairs)
    points.emplace_back(x, y);
  return points;
}

/// The names of the keys of r among `names` that are present, quoted.
std::vector<std::string> present(const MapReader& r, const std::vector<std::string>& names)
{
  std::vector<std::string> found;
  for (const std::string& name : names)
    if (r.has(name))
      found.push_back("'" + name + "'");
  return found;
}

/// `rock_mass.region`: the rectangle's or the polygon's corners, anticlockwise.
std::vector<Point> read_region(const MapReader& r)
{
  const std::vector<std::string> given = present(r, {"rectangle", "polygon"});
  if (given.size() != 1)
    throw r.ctx().locator.error(
        r.yaml(), r.key_path(), "",
        (given.empty() ? std::string("no region given") : "both " + join(given, " and ")) +
            ": expected exactly one of 'rectangle: {lower: [x, y], upper: [x, y]}' or "
            "'polygon: [[x, y], ...]'");
  if (r.has("polygon"))
    return clean_polygon(r, "polygon", points_of(r.pair_list("polygon")));
  const MapReader rectangle = r.section_reader("rectangle");
  const Vector2 lower = rectangle.vector2("lower"), upper = rectangle.vector2("upper");
  if (!(upper.x() > lower.x() && upper.y() > lower.y()))
    throw rectangle.error("upper",
                          "expected upper > lower in both x and y, lower = " + format_point(lower));
  return {lower, Point(upper.x(), lower.y()), upper, Point(lower.x(), upper.y())};
}

dda::JointSet read_joint_set(const MapReader& r)
{
  dda::JointSet set;
  set.dip = r.number("dip");
  set.spacing = r.number("spacing");
  set.offset = r.number("offset");
  const bool has_trace = r.has("trace_length"), has_bridge = r.has("bridge");
  if (has_trace != has_bridge)
    throw r.error(has_trace ? "trace_length" : "bridge",
                  std::string(has_trace ? "a trace length needs a `bridge`"
                                        : "a bridge needs a `trace_length`") +
                      ": expected both (non-persistent joints) or neither (persistent joints)");
  if (has_trace)
  {
    set.trace_length = r.number("trace_length");
    set.bridge = r.number("bridge");
  }
  const MapReader p = r.section_reader("perturbation");
  set.perturbation.spacing = p.number("spacing");
  set.perturbation.position = p.number("position");
  set.perturbation.distribution =
      p.choice("distribution") == "normal" ? dda::Distribution::normal : dda::Distribution::uniform;
  return set;
}

/// `rock_mass.openings[i]`, checked to lie inside the region (as the polygon excavated).
dda::Opening read_opening(const MapReader& r, const std::vector<Point>& region,
                          double chord_tolerance)
{
  const std::vector<std::string> given = present(r, {"circle", "horseshoe", "polygon"});
  if (given.size() != 1)
    throw r.ctx().locator.error(
        r.yaml(), r.key_path(), "",
        (given.empty() ? std::string("no shape given")
                       : "more than one shape (" + join(given, ", ") + ")") +
            ": expected exactly one of 'circle: {center, radius}', 'horseshoe: {floor_center, "
            "width, wall_height}' or 'polygon: [[x, y], ...]'");
  dda::Opening o;
  std::string shape = "polygon";
  if (r.has("circle"))
  {
    shape = "circle";
    const MapReader c = r.section_reader("circle");
    o.shape = dda::Opening::Shape::circle;
    o.center = c.vector2("center");
    o.radius = c.number("radius");
  }
  else if (r.has("horseshoe"))
  {
    shape = "horseshoe";
    const MapReader h = r.section_reader("horseshoe");
    o.shape = dda::Opening::Shape::horseshoe;
    o.center = h.vector2("floor_center");
    o.width = h.number("width");
    o.wall_height = h.number("wall_height");
  }
  else
  {
    o.shape = dda::Opening::Shape::polygon;
    o.vertices = clean_polygon(r, "polygon", points_of(r.pair_list("polygon")));
  }
  const std::vector<Point> polygon = dda::opening_polygon(o, chord_tolerance);
  const double area = dda::signed_area(polygon);
  const double outside = area - dda::overlap_area(polygon, region);
  if (outside > 1e-9 * area)
    throw r.error(shape, "the opening reaches outside the region (" + format_number(outside) +
                             " of its " + format_number(area) +
                             " m^2): expected an opening inside the region");
  return o;
}

/// The `joint_material` of a joint set or explicit joint (an index into joint_names), if given.
std::optional<std::size_t> read_joint_material(const MapReader& r,
                                               const std::vector<std::string>& joint_names)
{
  if (!r.has("joint_material"))
    return std::nullopt;
  return find_name(r, "joint_material", r.string("joint_material"), joint_names, "joint material");
}

/// The `rock_mass` section: generates its blocks and appends them to the model.
RockMassReport read_rock_mass(const MapReader& r, const std::vector<std::string>& material_names,
                              const std::vector<std::string>& joint_names,
                              dda::ModelDescription& model, std::vector<BlockSource>& sources)
{
  dda::RockMassDescription d;
  RockMassReport report;
  const std::size_t material =
      find_name(r, "material", r.string("material"), material_names, "material");
  d.region = read_region(r.section_reader("region"));
  d.chord_tolerance = r.number("chord_tolerance");
  d.seed = static_cast<std::uint64_t>(r.integer("seed"));
  for (const MapReader& j : r.section_list("joint_sets"))
  {
    d.joint_sets.push_back(read_joint_set(j));
    report.joint_set_materials.push_back(read_joint_material(j, joint_names));
  }
  for (const MapReader& j : r.section_list("joints"))
  {
    d.joints.push_back({j.vector2("from"), j.vector2("to")});
    report.joint_materials.push_back(read_joint_material(j, joint_names));
    if (d.joints.back().from == d.joints.back().to)
      throw j.error("to", "the joint ends where it starts: expected a point other than `from`");
  }
  for (const MapReader& o : r.section_list("openings"))
    d.openings.push_back(read_opening(o, d.region, d.chord_tolerance));
  if (r.has("min_block_area"))
    d.slivers.min_area = r.number("min_block_area");
  d.slivers.min_inscribed_radius = r.number("min_inscribed_radius");
  d.slivers.action =
      r.choice("slivers") == "report" ? dda::SliverAction::report : dda::SliverAction::merge;

  dda::RockMassResult result;
  try
  {
    result = dda::generate_blocks(d);
  }
  catch (const InputError& e)
  {
    throw r.ctx().locator.error(r.yaml(), r.key_path(), "", e.what());
  }
  if (result.blocks.empty())
    throw r.ctx().locator.error(r.yaml(), r.key_path(), "",
                                "the openings cover the whole region: expected rock left");
  report.first_block = model.blocks.size();
  report.statistics = result.statistics;
  report.joint_sets = d.joint_sets;
  report.joints = d.joints;
  for (std::size_t i = 0; i < result.blocks.size(); ++i)
  {
    dda::BlockDescription block;
    block.vertices = std::move(result.blocks[i].vertices);
    block.edge_joint_materials = edge_joint_materials(result.blocks[i], report);
    block.material = material;
    block.origin = "rock_mass block " + std::to_string(i);
    model.blocks.push_back(std::move(block));
    sources.push_back({r.yaml(), r.key_path(), true});
  }
  for (dda::Sliver sliver : result.slivers)
  {
    sliver.block += report.first_block;
    report.slivers.push_back(sliver);
  }
  return report;
}

/// The node at `keys` below `node`, or an undefined node if some map on the way is missing.
YAML::Node nested(const YAML::Node& node, const std::vector<std::string>& keys)
{
  YAML::Node n = node;
  for (const std::string& k : keys)
  {
    if (!n.IsMap())
      return YAML::Node(YAML::NodeType::Undefined);
    const YAML::Node next = child(n, k);
    if (!next.IsDefined())
      return YAML::Node(YAML::NodeType::Undefined);
    n.reset(next);
  }
  return n;
}

/// The `tunnel` section's joint sets and explicit joints. Their joint material names (passed on
/// to `rock_mass` with them) are checked here, so that errors name the tunnel's keys.
void read_tunnel_joints(const MapReader& r, const YAML::Node& root, dda::RockMassDescription& d)
{
  std::vector<std::string> joint_names;
  for (const auto& named : nested(root, {"joint_materials"}))
    joint_names.push_back(named.first.Scalar());
  for (const MapReader& j : r.section_list("joint_sets"))
  {
    d.joint_sets.push_back(read_joint_set(j));
    read_joint_material(j, joint_names);
  }
  for (const MapReader& j : r.section_list("joints"))
  {
    d.joints.push_back({j.vector2("from"), j.vector2("to")});
    read_joint_material(j, joint_names);
  }
}

/// The `tunnel` section: reads it, plans the model (app/tunnel_scene.h) and writes the sections
/// it generates into `root`, which is then read like any scene.
TunnelPlan expand_tunnel(YAML::Node& root, const Context& context)
{
  const YAML::Node tunnel_node = child(root, "tunnel");
  const MapReader r(tunnel_node, context.schema.section("tunnel"), "tunnel", context);
  TunnelDescription t;
  t.rock = r.string("rock");
  const YAML::Node rock_node = nested(root, {"materials", t.rock});
  if (!rock_node.IsDefined())
    throw r.error("rock", "expected the name of a material in `materials`");
  const MapReader rock(rock_node, context.schema.section("materials.<name>"), "materials." + t.rock,
                       context);
  t.density = rock.number("density");
  t.youngs_modulus = rock.number("youngs_modulus");
  t.poisson_ratio = rock.number("poisson_ratio");
  const YAML::Node default_joint = nested(root, {"joints", "default"});
  if (default_joint.IsDefined() && default_joint.IsScalar())
  {
    const YAML::Node j = nested(root, {"joint_materials", default_joint.Scalar()});
    if (j.IsDefined())
      t.joint_normal_stiffness = MapReader(j, context.schema.section("joint_materials.<name>"),
                                           "joint_materials." + default_joint.Scalar(), context)
                                     .number("normal_stiffness");
  }
  const YAML::Node gravity = child(root, "gravity");
  if (gravity.IsDefined())
  {
    const MapReader top(root, context.schema.section(SceneSchema::top_level), "", context);
    const Vector2 g = top.vector2("gravity");
    if (!(g.y() < 0.0) || g.x() != 0.0)
      throw top.error("gravity", "expected gravity [0, -g] (downwards) with a tunnel");
    t.gravity = -g.y();
  }
  const YAML::Node plane = nested(root, {"analysis", "plane"});
  if (plane.IsDefined() && plane.IsScalar() && plane.Scalar() != "strain")
    throw context.locator.error(plane, "analysis.plane", plane.Scalar(),
                                "expected strain (or nothing) with a tunnel: a section through "
                                "a long tunnel is in plane strain");

  t.rock_mass.chord_tolerance = r.number("chord_tolerance");
  t.rock_mass.seed = static_cast<std::uint64_t>(r.integer("seed"));
  read_tunnel_joints(r, root, t.rock_mass);
  const double far = 1e12;
  t.rock_mass.openings.push_back(
      read_opening(r.section_reader("opening"),
                   {Point(-far, -far), Point(far, -far), Point(far, far), Point(-far, far)},
                   t.rock_mass.chord_tolerance));
  t.depth = r.number("depth");
  t.k0 = r.number("k0");

  const MapReader wave = r.section_reader("wave");
  t.wave_type = wave.choice("type");
  const TimeFunction velocity = read_time_function(wave, "velocity");
  const bool pulse = nested(tunnel_node, {"wave", "velocity", "type"}).Scalar() == "sine_pulse";
  if (wave.has("frequency"))
    t.wave_frequency = wave.number("frequency");
  else if (pulse)
    t.wave_frequency = velocity.characteristic_frequency();
  else
    throw wave.error("frequency", "expected the wave's dominant frequency [Hz] for a record");
  t.max_frequency =
      wave.has("max_frequency") ? wave.number("max_frequency") : 2.0 * t.wave_frequency;
  t.wave_duration = velocity.active_until();

  const MapReader near = r.section_reader("near_field");
  t.size_factor = near.number("size_factor");
  if (near.has("lower") != near.has("upper"))
    throw near.error(near.has("lower") ? "upper" : "lower",
                     "expected both `lower` and `upper`, or neither (size_factor)");
  if (near.has("lower"))
  {
    const Vector2 lower = near.vector2("lower"), upper = near.vector2("upper");
    if (!(upper.x() > lower.x() && upper.y() > lower.y()))
      throw near.error("upper", "expected upper > lower in both x and y");
    t.near_field = std::array<Point, 2>{lower, upper};
  }
  const std::string truncation = r.choice("truncation");
  t.truncation = truncation == "vb1"         ? TunnelTruncation::vb1
                 : truncation == "dashpot"   ? TunnelTruncation::dashpot
                 : truncation == "reference" ? TunnelTruncation::reference
                 : truncation == "blocks"    ? TunnelTruncation::blocks
                                             : TunnelTruncation::hybrid;
  if (r.has("margin"))
    t.margin = r.number("margin");
  if (r.has("reference_margin"))
    t.reference_margin = r.number("reference_margin");
  t.points_per_wavelength = r.number("points_per_wavelength");
  t.growth_ratio = r.number("growth_ratio");
  if (r.has("window"))
    t.window = r.number("window");
  if (r.has("dt"))
    t.dt = r.number("dt");
  const MapReader stage = r.section_reader("static");
  if (stage.has("dt"))
    t.static_dt = stage.number("dt");
  t.static_tolerance = stage.number("tolerance");
  t.static_max_steps = stage.integer("max_steps");
  t.static_release = stage.choice("release");
  const MapReader settle = r.section_reader("settle");
  if (settle.has("enabled"))
    t.settle = settle.boolean("enabled");
  t.settle_rest_speed = settle.number("rest_speed");
  if (settle.has("rest_duration"))
    t.settle_rest_duration = settle.number("rest_duration");
  if (settle.has("max_duration"))
    t.settle_max_duration = settle.number("max_duration");
  t.settle_remove_fallen = settle.boolean("remove_fallen");

  try
  {
    TunnelPlan plan = plan_tunnel(t);
    write_tunnel_sections(t, plan,
                          {child(tunnel_node, "opening"), child(tunnel_node, "joint_sets"),
                           child(tunnel_node, "joints"), nested(tunnel_node, {"wave", "velocity"})},
                          root);
    return plan;
  }
  catch (const InputError& e)
  {
    throw context.locator.error(tunnel_node, "tunnel", "", e.what());
  }
}

void read_blocks(const MapReader& top, const std::vector<std::string>& material_names,
                 const std::vector<std::string>& joint_names, dda::ModelDescription& model,
                 std::vector<BlockSource>& sources, std::optional<RockMassReport>& rock_mass)
{
  const std::vector<MapReader> items = top.section_list("blocks");
  const bool has_blocks = !items.empty() || top.has("rock_mass");
  if (!has_blocks && !top.has("far_field"))
    throw top.error("blocks", "expected at least one block (or a `rock_mass` or a `far_field`)");
  if (has_blocks && top.has("far_field") && !top.has("interface"))
    throw top.error("far_field", "blocks and a far field need an `interface` section: expected "
                                 "`interface: {part: PART}` naming the far field's part the "
                                 "blocks fill (e.g. hole)");
  if (top.has("interface") && (!has_blocks || !top.has("far_field")))
    throw top.error("interface", "an interface ties blocks to a far field: expected both "
                                 "`blocks` and `far_field`");
  for (std::size_t i = 0; i < items.size(); ++i)
  {
    const MapReader& r = items[i];
    dda::BlockDescription block;
    block.material = find_name(r, "material", r.string("material"), material_names, "material");
    block.initial_velocity = r.vector2("initial_velocity");
    block.initial_stress = r.voigt("initial_stress");
    const bool has_vertices = r.has("vertices"), has_grid = r.has("grid");
    if (has_vertices == has_grid)
      throw top.ctx().locator.error(r.yaml(), r.key_path(), "",
                                    has_vertices ? "give either 'vertices' or 'grid', not both"
                                                 : "missing key: give 'vertices' or 'grid'");
    if (has_vertices)
    {
      std::vector<Point> vertices;
      for (const auto& [x, y] : r.pair_list("vertices"))
        vertices.emplace_back(x, y);
      block.vertices = clean_polygon(r, "vertices", std::move(vertices));
      block.origin = r.key_path();
      model.blocks.push_back(block);
      sources.push_back({r.yaml(), r.key_path(), false, r.has("initial_stress")});
      continue;
    }
    const MapReader grid = r.section_reader("grid");
    const Vector2 origin = grid.vector2("origin");
    const Vector2 cell = grid.vector2("cell_size");
    const std::array<long long, 2> count = grid.integer_pair("count");
    constexpr long long max_cells = 1000000;
    if (count[0] > max_cells || count[1] > max_cells || count[0] * count[1] > max_cells)
      throw grid.error("count", "expected at most " + std::to_string(max_cells) + " cells in all");
    for (long long iy = 0; iy < count[1]; ++iy)
      for (long long ix = 0; ix < count[0]; ++ix)
      {
        const double x0 = origin.x() + static_cast<double>(ix) * cell.x();
        const double x1 = origin.x() + static_cast<double>(ix + 1) * cell.x();
        const double y0 = origin.y() + static_cast<double>(iy) * cell.y();
        const double y1 = origin.y() + static_cast<double>(iy + 1) * cell.y();
        block.vertices = {Point(x0, y0), Point(x1, y0), Point(x1, y1), Point(x0, y1)};
        block.origin =
            r.key_path() + " (grid cell " + std::to_string(ix) + ", " + std::to_string(iy) + ")";
        model.blocks.push_back(block);
        sources.push_back({r.yaml(), r.key_path(), false, r.has("initial_stress")});
      }
  }
  if (top.has("rock_mass"))
    rock_mass = read_rock_mass(top.section_reader("rock_mass"), material_names, joint_names, model,
                               sources);
}

/// Axis-aligned bounding box [m].
struct Box
{
  Point lower = Point::Constant(std::numeric_limits<double>::max());
  Point upper = Point::Constant(std::numeric_limits<double>::lowest());

  explicit Box(const std::vector<Point>& vertices)
  {
    for (const Point& v : vertices)
    {
      lower = lower.cwiseMin(v);
      upper = upper.cwiseMax(v);
    }
  }
  bool contains(const Point& p, double tol) const
  {
    return p.x() >= lower.x() - tol && p.x() <= upper.x() + tol && p.y() >= lower.y() - tol &&
           p.y() <= upper.y() + tol;
  }
};

/// Interval [min, max] of the projections of a polygon's vertices onto a direction.
std::pair<double, double> projection(const std::vector<Point>& vertices, const Vector2& direction)
{
  double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
  for (const Point& v : vertices)
  {
    const double x = v.dot(direction);
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  return {lo, hi};
}

/// An upper bound of the overlap area of two polygons [m^2], from their projections onto the
/// edge normals of both: the intersection lies in the slab where the projections overlap, and its
/// length along the slab is at most the smaller extent of the two polygons along it. Zero for
/// convex polygons that are separated or only touch; cheap next to the exact computation.
double overlap_area_bound(const std::vector<Point>& a, const std::vector<Point>& b)
{
  double bound = std::numeric_limits<double>::max();
  for (const std::vector<Point>* polygon : {&a, &b})
  {
    const std::size_t n = polygon->size();
    for (std::size_t k = 0; k < n; ++k)
    {
      const Vector2 edge = (*polygon)[(k + 1) % n] - (*polygon)[k];
      if (edge.norm() == 0.0)
        continue;
      const Vector2 along = edge.normalized();
      const Vector2 normal(-along.y(), along.x());
      const auto [a_lo, a_hi] = projection(a, normal);
      const auto [b_lo, b_hi] = projection(b, normal);
      const double width = std::min(a_hi, b_hi) - std::max(a_lo, b_lo);
      if (width <= 0.0)
        return 0.0;
      const auto [a_first, a_last] = projection(a, along);
      const auto [b_first, b_last] = projection(b, along);
      bound = std::min(bound, width * std::min(a_last - a_first, b_last - b_first));
    }
  }
  return bound;
}

/// Overlapping blocks are an error. Only pairs whose bounding boxes (and projections onto their
/// edge normals) overlap by more than the tolerated area are handed to the exact but slow
/// overlap computation; candidate pairs come from a sweep over the boxes sorted by lower x.
void check_overlaps(const dda::ModelDescription& model, const std::vector<BlockSource>& sources,
                    const Locator& locator)
{
  const std::size_t n = model.blocks.size();
  std::vector<Box> boxes;
  std::vector<double> areas;
  for (const dda::BlockDescription& b : model.blocks)
  {
    boxes.emplace_back(b.vertices);
    areas.push_back(std::abs(dda::signed_area(b.vertices)));
  }
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i)
    order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return boxes[a].lower.x() < boxes[b].lower.x(); });
  for (std::size_t oi = 0; oi < n; ++oi)
  {
    const std::size_t i = order[oi];
    for (std::size_t oj = oi + 1; oj < n && boxes[order[oj]].lower.x() < boxes[i].upper.x(); ++oj)
    {
      const std::size_t j = order[oj];
      if (sources[i].generated && sources[j].generated)
        continue; // faces of one arrangement
      const double tolerated = 1e-9 * std::min(areas[i], areas[j]);
      const double wx = std::min(boxes[i].upper.x(), boxes[j].upper.x()) -
                        std::max(boxes[i].lower.x(), boxes[j].lower.x());
      const double wy = std::min(boxes[i].upper.y(), boxes[j].upper.y()) -
                        std::max(boxes[i].lower.y(), boxes[j].lower.y());
      if (wx <= 0.0 || wy <= 0.0 || wx * wy <= tolerated ||
          overlap_area_bound(model.blocks[i].vertices, model.blocks[j].vertices) <= tolerated)
        continue;
      const double overlap = dda::overlap_area(model.blocks[i].vertices, model.blocks[j].vertices);
      if (overlap > tolerated)
      {
        const std::size_t first = std::min(i, j), second = std::max(i, j);
        throw locator.error(sources[second].node, sources[second].key_path, "",
                            "blocks overlap: " + model.blocks[first].origin + " and " +
                                model.blocks[second].origin + " share an area of " +
                                format_number(overlap) +
                                " m^2; expected blocks that touch at most");
      }
    }
  }
}

/// Points of loads, supports and monitors must be inside or on the boundary of some block.
bool in_some_block(const Point& p, const dda::ModelDescription& model,
                   const std::vector<Box>& boxes, double tol)
{
  for (std::size_t b = 0; b < model.blocks.size(); ++b)
    if (boxes[b].contains(p, tol) &&
        dda::locate_point(model.blocks[b].vertices, p, tol) != dda::PointLocation::outside)
      return true;
  return false;
}

void check_point_in_blocks(const MapReader& r, const std::string& key, const Point& p,
                           const dda::ModelDescription& model, const std::vector<Box>& boxes,
                           double tol)
{
  if (in_some_block(p, model, boxes, tol))
    return;
  throw r.error(key, "the point " + format_point(p) +
                         " lies outside every block; expected a point inside or on the boundary "
                         "of a block");
}

/// Monitors of a far-field scene must lie in its rectangle.
void check_point_in_far_field(const MapReader& r, const std::string& key, const Point& p,
                              const fem::FarFieldDescription& far_field)
{
  const double tol = 1e-9 * std::hypot(far_field.upper[0] - far_field.lower[0],
                                       far_field.upper[1] - far_field.lower[1]);
  if (p.x() < far_field.lower[0] - tol || p.x() > far_field.upper[0] + tol ||
      p.y() < far_field.lower[1] - tol || p.y() > far_field.upper[1] + tol)
    throw r.error(
        key, "the point " + format_point(p) + " lies outside the far field; expected a point in [" +
                 format_number(far_field.lower[0]) + ", " + format_number(far_field.upper[0]) +
                 "] x [" + format_number(far_field.lower[1]) + ", " +
                 format_number(far_field.upper[1]) + "]");
}

fem::BoundaryPart part_of(const std::string& name)
{
  return name == "bottom"  ? fem::BoundaryPart::bottom
         : name == "right" ? fem::BoundaryPart::right
         : name == "top"   ? fem::BoundaryPart::top
         : name == "left"  ? fem::BoundaryPart::left
                           : fem::BoundaryPart::hole;
}

/// `far_field.rayleigh`: {alpha, beta} or {ratio, frequencies}.
fem::RayleighDamping read_rayleigh(const MapReader& r)
{
  fem::RayleighDamping rayleigh;
  const bool factors = r.has("alpha") || r.has("beta");
  const bool ratio = r.has("ratio") || r.has("frequencies");
  if (factors == ratio)
    throw r.error(factors ? "ratio" : "alpha",
                  "expected either `alpha` and/or `beta`, or `ratio` with `frequencies`");
  if (factors)
  {
    rayleigh.alpha = r.has("alpha") ? r.number("alpha") : 0.0;
    rayleigh.beta = r.has("beta") ? r.number("beta") : 0.0;
    return rayleigh;
  }
  for (const char* k : {"ratio", "frequencies"})
    if (!r.has(k))
      throw r.error(k, "missing required key: `ratio` needs `frequencies` [f1, f2] and back");
  const double zeta = r.number("ratio");
  const Vector2 f = r.vector2("frequencies");
  if (!(f.y() > f.x()))
    throw r.error("frequencies", "expected f1 < f2");
  const double w1 = 2.0 * M_PI * f.x(), w2 = 2.0 * M_PI * f.y();
  rayleigh.alpha = 2.0 * zeta * w1 * w2 / (w1 + w2);
  rayleigh.beta = 2.0 * zeta / (w1 + w2);
  return rayleigh;
}

/// `far_field.mesh`: the Gmsh file (relative to the scene) and its tags.
fem::MeshFile read_mesh_file(const MapReader& f)
{
  for (const char* corner : {"lower", "upper"})
    if (f.has(corner))
      throw f.error(corner, "expected no rectangle corners with a `mesh` file (the mesh is the "
                            "file's)");
  if (f.has("hole"))
    throw f.error("hole", "expected no `hole` with a `mesh` file (the file brings its own)");
  const MapReader r = f.section_reader("mesh");
  fem::MeshFile mesh;
  std::filesystem::path path(r.string("file"));
  if (path.is_relative())
    path = r.ctx().scene_directory / path;
  mesh.file = path.lexically_normal().string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw r.error("file", "cannot open mesh file '" + mesh.file + "': expected a Gmsh .msh file");
  const MapReader parts = r.section_reader("parts");
  std::map<long long, std::string> seen;
  for (const char* part : {"bottom", "right", "top", "left", "hole"})
    if (parts.has(part))
    {
      const long long tag = parts.integer(part);
      const auto [it, inserted] = seen.emplace(tag, part);
      if (!inserted)
        throw parts.error(part, "the tag is also given to `" + it->second +
                                    "`: expected one physical tag per part");
      mesh.parts[part_of(part)] = static_cast<unsigned int>(tag);
    }
  return mesh;
}

/// `far_field.hole`: the keys of its shape, no others.
fem::HoleDescription read_hole(const MapReader& r, const fem::FarFieldDescription& d)
{
  fem::HoleDescription hole;
  const std::string shape = r.choice("shape");
  const std::map<std::string, std::vector<std::string>> keys = {{"rectangle", {"lower", "upper"}},
                                                                {"polygon", {"vertices"}},
                                                                {"circle", {"center", "radius"}}};
  for (const auto& [other, names] : keys)
    for (const std::string& name : names)
    {
      const bool mine = other == shape;
      if (mine && !r.has(name))
        throw r.error(name, "missing required key for shape " + shape);
      if (!mine && r.has(name) &&
          std::find(keys.at(shape).begin(), keys.at(shape).end(), name) == keys.at(shape).end())
        throw r.error(name, "expected only the keys of shape " + shape + " (" +
                                join(keys.at(shape), ", ") + ")");
    }
  hole.shape = shape == "rectangle" ? fem::HoleShape::rectangle
               : shape == "polygon" ? fem::HoleShape::polygon
                                    : fem::HoleShape::circle;
  std::array<double, 4> box{}; // x0, x1, y0, y1 of the hole
  if (hole.shape == fem::HoleShape::rectangle)
  {
    const Vector2 lower = r.vector2("lower"), upper = r.vector2("upper");
    if (!(upper.x() > lower.x() && upper.y() > lower.y()))
      throw r.error("upper",
                    "expected upper > lower in both x and y, lower = " + format_point(lower));
    hole.lower = {lower.x(), lower.y()};
    hole.upper = {upper.x(), upper.y()};
    box = {lower.x(), upper.x(), lower.y(), upper.y()};
  }
  else if (hole.shape == fem::HoleShape::polygon)
  {
    hole.vertices = r.pair_list("vertices");
    if (hole.vertices.size() < 3)
      throw r.error("vertices", "expected at least 3 vertices");
    box = {hole.vertices[0][0], hole.vertices[0][0], hole.vertices[0][1], hole.vertices[0][1]};
    for (const auto& v : hole.vertices)
      box = {std::min(box[0], v[0]), std::max(box[1], v[0]), std::min(box[2], v[1]),
             std::max(box[3], v[1])};
  }
  else
  {
    const Vector2 c = r.vector2("center");
    hole.center = {c.x(), c.y()};
    hole.radius = r.number("radius");
    box = {c.x() - hole.radius, c.x() + hole.radius, c.y() - hole.radius, c.y() + hole.radius};
  }
  if (!(box[0] > d.lower[0] && box[1] < d.upper[0] && box[2] > d.lower[1] && box[3] < d.upper[1]))
    throw r.error("shape",
                  "the hole spans [" + format_number(box[0]) + ", " + format_number(box[1]) +
                      "] x [" + format_number(box[2]) + ", " + format_number(box[3]) +
                      "]: expected it strictly inside the far field [" + format_number(d.lower[0]) +
                      ", " + format_number(d.upper[0]) + "] x [" + format_number(d.lower[1]) +
                      ", " + format_number(d.upper[1]) + "]");
  hole.element_size = r.number("element_size");
  hole.growth_ratio = r.number("growth_ratio");
  return hole;
}

/// The `far_field` section (the plane mode, time step and integrator come from the scene).
fem::FarFieldDescription read_far_field(const MapReader& f, const dda::ModelDescription& model,
                                        const std::vector<std::string>& material_names)
{
  fem::FarFieldDescription d;
  const dda::Material& m =
      model.materials[find_name(f, "material", f.string("material"), material_names, "material")];
  d.density = m.density;
  d.youngs_modulus = m.youngs_modulus;
  d.poisson_ratio = m.poisson_ratio;
  if (f.has("mesh"))
    d.mesh_file = read_mesh_file(f);
  else
  {
    for (const char* corner : {"lower", "upper"})
      if (!f.has(corner))
        throw f.error(corner, "missing required key: expected [x, y] in m (or a `mesh` file)");
    const Vector2 lower = f.vector2("lower"), upper = f.vector2("upper");
    if (!(upper.x() > lower.x() && upper.y() > lower.y()))
      throw f.error("upper",
                    "expected upper > lower in both x and y, lower = " + format_point(lower));
    d.lower = {lower.x(), lower.y()};
    d.upper = {upper.x(), upper.y()};
  }
  d.element_size = f.number("element_size");
  d.max_frequency = f.number("max_frequency");
  d.points_per_wavelength = f.number("points_per_wavelength");
  if (d.element_size == 0.0 && d.max_frequency == 0.0 && !f.has("mesh"))
    throw f.error("element_size", "expected element_size > 0, or max_frequency > 0 to choose it");
  if (f.has("hole"))
    d.hole = read_hole(f.section_reader("hole"), d);
  d.solver = f.choice("solver") == "cg" ? fem::LinearSolver::cg : fem::LinearSolver::direct;
  if (f.has("static_stage"))
  {
    const MapReader r = f.section_reader("static_stage");
    fem::StaticStage& s = d.static_stage;
    s.enabled = true;
    if (r.has("gravity"))
    {
      const Vector2 g = r.vector2("gravity");
      s.gravity = {g.x(), g.y()};
    }
    const Voigt stress = r.voigt("stress"), gradient = r.voigt("stress_gradient");
    s.stress = {stress[0], stress[1], stress[2]};
    s.stress_gradient = {gradient[0], gradient[1], gradient[2]};
    s.reference_y = r.has("reference_y") ? r.number("reference_y") : d.upper[1];
    s.support =
        r.choice("support") == "roller" ? fem::StaticSupport::roller : fem::StaticSupport::fixed;
  }
  if (f.has("rayleigh"))
    d.rayleigh = read_rayleigh(f.section_reader("rayleigh"));
  d.solver_tolerance = f.number("solver_tolerance");
  const long long degree = f.integer("degree");
  if (degree != 1 && degree != 2)
    throw f.error("degree", "expected 1 or 2");
  d.degree = static_cast<unsigned int>(degree);
  d.plane_mode =
      model.plane_mode == dda::PlaneMode::stress ? fem::PlaneMode::stress : fem::PlaneMode::strain;
  std::set<std::string> parts;
  for (const MapReader& r : f.section_list("boundaries"))
  {
    fem::BoundaryCondition bc;
    const std::string part = r.choice("part");
    if (!parts.insert(part).second)
      throw r.error("part", "side '" + part + "' is listed twice: expected each side once");
    bc.part = part_of(part);
    if (bc.part == fem::BoundaryPart::hole && d.hole.shape == fem::HoleShape::none &&
        d.mesh_file.parts.count(fem::BoundaryPart::hole) == 0)
      throw r.error("part", "the far field has no hole: expected a `far_field.hole` section or "
                            "a `hole` tag in `far_field.mesh.parts`");
    const std::string type = r.choice("type");
    bc.kind = type == "fixed"        ? fem::BoundaryKind::fixed
              : type == "lysmer"     ? fem::BoundaryKind::lysmer
              : type == "input"      ? fem::BoundaryKind::input
              : type == "roller"     ? fem::BoundaryKind::roller
              : type == "free_field" ? fem::BoundaryKind::free_field
                                     : fem::BoundaryKind::free;
    bc.a = r.number("a");
    bc.b = r.number("b");
    if (r.has("springs"))
    {
      if (bc.kind != fem::BoundaryKind::lysmer)
        throw r.error("springs", "springs stand beside Lysmer dashpots: expected `type: lysmer`");
      const MapReader sr = r.section_reader("springs");
      bc.springs.enabled = true;
      const Vector2 c = sr.vector2("center");
      bc.springs.center = {c.x(), c.y()};
      bc.springs.alpha_n = sr.number("alpha_n");
      bc.springs.alpha_t = sr.number("alpha_t");
    }
    d.boundaries.push_back(bc);
  }
  if (f.has("incident"))
  {
    const MapReader inc = f.section_reader("incident");
    d.incident.type =
        inc.choice("type") == "p" ? fem::IncidentWave::Type::p : fem::IncidentWave::Type::sv;
    d.incident.velocity = read_time_function(inc, "velocity");
  }
  return d;
}

/// The `interface` section: ties between the blocks and the far field's part they fill.
coupling::InterfaceDescription read_interface(const MapReader& r,
                                              const dda::ModelDescription& model,
                                              const std::vector<std::string>& joint_names)
{
  coupling::InterfaceDescription d;
  d.part = part_of(r.choice("part"));
  // Springs from the named joint material (and its strength), else from joints.default.
  const dda::JointMaterial* source = nullptr;
  if (r.has("joint_material"))
  {
    source = &model.joint_materials[find_name(r, "joint_material", r.string("joint_material"),
                                              joint_names, "joint material")];
    d.cohesion = source->cohesion;
    d.tensile_strength = source->tensile_strength;
    d.friction_angle = source->friction_angle;
  }
  else if (model.default_joint_material < model.joint_materials.size())
    source = &model.joint_materials[model.default_joint_material];
  d.normal_stiffness = r.has("normal_stiffness") ? r.number("normal_stiffness")
                       : source                  ? source->normal_stiffness
                                                 : 0.0;
  if (!(d.normal_stiffness > 0.0))
    throw r.error("normal_stiffness", "no spring for the ties: expected `normal_stiffness` [N/m], "
                                      "a `joint_material`, or `joints.default`");
  d.shear_ratio = r.has("shear_ratio") ? r.number("shear_ratio")
                  : source             ? source->shear_ratio
                                       : d.shear_ratio;
  d.points_per_face = static_cast<unsigned>(r.integer("points_per_face"));
  d.tolerance = r.number("tolerance");
  return d;
}

/// A `stages[i]` item with `mode: settle`: its SettleCriterion (no `dt`, no `end_time`: it runs
/// with time.dt from where the previous stage ended, to rest or its max_duration).
dda::SettleCriterion read_settle_criterion(const MapReader& r)
{
  for (const char* key : {"dt", "end_time", "max_steps", "tolerance", "release"})
    if (r.has(key))
      throw r.error(key, std::string("a settle stage runs with time.dt until its blocks are at "
                                     "rest or max_duration: expected no `") +
                             key + "` here");
  dda::SettleCriterion c;
  c.rest_speed = r.number("rest_speed");
  c.rest_duration = r.number("rest_duration");
  c.fall_distance = r.number("fall_distance");
  c.max_duration = r.number("max_duration");
  c.remove_fallen = r.boolean("remove_fallen");
  if (c.remove_fallen && c.fall_distance <= 0.0)
    throw r.error("remove_fallen",
                  "fallen blocks are removed once they have fallen: expected fall_distance > 0 "
                  "with remove_fallen true");
  return c;
}

/// Stages of blocks tied to a far field: static stages hold the far field (the ties are
/// springs to fixed ground) and the far field starts at rest from the first dynamic stage, so
/// every static stage must come before it; a static stage cannot carry a frictional interface
/// (its ties would need Mohr-Coulomb on the preload plus the spring force).
void check_coupled_stages(const MapReader& top, const dda::ModelDescription& model)
{
  const std::vector<MapReader> items = top.section_list("stages");
  bool dynamic_seen = false;
  for (std::size_t i = 0; i < model.stages.size(); ++i)
  {
    if (model.stages[i].mode == dda::StageMode::dynamic)
    {
      dynamic_seen = true;
      continue;
    }
    if (dynamic_seen)
      throw items[i].error("mode", "a static stage after a dynamic one in a coupled scene: the "
                                   "far field carries only the dynamic increment from the first "
                                   "dynamic stage on and cannot be held again; expected every "
                                   "static stage before the dynamic ones");
    if (top.section_reader("interface").has("joint_material"))
      throw top.section_reader("interface")
          .error("joint_material",
                 "static stages hold the ties as springs to fixed ground and do not follow a "
                 "frictional interface: expected no `interface.joint_material` (a linear "
                 "interface) with the static stage " +
                     items[i].key_path());
  }
}

// ---- Boundaries -----------------------------------------------------------------------------

/// One `boundaries[i]` item. Only what the text can tell is checked here (types, ranges, one
/// selector, block and edge indices); which edges a line or `outer` selects, and whether an edge
/// is outer at all, is for the engine, which sees the geometry.
dda::BoundaryDescription read_boundary(const MapReader& r, const dda::ModelDescription& model)
{
  dda::BoundaryDescription b;
  b.origin = r.key_path();
  const std::string type = r.choice("type");
  b.type = type == "vb1"       ? dda::BoundaryType::vb1
           : type == "vb2"     ? dda::BoundaryType::vb2
           : type == "dashpot" ? dda::BoundaryType::dashpot
                               : dda::BoundaryType::free;
  b.impedance = r.choice("impedance") == "effective" ? dda::ImpedanceKind::effective
                                                     : dda::ImpedanceKind::textbook;
  b.a_n = r.number("a_n");
  b.a_t = r.number("a_t");
  b.outer = r.boolean("outer");
  if (r.has("input"))
  {
    if (b.type == dda::BoundaryType::free)
      throw r.error("input", "an incident wave enters through the dashpots of a viscous "
                             "boundary: expected `type: vb1`, `vb2` or `dashpot`");
    const MapReader in = r.section_reader("input");
    b.has_input = true;
    b.input.type =
        in.choice("type") == "p" ? dda::BoundaryInput::Type::p : dda::BoundaryInput::Type::sv;
    b.input.velocity = read_time_function(in, "velocity");
  }

  std::vector<std::string> selectors;
  if (r.has("edges"))
    selectors.push_back("'edges'");
  if (r.has("on_line"))
    selectors.push_back("'on_line'");
  if (b.outer)
    selectors.push_back("'outer: true'");
  if (selectors.size() != 1)
    throw r.ctx().locator.error(
        r.yaml(), r.key_path(), "",
        (selectors.empty() ? std::string("no edges selected")
                           : "more than one selector (" + join(selectors, ", ") + ")") +
            ": expected exactly one of 'edges: [[block, edge], ...]', 'on_line: {point: [x, y], "
            "direction: [dx, dy]}' or 'outer: true'. Allowed keys here: " +
            join(r.ctx().schema.section("boundaries[i]").key_names(), ", "));

  if (r.has("edges"))
  {
    const std::vector<std::array<long long, 2>> edges = r.integer_pair_list("edges");
    const std::size_t n_blocks = model.blocks.size();
    for (std::size_t i = 0; i < edges.size(); ++i)
    {
      const auto block = static_cast<std::size_t>(edges[i][0]);
      const auto edge = static_cast<std::size_t>(edges[i][1]);
      if (block >= n_blocks)
        throw r.item_error("edges", i,
                           "block index " + std::to_string(block) +
                               " is out of range: expected 0 to " + std::to_string(n_blocks - 1) +
                               " (the " + std::to_string(n_blocks) +
                               " blocks of the scene, grid cells counted one by one)");
      const std::size_t n_edges = model.blocks[block].vertices.size();
      if (edge >= n_edges)
        throw r.item_error("edges", i,
                           "edge index " + std::to_string(edge) + " is out of range: block " +
                               std::to_string(block) + " (" + model.blocks[block].origin +
                               ") has " + std::to_string(n_edges) + " edges, expected 0 to " +
                               std::to_string(n_edges - 1));
      const std::pair<std::size_t, std::size_t> e(block, edge);
      const auto previous = std::find(b.edges.begin(), b.edges.end(), e);
      if (previous != b.edges.end())
        throw r.item_error("edges", i,
                           "duplicate edge (also edges[" +
                               std::to_string(previous - b.edges.begin()) +
                               "]): expected each edge once");
      b.edges.push_back(e);
    }
  }
  if (r.has("on_line"))
  {
    const MapReader line = r.section_reader("on_line");
    b.on_line = true;
    b.line_point = line.vector2("point");
    const Vector2 direction = line.vector2("direction");
    const double scale = direction.cwiseAbs().maxCoeff();
    if (scale == 0.0)
      throw line.error("direction", "expected a non-zero direction [dx, dy]");
    b.line_direction = (direction / scale).normalized(); // a unit vector
  }
  return b;
}

// ---- Overrides ------------------------------------------------------------------------------

/// Sets the value of one --set override in the YAML tree; returns where it went.
AppliedOverride apply_override(YAML::Node& root, const Override& o)
{
  const std::string argument = o.path + "=" + o.value;
  const std::string where = command_line_location(argument);
  YAML::Node value;
  try
  {
    value = YAML::Load(o.value);
  }
  catch (const YAML::Exception& e)
  {
    throw InputError::at(where, 0, "", "", "cannot parse the value as YAML: " + e.msg);
  }

  const std::vector<std::string> components = split(o.path, '.');
  YAML::Node current = root;
  std::string key_path;
  for (std::size_t i = 0; i < components.size(); ++i)
  {
    const std::string& c = components[i];
    const bool last = i + 1 == components.size();
    if (c.empty())
      throw InputError::at(where, 0, "", "", "empty key in the path '" + o.path + "'");
    if (current.IsSequence())
    {
      const bool digits = c.find_first_not_of("0123456789") == std::string::npos;
      const std::size_t index = digits && c.size() < 10 ? std::stoul(c) : current.size();
      if (!digits || index >= current.size())
        throw InputError::at(where, 0, key_path, "",
                             "'" + c + "' is not an index of this list of " +
                                 std::to_string(current.size()) + " item(s)" +
                                 (current.size() == 0
                                      ? std::string()
                                      : ": expected 0 to " + std::to_string(current.size() - 1)));
      key_path += "[" + c + "]";
      if (last)
        current[index] = value;
      else
      {
        YAML::Node next = current[index];
        current.reset(next);
      }
    }
    else if (!current.IsDefined() || current.IsMap() || current.IsNull())
    {
      key_path += (key_path.empty() ? "" : ".") + c;
      if (last)
        current[c] = value;
      else
      {
        YAML::Node next = current[c];
        current.reset(next);
      }
    }
    else
      throw InputError::at(where, 0, key_path, yaml_text(current),
                           "cannot set '" + c +
                               "' inside a single value: expected a map or a "
                               "list here");
  }
  return {key_path, argument};
}

YAML::Node load_yaml(const std::string& file)
{
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw InputError::at(file, 0, "", "",
                         std::filesystem::exists(file, ec) ? "the scene file is not a regular file"
                                                           : "cannot open the scene file: no "
                                                             "such file");
  std::ifstream in(file);
  if (!in)
    throw InputError::at(file, 0, "", "", "cannot open the scene file");
  try
  {
    return YAML::Load(in);
  }
  catch (const YAML::ParserException& e)
  {
    throw InputError::at(file, e.mark.is_null() ? 0 : e.mark.line + 1, "", "",
                         "YAML syntax error: " + e.msg);
  }
}

// ---- The scene ------------------------------------------------------------------------------

Scene read_validated_scene(const std::string& file, const YAML::Node& root, const Context& context)
{
  if (!root.IsMap())
    throw context.locator.error(root, "", yaml_text(root),
                                "expected a map of scene sections (materials, blocks, time, ...)");
  const MapReader top(root, context.schema.section(SceneSchema::top_level), "", context);
  Scene scene;
  scene.file = file;
  scene.name = top.has("name") ? top.string("name") : std::filesystem::path(file).stem().string();
  scene.description = top.string("description");
  dda::ModelDescription& model = scene.model;

  const MapReader analysis = top.section_reader("analysis");
  model.plane_mode =
      analysis.choice("plane") == "strain" ? dda::PlaneMode::strain : dda::PlaneMode::stress;
  model.geometry = analysis.choice("geometry") == "small_displacement"
                       ? dda::GeometryMode::small_displacement
                       : dda::GeometryMode::updated;

  std::vector<std::string> material_names;
  for (const auto& [name, r] : top.section_map("materials"))
  {
    dda::Material m;
    m.name = name;
    m.density = r.number("density");
    m.youngs_modulus = r.number("youngs_modulus");
    m.poisson_ratio = r.number("poisson_ratio");
    model.materials.push_back(m);
    material_names.push_back(name);
  }
  if (model.materials.empty())
    throw top.error("materials", "expected at least one material");

  std::vector<std::string> joint_names;
  for (const auto& [name, r] : top.section_map("joint_materials"))
  {
    dda::JointMaterial j;
    j.name = name;
    j.normal_stiffness = r.number("normal_stiffness");
    j.shear_ratio = r.number("shear_ratio");
    j.friction_angle = r.number("friction_angle");
    j.cohesion = r.number("cohesion");
    j.tensile_strength = r.number("tensile_strength");
    j.bonded = r.boolean("bonded");
    model.joint_materials.push_back(j);
    joint_names.push_back(name);
  }

  const MapReader joints = top.section_reader("joints");
  if (joints.has("default"))
    model.default_joint_material =
        find_name(joints, "default", joints.string("default"), joint_names, "joint material");
  for (const MapReader& r : joints.section_list("pairs"))
  {
    const std::array<std::string, 2> pair = r.name_pair("materials");
    dda::JointAssignment a;
    a.material_a = find_name(r, "materials", pair[0], material_names, "material");
    a.material_b = find_name(r, "materials", pair[1], material_names, "material");
    a.joint_material = find_name(r, "joint", r.string("joint"), joint_names, "joint material");
    model.joint_assignments.push_back(a);
  }

  if (top.has("far_field"))
    scene.far_field = read_far_field(top.section_reader("far_field"), model, material_names);

  std::vector<BlockSource> sources;
  read_blocks(top, material_names, joint_names, model, sources, scene.rock_mass);
  check_overlaps(model, sources, context.locator);
  if (top.has("in_situ_stress"))
  {
    const MapReader r = top.section_reader("in_situ_stress");
    model.in_situ_stress.stress = r.voigt("stress");
    model.in_situ_stress.gradient = r.voigt("stress_gradient");
    model.in_situ_stress.reference_y = r.number("reference_y");
    for (std::size_t i = 0; i < model.blocks.size(); ++i)
      if (!sources[i].initial_stress)
        model.blocks[i].initial_stress =
            model.in_situ_stress.at(dda::polygon_moments(model.blocks[i].vertices).centroid);
  }

  std::vector<Box> boxes;
  double tol = 0.0;
  if (!model.blocks.empty())
  {
    Box all(model.blocks.front().vertices);
    for (const dda::BlockDescription& b : model.blocks)
    {
      boxes.emplace_back(b.vertices);
      all.lower = all.lower.cwiseMin(boxes.back().lower);
      all.upper = all.upper.cwiseMax(boxes.back().upper);
    }
    tol = 1e-9 * (all.upper - all.lower).norm();
  }

  for (const MapReader& r : top.section_list("point_loads"))
  {
    dda::PointLoad load;
    load.point = r.vector2("point");
    load.force = r.vector2("force");
    load.time_function = read_time_function(r, "time_function");
    load.origin = r.key_path();
    check_point_in_blocks(r, "point", load.point, model, boxes, tol);
    model.point_loads.push_back(load);
  }

  for (const MapReader& r : top.section_list("fixed_points"))
  {
    dda::FixedPoint f;
    f.point = r.vector2("point");
    f.stiffness = r.number("stiffness");
    f.displacement_x = read_time_function(r, "displacement_x");
    f.displacement_y = read_time_function(r, "displacement_y");
    f.origin = r.key_path();
    check_point_in_blocks(r, "point", f.point, model, boxes, tol);
    model.fixed_points.push_back(f);
  }

  model.gravity = top.vector2("gravity");
  if (scene.far_field && scene.far_field->static_stage.enabled &&
      !top.section_reader("far_field").section_reader("static_stage").has("gravity"))
    scene.far_field->static_stage.gravity = {model.gravity.x(), model.gravity.y()};

  std::map<std::string, std::string> monitor_paths;
  for (const MapReader& r : top.section_list("monitors"))
  {
    dda::Monitor m;
    m.name = r.string("name");
    if (trim(m.name).empty())
      throw r.error("name", "expected a non-empty name");
    const auto [it, inserted] = monitor_paths.emplace(m.name, r.key_path());
    if (!inserted)
      throw r.error("name", "duplicate monitor name (also used by " + it->second +
                                "): expected unique names");
    m.point = r.vector2("point");
    // In a coupled scene a monitor belongs to the block it lies in, else to the far field.
    const bool in_blocks = !model.blocks.empty() && in_some_block(m.point, model, boxes, tol);
    if (scene.far_field && !in_blocks)
    {
      if (scene.far_field->mesh_file.file.empty())
        check_point_in_far_field(r, "point", m.point, *scene.far_field);
      scene.far_field->monitors.push_back({m.name, {m.point.x(), m.point.y()}});
      continue;
    }
    check_point_in_blocks(r, "point", m.point, model, boxes, tol);
    model.monitors.push_back(m);
  }

  for (const MapReader& r : top.section_list("boundaries"))
    model.boundaries.push_back(read_boundary(r, model));

  if (!top.has("time"))
    throw top.error("time", "expected a `time` section (dt, end_time) or a `tunnel`");
  const MapReader time = top.section_reader("time");
  model.time.dt = time.number("dt");
  model.time.end_time = time.number("end_time");
  if (model.time.end_time < model.time.dt)
    throw time.error("end_time",
                     "expected end_time >= dt = " + format_number(model.time.dt) + " s");
  for (const dda::Integrator i : {dda::Integrator::generalized_alpha, dda::Integrator::bathe,
                                  dda::Integrator::dda, dda::Integrator::newmark_trapezoidal})
    if (time.choice("integrator") == dda::integrator_name(i))
      model.time.integrator = i;
  model.time.spectral_radius = time.number("spectral_radius");
  model.time.control =
      time.choice("control") == "fixed" ? dda::TimeControl::fixed : dda::TimeControl::adaptive;
  if (time.has("dt_min"))
  {
    model.time.dt_min = time.number("dt_min");
    if (model.time.dt_min > model.time.dt)
      throw time.error("dt_min", "expected dt_min <= dt = " + format_number(model.time.dt) + " s");
  }
  model.time.cut_factor = time.number("cut_factor");
  model.time.growth_factor = time.number("growth_factor");
  model.time.reversal_tolerance = time.number("reversal_tolerance");

  const MapReader contacts = top.section_reader("contacts");
  model.contacts.max_displacement_ratio = contacts.number("max_displacement_ratio");
  if (contacts.has("search_distance"))
    model.contacts.search_distance = contacts.number("search_distance");
  if (contacts.has("max_penetration"))
    model.contacts.max_penetration = contacts.number("max_penetration");
  model.contacts.max_open_close_iterations =
      static_cast<unsigned>(contacts.integer("max_open_close_iterations"));
  model.contacts.angle_tolerance_deg = contacts.number("angle_tolerance");
  model.contacts.max_penalty_factor = contacts.number("max_penalty_factor");
  model.contacts.flip_force_ratio = contacts.number("flip_force_ratio");

  for (const MapReader& r : top.section_list("stages"))
  {
    if (!model.stages.empty() && model.stages.back().settle)
      throw r.error("mode", "a stage after the settle stage " + model.stages.back().name +
                                ", whose end is not known before the run: expected the settle "
                                "stage last");
    dda::Stage stage;
    stage.name = r.string("name");
    stage.mode =
        r.choice("mode") == "static" ? dda::StageMode::static_equilibrium : dda::StageMode::dynamic;
    if (r.choice("mode") == "settle")
      stage.settle = read_settle_criterion(r);
    stage.dt = r.has("dt") ? r.number("dt") : model.time.dt;
    stage.end_time = r.has("end_time") ? r.number("end_time") : model.time.end_time;
    stage.max_steps = static_cast<std::size_t>(r.integer("max_steps"));
    stage.tolerance = r.number("tolerance");
    stage.release =
        r.choice("release") == "remove" ? dda::ReleaseAction::remove : dda::ReleaseAction::fall;
    if (stage.mode == dda::StageMode::dynamic && !stage.settle)
    {
      if (r.has("dt"))
        throw r.error("dt", "a dynamic stage steps with time.dt: expected no `dt` here");
      const double start = model.stages.empty() ? 0.0
                                                : [&]
      {
        for (auto it = model.stages.rbegin(); it != model.stages.rend(); ++it)
          if (it->mode == dda::StageMode::dynamic)
            return it->end_time;
        return 0.0;
      }();
      if (stage.end_time <= start)
        throw r.error("end_time", "expected a time after the previous dynamic stage's end (" +
                                      format_number(start) + " s)");
    }
    model.stages.push_back(stage);
  }
  if (scene.far_field && !model.blocks.empty() && !model.stages.empty())
    check_coupled_stages(top, model);
  else if (scene.far_field && !model.stages.empty())
    throw top.error("stages", "stages apply to block models: expected no `stages` in a "
                              "far-field-only scene (its own static stage is "
                              "`far_field.static_stage`)");
  if (scene.far_field)
  {
    // Blocks tied to a far field keep their integrator (Bathe's by default: frictional sliding
    // right); the far field takes the trapezoidal rule for each of the blocks' steps (each half
    // of a composite step), or DDA's scheme with the blocks' (coupling/README.md).
    scene.far_field->dt = model.time.dt;
    scene.far_field->end_time = model.time.end_time;
    const MapReader f = top.section_reader("far_field");
    const bool dda_scheme = f.has("integrator") ? f.choice("integrator") == "dda"
                                                : model.time.integrator == dda::Integrator::dda;
    scene.far_field->integrator =
        dda_scheme ? fem::Integrator::dda : fem::Integrator::newmark_trapezoidal;
  }
  if (scene.coupled())
  {
    scene.interface = read_interface(top.section_reader("interface"), model, joint_names);
    if (top.has("in_situ_stress") && top.section_reader("interface").has("joint_material"))
      throw top.section_reader("interface")
          .error("joint_material",
                 "a frictional interface cannot carry the in-situ stress's preloads "
                 "(Mohr-Coulomb would see only the dynamic increment of the tie forces): "
                 "expected no `interface.joint_material` (a linear interface) with "
                 "`in_situ_stress`");
    // The far field carries only the dynamic increment; gravity and the in-situ stress reach
    // the blocks as the ties' preloads (top-level `in_situ_stress`, coupling/README.md).
    if (scene.far_field->static_stage.enabled)
      throw top.section_reader("far_field")
          .error("static_stage",
                 "blocks tied to a far field: the far field carries only the dynamic increment "
                 "(no gravity, no in-situ stress, at rest when the dynamic stage starts), and "
                 "the in-situ stress reaches the blocks through the ties' preloads: expected a "
                 "top-level `in_situ_stress` section and `stages` instead");
  }

  const MapReader solver = top.section_reader("solver");
  const std::string solver_type = solver.choice("type");
  model.solver = solver_type == "amesos_klu"   ? dda::SolverKind::amesos_klu
                 : solver_type == "eigen_ldlt" ? dda::SolverKind::eigen_ldlt
                                               : dda::SolverKind::block_ldlt;

  const MapReader output = top.section_reader("output");
  scene.output.directory = output.string("directory");
  if (trim(scene.output.directory).empty())
    throw output.error("directory", "expected a non-empty directory name");
  scene.output.interval = output.number("interval");
  scene.output.history_every = static_cast<std::size_t>(output.integer("history_every"));
  const std::string compression = output.choice("vtu_compression");
  scene.output.vtu_compression = compression == "none" ? fem::VtuCompression::none
                                 : compression == "best_compression"
                                     ? fem::VtuCompression::best_compression
                                     : fem::VtuCompression::best_speed;
  return scene;
}

// ---- Reference ------------------------------------------------------------------------------

} // namespace

Override parse_override(const std::string& argument)
{
  const auto equals = argument.find('=');
  if (equals == std::string::npos || trim(argument.substr(0, equals)).empty())
    throw InputError::at(command_line_location(argument), 0, "", "",
                         "expected path.to.key=value, e.g. --set time.dt=1e-4 or --set "
                         "blocks.0.material=granite");
  return {trim(argument.substr(0, equals)), argument.substr(equals + 1)};
}

Scene read_scene(const std::string& file, const std::vector<Override>& overrides)
{
  const SceneSchema schema;
  Locator locator(file);
  YAML::Node root = load_yaml(file);
  try
  {
    for (const Override& o : overrides)
      locator.add_override(apply_override(root, o));
    const Context context{schema, locator, std::filesystem::path(file).parent_path()};
    std::optional<TunnelPlan> tunnel;
    if (root.IsMap() && child(root, "tunnel").IsDefined())
      tunnel = expand_tunnel(root, context);
    Scene scene = read_validated_scene(file, root, context);
    scene.tunnel = std::move(tunnel);
    if (scene.tunnel)
      scene.expanded_yaml = YAML::Dump(root);
    return scene;
  }
  catch (const YAML::Exception& e)
  {
    // Anything the YAML library objects to beyond syntax (aliases, conversions).
    throw InputError::at(file, e.mark.is_null() ? 0 : e.mark.line + 1, "", "",
                         "cannot read the YAML tree: " + e.msg);
  }
}

} // namespace ddafem
