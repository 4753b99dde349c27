// A check shared by the tests of every library's name tables (common/enum_names.h).
#pragma once

#include "common/enum_names.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace ddafem::test_support
{
/// Every name of E's table leads back to itself (name_of(value_of(n)) == n), no two entries
/// share a name or a value, and a name outside the table gives nullopt.
template <typename E>
void expect_round_trip()
{
  std::set<std::string> names;
  std::set<E> values;
  for (const std::string& name : names_of<E>())
  {
    const std::optional<E> value = value_of<E>(name);
    ASSERT_TRUE(value.has_value()) << name;
    EXPECT_EQ(name_of(*value), name);
    EXPECT_TRUE(names.insert(name).second) << name << " is in the table twice";
    EXPECT_TRUE(values.insert(*value).second) << name << "'s value is in the table twice";
  }
  EXPECT_FALSE(names.empty());
  EXPECT_FALSE(value_of<E>("no_such_name").has_value());
  EXPECT_FALSE(value_of<E>("").has_value());
}
} // namespace ddafem::test_support
