// The DDA model's construction (blocks, joints, contact settings, attached points, boundaries),
// its stages, ties and observers; the step itself is in system_step.cc.
#include "dda/system.h"

#include "common/input_error.h"
#include "dda/submatrices.h"
#include "dda/system_helpers.h"

#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <sstream>

namespace ddafem::dda
{
bool can_retry_with_smaller_step(StepOutcome outcome)
{
  return outcome == StepOutcome::not_converged || outcome == StepOutcome::displacement_too_large ||
         outcome == StepOutcome::penetration_too_large;
}

Point System::AttachedFixedPoint::target(double t) const
{
  return point.initial + Vector2(displacement_x.value(t), displacement_y.value(t));
}

System::System(const ModelDescription& model_)
    : model(model_), matrix(0, {}), base_matrix(0, {}), tied_matrix(0, {}), solver(model_.solver),
      parallel(model_.solver.threads)
{
  set_material_constants();
  const std::vector<std::string> names = make_blocks();
  const double size = model_size(blocks);
  find_bonded_joints(names, size);
  contact_set.set_up(model, blocks, size, !small_displacement());
  rhs.setZero(static_cast<Eigen::Index>(n_dofs()));
  solution.setZero(static_cast<Eigen::Index>(n_dofs()));
  set_default_fixed_stiffness();
  attach_points();
  select_boundaries(size);
  apply_in_situ_stress();
  // The step's matrix structure: joints now, contacts once found.
  set_matrix_structure({});
  initial_energy = energy().stored();
}

void System::set_material_constants()
{
  integration = integrator_coefficients(model.time.integrator, model.time.spectral_radius);
  for (const Material& m : model.materials)
  {
    elasticity.push_back(elasticity_matrix(m.youngs_modulus, m.poisson_ratio, model.plane_mode));
    compliance.push_back(elasticity.back().inverse());
  }
  for (const JointMaterial& jm : model.joint_materials)
    tan_friction.push_back(std::tan(jm.friction_angle * M_PI / 180.0));
  for (const Material& m : model.materials)
    damped = damped || m.damping.active();
  for (const JointMaterial& jm : model.joint_materials)
    damped = damped || jm.damping.active();
}

std::vector<std::string> System::make_blocks()
{
  std::vector<std::string> names;
  for (std::size_t i = 0; i < model.blocks.size(); ++i)
  {
    const BlockDescription& bd = model.blocks[i];
    blocks.emplace_back(bd.material, bd.vertices);
    Block& b = blocks.back();
    b.velocity.head<2>() = bd.initial_velocity;
    b.stress = bd.initial_stress;
    names.push_back(bd.origin.empty() ? "block " + std::to_string(i) : bd.origin);
  }
  if (blocks.empty())
    throw InputError("the model has no blocks: expected at least one entry in `blocks`");
  held.assign(blocks.size(), false);
  removed.assign(blocks.size(), false);
  return names;
}

void System::find_bonded_joints(const std::vector<std::string>& names, double size)
{
  // Blocks that share an edge through a frictional joint material meet through contacts.
  std::vector<Joint> found = find_joints(blocks, model, names, 1e-9 * size);
  for (const Joint& j : found)
    if (model.joint_materials[j.joint_material].bonded)
      joints.push_back(j);
  if (small_displacement())
    for (const Joint& j : found)
      if (!model.joint_materials[j.joint_material].bonded)
        throw InputError("joint material '" + model.joint_materials[j.joint_material].name +
                         "' (between " + names[j.block_a] + " and " + names[j.block_b] +
                         ") is frictional (`bonded: false`), but `analysis.geometry: "
                         "small_displacement` cannot follow contacts: expected `geometry: "
                         "updated` or a bonded joint material");
}

void System::set_default_fixed_stiffness()
{
  // Fixed-point penalty: 10x the stiffest spring or block in the model (Shi uses a large
  // multiple of the contact penalty), so that fixed points move by < 10% of the joint opening.
  double stiffest = 0.0;
  for (const JointMaterial& jm : model.joint_materials)
    stiffest = std::max(stiffest, jm.normal_stiffness);
  for (const Material& m : model.materials)
    stiffest = std::max(stiffest, m.youngs_modulus * 1.0 /* [Pa] x 1 m */);
  default_fixed_stiffness = 10.0 * stiffest;
}

void System::attach_points()
{
  for (const PointLoad& l : model.point_loads)
    loads.push_back(
        {attach(l.point, l.origin.empty() ? "point load" : l.origin), l.force, l.time_function});
  for (const FixedPoint& f : model.fixed_points)
    fixed_points.push_back({attach(f.point, f.origin.empty() ? "fixed point" : f.origin),
                            f.stiffness > 0.0 ? f.stiffness : default_fixed_stiffness,
                            f.displacement_x, f.displacement_y});
  for (const Monitor& m : model.monitors)
  {
    monitors.push_back(attach(m.point, "monitor " + m.name));
    monitor_origins.push_back(m.point);
  }
  element_kinds = make_element_kinds(model, *this);
}

void System::select_boundaries(double size)
{
  for (std::size_t k = 0; k < model.boundaries.size(); ++k)
  {
    const std::vector<BoundaryEdge> selected =
        select_boundary_edges(k, model, blocks, joints, 1e-6 * size);
    boundary_edges.insert(boundary_edges.end(), selected.begin(), selected.end());
  }
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> owner; // (block, edge) -> boundary
  for (const BoundaryEdge& e : boundary_edges)
  {
    const auto [it, inserted] = owner.emplace(std::make_pair(e.block, e.edge), e.boundary);
    if (!inserted)
      throw InputError(model.boundaries[e.boundary].origin + " selects block " +
                       std::to_string(e.block) + " edge " + std::to_string(e.edge) + ", which " +
                       model.boundaries[it->second].origin +
                       " already has: expected each edge in one boundary only");
  }
  boundary_steps.resize(boundary_edges.size());
}

void System::apply_in_situ_stress()
{
  const InSituStress& in_situ = model.in_situ_stress;
  // The traction sigma0 n, linear along a straight edge from x0 to x1 (length l), as the two
  // end forces that give its exact generalised force for the linear T along the edge:
  // l/6 (2 t0 + t1) and l/6 (t0 + 2 t1) (each end's half, l/2 t, would miss the moment of a
  // stress gradient along the edge on the shear-strain unknown).
  const auto end_forces = [&](const Point& x0, const Point& x1, const Vector2& n, double l)
  {
    const Vector2 t0 = in_situ.traction(x0, n), t1 = in_situ.traction(x1, n);
    return std::array<Vector2, 2>{l / 6.0 * (2.0 * t0 + t1), l / 6.0 * (t0 + 2.0 * t1)};
  };
  // Bonded joints: the traction on block a (n out of a): what b puts on a across the joint in
  // the rock mass at rest.
  for (Joint& j : joints)
  {
    const Vector2 n = j.normal(), t = j.tangent();
    const std::array<Vector2, 2> f =
        end_forces(j.points[0].on_a.position, j.points[1].on_a.position, n, j.length);
    for (std::size_t e = 0; e < 2; ++e)
    {
      JointPoint& p = j.points[e];
      p.normal_preload = p.normal_force = n.dot(f[e]);
      p.shear_preload = p.shear_force = t.dot(f[e]);
    }
  }

  // Static supports of the viscous boundaries' edges: springs like a bonded joint's at both
  // ends (joints.default's, else the fixed points' default penalty), preloaded with the
  // in-situ traction over the edge.
  double ratio = 0.4;
  support_normal_stiffness = default_fixed_stiffness;
  if (model.default_joint_material < model.joint_materials.size())
  {
    const JointMaterial& jm = model.joint_materials[model.default_joint_material];
    support_normal_stiffness = jm.normal_stiffness;
    ratio = jm.shear_ratio;
  }
  for (const BoundaryEdge& e : boundary_edges)
  {
    if (model.boundaries[e.boundary].type == BoundaryType::free)
      continue;
    const std::vector<Point>& v = blocks[e.block].vertices;
    const Vector2 n = boundary_normal(e), t(-n.y(), n.x());
    const Eigen::Matrix2d k =
        support_normal_stiffness * (n * n.transpose() + ratio * (t * t.transpose()));
    const Point& x0 = v[e.edge];
    const Point& x1 = v[(e.edge + 1) % v.size()];
    const std::array<Vector2, 2> f = end_forces(x0, x1, n, e.length);
    supports.push_back({{e.block, x0, x0}, k, f[0], x0});
    supports.push_back({{e.block, x1, x1}, k, f[1], x1});
  }
}

MaterialPoint System::attach(const Point& p, const std::string& what) const
{
  const double tol = 1e-9 * model_size(blocks);
  for (std::size_t i = 0; i < blocks.size(); ++i)
    if (locate_point(blocks[i].vertices, p, tol) != PointLocation::outside)
      return {i, p, p};
  std::ostringstream s;
  s << what << " at (" << p.x() << ", " << p.y()
    << ") lies outside every block: expected a point inside or on a block";
  throw InputError(s.str());
}

void System::tie(TiedBody& body, const std::vector<MaterialPoint>& points)
{
  if (timings.n_attempts > 0)
    throw InputError("tie(): the ties must be made before the first step");
  const double tol = 1e-6 * model_size(blocks);
  for (const MaterialPoint& p : points)
  {
    if (p.block >= blocks.size() ||
        locate_point(blocks[p.block].vertices, p.position, tol) != PointLocation::on_boundary)
    {
      std::ostringstream s;
      s << "tie point (" << p.position.x() << ", " << p.position.y() << ") is not on the boundary "
        << "of block " << p.block << ": expected points on the blocks' outer edges";
      throw InputError(s.str());
    }
    tie_blocks.push_back(p.block);
  }
  std::sort(tie_blocks.begin(), tie_blocks.end());
  tie_blocks.erase(std::unique(tie_blocks.begin(), tie_blocks.end()), tie_blocks.end());
  // Runs of consecutive tie points on one block (FarFieldTies places each block's points
  // together: one run per tie block).
  tie_pairs.set_points(points);
  tied_body = &body;
  tie_points = points;
  tie_origins.clear();
  for (const MaterialPoint& p : points)
    tie_origins.push_back(p.position);
  tie_matrices.resize(points.size());
  set_matrix_structure(coupling_pairs);
  ++contact_set.geometry_epoch;
}

void System::hold_block(std::size_t i)
{
  held[i] = true;
  matrix_dt = 0.0; // assemble the matrix anew, with the hold
}

void System::remove_block(std::size_t i)
{
  Block& b = blocks[i];
  removed_energy += kinetic_energy(b);
  b.velocity.setZero();
  b.acceleration.setZero();
  removed[i] = true;
  matrix_dt = 0.0;
  ++contact_set.geometry_epoch;
  ++joint_revision;
  joints.erase(std::remove_if(joints.begin(), joints.end(),
                              [&](const Joint& j) { return j.block_a == i || j.block_b == i; }),
               joints.end());
}

void System::set_at_rest()
{
  for (Block& b : blocks)
  {
    b.velocity.setZero();
    b.acceleration.setZero();
    b.force.setZero();
  }
  motion_starts = true;
}

void System::begin_stage(StageMode new_mode)
{
  const bool after_static = mode == StageMode::static_equilibrium;
  mode = new_mode;
  matrix_dt = 0.0; // the boundary terms change with the stage: assemble the matrix anew
  ++contact_set.geometry_epoch;
  held.assign(blocks.size(), false);
  for (const std::unique_ptr<ElementKind>& k : element_kinds)
    k->begin_stage(stages_begun, current_time);
  ++stages_begun;
  if (tied_body)
    tied_body->begin_stage(mode);
  if (mode == StageMode::dynamic && !after_static)
    return;
  set_at_rest();
  // Reaction transfer: what the supports hold at the end of a static stage stays as a constant
  // load on the edges; a static stage anchors them where the edges are.
  for (Support& s : supports)
  {
    if (after_static)
      s.load = s.force();
    if (mode == StageMode::static_equilibrium)
      s.anchor = s.point.position;
  }
  if (mode == StageMode::dynamic)
  {
    // Measure the dynamic stage from the equilibrium reached.
    for (std::size_t k = 0; k < monitors.size(); ++k)
      monitor_origins[k] = monitors[k].position;
    for (std::size_t k = 0; k < tie_points.size(); ++k)
      tie_origins[k] = tie_points[k].position;
    work_of_loads = work_of_supports = work_of_boundaries = work_of_damping = 0.0;
    largest_energy_input = 0.0;
    initial_energy = energy().stored();
  }
}

// ---- observers -------------------------------------------------------------------------------

std::vector<BlockSnapshot> System::snapshot() const
{
  std::vector<BlockSnapshot> out;
  out.reserve(blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i)
  {
    const Block& b = blocks[i];
    out.push_back({i, b.material, b.vertices, b.displacement(), b.velocity.head<2>(), b.stress});
  }
  return out;
}

MonitorSample System::sample_monitor(std::size_t k) const
{
  const MaterialPoint& p = monitors[k];
  const Block& b = blocks[p.block];
  MonitorSample s;
  s.block = p.block;
  s.displacement = p.position - monitor_origins[k];
  s.velocity = point_matrix(p) * b.velocity;
  s.stress = b.stress;
  return s;
}

} // namespace ddafem::dda
