// The generic part of the scene reader: a YAML map checked against a schema section, errors that
// name the file and line (or the --set argument), --set overrides and loading the file.
#pragma once

#include "app/scene/scene.h"
#include "app/scene/scene_text.h"
#include "app/schema/scene_schema.h"
#include "common/enum_names.h"
#include "common/input_error.h"
#include "common/resource_limits.h"

#include <yaml-cpp/yaml.h>

#include <array>
#include <cstddef>
#include <filesystem>
#include <istream>
#include <string>
#include <utility>
#include <vector>

namespace ddafem::scene_reading
{
using dda::Point;
using dda::Vector2;
using dda::Voigt;
using schema::Key;
using schema::SceneSchema;
using schema::Section;
using schema::ValueType;

/// "a number > 0 [kg/m^3]", "one of 'stress', 'strain'", ...
std::string expected_text(const Key& key, const SceneSchema& schema);

/// A --set override as applied: the key path it set (in message form, "blocks[0].material") and
/// the argument as typed.
struct AppliedOverride
{
  std::string key_path;
  std::string argument;
};

/// "command line --set ARGUMENT": where a problem in an override is.
std::string command_line_location(const std::string& argument);

/// Turns problems at YAML nodes into InputErrors naming the file and line, or the --set argument
/// that put the value there.
class Locator
{
public:
  explicit Locator(std::string file_) : file(std::move(file_)) {}

  void add_override(AppliedOverride o) { overrides.push_back(std::move(o)); }
  InputError error(const YAML::Node& node, const std::string& key_path, const std::string& value,
                   const std::string& expected) const;

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
  /// The memory a scene may take: readers refuse one estimated beyond it before building it.
  ResourceLimits limits;
};

// ---- Reading one map against its schema section ---------------------------------------------

/// A YAML map checked against a schema section: no unknown or duplicate keys, all required keys
/// present. Its getters convert and range-check one key each, using the schema's default when the
/// key is absent; asking for a key that is not in the section is a programming error.
class MapReader
{
public:
  MapReader(const YAML::Node& node_, const Section& section_, std::string path_,
            const Context& context_);

  bool has(const std::string& name) const { return child(node, name).IsDefined(); }

  const std::string& key_path() const { return path; }
  const YAML::Node& yaml() const { return node; }
  const Context& ctx() const { return *context; }

  /// Path of a key of this map: "materials.rock.density".
  std::string path_of(const std::string& name) const;

  /// An error about key `name` (at its line, or the map's if it is absent).
  InputError error(const std::string& name, const std::string& expected) const;

  double number(const std::string& name) const;

  long long integer(const std::string& name) const;

  bool boolean(const std::string& name) const;

  std::string string(const std::string& name) const;

  std::string choice(const std::string& name) const;

  /// The enumerator a choice names: the key's choices are names of E's table
  /// (common/enum_names.h), so choice() has already refused any other name.
  template <typename E>
  E choice_of(const std::string& name) const
  {
    return *value_of<E>(choice(name));
  }

  Vector2 vector2(const std::string& name) const;

  Voigt voigt(const std::string& name) const;

  std::array<long long, 2> integer_pair(const std::string& name) const;

  /// A non-empty list of pairs of integers ([[block, edge], ...]).
  std::vector<std::array<long long, 2>> integer_pair_list(const std::string& name) const;

  /// An error about item `i` of the list at key `name` (at the item's line).
  InputError item_error(const std::string& name, std::size_t i, const std::string& expected) const;

  std::array<std::string, 2> name_pair(const std::string& name) const;

  /// A list of pairs of numbers ([[x, y], ...] or [[t, value], ...]).
  std::vector<std::array<double, 2>> pair_list(const std::string& name) const;

  MapReader section_reader(const std::string& name) const;

  /// Entries of a map of named maps, in file order.
  std::vector<std::pair<std::string, MapReader>> section_map(const std::string& name) const;

  std::vector<MapReader> section_list(const std::string& name) const;

  /// The time function's map, checked against the section its `type` selects.
  MapReader time_function_reader(const std::string& name) const;

private:
  /// A key's value node: the user's, or the schema default parsed as YAML.
  struct Value
  {
    YAML::Node node;
    std::string path;
    const Key* key = nullptr;
  };

  Value value(const std::string& name, ValueType type) const;

  /// Like value(), for optional sections without a YAML default: absent means empty.
  Value value_or_empty(const std::string& name, ValueType type) const;

  InputError mismatch(const Value& v) const;

  std::vector<double> numbers(const Value& v, std::size_t n) const;

  YAML::Node node;
  const Section* section;
  std::string path;
  const Context* context;
};

/// Index of `name` in `names`, or an error at key `key` of `r` listing the defined names.
std::size_t find_name(const MapReader& r, const std::string& key, const std::string& name,
                      const std::vector<std::string>& names, const std::string& what);

/// Sets the value of one --set override in the YAML tree; returns where it went.
AppliedOverride apply_override(YAML::Node& root, const Override& o);

/// The scene file's YAML tree; a missing file or a syntax error throws InputError.
YAML::Node load_yaml(const std::string& file);
/// The YAML tree of a scene's text from `in`; a syntax error throws InputError at `file`.
YAML::Node parse_yaml(std::istream& in, const std::string& file);

} // namespace ddafem::scene_reading
