// Keys declared once (app/schema/bound_keys.h): the key's type follows from its field, its
// default is the field's initialiser, and fill() writes what a scene gives (or the default) into
// the struct, leaving a key whose default is a note alone when the scene does not give it.
#include "app/schema/bound_keys.h"

#include "app/scene/map_reader.h"
#include "app/schema/scene_schema.h"
#include "common/input_error.h"
#include "dda/model_description.h"

#include <gtest/gtest.h>

#include <yaml-cpp/yaml.h>

#include <array>
#include <string>

namespace
{
using namespace ddafem;
using schema::BoundKeys;
using schema::Key;
using schema::Section;
using schema::ValueType;

struct Settings
{
  double ratio = 0.3;
  double small = 1e-6;
  double automatic = 0.0; ///< 0: derived (a note, no literal default)
  unsigned count = 6;
  bool flag = false;
  dda::TimeControl control = dda::TimeControl::adaptive;
  std::string name = "results";
  double needed = 0.0;
  std::array<double, 2> point{{1.5, -2.0}};
};

BoundKeys<Settings> settings_keys()
{
  using S = Settings;
  BoundKeys<S> k;
  k.field("ratio", &S::ratio).greater_than(0).less_than(1).meaning("a ratio");
  k.field("small", &S::small).unit("m").meaning("a length");
  k.field("automatic", &S::automatic).default_note("derived").meaning("a derived length");
  k.field("count", &S::count).meaning("a count");
  k.field("flag", &S::flag).meaning("a switch");
  k.field("control", &S::control).meaning("a choice");
  k.field("name", &S::name).meaning("a name");
  k.field("needed", &S::needed).required().meaning("a required number");
  k.field("point", &S::point).unit("m").meaning("a point");
  k.add(schema::key("by_hand", ValueType::number).default_yaml("5").meaning("read by the reader"));
  return k;
}

/// `text` read as the map of a section made of settings_keys(), filled into a Settings whose
/// fields start at `start`.
Settings filled(const std::string& text, Settings start = {})
{
  const schema::SceneSchema scene_schema;
  const scene_reading::Locator locator("made_up.yaml");
  const scene_reading::Context context{scene_schema, locator, ".", {}};
  const BoundKeys<Settings> keys = settings_keys();
  const Section section{"made_up", "A made-up section.", keys.keys()};
  const YAML::Node node = YAML::Load(text);
  const scene_reading::MapReader reader(node, section, "made_up", context);
  keys.fill(reader, start);
  return start;
}

TEST(BoundKeys, TypeAndDefaultFollowTheField)
{
  const std::vector<Key> keys = settings_keys().keys();
  ASSERT_EQ(keys.size(), 10u);
  EXPECT_EQ(keys[0].type, ValueType::number);
  EXPECT_EQ(keys[0].default_yaml, "0.3");
  EXPECT_EQ(keys[1].default_yaml, "1e-6"); // not "1e-06"
  EXPECT_EQ(keys[1].unit, "m");
  EXPECT_EQ(keys[2].default_yaml, ""); // a note replaces the literal default
  EXPECT_EQ(keys[2].default_note, "derived");
  EXPECT_EQ(keys[3].type, ValueType::integer);
  EXPECT_EQ(keys[3].default_yaml, "6");
  EXPECT_EQ(keys[4].type, ValueType::boolean);
  EXPECT_EQ(keys[4].default_yaml, "false");
  EXPECT_EQ(keys[5].type, ValueType::choice);
  EXPECT_EQ(keys[5].choices, (std::vector<std::string>{"adaptive", "fixed"}));
  EXPECT_EQ(keys[5].default_yaml, "adaptive");
  EXPECT_EQ(keys[6].type, ValueType::string);
  EXPECT_EQ(keys[6].default_yaml, "results");
  EXPECT_TRUE(keys[7].required);
  EXPECT_EQ(keys[7].default_yaml, ""); // required: no default
  EXPECT_EQ(keys[8].type, ValueType::vector2);
  EXPECT_EQ(keys[8].default_yaml, "[1.5, -2]");
  EXPECT_EQ(keys[9].name, "by_hand"); // a key read by hand keeps its declaration
  EXPECT_EQ(keys[9].default_yaml, "5");
}

TEST(BoundKeys, FillsGivenKeysAndDefaults)
{
  Settings start;
  start.ratio = 0.9; // a default overwrites what the struct held
  start.automatic = 7.0;
  const Settings s =
      filled("{needed: 2.5, count: 3, flag: true, control: fixed, name: out}", start);
  EXPECT_EQ(s.needed, 2.5);
  EXPECT_EQ(s.count, 3u);
  EXPECT_TRUE(s.flag);
  EXPECT_EQ(s.control, dda::TimeControl::fixed);
  EXPECT_EQ(s.name, "out");
  EXPECT_EQ(s.ratio, 0.3);
  EXPECT_EQ(s.small, 1e-6);
  EXPECT_EQ(s.automatic, 7.0); // a note's key left alone when absent
  EXPECT_EQ(filled("{needed: 1, automatic: 0.5}").automatic, 0.5);
  EXPECT_NO_THROW(filled("{needed: 1, by_hand: 2}")); // known to the section, not filled
}

TEST(BoundKeys, RefusesWhatTheKeyDoesNotAllow)
{
  EXPECT_THROW(filled("{count: 2}"), InputError);              // needed is required
  EXPECT_THROW(filled("{needed: 1, ratio: 1.5}"), InputError); // out of range
  EXPECT_THROW(filled("{needed: 1, count: -1}"), InputError);  // unsigned field
  EXPECT_THROW(filled("{needed: 1, control: sometimes}"), InputError);
}

/// A struct with Eigen vectors and a part of its own (as the rock mass's sliver settings).
struct Part
{
  double width = 0.25;
};
struct Nested
{
  dda::Vector2 velocity = dda::Vector2(0.0, -1.5);
  dda::Voigt stress = dda::Voigt(1.0, 2.0, 0.0);
  std::array<double, 3> gradient{{0.0, 9.81, 0.0}};
  Part part;
};

Nested filled_nested(const std::string& text)
{
  using S = Nested;
  BoundKeys<S> k;
  k.field("velocity", &S::velocity).unit("m/s").meaning("a velocity");
  k.field("stress", &S::stress).unit("Pa").meaning("a stress");
  k.field("gradient", &S::gradient).unit("Pa/m").meaning("a gradient");
  k.field("width", &S::part, &Part::width).unit("m").meaning("a part's width");
  const std::vector<Key> keys = k.keys();
  EXPECT_EQ(keys[0].type, ValueType::vector2);
  EXPECT_EQ(keys[0].default_yaml, "[0, -1.5]");
  EXPECT_EQ(keys[1].type, ValueType::voigt);
  EXPECT_EQ(keys[1].default_yaml, "[1, 2, 0]");
  EXPECT_EQ(keys[2].type, ValueType::voigt);
  EXPECT_EQ(keys[2].default_yaml, "[0, 9.81, 0]");
  EXPECT_EQ(keys[3].type, ValueType::number);
  EXPECT_EQ(keys[3].default_yaml, "0.25"); // the part's initialiser
  const schema::SceneSchema scene_schema;
  const scene_reading::Locator locator("made_up.yaml");
  const scene_reading::Context context{scene_schema, locator, ".", {}};
  const Section section{"made_up", "A made-up section.", keys};
  const YAML::Node node = YAML::Load(text);
  Nested n;
  n.part.width = 5.0;
  k.fill(scene_reading::MapReader(node, section, "made_up", context), n);
  return n;
}

TEST(BoundKeys, FillsVectorsStressesAndAPartsField)
{
  const Nested given = filled_nested("{velocity: [1, 2], stress: [3, 4, 5], gradient: [0, 1, 0], "
                                     "width: 0.5}");
  EXPECT_EQ(given.velocity, dda::Vector2(1.0, 2.0));
  EXPECT_EQ(given.stress, dda::Voigt(3.0, 4.0, 5.0));
  EXPECT_EQ(given.gradient[1], 1.0);
  EXPECT_EQ(given.part.width, 0.5);
  const Nested defaults = filled_nested("{}");
  EXPECT_EQ(defaults.velocity, dda::Vector2(0.0, -1.5));
  EXPECT_EQ(defaults.part.width, 0.25); // the default overwrites what the part held
  EXPECT_THROW(filled_nested("{stress: [1, 2]}"), InputError);
}

TEST(BoundKeys, ShortestNumberTextReadsBack)
{
  for (const double v :
       {0.0, 1.0, 1.2, 0.3, 1e-6, 1e-10, 2.5e10, 60.0, 0.01, 1.0 / 3.0, 1e300, -7e-5})
    EXPECT_EQ(std::stod(schema::shortest_number_text(v)), v) << v;
  EXPECT_EQ(schema::shortest_number_text(1e-10), "1e-10");
  EXPECT_EQ(schema::shortest_number_text(2.5e10), "25e9"); // moduli as engineers write them
  EXPECT_EQ(schema::shortest_number_text(200e9), "200e9");
  EXPECT_EQ(schema::shortest_number_text(1e6), "1e6");
  EXPECT_EQ(schema::shortest_number_text(100.0), "100");
  EXPECT_EQ(schema::shortest_number_text(1e-3), "1e-3"); // shorter than 0.001
  EXPECT_EQ(schema::shortest_number_text(0.01), "0.01"); // as short as 1e-2: fixed
  EXPECT_EQ(schema::shortest_number_text(-0.25), "-0.25");
}

} // namespace
