// The `far_field` section of scenes.
#include "app/scene/scene.h"
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
                .find("blocks and a far field need an `interface` section"),
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

namespace
{
/// `base` with `extra` lines inserted into the far_field section (after element_size).
std::string with_far_field_keys(const std::string& extra)
{
  std::string text = base;
  text.replace(text.find("  element_size: 20\n"), 19, "  element_size: 20\n" + extra);
  return text;
}
} // namespace

TEST(FarFieldScene, HoleMeshFileAndSolverKeys)
{
  const Scene s = read_text(
      with_far_field_keys("  hole: {shape: polygon, vertices: [[10, 100], [30, 100], [20, 120]], "
                          "element_size: 1, growth_ratio: 1.5}\n  solver: cg\n"
                          "  solver_tolerance: 1e-11\n  boundaries:\n"
                          "    - {part: hole, type: fixed}\n"),
      "ff_hole.yaml");
  const fem::FarFieldDescription& d = *s.far_field;
  EXPECT_EQ(d.hole.shape, fem::HoleShape::polygon);
  ASSERT_EQ(d.hole.vertices.size(), 3u);
  EXPECT_DOUBLE_EQ(d.hole.vertices[2][1], 120.0);
  EXPECT_DOUBLE_EQ(d.hole.element_size, 1.0);
  EXPECT_DOUBLE_EQ(d.hole.growth_ratio, 1.5);
  EXPECT_EQ(d.solver, fem::LinearSolver::cg);
  EXPECT_DOUBLE_EQ(d.solver_tolerance, 1e-11);
  EXPECT_EQ(d.boundaries[0].part, fem::BoundaryPart::hole);

  // A Gmsh file relative to the scene, its tags by part name; no rectangle corners.
  const std::string msh = std::string(DDAFEM_SOURCE_DIR) + "/tests/fem/data/plate_with_hole.msh";
  std::string gmsh = base;
  gmsh.replace(gmsh.find("  lower: [0, 0]\n  upper: [40, 400]\n"), 34,
               "  mesh: {file: " + msh + ", parts: {bottom: 1, hole: 5}}\n");
  const Scene g = read_text(gmsh, "ff_gmsh.yaml");
  EXPECT_EQ(g.far_field->mesh_file.file, msh);
  EXPECT_EQ(g.far_field->mesh_file.parts.at(fem::BoundaryPart::hole), 5u);
}

TEST(FarFieldScene, HoleAndMeshErrorsNameTheKey)
{
  EXPECT_NE(error_of(with_far_field_keys("  hole: {shape: circle, center: [20, 100]}\n"),
                     "ff_hole_radius.yaml")
                .find("far_field.hole.radius': missing required key for shape circle"),
            std::string::npos);
  EXPECT_NE(error_of(with_far_field_keys(
                         "  hole: {shape: circle, center: [20, 100], radius: 3, lower: [0, 0]}\n"),
                     "ff_hole_extra.yaml")
                .find("expected only the keys of shape circle"),
            std::string::npos);
  EXPECT_NE(error_of(with_far_field_keys("  hole: {shape: circle, center: [38, 100], radius: 3}\n"),
                     "ff_hole_out.yaml")
                .find("expected it strictly inside the far field"),
            std::string::npos);
  EXPECT_NE(error_of(with_far_field_keys("  boundaries:\n    - {part: hole, type: fixed}\n"),
                     "ff_no_hole.yaml")
                .find("the far field has no hole"),
            std::string::npos);
  EXPECT_NE(error_of(with_far_field_keys("  solver: lu\n"), "ff_solver.yaml")
                .find("expected one of 'direct', 'cg'"),
            std::string::npos);
  EXPECT_NE(error_of(with_far_field_keys("  mesh: {file: absent.msh}\n"), "ff_mesh_corners.yaml")
                .find("expected no rectangle corners"),
            std::string::npos);
  std::string absent = base;
  absent.replace(absent.find("  lower: [0, 0]\n  upper: [40, 400]\n"), 34,
                 "  mesh: {file: absent.msh}\n");
  EXPECT_NE(error_of(absent, "ff_mesh_absent.yaml").find("cannot open mesh file"),
            std::string::npos);
  std::string twice = base;
  twice.replace(twice.find("  lower: [0, 0]\n  upper: [40, 400]\n"), 34,
                "  mesh: {file: " + std::string(DDAFEM_SOURCE_DIR) +
                    "/tests/fem/data/plate_with_hole.msh, parts: {bottom: 1, top: 1}}\n");
  EXPECT_NE(error_of(twice, "ff_mesh_twice.yaml").find("one physical tag per part"),
            std::string::npos);
}

TEST(FarFieldScene, StaticStageAndRayleighKeys)
{
  const Scene s = read_text(
      "gravity: [0, -9.81]\n" +
          with_far_field_keys("  static_stage: {stress_gradient: [1e4, 2e4, 0], support: roller}\n"
                              "  rayleigh: {ratio: 0.05, frequencies: [1, 3]}\n"),
      "ff_static.yaml");
  const fem::FarFieldDescription& d = *s.far_field;
  EXPECT_TRUE(d.static_stage.enabled);
  EXPECT_DOUBLE_EQ(d.static_stage.gravity[1], -9.81); // the scene's gravity
  EXPECT_DOUBLE_EQ(d.static_stage.stress_gradient[1], 2e4);
  EXPECT_DOUBLE_EQ(d.static_stage.reference_y, 400.0); // the top
  EXPECT_EQ(d.static_stage.support, fem::StaticSupport::roller);
  // alpha = 2 zeta w1 w2 / (w1 + w2), beta = 2 zeta / (w1 + w2).
  const double w1 = 2.0 * M_PI, w2 = 6.0 * M_PI;
  EXPECT_NEAR(d.rayleigh.alpha, 0.1 * w1 * w2 / (w1 + w2), 1e-12);
  EXPECT_NEAR(d.rayleigh.beta, 0.1 / (w1 + w2), 1e-15);

  EXPECT_NE(error_of(with_far_field_keys("  rayleigh: {alpha: 1, ratio: 0.05}\n"), "ff_ray.yaml")
                .find("expected either `alpha` and/or `beta`, or `ratio` with `frequencies`"),
            std::string::npos);
  EXPECT_NE(error_of(with_far_field_keys("  rayleigh: {ratio: 0.05, frequencies: [3, 1]}\n"),
                     "ff_ray_order.yaml")
                .find("expected f1 < f2"),
            std::string::npos);
  EXPECT_NE(error_of(with_far_field_keys("  static_stage: {support: pinned}\n"), "ff_support.yaml")
                .find("expected one of 'fixed', 'roller'"),
            std::string::npos);
}
