#include "app/scene/tunnel_scene.h"

#include "common/format.h"
#include "common/input_error.h"
#include "fem/far_field_description.h"

#include <cmath>

namespace ddafem
{
namespace
{

YAML::Node pair(double x, double y)
{
  YAML::Node n(YAML::NodeType::Sequence);
  n.push_back(x);
  n.push_back(y);
  n.SetStyle(YAML::EmitterStyle::Flow);
  return n;
}

YAML::Node triple(double a, double b, double c)
{
  YAML::Node n(YAML::NodeType::Sequence);
  n.push_back(a);
  n.push_back(b);
  n.push_back(c);
  n.SetStyle(YAML::EmitterStyle::Flow);
  return n;
}

/// An on_line block boundary along the segment from a to b.
YAML::Node line_boundary(const dda::BoundaryType type, const Point& a, const Point& b)
{
  YAML::Node n;
  n["type"] = name_of(type);
  n["impedance"] = name_of(dda::ImpedanceKind::effective);
  n["on_line"]["point"] = pair(a.x(), a.y());
  n["on_line"]["direction"] = pair(b.x() - a.x(), b.y() - a.y());
  return n;
}

/// Adds a material `name` of the rock's density and Poisson's ratio and `youngs_modulus` [Pa]
/// to the scene's `materials`; throws InputError if the scene has one of that name (`what` it
/// is, for the message).
void add_material(const TunnelDescription& t, const std::string& name, double youngs_modulus,
                  const std::string& what, YAML::Node& root)
{
  const YAML::Node& given = root;
  if (given["materials"][name])
    throw InputError("the material name `" + name + "` is taken: the tunnel names " + what +
                     " so; expected another name for yours");
  YAML::Node m;
  m["density"] = t.density;
  m["youngs_modulus"] = youngs_modulus;
  m["poisson_ratio"] = t.poisson_ratio;
  YAML::Node materials = YAML::Clone(given["materials"]);
  materials[name] = m;
  root["materials"] = materials;
}

YAML::Node monitor(const std::string& name, double x, double y)
{
  YAML::Node n;
  n["name"] = name;
  n["point"] = pair(x, y);
  n.SetStyle(YAML::EmitterStyle::Flow);
  return n;
}
/// `rock_mass`: the near field's rectangle with the tunnel's joints and opening.
void write_rock_mass(const TunnelDescription& t, const TunnelPlan& plan, const TunnelNodes& nodes,
                     YAML::Node& root)
{
  YAML::Node rock_mass;
  rock_mass["material"] = t.rock;
  rock_mass["region"]["rectangle"]["lower"] = pair(plan.near_lower.x(), plan.near_lower.y());
  rock_mass["region"]["rectangle"]["upper"] = pair(plan.near_upper.x(), plan.near_upper.y());
  if (nodes.joint_sets)
    rock_mass["joint_sets"] = nodes.joint_sets;
  if (nodes.joints)
    rock_mass["joints"] = nodes.joints;
  rock_mass["openings"].push_back(nodes.opening);
  rock_mass["seed"] = static_cast<long long>(t.rock_mass.seed);
  rock_mass["chord_tolerance"] = t.rock_mass.chord_tolerance;
  root["rock_mass"] = rock_mass;
}

/// `in_situ_stress`: lithostatic, with k0 horizontally; returns the opening's centre height [m].
double write_in_situ_stress(const TunnelDescription& t, const TunnelPlan& plan, YAML::Node& root)
{
  // Lithostatic stress, tension positive: sigma_yy = -rho g (depth of the point).
  const double center_y = 0.5 * (plan.opening_lower.y() + plan.opening_upper.y());
  const double syy = -t.density * t.gravity * t.depth, gradient = t.density * t.gravity;
  YAML::Node in_situ;
  in_situ["stress"] = triple(t.k0 * syy, syy, 0.0);
  in_situ["stress_gradient"] = triple(t.k0 * gradient, gradient, 0.0);
  in_situ["reference_y"] = center_y;
  root["in_situ_stress"] = in_situ;

  return center_y;
}

/// `far_field` and `interface`: the equivalent rock mass around the near field's blocks.
void write_far_field(const TunnelDescription& t, const TunnelPlan& plan, const YAML::Node& input,
                     YAML::Node& root)
{
  add_material(t, "rock_mass_equivalent", plan.rock_mass_modulus, "the far field's material", root);

  YAML::Node f;
  f["material"] = "rock_mass_equivalent";
  f["lower"] = pair(plan.far_lower.x(), plan.far_lower.y());
  f["upper"] = pair(plan.far_upper.x(), plan.far_upper.y());
  f["element_size"] = plan.far_element_size;
  f["max_frequency"] = t.max_frequency;
  f["points_per_wavelength"] = t.points_per_wavelength;
  f["degree"] = 2;
  f["hole"]["shape"] = name_of(fem::HoleShape::rectangle);
  f["hole"]["lower"] = pair(plan.near_lower.x(), plan.near_lower.y());
  f["hole"]["upper"] = pair(plan.near_upper.x(), plan.near_upper.y());
  f["hole"]["element_size"] = plan.near_element_size;
  f["hole"]["growth_ratio"] = t.growth_ratio;
  const auto boundary = [](const fem::BoundaryPart part, const fem::BoundaryKind type)
  {
    YAML::Node b;
    b["part"] = name_of(part);
    b["type"] = name_of(type);
    b.SetStyle(YAML::EmitterStyle::Flow);
    return b;
  };
  using fem::BoundaryKind;
  using fem::BoundaryPart;
  f["boundaries"].push_back(boundary(BoundaryPart::bottom, BoundaryKind::input));
  f["boundaries"].push_back(boundary(BoundaryPart::left, BoundaryKind::free_field));
  f["boundaries"].push_back(boundary(BoundaryPart::right, BoundaryKind::free_field));
  f["boundaries"].push_back(
      boundary(BoundaryPart::top, plan.top_is_surface ? BoundaryKind::free : BoundaryKind::lysmer));
  f["incident"] = input;
  root["far_field"] = f;
  YAML::Node interface;
  interface["part"] = name_of(fem::BoundaryPart::hole);
  root["interface"] = interface;
}

/// The outer blocks' material, their bonded joints with each other and with the rock.
void write_outer_joints(const TunnelDescription& t, const TunnelPlan& plan, YAML::Node& root)
{
  const YAML::Node& given = root; // lookups without creating keys
  add_material(t, "outer_rock", plan.outer_youngs_modulus, "the outer blocks' material", root);
  if (given["joint_materials"]["outer_bond"])
    throw InputError("the joint material name `outer_bond` is taken: the tunnel names the outer "
                     "blocks' joints so; expected another name for yours");
  YAML::Node j;
  j["normal_stiffness"] = plan.outer_joint_stiffness;
  j["shear_ratio"] = plan.outer_shear_ratio;
  j["cohesion"] = plan.outer_strength;
  j["tensile_strength"] = plan.outer_strength;
  j["bonded"] = true;
  YAML::Node joint_materials = given["joint_materials"] ? YAML::Clone(given["joint_materials"])
                                                        : YAML::Node(YAML::NodeType::Map);
  joint_materials["outer_bond"] = j;
  root["joint_materials"] = joint_materials;
  YAML::Node joints =
      given["joints"] ? YAML::Clone(given["joints"]) : YAML::Node(YAML::NodeType::Map);
  for (const std::string& other : {t.rock, std::string("outer_rock")})
  {
    YAML::Node entry;
    entry["materials"].push_back("outer_rock");
    entry["materials"].push_back(other);
    entry["materials"].SetStyle(YAML::EmitterStyle::Flow);
    entry["joint"] = "outer_bond";
    entry.SetStyle(YAML::EmitterStyle::Flow);
    joints["pairs"].push_back(entry);
  }
  root["joints"] = joints;
}

/// `blocks` (the outer grids) and `boundaries` (dashpots around them, the wave at the base).
void write_outer_blocks(const TunnelPlan& plan, const YAML::Node& input, YAML::Node& root)
{
  YAML::Node blocks(YAML::NodeType::Sequence);
  for (const BlockGrid& g : plan.outer_grids)
  {
    YAML::Node b;
    b["material"] = "outer_rock";
    b["grid"]["origin"] = pair(g.origin.x(), g.origin.y());
    b["grid"]["cell_size"] = pair(g.cell_size.x(), g.cell_size.y());
    YAML::Node count(YAML::NodeType::Sequence);
    count.push_back(static_cast<long long>(g.count[0]));
    count.push_back(static_cast<long long>(g.count[1]));
    count.SetStyle(YAML::EmitterStyle::Flow);
    b["grid"]["count"] = count;
    blocks.push_back(b);
  }
  root["blocks"] = blocks;

  // Textbook impedance of E_o scaled to E_eff's (VP and VS go with sqrt(E) at a fixed nu): the
  // dashpots rho VP and rho VS of the rock mass, as the far field's Lysmer base.
  const double a = std::sqrt(plan.rock_mass_modulus / plan.outer_youngs_modulus);
  const auto dashpot = [&](const Point& from, const Point& to)
  {
    YAML::Node b = line_boundary(dda::BoundaryType::dashpot, from, to);
    b["impedance"] = name_of(dda::ImpedanceKind::textbook);
    b["a_n"] = a;
    b["a_t"] = a;
    return b;
  };
  const Point& lo = plan.far_lower;
  const Point& hi = plan.far_upper;
  YAML::Node base = dashpot(lo, Point(hi.x(), lo.y()));
  base["input"] = input;
  YAML::Node boundaries(YAML::NodeType::Sequence);
  boundaries.push_back(base);
  boundaries.push_back(dashpot(Point(hi.x(), lo.y()), hi));
  if (!plan.top_is_surface)
    boundaries.push_back(dashpot(hi, Point(lo.x(), hi.y())));
  boundaries.push_back(dashpot(Point(lo.x(), hi.y()), lo));
  root["boundaries"] = boundaries;
}

/// `boundaries` of the near field's blocks (the truncation vb1 or dashpot is their type, the
/// wave enters at the base).
void write_near_boundaries(const TunnelDescription& t, const TunnelPlan& plan,
                           const YAML::Node& input, YAML::Node& root)
{
  const Point& lo = plan.near_lower;
  const Point& hi = plan.near_upper;
  const dda::BoundaryType type =
      t.truncation == TunnelTruncation::vb1 ? dda::BoundaryType::vb1 : dda::BoundaryType::dashpot;
  YAML::Node base = line_boundary(type, lo, Point(hi.x(), lo.y()));
  base["input"] = input;
  YAML::Node boundaries(YAML::NodeType::Sequence);
  boundaries.push_back(base);
  boundaries.push_back(line_boundary(type, Point(hi.x(), lo.y()), hi));
  boundaries.push_back(line_boundary(type, hi, Point(lo.x(), hi.y())));
  boundaries.push_back(line_boundary(type, Point(lo.x(), hi.y()), lo));
  root["boundaries"] = boundaries;
}

/// `monitors` just outside the opening and where the wave enters the blocks, after the user's.
void write_monitors(const TunnelPlan& plan, double center_y, YAML::Node& root)
{
  const YAML::Node& given = root; // lookups without creating keys
  const double offset = 0.1 * plan.mean_block_size;
  const double cx = 0.5 * (plan.opening_lower.x() + plan.opening_upper.x());
  YAML::Node monitors =
      given["monitors"] ? YAML::Clone(given["monitors"]) : YAML::Node(YAML::NodeType::Sequence);
  monitors.push_back(monitor("crown", cx, plan.opening_upper.y() + offset));
  monitors.push_back(monitor("invert", cx, plan.opening_lower.y() - offset));
  monitors.push_back(monitor("left_wall", plan.opening_lower.x() - offset, center_y));
  monitors.push_back(monitor("right_wall", plan.opening_upper.x() + offset, center_y));
  monitors.push_back(monitor("near_field_base", cx, plan.near_lower.y() + offset));
  root["monitors"] = monitors;
}

/// `linings`: the user's, and tunnel.lining's around the opening (rock_mass.openings[0]),
/// installed after the static excavation stage (it carries the dynamic increment).
void write_lining(const YAML::Node& lining, YAML::Node& root)
{
  const YAML::Node& given = root; // lookups without creating keys
  YAML::Node linings =
      given["linings"] ? YAML::Clone(given["linings"]) : YAML::Node(YAML::NodeType::Sequence);
  for (const YAML::Node& l : given["linings"])
    if (l["name"] && l["name"].as<std::string>() == "lining")
      throw InputError("the lining name `lining` is taken: the tunnel names its lining so; "
                       "expected another name for yours");
  YAML::Node l = YAML::Clone(lining);
  l["name"] = "lining";
  l["opening"] = 0;
  l["installed_after"] = "excavate";
  linings.push_back(l);
  root["linings"] = linings;
}

/// `stages`: excavate (static), shake (dynamic) and, if planned, settle.
void write_stages(const TunnelDescription& t, const TunnelPlan& plan, YAML::Node& root)
{
  YAML::Node stage_static, stage_dynamic;
  stage_static["name"] = "excavate";
  stage_static["mode"] = name_of(dda::StageMode::static_equilibrium);
  stage_static["dt"] = plan.static_dt;
  stage_static["tolerance"] = t.static_tolerance;
  stage_static["max_steps"] = t.static_max_steps;
  stage_static["release"] = name_of(t.static_release);
  stage_dynamic["name"] = "shake";
  stage_dynamic["mode"] = name_of(dda::StageMode::dynamic);
  YAML::Node stages(YAML::NodeType::Sequence);
  stages.push_back(stage_static);
  stages.push_back(stage_dynamic);
  if (plan.settle)
  {
    YAML::Node stage_settle;
    stage_settle["name"] = "settle";
    stage_settle["mode"] = dda::settle_mode_name;
    stage_settle["rest_speed"] = plan.settle->rest_speed;
    stage_settle["rest_duration"] = plan.settle->rest_duration;
    stage_settle["fall_distance"] = plan.settle->fall_distance;
    stage_settle["max_duration"] = plan.settle->max_duration;
    stage_settle["remove_fallen"] = plan.settle->remove_fallen;
    stages.push_back(stage_settle);
  }
  root["stages"] = stages;
}

/// `time` and `output`: the plan's step, end and snapshot interval unless the user gave them.
void write_time_and_output(const TunnelPlan& plan, YAML::Node& root)
{
  const YAML::Node& given = root; // lookups without creating keys
  YAML::Node time = given["time"] ? YAML::Clone(given["time"]) : YAML::Node(YAML::NodeType::Map);
  if (!time["dt"])
    time["dt"] = plan.dt;
  if (!time["end_time"])
    time["end_time"] = plan.end_time;
  // Blocks step adaptively (cut on a failed step, grow back; tied to a far field, on the
  // levels dt / 2^k).
  if (!time["control"])
    time["control"] = name_of(dda::TimeControl::adaptive);
  root["time"] = time;
  YAML::Node output =
      given["output"] ? YAML::Clone(given["output"]) : YAML::Node(YAML::NodeType::Map);
  if (!output["interval"])
    output["interval"] = plan.end_time / 40.0;
  root["output"] = output;
}
} // namespace

void write_tunnel_sections(const TunnelDescription& t, const TunnelPlan& plan,
                           const TunnelNodes& nodes, YAML::Node& root)
{
  const YAML::Node& given = root; // lookups without creating keys
  for (const char* generated : {"blocks", "rock_mass", "far_field", "interface", "boundaries",
                                "in_situ_stress", "stages", "fixed_points"})
    if (given[generated])
      throw InputError(std::string("the scene has both `tunnel` and `") + generated +
                       "`: the tunnel generates " + generated +
                       "; expected one or the other (see `ddafem check` for what it generates)");

  YAML::Node analysis =
      given["analysis"] ? YAML::Clone(given["analysis"]) : YAML::Node(YAML::NodeType::Map);
  analysis["plane"] = name_of(PlaneMode::strain);
  root["analysis"] = analysis;
  if (!given["gravity"])
    root["gravity"] = pair(0.0, -t.gravity);

  write_rock_mass(t, plan, nodes, root);
  const double center_y = write_in_situ_stress(t, plan, root);

  YAML::Node input;
  input["type"] = name_of(t.wave_type);
  input["velocity"] = nodes.velocity;
  if (plan.far_field)
    write_far_field(t, plan, input, root);
  else if (t.truncation == TunnelTruncation::blocks)
  {
    write_outer_joints(t, plan, root);
    write_outer_blocks(plan, input, root);
  }
  else
    write_near_boundaries(t, plan, input, root);

  write_monitors(plan, center_y, root);
  write_stages(t, plan, root);
  if (nodes.lining)
    write_lining(nodes.lining, root);
  write_time_and_output(plan, root);
}

} // namespace ddafem
