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

namespace
{
/// The blocks of `model` with their initial velocity and stress, and their names for messages
/// (`names`). Throws InputError for a model without blocks.
std::vector<Block> make_blocks(const ModelDescription& model, std::vector<std::string>& names)
{
  std::vector<Block> blocks;
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
  return blocks;
}

} // namespace

System::System(const ModelDescription& model_)
    : model(model_), solver(model_.solver), parallel(model_.solver.threads)
{
  scheme.set_up(model.time.integrator, model.time.spectral_radius);
  materials = block_materials(model);
  std::vector<std::string> names;
  blocks = make_blocks(model, names);
  held.assign(blocks.size(), false);
  removed.assign(blocks.size(), false);
  const double size = model_size(blocks);
  bonded.find(model, blocks, names, 1e-9 * size, small_displacement());
  contact_set.set_up(model, blocks, size, !small_displacement());
  equations.rhs.setZero(static_cast<Eigen::Index>(n_dofs()));
  equations.solution.setZero(static_cast<Eigen::Index>(n_dofs()));
  // Point loads, fixed points and monitors onto their blocks, then the element kinds (each
  // throws InputError for a point or an element the blocks cannot carry).
  point_set.attach(model, *this);
  element_kinds = make_element_kinds(model, *this);
  boundary_set.select(model, blocks, bonded.list, 1e-6 * size);
  // The joints' preloads and the static supports of the viscous boundaries' edges from the
  // in-situ stress.
  bonded.apply_in_situ_stress(model.in_situ_stress);
  boundary_set.set_up_supports(model, blocks, point_set.default_stiffness, small_displacement());
  // The step's matrix structure: joints now, contacts once found.
  set_matrix_structure({});
  ledger.initial = energy().stored();
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
  tie_set.attach(body, points, blocks, 1e-6 * model_size(blocks));
  set_matrix_structure(equations.coupling_pairs);
  ++contact_set.geometry_epoch;
}

void System::hold_block(std::size_t i)
{
  held[i] = true;
  equations.reassemble(); // with the hold
}

void System::remove_block(std::size_t i)
{
  Block& b = blocks[i];
  ledger.removed += kinetic_energy(b);
  b.velocity.setZero();
  b.acceleration.setZero();
  removed[i] = true;
  equations.reassemble();
  ++contact_set.geometry_epoch;
  bonded.remove_block(i);
}

void System::set_at_rest()
{
  for (Block& b : blocks)
  {
    b.velocity.setZero();
    b.acceleration.setZero();
    b.force.setZero();
  }
  scheme.motion_starts = true;
}

void System::begin_stage(StageMode new_mode)
{
  const bool after_static = mode == StageMode::static_equilibrium;
  mode = new_mode;
  equations.reassemble(); // the boundary terms change with the stage
  ++contact_set.geometry_epoch;
  held.assign(blocks.size(), false);
  for (const std::unique_ptr<ElementKind>& k : element_kinds)
    k->begin_stage(stages_begun, current_time);
  ++stages_begun;
  if (tie_set.has_body())
    tie_set.body->begin_stage(mode);
  if (mode == StageMode::dynamic && !after_static)
    return;
  set_at_rest();
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
  const MaterialPoint& p = point_set.monitors[k];
  const Block& b = blocks[p.block];
  MonitorSample s;
  s.block = p.block;
  s.displacement = p.position - point_set.monitor_origins[k];
  s.velocity = point_matrix(p) * b.velocity;
  s.stress = b.stress;
  return s;
}

} // namespace ddafem::dda
