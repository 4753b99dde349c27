#include "app/scene/map_reader.h"

#include <algorithm>
#include <cassert>
#include <fstream>

namespace ddafem::scene_reading
{
using schema::TimeFunctionType;

namespace
{
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

bool is_within(const std::string& path, const std::string& prefix)
{
  if (path.compare(0, prefix.size(), prefix) != 0)
    return false;
  return path.size() == prefix.size() || path[prefix.size()] == '.' || path[prefix.size()] == '[';
}
} // namespace

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
    return "a time function: a map with 'type' one of " + quoted_list(names_of<TimeFunctionType>());
  }
  return "";
}

std::string command_line_location(const std::string& argument)
{
  return "command line --set " + argument;
}

InputError Locator::error(const YAML::Node& node, const std::string& key_path,
                          const std::string& value, const std::string& expected) const
{
  // A problem at or inside an overridden key, or at a key an override changed something in.
  for (auto o = overrides.rbegin(); o != overrides.rend(); ++o)
    if (is_within(key_path, o->key_path) || (!key_path.empty() && is_within(o->key_path, key_path)))
      return InputError::at(command_line_location(o->argument), 0, key_path, value, expected);
  int line = 0;
  if (node.IsDefined() && !node.Mark().is_null())
    line = node.Mark().line + 1;
  return InputError::at(file, line, key_path, value, expected);
}

MapReader::MapReader(const YAML::Node& node_, const Section& section_, std::string path_,
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

std::string MapReader::path_of(const std::string& name) const
{
  return path.empty() ? name : path + "." + name;
}

InputError MapReader::error(const std::string& name, const std::string& expected) const
{
  const YAML::Node n = child(node, name);
  return context->locator.error(n.IsDefined() ? n : node, path_of(name), yaml_text(n), expected);
}

double MapReader::number(const std::string& name) const
{
  const Value v = value(name, ValueType::number);
  const std::optional<double> x = parse_double(v.node);
  if (!x || !v.key->range.contains(*x))
    throw mismatch(v);
  return *x;
}

long long MapReader::integer(const std::string& name) const
{
  const Value v = value(name, ValueType::integer);
  const std::optional<long long> x = parse_integer(v.node);
  if (!x || !v.key->range.contains(static_cast<double>(*x)))
    throw mismatch(v);
  return *x;
}

bool MapReader::boolean(const std::string& name) const
{
  const Value v = value(name, ValueType::boolean);
  bool b = false;
  if (!v.node.IsScalar() || !YAML::convert<bool>::decode(v.node, b))
    throw mismatch(v);
  return b;
}

std::string MapReader::string(const std::string& name) const
{
  const Value v = value(name, ValueType::string);
  if (!v.node.IsScalar())
    throw mismatch(v);
  return v.node.Scalar();
}

std::string MapReader::choice(const std::string& name) const
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

Vector2 MapReader::vector2(const std::string& name) const
{
  const Value v = value(name, ValueType::vector2);
  const std::vector<double> x = numbers(v, 2);
  return Vector2(x[0], x[1]);
}

Voigt MapReader::voigt(const std::string& name) const
{
  const Value v = value(name, ValueType::voigt);
  const std::vector<double> x = numbers(v, 3);
  return Voigt(x[0], x[1], x[2]);
}

std::array<long long, 2> MapReader::integer_pair(const std::string& name) const
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

std::vector<std::array<long long, 2>> MapReader::integer_pair_list(const std::string& name) const
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

InputError MapReader::item_error(const std::string& name, std::size_t i,
                                 const std::string& expected) const
{
  const YAML::Node list = child(node, name);
  const YAML::Node& const_list = list;
  const YAML::Node item = const_list[i];
  return context->locator.error(item, path_of(name) + "[" + std::to_string(i) + "]",
                                yaml_text(item), expected);
}

std::array<std::string, 2> MapReader::name_pair(const std::string& name) const
{
  const Value v = value(name, ValueType::name_pair);
  if (!v.node.IsSequence() || v.node.size() != 2 || !v.node[0].IsScalar() || !v.node[1].IsScalar())
    throw mismatch(v);
  return {v.node[0].Scalar(), v.node[1].Scalar()};
}

std::vector<std::array<double, 2>> MapReader::pair_list(const std::string& name) const
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

MapReader MapReader::section_reader(const std::string& name) const
{
  const Value v = value_or_empty(name, ValueType::section);
  return MapReader(v.node, context->schema.section(v.key->section), v.path, *context);
}

std::vector<std::pair<std::string, MapReader>> MapReader::section_map(const std::string& name) const
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

std::vector<MapReader> MapReader::section_list(const std::string& name) const
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

MapReader MapReader::time_function_reader(const std::string& name) const
{
  const Value v = value(name, ValueType::time_function);
  const std::vector<std::string> types = names_of<TimeFunctionType>();
  if (!v.node.IsMap())
    throw mismatch(v);
  const YAML::Node type_node = child(v.node, "type");
  if (!type_node.IsDefined())
    throw context->locator.error(v.node, v.path + ".type", "",
                                 "missing required key: expected one of " + quoted_list(types));
  const std::string type_name = type_node.IsScalar() ? type_node.Scalar() : "";
  const std::optional<TimeFunctionType> type = value_of<TimeFunctionType>(type_name);
  if (!type)
    throw context->locator.error(type_node, v.path + ".type", yaml_text(type_node),
                                 "expected one of " + quoted_list(types) +
                                     suggestion(type_name, types));
  return MapReader(v.node, context->schema.section(SceneSchema::time_function_section(*type)),
                   v.path, *context);
}

MapReader::Value MapReader::value(const std::string& name, ValueType type) const
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

MapReader::Value MapReader::value_or_empty(const std::string& name, ValueType type) const
{
  const Key& k = section->key(name);
  const YAML::Node n = child(node, name);
  if (n.IsDefined() || !k.default_yaml.empty())
    return value(name, type);
  return {YAML::Node(), path_of(name), &k};
}

InputError MapReader::mismatch(const Value& v) const
{
  return context->locator.error(v.node, v.path, yaml_text(v.node),
                                "expected " + expected_text(*v.key, context->schema));
}

std::vector<double> MapReader::numbers(const Value& v, std::size_t n) const
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
  return parse_yaml(in, file);
}

YAML::Node parse_yaml(std::istream& in, const std::string& file)
{
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

} // namespace ddafem::scene_reading
