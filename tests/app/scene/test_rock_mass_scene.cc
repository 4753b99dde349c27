// Joint materials per joint set and explicit joint of `rock_mass` (and through `tunnel`): the
// generated blocks' edges carry them, names are checked, `check` prints them.
#include "app/scene/rock_mass_scene.h"
#include "app/scene/scene.h"
#include "common/input_error.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

using namespace ddafem;

namespace
{
namespace fs = std::filesystem;

/// A 10 m square cut by horizontal bedding (set 0, y = 1, 3, ..., 9) and vertical cross joints
/// (set 1, x = 2.5, 5, 7.5), and one explicit joint along the cross joint x = 5 below y = 4.5,
/// with its own material.
const char* two_materials_scene = R"(materials:
  rock: {density: 2650, youngs_modulus: 20e9, poisson_ratio: 0.25}
joint_materials:
  bonded: {normal_stiffness: 2e11, cohesion: 4e6, tensile_strength: 2e6}
  bedding: {normal_stiffness: 2e11, friction_angle: 30, bonded: false}
  cross: {normal_stiffness: 2e11, friction_angle: 35, cohesion: 2e5}
  fault: {normal_stiffness: 1e11, friction_angle: 20, bonded: false}
joints: {default: bonded}
rock_mass:
  material: rock
  region:
    rectangle: {lower: [0, 0], upper: [10, 10]}
  joint_sets:
    - {dip: 0, spacing: 2, offset: 1, joint_material: bedding}
    - {dip: 90, spacing: 2.5, joint_material: cross}
  joints:
    - {from: [5, 0], to: [5, 4.5], joint_material: fault}
time: {dt: 1e-4, end_time: 0.01}
)";

/// Writes `text` to a file of the test's own and reads it as a scene.
Scene read_text(const std::string& text)
{
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path file = fs::temp_directory_path() /
                        (std::string("ddafem_test_rock_mass_scene_") + info->name() + ".yaml");
  std::ofstream(file) << text;
  const Scene scene = read_scene(file.string());
  fs::remove(file);
  return scene;
}

std::size_t joint_material_index(const dda::ModelDescription& m, const std::string& name)
{
  for (std::size_t i = 0; i < m.joint_materials.size(); ++i)
    if (m.joint_materials[i].name == name)
      return i;
  throw std::runtime_error("no joint material " + name);
}
} // namespace

// Horizontal interior edges are on the bedding, vertical ones on the cross joints, except along
// the explicit joint (x = 5 below y = 4.5: the fault, also on the edge from y = 3 to 5, 1.5 m of
// which is on it); edges on the region's boundary have none.
TEST(RockMassScene, EdgesCarryTheirJointSetsMaterial)
{
  const Scene scene = read_text(two_materials_scene);
  const dda::ModelDescription& m = scene.model;
  const std::size_t bedding = joint_material_index(m, "bedding");
  const std::size_t cross = joint_material_index(m, "cross");
  const std::size_t fault = joint_material_index(m, "fault");
  std::size_t n_edges[3] = {0, 0, 0};
  for (const dda::BlockDescription& b : m.blocks)
  {
    ASSERT_EQ(b.edge_joint_materials.size(), b.vertices.size());
    for (std::size_t k = 0; k < b.vertices.size(); ++k)
    {
      const dda::Point& p = b.vertices[k];
      const dda::Point& q = b.vertices[(k + 1) % b.vertices.size()];
      const dda::Point mid = 0.5 * (p + q);
      const std::optional<std::size_t>& jm = b.edge_joint_materials[k];
      if (mid.x() == 0 || mid.x() == 10 || mid.y() == 0 || mid.y() == 10)
        EXPECT_FALSE(jm.has_value()) << mid.transpose();
      else if (p.y() == q.y())
        EXPECT_EQ(jm, bedding) << mid.transpose();
      else if (mid.x() == 5 && mid.y() < 4.5)
        EXPECT_EQ(jm, fault) << mid.transpose();
      else
        EXPECT_EQ(jm, cross) << mid.transpose();
      for (std::size_t i : {bedding, cross, fault})
        n_edges[i == bedding ? 0 : i == cross ? 1 : 2] += jm == i;
    }
  }
  EXPECT_GT(n_edges[0], 0u);
  EXPECT_GT(n_edges[1], 0u);
  EXPECT_EQ(n_edges[2], 2u * 3u); // three blocks on each side of the fault
  ASSERT_TRUE(scene.rock_mass);
  std::ostringstream check;
  describe_rock_mass(scene, check);
  EXPECT_NE(check.str().find("joint set 0 (dip 0 deg, spacing 2 m): joint material bedding"),
            std::string::npos)
      << check.str();
  EXPECT_NE(check.str().find("joint set 1 (dip 90 deg, spacing 2.5 m): joint material cross"),
            std::string::npos);
  EXPECT_NE(check.str().find("joint 0 from (5, 0) to (5, 4.5) m: joint material fault"),
            std::string::npos);
}

// Without `joint_material` the edges have none: joints.default applies as before.
TEST(RockMassScene, SetsWithoutJointMaterialKeepTheDefault)
{
  std::string text = two_materials_scene;
  for (const std::string key :
       {", joint_material: bedding", ", joint_material: cross", ", joint_material: fault"})
    text.erase(text.find(key), key.size());
  const Scene scene = read_text(text);
  for (const dda::BlockDescription& b : scene.model.blocks)
    EXPECT_TRUE(b.edge_joint_materials.empty());
  std::ostringstream check;
  describe_rock_mass(scene, check);
  EXPECT_NE(check.str().find("joint set 0 (dip 0 deg, spacing 2 m): joint material bonded "
                             "(joints.default)"),
            std::string::npos)
      << check.str();
}

// The tunnel section passes its joint sets' materials on to the rock mass it generates; an
// unknown name is reported at the tunnel's key.
TEST(RockMassScene, TunnelPassesJointMaterialsOn)
{
  const std::string tunnel = std::string(R"(materials:
  rock: {density: 2650, youngs_modulus: 20e9, poisson_ratio: 0.25}
joint_materials:
  joint: {normal_stiffness: 2e11, friction_angle: 35, cohesion: 4e6, tensile_strength: 2e6}
  bedding: {normal_stiffness: 2e11, friction_angle: 30}
joints: {default: joint}
tunnel:
  rock: rock
  opening:
    circle: {center: [0, 0], radius: 3}
  depth: 50
  k0: 0.5
  joint_sets:
    - {dip: 0, spacing: 3, offset: 1.5, joint_material: )");
  const std::string rest = R"(}
    - {dip: 90, spacing: 3, offset: 1.5}
  wave:
    type: sv
    velocity: {type: sine_pulse, frequency: 25, cycles: 1, amplitude: 0.1}
  truncation: vb1
)";
  const Scene scene = read_text(tunnel + "bedding" + rest);
  const std::size_t bedding = joint_material_index(scene.model, "bedding");
  std::size_t n_bedding = 0, n_other = 0;
  for (const dda::BlockDescription& b : scene.model.blocks)
    for (std::size_t k = 0; k < b.edge_joint_materials.size(); ++k)
    {
      const dda::Point& p = b.vertices[k];
      const dda::Point& q = b.vertices[(k + 1) % b.vertices.size()];
      if (b.edge_joint_materials[k] == bedding)
      {
        EXPECT_EQ(p.y(), q.y());
        ++n_bedding;
      }
      else
        n_other += p.y() == q.y() && b.edge_joint_materials[k].has_value();
    }
  EXPECT_GT(n_bedding, 20u);
  EXPECT_EQ(n_other, 0u);
  try
  {
    read_text(tunnel + "beding" + rest);
    ADD_FAILURE() << "no InputError for an unknown joint material";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("joint_sets[0].joint_material' = 'beding': unknown "
                                         "joint material 'beding'; did you mean 'bedding'?"),
              std::string::npos)
        << e.what();
  }
}
