#include "app/scene_schema.h"

#include "app/schema_key_builder.h"

#include <cassert>
#include <sstream>
#include <utility>

namespace ddafem::schema
{
namespace
{
std::string format_number(double v)
{
  std::ostringstream s;
  s << v;
  return s.str();
}

/// `stress` of an in-situ stress sigma0(y) = stress + stress_gradient (y - reference_y)
/// (`in_situ_stress`, `far_field.static_stage`).
Key in_situ_stress_key()
{
  return key("stress", ValueType::voigt)
      .unit("Pa")
      .default_yaml("[0, 0, 0]")
      .meaning("in-situ stress [sxx, syy, sxy] at reference_y, tension positive");
}

/// `stress_gradient` of an in-situ stress.
Key in_situ_gradient_key()
{
  return key("stress_gradient", ValueType::voigt)
      .unit("Pa/m")
      .default_yaml("[0, 0, 0]")
      .meaning("d/dy of the in-situ stress, e.g. [K0 rho g, rho g, 0] for lithostatic stress "
               "with reference_y at the surface");
}

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
Key time_function_type(const std::string& type_name)
{
  return key("type", ValueType::choice)
      .required()
      .choices({type_name})
      .meaning("selects this kind of time function");
}
} // namespace

std::string describe(ValueType type)
{
  switch (type)
  {
  case ValueType::string:
    return "string";
  case ValueType::number:
    return "number";
  case ValueType::integer:
    return "integer";
  case ValueType::boolean:
    return "boolean";
  case ValueType::choice:
    return "choice";
  case ValueType::vector2:
    return "[x, y]";
  case ValueType::integer_pair:
    return "[integer, integer]";
  case ValueType::integer_pair_list:
    return "list of [integer, integer]";
  case ValueType::name_pair:
    return "[name, name]";
  case ValueType::voigt:
    return "[xx, yy, xy]";
  case ValueType::point_list:
    return "list of [x, y]";
  case ValueType::table:
    return "list of [t, value]";
  case ValueType::section:
    return "map";
  case ValueType::section_map:
    return "map of named maps";
  case ValueType::section_list:
    return "list of maps";
  case ValueType::time_function:
    return "time function";
  }
  return "";
}

bool Range::contains(double value) const
{
  if (min && (min_inclusive ? value < *min : value <= *min))
    return false;
  if (max && (max_inclusive ? value > *max : value >= *max))
    return false;
  return true;
}

std::string Range::describe() const
{
  if (min && max)
    return std::string(min_inclusive ? "[" : "(") + format_number(*min) + ", " +
           format_number(*max) + (max_inclusive ? "]" : ")");
  if (min)
    return std::string(min_inclusive ? ">= " : "> ") + format_number(*min);
  if (max)
    return std::string(max_inclusive ? "<= " : "< ") + format_number(*max);
  return "";
}

const Key* Section::find(const std::string& name) const
{
  for (const Key& k : keys)
    if (k.name == name)
      return &k;
  return nullptr;
}

const Key& Section::key(const std::string& name) const
{
  const Key* k = find(name);
  assert(k != nullptr && "the reader asked for a key that is not in the schema");
  return *k;
}

std::vector<std::string> Section::key_names() const
{
  std::vector<std::string> names;
  for (const Key& k : keys)
    names.push_back(k.name);
  return names;
}

std::string SceneSchema::time_function_section(const std::string& type_name)
{
  return "time function: " + type_name;
}

const Section& SceneSchema::section(const std::string& id) const
{
  for (const Section& s : all_sections)
    if (s.id == id)
      return s;
  assert(false && "unknown schema section");
  return all_sections.front();
}

SceneSchema::SceneSchema()
{
  using T = ValueType;
  tf_types = {"constant", "sine_pulse", "table", "csv"};

  all_sections.push_back(
      {top_level,
       "A scene is one YAML map with these sections.",
       {key("name", T::string)
            .default_note("file name without extension")
            .meaning("scene name shown in summaries and result files"),
        key("description", T::string).default_yaml("''").meaning("free text"),
        key("analysis", T::section)
            .section("analysis")
            .default_note("plane stress, updated geometry")
            .meaning("2D idealisation of the blocks and geometry update"),
        key("materials", T::section_map)
            .section("materials.<name>")
            .required()
            .meaning("block materials by name"),
        key("joint_materials", T::section_map)
            .section("joint_materials.<name>")
            .default_note("none")
            .meaning("joint (contact) materials by name"),
        key("joints", T::section)
            .section("joints")
            .default_note("none")
            .meaning("which joint material acts between blocks of which materials"),
        key("blocks", T::section_list)
            .section("blocks[i]")
            .default_note("required unless `far_field` or `rock_mass` is given")
            .meaning("the blocks: polygons or grids of rectangles"),
        key("rock_mass", T::section)
            .section("rock_mass")
            .default_note("none")
            .meaning("blocks generated from a region cut by joint sets, with openings excavated "
                     "(after the `blocks`)"),
        key("tunnel", T::section)
            .section("tunnel")
            .default_note("none")
            .meaning("a tunnel in jointed rock under a seismic wave: generates rock_mass, "
                     "far_field, interface or boundaries, in_situ_stress, stages, monitors and "
                     "time (see `tunnel`)"),
        key("far_field", T::section)
            .section("far_field")
            .default_note("none")
            .meaning("a deal.II continuum; without blocks the scene is FE only, with blocks it "
                     "surrounds them (see `interface`)"),
        key("interface", T::section)
            .section("interface")
            .default_note("required with both blocks (`blocks` or `rock_mass`) and `far_field`")
            .meaning("ties between the blocks and the far-field part they fill"),
        key("point_loads", T::section_list)
            .section("point_loads[i]")
            .default_note("none")
            .meaning("forces at material points"),
        key("fixed_points", T::section_list)
            .section("fixed_points[i]")
            .default_note("none")
            .meaning("material points tied to their initial position (plus a prescribed motion)"),
        key("gravity", T::vector2)
            .unit("m/s^2")
            .default_yaml("[0, 0]")
            .meaning("body acceleration, e.g. [0, -9.81]"),
        key("in_situ_stress", T::section)
            .section("in_situ_stress")
            .default_note("none")
            .meaning("the rock mass's initial stress: blocks start with it, and bonded joints, "
                     "ties to the far field and the static supports of viscous boundaries carry "
                     "its traction"),
        key("monitors", T::section_list)
            .section("monitors[i]")
            .default_note("none")
            .meaning("points whose displacement, velocity and stress histories are recorded"),
        key("boundaries", T::section_list)
            .section("boundaries[i]")
            .default_note("none")
            .meaning("absorbing (viscous) or free boundaries on outer block edges"),
        key("time", T::section)
            .section("time")
            .default_note("required unless `tunnel` is given")
            .meaning("time step and duration"),
        key("contacts", T::section)
            .section("contacts")
            .default_note("see `contacts`")
            .meaning("contact detection and the open-close iteration"),
        key("stages", T::section_list)
            .section("stages[i]")
            .default_note("one dynamic stage up to time.end_time")
            .meaning("stages run in sequence, e.g. static equilibrium under gravity, then the "
                     "dynamic load"),
        key("solver", T::section)
            .section("solver")
            .default_note("block_ldlt")
            .meaning("linear solver of each step"),
        key("output", T::section)
            .section("output")
            .default_note("see `output`")
            .meaning("where and how often results are written")}});

  all_sections.push_back(
      {"analysis",
       "How the 2D model idealises the third dimension, and whether the step matrix follows the "
       "moving geometry.",
       {key("plane", T::choice)
            .choices({"stress", "strain"})
            .default_yaml("stress")
            .meaning("plane stress (thin slab, one-block-high bar) or plane strain (long "
                     "section)"),
        key("geometry", T::choice)
            .choices({"updated", "small_displacement"})
            .default_yaml("updated")
            .meaning("updated: Shi's DDA, every step is linearised about the current block "
                     "geometry; small_displacement: linear analysis about the initial geometry "
                     "(matrix assembled and factorized once; for waves of small amplitude)")}});

  all_sections.push_back(
      {"materials.<name>",
       "A linear elastic, isotropic block material. `<name>` is any name; blocks refer to it.",
       {key("density", T::number)
            .unit("kg/m^3")
            .required()
            .greater_than(0)
            .meaning("mass density rho"),
        key("youngs_modulus", T::number)
            .unit("Pa")
            .required()
            .greater_than(0)
            .meaning("Young's modulus E"),
        key("poisson_ratio", T::number)
            .required()
            .at_least(0)
            .less_than(0.5)
            .meaning("Poisson's ratio nu")}});

  all_sections.push_back(
      {"joint_materials.<name>",
       "Properties of the joints (contacts) between blocks. `<name>` is any name; `joints` "
       "refers to it.",
       {key("normal_stiffness", T::number)
            .unit("N/m")
            .required()
            .greater_than(0)
            .meaning("penalty spring at each contact point"),
        key("shear_ratio", T::number)
            .default_yaml("0.4")
            .greater_than(0)
            .meaning("shear spring / normal spring"),
        key("friction_angle", T::number)
            .unit("deg")
            .default_yaml("0")
            .at_least(0)
            .less_than(90)
            .meaning("Coulomb friction angle phi"),
        key("cohesion", T::number)
            .unit("Pa")
            .default_yaml("0")
            .at_least(0)
            .meaning("cohesion c: of a bonded joint, or of a frictional contact until it first "
                     "slides or opens (per unit joint length carried by the contact)"),
        key("tensile_strength", T::number)
            .unit("Pa")
            .default_yaml("0")
            .at_least(0)
            .meaning("tensile strength: of a bonded joint, or of a frictional contact until it "
                     "first slides or opens"),
        key("bonded", T::boolean)
            .default_yaml("true")
            .meaning("true: blocks sharing an edge are glued by springs until the strength is "
                     "exceeded, then they meet through frictional contacts (residual friction, no "
                     "cohesion); false: frictional contacts from the start")}});

  all_sections.push_back(
      {"joints",
       "Assigns joint materials to pairs of block materials. Any two blocks may come into "
       "contact, so every pair of materials in use needs a joint material, from a pair entry or "
       "the default.",
       {key("default", T::string)
            .default_note("none")
            .meaning("name of the joint material for pairs not listed in `pairs`"),
        key("pairs", T::section_list)
            .section("joints.pairs[i]")
            .default_note("none")
            .meaning("joint materials for given pairs of block materials")}});

  all_sections.push_back(
      {"joints.pairs[i]",
       "The joint material between blocks of materials A and B (in either order).",
       {key("materials", T::name_pair)
            .required()
            .meaning("the two block material names, e.g. [rock, concrete]"),
        key("joint", T::string).required().meaning("the joint material name")}});

  all_sections.push_back(
      {"blocks[i]",
       "One block (`vertices`) or a grid of rectangular blocks (`grid`): give exactly one of the "
       "two. Vertices may be given clockwise or anticlockwise, and the first vertex may be "
       "repeated at the end. Blocks may touch but not overlap.",
       {key("material", T::string).required().meaning("name of the block's material"),
        key("vertices", T::point_list)
            .unit("m")
            .default_note("(give vertices or grid)")
            .meaning("corners of a simple polygon, at least 3"),
        key("grid", T::section)
            .section("blocks[i].grid")
            .default_note("(give vertices or grid)")
            .meaning("a grid of nx * ny rectangles, numbered row by row, x fastest"),
        key("initial_velocity", T::vector2)
            .unit("m/s")
            .default_yaml("[0, 0]")
            .meaning("translational velocity at t = 0"),
        key("initial_stress", T::voigt)
            .unit("Pa")
            .default_yaml("[0, 0, 0]")
            .meaning("stress [sxx, syy, sxy] at t = 0, tension positive")}});

  all_sections.push_back(
      {"blocks[i].grid",
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
            .meaning("[nx, ny] rectangles in x and y, at most 10^6 in all")}});

  all_sections.push_back(
      {"rock_mass",
       "A rock mass: the region is cut into blocks by the joint sets and the explicit joints, and "
       "the openings are excavated (an exact CGAL arrangement, dda/rock_mass.h). A trace that "
       "ends inside rock (persistence below 1) leaves intact rock beyond its tip: the bridge. A "
       "block that would enclose an opening, or touch itself at a vertex, is split by vertical "
       "cuts. Blocks below `min_block_area` or `min_inscribed_radius` are merged into the "
       "neighbour they share the longest boundary with, or kept and listed by `check`. The "
       "blocks follow those of `blocks`, numbered by centroid (bottom first, then by x), named "
       "`rock_mass block N` in messages; joints between them come from `joints` like any "
       "other, except along a joint set or explicit joint with its own `joint_material`.",
       {key("region", T::section)
            .section("rock_mass.region")
            .required()
            .meaning("the rock to cut: a rectangle or a polygon"),
        key("material", T::string).required().meaning("name of the blocks' material"),
        key("joint_sets", T::section_list)
            .section("rock_mass.joint_sets[i]")
            .default_note("none")
            .meaning("sets of parallel joints"),
        key("joints", T::section_list)
            .section("rock_mass.joints[i]")
            .default_note("none")
            .meaning("single joints (segments)"),
        key("openings", T::section_list)
            .section("rock_mass.openings[i]")
            .default_note("none")
            .meaning("openings to excavate, inside the region (they may overlap)"),
        key("seed", T::integer)
            .default_yaml("0")
            .at_least(0)
            .meaning("seed of the random perturbations: the same seed gives the same blocks"),
        key("chord_tolerance", T::number)
            .unit("m")
            .default_yaml("0.01")
            .greater_than(0)
            .meaning("largest distance between a circular arc and its chords (circles and "
                     "horseshoe roofs become polygons with the fewest sides within it)"),
        key("min_block_area", T::number)
            .unit("m^2")
            .default_note("0.01 x (mean spacing of the sets)^2")
            .at_least(0)
            .meaning("blocks with a smaller area are slivers"),
        key("min_inscribed_radius", T::number)
            .unit("m")
            .default_yaml("0")
            .at_least(0)
            .meaning("blocks with a smaller 2 area / perimeter (the inscribed radius of a "
                     "triangle, half the width of a long strip) are slivers"),
        key("slivers", T::choice)
            .choices({"merge", "report"})
            .default_yaml("merge")
            .meaning("merge: join each sliver to the neighbouring block it shares the longest "
                     "boundary with; report: keep them, `check` lists them")}});

  all_sections.push_back({"rock_mass.region",
                          "Give exactly one of `rectangle` and `polygon`.",
                          {key("rectangle", T::section)
                               .section("rock_mass.region.rectangle")
                               .default_note("(give rectangle or polygon)")
                               .meaning("an axis-parallel rectangle"),
                           key("polygon", T::point_list)
                               .unit("m")
                               .default_note("(give rectangle or polygon)")
                               .meaning("corners of a simple polygon, either orientation")}});

  all_sections.push_back(
      {"rock_mass.region.rectangle",
       "An axis-parallel rectangle.",
       {key("lower", T::vector2).unit("m").required().meaning("lower-left corner"),
        key("upper", T::vector2).unit("m").required().meaning("upper-right corner")}});

  all_sections.push_back(
      {"tunnel",
       "A tunnel dynamic stability analysis from what a rock engineer knows (app/tunnel_scene.h): "
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
            .meaning("the region that is blocks"),
        key("truncation", T::choice)
            .choices({"hybrid", "vb1", "dashpot", "reference", "blocks"})
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
            .meaning("time step of the dynamic stage (time.dt, if given, wins)"),
        key("static", T::section)
            .section("tunnel.static")
            .default_note("see `tunnel.static`")
            .meaning("the static stage: gravity, in-situ stress and the excavation"),
        key("settle", T::section)
            .section("tunnel.settle")
            .default_note("see `tunnel.settle`")
            .meaning("the settle stage after the wave: until every block is at rest or fell")}});

  all_sections.push_back(
      {"tunnel.settle",
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
                     "of the opening and its impacts there are not followed; false: they are")}});

  all_sections.push_back(
      {"tunnel.wave",
       "A vertically incident plane wave: particle velocity v_in(t), horizontal for SV, "
       "vertical for P. It enters through the far field's base (hybrid, reference), the "
       "near field's base (vb1, dashpot) or the outer blocks' base (blocks).",
       {key("type", T::choice).choices({"p", "sv"}).required().meaning("wave type"),
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
            .meaning("highest frequency the model must carry (element sizes, dt)")}});

  all_sections.push_back(
      {"tunnel.near_field",
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
            .meaning("upper-right corner")}});

  all_sections.push_back(
      {"tunnel.static",
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
            .choices({"fall", "remove"})
            .default_yaml("fall")
            .meaning("what becomes of blocks that cannot be in equilibrium (see `stages[i]`)")}});

  all_sections.push_back(
      {"rock_mass.joint_sets[i]",
       "Parallel joints. Traces run along d = (cos dip, sin dip), with normal n = (-sin dip, cos "
       "dip); joint line k (k = 0, +-1, ...) is n.x = offset + k spacing (before perturbation). "
       "On a line, trace j covers t = d.x in [phase + j P, phase + j P + trace_length], with "
       "the period P = trace_length + bridge and phase 0 on even lines, P / 2 on odd lines "
       "(staggered like brickwork). Persistence is trace_length / P.",
       {key("dip", T::number)
            .unit("deg")
            .required()
            .meaning("angle of the traces from the +x axis, anticlockwise (0: horizontal)"),
        key("spacing", T::number)
            .unit("m")
            .required()
            .greater_than(0)
            .meaning("mean distance between neighbouring joints, normal to them"),
        key("trace_length", T::number)
            .unit("m")
            .greater_than(0)
            .default_note("persistent: traces cross the region")
            .meaning("length of each trace; needs `bridge`"),
        key("bridge", T::number)
            .unit("m")
            .greater_than(0)
            .default_note("none (persistent)")
            .meaning("intact rock between collinear traces; needs `trace_length`"),
        key("offset", T::number)
            .unit("m")
            .default_yaml("0")
            .meaning("normal position of joint line 0: n.x = offset"),
        key("perturbation", T::section)
            .section("rock_mass.joint_sets[i].perturbation")
            .default_note("none")
            .meaning("random perturbation of the spacing and of the traces' positions"),
        joint_material_key("the set's traces")}});

  all_sections.push_back(
      {"rock_mass.joint_sets[i].perturbation",
       "Random perturbation by independent draws xi (uniform in [-1, 1] or standard normal) "
       "from `rock_mass.seed`: one for each gap between lines, one for each line's traces.",
       {key("spacing", T::number)
            .default_yaml("0")
            .at_least(0)
            .less_than(1)
            .meaning("each gap between neighbouring lines is spacing (1 + this xi); gaps below "
                     "0.1 spacing are drawn again"),
        key("position", T::number)
            .default_yaml("0")
            .at_least(0)
            .meaning("each line's traces shift along it by this xi times the period "
                     "trace_length + bridge (no effect on persistent sets)"),
        key("distribution", T::choice)
            .choices({"uniform", "normal"})
            .default_yaml("uniform")
            .meaning("of xi: uniform in [-1, 1] or standard normal")}});

  all_sections.push_back({"rock_mass.joints[i]",
                          "A single joint: the segment from `from` to `to` (cut at the region).",
                          {key("from", T::vector2).unit("m").required().meaning("one end"),
                           key("to", T::vector2).unit("m").required().meaning("the other end"),
                           joint_material_key("the joint")}});

  all_sections.push_back(
      {"rock_mass.openings[i]",
       "An opening to excavate, inside the region: give exactly one of `circle`, `horseshoe` "
       "and `polygon`.",
       {key("circle", T::section)
            .section("rock_mass.openings[i].circle")
            .default_note("(give one shape)")
            .meaning("a circle, excavated as an inscribed polygon (see `chord_tolerance`)"),
        key("horseshoe", T::section)
            .section("rock_mass.openings[i].horseshoe")
            .default_note("(give one shape)")
            .meaning("a flat floor, straight walls and a semicircular roof"),
        key("polygon", T::point_list)
            .unit("m")
            .default_note("(give one shape)")
            .meaning("corners of a simple polygon, either orientation")}});

  all_sections.push_back(
      {"rock_mass.openings[i].circle",
       "A circle.",
       {key("center", T::vector2).unit("m").required().meaning("centre"),
        key("radius", T::number).unit("m").required().greater_than(0).meaning("radius")}});

  all_sections.push_back(
      {"rock_mass.openings[i].horseshoe",
       "A tunnel section: floor of `width`, vertical walls of `wall_height`, and a semicircular "
       "roof of diameter `width` on top of the walls.",
       {key("floor_center", T::vector2).unit("m").required().meaning("middle of the floor"),
        key("width", T::number).unit("m").required().greater_than(0).meaning("floor width"),
        key("wall_height", T::number)
            .unit("m")
            .required()
            .at_least(0)
            .meaning("height of the straight walls, floor to springline")}});

  all_sections.push_back(
      {"point_loads[i]",
       "A force F(t) = force * f(t) at a material point; the point must lie inside or on the "
       "boundary of a block.",
       {key("point", T::vector2).unit("m").required().meaning("where the force acts"),
        key("force", T::vector2).unit("N").required().meaning("[fx, fy]"),
        key("time_function", T::time_function)
            .default_yaml("{type: constant, value: 1}")
            .meaning("dimensionless factor f(t)")}});

  all_sections.push_back(
      {"fixed_points[i]",
       "A material point tied by a stiff spring to its initial position plus a prescribed "
       "displacement; the point must lie inside or on the boundary of a block.",
       {key("point", T::vector2).unit("m").required().meaning("the tied material point"),
        key("stiffness", T::number)
            .unit("N/m")
            .default_yaml("0")
            .at_least(0)
            .meaning("penalty spring; 0 selects the engine's default"),
        key("displacement_x", T::time_function)
            .unit("m")
            .default_yaml("{type: constant, value: 0}")
            .meaning("prescribed displacement ux(t)"),
        key("displacement_y", T::time_function)
            .unit("m")
            .default_yaml("{type: constant, value: 0}")
            .meaning("prescribed displacement uy(t)")}});

  all_sections.push_back(
      {"monitors[i]",
       "A measurement point; it must lie inside or on the boundary of a block.",
       {key("name", T::string).required().meaning("unique name of the history"),
        key("point", T::vector2).unit("m").required().meaning("the monitored material point")}});

  all_sections.push_back(
      {"far_field",
       "A rectangular elastic continuum meshed with FE_Q elements (deal.II), in the scene's "
       "`analysis.plane` and advanced with the trapezoidal rule (exact for energy) at `time.dt`, "
       "or with `dda` (damps like the blocks). Monitors may lie in it. With `blocks` the far "
       "field surrounds them (a `hole`, or a side they adjoin) and `interface` ties the two into "
       "one implicit system per step of the blocks (per half step of Bathe's scheme), on the dt "
       "levels time.dt / 2^k of adaptive control.",
       {key("material", T::string).required().meaning("name of a material in `materials`"),
        key("lower", T::vector2)
            .unit("m")
            .default_note("required unless `mesh` is given")
            .meaning("lower-left corner [x0, y0]"),
        key("upper", T::vector2)
            .unit("m")
            .default_note("required unless `mesh` is given")
            .meaning("upper-right corner [x1, y1]"),
        key("element_size", T::number)
            .unit("m")
            .default_yaml("0")
            .at_least(0)
            .meaning("element edge length; 0: VS / (max_frequency points_per_wavelength) x degree"),
        key("max_frequency", T::number)
            .unit("Hz")
            .default_yaml("0")
            .at_least(0)
            .meaning("highest frequency to resolve (needed when element_size is 0)"),
        key("points_per_wavelength", T::number)
            .default_yaml("10")
            .greater_than(0)
            .meaning("nodes per shortest S wavelength"),
        key("degree", T::integer).default_yaml("2").at_least(1).meaning("FE_Q degree: 1 or 2"),
        key("hole", T::section)
            .section("far_field.hole")
            .default_note("none")
            .meaning("a hole in the rectangle (for the near field), elements graded towards it"),
        key("mesh", T::section)
            .section("far_field.mesh")
            .default_note("none: the generated rectangle")
            .meaning("a Gmsh mesh instead of the rectangle"),
        key("solver", T::choice)
            .default_yaml("direct")
            .choices({"direct", "cg"})
            .meaning("direct: sparse LU factorized once; cg: conjugate gradients (Jacobi), "
                     "warm-started from the predicted displacement: faster on large models"),
        key("solver_tolerance", T::number)
            .default_yaml("1e-12")
            .greater_than(0)
            .less_than(1)
            .meaning("cg: residual relative to the right-hand side (1e-12: monitors agree with "
                     "`direct` to about 1e-8)"),
        key("static_stage", T::section)
            .section("far_field.static_stage")
            .default_note("none: the dynamic stage starts unstressed")
            .meaning("gravity and in-situ stress solved statically before the dynamic stage"),
        key("rayleigh", T::section)
            .section("far_field.rayleigh")
            .default_note("none")
            .meaning("Rayleigh damping C += alpha M + beta K"),
        key("boundaries", T::section_list)
            .section("far_field.boundaries[i]")
            .default_note("all parts free")
            .meaning("what each side of the rectangle does"),
        key("incident", T::section)
            .section("far_field.incident")
            .default_note("none")
            .meaning("a vertically incident plane wave entering through an `input` side"),
        key("integrator", T::choice)
            .choices({"dda", "newmark_trapezoidal"})
            .default_note("dda with time.integrator dda, else newmark_trapezoidal")
            .meaning("the far field's Newmark scheme")}});

  all_sections.push_back(
      {"interface",
       "Blocks tied to the far field (coupling/README.md). The block edges on the far field's "
       "part are tied at Gauss points (composite over the pieces between far-field face ends) "
       "by normal and shear springs, like a bonded joint; the far field is condensed onto the "
       "ties so that blocks and far field advance in one implicit system per step with "
       "`time.dt` (`time.control` must be fixed). The blocks must cover the part exactly.",
       {key("part", T::choice)
            .required()
            .choices({"bottom", "right", "top", "left", "hole"})
            .meaning("the far field's part the blocks fill or adjoin"),
        key("normal_stiffness", T::number)
            .unit("N/m")
            .default_note("that of `joint_material`, else of `joints.default`")
            .greater_than(0)
            .meaning("normal spring per tied edge end (a bonded joint's p): an edge's ties share "
                     "2 p by their quadrature weights"),
        key("shear_ratio", T::number)
            .default_note("that of `joint_material`, else of `joints.default`, else 0.4")
            .greater_than(0)
            .meaning("shear spring / normal spring"),
        key("joint_material", T::string)
            .default_note("none: ties of unlimited strength (a linear interface)")
            .meaning("a joint material whose friction angle, cohesion and tensile strength the "
                     "ties follow (Mohr-Coulomb per tie, open / slide / lock in the open-close "
                     "iteration): blocks can slip on or separate from the far field"),
        key("points_per_face", T::integer)
            .default_yaml("3")
            .at_least(1)
            .meaning("Gauss points per piece of a block edge between far-field face ends (3 "
                     "integrates the ties exactly against degree-2 faces)"),
        key("tolerance", T::number)
            .unit("m")
            .default_yaml("0")
            .at_least(0)
            .meaning("largest distance of a tied block edge from the part; 0: 1e-6 of the "
                     "blocks' extent")}});

  all_sections.push_back(
      {"far_field.boundaries[i]",
       "One side of the far-field rectangle. Sides not listed are traction free.",
       {key("part", T::choice)
            .required()
            .choices({"bottom", "right", "top", "left", "hole"})
            .meaning("the side, or the hole's boundary"),
        key("type", T::choice)
            .required()
            .choices({"free", "fixed", "lysmer", "input", "roller", "free_field"})
            .meaning("fixed: zero displacement; lysmer: dashpots t = -rho (a VP (v.n) n + b VS (v "
                     "- (v.n) n)) (Lysmer & Kuhlemeyer 1969); input: those dashpots plus the "
                     "traction rho c 2 v_in of the incident wave (Joyner & Chen 1975); roller: the "
                     "displacement component the incident wave does not move is fixed (uy for a "
                     "vertical SV wave, ux for P), keeping a column one-dimensional; free_field "
                     "(left, right): dashpots on the motion relative to a 1D column solved "
                     "alongside plus its stress, t = sigma_ff n - D (v - v_ff) (free-field "
                     "boundary of Zienkiewicz et al. 1989, Nielsen 2006)"),
        key("a", T::number).default_yaml("1").greater_than(0).meaning("normal dashpot factor"),
        key("b", T::number).default_yaml("1").greater_than(0).meaning("tangential dashpot factor"),
        key("springs", T::section)
            .section("far_field.boundaries[i].springs")
            .default_note("none: dashpots only")
            .meaning("lysmer: springs beside the dashpots (viscous-spring boundary) for waves "
                     "radiating from a source inside")}});

  all_sections.push_back(
      {"far_field.boundaries[i].springs",
       "The viscous-spring artificial boundary (Deeks & Randolph 1994; Liu et al. 2006): "
       "springs K = G / R (alpha_n n n^T + alpha_t (I - n n^T)) per unit length beside the "
       "dashpots, R the distance from the source. A wave from a source inside reaches the "
       "boundary as a cylindrical wave whose near-field part the dashpots alone reflect.",
       {key("center", T::vector2)
            .unit("m")
            .required()
            .meaning("where the waves come from (the source, the opening)"),
        key("alpha_n", T::number)
            .default_yaml("1")
            .at_least(0)
            .meaning("normal spring factor (Liu et al. 2006, 2D: 0.8 to 1.2)"),
        key("alpha_t", T::number)
            .default_yaml("0.5")
            .at_least(0)
            .meaning("tangential spring factor (0.35 to 0.65)")}});

  all_sections.push_back(
      {"far_field.hole",
       "A hole in the far-field rectangle, its boundary the part `hole`. The mesh is an O-grid of "
       "quadrilaterals between the hole and a box twice its size, a Cartesian grid outside, "
       "refined near the hole (hanging nodes) until each element's longest edge is at most "
       "min(far size, element_size + (growth_ratio - 1) d), d the distance from the hole. Give "
       "the keys of the shape: rectangle `lower`, `upper`; polygon `vertices`; circle `center`, "
       "`radius`.",
       {key("shape", T::choice)
            .required()
            .choices({"rectangle", "polygon", "circle"})
            .meaning("the hole's shape"),
        key("lower", T::vector2)
            .unit("m")
            .default_note("rectangle only")
            .meaning("lower-left "
                     "corner"),
        key("upper", T::vector2)
            .unit("m")
            .default_note("rectangle only")
            .meaning("upper-right "
                     "corner"),
        key("vertices", T::point_list)
            .unit("m")
            .default_note("polygon only")
            .meaning("at least 3 vertices, star-shaped about their centroid (e.g. convex)"),
        key("center", T::vector2).unit("m").default_note("circle only").meaning("centre"),
        key("radius", T::number)
            .unit("m")
            .default_note("circle only")
            .greater_than(0)
            .meaning("radius; the boundary follows the circle under refinement"),
        key("element_size", T::number)
            .unit("m")
            .default_yaml("0")
            .at_least(0)
            .meaning("element size at the hole; 0: the far size (no grading)"),
        key("growth_ratio", T::number)
            .default_yaml("1.3")
            .greater_than(1)
            .meaning("size ratio of neighbouring elements away from the hole")}});

  all_sections.push_back(
      {"far_field.static_stage",
       "A static stage ahead of the dynamic one: K u_s = f_gravity - integral(B^T sigma0) with "
       "the `lysmer` and `input` parts held (`support`), sigma0(y) = stress + stress_gradient (y "
       "- reference_y) the in-situ stress. The reactions are then kept as constant forces and "
       "the dashpots act: the dynamic stage starts from u_s at rest. Monitors and snapshots "
       "report displacements relative to u_s and the total stress sigma0 + D B u.",
       {key("gravity", T::vector2)
            .unit("m/s^2")
            .default_note("the scene's `gravity`")
            .meaning("body acceleration of the far field, e.g. [0, -9.81]"),
        in_situ_stress_key(), in_situ_gradient_key(),
        key("reference_y", T::number)
            .unit("m")
            .default_note("the top of the far field")
            .meaning("height where the in-situ stress is `stress`"),
        key("support", T::choice)
            .default_yaml("fixed")
            .choices({"fixed", "roller"})
            .meaning("how `lysmer` and `input` parts are held in the static stage: fixed, or "
                     "roller (normal displacement only; the hole is held fixed)")}});

  all_sections.push_back(
      {"far_field.rayleigh",
       "Rayleigh damping C += alpha M + beta K; its damping ratio at circular frequency omega is "
       "alpha / (2 omega) + beta omega / 2. Give `alpha` and `beta`, or `ratio` and "
       "`frequencies` (then alpha = 2 ratio w1 w2 / (w1 + w2), beta = 2 ratio / (w1 + w2): the "
       "ratio is exact at both frequencies and lower between them).",
       {key("alpha", T::number).unit("1/s").at_least(0).default_note("0").meaning("mass factor"),
        key("beta", T::number).unit("s").at_least(0).default_note("0").meaning("stiffness factor"),
        key("ratio", T::number)
            .at_least(0)
            .less_than(1)
            .default_note("none")
            .meaning("damping ratio at both `frequencies`, e.g. 0.05"),
        key("frequencies", T::vector2)
            .unit("Hz")
            .greater_than(0)
            .default_note("none")
            .meaning("[f1, f2], f1 < f2: where the ratio is exact")}});

  all_sections.push_back(
      {"far_field.mesh",
       "A quadrilateral mesh from a Gmsh file (ASCII msh 2 or 4, read by deal.II GridIn) instead "
       "of the rectangle: the far field is the file's mesh, not refined. Its physical line tags "
       "name the boundary parts; boundary lines with other tags or none are free.",
       {key("file", T::string).required().meaning("path of the .msh file, relative to the scene"),
        key("parts", T::section)
            .section("far_field.mesh.parts")
            .default_note("none: all boundary lines free")
            .meaning("physical line tag of each named part")}});

  all_sections.push_back(
      {"far_field.mesh.parts",
       "Physical line tags of the parts used in `far_field.boundaries` (each tag must occur in "
       "the file).",
       {key("bottom", T::integer).at_least(1).default_note("none").meaning("tag of `bottom`"),
        key("right", T::integer).at_least(1).default_note("none").meaning("tag of `right`"),
        key("top", T::integer).at_least(1).default_note("none").meaning("tag of `top`"),
        key("left", T::integer).at_least(1).default_note("none").meaning("tag of `left`"),
        key("hole", T::integer).at_least(1).default_note("none").meaning("tag of `hole`")}});

  all_sections.push_back(
      {"far_field.incident",
       "A plane wave travelling up from the `input` side: particle velocity v_in(t), horizontal "
       "for SV, vertical for P.",
       {key("type", T::choice).required().choices({"p", "sv"}).meaning("wave type"),
        key("velocity", T::time_function)
            .required()
            .meaning("v_in(t) [m/s] of the incident (upgoing) wave")}});

  all_sections.push_back(
      {"boundaries[i]",
       "A treatment of outer block edges (physics.md section 3). Give exactly one selector: "
       "`edges`, `on_line` or `outer: true`. Each selected edge of length l0 gets the dashpot "
       "coefficients cn = a_n rho l0 VP and ct = a_t rho l0 VS (rho, VP, VS of its block's "
       "material). Edges that are not selected stay free. Which edges a line or `outer` selects "
       "is decided by the engine: a selector that selects no edge is an error. In a static "
       "stage a vb1, vb2 or dashpot edge is held instead by a normal and a shear spring to "
       "fixed ground at each end (those of `joints.default`, else the fixed points' default "
       "penalty and shear ratio 0.4), preloaded with the `in_situ_stress` traction; when the "
       "first dynamic stage starts their forces become constant edge loads and the dashpots "
       "take over.",
       {key("type", T::choice)
            .required()
            .choices({"free", "vb1", "vb2", "dashpot"})
            .meaning("free: no boundary term (a traction-free edge; kept so that --set can "
                     "switch types); vb1: Bao, Hatzor & Huang (2012) eq. 39; vb2: Jiao et al. "
                     "(2007) eq. 40; dashpot: the consistent dashpot, the force -C v1 with the "
                     "integrator's end-of-step velocity v1"),
        key("impedance", T::choice)
            .choices({"textbook", "effective"})
            .default_yaml("textbook")
            .meaning("textbook: VP = sqrt(E (1-nu) / (rho (1+nu) (1-2nu))), VS = sqrt(E / (2 rho "
                     "(1+nu))); effective: the model's actual wave speeds (block modulus in "
                     "series with the joint compliance behind the boundary block)"),
        key("a_n", T::number)
            .default_yaml("1")
            .greater_than(0)
            .meaning("normal coefficient in cn = a_n rho l0 VP"),
        key("a_t", T::number)
            .default_yaml("1")
            .greater_than(0)
            .meaning("tangential coefficient in ct = a_t rho l0 VS"),
        key("edges", T::integer_pair_list)
            .at_least(0)
            .default_note("(give one selector)")
            .meaning("explicit edges [[block, edge], ...]: block indexes the final block list "
                     "(each grid cell is one block, in grid order; the `rock_mass` blocks follow "
                     "the `blocks`); edge k runs from vertex k to "
                     "vertex k + 1 of the block's polygon as stored: anticlockwise (clockwise "
                     "vertices are reversed, a repeated first vertex is dropped), so edges 0 to 3 "
                     "of a grid cell are its bottom, right, top and left sides"),
        key("on_line", T::section)
            .section("boundaries[i].on_line")
            .default_note("(give one selector)")
            .meaning("every outer edge lying on a straight line"),
        key("outer", T::boolean)
            .default_yaml("false")
            .meaning("true selects every outer edge (an edge not shared by a joint)"),
        key("input", T::section)
            .section("boundaries[i].input")
            .default_note("none")
            .meaning("an incident wave entering through the boundary (vb1, vb2, dashpot)")}});

  all_sections.push_back(
      {"in_situ_stress",
       "sigma0(y) = stress + stress_gradient (y - reference_y), tension positive. Every block "
       "without an explicit `initial_stress` starts with sigma0 at its centroid; every bonded "
       "joint end, every tie to the far field and every static support of a viscous boundary "
       "carries the force sigma0 n times its share of the edge (n out of the block): the "
       "traction the in-situ stress puts across it. With stress_gradient [K0 rho g, rho g, 0] "
       "and reference_y at the surface it balances gravity. Bonded joints and ties keep this "
       "preload; a viscous boundary's support hands it on as a constant edge load when the "
       "first dynamic stage starts.",
       {in_situ_stress_key(), in_situ_gradient_key(),
        key("reference_y", T::number)
            .unit("m")
            .default_yaml("0")
            .meaning("height where the in-situ stress is `stress`")}});

  all_sections.push_back(
      {"boundaries[i].input",
       "An incident plane wave travelling up (+y) that enters through the boundary's dashpots "
       "(Joyner & Chen 1975): each edge receives the force 2 C v_in(t) at its midpoint, C = cn n "
       "n^T + ct t t^T its own dashpots and v_in the incident particle velocity, (0, v_in) for P "
       "and (v_in, 0) for SV; on a horizontal base that is 2 cn v_in upward (P) or 2 ct v_in "
       "along x (SV). A uniform traction over a block edge equals its resultant at the midpoint "
       "for DDA's first-order blocks. Dynamic stages only.",
       {key("type", T::choice).required().choices({"p", "sv"}).meaning("wave type"),
        key("velocity", T::time_function)
            .required()
            .meaning("v_in(t) [m/s] of the incident (upgoing) wave")}});

  all_sections.push_back(
      {"boundaries[i].on_line",
       "A straight line through `point` along `direction`; it selects the outer block edges "
       "that lie on it.",
       {key("point", T::vector2).unit("m").required().meaning("a point of the line"),
        key("direction", T::vector2)
            .required()
            .meaning("direction of the line [dx, dy], non-zero (any length)")}});

  all_sections.push_back(
      {"time",
       "Time stepping.",
       {key("dt", T::number).unit("s").required().greater_than(0).meaning("time step"),
        key("end_time", T::number)
            .unit("s")
            .required()
            .greater_than(0)
            .meaning("simulated duration; must be >= dt"),
        key("integrator", T::choice)
            .choices({"generalized_alpha", "bathe", "dda", "newmark_trapezoidal"})
            .default_yaml("bathe")
            .meaning("bathe (the default): Bathe's composite scheme, a generalized-alpha "
                     "(rho_inf 1/2) and a three-point backward Euler half step per dt, two solves "
                     "per step; right for frictional sliding and falls (within 0.71%) and for "
                     "waves (the bar's record error 0.70% at 200 steps per period), "
                     "docs/verification/failure.md; with a far field, the far field takes the "
                     "trapezoidal rule on each half step. generalized_alpha "
                     "(Chung & Hulbert 1993): one solve per step, sliding within 0.51%, but the "
                     "bar's record error 1.55% at 200 steps per period; dda: Shi's first-order "
                     "scheme (damps waves, but not stiff contact modes: its spectral radius "
                     "returns to 1 as omega dt grows); newmark_trapezoidal: energy-conserving, "
                     "second order (penalty contacts ring: blocks bounce and slide too far)"),
        key("spectral_radius", T::number)
            .default_yaml("0.2")
            .at_least(0)
            .at_most(1)
            .meaning("generalized_alpha: the spectral radius at infinite frequency rho_inf (1: "
                     "no algorithmic damping; 0: stiff modes annihilated in one step)"),
        key("control", T::choice)
            .choices({"adaptive", "fixed"})
            .default_yaml("adaptive")
            .meaning("adaptive: dt is the largest step, cut by cut_factor when a step fails "
                     "(open-close iteration not converged, a vertex moving more than "
                     "contacts.max_displacement_ratio allows, too deep a penetration) and grown "
                     "back by growth_factor (blocks tied to a far field: on the levels "
                     "dt / 2^k, doubling after as many steps as growth_factor takes to double; "
                     "coupling/README.md); fixed: every step has dt and such a failure stops "
                     "the run (wave problems)"),
        key("dt_min", T::number)
            .unit("s")
            .default_note("dt / 10^4")
            .greater_than(0)
            .meaning("smallest step of adaptive control; a step that needs less stops the run"),
        key("cut_factor", T::number)
            .default_yaml("0.3")
            .greater_than(0)
            .less_than(1)
            .meaning("dt multiplier after a failed step (Shi: 0.3)"),
        key("growth_factor", T::number)
            .default_yaml("1.2")
            .at_least(1)
            .meaning("dt multiplier after an accepted step, up to dt"),
        key("reversal_tolerance", T::number)
            .unit("m")
            .default_yaml("1e-6")
            .at_least(0)
            .meaning("adaptive control: the slip error a sliding contact's reversal within a "
                     "step may leave (its friction acted the wrong way for part of the step: "
                     "the speed error times the duration of the slide it ends); a step with a "
                     "larger one is redone to end just before the reversal and dt goes back up "
                     "at the next step; with generalized-alpha, a step in which friction turns "
                     "around is redone from the jump and the open-close iteration locks a "
                     "contact whose sliding reverses between trials (these two only on slides "
                     "of at least 10 steps: shorter ones are contacts chattering under a wave). "
                     "1e-6 makes two-way sliding on a shaken joint exact "
                     "(docs/verification/failure.md, part 1b); 0: none (docs/design.md, "
                     "Integrators)")}});

  all_sections.push_back(
      {"contacts",
       "Contact detection and the open-close iteration (Shi 1988). w0 is half the model's size "
       "(the larger side of the blocks' bounding box, halved). The step displacement bound is "
       "g2 w0, but at most a tenth of the shortest block edge.",
       {key("max_displacement_ratio", T::number)
            .default_yaml("0.01")
            .greater_than(0)
            .less_than(1)
            .meaning("Shi's g2: the largest vertex displacement of a step over w0 (the bound is "
                     "at most a tenth of the shortest edge); a step beyond is cut"),
        key("search_distance", T::number)
            .unit("m")
            .default_note("2.5 x the step displacement bound")
            .greater_than(0)
            .meaning("how close a vertex must come to an edge to be a contact candidate"),
        key("max_penetration", T::number)
            .unit("m")
            .default_note("the step displacement bound")
            .greater_than(0)
            .meaning("deepest penetration a step may leave; a step beyond is cut"),
        key("max_open_close_iterations", T::integer)
            .default_yaml("6")
            .at_least(1)
            .meaning("open-close iterations before the step is cut (Shi: 6)"),
        key("max_penalty_factor", T::number)
            .default_yaml("100")
            .at_least(1)
            .meaning("a contact penetrating deeper than max_penetration has its springs raised "
                     "x 10 and the step redone (ntdda), up to this multiple of its joint "
                     "material's; then dt is cut"),
        key("flip_force_ratio", T::number)
            .default_yaml("1e-3")
            .at_least(0)
            .less_than(1)
            .meaning("from the third open-close iteration on, a contact whose forces stay below "
                     "this fraction of the step's largest contact normal force changes state "
                     "without holding the iteration back (no flipping between slide and lock "
                     "at almost no force); 0 counts every change"),
        key("angle_tolerance", T::number)
            .unit("deg")
            .default_yaml("1")
            .greater_than(0)
            .less_than(30)
            .meaning("edges this close to parallel touch edge to edge; vertices this close to "
                     "180 degrees are straight (never enter)")}});

  all_sections.push_back(
      {"stages[i]",
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
       {key("name", T::string).required().meaning("shown in messages and summary.json"),
        key("mode", T::choice)
            .choices({"static", "dynamic", "settle"})
            .required()
            .meaning("static: seek equilibrium; dynamic: integrate the motion to end_time; "
                     "settle: integrate the motion from where the previous stage ended until "
                     "every block is at rest or has fallen (at most max_duration), so that a "
                     "block reported as fallen fell"),
        key("dt", T::number)
            .unit("s")
            .default_note("time.dt")
            .greater_than(0)
            .meaning("static stages: the (largest) pseudo time step"),
        key("end_time", T::number)
            .unit("s")
            .default_note("time.end_time")
            .greater_than(0)
            .meaning("dynamic stages: the time the stage runs to"),
        key("max_steps", T::integer)
            .default_yaml("10000")
            .at_least(1)
            .meaning("static stages: the run fails if equilibrium is not reached in this many "
                     "steps"),
        key("tolerance", T::number)
            .default_yaml("1e-5")
            .greater_than(0)
            .meaning("static stages: the out-of-balance force ratio of equilibrium, each "
                     "block's resultant force over its own load (the sum of the magnitudes of "
                     "the forces on it: weight, loads, joints, contacts, supports, ties)"),
        key("rest_speed", T::number)
            .unit("m/s")
            .default_yaml("1e-3")
            .greater_than(0)
            .meaning("settle stages: a block is at rest while the largest speed of its "
                     "vertices stays at most this for rest_duration"),
        key("rest_duration", T::number)
            .unit("s")
            .default_yaml("0.1")
            .greater_than(0)
            .meaning("settle stages: how long a block must stay below rest_speed without a "
                     "break (longer than the period of its slowest bounce)"),
        key("fall_distance", T::number)
            .unit("m")
            .default_yaml("0")
            .at_least(0)
            .meaning("settle stages: a block whose centroid has moved this far along gravity "
                     "since the first dynamic stage began has fallen and is not waited for; 0: "
                     "every block must come to rest"),
        key("max_duration", T::number)
            .unit("s")
            .default_yaml("2")
            .greater_than(0)
            .meaning("settle stages: the stage ends after this long even if blocks still move "
                     "(summary.json lists them; not a failure)"),
        key("remove_fallen", T::boolean)
            .default_yaml("false")
            .meaning("settle stages: a fallen block is removed as debris once it has left "
                     "its place (along the direction it moved since the first dynamic stage "
                     "began, its vertices' interval no longer overlaps the one they covered "
                     "then): its tumble and impacts are not followed; needs fall_distance > 0"),
        key("release", T::choice)
            .choices({"fall", "remove"})
            .default_yaml("fall")
            .meaning("static stages: what becomes of a released block, one that cannot be in "
                     "equilibrium (its out-of-balance force stays >= 5% of its own load, does "
                     "not drop by 10% and drives it straight on for 50 steps): fall, held where "
                     "it is for the rest of the stage and free in the dynamic stage, where it "
                     "falls onto whatever is below; remove, inert for the rest of the run (held, "
                     "no joints, no contacts). Released blocks are listed in summary.json")}});

  all_sections.push_back({"solver",
                          "Sparse direct solver for each step's linear system.",
                          {key("type", T::choice)
                               .choices({"block_ldlt", "eigen_ldlt", "amesos_klu"})
                               .default_yaml("block_ldlt")
                               .meaning("block_ldlt: sparse Cholesky on the 6x6 blocks (fastest, "
                                        "see docs/performance/dda_bench.md); eigen_ldlt: Eigen "
                                        "SimplicialLDLT; amesos_klu: Trilinos Amesos KLU")}});

  all_sections.push_back(
      {"output",
       "Where and how often results are written.",
       {key("directory", T::string)
            .default_yaml("results")
            .meaning("output directory, relative to the working directory; `-o DIR` overrides"),
        key("interval", T::number)
            .unit("s")
            .default_yaml("0")
            .at_least(0)
            .meaning("simulated time between block snapshots; 0: first and last only"),
        key("history_every", T::integer)
            .default_yaml("1")
            .at_least(1)
            .meaning("time steps between rows of the monitor histories (a step of bathe is "
                     "its pair of half steps)"),
        key("vtu_compression", T::choice)
            .default_yaml("best_speed")
            .choices({"best_speed", "best_compression", "none"})
            .meaning("zlib level of the far field's VTU files (deal.II DataOut): best_compression "
                     "writes files a few percent smaller in about four times the time "
                     "(docs/performance.md, profile); the blocks' files are plain text")}});

  all_sections.push_back({time_function_section("constant"),
                          "f(t) = value.",
                          {time_function_type("constant"),
                           key("value", T::number)
                               .required()
                               .meaning("the constant (in the unit of the quantity it gives)")}});

  all_sections.push_back(
      {time_function_section("sine_pulse"),
       "f(t) = amplitude sin(2 pi frequency (t - start)) for start <= t <= start + "
       "cycles / frequency, 0 elsewhere.",
       {time_function_type("sine_pulse"),
        key("frequency", T::number).unit("Hz").required().greater_than(0).meaning("frequency"),
        key("cycles", T::number).default_yaml("1").greater_than(0).meaning("number of cycles"),
        key("amplitude", T::number).default_yaml("1").meaning("peak value"),
        key("start", T::number).unit("s").default_yaml("0").meaning("time the pulse starts")}});

  all_sections.push_back(
      {time_function_section("table"),
       "Piecewise-linear interpolation of (time, value) points; the first value holds before "
       "the first time and the last value after the last time.",
       {time_function_type("table"),
        key("points", T::table)
            .unit("s, -")
            .required()
            .meaning("[[t, value], ...] with strictly increasing t, at least one point")}});

  all_sections.push_back(
      {time_function_section("csv"),
       "A table read from a CSV file (comma-separated numbers; blank lines are ignored).",
       {time_function_type("csv"),
        key("file", T::string)
            .required()
            .meaning("path of the CSV file, relative to the scene file's directory"),
        key("time_column", T::integer)
            .default_yaml("0")
            .at_least(0)
            .meaning("column of the times [s], counted from 0"),
        key("value_column", T::integer)
            .default_yaml("1")
            .at_least(0)
            .meaning("column of the values, counted from 0"),
        key("skip_rows", T::integer)
            .default_yaml("0")
            .at_least(0)
            .meaning("header rows to skip")}});
}

} // namespace ddafem::schema
