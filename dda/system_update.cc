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
  point_set.move_points(block_set, d);
  tie_set.move_points(block_set, d);
  boundary_set.move_points(block_set, d);
  bonded.move_points(block_set, d);
  for (const std::unique_ptr<ElementKind>& k : element_kinds)
    k->move_points(block_set, d);
  block_set.advance_states(d, dt, equations.masses, scheme, mode == StageMode::dynamic);
  bonded.update_forces(model, block_set.small_displacement());
  for (const std::unique_ptr<ElementKind>& k : element_kinds)
    k->update(block_set, current_time);
}

void System::add_work_of_step(double dt, const Eigen::VectorXd& d)
{
  const double t0 = current_time;
  const double t1 = mode == StageMode::static_equilibrium ? current_time : current_time + dt;

  // Work of the loads (trapezoidal in time) and of moving fixed points, then of gravity, on the
  // displacement of the step.
  point_set.add_work(block_set, d, t0, t1, ledger);
  for (std::size_t i = 0; i < block_set.list.size(); ++i)
    ledger.loads += block_set.mass_of(i) * model.gravity.dot(d.segment<2>(6 * i));

  // Work of the boundaries: their force in the step's equation, -k T d + f, on T d. The
  // incident wave's input forces (trapezoidal in time) and the supports' constant loads of a
  // dynamic stage count as loads (static stages: the energy restarts with the dynamic stage).
  boundary_set.add_work(
      {model, block_set.list, block_set, mode == StageMode::static_equilibrium, t0, t1}, d, ledger);
  // The rock's dashpots' work on the step's d (none when they do not act).
  const std::vector<Vector6> mean = dashpots.mean_velocities(d);
  if (mean.empty())
    return;
  dashpots.add_work_of_blocks(block_set, model, mean, d, ledger.damping);
  bonded.add_work_of_damping(block_set, model, dashpots, mean, d, ledger.damping);
  contact_set.add_work_of_damping(ledger.damping, mean, d, dashpots);
}

} // namespace ddafem::dda
