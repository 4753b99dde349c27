// Chained construction of schema keys (app/schema/scene_schema.cc): key("dt", ValueType::number)
// .unit("s").greater_than(0).meaning(...).
#pragma once

#include "app/schema/scene_schema.h"

#include <string>
#include <utility>
#include <vector>

namespace ddafem::schema
{
/// Chained construction of a Key, so that the schema below reads like a table.
class KeyBuilder
{
public:
  KeyBuilder(std::string name, ValueType type)
  {
    k.name = std::move(name);
    k.type = type;
  }
  explicit KeyBuilder(Key key) : k(std::move(key)) {}
  KeyBuilder& unit(std::string u)
  {
    k.unit = std::move(u);
    return *this;
  }
  KeyBuilder& required()
  {
    k.required = true;
    return *this;
  }
  KeyBuilder& default_yaml(std::string yaml)
  {
    k.default_yaml = std::move(yaml);
    return *this;
  }
  KeyBuilder& default_note(std::string note)
  {
    k.default_note = std::move(note);
    return *this;
  }
  KeyBuilder& greater_than(double v)
  {
    k.range.min = v;
    k.range.min_inclusive = false;
    return *this;
  }
  KeyBuilder& at_least(double v)
  {
    k.range.min = v;
    k.range.min_inclusive = true;
    return *this;
  }
  KeyBuilder& at_most(double v)
  {
    k.range.max = v;
    k.range.max_inclusive = true;
    return *this;
  }
  KeyBuilder& less_than(double v)
  {
    k.range.max = v;
    k.range.max_inclusive = false;
    return *this;
  }
  KeyBuilder& choices(std::vector<std::string> c)
  {
    k.choices = std::move(c);
    return *this;
  }
  KeyBuilder& section(std::string id)
  {
    k.section = std::move(id);
    return *this;
  }
  KeyBuilder& meaning(std::string m)
  {
    k.meaning = std::move(m);
    return *this;
  }
  operator Key() const { return k; }

private:
  Key k;
};

inline KeyBuilder key(std::string name, ValueType type)
{
  return KeyBuilder(std::move(name), type);
}

} // namespace ddafem::schema
