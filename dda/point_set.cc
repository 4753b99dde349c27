#include "dda/point_set.h"

#include "dda/linear_solver.h"
#include "dda/step_equations.h"

#include <algorithm>
#include <cmath>

namespace ddafem::dda
{
Point AttachedFixedPoint::target(double t) const
{
  return point.initial + Vector2(displacement_x.value(t), displacement_y.value(t));
}

double default_fixed_stiffness(const ModelDescription& model)
{
  // Shi uses a large multiple of the contact penalty: fixed points then move by < 10 % of the
  // joint opening.
  double stiffest = 0.0;
  for (const JointMaterial& jm : model.joint_materials)
    stiffest = std::max(stiffest, jm.normal_stiffness);
  for (const Material& m : model.materials)
    stiffest = std::max(stiffest, m.youngs_modulus * 1.0 /* [Pa] x 1 m */);
  return 10.0 * stiffest;
}

void PointSet::attach(const ModelDescription& model, const ElementHost& host)
{
  default_stiffness = default_fixed_stiffness(model);
  for (const PointLoad& l : model.point_loads)
    loads.push_back({host.attach(l.point, l.origin.empty() ? "point load" : l.origin), l.force,
                     l.time_function});
  for (const FixedPoint& f : model.fixed_points)
    fixed_points.push_back({host.attach(f.point, f.origin.empty() ? "fixed point" : f.origin),
                            f.stiffness > 0.0 ? f.stiffness : default_stiffness, f.displacement_x,
                            f.displacement_y});
  for (const Monitor& m : model.monitors)
  {
    monitors.push_back(host.attach(m.point, "monitor " + m.name));
    monitor_origins.push_back(m.point);
  }
}

void PointSet::assemble(const ElementHost& host, StepEquations& step, double t1,
                        bool with_matrix) const
{
  for (const AttachedLoad& l : loads)
    step.rhs.segment<6>(6 * l.point.block).noalias() +=
        host.point_matrix(l.point).transpose() * (l.force * l.function.value(t1));
  for (const AttachedFixedPoint& f : fixed_points)
  {
    const Matrix26 t = host.point_matrix(f.point);
    if (with_matrix)
      step.matrix.diagonal(f.point.block).noalias() += f.stiffness * t.transpose() * t;
    step.rhs.segment<6>(6 * f.point.block).noalias() +=
        f.stiffness * t.transpose() * (f.target(t1) - f.point.position);
  }
}

void PointSet::add_work(const ElementHost& host, const Eigen::VectorXd& d, double t0, double t1,
                        EnergyLedger& ledger) const
{
  for (const AttachedLoad& l : loads)
  {
    const Vector2 du = host.point_displacement(l.point, d.segment<6>(6 * l.point.block));
    ledger.loads += 0.5 * (l.function.value(t0) + l.function.value(t1)) * l.force.dot(du);
  }
  for (const AttachedFixedPoint& f : fixed_points)
  {
    const Point x0 = f.point.position;
    const Point x1 = x0 + host.point_displacement(f.point, d.segment<6>(6 * f.point.block));
    const Point target0 = f.target(t0), target1 = f.target(t1);
    const Vector2 stretch_mid = 0.5 * ((x0 - target0) + (x1 - target1));
    ledger.supports -= f.stiffness * stretch_mid.dot(target1 - target0);
  }
}

void PointSet::move_points(const ElementHost& host, const Eigen::VectorXd& d)
{
  for (AttachedLoad& l : loads)
    host.move_with_block(l.point, d);
  for (AttachedFixedPoint& f : fixed_points)
    host.move_with_block(f.point, d);
  for (MaterialPoint& m : monitors)
    host.move_with_block(m, d);
}

void PointSet::add_loads(const std::function<void(std::size_t, double)>& add, double t) const
{
  for (const AttachedLoad& l : loads)
    add(l.point.block, std::abs(l.function.value(t)) * l.force.norm());
  for (const AttachedFixedPoint& f : fixed_points)
    add(f.point.block, f.stiffness * (f.target(t) - f.point.position).norm());
}

void PointSet::add_energy(double& energy, double t) const
{
  for (const AttachedFixedPoint& f : fixed_points)
    energy += 0.5 * f.stiffness * (f.point.position - f.target(t)).squaredNorm();
}

void PointSet::measure_from_here()
{
  for (std::size_t k = 0; k < monitors.size(); ++k)
    monitor_origins[k] = monitors[k].position;
}

} // namespace ddafem::dda
