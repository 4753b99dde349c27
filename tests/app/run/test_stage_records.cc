// A scene's static stage end to end (app/run/stage_records.h): a block that cannot be in
// equilibrium is released, recorded in summary.json, and the run goes on to its dynamic stage (exit
// 0).
#include "app/run/stage_records.h"

#include "app/run/run.h"
#include "app/scene/scene.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

using namespace ddafem;

namespace
{
const std::string source_dir = DDAFEM_SOURCE_DIR;

/// Runs examples/keyblock/keyblock.yaml with a frictionless key (phi = 0: it cannot stay
/// between the abutments) through a static stage with `release` (fall | remove) and a dynamic
/// stage to `end_time` [s]; returns summary.json.
nlohmann::json run_keyblock_with_static_stage(const std::string& release, double end_time)
{
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("ddafem_test_static_stage_" + release);
  std::filesystem::create_directories(dir);
  std::ifstream example(source_dir + "/examples/keyblock/keyblock.yaml");
  std::ostringstream text;
  text << example.rdbuf() << "\nstages:\n"
       << "  - {name: settle, mode: static, dt: 1e-3, tolerance: 1e-6, max_steps: 2000, "
       << "release: " << release << "}\n"
       << "  - {name: fall, mode: dynamic, end_time: " << end_time << "}\n";
  const std::string file = (dir / "keyblock_static.yaml").string();
  std::ofstream(file) << text.str();
  const Scene scene = read_scene(file, {{"joint_materials.rough.friction_angle", "0"}});
  RunOptions options;
  options.output_directory = (dir / "out").string();
  options.quiet = true;
  std::ostringstream log;
  EXPECT_EQ(run_scene(scene, options, log), 0) << log.str();
  std::ifstream f(dir / "out" / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(f);
  std::filesystem::remove_all(dir);
  return summary;
}

const nlohmann::json& keyblock(const nlohmann::json& summary, std::size_t id)
{
  for (const nlohmann::json& b : summary.at("keyblocks").at("blocks"))
    if (b.at("id") == id)
      return b;
  throw std::runtime_error("no keyblock " + std::to_string(id));
}
} // namespace

TEST(SceneStaticStage, FrictionlessKeyIsReleasedAndFalls)
{
  const nlohmann::json s = run_keyblock_with_static_stage("fall", 0.3);
  EXPECT_EQ(s.at("status"), "completed");
  const nlohmann::json& stage = s.at("stages")[0];
  EXPECT_TRUE(stage.at("converged").get<bool>());
  EXPECT_EQ(stage.at("release"), "fall");
  ASSERT_EQ(stage.at("released").size(), 1u);
  const nlohmann::json& r = stage.at("released")[0];
  EXPECT_EQ(r.at("block"), 2);
  EXPECT_EQ(r.at("opening"), 0);
  EXPECT_NEAR(r.at("mass_kg").get<double>(), 2650.0, 1e-9);
  EXPECT_NEAR(r.at("centroid_m")[0].get<double>(), 0.0, 1e-6);
  EXPECT_NEAR(r.at("centroid_m")[1].get<double>(), 1.0, 1e-3);
  // Free in the dynamic stage: it falls between the abutments (g t^2 / 2 = 0.44 m in 0.3 s).
  EXPECT_TRUE(keyblock(s, 2).at("released").get<bool>());
  EXPECT_TRUE(keyblock(s, 2).at("fell").get<bool>());
  EXPECT_NEAR(keyblock(s, 2).at("residual_displacement_m")[1].get<double>(),
              -0.5 * 9.81 * 0.3 * 0.3, 0.01);
  EXPECT_FALSE(keyblock(s, 1).at("released").get<bool>());
  EXPECT_EQ(s.at("keyblocks").at("released"), 1);
}

// Without the key nothing holds the abutments, pushed inward by H on a frictionless base: they
// are released too (and slide towards each other in the short dynamic stage).
TEST(SceneStaticStage, RemovedKeyStaysInert)
{
  const nlohmann::json s = run_keyblock_with_static_stage("remove", 0.01);
  EXPECT_EQ(s.at("status"), "completed");
  const nlohmann::json& released = s.at("stages")[0].at("released");
  ASSERT_GE(released.size(), 1u);
  EXPECT_EQ(released[0].at("block"), 2);
  EXPECT_TRUE(keyblock(s, 2).at("released").get<bool>());
  EXPECT_LT(keyblock(s, 2).at("residual_m").get<double>(), 1e-6);
}
