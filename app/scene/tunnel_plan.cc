#include "app/scene/tunnel_plan.h"

#include "common/elasticity.h"
#include "common/format.h"
#include "common/input_error.h"
#include "dda/geometry.h"
#include "dda/jointed_block_modulus.h"
#include "dda/keyblocks.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ddafem
{
namespace
{
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
} // namespace

double outer_block_modulus(double grid_modulus, double normal_stiffness)
{
  // A square block of side s [m] (1 m thick) under a stress sigma [Pa] across two opposite
  // edges shortens by sigma s / E_o; the edge's force sigma s (1 m) [N] on its two springs p
  // [N/m] closes the joint behind it by sigma s (1 m) / (2 p). Over the cell's s:
  // 1 / E_grid = 1 / E_o + (1 m) / (2 p), whatever s is: jointed_block_modulus(E_o, p, s^2, s).
  const double compliance = 1.0 / grid_modulus - 1.0 / (2.0 * normal_stiffness);
  if (!(compliance > 0.0))
    throw InputError("outer blocks with joints of p = " + format_significant(normal_stiffness) +
                     " N/m cannot be as stiff as the rock mass (E_eff " +
                     format_significant(grid_modulus) +
                     " Pa): their two springs per edge alone give at most 2 p = " +
                     format_significant(2.0 * normal_stiffness) +
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
                format_significant(plan.outer_block_size) + " m (" +
                format_significant(t.points_per_wavelength) +
                " per shortest S wavelength, the far field's rule with one point per block), in 8 "
                "grids that tile the ring exactly (cells up to " +
                format_significant(aspect, 3) +
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
  why.push_back("outer material: E_o " + format_significant(plan.outer_youngs_modulus) +
                " Pa = 1 / (1 / E_eff - 1 / (2 p)) with the springs p " +
                format_significant(plan.outer_joint_stiffness) +
                " N/m of joints.default: square blocks bonded by them have the rock mass's E_eff " +
                format_significant(plan.rock_mass_modulus) +
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
  c.fall_distance = dda::FallCriterion{}.fall_fraction * size;
  c.remove_fallen = t.settle_remove_fallen;
  const double fall_time = std::sqrt(2.0 * size / t.gravity);
  c.max_duration =
      t.settle_max_duration > 0.0 ? t.settle_max_duration : c.rest_duration + 2.0 * fall_time;
  why.push_back(
      "settle stage after the wave: until every block moves slower than " +
      format_significant(c.rest_speed) + " m/s for " + format_significant(c.rest_duration) +
      " s or has fallen " + format_significant(c.fall_distance) + " m (1% of the opening's " +
      format_significant(size) + " m), at most " + format_significant(c.max_duration) + " s" +
      (t.settle_max_duration > 0.0 ? std::string(" (tunnel.settle.max_duration)")
                                   : " = rest + twice the " + format_significant(fall_time) +
                                         " s of a fall across the opening") +
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
    why.push_back("near field: " + format_significant(plan.near_upper.x() - plan.near_lower.x()) +
                  " x " + format_significant(plan.near_upper.y() - plan.near_lower.y()) +
                  " m of blocks, as given (tunnel.near_field.lower/upper)");
  }
  else
  {
    const double side = t.size_factor * size.maxCoeff();
    plan.near_lower = center - Point(0.5 * side, 0.5 * side);
    plan.near_upper = center + Point(0.5 * side, 0.5 * side);
    why.push_back("near field: " + format_significant(side) + " x " + format_significant(side) +
                  " m of blocks around the " + format_significant(size.x()) + " x " +
                  format_significant(size.y()) + " m opening, " +
                  format_significant(t.size_factor) +
                  " x its size (tunnel.near_field.size_factor): the joints matter where the "
                  "opening concentrates stress, about a diameter around it");
  }
  if (!(plan.opening_lower.x() > plan.near_lower.x() &&
        plan.opening_lower.y() > plan.near_lower.y() &&
        plan.opening_upper.x() < plan.near_upper.x() &&
        plan.opening_upper.y() < plan.near_upper.y()))
    throw InputError("the opening (" + format_significant(plan.opening_lower.x()) + ", " +
                     format_significant(plan.opening_lower.y()) + ") to (" +
                     format_significant(plan.opening_upper.x()) + ", " +
                     format_significant(plan.opening_upper.y()) +
                     ") does not lie inside the near field: expected a larger near field");
  plan.surface_y = center.y() + t.depth;
  if (plan.near_upper.y() >= plan.surface_y)
    throw InputError("the near field reaches y = " + format_significant(plan.near_upper.y()) +
                     " m, above the ground surface at y = " + format_significant(plan.surface_y) +
                     " m (the opening's centre " + format_significant(t.depth) +
                     " m deep): expected a deeper tunnel or a smaller near field");
}

/// The shortest S wavelength [m] and VB I's time-step limit [s] of the near field's worst edge
/// block, found while measuring the blocks.
struct BlockMeasures
{
  double wavelength = 0.0;
  double vb1_limit = std::numeric_limits<double>::infinity();
};

/// Refuses a far field (with the near field's blocks) estimated beyond the memory limit before
/// it is made: names tunnel.wave.max_frequency, which sets its element size, and the largest
/// value that fits (DOFs ~ max_frequency^2).
void require_far_field_fits(const TunnelDescription& t, const TunnelPlan& plan)
{
  const Point far = plan.far_upper - plan.far_lower, near = plan.near_upper - plan.near_lower;
  const double dofs =
      estimate_far_field_dofs(far.x() * far.y(), plan.far_element_size, 2.0 * (near.x() + near.y()),
                              plan.near_element_size, t.growth_ratio, 2);
  const double blocks = MemoryModel::per_block * static_cast<double>(plan.n_blocks);
  const double bytes = MemoryModel::of_far_field(dofs) + blocks;
  if (t.limits.fits(bytes))
    return;
  const double dofs_fit =
      std::max(MemoryModel::far_field_dofs_within(t.limits.memory - blocks), 1.0);
  throw InputError("tunnel.wave.max_frequency = " + format_significant(t.max_frequency) +
                   " Hz (2 x the wave's frequency unless given): about " +
                   format_number(std::round(dofs)) + " far-field DOFs and " +
                   std::to_string(plan.n_blocks) + " blocks would need " +
                   t.limits.too_much(bytes) + ": expected a highest frequency of at most " +
                   format_significant(t.max_frequency * std::sqrt(dofs_fit / dofs), 3) +
                   " Hz (or fewer tunnel.points_per_wavelength)");
}

/// The message of a near field beyond the limits, naming the tunnel's key and its value.
std::string near_field_refusal(const dda::RockMassDescription& d,
                               const dda::RockMassTooLarge& refusal)
{
  using Key = dda::RockMassTooLarge::Key;
  const std::string name = name_of(refusal.key);
  std::string key = "tunnel." + name;
  if (refusal.key == Key::spacing || refusal.key == Key::trace_length)
  {
    const dda::JointSet& set = d.joint_sets[refusal.joint_set];
    key = "tunnel.joint_sets[" + std::to_string(refusal.joint_set) + "]." + name + " = " +
          format_significant(refusal.key == Key::spacing ? set.spacing : set.trace_length) + " m";
  }
  else if (refusal.key == Key::chord_tolerance)
    key += " = " + format_significant(d.chord_tolerance) + " m";
  return key + ", in the near field: " + refusal.message;
}

/// The near field's blocks, generated once to measure them: their number and size, the rock
/// mass's modulus where the far field meets them and its wave speeds (plan.n_blocks,
/// mean_block_size, rock_mass_modulus, vp, vs, wave_speed).
BlockMeasures plan_rock_mass(const TunnelDescription& t, TunnelPlan& plan)
{
  std::vector<std::string>& why = plan.reasons;
  dda::RockMassDescription d = t.rock_mass;
  d.region = {plan.near_lower, Point(plan.near_upper.x(), plan.near_lower.y()), plan.near_upper,
              Point(plan.near_lower.x(), plan.near_upper.y())};
  if (const auto refusal = dda::refuse_beyond(d, 0, t.limits))
    throw InputError(near_field_refusal(d, *refusal));
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
            ? dda::jointed_block_modulus(t.youngs_modulus, t.joint_normal_stiffness, b.area, length)
            : t.youngs_modulus;
    sum += length * e;
    weight += length;
    // VB I's bound dt <= m / cn (docs/reference/physics.md eq. 44) with m = rho A and cn = rho L
    // VP.
    measures.vb1_limit = std::min(measures.vb1_limit, b.area / (length * vp_rock));
  }
  plan.rock_mass_modulus = weight > 0.0 ? sum / weight : t.youngs_modulus;
  const double nu = t.poisson_ratio, rho = t.density, e = plan.rock_mass_modulus;
  plan.vp = p_wave_speed(e, nu, rho);
  plan.vs = s_wave_speed(e, nu, rho);
  plan.wave_speed = t.wave_type == WaveType::p ? plan.vp : plan.vs;
  why.push_back("blocks: " + std::to_string(plan.n_blocks) + ", mean size " +
                format_significant(plan.mean_block_size) + " m, shortest edge " +
                format_significant(blocks.statistics.shortest_edge) + " m; rock mass E_eff " +
                format_significant(plan.rock_mass_modulus) + " Pa (intact " +
                format_significant(t.youngs_modulus) +
                " Pa with the joints behind the near field's edge): VP " +
                format_significant(plan.vp) + " m/s, VS " + format_significant(plan.vs) + " m/s");
  measures.wavelength = plan.vs / t.max_frequency;
  const double wavelength = measures.wavelength;
  why.push_back("shortest S wavelength " + format_significant(wavelength) + " m at " +
                format_significant(t.max_frequency) + " Hz: " +
                format_significant(wavelength / plan.mean_block_size) + " blocks per wavelength");
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
    why.push_back("far field: " + format_significant(plan.margin) + " m beyond the blocks" +
                  (t.margin > 0.0 ? std::string(" (tunnel.margin)")
                                  : ", one wavelength of the incident wave at " +
                                        format_significant(t.wave_frequency) +
                                        " Hz: what the opening scatters meets the dashpots "
                                        "nearly normally (tunnel.margin overrides)"));
  }
  else
  {
    // Nothing reflected at the truncation may return to the opening before the end: a P
    // wave from the near field's edge there and back takes 2 margin / VP.
    plan.margin = t.reference_margin > 0.0 ? t.reference_margin : 0.5 * plan.vp * window;
    why.push_back(std::string(outer) + " (" + name_of(t.truncation) +
                  "): " + format_significant(plan.margin) + " m beyond the near field" +
                  (t.reference_margin > 0.0
                       ? std::string(" (tunnel.reference_margin)")
                       : ": a P wave reflected at the truncation needs more than the " +
                             format_significant(window) + " s window to come back"));
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
    why.push_back("outer blocks: " + format_significant(plan.side_margin) +
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
                  " the ground surface at y = " + format_significant(plan.surface_y) +
                  " m: its top is traction free");
  }
  else if (outer_blocks)
    why.push_back("the ground surface (y = " + format_significant(plan.surface_y) +
                  " m) lies beyond the outer blocks: their top absorbs (dashpot)");
  else
    why.push_back("the ground surface (y = " + format_significant(plan.surface_y) +
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
    std::string reason = "20 steps per period at " + format_significant(t.max_frequency) + " Hz";
    if (t.truncation == TunnelTruncation::vb1 && 0.9 * vb1_limit < plan.dt)
    {
      plan.dt = 0.9 * vb1_limit;
      reason = "0.9 x VB I's limit m / cn = " + format_significant(vb1_limit) +
               " s of the worst boundary block";
    }
    if (outer_blocks)
      reason += " (the consistent dashpot dissipates at any dt: no limit)";
    why.push_back("dt " + format_significant(plan.dt) + " s: " + reason);
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
    static_reason = " = 1 ms x " + format_significant(scale) +
                    ", the model's size over the near field's: it settles in about as many "
                    "steps as the near field alone";
  why.push_back("static stage: pseudo time step " + format_significant(plan.static_dt) + " s" +
                static_reason);
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
    why.push_back("far elements FE_Q2 of " + format_significant(plan.far_element_size) + " m (" +
                  format_significant(t.points_per_wavelength) + " nodes per S wavelength at " +
                  format_significant(t.max_frequency) + " Hz), " +
                  format_significant(plan.near_element_size) +
                  " m at the blocks (their mean size), growing by " +
                  format_significant(t.growth_ratio));
    require_far_field_fits(t, plan);
  }
  else
    why.push_back("no far field: the blocks' outer edges carry " +
                  std::string(name_of(t.truncation)) +
                  " boundaries and the wave enters at their base");

  plan.end_time = plan.arrival_time + window;
  why.push_back("dynamic stage: " + format_significant(plan.end_time) +
                " s = " + format_significant(plan.arrival_time) +
                " s for the wave to reach the blocks + " + format_significant(window) +
                " s to cross them, the pulse and two periods after it" +
                (t.window > 0.0 ? std::string(" (tunnel.window)") : std::string()));
  plan_time_steps(t, measures.vb1_limit, plan);
  if (t.settle)
    plan.settle = plan_settle_stage(t, plan, why);
  else
    why.push_back("no settle stage (tunnel.settle.enabled false): the run ends with the window");
  return plan;
}

} // namespace ddafem
