// Every name table of dda/, fem/ and app/ (common/enum_names.h) leads from each name back to
// itself, and the choices the schema offers are exactly those names.
#include "app/scene/tunnel_scene.h"
#include "app/schema/scene_schema.h"
#include "common/ground_motion.h"
#include "dda/model_description.h"
#include "dda/rock_mass.h"
#include "dda/system.h"
#include "fem/far_field_description.h"
#include "tests/enum_round_trip.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace
{
using namespace ddafem;
using test_support::expect_round_trip;

TEST(EnumNames, BlockTablesRoundTrip)
{
  expect_round_trip<dda::Integrator>();
  expect_round_trip<dda::StepOutcome>();
  expect_round_trip<dda::GeometryMode>();
  expect_round_trip<dda::BoundaryType>();
  expect_round_trip<dda::ImpedanceKind>();
  expect_round_trip<dda::SolverKind>();
  expect_round_trip<dda::TimeControl>();
  expect_round_trip<dda::StageMode>();
  expect_round_trip<dda::ReleaseAction>();
  expect_round_trip<dda::Distribution>();
  expect_round_trip<dda::SliverAction>();
}

TEST(EnumNames, FarFieldTablesRoundTrip)
{
  expect_round_trip<fem::Integrator>();
  expect_round_trip<fem::BoundaryKind>();
  expect_round_trip<fem::BoundaryPart>();
  expect_round_trip<fem::HoleShape>();
  expect_round_trip<fem::LinearSolver>();
  expect_round_trip<fem::StaticSupport>();
  expect_round_trip<fem::VtuCompression>();
}

TEST(EnumNames, AppTablesRoundTrip)
{
  expect_round_trip<TunnelTruncation>();
  expect_round_trip<schema::ValueType>();
  expect_round_trip<schema::TimeFunctionType>();
  expect_round_trip<schema::RecordFormat>();
  expect_round_trip<schema::RecordUnit>();
  expect_round_trip<schema::BaselineMethod>();
  expect_round_trip<RecordMotion>();
  expect_round_trip<MotionQuantity>();
}

TEST(EnumNames, SpellingsOfScenesAndSummaries)
{
  EXPECT_EQ(names_of<dda::Integrator>(),
            (std::vector<std::string>{"generalized_alpha", "bathe", "dda", "newmark_trapezoidal"}));
  EXPECT_STREQ(name_of(dda::StepOutcome::penetration_too_large), "penetration_too_large");
  EXPECT_STREQ(name_of(dda::StageMode::static_equilibrium), "static");
  EXPECT_STREQ(name_of(dda::SolverKind::block_ldlt), "block_ldlt");
  EXPECT_STREQ(name_of(fem::BoundaryKind::free_field), "free_field");
  EXPECT_STREQ(name_of(schema::ValueType::vector2), "[x, y]");
  EXPECT_EQ(names_of<schema::TimeFunctionType>(),
            (std::vector<std::string>{"constant", "sine_pulse", "table", "csv", "record"}));
  EXPECT_EQ(names_of<schema::RecordUnit>(),
            (std::vector<std::string>{"g", "m/s^2", "cm/s^2", "m/s", "cm/s", "m", "cm"}));
  EXPECT_EQ(names_of<RecordMotion>(), (std::vector<std::string>{"outcrop", "within", "incident"}));
  // A hole shape of none is no scene's choice.
  EXPECT_STREQ(name_of(fem::HoleShape::none), "");
}
} // namespace
