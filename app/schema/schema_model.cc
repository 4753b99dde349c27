// The scene schema: blocks, materials, joints, loads, boundaries and stages (the settings
// sections time, contacts, solver and output: app/schema/schema_settings.cc).
#include "app/schema/bound_sections.h"
#include "app/schema/schema_sections.h"
#include "common/wave_type.h"
#include "dda/model_description.h"
#include "fem/far_field_description.h"

#include <utility>
#include <vector>

namespace ddafem::schema
{
namespace
{
/// stages[i].mode: the stage modes, and a dynamic stage that ends when the blocks settle.
std::vector<std::string> stage_mode_names()
{
  std::vector<std::string> names = names_of<dda::StageMode>();
  names.emplace_back(dda::settle_mode_name);
  return names;
}
} // namespace

/// `joint_material` of a joint set or an explicit joint of `rock_mass` (`along`: what it cuts).
Key joint_material_key(const std::string& along)
{
  return key("joint_material", ValueType::string)
      .default_note("`joints.default` (or a `joints.pairs` entry)")
      .meaning("name of the joint material of the joints (bonded) or contacts (`bonded: false`) "
               "along " +
               along +
               ": where blocks were cut by it; edges on the region's or an opening's boundary, "
               "and edges on no joint (vertical cuts around islands), take `joints`");
}

/// The `type` key of one time-function variant.
Key time_function_type(const TimeFunctionType type)
{
  return key("type", ValueType::choice)
      .required()
      .choices({name_of(type)})
      .meaning("selects this kind of time function");
}

namespace
{
/// The top level's keys that describe the rock: name, analysis, materials, joints, blocks and their
/// generators, the far field.
void add_top_level_model_keys(BoundKeys<Scene>& k)
{
  using T = ValueType;
  k.add(key("name", T::string)
            .default_note("file name without extension")
            .meaning("scene name shown in summaries and result files"));
  k.field("description", &Scene::description).meaning("free text");
  k.add(key("analysis", T::section)
            .section("analysis")
            .default_note("plane stress, updated geometry")
            .meaning("2D idealisation of the blocks and geometry update"));
  k.add(key("materials", T::section_map)
            .section("materials.<name>")
            .required()
            .meaning("block materials by name"));
  k.add(key("joint_materials", T::section_map)
            .section("joint_materials.<name>")
            .default_note("none")
            .meaning("joint (contact) materials by name"));
  k.add(key("joints", T::section)
            .section("joints")
            .default_note("none")
            .meaning("which joint material acts between blocks of which materials"));
  k.add(key("blocks", T::section_list)
            .section("blocks[i]")
            .default_note("required unless `far_field` or `rock_mass` is given")
            .meaning("the blocks: polygons or grids of rectangles"));
  k.add(key("rock_mass", T::section)
            .section("rock_mass")
            .default_note("none")
            .meaning("blocks generated from a region cut by joint sets, with openings excavated "
                     "(after the `blocks`)"));
  k.add(key("tunnel", T::section)
            .section("tunnel")
            .default_note("none")
            .meaning("a tunnel in jointed rock under a seismic wave: generates rock_mass, "
                     "far_field, interface or boundaries, in_situ_stress, stages, monitors and "
                     "time (see `tunnel`)"));
  k.add(key("far_field", T::section)
            .section("far_field")
            .default_note("none")
            .meaning("a deal.II continuum; without blocks the scene is FE only, with blocks it "
                     "surrounds them (see `interface`)"));
  k.add(key("interface", T::section)
            .section("interface")
            .default_note("required with both blocks (`blocks` or `rock_mass`) and `far_field`")
            .meaning("ties between the blocks and the far-field part they fill"));
}

/// The top level's keys of loads and the run: loads, supports, gravity, in-situ stress, monitors,
/// boundaries, time, contacts, stages, solver, output.
void add_top_level_run_keys(BoundKeys<Scene>& k)
{
  using T = ValueType;
  k.add(key("point_loads", T::section_list)
            .section("point_loads[i]")
            .default_note("none")
            .meaning("forces at material points"));
  k.add(key("fixed_points", T::section_list)
            .section("fixed_points[i]")
            .default_note("none")
            .meaning("material points tied to their initial position (plus a prescribed motion)"));
  k.add(key("bolts", T::section_list)
            .section("bolts[i]")
            .default_note("none")
            .meaning("rock bolts: end-anchored between two blocks, or grouted through the "
                     "blocks they cross"));
  k.add(key("linings", T::section_list)
            .section("linings[i]")
            .default_note("none")
            .meaning("shotcrete or concrete linings on the blocks' surface (frame elements)"));
  k.field("gravity", &Scene::model, &dda::ModelDescription::gravity)
      .unit("m/s^2")
      .meaning("body acceleration, e.g. [0, -9.81]");
  k.add(key("in_situ_stress", T::section)
            .section("in_situ_stress")
            .default_note("none")
            .meaning("the rock mass's initial stress: blocks start with it, and bonded joints, "
                     "ties to the far field and the static supports of viscous boundaries carry "
                     "its traction"));
  k.add(key("monitors", T::section_list)
            .section("monitors[i]")
            .default_note("none")
            .meaning("points whose displacement, velocity and stress histories are recorded"));
  k.add(key("boundaries", T::section_list)
            .section("boundaries[i]")
            .default_note("none")
            .meaning("absorbing (viscous) or free boundaries on outer block edges"));
  k.add(key("time", T::section)
            .section("time")
            .default_note("required unless `tunnel` is given")
            .meaning("time step and duration"));
  k.add(key("contacts", T::section)
            .section("contacts")
            .default_note("see `contacts`")
            .meaning("contact detection and the open-close iteration"));
  k.add(key("stages", T::section_list)
            .section("stages[i]")
            .default_note("one dynamic stage up to time.end_time")
            .meaning("stages run in sequence, e.g. static equilibrium under gravity, then the "
                     "dynamic load"));
  k.add(key("solver", T::section)
            .section("solver")
            .default_note("block_ldlt")
            .meaning("linear solver of each step"));
  k.add(key("output", T::section)
            .section("output")
            .default_note("see `output`")
            .meaning("where and how often results are written"));
}

} // namespace

BoundKeys<Scene> top_level_keys()
{
  BoundKeys<Scene> k;
  add_top_level_model_keys(k);
  add_top_level_run_keys(k);
  return k;
}

Section top_level_section()
{
  return {SceneSchema::top_level, "A scene is one YAML map with these sections.",
          top_level_keys().keys()};
}

BoundKeys<dda::ModelDescription> analysis_keys()
{
  using S = dda::ModelDescription;
  BoundKeys<S> k;
  k.field("plane", &S::plane_mode)
      .meaning("plane stress (thin slab, one-block-high bar) or plane strain (long section)");
  k.field("geometry", &S::geometry)
      .meaning("updated: Shi's DDA, every step is linearised about the current block geometry; "
               "small_displacement: linear analysis about the initial geometry (matrix assembled "
               "and factorized once; for waves of small amplitude)");
  return k;
}

Section analysis_section()
{
  return {"analysis",
          "How the 2D model idealises the third dimension, and whether the step matrix follows the "
          "moving geometry.",
          analysis_keys().keys()};
}

BoundKeys<dda::Material> material_keys()
{
  using S = dda::Material;
  BoundKeys<S> k;
  k.field("density", &S::density)
      .unit("kg/m^3")
      .required()
      .greater_than(0)
      .meaning("mass density rho");
  k.field("youngs_modulus", &S::youngs_modulus)
      .unit("Pa")
      .required()
      .greater_than(0)
      .meaning("Young's modulus E");
  k.field("poisson_ratio", &S::poisson_ratio)
      .required()
      .at_least(0)
      .less_than(0.5)
      .meaning("Poisson's ratio nu");
  k.add(damping_key("materials.<name>.damping", "the blocks' strain rates"));
  return k;
}

Section materials_section()
{
  return {"materials.<name>",
          "A linear elastic, isotropic block material. `<name>` is any name; blocks refer to it.",
          material_keys().keys()};
}

BoundKeys<dda::JointMaterial> joint_material_keys()
{
  using S = dda::JointMaterial;
  BoundKeys<S> k;
  k.field("normal_stiffness", &S::normal_stiffness)
      .unit("N/m")
      .required()
      .greater_than(0)
      .meaning("penalty spring at each contact point");
  k.field("shear_ratio", &S::shear_ratio).greater_than(0).meaning("shear spring / normal spring");
  k.field("friction_angle", &S::friction_angle)
      .unit("deg")
      .at_least(0)
      .less_than(90)
      .meaning("Coulomb friction angle phi");
  k.field("cohesion", &S::cohesion)
      .unit("Pa")
      .at_least(0)
      .meaning("cohesion c: of a bonded joint, or of a frictional contact until it first slides "
               "or opens (per unit joint length carried by the contact)");
  k.field("tensile_strength", &S::tensile_strength)
      .unit("Pa")
      .at_least(0)
      .meaning("tensile strength: of a bonded joint, or of a frictional contact until it first "
               "slides or opens");
  k.field("bonded", &S::bonded)
      .meaning("true: blocks sharing an edge are glued by springs until the strength is "
               "exceeded, then they meet through frictional contacts (residual friction, no "
               "cohesion); false: frictional contacts from the start");
  k.add(damping_key("joint_materials.<name>.damping", "the joints' and contacts' relative motion"));
  return k;
}

Section joint_materials_section()
{
  return {"joint_materials.<name>",
          "Properties of the joints (contacts) between blocks. `<name>` is any name; `joints` "
          "refers to it.",
          joint_material_keys().keys()};
}

Section joints_section()
{
  using T = ValueType;
  return {"joints",
          "Assigns joint materials to pairs of block materials. Any two blocks may come into "
          "contact, so every pair of materials in use needs a joint material, from a pair entry or "
          "the default.",
          {key("default", T::string)
               .default_note("none")
               .meaning("name of the joint material for pairs not listed in `pairs`"),
           key("pairs", T::section_list)
               .section("joints.pairs[i]")
               .default_note("none")
               .meaning("joint materials for given pairs of block materials")}};
}

Section joints_pairs_section()
{
  using T = ValueType;
  return {"joints.pairs[i]",
          "The joint material between blocks of materials A and B (in either order).",
          {key("materials", T::name_pair)
               .required()
               .meaning("the two block material names, e.g. [rock, concrete]"),
           key("joint", T::string).required().meaning("the joint material name")}};
}

BoundKeys<dda::BlockDescription> block_keys()
{
  using S = dda::BlockDescription;
  using T = ValueType;
  BoundKeys<S> k;
  k.add(key("material", T::string).required().meaning("name of the block's material"));
  k.add(key("vertices", T::point_list)
            .unit("m")
            .default_note("(give vertices or grid)")
            .meaning("corners of a simple polygon, at least 3"));
  k.add(key("grid", T::section)
            .section("blocks[i].grid")
            .default_note("(give vertices or grid)")
            .meaning("a grid of nx * ny rectangles, numbered row by row, x fastest"));
  k.field("initial_velocity", &S::initial_velocity)
      .unit("m/s")
      .meaning("translational velocity at t = 0");
  k.field("initial_stress", &S::initial_stress)
      .unit("Pa")
      .meaning("stress [sxx, syy, sxy] at t = 0, tension positive");
  return k;
}

Section blocks_section()
{
  return {
      "blocks[i]",
      "One block (`vertices`) or a grid of rectangular blocks (`grid`): give exactly one of the "
      "two. Vertices may be given clockwise or anticlockwise, and the first vertex may be "
      "repeated at the end. Blocks may touch but not overlap.",
      block_keys().keys()};
}

Section blocks_grid_section()
{
  using T = ValueType;
  return {"blocks[i].grid",
          "A grid of equal rectangles; each becomes one block.",
          {key("origin", T::vector2).unit("m").required().meaning("lower-left corner of the grid"),
           key("cell_size", T::vector2)
               .unit("m")
               .required()
               .greater_than(0)
               .meaning("[width, height] of each rectangle"),
           key("count", T::integer_pair)
               .required()
               .at_least(1)
               .meaning("[nx, ny] rectangles in x and y, at most 10^6 in all")}};
}

BoundKeys<dda::PointLoad> point_load_keys()
{
  using S = dda::PointLoad;
  using T = ValueType;
  BoundKeys<S> k;
  k.field("point", &S::point).unit("m").required().meaning("where the force acts");
  k.field("force", &S::force).unit("N").required().meaning("[fx, fy]");
  k.add(key("time_function", T::time_function)
            .default_yaml("{type: constant, value: 1}")
            .meaning("dimensionless factor f(t)"));
  return k;
}

Section point_loads_section()
{
  return {"point_loads[i]",
          "A force F(t) = force * f(t) at a material point; the point must lie inside or on the "
          "boundary of a block.",
          point_load_keys().keys()};
}

BoundKeys<dda::FixedPoint> fixed_point_keys()
{
  using S = dda::FixedPoint;
  using T = ValueType;
  BoundKeys<S> k;
  k.field("point", &S::point).unit("m").required().meaning("the tied material point");
  k.field("stiffness", &S::stiffness)
      .unit("N/m")
      .at_least(0)
      .meaning("penalty spring; 0 selects the engine's default");
  k.add(key("displacement_x", T::time_function)
            .unit("m")
            .default_yaml("{type: constant, value: 0}")
            .meaning("prescribed displacement ux(t)"));
  k.add(key("displacement_y", T::time_function)
            .unit("m")
            .default_yaml("{type: constant, value: 0}")
            .meaning("prescribed displacement uy(t)"));
  return k;
}

Section fixed_points_section()
{
  return {"fixed_points[i]",
          "A material point tied by a stiff spring to its initial position plus a prescribed "
          "displacement; the point must lie inside or on the boundary of a block.",
          fixed_point_keys().keys()};
}

BoundKeys<dda::Monitor> monitor_keys()
{
  using S = dda::Monitor;
  BoundKeys<S> k;
  k.field("name", &S::name).required().meaning("unique name of the history");
  k.field("point", &S::point).unit("m").required().meaning("the monitored material point");
  return k;
}

Section monitors_section()
{
  return {"monitors[i]", "A measurement point; it must lie inside or on the boundary of a block.",
          monitor_keys().keys()};
}

BoundKeys<dda::BoundaryDescription> boundary_keys()
{
  using S = dda::BoundaryDescription;
  using T = ValueType;
  BoundKeys<S> k;
  k.field("type", &S::type)
      .required()
      .meaning("free: no boundary term (a traction-free edge; kept so that --set can "
               "switch types); vb1: Bao, Hatzor & Huang (2012) eq. 39; vb2: Jiao et al. "
               "(2007) eq. 40; dashpot: the consistent dashpot, the force -C v1 with the "
               "integrator's end-of-step velocity v1");
  k.field("impedance", &S::impedance)
      .meaning("textbook: VP = sqrt(E (1-nu) / (rho (1+nu) (1-2nu))), VS = sqrt(E / (2 rho "
               "(1+nu))); effective: the model's actual wave speeds (block modulus in "
               "series with the joint compliance behind the boundary block)");
  k.field("a_n", &S::a_n).greater_than(0).meaning("normal coefficient in cn = a_n rho l0 VP");
  k.field("a_t", &S::a_t).greater_than(0).meaning("tangential coefficient in ct = a_t rho l0 VS");
  k.add(key("edges", T::integer_pair_list)
            .at_least(0)
            .default_note("(give one selector)")
            .meaning("explicit edges [[block, edge], ...]: block indexes the final block list "
                     "(each grid cell is one block, in grid order; the `rock_mass` blocks follow "
                     "the `blocks`); edge k runs from vertex k to "
                     "vertex k + 1 of the block's polygon as stored: anticlockwise (clockwise "
                     "vertices are reversed, a repeated first vertex is dropped), so edges 0 to 3 "
                     "of a grid cell are its bottom, right, top and left sides"));
  k.add(key("on_line", T::section)
            .section("boundaries[i].on_line")
            .default_note("(give one selector)")
            .meaning("every outer edge lying on a straight line"));
  k.field("outer", &S::outer)
      .meaning("true selects every outer edge (an edge not shared by a joint)");
  k.add(key("input", T::section)
            .section("boundaries[i].input")
            .default_note("none")
            .meaning("an incident wave entering through the boundary (vb1, vb2, dashpot)"));
  return k;
}

Section boundaries_section()
{
  return {
      "boundaries[i]",
      "A treatment of outer block edges (docs/reference/physics.md section 3). Give exactly one "
      "selector: `edges`, `on_line` or `outer: true`. Each selected edge of length l0 gets the "
      "dashpot "
      "coefficients cn = a_n rho l0 VP and ct = a_t rho l0 VS (rho, VP, VS of its block's "
      "material). Edges that are not selected stay free. Which edges a line or `outer` selects "
      "is decided by the engine: a selector that selects no edge is an error. In a static "
      "stage a vb1, vb2 or dashpot edge is held instead by a normal and a shear spring to "
      "fixed ground at each end (those of `joints.default`, else the fixed points' default "
      "penalty and shear ratio 0.4), preloaded with the `in_situ_stress` traction; when the "
      "first dynamic stage starts their forces become constant edge loads and the dashpots "
      "take over.",
      boundary_keys().keys()};
}

BoundKeys<dda::InSituStress> in_situ_stress_keys()
{
  using S = dda::InSituStress;
  BoundKeys<S> k;
  add_in_situ_keys(k, &S::stress, &S::gradient);
  k.field("reference_y", &S::reference_y)
      .unit("m")
      .meaning("height where the in-situ stress is `stress`");
  return k;
}

Section in_situ_stress_section()
{
  return {"in_situ_stress",
          "sigma0(y) = stress + stress_gradient (y - reference_y), tension positive. Every block "
          "without an explicit `initial_stress` starts with sigma0 at its centroid; every bonded "
          "joint end, every tie to the far field and every static support of a viscous boundary "
          "carries the force sigma0 n times its share of the edge (n out of the block): the "
          "traction the in-situ stress puts across it. With stress_gradient [K0 rho g, rho g, 0] "
          "and reference_y at the surface it balances gravity. Bonded joints and ties keep this "
          "preload; a viscous boundary's support hands it on as a constant edge load when the "
          "first dynamic stage starts.",
          in_situ_stress_keys().keys()};
}

Section boundaries_input_section()
{
  using T = ValueType;
  return {
      "boundaries[i].input",
      "An incident plane wave travelling up (+y) that enters through the boundary's dashpots "
      "(Joyner & Chen 1975): each edge receives the force 2 C v_in(t) at its midpoint, C = cn n "
      "n^T + ct t t^T its own dashpots and v_in the incident particle velocity, (0, v_in) for P "
      "and (v_in, 0) for SV; on a horizontal base that is 2 cn v_in upward (P) or 2 ct v_in "
      "along x (SV). A uniform traction over a block edge equals its resultant at the midpoint "
      "for DDA's first-order blocks. Dynamic stages only.",
      {key("type", T::choice).required().choices(names_of<WaveType>()).meaning("wave type"),
       key("velocity", T::time_function)
           .required()
           .meaning("v_in(t) [m/s] of the incident (upgoing) wave")}};
}

Section boundaries_on_line_section()
{
  using T = ValueType;
  return {"boundaries[i].on_line",
          "A straight line through `point` along `direction`; it selects the outer block edges "
          "that lie on it.",
          {key("point", T::vector2).unit("m").required().meaning("a point of the line"),
           key("direction", T::vector2)
               .required()
               .meaning("direction of the line [dx, dy], non-zero (any length)")}};
}

/// The keys of every stage and of static stages: name, mode, dt, end_time, max_steps, tolerance,
/// release.
BoundKeys<dda::Stage> stage_keys()
{
  using S = dda::Stage;
  using T = ValueType;
  BoundKeys<S> k;
  k.add(key("name", T::string).required().meaning("shown in messages and summary.json"));
  k.add(key("mode", T::choice)
            .choices(stage_mode_names())
            .required()
            .meaning("static: seek equilibrium; dynamic: integrate the motion to end_time; "
                     "settle: integrate the motion from where the previous stage ended until "
                     "every block is at rest or has fallen (at most max_duration), so that a "
                     "block reported as fallen fell"));
  k.add(key("dt", T::number)
            .unit("s")
            .default_note("time.dt")
            .greater_than(0)
            .meaning("static stages: the (largest) pseudo time step"));
  k.add(key("end_time", T::number)
            .unit("s")
            .default_note("time.end_time")
            .greater_than(0)
            .meaning("dynamic stages: the time the stage runs to"));
  k.field("max_steps", &S::max_steps)
      .at_least(1)
      .meaning("static stages: the run fails if equilibrium is not reached in this many "
               "steps");
  k.field("tolerance", &S::tolerance)
      .greater_than(0)
      .meaning("static stages: the out-of-balance force ratio of equilibrium, each "
               "block's resultant force over its own load (the sum of the magnitudes of "
               "the forces on it: weight, loads, joints, contacts, supports, ties)");
  k.field("release", &S::release)
      .meaning("static stages: what becomes of a released block, one that cannot be in "
               "equilibrium (its out-of-balance force stays >= 5% of its own load, does "
               "not drop by 10% and drives it straight on for 50 steps): fall, held where "
               "it is for the rest of the stage and free in the dynamic stage, where it "
               "falls onto whatever is below; remove, inert for the rest of the run (held, "
               "no joints, no contacts). Released blocks are listed in summary.json");
  return k;
}

/// The keys of settle stages.
BoundKeys<dda::SettleCriterion> settle_keys()
{
  using S = dda::SettleCriterion;
  BoundKeys<S> k;
  k.field("rest_speed", &S::rest_speed)
      .unit("m/s")
      .greater_than(0)
      .meaning("settle stages: a block is at rest while the largest speed of its "
               "vertices stays at most this for rest_duration");
  k.field("rest_duration", &S::rest_duration)
      .unit("s")
      .greater_than(0)
      .meaning("settle stages: how long a block must stay below rest_speed without a "
               "break (longer than the period of its slowest bounce)");
  k.field("fall_distance", &S::fall_distance)
      .unit("m")
      .at_least(0)
      .meaning("settle stages: a block whose centroid has moved this far along gravity "
               "since the first dynamic stage began has fallen and is not waited for; 0: "
               "every block must come to rest");
  k.field("max_duration", &S::max_duration)
      .unit("s")
      .greater_than(0)
      .meaning("settle stages: the stage ends after this long even if blocks still move "
               "(summary.json lists them; not a failure)");
  k.field("remove_fallen", &S::remove_fallen)
      .meaning("settle stages: a fallen block is removed as debris once it has left "
               "its place (along the direction it moved since the first dynamic stage "
               "began, its vertices' interval no longer overlaps the one they covered "
               "then): its tumble and impacts are not followed; needs fall_distance > 0");
  return k;
}

Section stages_section()
{
  std::vector<Key> keys = stage_keys().keys();
  for (Key& k : settle_keys().keys())
    keys.push_back(std::move(k));
  return {
      "stages[i]",
      "A stage of the analysis. A static stage (Shi's static analysis) zeroes the velocities "
      "before every step and keeps the clock at its time, so the blocks creep to equilibrium "
      "under gravity, loads and initial stress; it ends when every block's out-of-balance force "
      "falls below tolerance x its own load. A block that cannot be in equilibrium (a wedge "
      "that falls, a block that slides out) is released, not a failure: see `release`. A dynamic "
      "stage after it starts at rest from that equilibrium; histories and "
      "monitor displacements start there. With a far field (coupled scenes) the far field is "
      "held in static stages (the ties are springs to fixed ground with their in-situ "
      "preloads) and carries only the dynamic increment from the first dynamic stage on: "
      "static stages come first, with a linear interface.",
      std::move(keys)};
}

} // namespace ddafem::schema
