// Phase 5 of the step: blocks, material points and joints take the accepted solution, the
// works of the step are added up, and bonded joints beyond their strength break.
#include "dda/system.h"

#include "dda/submatrices.h"
#include "dda/system_helpers.h"

#include <algorithm>
#include <cmath>

namespace ddafem::dda
{
void System::update_blocks(double dt, const Eigen::VectorXd& d)
{
  add_work_of_step(dt, d);
  move_material_points(d);
  advance_block_states(dt, d);
  update_joint_forces();
  for (const std::unique_ptr<ElementKind>& k : element_kinds)
    k->update(*this, current_time);
}

void System::add_work_of_step(double dt, const Eigen::VectorXd& d)
{
  const double t0 = current_time;
  const double t1 = mode == StageMode::static_equilibrium ? current_time : current_time + dt;

  // Work of the loads (trapezoidal in time) and of gravity, on the displacement of the step.
  for (const AttachedLoad& l : loads)
  {
    const Vector2 du = point_displacement(l.point, d.segment<6>(6 * l.point.block));
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
    const Vector2 du = point_displacement(e.midpoint, d.segment<6>(6 * e.block));
    work_of_boundaries += (boundary_steps[k].f - boundary_steps[k].k * du).dot(du);
    if (!is_static)
      work_of_loads += 0.5 * (input_force(e, t0) + input_force(e, t1)).dot(du);
  }
  if (!is_static)
    for (const Support& s : supports)
      work_of_loads += s.load.dot(point_displacement(s.point, d.segment<6>(6 * s.point.block)));
  add_work_of_damping(d);

  // Work done by moving supports: -k (x - X)_mid . dX.
  for (const AttachedFixedPoint& f : fixed_points)
  {
    const Point x0 = f.point.position;
    const Point x1 = x0 + point_displacement(f.point, d.segment<6>(6 * f.point.block));
    const Point target0 = f.target(t0), target1 = f.target(t1);
    const Vector2 stretch_mid = 0.5 * ((x0 - target0) + (x1 - target1));
    work_of_supports -= f.stiffness * stretch_mid.dot(target1 - target0);
  }
}

void System::move_material_points(const Eigen::VectorXd& d)
{
  // Material points move with their blocks (T of the configuration the step is linearised
  // about, i.e. before the update).
  const auto move = [&](MaterialPoint& p)
  { p.position += point_displacement(p, d.segment<6>(6 * p.block)); };
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
  for (const std::unique_ptr<ElementKind>& k : element_kinds)
    k->move_points(*this, d);
}

void System::advance_block_states(double dt, const Eigen::VectorXd& d)
{
  // Velocity, acceleration and force at the step's end (with the mass matrix the step used),
  // then geometry and stress.
  for (std::size_t i = 0; i < blocks.size(); ++i)
  {
    Block& b = blocks[i];
    const Vector6 di = d.segment<6>(6 * i);
    const Matrix6& m = step_masses[i]; // the attempt's assembly: the same configuration
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
}

void System::update_joint_forces()
{
  // Joint spring forces at the new gaps (the points have moved with their blocks).
  for (Joint& j : joints)
  {
    const JointMaterial& jm = model.joint_materials[j.joint_material];
    const Vector2 t = j.tangent(small_displacement());
    const Vector2 n = Joint::normal_of(t);
    for (JointPoint& p : j.points)
      update_joint_point_forces(p, jm, n, t);
  }
}

std::string System::break_joints()
{
  // The intact joints move forward over the broken ones, in order (nothing moves while none
  // broke).
  std::string failure;
  std::size_t n_intact = 0;
  for (std::size_t k = 0; k < joints.size(); ++k)
  {
    const Joint& j = joints[k];
    // Each end spring carries half of the joint's length.
    const ContactLaw law = joint_point_law(model.joint_materials[j.joint_material],
                                           tan_friction[j.joint_material], 0.5 * j.length);
    bool broken = false;
    for (const JointPoint& p : j.points)
      broken = broken || exceeds_strength(law, -p.normal_force, p.shear_force);
    if (!broken)
    {
      if (n_intact != k)
        joints[n_intact] = joints[k];
      ++n_intact;
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
  if (n_intact != joints.size())
  {
    joints.resize(n_intact);
    ++joint_revision;
  }
  ++contact_set.geometry_epoch;
  return failure;
}

double System::largest_vertex_displacement(const Eigen::VectorXd& d) const
{
  // The largest squared length, one square root at the end (sqrt is monotonic: the same value).
  double largest = 0.0;
  for (std::size_t i = 0; i < blocks.size(); ++i)
  {
    const Block& b = blocks[i];
    const Vector6 di = d.segment<6>(6 * i);
    const std::vector<Point>& v = small_displacement() ? b.initial_vertices : b.vertices;
    const Point& c = small_displacement() ? b.initial_centroid : b.moments.centroid;
    for (const Point& x : v)
      largest = std::max(largest, displacement_at(c, x, di).squaredNorm());
  }
  return std::sqrt(largest);
}

} // namespace ddafem::dda
