// The `far_field` section of scenes.
#include "app/scene.h"
#include "common/input_error.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

using namespace ddafem;

namespace
{
const std::string column = std::string(DDAFEM_SOURCE_DIR) + "/examples/far_field/sv_column.yaml";

/// Writes `text` to a scene file in the test's working directory and reads it.
Scene read_text(const std::string& text, const std::string& name)
{
  {
    std::ofstream f(name);
    f << text;
  }
  return read_scene(name);
}

std::string error_of(const std::string& text, const std::string& name)
{
  try
  {
    read_text(text, name);
  }
  catch (const InputError& e)
  {
    return e.what();
  }
  return "";
}

const std::string base = R"(materials:
  rock: {density: 2650, youngs_modulus: 50e9, poisson_ratio: 0.25}
far_field:
  material: rock
  lower: [0, 0]
  upper: [40, 400]
  element_size: 20
time: {dt: 1e-3, end_time: 0.01}
)";
} // namespace

TEST(FarFieldScene, ExampleColumnIsReadAsWritten)
{
  const Scene s = read_scene(column);
  ASSERT_TRUE(s.far_field.has_value());
  const fem::FarFieldDescription& d = *s.far_field;
  EXPECT_TRUE(s.model.blocks.empty());
  EXPECT_DOUBLE_EQ(d.upper[1], 400.0);
  EXPECT_DOUBLE_EQ(d.max_frequency, 20.0);
  EXPECT_EQ(d.degree, 2u);
  EXPECT_EQ(d.plane_mode, fem::PlaneMode::strain);
  ASSERT_EQ(d.boundaries.size(), 4u);
  EXPECT_EQ(d.boundaries[0].part, fem::BoundaryPart::bottom);
  EXPECT_EQ(d.boundaries[0].kind, fem::BoundaryKind::input);
  EXPECT_EQ(d.boundaries[2].kind, fem::BoundaryKind::roller);
  EXPECT_EQ(d.incident.type, fem::IncidentWave::Type::sv);
  EXPECT_NEAR(d.incident.velocity.value(0.025), 0.1, 1e-12); // quarter period of 10 Hz
  ASSERT_EQ(d.monitors.size(), 3u);
  EXPECT_EQ(d.monitors[2].name, "surface");
  EXPECT_DOUBLE_EQ(d.dt, 1e-3);
  EXPECT_EQ(d.integrator, fem::Integrator::newmark_trapezoidal);
  EXPECT_DOUBLE_EQ(d.density, 2650.0);
}

TEST(FarFieldScene, Errors)
{
  EXPECT_NE(error_of(base + "blocks:\n  - {material: rock, vertices: [[0,0],[1,0],[1,1]]}\n",
                     "ff_and_blocks.yaml")
                .find("need the DDA-FEM coupling"),
            std::string::npos);
  EXPECT_NE(error_of(base + "monitors:\n  - {name: m, point: [50, 10]}\n", "ff_monitor.yaml")
                .find("lies outside the far field"),
            std::string::npos);
  std::string no_size = base;
  no_size.replace(no_size.find("  element_size: 20\n"), 19, "");
  EXPECT_NE(error_of(no_size, "ff_no_size.yaml").find("max_frequency > 0"), std::string::npos);
  std::string degree = base;
  degree.replace(degree.find("  element_size: 20\n"), 19, "  element_size: 20\n  degree: 3\n");
  EXPECT_NE(error_of(degree, "ff_degree.yaml").find("expected 1 or 2"), std::string::npos);
  std::string twice = base;
  twice.replace(twice.find("  element_size: 20\n"), 19,
                "  element_size: 20\n  boundaries:\n    - {part: top, type: lysmer}\n"
                "    - {part: top, type: free}\n");
  EXPECT_NE(error_of(twice, "ff_twice.yaml").find("listed twice"), std::string::npos);
}
