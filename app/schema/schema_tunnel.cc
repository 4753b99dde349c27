// The scene schema: the tunnel section and its stages, wave and near field.
#include "app/scene/tunnel_scene.h"
#include "app/schema/schema_sections.h"
#include "common/wave_type.h"

#include <vector>

namespace ddafem::schema
{
namespace
{
/// The tunnel's truncation and its far field's size, mesh and time step.
std::vector<Key> tunnel_far_field_keys()
{
  using T = ValueType;
  return {key("truncation", T::choice)
              .choices(names_of<TunnelTruncation>())
              .default_yaml("hybrid")
              .meaning("hybrid: blocks in a graded FE far field with Lysmer dashpots and "
                       "free-field sides; vb1 / dashpot: blocks only, VB I or the dashpot on the "
                       "near field's edges, the wave entering at its base; reference: the hybrid "
                       "with a far field so large that no reflection returns within the run; "
                       "blocks: blocks only out to the reference's extent, the near field in a "
                       "ring of bonded rectangular blocks of shortest S wavelength / "
                       "points_per_wavelength with the rock mass's E_eff (material `outer_rock`, "
                       "joint material `outer_bond`, joints that never break), dashpots on its "
                       "sides and base (the wave entering there), its top free at the ground "
                       "surface"),
          key("margin", T::number)
              .unit("m")
              .at_least(0)
              .default_note("one wavelength of the incident wave at its dominant frequency")
              .meaning("hybrid: far field beyond the near field on each side"),
          key("reference_margin", T::number)
              .unit("m")
              .at_least(0)
              .default_note("VP x window / 2")
              .meaning("reference and blocks: far field (outer blocks) beyond the near field on "
                       "each side"),
          key("points_per_wavelength", T::number)
              .default_yaml("10")
              .greater_than(0)
              .meaning("FE nodes (blocks: outer blocks) per shortest S wavelength (at "
                       "wave.max_frequency)"),
          key("growth_ratio", T::number)
              .default_yaml("1.3")
              .greater_than(1)
              .meaning("size ratio of neighbouring far-field elements away from the blocks"),
          key("window", T::number)
              .unit("s")
              .at_least(0)
              .default_note("near-field crossing x 2 + the pulse + 2 periods")
              .meaning("dynamic stage after the wave reaches the near field"),
          key("dt", T::number)
              .unit("s")
              .at_least(0)
              .default_note("1 / (20 max_frequency), within VB I's limit for vb1 (the dashpots of "
                            "dashpot and blocks set no limit)")
              .meaning("time step of the dynamic stage (time.dt, if given, wins)")};
}

/// The tunnel's stages and what acts in them: static, settle, damping, lining.
std::vector<Key> tunnel_stage_keys()
{
  using T = ValueType;
  return {key("static", T::section)
              .section("tunnel.static")
              .default_note("see `tunnel.static`")
              .meaning("the static stage: gravity, in-situ stress and the excavation"),
          key("settle", T::section)
              .section("tunnel.settle")
              .default_note("see `tunnel.settle`")
              .meaning("the settle stage after the wave: until every block is at rest or fell"),
          damping_key("tunnel.damping", "every material and joint material that has none of its "
                                        "own, and the far field"),
          key("lining", T::section)
              .section("tunnel.lining")
              .default_note("none")
              .meaning("shotcrete or concrete around the opening, installed after the excavation")};
}
} // namespace

Section tunnel_section()
{
  using T = ValueType;
  Section section{
      "tunnel",
      "A tunnel dynamic stability analysis from what a rock engineer knows "
      "(app/scene/tunnel_scene.h): "
      "the opening, the joint sets, the depth and k0, the incident wave and the accuracy "
      "wanted. The program chooses the near field that must be blocks (size_factor x the "
      "opening), generates them, derives the rock mass's modulus (the blocks with their joints) "
      "for the far field, sizes the far-field elements by the shortest S wavelength and grades "
      "them outward, places the truncation, and writes the sections `rock_mass`, `far_field`, "
      "`interface` (or the blocks' `boundaries`), `in_situ_stress` (lithostatic, k0), "
      "`stages` (static excavation, then the wave), `monitors` (crown, invert, walls, near-field "
      "base) and `time` (keys given in `time` win); truncation blocks writes `blocks` (the outer "
      "grids) and adds the material `outer_rock`, the joint material `outer_bond` and their "
      "`joints.pairs`. `check` prints each choice and why. The scene must not give those "
      "sections itself; joint materials come from `joints` as usual, and from the joint sets' "
      "`joint_material` along them.",
      {key("rock", T::string).required().meaning("name of the intact rock's material"),
       key("opening", T::section)
           .section("rock_mass.openings[i]")
           .required()
           .meaning("the tunnel's cross-section: circle, horseshoe or polygon"),
       key("joint_sets", T::section_list)
           .section("rock_mass.joint_sets[i]")
           .default_note("none")
           .meaning("sets of parallel joints, as in `rock_mass`"),
       key("joints", T::section_list)
           .section("rock_mass.joints[i]")
           .default_note("none")
           .meaning("single joints, as in `rock_mass`"),
       key("bolts", T::section)
           .section("tunnel.bolts")
           .default_note("none")
           .meaning("a pattern of radial rock bolts from the opening's surface"),
       key("seed", T::integer)
           .default_yaml("0")
           .at_least(0)
           .meaning("seed of the joint sets' random perturbations"),
       key("chord_tolerance", T::number)
           .unit("m")
           .default_yaml("0.02")
           .greater_than(0)
           .meaning("largest distance between the opening's arcs and its chords"),
       key("depth", T::number)
           .unit("m")
           .required()
           .greater_than(0)
           .meaning("depth of the opening's centre below the ground surface (overburden)"),
       key("k0", T::number)
           .default_yaml("0.5")
           .at_least(0)
           .meaning("horizontal over vertical in-situ stress"),
       key("wave", T::section)
           .section("tunnel.wave")
           .required()
           .meaning("the incident plane wave, travelling up from below"),
       key("near_field", T::section)
           .section("tunnel.near_field")
           .default_note("a square of 4 x the opening's size")
           .meaning("the region that is blocks")}};
  for (const auto& keys : {tunnel_far_field_keys(), tunnel_stage_keys()})
    section.keys.insert(section.keys.end(), keys.begin(), keys.end());
  return section;
}

Section tunnel_settle_section()
{
  using T = ValueType;
  return {"tunnel.settle",
          "The settle stage (stages[i] with mode settle) after the wave: the motion goes on until "
          "every block is at rest or has fallen (its centroid 1% of the opening's size below where "
          "the wave found it, the keyblocks' fall threshold), so that a keyblock reported as "
          "fallen fell and one reported as held stays.",
          {key("enabled", T::boolean)
               .default_yaml("true")
               .meaning("false: the run ends with the wave's window"),
           key("rest_speed", T::number)
               .unit("m/s")
               .default_yaml("1e-3")
               .greater_than(0)
               .meaning("a block is at rest while its vertices move no faster than this (blocks "
                        "tied to the far field move with it and are not judged)"),
           key("rest_duration", T::number)
               .unit("s")
               .default_note("max(0.1, 1 / tunnel.wave.frequency)")
               .greater_than(0)
               .meaning("how long without a break a block must stay below rest_speed"),
           key("max_duration", T::number)
               .unit("s")
               .default_note("rest_duration + 2 sqrt(2 D / g), D the opening's size: twice a fall "
                             "across the opening")
               .greater_than(0)
               .meaning("the stage ends after this long even if blocks still move (listed in "
                        "summary.json, not a failure)"),
           key("remove_fallen", T::boolean)
               .default_yaml("true")
               .meaning("a fallen block is removed as debris once it has left its place (no part "
                        "of it is still where it was when the wave came): its tumble on the floor "
                        "of the opening and its impacts there are not followed; false: they are")}};
}

Section tunnel_wave_section()
{
  using T = ValueType;
  return {
      "tunnel.wave",
      "A vertically incident plane wave: particle velocity v_in(t), horizontal for SV, "
      "vertical for P. It enters through the far field's base (hybrid, reference), the "
      "near field's base (vb1, dashpot) or the outer blocks' base (blocks).",
      {key("type", T::choice).choices(names_of<WaveType>()).required().meaning("wave type"),
       key("velocity", T::time_function).required().meaning("v_in(t) [m/s] of the incident wave"),
       key("frequency", T::number)
           .unit("Hz")
           .greater_than(0)
           .default_note("the sine pulse's frequency; required for a table or csv")
           .meaning("dominant frequency (sets the margin and the window)"),
       key("max_frequency", T::number)
           .unit("Hz")
           .greater_than(0)
           .default_note("2 x frequency")
           .meaning("highest frequency the model must carry (element sizes, dt)")}};
}

Section tunnel_near_field_section()
{
  using T = ValueType;
  return {"tunnel.near_field",
          "The rectangle that is blocks: a square of size_factor x the opening's larger side "
          "around it, or `lower` and `upper`.",
          {key("size_factor", T::number)
               .default_yaml("4")
               .greater_than(1)
               .meaning("side of the square over the opening's larger side"),
           key("lower", T::vector2)
               .unit("m")
               .default_note("from size_factor")
               .meaning("lower-left "
                        "corner"),
           key("upper", T::vector2)
               .unit("m")
               .default_note("from size_factor")
               .meaning("upper-right corner")}};
}

Section tunnel_static_section()
{
  using T = ValueType;
  return {"tunnel.static",
          "The static stage (stages[i] with mode static).",
          {key("dt", T::number)
               .unit("s")
               .default_note("1e-3; blocks: 1e-3 x the model's half size over the near field's")
               .greater_than(0)
               .meaning("pseudo time step (a larger one relaxes a larger model in as few steps)"),
           key("tolerance", T::number)
               .default_yaml("1e-5")
               .greater_than(0)
               .meaning("out-of-balance force ratio of equilibrium (each block's against its own "
                        "load, which the in-situ joint forces dominate: 1e-3 left the default "
                        "tunnel too unsettled for its dynamic stage)"),
           key("max_steps", T::integer)
               .default_yaml("5000")
               .at_least(1)
               .meaning("the run fails if equilibrium is not reached in this many steps"),
           key("release", T::choice)
               .choices(names_of<dda::ReleaseAction>())
               .default_yaml("fall")
               .meaning("what becomes of blocks that cannot be in equilibrium (see `stages[i]`)")}};
}

} // namespace ddafem::schema
