// The scene schema: the tunnel section and its stages, wave and near field.
#include "app/scene/tunnel_scene.h"
#include "app/schema/bound_sections.h"
#include "app/schema/schema_sections.h"
#include "common/wave_type.h"

#include <vector>

namespace ddafem::schema
{
namespace
{
/// The tunnel's truncation and its far field's size, mesh and time step.
void add_tunnel_far_field_keys(BoundKeys<TunnelDescription>& k)
{
  using S = TunnelDescription;
  k.field("truncation", &S::truncation)
      .meaning("hybrid: blocks in a graded FE far field with Lysmer dashpots and "
               "free-field sides; vb1 / dashpot: blocks only, VB I or the dashpot on the "
               "near field's edges, the wave entering at its base; reference: the hybrid "
               "with a far field so large that no reflection returns within the run; "
               "blocks: blocks only out to the reference's extent, the near field in a "
               "ring of bonded rectangular blocks of shortest S wavelength / "
               "points_per_wavelength with the rock mass's E_eff (material `outer_rock`, "
               "joint material `outer_bond`, joints that never break), dashpots on its "
               "sides and base (the wave entering there), its top free at the ground "
               "surface");
  k.field("margin", &S::margin)
      .unit("m")
      .at_least(0)
      .default_note("one wavelength of the incident wave at its dominant frequency")
      .meaning("hybrid: far field beyond the near field on each side");
  k.field("reference_margin", &S::reference_margin)
      .unit("m")
      .at_least(0)
      .default_note("VP x window / 2")
      .meaning("reference and blocks: far field (outer blocks) beyond the near field on "
               "each side");
  k.field("points_per_wavelength", &S::points_per_wavelength)
      .greater_than(0)
      .meaning("FE nodes (blocks: outer blocks) per shortest S wavelength (at "
               "wave.max_frequency)");
  k.field("growth_ratio", &S::growth_ratio)
      .greater_than(1)
      .meaning("size ratio of neighbouring far-field elements away from the blocks");
  k.field("window", &S::window)
      .unit("s")
      .at_least(0)
      .default_note("near-field crossing x 2 + the pulse + 2 periods")
      .meaning("dynamic stage after the wave reaches the near field");
  k.field("dt", &S::dt)
      .unit("s")
      .at_least(0)
      .default_note("1 / (20 max_frequency), within VB I's limit for vb1 (the dashpots of "
                    "dashpot and blocks set no limit)")
      .meaning("time step of the dynamic stage (time.dt, if given, wins)");
}

/// The tunnel's stages and what acts in them: static, settle, damping, lining.
void add_tunnel_stage_keys(BoundKeys<TunnelDescription>& k)
{
  using T = ValueType;
  k.add(key("static", T::section)
            .section("tunnel.static")
            .default_note("see `tunnel.static`")
            .meaning("the static stage: gravity, in-situ stress and the excavation"));
  k.add(key("settle", T::section)
            .section("tunnel.settle")
            .default_note("see `tunnel.settle`")
            .meaning("the settle stage after the wave: until every block is at rest or fell"));
  k.add(damping_key("tunnel.damping", "every material and joint material that has none of its "
                                      "own, and the far field"));
  k.add(key("lining", T::section)
            .section("tunnel.lining")
            .default_note("none")
            .meaning("shotcrete or concrete around the opening, installed after the excavation"));
}
} // namespace

BoundKeys<TunnelDescription> tunnel_keys()
{
  using S = TunnelDescription;
  using T = ValueType;
  BoundKeys<S> k;
  k.add(key("rock", T::string).required().meaning("name of the intact rock's material"));
  k.add(key("opening", T::section)
            .section("rock_mass.openings[i]")
            .required()
            .meaning("the tunnel's cross-section: circle, horseshoe or polygon"));
  k.add(key("joint_sets", T::section_list)
            .section("rock_mass.joint_sets[i]")
            .default_note("none")
            .meaning("sets of parallel joints, as in `rock_mass`"));
  k.add(key("joints", T::section_list)
            .section("rock_mass.joints[i]")
            .default_note("none")
            .meaning("single joints, as in `rock_mass`"));
  k.add(key("bolts", T::section)
            .section("tunnel.bolts")
            .default_note("none")
            .meaning("a pattern of radial rock bolts from the opening's surface"));
  k.field("seed", &S::rock_mass, &dda::RockMassDescription::seed)
      .at_least(0)
      .meaning("seed of the joint sets' random perturbations");
  k.field("chord_tolerance", &S::rock_mass, &dda::RockMassDescription::chord_tolerance)
      .unit("m")
      .default_yaml("0.02") // coarser than a rock_mass's: the opening's scale
      .greater_than(0)
      .meaning("largest distance between the opening's arcs and its chords");
  k.field("depth", &S::depth)
      .unit("m")
      .required()
      .greater_than(0)
      .meaning("depth of the opening's centre below the ground surface (overburden)");
  k.field("k0", &S::k0).at_least(0).meaning("horizontal over vertical in-situ stress");
  k.add(key("wave", T::section)
            .section("tunnel.wave")
            .required()
            .meaning("the incident plane wave, travelling up from below"));
  k.add(key("near_field", T::section)
            .section("tunnel.near_field")
            .default_note("a square of 4 x the opening's size")
            .meaning("the region that is blocks"));
  add_tunnel_far_field_keys(k);
  add_tunnel_stage_keys(k);
  return k;
}

Section tunnel_section()
{
  return {
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
      tunnel_keys().keys()};
}

BoundKeys<TunnelDescription> tunnel_settle_keys()
{
  using S = TunnelDescription;
  BoundKeys<S> k;
  k.field("enabled", &S::settle).meaning("false: the run ends with the wave's window");
  k.field("rest_speed", &S::settle_rest_speed)
      .unit("m/s")
      .greater_than(0)
      .meaning("a block is at rest while its vertices move no faster than this (blocks "
               "tied to the far field move with it and are not judged)");
  k.field("rest_duration", &S::settle_rest_duration)
      .unit("s")
      .default_note("max(0.1, 1 / tunnel.wave.frequency)")
      .greater_than(0)
      .meaning("how long without a break a block must stay below rest_speed");
  k.field("max_duration", &S::settle_max_duration)
      .unit("s")
      .default_note("rest_duration + 2 sqrt(2 D / g), D the opening's size: twice a fall "
                    "across the opening")
      .greater_than(0)
      .meaning("the stage ends after this long even if blocks still move (listed in "
               "summary.json, not a failure)");
  k.field("remove_fallen", &S::settle_remove_fallen)
      .meaning("a fallen block is removed as debris once it has left its place (no part "
               "of it is still where it was when the wave came): its tumble on the floor "
               "of the opening and its impacts there are not followed; false: they are");
  return k;
}

Section tunnel_settle_section()
{
  return {"tunnel.settle",
          "The settle stage (stages[i] with mode settle) after the wave: the motion goes on until "
          "every block is at rest or has fallen (its centroid 1% of the opening's size below where "
          "the wave found it, the keyblocks' fall threshold), so that a keyblock reported as "
          "fallen fell and one reported as held stays.",
          tunnel_settle_keys().keys()};
}

BoundKeys<TunnelDescription> tunnel_wave_keys()
{
  using S = TunnelDescription;
  using T = ValueType;
  BoundKeys<S> k;
  k.field("type", &S::wave_type).required().meaning("wave type");
  k.add(key("velocity", T::time_function).required().meaning("v_in(t) [m/s] of the incident wave"));
  k.add(key("frequency", T::number)
            .unit("Hz")
            .greater_than(0)
            .default_note("the sine pulse's frequency; required for a table or csv")
            .meaning("dominant frequency (sets the margin and the window)"));
  k.add(key("max_frequency", T::number)
            .unit("Hz")
            .greater_than(0)
            .default_note("2 x frequency")
            .meaning("highest frequency the model must carry (element sizes, dt)"));
  return k;
}

Section tunnel_wave_section()
{
  return {"tunnel.wave",
          "A vertically incident plane wave: particle velocity v_in(t), horizontal for SV, "
          "vertical for P. It enters through the far field's base (hybrid, reference), the "
          "near field's base (vb1, dashpot) or the outer blocks' base (blocks).",
          tunnel_wave_keys().keys()};
}

BoundKeys<TunnelDescription> tunnel_near_field_keys()
{
  using S = TunnelDescription;
  using T = ValueType;
  BoundKeys<S> k;
  k.field("size_factor", &S::size_factor)
      .greater_than(1)
      .meaning("side of the square over the opening's larger side");
  k.add(key("lower", T::vector2)
            .unit("m")
            .default_note("from size_factor")
            .meaning("lower-left "
                     "corner"));
  k.add(key("upper", T::vector2)
            .unit("m")
            .default_note("from size_factor")
            .meaning("upper-right corner"));
  return k;
}

Section tunnel_near_field_section()
{
  return {"tunnel.near_field",
          "The rectangle that is blocks: a square of size_factor x the opening's larger side "
          "around it, or `lower` and `upper`.",
          tunnel_near_field_keys().keys()};
}

BoundKeys<TunnelDescription> tunnel_static_keys()
{
  using S = TunnelDescription;
  BoundKeys<S> k;
  k.field("dt", &S::static_dt)
      .unit("s")
      .default_note("1e-3; blocks: 1e-3 x the model's half size over the near field's")
      .greater_than(0)
      .meaning("pseudo time step (a larger one relaxes a larger model in as few steps)");
  k.field("tolerance", &S::static_tolerance)
      .greater_than(0)
      .meaning("out-of-balance force ratio of equilibrium (each block's against its own "
               "load, which the in-situ joint forces dominate: 1e-3 left the default "
               "tunnel too unsettled for its dynamic stage)");
  k.field("max_steps", &S::static_max_steps)
      .at_least(1)
      .meaning("the run fails if equilibrium is not reached in this many steps");
  k.field("release", &S::static_release)
      .meaning("what becomes of blocks that cannot be in equilibrium (see `stages[i]`)");
  return k;
}

Section tunnel_static_section()
{
  return {"tunnel.static", "The static stage (stages[i] with mode static).",
          tunnel_static_keys().keys()};
}

} // namespace ddafem::schema
