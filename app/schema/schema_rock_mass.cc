// The scene schema: the generated rock mass: region, joint sets, explicit joints, openings.
#include "app/schema/bound_sections.h"
#include "app/schema/schema_sections.h"
#include "dda/rock_mass.h"

namespace ddafem::schema
{
BoundKeys<dda::RockMassDescription> rock_mass_keys()
{
  using S = dda::RockMassDescription;
  using T = ValueType;
  BoundKeys<S> k;
  k.add(key("region", T::section)
            .section("rock_mass.region")
            .required()
            .meaning("the rock to cut: a rectangle or a polygon"));
  k.add(key("material", T::string).required().meaning("name of the blocks' material"));
  k.add(key("joint_sets", T::section_list)
            .section("rock_mass.joint_sets[i]")
            .default_note("none")
            .meaning("sets of parallel joints"));
  k.add(key("joints", T::section_list)
            .section("rock_mass.joints[i]")
            .default_note("none")
            .meaning("single joints (segments)"));
  k.add(key("openings", T::section_list)
            .section("rock_mass.openings[i]")
            .default_note("none")
            .meaning("openings to excavate, inside the region (they may overlap)"));
  k.field("seed", &S::seed)
      .at_least(0)
      .meaning("seed of the random perturbations: the same seed gives the same blocks");
  k.field("chord_tolerance", &S::chord_tolerance)
      .unit("m")
      .greater_than(0)
      .meaning("largest distance between a circular arc and its chords (circles and "
               "horseshoe roofs become polygons with the fewest sides within it)");
  k.add(key("min_block_area", T::number)
            .unit("m^2")
            .default_note("0.01 x (mean spacing of the sets)^2")
            .at_least(0)
            .meaning("blocks with a smaller area are slivers"));
  k.field("min_inscribed_radius", &S::slivers, &dda::SliverSettings::min_inscribed_radius)
      .unit("m")
      .at_least(0)
      .meaning("blocks with a smaller 2 area / perimeter (the inscribed radius of a triangle, "
               "half the width of a long strip) are slivers");
  k.field("slivers", &S::slivers, &dda::SliverSettings::action)
      .meaning("merge: join each sliver to the neighbouring block it shares the longest boundary "
               "with; report: keep them, `check` lists them");
  return k;
}

Section rock_mass_section()
{
  return {
      "rock_mass",
      "A rock mass: the region is cut into blocks by the joint sets and the explicit joints, and "
      "the openings are excavated (an exact CGAL arrangement, dda/rock_mass.h). A trace that "
      "ends inside rock (persistence below 1) leaves intact rock beyond its tip: the bridge. A "
      "block that would enclose an opening, or touch itself at a vertex, is split by vertical "
      "cuts. Blocks below `min_block_area` or `min_inscribed_radius` are merged into the "
      "neighbour they share the longest boundary with, or kept and listed by `check`. The "
      "blocks follow those of `blocks`, numbered by centroid (bottom first, then by x), named "
      "`rock_mass block N` in messages; joints between them come from `joints` like any "
      "other, except along a joint set or explicit joint with its own `joint_material`.",
      rock_mass_keys().keys()};
}

Section rock_mass_region_section()
{
  using T = ValueType;
  return {"rock_mass.region",
          "Give exactly one of `rectangle` and `polygon`.",
          {key("rectangle", T::section)
               .section("rock_mass.region.rectangle")
               .default_note("(give rectangle or polygon)")
               .meaning("an axis-parallel rectangle"),
           key("polygon", T::point_list)
               .unit("m")
               .default_note("(give rectangle or polygon)")
               .meaning("corners of a simple polygon, either orientation")}};
}

Section rock_mass_region_rectangle_section()
{
  using T = ValueType;
  return {"rock_mass.region.rectangle",
          "An axis-parallel rectangle.",
          {key("lower", T::vector2).unit("m").required().meaning("lower-left corner"),
           key("upper", T::vector2).unit("m").required().meaning("upper-right corner")}};
}

BoundKeys<dda::JointSet> joint_set_keys()
{
  using S = dda::JointSet;
  using T = ValueType;
  BoundKeys<S> k;
  k.field("dip", &S::dip)
      .unit("deg")
      .required()
      .meaning("angle of the traces from the +x axis, anticlockwise (0: horizontal)");
  k.field("spacing", &S::spacing)
      .unit("m")
      .required()
      .greater_than(0)
      .meaning("mean distance between neighbouring joints, normal to them");
  k.add(key("trace_length", T::number)
            .unit("m")
            .greater_than(0)
            .default_note("persistent: traces cross the region")
            .meaning("length of each trace; needs `bridge`"));
  k.add(key("bridge", T::number)
            .unit("m")
            .greater_than(0)
            .default_note("none (persistent)")
            .meaning("intact rock between collinear traces; needs `trace_length`"));
  k.field("offset", &S::offset).unit("m").meaning("normal position of joint line 0: n.x = offset");
  k.add(key("perturbation", T::section)
            .section("rock_mass.joint_sets[i].perturbation")
            .default_note("none")
            .meaning("random perturbation of the spacing and of the traces' positions"));
  k.add(joint_material_key("the set's traces"));
  return k;
}

Section rock_mass_joint_sets_section()
{
  return {
      "rock_mass.joint_sets[i]",
      "Parallel joints. Traces run along d = (cos dip, sin dip), with normal n = (-sin dip, cos "
      "dip); joint line k (k = 0, +-1, ...) is n.x = offset + k spacing (before perturbation). "
      "On a line, trace j covers t = d.x in [phase + j P, phase + j P + trace_length], with "
      "the period P = trace_length + bridge and phase 0 on even lines, P / 2 on odd lines "
      "(staggered like brickwork). Persistence is trace_length / P.",
      joint_set_keys().keys()};
}

BoundKeys<dda::JointPerturbation> perturbation_keys()
{
  using S = dda::JointPerturbation;
  BoundKeys<S> k;
  k.field("spacing", &S::spacing)
      .at_least(0)
      .less_than(1)
      .meaning("each gap between neighbouring lines is spacing (1 + this xi); gaps below "
               "0.1 spacing are drawn again");
  k.field("position", &S::position)
      .at_least(0)
      .meaning("each line's traces shift along it by this xi times the period "
               "trace_length + bridge (no effect on persistent sets)");
  k.field("distribution", &S::distribution).meaning("of xi: uniform in [-1, 1] or standard normal");
  return k;
}

Section rock_mass_joint_sets_perturbation_section()
{
  return {"rock_mass.joint_sets[i].perturbation",
          "Random perturbation by independent draws xi (uniform in [-1, 1] or standard normal) "
          "from `rock_mass.seed`: one for each gap between lines, one for each line's traces.",
          perturbation_keys().keys()};
}

Section rock_mass_joints_section()
{
  using T = ValueType;
  return {"rock_mass.joints[i]",
          "A single joint: the segment from `from` to `to` (cut at the region).",
          {key("from", T::vector2).unit("m").required().meaning("one end"),
           key("to", T::vector2).unit("m").required().meaning("the other end"),
           joint_material_key("the joint")}};
}

Section rock_mass_openings_section()
{
  using T = ValueType;
  return {"rock_mass.openings[i]",
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
               .meaning("corners of a simple polygon, either orientation")}};
}

BoundKeys<dda::Opening> circle_keys()
{
  using S = dda::Opening;
  using T = ValueType;
  BoundKeys<S> k;
  k.add(key("center", T::vector2).unit("m").required().meaning("centre"));
  k.field("radius", &S::radius).unit("m").required().greater_than(0).meaning("radius");
  return k;
}

Section rock_mass_openings_circle_section()
{
  return {"rock_mass.openings[i].circle", "A circle.", circle_keys().keys()};
}

BoundKeys<dda::Opening> horseshoe_keys()
{
  using S = dda::Opening;
  using T = ValueType;
  BoundKeys<S> k;
  k.add(key("floor_center", T::vector2).unit("m").required().meaning("middle of the floor"));
  k.field("width", &S::width).unit("m").required().greater_than(0).meaning("floor width");
  k.field("wall_height", &S::wall_height)
      .unit("m")
      .required()
      .at_least(0)
      .meaning("height of the straight walls, floor to springline");
  return k;
}

Section rock_mass_openings_horseshoe_section()
{
  return {"rock_mass.openings[i].horseshoe",
          "A tunnel section: floor of `width`, vertical walls of `wall_height`, and a semicircular "
          "roof of diameter `width` on top of the walls.",
          horseshoe_keys().keys()};
}

} // namespace ddafem::schema
