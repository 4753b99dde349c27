// The rock's damping in scenes (docs/damping.md): `materials.<name>.damping`,
// `joint_materials.<name>.damping`, the input's frequency by default, and `tunnel.damping`.
#include "app/scene/scene.h"
#include "common/input_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace ddafem;

namespace
{
const std::string tunnel_scene =
    std::string(DDAFEM_SOURCE_DIR) + "/examples/tunnel/circular_sv.yaml";

/// One block with `damping` on its material, and `extra` sections.
std::string damped_block(const std::string& damping, const std::string& extra = "")
{
  return "materials:\n  rock: {density: 2650, youngs_modulus: 50e9, poisson_ratio: 0.25, "
         "damping: " +
         damping +
         "}\n"
         "blocks:\n  - {material: rock, vertices: [[0, 0], [1, 0], [1, 1], [0, 1]]}\n"
         "time: {dt: 1e-4, end_time: 0.01}\n" +
         extra;
}

/// The InputError's text of reading `text`, or "" if it reads.
std::string error_of(const std::string& text)
{
  try
  {
    read_scene_text(text, "damped.yaml");
  }
  catch (const InputError& e)
  {
    return e.what();
  }
  return "";
}
} // namespace

TEST(DampingScene, RatioAndFrequencyAreRead)
{
  const Scene s = read_scene_text(damped_block("{ratio: 0.05, frequency: 10}"), "damped.yaml");
  const dda::RockDamping& d = s.model.materials[0].damping;
  EXPECT_EQ(d.ratio, 0.05);
  EXPECT_EQ(d.frequency, 10.0);
  EXPECT_DOUBLE_EQ(d.stiffness_factor(), 0.05 / (M_PI * 10.0));
}

TEST(DampingScene, FrequencyDefaultsToTheInputWaves)
{
  // A boundary's input: a 40 Hz sine pulse sets the frequency where the ratio holds.
  const std::string boundary =
      "boundaries:\n  - {type: vb2, on_line: {point: [0, 0], direction: [1, 0]}, input: {type: "
      "sv, velocity: {type: sine_pulse, frequency: 40, cycles: 1, amplitude: 0.1}}}\n";
  const Scene s = read_scene_text(damped_block("{ratio: 0.05}", boundary), "damped.yaml");
  EXPECT_EQ(s.model.materials[0].damping.frequency, 40.0);
}

TEST(DampingScene, BadDampingIsRefusedNamingTheKey)
{
  // No input wave and no frequency; a ratio out of range; a negative frequency; no ratio;
  // an unknown key.
  EXPECT_NE(error_of(damped_block("{ratio: 0.05}")).find("materials.rock.damping.frequency"),
            std::string::npos)
      << error_of(damped_block("{ratio: 0.05}"));
  EXPECT_NE(error_of(damped_block("{ratio: 1.5, frequency: 5}")).find("ratio"), std::string::npos);
  EXPECT_NE(error_of(damped_block("{ratio: 0.05, frequency: -5}")).find("frequency"),
            std::string::npos);
  EXPECT_NE(error_of(damped_block("{frequency: 5}")).find("ratio"), std::string::npos);
  EXPECT_NE(error_of(damped_block("{ratio: 0.05, frequency: 5, band: 3}")).find("band"),
            std::string::npos);
}

TEST(DampingScene, TunnelsAreDampedByDefaultAndTheFarFieldAlike)
{
  // 2 % at the wave's 25 Hz on every material and joint material, and the far field's Rayleigh
  // beta the same: 0.02 / (pi 25 Hz) = 2.546e-4 s.
  const Scene s = read_scene(tunnel_scene);
  const double beta = 0.02 / (M_PI * 25.0);
  for (const dda::Material& m : s.model.materials)
    EXPECT_DOUBLE_EQ(m.damping.stiffness_factor(), beta) << m.name;
  for (const dda::JointMaterial& j : s.model.joint_materials)
    EXPECT_DOUBLE_EQ(j.damping.stiffness_factor(), beta) << j.name;
  ASSERT_TRUE(s.far_field.has_value());
  EXPECT_DOUBLE_EQ(s.far_field->rayleigh.beta, beta);
  EXPECT_EQ(s.far_field->rayleigh.alpha, 0.0);
  // Off with one setting; another ratio and frequency with two.
  const Scene off = read_scene(tunnel_scene, {{"tunnel.damping.ratio", "0"}});
  for (const dda::Material& m : off.model.materials)
    EXPECT_FALSE(m.damping.active()) << m.name;
  EXPECT_EQ(off.far_field->rayleigh.beta, 0.0);
  const Scene five = read_scene(
      tunnel_scene, {{"tunnel.damping.ratio", "0.05"}, {"tunnel.damping.frequency", "10"}});
  EXPECT_DOUBLE_EQ(five.far_field->rayleigh.beta, 0.05 / (M_PI * 10.0));
  // A material's own damping wins over the tunnel's.
  const Scene own = read_scene(tunnel_scene, {{"materials.rock.damping.ratio", "0.04"},
                                              {"materials.rock.damping.frequency", "5"}});
  for (const dda::Material& m : own.model.materials)
  {
    if (m.name == "rock")
    {
      EXPECT_EQ(m.damping.ratio, 0.04);
    }
  }
}
