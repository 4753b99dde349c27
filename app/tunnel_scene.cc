#include "app/tunnel_scene.h"

#include "app/keyblocks.h"
#include "app/run_support.h"

#include "common/elasticity.h"
#include "common/input_error.h"
#include "dda/geometry.h"
#include "fem/far_field_description.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ddafem
{
namespace
{
using run_support::format;

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

/// Length [m] of the polygon's edges lying on the rectangle's sides (to `tolerance`).
double length_on_rectangle(const std::vector<Point>& vertices, const Point& lower,
                           const Point& upper, double tolerance)
{
  const auto on_side = [&](const Point& a, const Point& b)
  {
    return (std::abs(a.x() - lower.x()) < tolerance && std::abs(b.x() - lower.x()) < tolerance) ||
           (std::abs(a.x() - upper.x()) < tolerance && std::abs(b.x() - upper.x()) < tolerance) ||
           (std::abs(a.y() - lower.y()) < tolerance && std::abs(b.y() - lower.y()) < tolerance) ||
           (std::abs(a.y() - upper.y()) < tolerance && std::abs(b.y() - upper.y()) < tolerance);
  };
  double length = 0.0;
  for (std::size_t k = 0; k < vertices.size(); ++k)
  {
    const Point& a = vertices[k];
    const Point& b = vertices[(k + 1) % vertices.size()];
    if (on_side(a, b))
      length += (b - a).norm();
  }
  return length;
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
} // namespace

double outer_block_modulus(double grid_modulus, double normal_stiffness)
{
  // A square block of side s [m] (1 m thick) under a stress sigma [Pa] across two opposite
  // edges shortens by sigma s / E_o; the edge's force sigma s (1 m) [N] on its two springs p
  // [N/m] closes the joint behind it by sigma s (1 m) / (2 p). Over the cell's s:
  // 1 / E_grid = 1 / E_o + (1 m) / (2 p), whatever s is: jointed_block_modulus(E_o, p, s^2, s).
  const double compliance = 1.0 / grid_modulus - 1.0 / (2.0 * normal_stiffness);
  if (!(compliance > 0.0))
    throw InputError("outer blocks with joints of p = " + format(normal_stiffness) +
                     " N/m cannot be as stiff as the rock mass (E_eff " + format(grid_modulus) +
                     " Pa): their two springs per edge alone give at most 2 p = " +
                     format(2.0 * normal_stiffness) +
                     " Pa; expected a stiffer `joints.default` (2 p > E_eff)");
  return 1.0 / compliance;
}

namespace
{
/// The blocks truncation's ring of outer blocks from the near field out to plan.far_lower /
/// far_upper, their material and their joints (plan.outer_*), and why (plan.reasons).
void plan_outer_blocks(const TunnelDescription& t, double wavelength, TunnelPlan& plan)
{
  std::vector<std::string>& why = plan.reasons;
  if (!(t.joint_normal_stiffness > 0.0))
    throw InputError("truncation blocks bonds its outer blocks with the springs of "
                     "`joints.default`: expected a `joints.default` joint material");
  // Each block is one point of a linear displacement field (like a Q1 element): the far
  // field's rule of points_per_wavelength points per shortest S wavelength gives its side. Not
  // graded: the FE far field grows from the blocks' size up to its wavelength rule, but here
  // the rule is already the coarsest size allowed, and the near field's blocks are not much
  // smaller (mean_block_size), so a grading would only add rows.
  plan.outer_block_size = wavelength / t.points_per_wavelength;
  // The 3 x 3 tensor grid: margin, near field, margin in x and in y, each split into cells as
  // close to outer_block_size as divide it exactly; its 8 outer rectangles are the grids.
  const auto split = [&](double lo, double hi)
  {
    const double length = hi - lo;
    const std::size_t n = std::max<std::size_t>(
        1, static_cast<std::size_t>(std::llround(length / plan.outer_block_size)));
    return std::make_pair(n, length / static_cast<double>(n));
  };
  const std::array<double, 4> xs = {plan.far_lower.x(), plan.near_lower.x(), plan.near_upper.x(),
                                    plan.far_upper.x()};
  const std::array<double, 4> ys = {plan.far_lower.y(), plan.near_lower.y(), plan.near_upper.y(),
                                    plan.far_upper.y()};
  double aspect = 1.0; // largest ratio of a cell's long to short side
  plan.outer_grids.clear();
  plan.n_outer_blocks = 0;
  for (std::size_t j = 0; j < 3; ++j)
    for (std::size_t i = 0; i < 3; ++i)
    {
      if (i == 1 && j == 1)
        continue; // the near field
      const auto [nx, wx] = split(xs[i], xs[i + 1]);
      const auto [ny, wy] = split(ys[j], ys[j + 1]);
      plan.outer_grids.push_back({Point(xs[i], ys[j]), Point(wx, wy), {nx, ny}});
      plan.n_outer_blocks += nx * ny;
      aspect = std::max(aspect, std::max(wx, wy) / std::min(wx, wy));
    }
  why.push_back("outer blocks: " + std::to_string(plan.n_outer_blocks) + " rectangles of about " +
                format(plan.outer_block_size) + " m (" + format(t.points_per_wavelength) +
                " per shortest S wavelength, the far field's rule with one point per block), in 8 "
                "grids that tile the ring exactly (cells up to " +
                format(aspect, 3) +
                " times longer than wide); not graded: that size is already the coarsest allowed");

  // Material and joints. Square cells of E_o with two springs p per edge have the rock mass's
  // E_eff (outer_block_modulus, whatever their size); shear springs p / (1 + nu) give them its
  // G_eff = E_eff / (2 (1 + nu)) too: in a grid under a shear stress tau both joint sets slip by
  // tau s (1 m) / (2 p_s) per cell, so 1 / G_grid = 1 / G_o + (1 m) / p_s, and
  // 1 / G_eff - 1 / G_o = 2 (1 + nu) (1 / E_eff - 1 / E_o) = (1 + nu) / p (per metre).
  plan.outer_joint_stiffness = t.joint_normal_stiffness;
  plan.outer_youngs_modulus = outer_block_modulus(plan.rock_mass_modulus, t.joint_normal_stiffness);
  plan.outer_shear_ratio = 1.0 / (1.0 + t.poisson_ratio);
  // Never breaks: a stress of E_eff would need a strain of 1.
  plan.outer_strength = plan.rock_mass_modulus;
  why.push_back("outer material: E_o " + format(plan.outer_youngs_modulus) +
                " Pa = 1 / (1 / E_eff - 1 / (2 p)) with the springs p " +
                format(plan.outer_joint_stiffness) +
                " N/m of joints.default: square blocks bonded by them have the rock mass's E_eff " +
                format(plan.rock_mass_modulus) +
                " Pa (the far field's), so the near field's edge "
                "reflects nothing; shear springs p / (1 + nu) for its G_eff; density and nu of the "
                "rock; joints that never break (cohesion and tensile strength E_eff)");
  why.push_back("outer edges: dashpots (rho VP and rho VS of E_eff) on the sides and base" +
                std::string(plan.top_is_surface ? "" : " and top") +
                ", the incident wave entering at the base");
}

/// The settle stage's criterion: falls measured as the keyblocks' (FallCriterion, 1% of the
/// opening's size), the bound twice a fall across the opening from rest.
dda::SettleCriterion plan_settle_stage(const TunnelDescription& t, const TunnelPlan& plan,
                                       std::vector<std::string>& why)
{
  const double size = (plan.opening_upper - plan.opening_lower).maxCoeff();
  dda::SettleCriterion c;
  c.rest_speed = t.settle_rest_speed;
  c.rest_duration =
      t.settle_rest_duration > 0.0 ? t.settle_rest_duration : std::max(0.1, 1.0 / t.wave_frequency);
  c.fall_distance = FallCriterion{}.fall_fraction * size;
  c.remove_fallen = t.settle_remove_fallen;
  const double fall_time = std::sqrt(2.0 * size / t.gravity);
  c.max_duration =
      t.settle_max_duration > 0.0 ? t.settle_max_duration : c.rest_duration + 2.0 * fall_time;
  why.push_back(
      "settle stage after the wave: until every block moves slower than " + format(c.rest_speed) +
      " m/s for " + format(c.rest_duration) + " s or has fallen " + format(c.fall_distance) +
      " m (1% of the opening's " + format(size) + " m), at most " + format(c.max_duration) + " s" +
      (t.settle_max_duration > 0.0
           ? std::string(" (tunnel.settle.max_duration)")
           : " = rest + twice the " + format(fall_time) + " s of a fall across the opening") +
      (c.remove_fallen ? "; a fallen block is removed as debris once it has left its place "
                         "(tunnel.settle.remove_fallen)"
                       : ""));
  return c;
}

/// The opening's bounding box, the near field of blocks around it and the ground surface
/// (plan.opening_*, near_*, surface_y).
void plan_near_field(const TunnelDescription& t, TunnelPlan& plan)
{
  std::vector<std::string>& why = plan.reasons;
  const std::vector<Point> opening =
      dda::opening_polygon(t.rock_mass.openings.front(), t.rock_mass.chord_tolerance);
  plan.opening_lower = plan.opening_upper = opening.front();
  for (const Point& p : opening)
  {
    plan.opening_lower = plan.opening_lower.cwiseMin(p);
    plan.opening_upper = plan.opening_upper.cwiseMax(p);
  }
  const Point size = plan.opening_upper - plan.opening_lower;
  const Point center = 0.5 * (plan.opening_lower + plan.opening_upper);
  if (t.near_field)
  {
    plan.near_lower = (*t.near_field)[0];
    plan.near_upper = (*t.near_field)[1];
    why.push_back("near field: " + format(plan.near_upper.x() - plan.near_lower.x()) + " x " +
                  format(plan.near_upper.y() - plan.near_lower.y()) +
                  " m of blocks, as given (tunnel.near_field.lower/upper)");
  }
  else
  {
    const double side = t.size_factor * size.maxCoeff();
    plan.near_lower = center - Point(0.5 * side, 0.5 * side);
    plan.near_upper = center + Point(0.5 * side, 0.5 * side);
    why.push_back("near field: " + format(side) + " x " + format(side) +
                  " m of blocks around the " + format(size.x()) + " x " + format(size.y()) +
                  " m opening, " + format(t.size_factor) +
                  " x its size (tunnel.near_field.size_factor): the joints matter where the "
                  "opening concentrates stress, about a diameter around it");
  }
  if (!(plan.opening_lower.x() > plan.near_lower.x() &&
        plan.opening_lower.y() > plan.near_lower.y() &&
        plan.opening_upper.x() < plan.near_upper.x() &&
        plan.opening_upper.y() < plan.near_upper.y()))
    throw InputError("the opening (" + format(plan.opening_lower.x()) + ", " +
                     format(plan.opening_lower.y()) + ") to (" + format(plan.opening_upper.x()) +
                     ", " + format(plan.opening_upper.y()) +
                     ") does not lie inside the near field: expected a larger near field");
  plan.surface_y = center.y() + t.depth;
  if (plan.near_upper.y() >= plan.surface_y)
    throw InputError("the near field reaches y = " + format(plan.near_upper.y()) +
                     " m, above the ground surface at y = " + format(plan.surface_y) +
                     " m (the opening's centre " + format(t.depth) +
                     " m deep): expected a deeper tunnel or a smaller near field");
}

/// The shortest S wavelength [m] and VB I's time-step limit [s] of the near field's worst edge
/// block, found while measuring the blocks.
struct BlockMeasures
{
  double wavelength = 0.0;
  double vb1_limit = std::numeric_limits<double>::infinity();
};

/// The near field's blocks, generated once to measure them: their number and size, the rock
/// mass's modulus where the far field meets them and its wave speeds (plan.n_blocks,
/// mean_block_size, rock_mass_modulus, vp, vs, wave_speed).
BlockMeasures plan_rock_mass(const TunnelDescription& t, TunnelPlan& plan)
{
  std::vector<std::string>& why = plan.reasons;
  dda::RockMassDescription d = t.rock_mass;
  d.region = {plan.near_lower, Point(plan.near_upper.x(), plan.near_lower.y()), plan.near_upper,
              Point(plan.near_lower.x(), plan.near_upper.y())};
  const dda::RockMassResult blocks = dda::generate_blocks(d);
  plan.n_blocks = blocks.blocks.size();
  plan.mean_block_size = std::sqrt(blocks.statistics.mean_area);

  // The rock mass's modulus where the far field meets the blocks (coupling/README.md).
  const double tolerance = 1e-9 * (plan.near_upper - plan.near_lower).norm();
  BlockMeasures measures;
  double sum = 0.0, weight = 0.0;
  const double vp_rock = p_wave_speed(t.youngs_modulus, t.poisson_ratio, t.density);
  for (const dda::RockMassBlock& b : blocks.blocks)
  {
    const double length =
        length_on_rectangle(b.vertices, plan.near_lower, plan.near_upper, tolerance);
    if (length <= 0.0)
      continue;
    const double e =
        t.joint_normal_stiffness > 0.0
            ? jointed_block_modulus(t.youngs_modulus, t.joint_normal_stiffness, b.area, length)
            : t.youngs_modulus;
    sum += length * e;
    weight += length;
    // VB I's bound dt <= m / cn (physics.md eq. 44) with m = rho A and cn = rho L VP.
    measures.vb1_limit = std::min(measures.vb1_limit, b.area / (length * vp_rock));
  }
  plan.rock_mass_modulus = weight > 0.0 ? sum / weight : t.youngs_modulus;
  const double nu = t.poisson_ratio, rho = t.density, e = plan.rock_mass_modulus;
  plan.vp = p_wave_speed(e, nu, rho);
  plan.vs = s_wave_speed(e, nu, rho);
  plan.wave_speed = t.wave_type == WaveType::p ? plan.vp : plan.vs;
  why.push_back("blocks: " + std::to_string(plan.n_blocks) + ", mean size " +
                format(plan.mean_block_size) + " m, shortest edge " +
                format(blocks.statistics.shortest_edge) + " m; rock mass E_eff " +
                format(plan.rock_mass_modulus) + " Pa (intact " + format(t.youngs_modulus) +
                " Pa with the joints behind the near field's edge): VP " + format(plan.vp) +
                " m/s, VS " + format(plan.vs) + " m/s");
  measures.wavelength = plan.vs / t.max_frequency;
  const double wavelength = measures.wavelength;
  why.push_back("shortest S wavelength " + format(wavelength) + " m at " + format(t.max_frequency) +
                " Hz: " + format(wavelength / plan.mean_block_size) + " blocks per wavelength");
  return measures;
}

/// How far the far field (or the outer blocks) reaches beyond the near field, and why
/// (plan.margin, side_margin, far_lower/upper, top_is_surface, arrival_time); `window` [s] is
/// the time the wave needs to cross the blocks.
void plan_extent(const TunnelDescription& t, double window, TunnelPlan& plan)
{
  std::vector<std::string>& why = plan.reasons;
  const bool outer_blocks = t.truncation == TunnelTruncation::blocks;
  const char* const outer = outer_blocks ? "outer blocks" : "far field";
  const double dominant_wavelength = plan.wave_speed / t.wave_frequency;
  if (t.truncation == TunnelTruncation::hybrid)
  {
    plan.margin = t.margin > 0.0 ? t.margin : dominant_wavelength;
    why.push_back("far field: " + format(plan.margin) + " m beyond the blocks" +
                  (t.margin > 0.0
                       ? std::string(" (tunnel.margin)")
                       : ", one wavelength of the incident wave at " + format(t.wave_frequency) +
                             " Hz: what the opening scatters meets the dashpots "
                             "nearly normally (tunnel.margin overrides)"));
  }
  else
  {
    // Nothing reflected at the truncation may return to the opening before the end: a P
    // wave from the near field's edge there and back takes 2 margin / VP.
    plan.margin = t.reference_margin > 0.0 ? t.reference_margin : 0.5 * plan.vp * window;
    why.push_back(std::string(outer) + " (" + name_of(t.truncation) + "): " + format(plan.margin) +
                  " m beyond the near field" +
                  (t.reference_margin > 0.0
                       ? std::string(" (tunnel.reference_margin)")
                       : ": a P wave reflected at the truncation needs more than the " +
                             format(window) + " s window to come back"));
  }
  plan.side_margin = plan.margin;
  if (outer_blocks && !(t.reference_margin > 0.0))
  {
    // The side dashpots resist the free-field motion itself (there are no free-field columns
    // for blocks): they radiate from the moment the wave enters at the base corners, a margin
    // below and side_margin beside the near field. Their P waves must not reach the near
    // field before the end, margin / wave_speed + window after the entry.
    const double reach = plan.vp * (plan.margin / plan.wave_speed + window);
    plan.side_margin = std::max(plan.margin, std::sqrt(reach * reach - plan.margin * plan.margin));
    why.push_back("outer blocks: " + format(plan.side_margin) +
                  " m beside the near field: the side dashpots resist the free-field motion and "
                  "radiate from the base corners; their P waves reach the near field after the "
                  "end");
  }
  plan.far_lower = plan.near_lower - Point(plan.side_margin, plan.margin);
  plan.far_upper = plan.near_upper + Point(plan.side_margin, plan.margin);
  if (plan.far_upper.y() >= plan.surface_y)
  {
    plan.far_upper.y() = plan.surface_y;
    plan.top_is_surface = true;
    why.push_back("the " + std::string(outer) + (outer_blocks ? " reach" : " reaches") +
                  " the ground surface at y = " + format(plan.surface_y) +
                  " m: its top is traction free");
  }
  else if (outer_blocks)
    why.push_back("the ground surface (y = " + format(plan.surface_y) +
                  " m) lies beyond the outer blocks: their top absorbs (dashpot)");
  else
    why.push_back("the ground surface (y = " + format(plan.surface_y) +
                  " m) lies beyond the far field: its top absorbs (Lysmer), its base takes the "
                  "incident wave (Lysmer with the input traction), its sides are free-field "
                  "columns");
  plan.arrival_time = (plan.near_lower.y() - plan.far_lower.y()) / plan.wave_speed;
}

/// The dynamic stage's dt and the static stage's pseudo time step, and why (plan.dt,
/// static_dt); `vb1_limit` [s] as BlockMeasures.
void plan_time_steps(const TunnelDescription& t, double vb1_limit, TunnelPlan& plan)
{
  std::vector<std::string>& why = plan.reasons;
  const bool outer_blocks = t.truncation == TunnelTruncation::blocks;
  if (t.dt > 0.0)
    plan.dt = t.dt;
  else
  {
    plan.dt = 1.0 / (20.0 * t.max_frequency);
    std::string reason = "20 steps per period at " + format(t.max_frequency) + " Hz";
    if (t.truncation == TunnelTruncation::vb1 && 0.9 * vb1_limit < plan.dt)
    {
      plan.dt = 0.9 * vb1_limit;
      reason =
          "0.9 x VB I's limit m / cn = " + format(vb1_limit) + " s of the worst boundary block";
    }
    if (outer_blocks)
      reason += " (the consistent dashpot dissipates at any dt: no limit)";
    why.push_back("dt " + format(plan.dt) + " s: " + reason);
  }
  // The static stage relaxes the model from the excavation outward; each pseudo step carries
  // that about a P wave's c dt, so a model k times the near field's size wants k times the
  // near field's 1 ms to settle in as many steps.
  const double scale = outer_blocks ? (plan.far_upper - plan.far_lower).maxCoeff() /
                                          (plan.near_upper - plan.near_lower).maxCoeff()
                                    : 1.0;
  plan.static_dt = t.static_dt > 0.0 ? t.static_dt : 1e-3 * scale;
  std::string static_reason;
  if (t.static_dt > 0.0)
    static_reason = " (tunnel.static.dt)";
  else if (outer_blocks)
    static_reason = " = 1 ms x " + format(scale) +
                    ", the model's size over the near field's: it settles in about as many "
                    "steps as the near field alone";
  why.push_back("static stage: pseudo time step " + format(plan.static_dt) + " s" + static_reason);
}

} // namespace

TunnelPlan plan_tunnel(const TunnelDescription& t)
{
  TunnelPlan plan;
  plan.truncation = t.truncation;
  std::vector<std::string>& why = plan.reasons;
  plan_near_field(t, plan);
  const BlockMeasures measures = plan_rock_mass(t, plan);

  // The far field, or the outer blocks out to the same extent.
  const double half_height = 0.5 * (plan.near_upper.y() - plan.near_lower.y());
  const double window = t.window > 0.0 ? t.window
                                       : 2.0 * half_height / plan.wave_speed + t.wave_duration +
                                             2.0 / t.wave_frequency;
  plan.far_field =
      t.truncation == TunnelTruncation::hybrid || t.truncation == TunnelTruncation::reference;
  const bool outer_blocks = t.truncation == TunnelTruncation::blocks;
  if (plan.far_field || outer_blocks)
    plan_extent(t, window, plan);
  if (outer_blocks)
    plan_outer_blocks(t, measures.wavelength, plan);
  else if (plan.far_field)
  {
    plan.far_element_size = 2.0 * measures.wavelength / t.points_per_wavelength;
    plan.near_element_size = std::min(plan.mean_block_size, plan.far_element_size);
    plan.elements_per_wavelength = measures.wavelength / plan.far_element_size;
    why.push_back("far elements FE_Q2 of " + format(plan.far_element_size) + " m (" +
                  format(t.points_per_wavelength) + " nodes per S wavelength at " +
                  format(t.max_frequency) + " Hz), " + format(plan.near_element_size) +
                  " m at the blocks (their mean size), growing by " + format(t.growth_ratio));
  }
  else
    why.push_back("no far field: the blocks' outer edges carry " +
                  std::string(name_of(t.truncation)) +
                  " boundaries and the wave enters at their base");

  plan.end_time = plan.arrival_time + window;
  why.push_back("dynamic stage: " + format(plan.end_time) + " s = " + format(plan.arrival_time) +
                " s for the wave to reach the blocks + " + format(window) +
                " s to cross them, the pulse and two periods after it" +
                (t.window > 0.0 ? std::string(" (tunnel.window)") : std::string()));
  plan_time_steps(t, measures.vb1_limit, plan);
  if (t.settle.value_or(true))
    plan.settle = plan_settle_stage(t, plan, why);
  else
    why.push_back("no settle stage (tunnel.settle.enabled false): the run ends with the window");
  return plan;
}

namespace
{
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
  write_time_and_output(plan, root);
}

} // namespace ddafem
