#include "dda/system.h"

#include "common/input_error.h"
#include "dda/submatrices.h"

#include <Eigen/LU>

#include <algorithm>
#include <chrono>
#include <cmath>
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
} // namespace

Point System::AttachedFixedPoint::target(double t) const
{
  return point.initial + Vector2(displacement_x.value(t), displacement_y.value(t));
}

System::System(const ModelDescription& model_)
    : model(model_), matrix(0, {}), solver(make_sparse_direct_solver(model_.solver))
{
  if (model.time.integrator == Integrator::newmark_trapezoidal)
  {
    beta = 0.25;
    gamma = 0.5;
  }
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

  const double size = model_size(blocks);
  joints = find_joints(blocks, model, names, 1e-9 * size);
  for (const Joint& j : joints)
    if (!model.joint_materials[j.joint_material].bonded)
      throw InputError("joint material '" + model.joint_materials[j.joint_material].name +
                       "' (between " + names[j.block_a] + " and " + names[j.block_b] +
                       ") has `bonded: false`: frictional contacts are not available yet "
                       "(contact mechanics, issue 4); expected `bonded: true`");

  // One coupling block per pair of joined blocks.
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> coupling_index;
  std::vector<std::pair<std::size_t, std::size_t>> couplings;
  for (Joint& j : joints)
  {
    const auto key = std::make_pair(j.block_a, j.block_b);
    const auto [it, inserted] = coupling_index.emplace(key, couplings.size());
    if (inserted)
      couplings.push_back(key);
    j.coupling = it->second;
  }
  matrix = BlockSparseMatrix(blocks.size(), couplings);
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
    monitors.push_back(attach(m.point, "monitor " + m.name));
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

  initial_energy = energy().stored();
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

// ---- the step --------------------------------------------------------------------------------

StepStatus System::advance(double dt)
{
  // Bonded joints are fixed at construction; issue 4 adds the phases "find contact candidates"
  // and "update contacts" before assembly, and the open-close iteration around the solve.
  auto start = Clock::now();
  // With updated geometry every step has its own matrix; a small-displacement analysis keeps
  // the matrix of the initial configuration for as long as dt does not change.
  const bool new_matrix = !small_displacement() || dt != matrix_dt;
  assemble(dt, new_matrix);
  matrix_dt = dt;
  timings.assemble += seconds_since(start);

  start = Clock::now();
  StepStatus status;
  status.solve = solver.solve(matrix, rhs, solution,
                              new_matrix ? MatrixChange::unknown : MatrixChange::unchanged);
  timings.solve += seconds_since(start);
  if (!status.solve.success)
  {
    status.outcome = StepOutcome::solver_failure;
    status.message = status.solve.message + " at t = " + format_time(current_time);
    return status;
  }

  start = Clock::now();
  update_blocks(dt, solution);
  timings.update += seconds_since(start);
  ++timings.n_steps;
  current_time += dt;

  const StepStatus strength = check_joint_strength();
  if (strength.outcome != StepOutcome::success)
    return {strength.outcome, strength.message, status.solve};

  // A boundary beyond its stability limit feeds energy into the model: stop when the stored
  // energy exceeds ten times all the energy ever put in.
  if (!boundary_edges.empty())
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
      return {StepOutcome::energy_growth, m.str(), status.solve};
    }
  }
  return status;
}

void System::assemble(double dt, bool with_matrix)
{
  if (with_matrix)
    matrix.set_zero();
  rhs.setZero();
  const double t1 = current_time + dt; // loads and supports are evaluated at the step's end

  // Blocks: inertia M / (beta dt^2) and elasticity; M (v0 / (beta dt) + (1 / (2 beta) - 1) a0),
  // the accumulated stress and gravity on the right-hand side.
  const double mass_factor = 1.0 / (beta * dt * dt);
  for (std::size_t i = 0; i < blocks.size(); ++i)
  {
    const Block& b = blocks[i];
    const Material& mat = model.materials[b.material];
    const PolygonMoments& g = linearisation_moments(b);
    const Matrix6 m = mass_matrix(g, mat.density);
    if (with_matrix)
    {
      matrix.diagonal(i).noalias() += mass_factor * m;
      matrix.diagonal(i).noalias() += elastic_stiffness(g.area, elasticity[b.material]);
    }
    const Vector6 inertia_velocity = b.velocity / (beta * dt) + (0.5 / beta - 1.0) * b.acceleration;
    auto f = rhs.segment<6>(6 * i);
    f.noalias() += m * inertia_velocity;
    f += stress_force(g.area, b.stress) + body_force(g.area, mat.density, model.gravity);
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

  // Viscous boundaries at their edge midpoints.
  for (std::size_t k = 0; k < boundary_edges.size(); ++k)
  {
    const BoundaryEdge& e = boundary_edges[k];
    const Block& b = blocks[e.block];
    const Matrix26 t = point_matrix(e.midpoint);
    boundary_steps[k] =
        boundary_step(model.boundaries[e.boundary].type, e, boundary_normal(e), block_mass(b), dt,
                      beta, gamma, t * b.velocity, t * b.acceleration);
    if (with_matrix)
      matrix.diagonal(e.block).noalias() += t.transpose() * boundary_steps[k].k * t;
    rhs.segment<6>(6 * e.block).noalias() += t.transpose() * boundary_steps[k].f;
  }

  // Bonded joints: springs K_s on the gap g + T_b d_b - T_a d_a, with g = x_b - x_a.
  for (const Joint& j : joints)
  {
    const Eigen::Matrix2d ks =
        joint_spring(model.joint_materials[j.joint_material], j.normal(small_displacement()),
                     j.tangent(small_displacement()));
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
      const Vector2 force = ks * (p.on_b.position - p.on_a.position);
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
  return model.materials[b.material].density * linearisation_moments(b).area;
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
  const double t0 = current_time, t1 = current_time + dt;

  // Work of the loads (trapezoidal in time) and of gravity, on the displacement of the step.
  for (const AttachedLoad& l : loads)
  {
    const Vector2 du = point_matrix(l.point) * d.segment<6>(6 * l.point.block);
    work_of_loads += 0.5 * (l.function.value(t0) + l.function.value(t1)) * l.force.dot(du);
  }
  for (std::size_t i = 0; i < blocks.size(); ++i)
    work_of_loads += model.materials[blocks[i].material].density *
                     linearisation_moments(blocks[i]).area * model.gravity.dot(d.segment<2>(6 * i));

  // Work of the boundaries: their force in the step's equation, -k T d + f, on T d.
  for (std::size_t k = 0; k < boundary_edges.size(); ++k)
  {
    const BoundaryEdge& e = boundary_edges[k];
    const Vector2 du = point_matrix(e.midpoint) * d.segment<6>(6 * e.block);
    work_of_boundaries += (boundary_steps[k].f - boundary_steps[k].k * du).dot(du);
  }

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
  for (BoundaryEdge& e : boundary_edges)
    move(e.midpoint);
  for (Joint& j : joints)
    for (JointPoint& p : j.points)
    {
      move(p.on_a);
      move(p.on_b);
    }

  // Newmark update of velocity and acceleration, then geometry and stress.
  for (std::size_t i = 0; i < blocks.size(); ++i)
  {
    Block& b = blocks[i];
    const Vector6 di = d.segment<6>(6 * i);
    const Vector6 a1 =
        (di - dt * b.velocity - dt * dt * (0.5 - beta) * b.acceleration) / (beta * dt * dt);
    b.velocity += dt * ((1.0 - gamma) * b.acceleration + gamma * a1);
    b.acceleration = a1;
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
      p.normal_force = jm.normal_stiffness * n.dot(gap);
      p.shear_force = jm.shear_ratio * jm.normal_stiffness * t.dot(gap);
    }
  }
}

StepStatus System::check_joint_strength() const
{
  for (const Joint& j : joints)
  {
    const JointMaterial& jm = model.joint_materials[j.joint_material];
    // Each end spring carries half of the joint's length.
    const double half = 0.5 * j.length;
    for (const JointPoint& p : j.points)
    {
      const double tensile_capacity = jm.tensile_strength * half;
      const double compression = -p.normal_force;
      const double shear_capacity =
          std::max(0.0, jm.cohesion * half + compression * tan_friction[j.joint_material]);
      const bool tension_failure = p.normal_force > tensile_capacity;
      if (!tension_failure && std::abs(p.shear_force) <= shear_capacity)
        continue;
      std::ostringstream s;
      s << "bonded joint " << j.id << " between blocks " << j.block_a << " and " << j.block_b;
      if (tension_failure)
        s << " exceeded its tensile strength (" << p.normal_force << " N > " << tensile_capacity
          << " N)";
      else
        s << " exceeded its shear strength (|" << p.shear_force << "| N > " << shear_capacity
          << " N)";
      s << " at t = " << format_time(current_time)
        << "; a broken joint becomes a frictional contact, which needs the contact mechanics of "
           "issue 4";
      return {StepOutcome::joint_broken, s.str(), {}};
    }
  }
  return {};
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
  s.displacement = p.position - p.initial;
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
  return e;
}

EnergyBalance System::energy() const
{
  EnergyBalance e;
  for (const Block& b : blocks)
  {
    const Material& mat = model.materials[b.material];
    const PolygonMoments& g = linearisation_moments(b);
    e.kinetic += 0.5 * b.velocity.dot(mass_matrix(g, mat.density) * b.velocity);
    e.strain += 0.5 * g.area * b.stress.dot(compliance[b.material] * b.stress);
  }
  e.spring = stored_spring_energy();
  e.work_of_loads = work_of_loads;
  e.work_of_supports = work_of_supports;
  e.work_of_boundaries = work_of_boundaries;
  e.initial = initial_energy;
  e.dissipated =
      e.initial + e.work_of_loads + e.work_of_supports + e.work_of_boundaries - e.stored();
  return e;
}

} // namespace ddafem::dda
