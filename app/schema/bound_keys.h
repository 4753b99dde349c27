// Scene keys declared once (deal.II's ParameterAcceptor, step-62): each key of a section is
// declared beside the field of the library's struct it fills, with its unit, range and meaning.
// Its type follows from the field's type and its default is the field's own initialiser, read
// off a default-constructed struct, so neither is written a second time. The section's schema
// takes keys() and its reader fills the struct by one call to fill().
#pragma once

#include "app/scene/map_reader.h"
#include "app/schema/schema_key_builder.h"
#include "common/enum_names.h"
#include "dda/types.h"

#include <array>
#include <cstddef>
#include <deque>
#include <functional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace ddafem::schema
{
/// The shortest text that YAML reads back as exactly `v`: "1.2", "1e-6", "100", "0.3".
std::string shortest_number_text(double v);

template <typename Target>
class BoundKeys
{
public:
  /// Declares the key `name` that fills `target.*member`. The default is the member's
  /// initialiser; `required()` or `default_note(...)` on the returned builder says there is none
  /// (a key with a note is then only read when the scene gives it: the field keeps its
  /// initialiser, which the library reads as the note says).
  template <typename Field>
  KeyBuilder& field(std::string name, Field Target::*member)
  {
    return bind(std::move(name), Target{}.*member,
                [member](Target& target) -> Field& { return target.*member; });
  }

  /// Declares the key `name` that fills `(target.*part).*member`, a field of a part of the
  /// struct (e.g. the rock mass's sliver criterion), as field() does.
  template <typename Part, typename Field>
  KeyBuilder& field(std::string name, Part Target::*part, Field Part::*member)
  {
    return bind(std::move(name), Target{}.*part.*member,
                [part, member](Target& target) -> Field& { return (target.*part).*member; });
  }

  /// A key the section's reader reads itself (a nested section, a name to look up): listed in
  /// the schema in its place, skipped by fill().
  void add(Key key)
  {
    builders.emplace_back(std::move(key));
    fillers.emplace_back();
  }

  /// The keys in declaration order, as the schema section lists them.
  std::vector<Key> keys() const
  {
    std::vector<Key> all;
    for (const KeyBuilder& b : builders)
      all.push_back(declared(b));
    return all;
  }

  /// Every bound key the map gives, or that has a default, written into `target`; the map has
  /// been checked against the keys' section (MapReader), so unknown keys are already refused.
  void fill(const scene_reading::MapReader& r, Target& target) const
  {
    for (std::size_t i = 0; i < builders.size(); ++i)
    {
      const Key k = declared(builders[i]);
      if (fillers[i] && (r.has(k.name) || !k.default_yaml.empty()))
        fillers[i](r, target);
    }
  }

private:
  std::deque<KeyBuilder> builders;
  std::vector<std::function<void(const scene_reading::MapReader&, Target&)>> fillers;

  /// The key `name` of the type of `initial`, its default, and its filler writing into the
  /// field `access` returns.
  template <typename Field, typename Access>
  KeyBuilder& bind(std::string name, const Field& initial, Access access)
  {
    builders.emplace_back(name, value_type<Field>());
    KeyBuilder& builder = builders.back();
    if constexpr (std::is_enum_v<Field>)
      builder.choices(names_of<Field>()).default_yaml(name_of(initial));
    else
      builder.default_yaml(default_text(initial));
    fillers.push_back([name, access](const scene_reading::MapReader& r, Target& target)
                      { access(target) = read<Field>(r, name); });
    return builder;
  }

  /// A required key or one whose default is a note has no literal default.
  static Key declared(const KeyBuilder& builder)
  {
    Key k = builder;
    if (k.required || !k.default_note.empty())
      k.default_yaml.clear();
    return k;
  }

  template <typename Field>
  static constexpr ValueType value_type()
  {
    if constexpr (std::is_same_v<Field, bool>)
      return ValueType::boolean;
    else if constexpr (std::is_enum_v<Field>)
      return ValueType::choice;
    else if constexpr (std::is_integral_v<Field>)
      return ValueType::integer;
    else if constexpr (std::is_floating_point_v<Field>)
      return ValueType::number;
    else if constexpr (std::is_same_v<Field, std::array<double, 2>> ||
                       std::is_same_v<Field, dda::Vector2>)
      return ValueType::vector2;
    else if constexpr (std::is_same_v<Field, std::array<double, 3>> ||
                       std::is_same_v<Field, dda::Voigt>)
      return ValueType::voigt;
    else
    {
      static_assert(std::is_same_v<Field, std::string>, "a field of a type keys cannot fill");
      return ValueType::string;
    }
  }

  template <typename Field>
  static std::string default_text(const Field& value)
  {
    if constexpr (std::is_same_v<Field, bool>)
      return value ? "true" : "false";
    else if constexpr (std::is_integral_v<Field>)
      return std::to_string(value);
    else if constexpr (std::is_floating_point_v<Field>)
      return shortest_number_text(value);
    else if constexpr (std::is_same_v<Field, std::string>)
      return value.empty() ? "''" : value; // YAML's empty string
    else                                   // [x, y] or [sxx, syy, sxy]
    {
      std::string text = "[";
      for (std::size_t i = 0; i < static_cast<std::size_t>(value.size()); ++i)
        text += (i > 0 ? ", " : "") + shortest_number_text(value[i]);
      return text + "]";
    }
  }

  template <typename Field>
  static Field read(const scene_reading::MapReader& r, const std::string& name)
  {
    if constexpr (std::is_same_v<Field, bool>)
      return r.boolean(name);
    else if constexpr (std::is_enum_v<Field>)
      return r.choice_of<Field>(name);
    else if constexpr (std::is_integral_v<Field>)
    {
      const long long value = r.integer(name);
      if (std::is_unsigned_v<Field> && value < 0)
        throw r.error(name, "expected an integer >= 0");
      return static_cast<Field>(value);
    }
    else if constexpr (std::is_floating_point_v<Field>)
      return r.number(name);
    else if constexpr (std::is_same_v<Field, std::array<double, 2>>)
    {
      const dda::Vector2 v = r.vector2(name);
      return Field{{v.x(), v.y()}};
    }
    else if constexpr (std::is_same_v<Field, dda::Vector2>)
      return r.vector2(name);
    else if constexpr (std::is_same_v<Field, dda::Voigt>)
      return r.voigt(name);
    else if constexpr (std::is_same_v<Field, std::array<double, 3>>)
    {
      const dda::Voigt v = r.voigt(name);
      return Field{{v[0], v[1], v[2]}};
    }
    else
      return r.string(name);
  }
};

} // namespace ddafem::schema
