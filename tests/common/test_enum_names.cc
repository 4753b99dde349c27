// The enum <-> name tables (common/enum_names.h): the generic look-ups on a table written here,
// and the round trip of the tables common/ declares.
#include "common/elasticity.h"
#include "common/enum_names.h"
#include "common/wave_type.h"
#include "tests/enum_round_trip.h"

#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

namespace
{
using namespace ddafem;

enum class Colour
{
  red,
  green,
  blue
};

constexpr std::array<EnumName<Colour>, 3> enum_names(Colour)
{
  return {{{Colour::green, "green"}, {Colour::red, "red"}, {Colour::blue, "light blue"}}};
}

enum class Unnamed
{
  first,
  second
};

constexpr std::array<EnumName<Unnamed>, 1> enum_names(Unnamed)
{
  return {{{Unnamed::first, "first"}}};
}

TEST(EnumNames, LookUpBothWays)
{
  EXPECT_STREQ(name_of(Colour::red), "red");
  EXPECT_STREQ(name_of(Colour::blue), "light blue");
  EXPECT_EQ(value_of<Colour>("green"), Colour::green);
  EXPECT_EQ(value_of<Colour>("light blue"), Colour::blue);
}

TEST(EnumNames, UnknownNameOrValue)
{
  EXPECT_EQ(value_of<Colour>("Red"), std::nullopt);
  EXPECT_EQ(value_of<Colour>("light"), std::nullopt);
  EXPECT_EQ(value_of<Colour>(""), std::nullopt);
  EXPECT_STREQ(name_of(Unnamed::second), "");
}

TEST(EnumNames, NamesInTheTablesOrder)
{
  EXPECT_EQ(names_of<Colour>(), (std::vector<std::string>{"green", "red", "light blue"}));
  EXPECT_EQ(names_of({Colour::blue, Colour::red}), (std::vector<std::string>{"light blue", "red"}));
}

TEST(EnumNames, CommonTablesRoundTrip)
{
  test_support::expect_round_trip<Colour>();
  test_support::expect_round_trip<WaveType>();
  test_support::expect_round_trip<PlaneMode>();
  EXPECT_EQ(names_of<WaveType>(), (std::vector<std::string>{"p", "sv"}));
  EXPECT_EQ(names_of<PlaneMode>(), (std::vector<std::string>{"stress", "strain"}));
}
} // namespace
