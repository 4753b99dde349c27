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
  // Material points move with their blocks (T of the configuration the step is linearised
  // about, i.e. before the update).
  point_set.move_points(*this, d);
  tie_set.move_points(*this, d);
  boundary_set.move_points(*this, d);
  bonded.move_points(*this, d);
  for (const std::unique_ptr<ElementKind>& k : element_kinds)
    k->move_points(*this, d);
  advance_block_states(dt, d);
  bonded.update_forces(model, small_displacement());
  for (const std::unique_ptr<ElementKind>& k : element_kinds)
    k->update(*this, current_time);
}

void System::add_work_of_step(double dt, const Eigen::VectorXd& d)
{
  const double t0 = current_time;
  const double t1 = mode == StageMode::static_equilibrium ? current_time : current_time + dt;

  // Work of the loads (trapezoidal in time) and of moving fixed points, then of gravity, on the
  // displacement of the step.
  point_set.add_work(*this, d, t0, t1, ledger);
  for (std::size_t i = 0; i < blocks.size(); ++i)
    ledger.loads += mass_of(i) * model.gravity.dot(d.segment<2>(6 * i));

  // Work of the boundaries: their force in the step's equation, -k T d + f, on T d. The
  // incident wave's input forces (trapezoidal in time) and the supports' constant loads of a
  // dynamic stage count as loads (static stages: the energy restarts with the dynamic stage).
  boundary_set.add_work(boundary_input(t0, t1), d, ledger);
  add_work_of_damping(d);
}

void System::advance_block_states(double dt, const Eigen::VectorXd& d)
{
  // Velocity, acceleration and force at the step's end (with the mass matrix the step used),
  // then geometry and stress.
  for (std::size_t i = 0; i < blocks.size(); ++i)
  {
    Block& b = blocks[i];
    const Vector6 di = d.segment<6>(6 * i);
    const Matrix6& m = equations.masses[i]; // the attempt's assembly: the same configuration
    const KinematicState end = advance_state(scheme.coefficients, m, step_start(i, dt), di, dt);
    b.velocity = end.velocity;
    b.acceleration = scheme.composite_acceleration(i, m, end, mode == StageMode::dynamic);
    b.force = end.force;
    if (removed[i]) // held by a penalty: the little it moves is not motion to carry on
    {
      b.velocity.setZero();
      b.acceleration.setZero();
      b.force.setZero();
    }
    b.apply_increment(di, materials.elasticity[b.material], small_displacement());
  }
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
