// Keyblocks (app/run/keyblocks.h): the keyblocks of a rock-mass tunnel, and what summary.json
// reports for them after a run (the keyblock example with frictionless, sliding and holding
// joints). Their geometry alone is tested in tests/dda/test_keyblocks.cc.
#include "app/run/keyblocks.h"

#include "app/run/run.h"
#include "app/scene/scene.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace ddafem;
using dda::Point;

namespace
{
const std::string source_dir = DDAFEM_SOURCE_DIR;

/// Runs examples/keyblock/keyblock.yaml with the key's friction angle `phi` [deg] and returns
/// summary.json's `keyblocks` section.
nlohmann::json run_keyblock_example(const std::string& phi)
{
  const Scene scene = read_scene(source_dir + "/examples/keyblock/keyblock.yaml",
                                 {{"joint_materials.rough.friction_angle", phi}});
  RunOptions options;
  options.output_directory =
      (std::filesystem::temp_directory_path() / ("ddafem_test_keyblocks_phi" + phi)).string();
  options.quiet = true;
  std::ostringstream log;
  EXPECT_EQ(run_scene(scene, options, log), 0) << log.str();
  std::ifstream f(std::filesystem::path(options.output_directory) / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(f);
  std::filesystem::remove_all(options.output_directory);
  return summary.at("keyblocks");
}

const nlohmann::json& block(const nlohmann::json& keyblocks, std::size_t id)
{
  for (const nlohmann::json& b : keyblocks.at("blocks"))
    if (b.at("id") == id)
      return b;
  throw std::runtime_error("no keyblock " + std::to_string(id));
}

constexpr double g = 9.81;
constexpr double t_end = 0.3; // s, the example's end_time
} // namespace

TEST(Keyblocks, RockMassTunnelKeyblocksAreTheBlocksOnTheOpening)
{
  // tests/app/scenes/small_tunnel.yaml: a circle of radius 1.5 m at the origin, cut as a
  // polygon inscribed in it. Its keyblocks are exactly the blocks with a vertex on that
  // polygon, i.e. no farther than R from the centre (the rock lies outside the polygon).
  const Scene scene = read_scene(source_dir + "/tests/app/scenes/small_tunnel.yaml");
  const KeyblockRecorder recorder(scene.model);
  const KeyblockGeometry& k = recorder.get_geometry();
  std::vector<std::size_t> expected;
  for (std::size_t b = 0; b < scene.model.blocks.size(); ++b)
    for (const Point& v : scene.model.blocks[b].vertices)
      if (v.norm() <= 1.5 + 1e-9)
      {
        expected.push_back(b);
        break;
      }
  EXPECT_EQ(k.blocks, expected);
  EXPECT_GE(k.blocks.size(), 4u);
  ASSERT_EQ(k.openings.size(), 1u);
  // The opening is the excavated polygon: its area, and 2 R across within the chord tolerance.
  EXPECT_NEAR(k.openings[0].area, scene.rock_mass->statistics.excavated_area, 1e-9);
  EXPECT_NEAR(k.openings[0].size(), 3.0, 2 * 0.03);
}

TEST(KeyblockRun, FrictionlessKeyFallsFreely)
{
  // phi = 0: the key (block 2) slides down between the abutments in free fall, u = g t^2 / 2
  // (DDA's Newmark (1/2, 1) is exact for a constant acceleration); 0.44 m > 1% of the 1 m void.
  // It is not detached: the abutments still press on it (closed, sliding contacts).
  const nlohmann::json k = run_keyblock_example("0");
  const nlohmann::json& key = block(k, 2);
  EXPECT_NEAR(key.at("residual_displacement_m")[1].get<double>(), -0.5 * g * t_end * t_end, 1e-4);
  EXPECT_NEAR(key.at("peak_displacement_m").get<double>(), 0.5 * g * t_end * t_end, 1e-4);
  EXPECT_NEAR(key.at("peak_time_s").get<double>(), t_end, 1e-9);
  EXPECT_NEAR(key.at("max_slip_m").get<double>(), 0.5 * g * t_end * t_end, 1e-3);
  EXPECT_TRUE(key.at("fell").get<bool>());
  EXPECT_FALSE(key.at("detached").get<bool>());
  EXPECT_EQ(k.at("keyblock_peak_id"), 2);
  EXPECT_EQ(k.at("fell"), 1);
  EXPECT_EQ(k.at("detached"), 0);
  EXPECT_EQ(k.at("count"), 4);
  EXPECT_NEAR(k.at("openings")[0].at("fall_threshold_m").get<double>(), 0.01, 1e-12);
  for (const std::size_t held : {0, 1, 3})
  {
    EXPECT_LT(block(k, held).at("residual_m").get<double>(), 1e-4) << "block " << held;
    EXPECT_FALSE(block(k, held).at("fell").get<bool>()) << "block " << held;
  }
}

TEST(KeyblockRun, SlidingKeyFollowsCoulomb)
{
  // phi = 10 deg < 20 deg: a = g - 2 H tan(phi) / m = 5.06 m/s^2, u = a t^2 / 2 = 0.228 m; 2%
  // covers the contact forces' settling under the suddenly applied H (as tests/dda's Keyblock).
  const nlohmann::json k = run_keyblock_example("10");
  const double a = g - 2.0 * 35712.4 * std::tan(10.0 * M_PI / 180.0) / 2650.0;
  const double expected = 0.5 * a * t_end * t_end;
  EXPECT_NEAR(-block(k, 2).at("residual_displacement_m")[1].get<double>(), expected,
              0.02 * expected);
  EXPECT_TRUE(block(k, 2).at("fell").get<bool>());
  EXPECT_EQ(k.at("fell"), 1);
}

TEST(KeyblockRun, FrictionHoldsTheKey)
{
  // phi = 30 deg > 20 deg: the key's shear springs carry its weight with about 1.6e-6 m
  // (tests/dda's Keyblock); nothing falls, everything stays in contact.
  const nlohmann::json k = run_keyblock_example("30");
  EXPECT_LT(block(k, 2).at("residual_m").get<double>(), 1e-5);
  EXPECT_LT(block(k, 2).at("peak_displacement_m").get<double>(), 1e-4);
  EXPECT_FALSE(block(k, 2).at("fell").get<bool>());
  EXPECT_EQ(k.at("fell"), 0);
  EXPECT_EQ(k.at("detached"), 0);
}
