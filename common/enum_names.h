// Names of enumerators as scene files, summary.json and messages spell them, written once per
// enum: next to the enum (or in its library's names header) one table
//   constexpr std::array<EnumName<E>, n> enum_names(E) { return {{{E::a, "a"}, ...}}; }
// which name_of, value_of and names_of find by argument-dependent lookup. The table's order is
// the order the schema lists the choices in (docs/scene_reference.md).
#pragma once

#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ddafem
{
/// One enumerator and its name.
template <typename E>
struct EnumName
{
  E value;
  const char* name;
};

/// The name of `value` in its enum's table; "" for a value the table lacks.
template <typename E>
const char* name_of(const E value)
{
  for (const EnumName<E>& entry : enum_names(E{}))
    if (entry.value == value)
      return entry.name;
  return "";
}

/// The enumerator named `name`, nullopt for a name not in the table.
template <typename E>
std::optional<E> value_of(const std::string_view name)
{
  for (const EnumName<E>& entry : enum_names(E{}))
    if (entry.name == name)
      return entry.value;
  return std::nullopt;
}

/// Every name of the table in its order (a schema key's choices).
template <typename E>
std::vector<std::string> names_of()
{
  std::vector<std::string> names;
  for (const EnumName<E>& entry : enum_names(E{}))
    names.emplace_back(entry.name);
  return names;
}

/// The names of some of the enum's values, in the order given (a key that accepts a subset).
template <typename E>
std::vector<std::string> names_of(const std::initializer_list<E> values)
{
  std::vector<std::string> names;
  for (const E value : values)
    names.emplace_back(name_of(value));
  return names;
}
} // namespace ddafem
