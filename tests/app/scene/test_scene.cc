// Scene files: reading, defaults, validation messages, --set overrides and the generated
// reference.
#include "app/scene/scene.h"
#include "app/schema/scene_schema.h"
#include "common/input_error.h"
#include "dda/geometry.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

namespace ddafem
{
namespace
{
namespace fs = std::filesystem;

const std::string source_dir = DDAFEM_SOURCE_DIR;

/// One rock material, one unit square block, a time section: the smallest valid scene.
const char* minimal_scene = R"(materials:
  rock: {density: 2650, youngs_modulus: 50e9, poisson_ratio: 0.25}
blocks:
  - material: rock
    vertices: [[0, 0], [1, 0], [1, 1], [0, 1]]
time: {dt: 1e-4, end_time: 0.01}
)";

/// Each test writes its scenes into a fresh directory of its own.
class SceneTest : public ::testing::Test
{
protected:
  void SetUp() override
  {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    directory = fs::temp_directory_path() /
                (std::string("ddafem_test_scene_") + info->test_suite_name() + "_" + info->name());
    fs::remove_all(directory);
    fs::create_directories(directory);
  }
  void TearDown() override { fs::remove_all(directory); }

  /// Writes `text` to `name` inside the test directory; returns its path.
  std::string write(const std::string& name, const std::string& text) const
  {
    const fs::path path = directory / name;
    fs::create_directories(path.parent_path());
    std::ofstream(path) << text;
    return path.string();
  }

  /// The message of the InputError that reading `text` (with `overrides`) throws.
  std::string error_of(const std::string& text, const std::vector<Override>& overrides = {}) const
  {
    const std::string file = write("scene.yaml", text);
    try
    {
      read_scene(file, overrides);
    }
    catch (const InputError& e)
    {
      return e.what();
    }
    ADD_FAILURE() << "no InputError for\n" << text;
    return "";
  }

  Scene read(const std::string& text, const std::vector<Override>& overrides = {}) const
  {
    return read_scene(write("scene.yaml", text), overrides);
  }

  fs::path directory;
};

/// The scene with `replacement` put in place of `original` (which must occur).
std::string replaced(const std::string& scene, const std::string& original,
                     const std::string& replacement)
{
  const auto at = scene.find(original);
  EXPECT_NE(at, std::string::npos) << original;
  std::string s = scene;
  return s.replace(at, original.size(), replacement);
}

/// A scene with `n_x` by `n_y` unit squares, rotated by `angle` [rad] about the origin and
/// written out as separate `vertices` blocks.
std::string scene_with_listed_blocks(int n_x, int n_y, double angle)
{
  const double c = std::cos(angle), s = std::sin(angle);
  std::ostringstream out;
  out.precision(17);
  out << "materials:\n  rock: {density: 2650, youngs_modulus: 50e9, poisson_ratio: 0.25}\n"
      << "blocks:\n";
  for (int j = 0; j < n_y; ++j)
    for (int i = 0; i < n_x; ++i)
    {
      out << "  - {material: rock, vertices: [";
      const int corners[4][2] = {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}};
      for (int k = 0; k < 4; ++k)
        out << (k == 0 ? "" : ", ") << "[" << c * corners[k][0] - s * corners[k][1] << ", "
            << s * corners[k][0] + c * corners[k][1] << "]";
      out << "]}\n";
    }
  out << "time: {dt: 1e-4, end_time: 0.01}\n";
  return out.str();
}

double seconds_since(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// ---- The example scenes ---------------------------------------------------------------------

TEST(SceneExamples, PWaveBarIsReadAsSpecified)
{
  const Scene scene = read_scene(source_dir + "/examples/bao2012/p_wave_bar.yaml");
  const dda::ModelDescription& m = scene.model;
  EXPECT_EQ(scene.name, "p_wave_bar");
  EXPECT_EQ(m.plane_mode, dda::PlaneMode::stress);

  ASSERT_EQ(m.materials.size(), 1u);
  EXPECT_EQ(m.materials[0].name, "rock");
  EXPECT_EQ(m.materials[0].density, 2650.0);
  EXPECT_EQ(m.materials[0].youngs_modulus, 50e9);
  EXPECT_EQ(m.materials[0].poisson_ratio, 0.25);

  ASSERT_EQ(m.joint_materials.size(), 1u);
  const dda::JointMaterial& j = m.joint_materials[0];
  EXPECT_EQ(j.name, "bonded");
  EXPECT_EQ(j.normal_stiffness, 2.5e12);
  EXPECT_EQ(j.shear_ratio, 0.4);
  EXPECT_EQ(j.friction_angle, 45.0);
  EXPECT_EQ(j.cohesion, 20e6);
  EXPECT_EQ(j.tensile_strength, 10e6);
  EXPECT_TRUE(j.bonded);
  EXPECT_EQ(m.default_joint_material, 0u);
  EXPECT_TRUE(m.joint_assignments.empty());

  ASSERT_EQ(m.blocks.size(), 100u);
  for (std::size_t i = 0; i < 100; ++i)
  {
    const auto& v = m.blocks[i].vertices;
    ASSERT_EQ(v.size(), 4u);
    EXPECT_EQ(v[0], dda::Point(static_cast<double>(i), 0.0));
    EXPECT_EQ(v[2], dda::Point(static_cast<double>(i + 1), 1.0));
    EXPECT_NEAR(dda::signed_area(v), 1.0, 1e-12);
  }
  EXPECT_EQ(m.blocks[0].origin, "blocks[0] (grid cell 0, 0)");
  EXPECT_EQ(m.blocks[99].origin, "blocks[0] (grid cell 99, 0)");

  ASSERT_EQ(m.point_loads.size(), 1u);
  EXPECT_EQ(m.point_loads[0].point, dda::Point(0.0, 0.5));
  EXPECT_EQ(m.point_loads[0].force, dda::Vector2(1.0e6, 0.0));
  const TimeFunction& f = m.point_loads[0].time_function;
  EXPECT_EQ(f.characteristic_frequency(), 100.0);
  EXPECT_NEAR(f.value(0.0025), 1.0, 1e-12); // a quarter period of 100 Hz
  EXPECT_NEAR(f.value(0.0075), -1.0, 1e-12);
  EXPECT_EQ(f.value(0.011), 0.0); // one cycle only

  ASSERT_EQ(m.monitors.size(), 2u);
  EXPECT_EQ(m.monitors[0].name, "M1");
  EXPECT_EQ(m.monitors[0].point, dda::Point(50.5, 0.5));
  EXPECT_EQ(m.monitors[1].name, "M2");
  EXPECT_EQ(m.monitors[1].point, dda::Point(98.5, 0.5));

  EXPECT_EQ(m.time.dt, 1e-5);
  EXPECT_EQ(m.time.end_time, 0.05);
  EXPECT_EQ(m.time.integrator, dda::Integrator::dda);
  EXPECT_EQ(m.gravity, dda::Vector2::Zero());
  EXPECT_TRUE(m.fixed_points.empty());
  EXPECT_EQ(scene.output.directory, "results/p_wave_bar");
  EXPECT_EQ(scene.output.interval, 0.001);

  // The right end x = 100 m, free by default.
  ASSERT_EQ(m.boundaries.size(), 1u);
  const dda::BoundaryDescription& b = m.boundaries[0];
  EXPECT_EQ(b.type, dda::BoundaryType::free);
  EXPECT_EQ(b.impedance, dda::ImpedanceKind::textbook);
  EXPECT_TRUE(b.on_line);
  EXPECT_FALSE(b.outer);
  EXPECT_TRUE(b.edges.empty());
  EXPECT_EQ(b.line_point, dda::Point(100.0, 0.0));
  EXPECT_EQ(b.line_direction, dda::Vector2(0.0, 1.0));
  EXPECT_EQ(b.origin, "boundaries[0]");
}

TEST(SceneExamples, PWaveBarSwitchesBoundaryAndFrequencyFromTheCommandLine)
{
  const Scene scene = read_scene(source_dir + "/examples/bao2012/p_wave_bar.yaml",
                                 {parse_override("boundaries.0.type=vb1"),
                                  parse_override("boundaries.0.impedance=effective"),
                                  parse_override("point_loads.0.time_function.frequency=50")});
  const dda::ModelDescription& m = scene.model;
  ASSERT_EQ(m.boundaries.size(), 1u);
  EXPECT_EQ(m.boundaries[0].type, dda::BoundaryType::vb1);
  EXPECT_EQ(m.boundaries[0].impedance, dda::ImpedanceKind::effective);
  const TimeFunction& f = m.point_loads[0].time_function;
  EXPECT_EQ(f.characteristic_frequency(), 50.0);
  EXPECT_NEAR(f.value(0.005), 1.0, 1e-12); // a quarter period of 50 Hz
  EXPECT_NEAR(f.value(0.015), -1.0, 1e-12);
  EXPECT_EQ(f.value(0.021), 0.0); // one cycle only
}

TEST(SceneExamples, SWaveColumnIsReadAsSpecified)
{
  const Scene scene = read_scene(source_dir + "/examples/bao2012/s_wave_column.yaml");
  const dda::ModelDescription& m = scene.model;
  EXPECT_EQ(scene.name, "s_wave_column");
  EXPECT_EQ(m.plane_mode, dda::PlaneMode::stress);
  ASSERT_EQ(m.materials.size(), 2u);
  for (const dda::Material& material : m.materials)
  {
    EXPECT_EQ(material.density, 2650.0);
    EXPECT_EQ(material.youngs_modulus, 50e9);
    EXPECT_EQ(material.poisson_ratio, 0.25);
  }
  ASSERT_EQ(m.joint_materials.size(), 1u);
  EXPECT_EQ(m.joint_materials[0].normal_stiffness, 2.5e12);
  EXPECT_EQ(m.joint_materials[0].shear_ratio, 0.4);
  EXPECT_TRUE(m.joint_materials[0].bonded);

  // The base (block 0, y in [0, 1]) and 50 layers of 50 m x 1 m above it.
  ASSERT_EQ(m.blocks.size(), 51u);
  EXPECT_EQ(m.materials[m.blocks[0].material].name, "base");
  for (std::size_t i = 0; i < 51; ++i)
  {
    const auto& v = m.blocks[i].vertices;
    ASSERT_EQ(v.size(), 4u);
    EXPECT_EQ(v[0], dda::Point(0.0, static_cast<double>(i))) << i;
    EXPECT_EQ(v[2], dda::Point(50.0, static_cast<double>(i + 1))) << i;
    EXPECT_NEAR(dda::signed_area(v), 50.0, 1e-9) << i;
    if (i > 0)
    {
      EXPECT_EQ(m.materials[m.blocks[i].material].name, "rock") << i;
    }
  }

  // One cycle of horizontal base displacement: 100 Hz, 1 mm (the paper's 0.02 m would break the
  // bonded joints; see the scene's comment).
  ASSERT_EQ(m.fixed_points.size(), 3u);
  for (const dda::FixedPoint& f : m.fixed_points)
  {
    EXPECT_EQ(f.point.y(), 0.5);
    EXPECT_EQ(f.stiffness, 1e14);
    EXPECT_NEAR(f.displacement_x.value(0.0025), 0.001, 1e-15);
    EXPECT_NEAR(f.displacement_x.value(0.0075), -0.001, 1e-15);
    EXPECT_EQ(f.displacement_x.value(0.011), 0.0);
    EXPECT_EQ(f.displacement_y.value(0.005), 0.0);
  }
  EXPECT_TRUE(m.point_loads.empty());

  ASSERT_EQ(m.boundaries.size(), 1u);
  EXPECT_EQ(m.boundaries[0].type, dda::BoundaryType::free);
  EXPECT_TRUE(m.boundaries[0].on_line);
  EXPECT_EQ(m.boundaries[0].line_point, dda::Point(0.0, 51.0));
  EXPECT_EQ(m.boundaries[0].line_direction, dda::Vector2(1.0, 0.0));

  ASSERT_EQ(m.monitors.size(), 3u);
  EXPECT_EQ(m.monitors[0].point, dda::Point(25.0, 0.5));
  EXPECT_EQ(m.monitors[1].point, dda::Point(25.0, 31.5));
  EXPECT_EQ(m.monitors[2].point, dda::Point(25.0, 49.5));
  EXPECT_EQ(m.time.dt, 1e-5);
  EXPECT_EQ(m.time.end_time, 0.06);
  EXPECT_EQ(m.time.integrator, dda::Integrator::dda);
  EXPECT_EQ(scene.output.directory, "results/s_wave_column");
  EXPECT_EQ(scene.output.interval, 0.002);

  // The stiffer joints of the paper's second case.
  const Scene stiff = read_scene(source_dir + "/examples/bao2012/s_wave_column.yaml",
                                 {parse_override("joint_materials.bonded.normal_stiffness=1.25e13"),
                                  parse_override("boundaries.0.type=vb2")});
  EXPECT_EQ(stiff.model.joint_materials[0].normal_stiffness, 1.25e13);
  EXPECT_EQ(stiff.model.boundaries[0].type, dda::BoundaryType::vb2);
}

TEST(SceneExamples, BlockStackIsReadAsSpecified)
{
  const Scene scene = read_scene(source_dir + "/examples/block_stack/stack.yaml");
  const dda::ModelDescription& m = scene.model;
  ASSERT_EQ(m.blocks.size(), 4u);
  EXPECT_NEAR(dda::signed_area(m.blocks[0].vertices), 4.0, 1e-12);
  for (std::size_t i = 1; i < 4; ++i)
  {
    const dda::PolygonMoments moments = dda::polygon_moments(m.blocks[i].vertices);
    EXPECT_NEAR(moments.area, 1.0, 1e-12);
    EXPECT_NEAR(moments.centroid.x(), 2.0, 1e-12);
    EXPECT_NEAR(moments.centroid.y(), 0.5 + static_cast<double>(i), 1e-12);
  }
  EXPECT_EQ(m.joint_materials.at(0).normal_stiffness, 5e10);
  ASSERT_EQ(m.fixed_points.size(), 2u);
  EXPECT_EQ(m.fixed_points[0].point, dda::Point(0.5, 0.5));
  EXPECT_EQ(m.fixed_points[1].point, dda::Point(3.5, 0.5));
  EXPECT_EQ(m.fixed_points[0].stiffness, 0.0);
  EXPECT_EQ(m.fixed_points[0].displacement_x.value(0.3), 0.0);
  EXPECT_EQ(m.fixed_points[0].displacement_y.value(0.3), 0.0);
  EXPECT_EQ(m.gravity, dda::Vector2(0.0, -9.81));
  ASSERT_EQ(m.monitors.size(), 2u);
  EXPECT_EQ(m.monitors[0].name, "top");
  EXPECT_EQ(m.monitors[1].name, "bottom");
  EXPECT_EQ(m.time.dt, 1e-3);
  EXPECT_EQ(m.time.end_time, 0.7);
  EXPECT_EQ(m.time.control, dda::TimeControl::adaptive);
  EXPECT_FALSE(m.joint_materials.at(0).bonded);
  ASSERT_EQ(m.point_loads.size(), 1u);
  EXPECT_NEAR(m.point_loads[0].time_function.value(0.35), 0.5, 1e-12);
  ASSERT_EQ(m.stages.size(), 2u);
  EXPECT_EQ(m.stages[0].name, "settle");
  EXPECT_EQ(m.stages[0].mode, dda::StageMode::static_equilibrium);
  EXPECT_EQ(m.stages[0].max_steps, 2000u);
  EXPECT_EQ(m.stages[0].dt, 1e-3);
  EXPECT_EQ(m.stages[1].mode, dda::StageMode::dynamic);
  EXPECT_EQ(m.stages[1].end_time, 0.7);
  EXPECT_EQ(scene.output.interval, 0.1);
}

TEST(SceneExamples, RockMassExampleIsGenerated)
{
  const Scene scene = read_scene(source_dir + "/examples/rock_mass/two_joint_sets.yaml");
  const dda::ModelDescription& m = scene.model;
  ASSERT_TRUE(scene.rock_mass);
  const dda::RockMassStatistics& s = scene.rock_mass->statistics;
  EXPECT_EQ(scene.rock_mass->first_block, 0u);
  EXPECT_EQ(s.n_blocks, m.blocks.size());
  EXPECT_GT(m.blocks.size(), 40u);
  EXPECT_EQ(m.blocks[0].origin, "rock_mass block 0");
  EXPECT_EQ(m.blocks.back().origin, "rock_mass block " + std::to_string(m.blocks.size() - 1));
  double total = 0.0;
  for (const dda::BlockDescription& b : m.blocks)
  {
    EXPECT_EQ(b.material, 0u);
    EXPECT_GT(dda::signed_area(b.vertices), 0.0);
    total += dda::signed_area(b.vertices);
  }
  // 40 m x 40 m minus the 28-gon inscribed in the 3 m circle.
  const double excavated = 14.0 * 9.0 * std::sin(2.0 * M_PI / 28.0);
  EXPECT_NEAR(total, 1600.0 - excavated, 1e-9 * 1600.0);
  EXPECT_NEAR(s.excavated_area, excavated, 1e-9 * excavated);
  EXPECT_TRUE(scene.rock_mass->slivers.empty());
  ASSERT_EQ(m.stages.size(), 1u);
  EXPECT_EQ(m.stages[0].mode, dda::StageMode::static_equilibrium);
  EXPECT_EQ(m.fixed_points.size(), 9u);
}

// ---- Values, defaults and conversions -------------------------------------------------------

TEST_F(SceneTest, DefaultsAreApplied)
{
  const Scene scene = read(minimal_scene);
  EXPECT_EQ(scene.name, "scene"); // the file's stem
  EXPECT_EQ(scene.description, "");
  const dda::ModelDescription& m = scene.model;
  EXPECT_EQ(m.plane_mode, dda::PlaneMode::stress);
  EXPECT_EQ(m.geometry, dda::GeometryMode::updated);
  EXPECT_TRUE(m.joint_materials.empty());
  EXPECT_EQ(m.default_joint_material, static_cast<std::size_t>(-1));
  EXPECT_EQ(m.gravity, dda::Vector2::Zero());
  EXPECT_EQ(m.time.integrator, dda::Integrator::bathe);
  EXPECT_EQ(m.time.spectral_radius, 0.2);
  EXPECT_EQ(m.solver.direct, dda::SolverKind::block_ldlt);
  EXPECT_EQ(m.blocks[0].initial_velocity, dda::Vector2::Zero());
  EXPECT_EQ(m.blocks[0].initial_stress, dda::Voigt::Zero());
  EXPECT_EQ(m.blocks[0].origin, "blocks[0]");
  EXPECT_EQ(scene.output.directory, "results");
  EXPECT_EQ(scene.output.interval, 0.0);
  EXPECT_EQ(scene.output.history_every, 1u);
  EXPECT_TRUE(m.boundaries.empty());
}

TEST_F(SceneTest, EverySectionIsRead)
{
  const Scene scene = read(R"(name: all
description: every section
analysis: {plane: strain, geometry: small_displacement}
materials:
  rock: {density: 2650, youngs_modulus: 50e9, poisson_ratio: 0.25}
  soft: {density: 2000, youngs_modulus: 1e9, poisson_ratio: 0.3}
joint_materials:
  glued: {normal_stiffness: 1e10}
  slippy: {normal_stiffness: 2e10, shear_ratio: 0.5, friction_angle: 30, cohesion: 1e5,
           tensile_strength: 2e5, bonded: false}
joints:
  default: glued
  pairs:
    - {materials: [soft, rock], joint: slippy}
blocks:
  - material: soft
    vertices: [[0, 0], [1, 0], [1, 1], [0, 1]]
    initial_velocity: [1, -2]
    initial_stress: [-1e5, -2e5, 3e4]
point_loads:
  - {point: [0.5, 0.5], force: [1, 2]}
fixed_points:
  - point: [0, 0]
    stiffness: 1e12
    displacement_x: {type: table, points: [[0, 0], [1, 0.01]]}
gravity: [0, -9.81]
time: {dt: 1e-4, end_time: 0.01, integrator: newmark_trapezoidal}
solver: {type: klu}
output: {directory: out, interval: 0.5, history_every: 10}
)");
  const dda::ModelDescription& m = scene.model;
  EXPECT_EQ(scene.name, "all");
  EXPECT_EQ(scene.description, "every section");
  EXPECT_EQ(m.plane_mode, dda::PlaneMode::strain);
  EXPECT_EQ(m.geometry, dda::GeometryMode::small_displacement);
  ASSERT_EQ(m.materials.size(), 2u);
  EXPECT_EQ(m.materials[1].name, "soft"); // file order
  ASSERT_EQ(m.joint_materials.size(), 2u);
  const dda::JointMaterial& s = m.joint_materials[1];
  EXPECT_EQ(s.shear_ratio, 0.5);
  EXPECT_EQ(s.friction_angle, 30.0);
  EXPECT_EQ(s.cohesion, 1e5);
  EXPECT_EQ(s.tensile_strength, 2e5);
  EXPECT_FALSE(s.bonded);
  EXPECT_EQ(m.joint_materials[0].shear_ratio, 0.4); // default
  EXPECT_TRUE(m.joint_materials[0].bonded);
  EXPECT_EQ(m.default_joint_material, 0u);
  ASSERT_EQ(m.joint_assignments.size(), 1u);
  EXPECT_EQ(m.joint_assignments[0].material_a, 1u);
  EXPECT_EQ(m.joint_assignments[0].material_b, 0u);
  EXPECT_EQ(m.joint_assignments[0].joint_material, 1u);
  EXPECT_EQ(m.blocks[0].material, 1u);
  EXPECT_EQ(m.blocks[0].initial_velocity, dda::Vector2(1, -2));
  EXPECT_EQ(m.blocks[0].initial_stress, dda::Voigt(-1e5, -2e5, 3e4));
  EXPECT_EQ(m.point_loads[0].time_function.value(123.0), 1.0); // default constant 1
  EXPECT_EQ(m.point_loads[0].origin, "point_loads[0]");
  EXPECT_EQ(m.fixed_points[0].stiffness, 1e12);
  EXPECT_NEAR(m.fixed_points[0].displacement_x.value(0.5), 0.005, 1e-15);
  EXPECT_EQ(m.fixed_points[0].origin, "fixed_points[0]");
  EXPECT_EQ(m.gravity, dda::Vector2(0, -9.81));
  EXPECT_EQ(m.time.integrator, dda::Integrator::newmark_trapezoidal);
  EXPECT_EQ(m.solver.direct, dda::SolverKind::klu);
  EXPECT_EQ(scene.output.directory, "out");
  EXPECT_EQ(scene.output.interval, 0.5);
  EXPECT_EQ(scene.output.history_every, 10u);
}

TEST_F(SceneTest, GridCellsGoRowByRowWithXFastest)
{
  const Scene scene =
      read(replaced(minimal_scene, "vertices: [[0, 0], [1, 0], [1, 1], [0, 1]]",
                    "grid: {origin: [10, 20], cell_size: [2, 0.5], count: [3, 2]}"));
  const auto& blocks = scene.model.blocks;
  ASSERT_EQ(blocks.size(), 6u);
  for (std::size_t k = 0; k < 6; ++k)
  {
    const double ix = static_cast<double>(k % 3), iy = static_cast<double>(k / 3);
    EXPECT_EQ(blocks[k].vertices[0], dda::Point(10 + 2 * ix, 20 + 0.5 * iy)) << k;
    EXPECT_NEAR(dda::signed_area(blocks[k].vertices), 1.0, 1e-12) << k;
  }
  EXPECT_EQ(blocks[1].origin, "blocks[0] (grid cell 1, 0)");
  EXPECT_EQ(blocks[3].origin, "blocks[0] (grid cell 0, 1)");
}

TEST_F(SceneTest, ClockwiseVerticesAreReversedAndAClosingVertexIsDropped)
{
  const Scene scene = read(replaced(minimal_scene, "[[0, 0], [1, 0], [1, 1], [0, 1]]",
                                    "[[0, 0], [0, 1], [1, 1], [1, 0], [0, 0]]\n  - material: rock\n"
                                    "    vertices: [[1, 0], [2, 0], [1.5, 1], [1, 0]]"));
  ASSERT_EQ(scene.model.blocks.size(), 2u);
  const auto& square = scene.model.blocks[0].vertices;
  ASSERT_EQ(square.size(), 4u);
  EXPECT_GT(dda::signed_area(square), 0.0);
  EXPECT_NEAR(dda::signed_area(square), 1.0, 1e-12);
  const auto& triangle = scene.model.blocks[1].vertices;
  ASSERT_EQ(triangle.size(), 3u);
  EXPECT_EQ(triangle[0], dda::Point(1, 0)); // already anticlockwise: order kept
  EXPECT_EQ(triangle[2], dda::Point(1.5, 1));
}

TEST_F(SceneTest, ConcaveBlocksAndBlocksThatTouchAreAccepted)
{
  // An L-shaped block with a square in its notch: they share two edges but do not overlap.
  const Scene scene =
      read(replaced(minimal_scene, "[[0, 0], [1, 0], [1, 1], [0, 1]]",
                    "[[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]]\n  - material: rock\n"
                    "    vertices: [[1, 1], [2, 1], [2, 2], [1, 2]]"));
  EXPECT_EQ(scene.model.blocks.size(), 2u);
}

TEST_F(SceneTest, AnOverlapBelowTheToleranceIsAccepted)
{
  // Overlap of 1e-12 m x 1 m = 1e-12 m^2 < 1e-9 * 1 m^2: round-off, not an overlap.
  const Scene scene = read(replaced(minimal_scene, "[[0, 0], [1, 0], [1, 1], [0, 1]]",
                                    "[[0, 0], [1, 0], [1, 1], [0, 1]]\n  - material: rock\n"
                                    "    vertices: [[0.999999999999, 0], [2, 0], [2, 1], "
                                    "[0.999999999999, 1]]"));
  EXPECT_EQ(scene.model.blocks.size(), 2u);
}

TEST_F(SceneTest, PointsOnBlockBoundariesAreInside)
{
  const Scene scene = read(std::string(minimal_scene) + R"(monitors:
  - {name: corner, point: [1, 1]}
  - {name: edge, point: [0.5, 0]}
  - {name: inside, point: [0.25, 0.75]}
point_loads:
  - {point: [0, 0.5], force: [1, 0]}
fixed_points:
  - {point: [1, 0]}
)");
  EXPECT_EQ(scene.model.monitors.size(), 3u);
  EXPECT_EQ(scene.model.point_loads.size(), 1u);
  EXPECT_EQ(scene.model.fixed_points.size(), 1u);
}

TEST_F(SceneTest, TimeFunctionsOfEveryKind)
{
  write("data/pulse.csv", "# a header line\ntime [s], ignored, force factor\n"
                          "0, 9, 0\n\n0.5, 9, 2\n1.0, 9, 0\n");
  const Scene scene = read(std::string(minimal_scene) + R"(point_loads:
  - {point: [0.5, 0.5], force: [1, 0], time_function: {type: constant, value: 3}}
  - point: [0.5, 0.5]
    force: [1, 0]
    time_function: {type: sine_pulse, frequency: 10, cycles: 2, amplitude: 5, start: 1}
  - point: [0.5, 0.5]
    force: [1, 0]
    time_function: {type: table, points: [[0, 0], [1, 10], [3, 30]]}
  - point: [0.5, 0.5]
    force: [1, 0]
    time_function: {type: csv, file: data/pulse.csv, time_column: 0, value_column: 2,
                    skip_rows: 2}
)");
  const auto& loads = scene.model.point_loads;
  ASSERT_EQ(loads.size(), 4u);
  EXPECT_EQ(loads[0].time_function.value(7.0), 3.0);
  const TimeFunction& sine = loads[1].time_function;
  EXPECT_EQ(sine.value(0.99), 0.0);
  EXPECT_NEAR(sine.value(1.025), 5.0, 1e-9);
  EXPECT_NEAR(sine.value(1.125), 5.0, 1e-9); // second cycle
  EXPECT_EQ(sine.value(1.25), 0.0);
  EXPECT_NEAR(loads[2].time_function.value(2.0), 20.0, 1e-12);
  EXPECT_EQ(loads[2].time_function.value(5.0), 30.0);
  const TimeFunction& csv = loads[3].time_function;
  EXPECT_NEAR(csv.value(0.25), 1.0, 1e-12);
  EXPECT_NEAR(csv.value(0.5), 2.0, 1e-12);
  EXPECT_NEAR(csv.value(0.75), 1.0, 1e-12);
  EXPECT_NEAR(csv.characteristic_frequency(), 2.0, 1e-12);
}

TEST_F(SceneTest, CsvPathsAreRelativeToTheSceneFile)
{
  write("deep/folder/data/f.csv", "0,1\n1,2\n");
  const std::string file =
      write("deep/folder/scene.yaml",
            std::string(minimal_scene) +
                "point_loads:\n  - {point: [0, 0], force: [1, 0], time_function: {type: csv, file: "
                "data/f.csv}}\n");
  const Scene scene = read_scene(file);
  EXPECT_NEAR(scene.model.point_loads[0].time_function.value(0.5), 1.5, 1e-12);
}

// The fuzz harness's entry point (tests/fuzz): a scene's text, read as if from a file that need
// not exist, its relative paths starting beside that file and its errors naming it.
TEST_F(SceneTest, TextIsReadAsIfFromItsFile)
{
  write("data/f.csv", "0,1\n1,2\n");
  const std::string file = (directory / "not_written.yaml").string();
  const Scene scene = read_scene_text(
      std::string(minimal_scene) +
          "point_loads:\n  - {point: [0, 0], force: [1, 0], time_function: {type: csv, file: "
          "data/f.csv}}\n",
      file, {{"time.dt", "2e-4"}});
  EXPECT_EQ(scene.name, "not_written");
  EXPECT_EQ(scene.model.time.dt, 2e-4);
  EXPECT_NEAR(scene.model.point_loads[0].time_function.value(0.5), 1.5, 1e-12);
  try
  {
    read_scene_text("materials:\n  rock: {density: 1\nblocks: []\n", file);
    FAIL() << "no InputError";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("not_written.yaml:3: YAML syntax error"),
              std::string::npos)
        << e.what();
  }
}

// ---- Boundaries -----------------------------------------------------------------------------

/// Three by two unit squares (blocks 0 to 5, row by row) and the boundaries in `boundaries`.
std::string grid_scene_with_boundaries(const std::string& boundaries)
{
  return replaced(minimal_scene, "vertices: [[0, 0], [1, 0], [1, 1], [0, 1]]",
                  "grid: {origin: [0, 0], cell_size: [1, 1], count: [3, 2]}") +
         "boundaries:\n" + boundaries;
}

TEST_F(SceneTest, EveryBoundarySelectorIsRead)
{
  const Scene scene = read(grid_scene_with_boundaries(
      "  - {type: vb1, edges: [[2, 1], [5, 1]]}\n"
      "  - type: vb2\n"
      "    impedance: effective\n"
      "    a_n: 0.5\n"
      "    a_t: 2\n"
      "    on_line: {point: [0, 0], direction: [3, 0]}\n"
      "  - {type: dashpot, outer: true}\n"
      "  - {type: free, on_line: {point: [0, 2], direction: [-1, 1e-300]}}\n"));
  const std::vector<dda::BoundaryDescription>& b = scene.model.boundaries;
  ASSERT_EQ(b.size(), 4u);

  EXPECT_EQ(b[0].type, dda::BoundaryType::vb1);
  EXPECT_EQ(b[0].impedance, dda::ImpedanceKind::textbook); // defaults
  EXPECT_EQ(b[0].a_n, 1.0);
  EXPECT_EQ(b[0].a_t, 1.0);
  const std::vector<std::pair<std::size_t, std::size_t>> edges = {{2, 1}, {5, 1}};
  EXPECT_EQ(b[0].edges, edges);
  EXPECT_FALSE(b[0].on_line);
  EXPECT_FALSE(b[0].outer);
  EXPECT_EQ(b[0].origin, "boundaries[0]");

  EXPECT_EQ(b[1].type, dda::BoundaryType::vb2);
  EXPECT_EQ(b[1].impedance, dda::ImpedanceKind::effective);
  EXPECT_EQ(b[1].a_n, 0.5);
  EXPECT_EQ(b[1].a_t, 2.0);
  EXPECT_TRUE(b[1].on_line);
  EXPECT_EQ(b[1].line_point, dda::Point(0, 0));
  EXPECT_EQ(b[1].line_direction, dda::Vector2(1, 0)); // normalized
  EXPECT_TRUE(b[1].edges.empty());
  EXPECT_FALSE(b[1].outer);

  EXPECT_EQ(b[2].type, dda::BoundaryType::dashpot);
  EXPECT_TRUE(b[2].outer);
  EXPECT_FALSE(b[2].on_line);
  EXPECT_TRUE(b[2].edges.empty());

  EXPECT_EQ(b[3].type, dda::BoundaryType::free);
  EXPECT_NEAR(b[3].line_direction.norm(), 1.0, 1e-15); // tiny but non-zero is a direction
  EXPECT_EQ(b[3].line_direction.x(), -1.0);
}

// Issue 7: blocks without an explicit initial stress start with the in-situ stress at their
// centroid; a viscous boundary may carry an incident wave.
TEST_F(SceneTest, InSituStressAndBoundaryInputAreRead)
{
  const Scene scene =
      read(replaced(grid_scene_with_boundaries("  - type: dashpot\n"
                                               "    on_line: {point: [0, 0], direction: [1, 0]}\n"
                                               "    input: {type: p, velocity: {type: sine_pulse, "
                                               "amplitude: 0.1, frequency: 50}}\n"),
                    "  - material: rock\n",
                    "  - material: rock\n"
                    "    vertices: [[0, 3], [1, 3], [1, 4], [0, 4]]\n"
                    "    initial_stress: [1, 2, 3]\n"
                    "  - material: rock\n") +
           "in_situ_stress:\n"
           "  stress: [-1e6, -2e6, 1e5]\n"
           "  stress_gradient: [1e4, 2e4, 0]\n"
           "  reference_y: 4\n");
  const dda::InSituStress& s = scene.model.in_situ_stress;
  EXPECT_EQ(s.stress, dda::Voigt(-1e6, -2e6, 1e5));
  EXPECT_EQ(s.gradient, dda::Voigt(1e4, 2e4, 0));
  EXPECT_EQ(s.reference_y, 4.0);
  ASSERT_EQ(scene.model.blocks.size(), 7u);
  EXPECT_EQ(scene.model.blocks[0].initial_stress, dda::Voigt(1, 2, 3)); // explicit
  // Grid cell (1, 1): centroid (1.5, 1.5), 2.5 m below reference_y.
  const dda::Voigt expected(-1e6 - 2.5e4, -2e6 - 5e4, 1e5);
  EXPECT_NEAR((scene.model.blocks[5].initial_stress - expected).norm(), 0.0, 1e-6);
  const dda::BoundaryDescription& b = scene.model.boundaries[0];
  EXPECT_TRUE(b.has_input);
  EXPECT_EQ(b.input.type, dda::BoundaryInput::Type::p);
  EXPECT_NEAR(b.input.velocity.value(0.005), 0.1, 1e-12);
}

TEST_F(SceneTest, EdgeIndicesCountGridCellsAndTheAnticlockwisePolygon)
{
  // A clockwise triangle after a 2-cell grid: block 2, its edges numbered anticlockwise.
  const Scene scene =
      read(replaced(minimal_scene, "    vertices: [[0, 0], [1, 0], [1, 1], [0, 1]]\n",
                    "    grid: {origin: [0, 0], cell_size: [1, 1], count: [2, 1]}\n"
                    "  - material: rock\n"
                    "    vertices: [[2, 0], [2, 1], [3, 0]]\n") +
           "boundaries: [{type: vb1, edges: [[2, 2]]}]\n");
  ASSERT_EQ(scene.model.blocks.size(), 3u);
  EXPECT_EQ(scene.model.boundaries[0].edges.front(),
            std::make_pair(std::size_t{2}, std::size_t{2}));
  // The triangle is stored reversed, (3, 0) (2, 1) (2, 0): its edge 2 runs from (2, 0) to (3, 0).
  const std::vector<dda::Point> triangle = {dda::Point(3, 0), dda::Point(2, 1), dda::Point(2, 0)};
  EXPECT_EQ(scene.model.blocks[2].vertices, triangle);
  EXPECT_NE(error_of(replaced(minimal_scene, "    vertices: [[0, 0], [1, 0], [1, 1], [0, 1]]\n",
                              "    vertices: [[2, 0], [2, 1], [3, 0]]\n") +
                     "boundaries: [{type: vb1, edges: [[0, 3]]}]\n")
                .find("key 'boundaries[0].edges[0]' = '[0, 3]': edge index 3 is out of range: "
                      "block 0 (blocks[0]) has 3 edges, expected 0 to 2"),
            std::string::npos);
}

TEST_F(SceneTest, BoundaryProblemsAreNamed)
{
  const auto message = [&](const std::string& boundaries)
  { return error_of(grid_scene_with_boundaries(boundaries)); };
  const auto expect_in = [](const std::string& m, const std::string& expected)
  { EXPECT_NE(m.find(expected), std::string::npos) << m << "\n  expected: " << expected; };

  expect_in(message("  - {type: vb_1, outer: true}\n"),
            "scene.yaml:8: key 'boundaries[0].type' = 'vb_1': expected one of 'free', 'vb1', "
            "'vb2', 'dashpot'; did you mean 'vb1'?");
  expect_in(message("  - {outer: true}\n"),
            "key 'boundaries[0].type': missing required key: expected one of 'free', 'vb1', "
            "'vb2', 'dashpot'");
  expect_in(message("  - {type: vb1, impedance: matched, outer: true}\n"),
            "key 'boundaries[0].impedance' = 'matched': expected one of 'textbook', 'effective'");
  expect_in(message("  - {type: vb1, a_n: 0, outer: true}\n"),
            "key 'boundaries[0].a_n' = '0': expected a number > 0");
  expect_in(message("  - {type: vb1, a_t: -1, outer: true}\n"),
            "key 'boundaries[0].a_t' = '-1': expected a number > 0");
  expect_in(message("  - {type: vb1, edge: [[0, 0]]}\n"),
            "key 'boundaries[0].edge': unknown key; did you mean 'edges'?");

  // Exactly one selector.
  const std::string allowed = "Allowed keys here: type, impedance, a_n, a_t, edges, on_line, outer";
  const std::string none = message("  - {type: vb1, outer: true}\n  - {type: vb1}\n");
  expect_in(none, "scene.yaml:9: key 'boundaries[1]': no edges selected: expected exactly one of "
                  "'edges: [[block, edge], ...]', 'on_line: {point: [x, y], direction: [dx, dy]}' "
                  "or 'outer: true'");
  expect_in(none, allowed);
  expect_in(message("  - {type: vb1, outer: false}\n"), "key 'boundaries[0]': no edges selected");
  const std::string two =
      message("  - {type: vb1, edges: [[0, 0]], on_line: {point: [0, 0], direction: [1, 0]}}\n");
  expect_in(two, "key 'boundaries[0]': more than one selector ('edges', 'on_line'): expected "
                 "exactly one of");
  expect_in(two, allowed);
  expect_in(message("  - {type: vb1, edges: [[0, 0]], on_line: {point: [0, 0], direction: [1, "
                    "0]}, outer: true}\n"),
            "more than one selector ('edges', 'on_line', 'outer: true')");

  // Edges: well-formed, in range, once each.
  expect_in(message("  - {type: vb1, edges: [[6, 0]]}\n"),
            "key 'boundaries[0].edges[0]' = '[6, 0]': block index 6 is out of range: expected 0 "
            "to 5 (the 6 blocks of the scene, grid cells counted one by one)");
  expect_in(message("  - {type: vb1, edges: [[0, 0], [5, 4]]}\n"),
            "key 'boundaries[0].edges[1]' = '[5, 4]': edge index 4 is out of range: block 5 "
            "(blocks[0] (grid cell 2, 1)) has 4 edges, expected 0 to 3");
  expect_in(message("  - {type: vb1, edges: [[1, 0], [2, 3], [1, 0]]}\n"),
            "key 'boundaries[0].edges[2]' = '[1, 0]': duplicate edge (also edges[0])");
  expect_in(message("  - {type: vb1, edges: [[0, -1]]}\n"),
            "key 'boundaries[0].edges[0]' = '[0, -1]': expected a pair of integers in a non-empty "
            "list of [integer, integer] pairs each >= 0");
  expect_in(message("  - {type: vb1, edges: [[0, 1.5]]}\n"), "expected a pair of integers");
  expect_in(message("  - {type: vb1, edges: [0, 1]}\n"), "expected a pair of integers");
  expect_in(message("  - {type: vb1, edges: []}\n"),
            "key 'boundaries[0].edges' = '[]': expected a non-empty list of [integer, integer] "
            "pairs each >= 0");

  // Lines: a point and a non-zero direction.
  expect_in(message("  - {type: vb1, on_line: {point: [0, 0], direction: [0, 0]}}\n"),
            "key 'boundaries[0].on_line.direction' = '[0, 0]': expected a non-zero direction");
  expect_in(message("  - {type: vb1, on_line: {point: [0, 0]}}\n"),
            "key 'boundaries[0].on_line.direction': missing required key");
  expect_in(message("  - {type: vb1, on_line: {point: [0, 0], direction: [1, 0], normal: [0, "
                    "1]}}\n"),
            "key 'boundaries[0].on_line.normal': unknown key. Allowed keys here: point, "
            "direction");
  expect_in(message("  - {type: vb1, on_line: [0, 0]}\n"),
            "key 'boundaries[0].on_line' = '[0, 0]': expected a map with keys 'point', "
            "'direction'");
}

TEST_F(SceneTest, BoundaryOverridesNameTheCommandLine)
{
  const std::string scene = grid_scene_with_boundaries("  - {type: free, edges: [[0, 0]]}\n");
  EXPECT_EQ(read(scene, {parse_override("boundaries.0.type=dashpot")}).model.boundaries[0].type,
            dda::BoundaryType::dashpot);
  EXPECT_EQ(error_of(scene, {parse_override("boundaries.0.a_n=0")}),
            "command line --set boundaries.0.a_n=0: key 'boundaries[0].a_n' = '0': expected a "
            "number > 0");
  EXPECT_NE(error_of(scene, {parse_override("boundaries.0.edges=[[0, 9]]")})
                .find("command line --set boundaries.0.edges=[[0, 9]]: key "
                      "'boundaries[0].edges[0]' = '[0, 9]': edge index 9 is out of range"),
            std::string::npos);
}

// ---- Error messages -------------------------------------------------------------------------

TEST_F(SceneTest, MessagesNameFileLineKeyValueAndExpectation)
{
  const std::string message = error_of(replaced(minimal_scene, "density: 2650", "density: -1"));
  const std::string file = (directory / "scene.yaml").string();
  EXPECT_EQ(message,
            file + ":2: key 'materials.rock.density' = '-1': expected a number > 0 [kg/m^3]");
}

TEST_F(SceneTest, UnknownKeysAreRejectedWithTheClosestAllowedKey)
{
  const std::string m = error_of(replaced(minimal_scene, "density", "densty"));
  EXPECT_NE(m.find(":2: key 'materials.rock.densty': unknown key; did you mean 'density'?"),
            std::string::npos)
      << m;
  EXPECT_NE(m.find("density, youngs_modulus, poisson_ratio"), std::string::npos) << m;

  const std::string top = error_of(std::string(minimal_scene) + "gravty: [0, -9.81]\n");
  EXPECT_NE(top.find("key 'gravty': unknown key; did you mean 'gravity'?"), std::string::npos)
      << top;

  // Far from every allowed key: no suggestion, only the list.
  const std::string far = error_of(std::string(minimal_scene) + "output: {zzzzzz: 1}\n");
  EXPECT_NE(far.find("key 'output.zzzzzz': unknown key. Allowed keys here: directory, interval, "
                     "history_every"),
            std::string::npos)
      << far;
}

TEST_F(SceneTest, DuplicateKeysAreRejected)
{
  const std::string m = error_of(replaced(minimal_scene, "dt: 1e-4", "dt: 1e-4, dt: 2e-4"));
  EXPECT_NE(m.find("key 'time.dt': duplicate key"), std::string::npos) << m;
}

TEST_F(SceneTest, WrongTypesSayWhatWasExpected)
{
  const auto expect =
      [&](const std::string& original, const std::string& replacement, const std::string& expected)
  {
    const std::string m = error_of(replaced(minimal_scene, original, replacement));
    EXPECT_NE(m.find(expected), std::string::npos) << m;
  };
  expect("youngs_modulus: 50e9", "youngs_modulus: 50 GPa",
         "key 'materials.rock.youngs_modulus' = '50 GPa': expected a number > 0 [Pa]");
  expect("youngs_modulus: 50e9", "youngs_modulus: [50e9]", "expected a number > 0 [Pa]");
  expect("youngs_modulus: 50e9", "youngs_modulus: .inf", "expected a number > 0 [Pa]");
  expect("poisson_ratio: 0.25", "poisson_ratio: 0.5", "expected a number in [0, 0.5)");
  expect("poisson_ratio: 0.25", "poisson_ratio: -0.1", "expected a number in [0, 0.5)");
  expect("time: {dt: 1e-4, end_time: 0.01}", "time: 3",
         "key 'time' = '3': expected a map with keys 'dt', 'end_time', 'integrator'");
  expect("  - material: rock", "  - material: rock\n    initial_velocity: [1, 2, 3]",
         "key 'blocks[0].initial_velocity' = '[1, 2, 3]': expected [x, y]: a list of 2 numbers "
         "[m/s]");
  expect("[[0, 0], [1, 0], [1, 1], [0, 1]]", "[[0, 0], [1, 0], [1, one], [0, 1]]",
         "key 'blocks[0].vertices[2]' = '[1, one]': expected a pair of numbers");
  expect("blocks:\n  - material: rock\n    vertices: [[0, 0], [1, 0], [1, 1], [0, 1]]",
         "blocks: {material: rock}", "key 'blocks' = '{material: rock}': expected a list of maps");
  expect("time: {dt: 1e-4, end_time: 0.01}",
         "time: {dt: 1e-4, end_time: 0.01}\noutput: {history_every: 0.5}",
         "key 'output.history_every' = '0.5': expected an integer >= 1");
  expect("time: {dt: 1e-4, end_time: 0.01}",
         "time: {dt: 1e-4, end_time: 0.01}\nanalysis: {plane: strian}",
         "expected one of 'stress', 'strain'; did you mean 'strain'?");
  expect("time: {dt: 1e-4, end_time: 0.01}",
         "time: {dt: 1e-4, end_time: 0.01}\njoint_materials: {j: {normal_stiffness: 1, "
         "bonded: maybe}}",
         "key 'joint_materials.j.bonded' = 'maybe': expected true or false");
}

TEST_F(SceneTest, MissingRequiredKeysAreNamed)
{
  const std::string m = error_of(replaced(minimal_scene, "dt: 1e-4, ", ""));
  EXPECT_NE(m.find(":6: key 'time.dt': missing required key: expected a number > 0 [s]"),
            std::string::npos)
      << m;
  const std::string no_blocks =
      error_of("materials:\n  rock: {density: 1, youngs_modulus: 1, poisson_ratio: 0}\n"
               "time: {dt: 1, end_time: 1}\n");
  EXPECT_NE(no_blocks.find(
                "key 'blocks': expected at least one block (or a `rock_mass` or a `far_field`)"),
            std::string::npos)
      << no_blocks;
  const std::string no_shape =
      error_of(replaced(minimal_scene, "    vertices: [[0, 0], [1, 0], [1, 1], [0, 1]]\n", ""));
  EXPECT_NE(no_shape.find("key 'blocks[0]': missing key: give 'vertices' or 'grid'"),
            std::string::npos)
      << no_shape;
}

TEST_F(SceneTest, MissingFilesAndSyntaxErrors)
{
  try
  {
    read_scene((directory / "absent.yaml").string());
    FAIL() << "no InputError";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("absent.yaml: cannot open the scene file"),
              std::string::npos)
        << e.what();
  }
  const std::string m = error_of("materials:\n  rock: {density: 1\nblocks: []\n");
  EXPECT_NE(m.find("scene.yaml:3: YAML syntax error"), std::string::npos) << m;
}

TEST_F(SceneTest, BadPolygons)
{
  const std::string open =
      error_of(replaced(minimal_scene, "[[0, 0], [1, 0], [1, 1], [0, 1]]", "[[0, 0], [1, 1]]"));
  EXPECT_NE(open.find("key 'blocks[0].vertices' = '[[0, 0], [1, 1]]': polygon is not closed: "
                      "needs at least 3 distinct vertices"),
            std::string::npos)
      << open;
  const std::string bow_tie = error_of(replaced(minimal_scene, "[[0, 0], [1, 0], [1, 1], [0, 1]]",
                                                "[[0, 0], [1, 1], [1, 0], [0, 1]]"));
  EXPECT_NE(bow_tie.find("blocks[0] is self-intersecting"), std::string::npos) << bow_tie;
  const std::string flat = error_of(
      replaced(minimal_scene, "[[0, 0], [1, 0], [1, 1], [0, 1]]", "[[0, 0], [1, 0], [2, 0]]"));
  EXPECT_NE(flat.find("self-intersecting"), std::string::npos) << flat;
  const std::string huge_grid =
      error_of(replaced(minimal_scene, "vertices: [[0, 0], [1, 0], [1, 1], [0, 1]]",
                        "grid: {origin: [0, 0], cell_size: [1, 1], count: [2000, 2000]}"));
  EXPECT_NE(huge_grid.find("key 'blocks[0].grid.count'"), std::string::npos) << huge_grid;
  const std::string bad_cell =
      error_of(replaced(minimal_scene, "vertices: [[0, 0], [1, 0], [1, 1], [0, 1]]",
                        "grid: {origin: [0, 0], cell_size: [1, 0], count: [2, 2]}"));
  EXPECT_NE(bad_cell.find("key 'blocks[0].grid.cell_size' = '[1, 0]': expected [x, y]: a list of 2 "
                          "numbers each > 0 [m]"),
            std::string::npos)
      << bad_cell;
}

TEST_F(SceneTest, OverlappingBlocksAreNamed)
{
  // A triangle poking into the second cell of a grid.
  const std::string m = error_of(
      replaced(minimal_scene, "vertices: [[0, 0], [1, 0], [1, 1], [0, 1]]",
               "grid: {origin: [0, 0], cell_size: [1, 1], count: [3, 1]}\n  - material: rock\n"
               "    vertices: [[1.5, 0.5], [2.5, 2], [0.5, 2]]"));
  EXPECT_NE(m.find("key 'blocks[1]': blocks overlap: blocks[0] (grid cell 1, 0) and blocks[1] "
                   "share an area of"),
            std::string::npos)
      << m;
}

TEST_F(SceneTest, NamesMustBeDefinedAndUnique)
{
  const std::string material =
      error_of(replaced(minimal_scene, "  - material: rock", "  - material: rok"));
  EXPECT_NE(material.find("key 'blocks[0].material' = 'rok': unknown material 'rok'; did you mean "
                          "'rock'? (defined: rock)"),
            std::string::npos)
      << material;
  const std::string joint = error_of(std::string(minimal_scene) + "joints: {default: glue}\n");
  EXPECT_NE(joint.find("unknown joint material 'glue' (none is defined)"), std::string::npos)
      << joint;
  const std::string pair = error_of(std::string(minimal_scene) +
                                    "joint_materials: {glue: {normal_stiffness: 1}}\n"
                                    "joints: {pairs: [{materials: [rock, rock], joint: glu}]}\n");
  EXPECT_NE(pair.find("key 'joints.pairs[0].joint' = 'glu': unknown joint material 'glu'; did "
                      "you mean 'glue'?"),
            std::string::npos)
      << pair;
  const std::string monitors = error_of(
      std::string(minimal_scene) + "monitors:\n  - {name: a, point: [0, 0]}\n"
                                   "  - {name: b, point: [0, 0]}\n  - {name: a, point: [1, 1]}\n");
  EXPECT_NE(monitors.find(":10: key 'monitors[2].name' = 'a': duplicate monitor name (also used by "
                          "monitors[0])"),
            std::string::npos)
      << monitors;
}

TEST_F(SceneTest, PointsOutsideEveryBlockAreNamed)
{
  const auto expect = [&](const std::string& section, const std::string& key)
  {
    const std::string m = error_of(std::string(minimal_scene) + section);
    EXPECT_NE(m.find("key '" + key +
                     "' = '[1.5, 0.5]': the point [1.5, 0.5] lies outside every "
                     "block"),
              std::string::npos)
        << m;
  };
  expect("point_loads:\n  - {point: [1.5, 0.5], force: [1, 0]}\n", "point_loads[0].point");
  expect("fixed_points:\n  - {point: [0, 0]}\n  - {point: [1.5, 0.5]}\n", "fixed_points[1].point");
  expect("monitors:\n  - {name: m, point: [1.5, 0.5]}\n", "monitors[0].point");
}

TEST_F(SceneTest, TimeSettingsAreChecked)
{
  const std::string zero = error_of(replaced(minimal_scene, "dt: 1e-4", "dt: 0"));
  EXPECT_NE(zero.find("key 'time.dt' = '0': expected a number > 0 [s]"), std::string::npos) << zero;
  const std::string short_run =
      error_of(replaced(minimal_scene, "end_time: 0.01", "end_time: 0.5e-4"));
  EXPECT_NE(short_run.find("key 'time.end_time' = '0.5e-4': expected end_time >= dt = 0.0001 s"),
            std::string::npos)
      << short_run;
  // end_time = dt is allowed: one step.
  EXPECT_EQ(read(replaced(minimal_scene, "end_time: 0.01", "end_time: 1e-4")).model.time.end_time,
            1e-4);
}

// A CSV "file" that is a named pipe is refused at once (opening it would wait for a writer).
TEST_F(SceneTest, CsvThatIsNotARegularFileIsRefusedAtOnce)
{
  const std::string load =
      "point_loads:\n  - {point: [0, 0], force: [1, 0], time_function: {type: csv, file: p.csv}}\n";
  ASSERT_EQ(mkfifo((directory / "p.csv").c_str(), 0600), 0);
  const auto start = std::chrono::steady_clock::now();
  const std::string pipe = error_of(std::string(minimal_scene) + load);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
  EXPECT_NE(pipe.find("cannot open CSV file '" + (directory / "p.csv").string() +
                      "': expected a regular file"),
            std::string::npos)
      << pipe;
}

TEST_F(SceneTest, CsvProblemsNameTheFileTheRowAndTheKey)
{
  const std::string load =
      "point_loads:\n  - {point: [0, 0], force: [1, 0], time_function: {type: csv, file: f.csv}}\n";
  const std::string csv = (directory / "f.csv").string();

  const std::string missing = error_of(std::string(minimal_scene) + load);
  EXPECT_NE(missing.find(":8: key 'point_loads[0].time_function.file' = 'f.csv': cannot open CSV "
                         "file '" +
                         csv + "'"),
            std::string::npos)
      << missing;

  write("f.csv", "0, 1\n0.1, 2\n0.2, x2\n");
  const std::string bad = error_of(std::string(minimal_scene) + load);
  EXPECT_NE(bad.find("CSV file '" + csv + "' row 3: column 1 is 'x2', expected a number"),
            std::string::npos)
      << bad;
  EXPECT_NE(bad.find("key 'point_loads[0].time_function.file'"), std::string::npos) << bad;

  write("f.csv", "0, 1\n0.1\n");
  const std::string narrow = error_of(std::string(minimal_scene) + load);
  EXPECT_NE(narrow.find("row 2: found 1 column(s), expected at least 2"), std::string::npos)
      << narrow;

  write("f.csv", "0, 1\n0.1, 2\n0.1, 3\n");
  const std::string repeated = error_of(std::string(minimal_scene) + load);
  EXPECT_NE(repeated.find("row 3: time 0.1 does not increase strictly"), std::string::npos)
      << repeated;

  write("f.csv", "\n \n");
  const std::string empty = error_of(std::string(minimal_scene) + load);
  EXPECT_NE(empty.find("has no data rows"), std::string::npos) << empty;
}

// ---- Overrides ------------------------------------------------------------------------------

// ---- Rock mass ------------------------------------------------------------------------------

/// A 20 m x 10 m rock mass with two joint sets and a circular opening, after one explicit block.
const char* rock_mass_scene = R"(materials:
  rock: {density: 2650, youngs_modulus: 20e9, poisson_ratio: 0.25}
  concrete: {density: 2400, youngs_modulus: 30e9, poisson_ratio: 0.2}
joint_materials:
  bonded: {normal_stiffness: 2e11}
joints: {default: bonded}
blocks:
  - material: concrete
    vertices: [[9, 4], [11, 4], [11, 6], [9, 6]]
rock_mass:
  material: rock
  region:
    rectangle: {lower: [0, 0], upper: [20, 10]}
  joint_sets:
    - {dip: 0, spacing: 2, offset: 1}
    - {dip: 90, spacing: 2.5, trace_length: 6, bridge: 2}
  openings:
    - circle: {center: [10, 5], radius: 2}
time: {dt: 1e-4, end_time: 0.01}
)";

TEST_F(SceneTest, RockMassBlocksFollowTheBlocks)
{
  const Scene scene = read(rock_mass_scene);
  const dda::ModelDescription& m = scene.model;
  ASSERT_TRUE(scene.rock_mass);
  EXPECT_EQ(scene.rock_mass->first_block, 1u);
  ASSERT_EQ(m.blocks.size(), 1 + scene.rock_mass->statistics.n_blocks);
  EXPECT_EQ(m.blocks[0].origin, "blocks[0]");
  EXPECT_EQ(m.blocks[0].material, 1u);
  EXPECT_EQ(m.blocks[1].origin, "rock_mass block 0");
  EXPECT_EQ(m.blocks[1].material, 0u);
  // The lining block sits in the opening; the rock mass's blocks are its strips (y = 1, 3, ...)
  // cut by the vertical traces and the opening.
  EXPECT_GT(m.blocks.size(), 10u);

  // Points of monitors and loads may lie in generated blocks.
  const Scene monitored =
      read(std::string(rock_mass_scene) + "monitors:\n  - {name: a, point: [1, 9]}\n");
  EXPECT_EQ(monitored.model.monitors.size(), 1u);

  // The same seed, the same blocks; --set changes it.
  const Scene again = read(rock_mass_scene);
  EXPECT_EQ(again.model.blocks.back().vertices, m.blocks.back().vertices);
  const Scene reported =
      read(rock_mass_scene, {{"rock_mass.slivers", "report"}, {"rock_mass.min_block_area", "3"}});
  EXPECT_FALSE(reported.rock_mass->slivers.empty());
  for (const dda::Sliver& sliver : reported.rock_mass->slivers)
  {
    EXPECT_GE(sliver.block, 1u);
    EXPECT_LT(sliver.area, 3.0);
  }
}

TEST_F(SceneTest, RockMassProblemsAreNamed)
{
  const auto expect_error =
      [&](const std::string& original, const std::string& replacement, const std::string& expected)
  {
    const std::string m = error_of(replaced(rock_mass_scene, original, replacement));
    EXPECT_NE(m.find(expected), std::string::npos) << m;
  };
  expect_error("{dip: 0, spacing: 2, offset: 1}", "{dip: 0, spacing: -2, offset: 1}",
               "scene.yaml:15: key 'rock_mass.joint_sets[0].spacing' = '-2': expected a number "
               "> 0 [m]");
  expect_error("trace_length: 6, bridge: 2", "trace_length: 6",
               "key 'rock_mass.joint_sets[1].trace_length' = '6': a trace length needs a "
               "`bridge`");
  expect_error("center: [10, 5], radius: 2", "center: [19, 5], radius: 2",
               "scene.yaml:18: key 'rock_mass.openings[0].circle' = '{center: [19, 5], radius: "
               "2}': the opening reaches outside the region");
  expect_error("- circle: {center: [10, 5], radius: 2}", "- {}",
               "key 'rock_mass.openings[0]': no shape given: expected exactly one of");
  expect_error("    rectangle: {lower: [0, 0], upper: [20, 10]}",
               "    rectangle: {lower: [0, 0], upper: [-20, 10]}",
               "key 'rock_mass.region.rectangle.upper' = '[-20, 10]': expected upper > lower");
  expect_error("    rectangle: {lower: [0, 0], upper: [20, 10]}",
               "    polygon: [[0, 0], [20, 10], [20, 0], [0, 10]]",
               "polygon of rock_mass.region is self-intersecting");
  expect_error("{dip: 0, spacing: 2, offset: 1}", "{dip: 0, spacing: 2, ofset: 1}",
               "key 'rock_mass.joint_sets[0].ofset': unknown key; did you mean 'offset'?");
  expect_error("  material: rock\n  region", "  material: granite\n  region",
               "key 'rock_mass.material' = 'granite': unknown material 'granite'");
  expect_error("  openings:", "  joints:\n    - {from: [1, 1], to: [1, 1]}\n  openings:",
               "key 'rock_mass.joints[0].to' = '[1, 1]': the joint ends where it starts");
  expect_error("  openings:", "  seed: -1\n  openings:",
               "key 'rock_mass.seed' = '-1': expected an integer >= 0");
  // The lining block moved to overlap the rock.
  expect_error("[[9, 4], [11, 4], [11, 6], [9, 6]]", "[[14, 4], [16, 4], [16, 6], [14, 6]]",
               "blocks overlap: blocks[0] and rock_mass block");
}

TEST(SceneOverride, ParsesAtTheFirstEqualsSign)
{
  const Override o = parse_override("time.dt=1e-4");
  EXPECT_EQ(o.path, "time.dt");
  EXPECT_EQ(o.value, "1e-4");
  const Override n = parse_override("name=a=b");
  EXPECT_EQ(n.path, "name");
  EXPECT_EQ(n.value, "a=b");
  EXPECT_THROW(parse_override("time.dt"), InputError);
  EXPECT_THROW(parse_override("=1"), InputError);
  try
  {
    parse_override("gravity");
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("command line --set gravity: expected path.to.key=value"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(SceneTest, OverridesChangeTheSceneBeforeValidation)
{
  const std::string scene = std::string(minimal_scene) +
                            "joint_materials: {glue: {normal_stiffness: 1e9}}\n"
                            "materials_unused: 0\n";
  const std::vector<Override> overrides = {
      parse_override("time.dt=2e-4"),
      parse_override("gravity=[0, -9.81]"),
      parse_override("blocks.0.material=granite"),
      parse_override("materials.granite={density: 2700, youngs_modulus: 60e9, "
                     "poisson_ratio: 0.2}"),
      parse_override("blocks.0.vertices.2=[1, 2]"),
      parse_override("joint_materials.glue.friction_angle=30"),
      parse_override("solver.type=klu"), // a section the file does not have
      parse_override("output.interval=1e-3")};
  // The unknown top-level key in the file is an error even with overrides ...
  EXPECT_NE(error_of(scene, overrides).find("key 'materials_unused': unknown key"),
            std::string::npos);
  // ... and without it, every override lands.
  const Scene s = read(replaced(scene, "materials_unused: 0\n", ""), overrides);
  const dda::ModelDescription& m = s.model;
  EXPECT_EQ(m.time.dt, 2e-4);
  EXPECT_EQ(m.gravity, dda::Vector2(0, -9.81));
  ASSERT_EQ(m.materials.size(), 2u);
  EXPECT_EQ(m.materials[m.blocks[0].material].name, "granite");
  EXPECT_EQ(m.materials[1].density, 2700.0);
  EXPECT_NEAR(dda::signed_area(m.blocks[0].vertices), 1.5, 1e-12);
  EXPECT_EQ(m.joint_materials[0].friction_angle, 30.0);
  EXPECT_EQ(m.solver.direct, dda::SolverKind::klu);
  EXPECT_EQ(s.output.interval, 1e-3);
}

TEST_F(SceneTest, ProblemsWithOverriddenValuesNameTheCommandLine)
{
  const auto message = [&](const std::string& argument)
  { return error_of(minimal_scene, {parse_override(argument)}); };
  EXPECT_EQ(message("time.dt=-1"),
            "command line --set time.dt=-1: key 'time.dt' = '-1': expected a number > 0 [s]");
  EXPECT_EQ(
      message("time.dtt=1e-4"),
      "command line --set time.dtt=1e-4: key 'time.dtt': unknown key; did you mean 'dt'? "
      "Allowed keys here: dt, end_time, integrator, spectral_radius, control, dt_min, cut_factor, "
      "growth_factor, reversal_tolerance");
  EXPECT_NE(message("blocks.0.vertices=[[0, 0], [1, 1]]")
                .find("command line --set blocks.0.vertices=[[0, 0], [1, 1]]: key "
                      "'blocks[0].vertices'"),
            std::string::npos);
  EXPECT_NE(message("output.extra.x=1")
                .find("command line --set output.extra.x=1: key "
                      "'output.extra': unknown key"),
            std::string::npos);
  // Problems elsewhere still name the file.
  EXPECT_NE(error_of(replaced(minimal_scene, "density: 2650", "density: 0"),
                     {parse_override("time.dt=1e-3")})
                .find("scene.yaml:2: key 'materials.rock.density'"),
            std::string::npos);
}

TEST_F(SceneTest, OverridePathsMustExist)
{
  const auto message = [&](const std::string& argument)
  { return error_of(minimal_scene, {parse_override(argument)}); };
  EXPECT_EQ(message("time.dt.x=1"),
            "command line --set time.dt.x=1: key 'time.dt' = '1e-4': cannot set 'x' inside a "
            "single value: expected a map or a list here");
  EXPECT_EQ(message("blocks.1.material=rock"),
            "command line --set blocks.1.material=rock: key 'blocks': '1' is not an index of this "
            "list of 1 item(s): expected 0 to 0");
  EXPECT_NE(message("blocks.first.material=rock").find("'first' is not an index"),
            std::string::npos);
  EXPECT_NE(message("time..dt=1").find("empty key in the path 'time..dt'"), std::string::npos);
  EXPECT_NE(message("gravity=[0,").find("command line --set gravity=[0,: cannot parse the value"),
            std::string::npos);
}

// ---- Scale ----------------------------------------------------------------------------------

TEST_F(SceneTest, TwoThousandBlocksValidateWellUnderASecond)
{
#ifdef NDEBUG
  const double slowdown = 1.0;
#else
  const double slowdown = 10.0; // unoptimised CGAL and yaml-cpp
#endif
  const auto start = std::chrono::steady_clock::now();
  const Scene grid =
      read(replaced(minimal_scene, "vertices: [[0, 0], [1, 0], [1, 1], [0, 1]]",
                    "grid: {origin: [0, 0], cell_size: [0.1, 0.1], count: [50, 40]}"));
  const double grid_seconds = seconds_since(start);
  EXPECT_EQ(grid.model.blocks.size(), 2000u);
  EXPECT_LT(grid_seconds, 0.5 * slowdown);

  // Rotated: every neighbour's bounding box overlaps, so the finer pre-check must do the work.
  const std::string listed = scene_with_listed_blocks(50, 40, 0.3);
  const auto start_listed = std::chrono::steady_clock::now();
  const Scene blocks = read(listed);
  const double listed_seconds = seconds_since(start_listed);
  EXPECT_EQ(blocks.model.blocks.size(), 2000u);
  EXPECT_LT(listed_seconds, 1.0 * slowdown);
}

// ---- Schema and reference -------------------------------------------------------------------

TEST(SceneSchema, DefaultsLieInTheirRanges)
{
  const schema::SceneSchema s;
  for (const schema::Section& section : s.sections())
    for (const schema::Key& key : section.keys)
    {
      EXPECT_FALSE(key.meaning.empty()) << section.id << "." << key.name;
      EXPECT_FALSE(key.required && !key.default_yaml.empty()) << section.id << "." << key.name;
      if (!key.section.empty())
      {
        EXPECT_TRUE(std::any_of(s.sections().begin(), s.sections().end(),
                                [&](const schema::Section& t) { return t.id == key.section; }))
            << section.id << "." << key.name << " refers to an unknown section";
      }
      if (key.default_yaml.empty())
        continue;
      const YAML::Node value = YAML::Load(key.default_yaml);
      if (key.type == schema::ValueType::number || key.type == schema::ValueType::integer)
      {
        EXPECT_TRUE(key.range.contains(value.as<double>())) << section.id << "." << key.name;
      }
      if (key.type == schema::ValueType::choice)
      {
        EXPECT_NE(std::find(key.choices.begin(), key.choices.end(), value.as<std::string>()),
                  key.choices.end())
            << section.id << "." << key.name;
      }
    }
}

TEST(SceneReference, ListsEveryKeyOfEverySection)
{
  const std::string md = scene_reference_markdown();
  const schema::SceneSchema s;
  for (const schema::Section& section : s.sections())
  {
    const std::string heading =
        section.id == schema::SceneSchema::top_level ? "## Top level" : "## `" + section.id + "`";
    const auto at = md.find("\n" + heading + "\n");
    ASSERT_NE(at, std::string::npos) << heading;
    for (const schema::Key& key : section.keys)
      EXPECT_NE(md.find("| `" + key.name + "` |", at), std::string::npos)
          << section.id << "." << key.name;
  }
  EXPECT_NE(md.find("| `density` | number | kg/m^3 | **required** | > 0 |"), std::string::npos);
  EXPECT_NE(md.find("| `poisson_ratio` | number | - | **required** | [0, 0.5) |"),
            std::string::npos);
}

TEST_F(SceneTest, TheReferenceExampleIsAValidScene)
{
  const std::string md = scene_reference_markdown();
  const auto begin = md.find("```yaml\n");
  ASSERT_NE(begin, std::string::npos);
  const auto end = md.find("```\n", begin + 8);
  ASSERT_NE(end, std::string::npos);
  const Scene scene = read(md.substr(begin + 8, end - begin - 8));
  EXPECT_EQ(scene.name, "two_blocks");
  EXPECT_EQ(scene.model.blocks.size(), 3u);
}

TEST(SceneReference, TheCommittedReferenceIsCurrent)
{
  std::ifstream in(source_dir + "/docs/scene_reference.md");
  ASSERT_TRUE(in) << "docs/scene_reference.md is missing";
  std::stringstream committed;
  committed << in.rdbuf();
  EXPECT_EQ(committed.str(), scene_reference_markdown())
      << "docs/scene_reference.md is stale; regenerate it with\n"
         "  build/ddafem scene-reference > docs/scene_reference.md";
}

} // namespace
} // namespace ddafem
