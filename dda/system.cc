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

System::System(const ModelDescription& model_)
    : model(model_), block_set(model), solver(model_.solver), parallel(model_.solver.threads)
{
  scheme.set_up(model.time.integrator, model.time.spectral_radius);
  const std::vector<std::string> names = block_names(model);
  const double size = model_size(block_set.list);
  bonded.find(model, block_set.list, names, 1e-9 * size, block_set.small_displacement());
  contact_set.set_up(model, block_set.list, size, !block_set.small_displacement());
  equations.rhs.setZero(static_cast<Eigen::Index>(block_set.n_dofs()));
  equations.solution.setZero(static_cast<Eigen::Index>(block_set.n_dofs()));
  // Point loads, fixed points and monitors onto their blocks, then the element kinds (each
  // throws InputError for a point or an element the blocks cannot carry).
  point_set.attach(model, block_set);
  element_kinds = make_element_kinds(model, block_set);
  boundary_set.select(model, block_set.list, bonded.list, 1e-6 * size);
  // The joints' preloads and the static supports of the viscous boundaries' edges from the
  // in-situ stress.
  bonded.apply_in_situ_stress(model.in_situ_stress);
  boundary_set.set_up_supports(model, block_set.list, point_set.default_stiffness,
                               block_set.small_displacement());
  // The step's matrix structure: joints now, contacts once found.
  set_matrix_structure({});
  ledger.initial = energy().stored();
}

void System::tie(TiedBody& body, const std::vector<MaterialPoint>& points)
{
  if (timings.n_attempts > 0)
    throw InputError("tie(): the ties must be made before the first step");
  tie_set.attach(body, points, block_set.list, 1e-6 * model_size(block_set.list));
  set_matrix_structure(equations.coupling_pairs);
  ++contact_set.geometry_epoch;
}

void System::hold_block(std::size_t i)
{
  block_set.held[i] = true;
  equations.reassemble(); // with the hold
}

void System::remove_block(std::size_t i)
{
  Block& b = block_set.list[i];
  ledger.removed += block_set.kinetic_energy(b);
  b.velocity.setZero();
  b.acceleration.setZero();
  block_set.removed[i] = true;
  equations.reassemble();
  ++contact_set.geometry_epoch;
  bonded.remove_block(i);
}

void System::begin_stage(StageMode new_mode)
{
  const bool after_static = mode == StageMode::static_equilibrium;
  mode = new_mode;
  equations.reassemble(); // the boundary terms change with the stage
  ++contact_set.geometry_epoch;
  block_set.held.assign(block_set.list.size(), false);
  for (const std::unique_ptr<ElementKind>& k : element_kinds)
    k->begin_stage(stages_begun, current_time);
  ++stages_begun;
  if (tie_set.has_body())
    tie_set.body->begin_stage(mode);
  if (mode == StageMode::dynamic && !after_static)
    return;
  block_set.set_at_rest();
  scheme.motion_starts = true;
  // Reaction transfer: what the supports hold at the end of a static stage stays as a constant
  // load on the edges; a static stage anchors them where the edges are.
  boundary_set.begin_stage(after_static, mode == StageMode::static_equilibrium);
  if (mode == StageMode::dynamic)
  {
    // Measure the dynamic stage from the equilibrium reached.
    point_set.measure_from_here();
    tie_set.measure_from_here();
    ledger.restart(energy().stored());
  }
}

// ---- observers -------------------------------------------------------------------------------

MonitorSample System::sample_monitor(std::size_t k) const
{
  const MaterialPoint& p = point_set.monitors[k];
  const Block& b = block_set.list[p.block];
  MonitorSample s;
  s.block = p.block;
  s.displacement = p.position - point_set.monitor_origins[k];
  s.velocity = block_set.point_matrix(p) * b.velocity;
  s.stress = b.stress;
  return s;
}

} // namespace ddafem::dda
