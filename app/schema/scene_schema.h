// The scene file format as data: every section and key with its type, unit, default, allowed
// values and meaning. The scene reader validates against it and the Markdown reference is
// rendered from it, so the two cannot drift apart.
#pragma once

#include "common/enum_names.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace ddafem::schema
{
/// What a key's value looks like in YAML.
enum class ValueType
{
  string,            ///< a scalar taken as text
  number,            ///< a real number
  integer,           ///< a whole number
  boolean,           ///< true or false
  choice,            ///< one of Key::choices
  vector2,           ///< [x, y] of numbers
  integer_pair,      ///< [nx, ny] of whole numbers
  integer_pair_list, ///< [[i, j], ...] of whole numbers
  name_pair,         ///< [A, B] of names
  voigt,             ///< [xx, yy, xy] of numbers
  point_list,        ///< [[x, y], ...]
  table,             ///< [[t, v], ...] with strictly increasing t
  section,           ///< a map described by the Section named Key::section
  section_map,       ///< a map from user-chosen names to maps described by Key::section
  section_list,      ///< a list of maps described by Key::section
  time_function      ///< a map whose `type` selects one of the time-function sections
};

/// Name of a value type as the reference and messages show it ("number", "[x, y]", ...).
constexpr std::array<EnumName<ValueType>, 16> enum_names(ValueType)
{
  return {{{ValueType::string, "string"},
           {ValueType::number, "number"},
           {ValueType::integer, "integer"},
           {ValueType::boolean, "boolean"},
           {ValueType::choice, "choice"},
           {ValueType::vector2, "[x, y]"},
           {ValueType::integer_pair, "[integer, integer]"},
           {ValueType::integer_pair_list, "list of [integer, integer]"},
           {ValueType::name_pair, "[name, name]"},
           {ValueType::voigt, "[xx, yy, xy]"},
           {ValueType::point_list, "list of [x, y]"},
           {ValueType::table, "list of [t, value]"},
           {ValueType::section, "map"},
           {ValueType::section_map, "map of named maps"},
           {ValueType::section_list, "list of maps"},
           {ValueType::time_function, "time function"}}};
}

/// The kinds of time function a scene can give (`type` of a time function's map); csv is a
/// table read from a file.
enum class TimeFunctionType
{
  constant,
  sine_pulse,
  table,
  csv,
  record
};

constexpr std::array<EnumName<TimeFunctionType>, 5> enum_names(TimeFunctionType)
{
  return {{{TimeFunctionType::constant, "constant"},
           {TimeFunctionType::sine_pulse, "sine_pulse"},
           {TimeFunctionType::table, "table"},
           {TimeFunctionType::csv, "csv"},
           {TimeFunctionType::record, "record"}}};
}

/// The file formats of a `record` time function.
enum class RecordFormat
{
  peer, ///< PEER NGA: four header lines (quantity and units, NPTS and DT), then the samples
  table ///< numbers in rows, separated by commas or blanks: a time column, or a fixed dt
};

constexpr std::array<EnumName<RecordFormat>, 2> enum_names(RecordFormat)
{
  return {{{RecordFormat::peer, "peer"}, {RecordFormat::table, "table"}}};
}

/// The units of a record's samples, which also say what they measure.
enum class RecordUnit
{
  g,
  m_per_s2,
  cm_per_s2,
  m_per_s,
  cm_per_s,
  m,
  cm
};

constexpr std::array<EnumName<RecordUnit>, 7> enum_names(RecordUnit)
{
  return {{{RecordUnit::g, "g"},
           {RecordUnit::m_per_s2, "m/s^2"},
           {RecordUnit::cm_per_s2, "cm/s^2"},
           {RecordUnit::m_per_s, "m/s"},
           {RecordUnit::cm_per_s, "cm/s"},
           {RecordUnit::m, "m"},
           {RecordUnit::cm, "cm"}}};
}

/// A record's baseline correction (common/ground_motion.h correct_baseline).
enum class BaselineMethod
{
  polynomial,
  none
};

constexpr std::array<EnumName<BaselineMethod>, 2> enum_names(BaselineMethod)
{
  return {{{BaselineMethod::polynomial, "polynomial"}, {BaselineMethod::none, "none"}}};
}

/// Allowed interval of a number (or of each component of a vector of numbers).
struct Range
{
  std::optional<double> min;
  bool min_inclusive = true;
  std::optional<double> max;
  bool max_inclusive = true;

  bool contains(double value) const;
  /// "> 0", ">= 1", "[0, 0.5)", or empty for an unbounded range.
  std::string describe() const;
};

/// One key of a section.
struct Key
{
  std::string name;
  ValueType type = ValueType::string;
  std::string unit; ///< SI unit, e.g. "Pa", "kg/m^3"; empty if dimensionless
  bool required = false;
  std::string default_yaml; ///< default as YAML text, read like a user's value; empty if none
  std::string default_note; ///< default in words, when it is not a literal value
  Range range;              ///< for numbers and vectors of numbers (each component)
  std::vector<std::string> choices; ///< for ValueType::choice
  std::string section;              ///< for section, section_map, section_list: the Section's id
  std::string meaning;              ///< one line
};

/// A map of keys: the top level, a named section (`time`), an item of a list (`blocks[i]`) or
/// of a named map (`materials.<name>`).
struct Section
{
  std::string id;      ///< the path pattern shown in the reference, e.g. "materials.<name>"
  std::string meaning; ///< a short paragraph
  std::vector<Key> keys;

  /// The key named `name`, or nullptr.
  const Key* find(const std::string& name) const;
  /// The key named `name`; the caller knows it exists (asserted).
  const Key& key(const std::string& name) const;
  /// Names of all keys, in schema order.
  std::vector<std::string> key_names() const;
};

/// The whole scene format.
class SceneSchema
{
public:
  SceneSchema();

  /// Id of the top-level section.
  static constexpr const char* top_level = "(top level)";
  /// Id of the time-function section whose `type` is `type_name`: "time function: <type>".
  static std::string time_function_section(TimeFunctionType type);

  const std::vector<Section>& sections() const { return all_sections; }
  /// The section with id `id`; the caller knows it exists (asserted).
  const Section& section(const std::string& id) const;

private:
  std::vector<Section> all_sections;
};

} // namespace ddafem::schema
