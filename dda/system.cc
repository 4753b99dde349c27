#include "dda/system.h"

#include "common/input_error.h"
#include "dda/submatrices.h"

#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <future>
#include <map>
#include <sstream>

namespace ddafem::dda
{
namespace
{
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Largest extent of the model [m], for tolerances.
double model_size(const std::vector<Block>& blocks)
{
  double x_min = blocks[0].vertices[0].x(), x_max = x_min;
  double y_min = blocks[0].vertices[0].y(), y_max = y_min;
  for (const Block& b : blocks)
    for (const Point& v : b.vertices)
    {
      x_min = std::min(x_min, v.x());
      x_max = std::max(x_max, v.x());
      y_min = std::min(y_min, v.y());
      y_max = std::max(y_max, v.y());
    }
  return std::max(x_max - x_min, y_max - y_min);
}

/// Joint springs at a contact point: p n n^T + p_s t t^T [N/m].
Eigen::Matrix2d joint_spring(const JointMaterial& jm, const Vector2& n, const Vector2& t)
{
  return jm.normal_stiffness * (n * n.transpose()) +
         jm.shear_ratio * jm.normal_stiffness * (t * t.transpose());
}

std::string format_time(double t)
{
  std::ostringstream s;
  s.precision(6);
  s << t << " s";
  return s.str();
}

/// Adds a spring K2 [N/m] between point i (T_i) and point j (T_j) of two different blocks, with
/// the force `force` [N] acting on i (and -force on j), to the matrix and the right-hand side.
void add_pair_spring(BlockSparseMatrix& matrix, Eigen::VectorXd& rhs, std::size_t coupling,
                     std::size_t i, const Matrix26& t_i, std::size_t j, const Matrix26& t_j,
                     const Eigen::Matrix2d& k2, const Vector2& force)
{
  const Matrix26 k_ti = k2 * t_i;
  const Matrix26 k_tj = k2 * t_j;
  matrix.diagonal(i).noalias() += t_i.transpose() * k_ti;
  matrix.diagonal(j).noalias() += t_j.transpose() * k_tj;
  if (i < j)
    matrix.upper(coupling).noalias() -= t_i.transpose() * k_tj;
  else
    matrix.upper(coupling).noalias() -= t_j.transpose() * k_ti;
  rhs.segment<6>(6 * i).noalias() += t_i.transpose() * force;
  rhs.segment<6>(6 * j).noalias() -= t_j.transpose() * force;
}

} // namespace

bool can_retry_with_smaller_step(StepOutcome outcome)
{
  return outcome == StepOutcome::not_converged || outcome == StepOutcome::displacement_too_large ||
         outcome == StepOutcome::penetration_too_large;
}

const char* outcome_name(StepOutcome outcome)
{
  switch (outcome)
  {
  case StepOutcome::success:
    return "success";
  case StepOutcome::solver_failure:
    return "solver_failure";
  case StepOutcome::not_converged:
    return "not_converged";
  case StepOutcome::displacement_too_large:
    return "displacement_too_large";
  case StepOutcome::penetration_too_large:
    return "penetration_too_large";
  case StepOutcome::joint_broken:
    return "joint_broken";
  case StepOutcome::energy_growth:
    return "energy_growth";
  case StepOutcome::slip_reversal:
    return "slip_reversal";
  }
  return "unknown";
}

Point System::AttachedFixedPoint::target(double t) const
{
  return point.initial + Vector2(displacement_x.value(t), displacement_y.value(t));
}

System::System(const ModelDescription& model_)
    : model(model_), matrix(0, {}), base_matrix(0, {}), tied_matrix(0, {}), solver(model_.solver)
{
  integration = integrator_coefficients(model.time.integrator, model.time.spectral_radius);
  for (const Material& m : model.materials)
  {
    elasticity.push_back(elasticity_matrix(m.youngs_modulus, m.poisson_ratio, model.plane_mode));
    compliance.push_back(elasticity.back().inverse());
  }
  for (const JointMaterial& jm : model.joint_materials)
    tan_friction.push_back(std::tan(jm.friction_angle * M_PI / 180.0));

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

  const double size = model_size(blocks);
  // Blocks that share an edge through a frictional joint material meet through contacts.
  std::vector<Joint> found = find_joints(blocks, model, names, 1e-9 * size);
  for (const Joint& j : found)
    if (model.joint_materials[j.joint_material].bonded)
      joints.push_back(j);
  contacts_enabled = !small_displacement();
  if (!contacts_enabled)
    for (const Joint& j : found)
      if (!model.joint_materials[j.joint_material].bonded)
        throw InputError("joint material '" + model.joint_materials[j.joint_material].name +
                         "' (between " + names[j.block_a] + " and " + names[j.block_b] +
                         ") is frictional (`bonded: false`), but `analysis.geometry: "
                         "small_displacement` cannot follow contacts: expected `geometry: "
                         "updated` or a bonded joint material");

  // Any two blocks may come into contact: every pair of materials needs a joint material.
  if (contacts_enabled && blocks.size() > 1)
  {
    std::vector<bool> used(model.materials.size(), false);
    for (const Block& b : blocks)
      used[b.material] = true;
    for (std::size_t m1 = 0; m1 < used.size(); ++m1)
      for (std::size_t m2 = m1; m2 < used.size(); ++m2)
        if (used[m1] && used[m2] &&
            joint_material_for(model, m1, m2) >= model.joint_materials.size())
          throw InputError("blocks of materials '" + model.materials[m1].name + "' and '" +
                           model.materials[m2].name +
                           "' may come into contact but no joint material applies to them: "
                           "expected `joints: {default: NAME}` or a `joints.pairs` entry");
  }

  for (const Block& b : blocks)
  {
    bool is_convex = true;
    const std::size_t n = b.vertices.size();
    for (std::size_t k = 0; k < n; ++k)
      is_convex = is_convex && interior_angle(b.vertices, k) < M_PI;
    convex.push_back(is_convex);
  }

  // Shi's w0 and the contact distances derived from it. Shi's bound g2 w0 alone would let a
  // long model of small blocks (a bar) move vertices farther than a block in one step; the
  // bound is also kept below a tenth of the shortest edge, so that the search distance
  // (2.5 times the bound) stays below a quarter of it and only neighbours are candidates.
  w0 = 0.5 * size;
  double shortest_edge = size;
  for (const Block& b : blocks)
    for (std::size_t k = 0; k < b.vertices.size(); ++k)
      shortest_edge =
          std::min(shortest_edge, (b.vertices[(k + 1) % b.vertices.size()] - b.vertices[k]).norm());
  const ContactSettings& cs = model.contacts;
  step_displacement_limit = std::min(cs.max_displacement_ratio * w0, 0.1 * shortest_edge);
  contact_search_distance =
      cs.search_distance > 0.0 ? cs.search_distance : 2.5 * step_displacement_limit;
  penetration_limit = cs.max_penetration > 0.0 ? cs.max_penetration : step_displacement_limit;
  angle_tolerance = cs.angle_tolerance_deg * M_PI / 180.0;

  rhs.setZero(static_cast<Eigen::Index>(n_dofs()));
  solution.setZero(static_cast<Eigen::Index>(n_dofs()));

  // Fixed-point penalty: 10x the stiffest spring or block in the model (Shi uses a large
  // multiple of the contact penalty), so that fixed points move by < 10% of the joint opening.
  double stiffest = 0.0;
  for (const JointMaterial& jm : model.joint_materials)
    stiffest = std::max(stiffest, jm.normal_stiffness);
  for (const Material& m : model.materials)
    stiffest = std::max(stiffest, m.youngs_modulus * 1.0 /* [Pa] x 1 m */);
  default_fixed_stiffness = 10.0 * stiffest;

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
  apply_in_situ_stress();

  // The step's matrix structure: joints now, contacts once found.
  set_matrix_structure({});
  initial_energy = energy().stored();
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

Vector2 System::input_force(const BoundaryEdge& e, double t) const
{
  const BoundaryDescription& b = model.boundaries[e.boundary];
  if (!b.has_input)
    return Vector2::Zero();
  const Vector2 n = boundary_normal(e), tangent(-n.y(), n.x());
  const double v = b.input.velocity.value(t);
  const Vector2 v_in = b.input.type == BoundaryInput::Type::p ? Vector2(0.0, v) : Vector2(v, 0.0);
  return 2.0 * (e.cn * n.dot(v_in) * n + e.ct * tangent.dot(v_in) * tangent);
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
  tie_runs.clear();
  for (std::size_t k = 0; k < points.size(); ++k)
    if (tie_runs.empty() || tie_runs.back().block != points[k].block)
      tie_runs.push_back({points[k].block, static_cast<Eigen::Index>(k), 1});
    else
      ++tie_runs.back().count;
  tie_stacks.resize(tie_runs.size());
  tied_body = &body;
  tie_points = points;
  tie_origins.clear();
  for (const MaterialPoint& p : points)
    tie_origins.push_back(p.position);
  tie_matrices.resize(points.size());
  set_matrix_structure(coupling_pairs);
}

// ---- the step --------------------------------------------------------------------------------

StepStatus System::advance(double dt)
{
  undo_friction_jumps(); // each attempt starts from the accepted state
  return attempt_step(dt);
}

StepStatus System::attempt_step(double dt)
{
  const std::string when =
      "at t = " + format_time(current_time) + " (dt = " + format_time(dt) + ")";
  ++timings.n_attempts;
  if (mode == StageMode::static_equilibrium)
    set_at_rest();
  choose_step_scheme(dt); // 0. the integrator's form of this step
  // A tied body begins its step (the far field's free response) on another thread while the
  // blocks find their contacts and assemble: the two touch no common data.
  std::future<std::string> tied = begin_tied_step(dt);
  detect_contacts();                         // 1. candidates, 2. contacts
  const bool new_matrix = assemble_step(dt); // 3. assemble
  if (tied_body)
  {
    const std::string failure = tied.get();
    if (!failure.empty())
      return {StepOutcome::solver_failure, failure + " " + when, {}};
  }
  StepStatus status = solve_step(when, new_matrix); // 4. solve with the open-close iteration
  if (status.outcome != StepOutcome::success)
    return status;
  if (mode == StageMode::static_equilibrium)
    measure_balance(status);

  // Step control: no vertex may move farther than g2 w0, no contact penetrate too deep, no
  // slip reversal leave more than the tolerance.
  check_motion_limits(status, when);
  if (status.outcome != StepOutcome::success)
    return status;
  if (localising_slip_reversals())
  {
    const ReversalScan scan = scan_slip_reversals(dt);
    if (scan.earliest > 0.0)
    {
      status.reversal_fraction = scan.earliest;
      status.outcome = StepOutcome::slip_reversal;
      status.message = "a sliding contact reverses its slip " + format_time(scan.earliest * dt) +
                       " after the step's start " + when;
      return status;
    }
    // A step at which friction turns around is redone with the integrator restarted at the
    // jump (generalized-alpha; the trapezoidal rule and Bathe's first half, whose end velocity
    // takes the start's acceleration). The redo repeats phases 1 and 2 too: they reset the
    // trial contacts to the step's start (the restart leaves the geometry as it was), and it
    // is taken on few steps.
    if (!scan.friction_turns.empty() && start_force_lag() > 0.0 && friction_jumps.empty())
    {
      restart_at_friction_jumps(scan.friction_turns);
      return attempt_step(dt);
    }
  }

  // 5. Update the tied body, blocks and contacts.
  const std::string failure = accept_step(dt);
  if (!failure.empty())
    return {StepOutcome::solver_failure, failure + " " + when, status.solve};
  const std::string broken = break_joints();
  if (!broken.empty())
    return {StepOutcome::joint_broken, broken, status.solve};
  if (!boundary_edges.empty() && mode == StageMode::dynamic)
    check_energy_growth(status);
  return status;
}

void System::detect_contacts()
{
  auto start = Clock::now();
  std::vector<std::pair<std::size_t, std::size_t>> pairs =
      contacts_enabled ? find_contact_candidates()
                       : std::vector<std::pair<std::size_t, std::size_t>>{};
  pairs.erase(std::remove_if(pairs.begin(), pairs.end(),
                             [&](const auto& p) { return removed[p.first] || removed[p.second]; }),
              pairs.end());
  timings.broad_phase += seconds_since(start);
  start = Clock::now();
  update_contacts(pairs);
  timings.narrow_phase += seconds_since(start);
}

bool System::assemble_step(double dt)
{
  // With updated geometry every step has its own matrix; a small-displacement analysis (no
  // contacts) keeps the matrix of the initial configuration while dt is unchanged.
  const auto start = Clock::now();
  const bool new_matrix = !small_displacement() || dt != matrix_dt ||
                          step_integration.mass_factor(dt) != matrix_mass_factor;
  assemble(dt, new_matrix);
  if (new_matrix)
    add_hold_terms();
  matrix_dt = dt;
  matrix_mass_factor = step_integration.mass_factor(dt);
  timings.assemble += seconds_since(start);
  return new_matrix;
}

std::future<std::string> System::begin_tied_step(double dt)
{
  if (!tied_body)
    return {};
  Eigen::VectorXd displacements(2 * tie_points.size());
  for (std::size_t k = 0; k < tie_points.size(); ++k)
  {
    tie_matrices[k] = point_matrix(tie_points[k]);
    displacements.segment<2>(2 * k) = tie_points[k].position - tie_origins[k];
  }
  return std::async(std::launch::async,
                    [this, dt, displacements = std::move(displacements)]
                    {
                      const auto start = Clock::now();
                      std::string failure = tied_body->begin_step(dt, displacements);
                      timings.tied_body += seconds_since(start);
                      return failure;
                    });
}

StepStatus System::solve_step(const std::string& when, bool new_matrix)
{
  const auto start = Clock::now();
  StepStatus status;
  if (trial_contacts.empty() && !tied_body)
  {
    status.solve = solver.solve(matrix, rhs, solution,
                                new_matrix ? MatrixChange::unknown : MatrixChange::unchanged,
                                matrix_mass_factor);
    if (!status.solve.success)
    {
      status.outcome = StepOutcome::solver_failure;
      status.message = status.solve.message + " " + when;
    }
  }
  else
    status = solve_with_open_close(when, new_matrix);
  timings.solve += seconds_since(start);
  return status;
}

void System::check_motion_limits(StepStatus& status, const std::string& when)
{
  status.max_displacement = largest_vertex_displacement(solution);
  if (status.max_displacement > step_displacement_limit)
  {
    std::ostringstream m;
    m << "a vertex moves " << status.max_displacement << " m in one step, more than the "
      << step_displacement_limit << " m allowed (g2 w0) " << when;
    status.outcome = StepOutcome::displacement_too_large;
    status.message = m.str();
    return;
  }
  for (const Contact& c : trial_contacts)
    if (c.trial.state != ContactState::open)
      status.max_penetration = std::max(status.max_penetration, -c.end_gap);
  if (status.max_penetration > penetration_limit)
  {
    std::ostringstream m;
    m << "a contact penetrates " << status.max_penetration << " m, deeper than the "
      << penetration_limit << " m allowed " << when
      << " (a stiffer joint normal_stiffness or a smaller dt reduces it)";
    status.penalty_raised = raise_penalties();
    status.outcome = StepOutcome::penetration_too_large;
    status.message = m.str();
  }
}

std::string System::accept_step(double dt)
{
  auto start = Clock::now();
  if (tied_body)
  {
    const std::string failure = tied_body->end_step(tie_increments(solution));
    timings.tied_body += seconds_since(start);
    if (!failure.empty())
      return failure;
  }
  start = Clock::now();
  record_half(dt, solution);
  update_blocks(dt, solution);
  for (Contact& c : trial_contacts)
  {
    if (c.trial.state == ContactState::slide)
      c.total_slip += c.step_slip;
    const bool slides_on = c.forces.state == ContactState::slide &&
                           c.trial.state == ContactState::slide &&
                           std::signbit(c.forces.shear_force) == std::signbit(c.trial.shear_force);
    c.slide_duration = c.trial.state != ContactState::slide ? 0.0
                       : slides_on                          ? c.slide_duration + dt
                                                            : dt;
    c.forces = c.trial;
  }
  contacts.swap(trial_contacts);
  raised_penalties.clear();
  if (mode == StageMode::static_equilibrium)
    set_at_rest();
  else
  {
    current_time += dt;
    motion_starts = false;
    friction_jumps.clear(); // the restarted state is the accepted one
  }
  timings.update += seconds_since(start);
  ++timings.n_steps;
  return {};
}

void System::check_energy_growth(StepStatus& status)
{
  const EnergyBalance e = energy();
  largest_energy_input = std::max(largest_energy_input, e.work_of_loads + e.work_of_supports);
  const double reference = e.initial + largest_energy_input;
  if (!std::isfinite(e.stored()) || e.stored() > 10.0 * reference)
  {
    std::ostringstream m;
    m << "the stored energy grew to " << e.stored() << " J, more than 10 times the " << reference
      << " J put into the model, at t = " << format_time(current_time)
      << ": a boundary is feeding energy into the model (see `ddafem check` for each "
         "boundary's time-step limit)";
    status.outcome = StepOutcome::energy_growth;
    status.message = m.str();
  }
}

void System::measure_balance(StepStatus& status)
{
  // With zero velocity the right-hand side's translational part is the resultant force at the
  // step start; the magnitudes of its terms, from the same step-start state, are the load.
  balances.assign(blocks.size(), {});
  for (std::size_t i = 0; i < blocks.size(); ++i)
  {
    balances[i].out_of_balance = rhs.segment<2>(6 * i);
    balances[i].weight = balances[i].load = block_mass(blocks[i]) * model.gravity.norm();
  }
  const auto add = [&](std::size_t block, double magnitude) { balances[block].load += magnitude; };
  for (const AttachedLoad& l : loads)
    add(l.point.block, std::abs(l.function.value(current_time)) * l.force.norm());
  for (const AttachedFixedPoint& f : fixed_points)
    add(f.point.block, f.stiffness * (f.target(current_time) - f.point.position).norm());
  for (const Support& s : supports)
    add(s.point.block, s.force().norm());
  for (const Joint& j : joints)
    for (const JointPoint& p : j.points)
    {
      add(j.block_a, std::hypot(p.normal_force, p.shear_force));
      add(j.block_b, std::hypot(p.normal_force, p.shear_force));
    }
  for (const Contact& c : trial_contacts)
    if (c.forces.state != ContactState::open)
    {
      add(c.vertex_block, std::hypot(c.forces.normal_force, c.forces.shear_force));
      add(c.edge_block, std::hypot(c.forces.normal_force, c.forces.shear_force));
    }
  if (tied_body)
    for (std::size_t k = 0; k < tie_points.size(); ++k)
      add(tie_points[k].block, tied_body->force().segment<2>(2 * k).norm());
  for (std::size_t i = 0; i < blocks.size(); ++i)
    if (!is_held(i) && balances[i].ratio() > status.unbalanced_force_ratio)
    {
      status.unbalanced_force_ratio = balances[i].ratio();
      status.unbalanced_block = i;
    }
}

void System::add_hold_terms()
{
  for (std::size_t i = 0; i < blocks.size(); ++i)
    if (is_held(i))
      matrix.diagonal(i).diagonal() *= 1.0 + 1e8;
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
  held.assign(blocks.size(), false);
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
    work_of_loads = work_of_supports = work_of_boundaries = 0.0;
    largest_energy_input = 0.0;
    initial_energy = energy().stored();
  }
}

// ---- contacts --------------------------------------------------------------------------------

ContactLaw System::contact_law(const Contact& c) const
{
  const JointMaterial& jm = model.joint_materials[c.joint_material];
  ContactLaw law;
  law.normal_stiffness = c.penalty_factor * jm.normal_stiffness;
  law.shear_stiffness = jm.shear_ratio * law.normal_stiffness;
  law.tan_friction = tan_friction[c.joint_material];
  // A bonded joint material's contacts come from broken joints: residual friction only.
  law.cohesive_force = jm.bonded ? 0.0 : jm.cohesion * c.length;
  law.tensile_capacity = jm.bonded ? 0.0 : jm.tensile_strength * c.length;
  return law;
}

StepStatus System::solve_with_open_close(const std::string& when, bool new_matrix)
{
  // The matrix without contact and tie terms: just assembled, or kept from the last assembly
  // (small-displacement analysis, same dt).
  if (new_matrix || !base_matrix.same_structure(matrix))
    base_matrix = matrix;
  else
    matrix = base_matrix;
  base_rhs = rhs;
  // A tied body's terms (dense over the tied blocks) change only when its ties change state:
  // the iterations start from the matrix with them, rebuilt only then.
  const auto add_ties_to_start = [&]
  {
    matrix = base_matrix;
    rhs = base_rhs;
    add_tie_terms();
    tied_matrix = matrix;
    tied_rhs = rhs;
  };
  if (tied_body)
    add_ties_to_start();
  bool ties_changed = false;
  StepStatus status;
  const unsigned max_iterations = std::max(1u, model.contacts.max_open_close_iterations);
  for (unsigned iteration = 1; iteration <= max_iterations; ++iteration)
  {
    if (iteration > 1 && ties_changed)
      add_ties_to_start();
    else if (iteration > 1)
    {
      matrix = tied_body ? tied_matrix : base_matrix;
      rhs = tied_body ? tied_rhs : base_rhs;
    }
    add_contact_terms();
    status.solve = solver.solve(matrix, rhs, solution, MatrixChange::unknown, matrix_mass_factor);
    ++status.n_open_close_iterations;
    ++timings.n_open_close_iterations;
    if (!status.solve.success)
    {
      status.outcome = StepOutcome::solver_failure;
      status.message = status.solve.message + " " + when;
      return status;
    }
    std::size_t n_changes = update_trial_states(iteration, status.n_flips_ignored);
    const std::size_t ignored_before = status.n_flips_ignored;
    const std::size_t n_tie_changes =
        tied_body
            ? tied_body->update_trial_states(tie_increments(solution), iteration,
                                             negligible_contact_force(), status.n_flips_ignored)
            : 0;
    ties_changed = n_tie_changes > 0 || status.n_flips_ignored > ignored_before;
    n_changes += n_tie_changes;
    status.n_state_changes += n_changes;
    if (n_changes == 0)
      return status;
  }
  status.outcome = StepOutcome::not_converged;
  status.message = "the open-close iteration did not converge in " +
                   std::to_string(max_iterations) + " iterations " + when;
  return status;
}

void System::add_contact_terms()
{
  for (std::size_t k = 0; k < trial_contacts.size(); ++k)
  {
    const Contact& c = trial_contacts[k];
    if (c.trial.state == ContactState::open)
      continue;
    const ContactFrame& f = frames[k];
    const ContactLaw law = contact_law(c);
    Eigen::Matrix2d k2 = law.normal_stiffness * (f.normal * f.normal.transpose());
    // Lock: the shear spring on the step's slip, starting from the previous shear force;
    // slide: the friction force of the trial, no shear spring.
    const bool was_closed = c.forces.state != ContactState::open;
    double shear = c.trial.shear_force;
    if (c.trial.state == ContactState::lock)
    {
      k2 += law.shear_stiffness * (f.tangent * f.tangent.transpose());
      shear = was_closed ? c.forces.shear_force : 0.0;
    }
    const Vector2 force_on_vertex = -law.normal_stiffness * c.gap * f.normal - shear * f.tangent;
    add_pair_spring(matrix, rhs, c.coupling, c.vertex_block, f.t_vertex, c.edge_block, f.t_edge, k2,
                    force_on_vertex);
  }
}

void System::add_tie_terms()
{
  if (!tied_body)
    return;
  const auto start = Clock::now();
  const Eigen::MatrixXd& h = tied_body->stiffness();
  const Eigen::VectorXd& g = tied_body->force();
  const auto m = static_cast<Eigen::Index>(tie_points.size());
  if (tied_body->stiffness_is_block_diagonal())
  {
    // Each tie point on its own: T_k^T H_kk T_k on its block's diagonal, O(m).
    for (Eigen::Index k = 0; k < m; ++k)
    {
      const std::size_t bk = tie_points[k].block;
      const Matrix26& tk = tie_matrices[k];
      rhs.segment<6>(6 * bk).noalias() += tk.transpose() * g.segment<2>(2 * k);
      matrix.diagonal(bk).noalias() += tk.transpose() * h.block<2, 2>(2 * k, 2 * k) * tk;
    }
    timings.tie_terms += seconds_since(start);
    return;
  }
  // (A + T^T H T) d = b + T^T g over the runs of tie points on one block, T_r the stacked T
  // of run r's points: Y(:, r) = H(:, points of r) T_r, and the blocks of runs a <= b gain
  // X = T_a^T Y(points of a, columns of b) (its transpose into the stored upper block when a's
  // block comes after b's; X + X^T on the diagonal for two runs on one block). H is symmetric, so
  // the columns of run b need only the rows of the runs up to b: half of H is read, in products
  // of whole runs (three times faster than point by point on the default tunnel).
  const std::size_t n_runs = tie_runs.size();
  tie_products.resize(2 * m, static_cast<Eigen::Index>(6 * n_runs));
  for (std::size_t r = 0; r < n_runs; ++r)
  {
    const TieRun& run = tie_runs[r];
    Eigen::Matrix<double, Eigen::Dynamic, 6>& t_r = tie_stacks[r];
    t_r.resize(2 * run.count, 6);
    for (Eigen::Index k = 0; k < run.count; ++k)
      t_r.middleRows<2>(2 * k) = tie_matrices[static_cast<std::size_t>(run.first + k)];
    const Eigen::Index rows = 2 * (run.first + run.count);
    tie_products.block(0, static_cast<Eigen::Index>(6 * r), rows, 6).noalias() =
        h.block(0, 2 * run.first, rows, 2 * run.count) * t_r;
  }
  for (std::size_t a = 0; a < n_runs; ++a)
  {
    const TieRun& ra = tie_runs[a];
    const Eigen::Matrix<double, Eigen::Dynamic, 6>& t_a = tie_stacks[a];
    rhs.segment<6>(static_cast<Eigen::Index>(6 * ra.block)).noalias() +=
        t_a.transpose() * g.segment(2 * ra.first, 2 * ra.count);
    for (std::size_t b = a; b < n_runs; ++b)
    {
      const std::size_t bb = tie_runs[b].block;
      const Matrix6 x =
          t_a.transpose() *
          tie_products.block(2 * ra.first, static_cast<Eigen::Index>(6 * b), 2 * ra.count, 6);
      if (b == a)
        matrix.diagonal(ra.block) += x;
      else if (bb == ra.block)
        matrix.diagonal(ra.block) += x + x.transpose();
      else if (ra.block < bb)
        matrix.upper(coupling_of(ra.block, bb)) += x;
      else
        matrix.upper(coupling_of(ra.block, bb)) += x.transpose();
    }
  }
  timings.tie_terms += seconds_since(start);
}

Eigen::VectorXd System::tie_increments(const Eigen::VectorXd& d) const
{
  Eigen::VectorXd delta(2 * tie_points.size());
  for (std::size_t k = 0; k < tie_points.size(); ++k)
    delta.segment<2>(2 * k) = tie_matrices[k] * d.segment<6>(6 * tie_points[k].block);
  return delta;
}

double System::negligible_contact_force() const
{
  double largest_force = 0.0;
  for (const Contact& c : trial_contacts)
    largest_force = std::max(largest_force, c.trial.normal_force);
  return model.contacts.flip_force_ratio * largest_force;
}

std::size_t System::update_trial_states(unsigned iteration, std::size_t& n_ignored)
{
  const double negligible = negligible_contact_force();
  const bool localising = localising_slip_reversals();
  std::size_t n_changes = 0;
  for (std::size_t k = 0; k < trial_contacts.size(); ++k)
  {
    Contact& c = trial_contacts[k];
    const ContactFrame& f = frames[k];
    const Vector2 relative = f.t_vertex * solution.segment<6>(6 * c.vertex_block) -
                             f.t_edge * solution.segment<6>(6 * c.edge_block);
    c.end_gap = c.gap + f.normal.dot(relative);
    c.step_slip = f.tangent.dot(relative);
    const ContactForces law = evaluate_contact(contact_law(c), c.forces, c.end_gap, c.step_slip);
    // With slip reversals localised, sliding that reverses between trials is taken as lock
    // (only on a slide of at least 10 steps: slides_long_enough).
    const ContactForces next = localising && slides_long_enough(c, matrix_dt)
                                   ? iteration_trial(iteration, c.trial, law)
                                   : law;
    // A contact that ends the step within rounding of zero gap (1e-12 of the model size; its
    // forces are then p x that, e.g. 0.5 N) is decided by rounding noise: it carries nothing
    // in either state and may flip between iterations (the head joints of bricks falling
    // together). Its change is taken but does not hold the iteration back.
    // From the third iteration on, so does one that carries almost nothing before and after
    // (contacts flipping between slide and lock under a kN where the rock carries MN).
    if (state_changed(c.trial, next) && std::abs(c.end_gap) > 2e-12 * w0)
    {
      if (change_holds_iteration(iteration, c.trial, next, negligible))
        ++n_changes;
      else
        ++n_ignored;
    }
    c.trial = next;
  }
  return n_changes;
}

bool System::raise_penalties()
{
  const double cap = model.contacts.max_penalty_factor;
  bool raised = false;
  for (const Contact& c : trial_contacts)
    if (c.trial.state != ContactState::open && -c.end_gap > penetration_limit &&
        c.penalty_factor < cap)
    {
      raised_penalties[c.key()] = std::min(cap, 10.0 * c.penalty_factor);
      raised = true;
    }
  return raised;
}

double System::largest_vertex_displacement(const Eigen::VectorXd& d) const
{
  double largest = 0.0;
  for (std::size_t i = 0; i < blocks.size(); ++i)
  {
    const Block& b = blocks[i];
    const Vector6 di = d.segment<6>(6 * i);
    const std::vector<Point>& v = small_displacement() ? b.initial_vertices : b.vertices;
    const Point& c = small_displacement() ? b.initial_centroid : b.moments.centroid;
    for (const Point& x : v)
      largest = std::max(largest, (displacement_matrix(c, x) * di).norm());
  }
  return largest;
}

void System::assemble(double dt, bool with_matrix)
{
  if (with_matrix)
    matrix.set_zero();
  rhs.setZero();
  // Loads and supports are evaluated at the step's end (the clock stands still in a static stage).
  const double t1 = mode == StageMode::static_equilibrium ? current_time : current_time + dt;

  // Blocks: inertia c M and elasticity; the inertia force of the block's past (v0, a0, r0), the
  // accumulated stress and gravity on the right-hand side.
  const double mass_factor = step_integration.mass_factor(dt);
  for (std::size_t i = 0; i < blocks.size(); ++i)
  {
    const Block& b = blocks[i];
    const PolygonMoments& g = linearisation_moments(b);
    const double density = block_density(b);
    const Matrix6 m = mass_matrix(g, density);
    if (with_matrix)
    {
      matrix.diagonal(i).noalias() += mass_factor * m;
      matrix.diagonal(i).noalias() += elastic_stiffness(g.area, elasticity[b.material]);
    }
    auto f = rhs.segment<6>(6 * i);
    f += inertia_force(step_integration, m, step_start(i, dt), dt);
    f += stress_force(g.area, b.stress) + body_force(g.area, density, model.gravity);
  }

  // Point loads at their material points.
  for (const AttachedLoad& l : loads)
    rhs.segment<6>(6 * l.point.block).noalias() +=
        point_matrix(l.point).transpose() * (l.force * l.function.value(t1));

  // Fixed points: penalty spring k |x + T d - X(t1)|^2 / 2.
  for (const AttachedFixedPoint& f : fixed_points)
  {
    const Matrix26 t = point_matrix(f.point);
    if (with_matrix)
      matrix.diagonal(f.point.block).noalias() += f.stiffness * t.transpose() * t;
    rhs.segment<6>(6 * f.point.block).noalias() +=
        f.stiffness * t.transpose() * (f.target(t1) - f.point.position);
  }

  // Viscous boundaries at their edge midpoints, with the incident wave's input force; in a
  // static stage their supports hold the edges instead (springs to the anchors plus the load),
  // in a dynamic one the supports' loads stay on as constant forces.
  const bool is_static = mode == StageMode::static_equilibrium;
  for (std::size_t k = 0; k < boundary_edges.size(); ++k)
  {
    boundary_steps[k] = {};
    if (is_static)
      continue;
    const BoundaryEdge& e = boundary_edges[k];
    const KinematicState start = step_start(e.block, dt);
    const Matrix26 t = point_matrix(e.midpoint);
    boundary_steps[k] = boundary_step(
        model.boundaries[e.boundary].type, e, boundary_normal(e), block_mass(blocks[e.block]), dt,
        step_integration.beta, step_integration.gamma, t * start.velocity, t * start.acceleration);
    if (with_matrix)
      matrix.diagonal(e.block).noalias() += t.transpose() * boundary_steps[k].k * t;
    rhs.segment<6>(6 * e.block).noalias() +=
        t.transpose() * (boundary_steps[k].f + input_force(e, t1));
  }
  for (const Support& s : supports)
  {
    const Matrix26 t = point_matrix(s.point);
    if (is_static && with_matrix)
      matrix.diagonal(s.point.block).noalias() += t.transpose() * s.stiffness * t;
    rhs.segment<6>(6 * s.point.block).noalias() += t.transpose() * (is_static ? s.force() : s.load);
  }

  // Bonded joints: springs K_s on the gap g + T_b d_b - T_a d_a, with g = x_b - x_a, plus the
  // preloads.
  for (const Joint& j : joints)
  {
    const Vector2 n = j.normal(small_displacement()), tangent = j.tangent(small_displacement());
    const Eigen::Matrix2d ks = joint_spring(model.joint_materials[j.joint_material], n, tangent);
    for (const JointPoint& p : j.points)
    {
      const Matrix26 ta = point_matrix(p.on_a);
      const Matrix26 tb = point_matrix(p.on_b);
      if (with_matrix)
      {
        const Matrix26 ks_ta = ks * ta;
        const Matrix26 ks_tb = ks * tb;
        matrix.diagonal(j.block_a).noalias() += ta.transpose() * ks_ta;
        matrix.diagonal(j.block_b).noalias() += tb.transpose() * ks_tb;
        matrix.upper(j.coupling).noalias() -= ta.transpose() * ks_tb;
      }
      const Vector2 force = ks * (p.on_b.position - p.on_a.position) + p.normal_preload * n +
                            p.shear_preload * tangent;
      rhs.segment<6>(6 * j.block_a).noalias() += ta.transpose() * force;
      rhs.segment<6>(6 * j.block_b).noalias() -= tb.transpose() * force;
    }
  }
}

Vector2 System::boundary_normal(const BoundaryEdge& e) const
{
  const Block& b = blocks[e.block];
  const std::vector<Point>& v = small_displacement() ? b.initial_vertices : b.vertices;
  const Vector2 t = (v[(e.edge + 1) % v.size()] - v[e.edge]).normalized();
  return Vector2(t.y(), -t.x());
}

double System::block_mass(const Block& b) const
{
  return model.materials[b.material].density * b.initial_moments.area;
}

double System::block_density(const Block& b) const
{
  const double density = model.materials[b.material].density;
  if (small_displacement())
    return density; // the linearisation area is the initial one
  return density * (b.initial_moments.area / b.moments.area);
}

BoundaryStability System::stability_of(std::size_t k, double dt) const
{
  const BoundaryEdge& e = boundary_edges[k];
  return boundary_stability(model.boundaries[e.boundary].type, e, block_mass(blocks[e.block]), dt);
}

const PolygonMoments& System::linearisation_moments(const Block& b) const
{
  return small_displacement() ? b.initial_moments : b.moments;
}

Matrix26 System::point_matrix(const MaterialPoint& p) const
{
  const Block& b = blocks[p.block];
  return small_displacement() ? displacement_matrix(b.initial_centroid, p.initial)
                              : displacement_matrix(b.moments.centroid, p.position);
}

void System::update_blocks(double dt, const Eigen::VectorXd& d)
{
  const double t0 = current_time;
  const double t1 = mode == StageMode::static_equilibrium ? current_time : current_time + dt;

  // Work of the loads (trapezoidal in time) and of gravity, on the displacement of the step.
  for (const AttachedLoad& l : loads)
  {
    const Vector2 du = point_matrix(l.point) * d.segment<6>(6 * l.point.block);
    work_of_loads += 0.5 * (l.function.value(t0) + l.function.value(t1)) * l.force.dot(du);
  }
  for (std::size_t i = 0; i < blocks.size(); ++i)
    work_of_loads += block_mass(blocks[i]) * model.gravity.dot(d.segment<2>(6 * i));

  // Work of the boundaries: their force in the step's equation, -k T d + f, on T d. The
  // incident wave's input forces (trapezoidal in time) and the supports' constant loads of a
  // dynamic stage count as loads (static stages: the energy restarts with the dynamic stage).
  const bool is_static = mode == StageMode::static_equilibrium;
  for (std::size_t k = 0; k < boundary_edges.size(); ++k)
  {
    const BoundaryEdge& e = boundary_edges[k];
    const Vector2 du = point_matrix(e.midpoint) * d.segment<6>(6 * e.block);
    work_of_boundaries += (boundary_steps[k].f - boundary_steps[k].k * du).dot(du);
    if (!is_static)
      work_of_loads += 0.5 * (input_force(e, t0) + input_force(e, t1)).dot(du);
  }
  if (!is_static)
    for (const Support& s : supports)
      work_of_loads += s.load.dot(point_matrix(s.point) * d.segment<6>(6 * s.point.block));

  // Work done by moving supports: -k (x - X)_mid . dX.
  for (const AttachedFixedPoint& f : fixed_points)
  {
    const Point x0 = f.point.position;
    const Point x1 = x0 + point_matrix(f.point) * d.segment<6>(6 * f.point.block);
    const Point target0 = f.target(t0), target1 = f.target(t1);
    const Vector2 stretch_mid = 0.5 * ((x0 - target0) + (x1 - target1));
    work_of_supports -= f.stiffness * stretch_mid.dot(target1 - target0);
  }

  // Material points move with their blocks (T of the configuration the step is linearised
  // about, i.e. before the update).
  const auto move = [&](MaterialPoint& p)
  { p.position += point_matrix(p) * d.segment<6>(6 * p.block); };
  for (AttachedLoad& l : loads)
    move(l.point);
  for (AttachedFixedPoint& f : fixed_points)
    move(f.point);
  for (MaterialPoint& m : monitors)
    move(m);
  for (MaterialPoint& p : tie_points)
    move(p);
  for (BoundaryEdge& e : boundary_edges)
    move(e.midpoint);
  for (Support& s : supports)
    move(s.point);
  for (Joint& j : joints)
    for (JointPoint& p : j.points)
    {
      move(p.on_a);
      move(p.on_b);
    }

  // Velocity, acceleration and force at the step's end (with the mass matrix the step used),
  // then geometry and stress.
  for (std::size_t i = 0; i < blocks.size(); ++i)
  {
    Block& b = blocks[i];
    const Vector6 di = d.segment<6>(6 * i);
    const Matrix6 m = mass_matrix(linearisation_moments(b), block_density(b));
    const KinematicState end = advance_state(step_integration, m, step_start(i, dt), di, dt);
    b.velocity = end.velocity;
    b.acceleration = composite_acceleration(i, m, end);
    b.force = end.force;
    if (removed[i]) // held by a penalty: the little it moves is not motion to carry on
    {
      b.velocity.setZero();
      b.acceleration.setZero();
      b.force.setZero();
    }
    b.apply_increment(di, elasticity[b.material], small_displacement());
  }

  // Joint spring forces at the new gaps.
  for (Joint& j : joints)
  {
    const JointMaterial& jm = model.joint_materials[j.joint_material];
    const Vector2 n = j.normal(small_displacement()), t = j.tangent(small_displacement());
    for (JointPoint& p : j.points)
    {
      const Vector2 gap = p.on_b.position - p.on_a.position;
      p.normal_force = p.normal_preload + jm.normal_stiffness * n.dot(gap);
      p.shear_force = p.shear_preload + jm.shear_ratio * jm.normal_stiffness * t.dot(gap);
    }
  }
}

std::string System::break_joints()
{
  std::string failure;
  std::vector<Joint> intact;
  intact.reserve(joints.size());
  for (const Joint& j : joints)
  {
    const JointMaterial& jm = model.joint_materials[j.joint_material];
    // Each end spring carries half of the joint's length.
    const double half = 0.5 * j.length;
    bool broken = false;
    for (const JointPoint& p : j.points)
    {
      const double compression = -p.normal_force;
      const double shear_capacity =
          std::max(0.0, jm.cohesion * half + compression * tan_friction[j.joint_material]);
      broken = broken || p.normal_force > jm.tensile_strength * half ||
               std::abs(p.shear_force) > shear_capacity;
    }
    if (!broken)
    {
      intact.push_back(j);
      continue;
    }
    ++broken_joint_count;
    if (small_displacement() && failure.empty())
      failure = "bonded joint " + std::to_string(j.id) + " between blocks " +
                std::to_string(j.block_a) + " and " + std::to_string(j.block_b) +
                " exceeded its strength at t = " + format_time(current_time) +
                "; a broken joint becomes a frictional contact, which a small-displacement "
                "analysis cannot follow: expected `analysis.geometry: updated`";
  }
  joints.swap(intact);
  return failure;
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

double System::stored_spring_energy() const
{
  double e = 0.0;
  for (const Joint& j : joints)
  {
    const JointMaterial& jm = model.joint_materials[j.joint_material];
    for (const JointPoint& p : j.points)
      e += 0.5 * (p.normal_force * p.normal_force / jm.normal_stiffness +
                  p.shear_force * p.shear_force / (jm.shear_ratio * jm.normal_stiffness));
  }
  for (const AttachedFixedPoint& f : fixed_points)
    e += 0.5 * f.stiffness * (f.point.position - f.target(current_time)).squaredNorm();
  for (const Contact& c : contacts)
    if (c.forces.state != ContactState::open)
    {
      const ContactLaw law = contact_law(c);
      e += 0.5 * (c.forces.normal_force * c.forces.normal_force / law.normal_stiffness +
                  c.forces.shear_force * c.forces.shear_force / law.shear_stiffness);
    }
  return e;
}

double System::kinetic_energy(const Block& b) const
{
  return 0.5 * b.velocity.dot(mass_matrix(linearisation_moments(b), block_density(b)) * b.velocity);
}

EnergyBalance System::energy() const
{
  EnergyBalance e;
  for (const Block& b : blocks)
  {
    const PolygonMoments& g = linearisation_moments(b);
    e.kinetic += kinetic_energy(b);
    e.strain += 0.5 * g.area * b.stress.dot(compliance[b.material] * b.stress);
  }
  e.spring = stored_spring_energy();
  e.work_of_loads = work_of_loads;
  e.work_of_supports = work_of_supports;
  e.work_of_boundaries = work_of_boundaries;
  e.work_of_ties = tied_body ? tied_body->work_on_blocks() : 0.0;
  e.removed = removed_energy;
  e.initial = initial_energy;
  e.dissipated = e.initial + e.work_of_loads + e.work_of_supports + e.work_of_boundaries +
                 e.work_of_ties - e.removed - e.stored();
  return e;
}

} // namespace ddafem::dda
