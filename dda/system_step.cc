// The step and its control: advance() in named phases (contacts, assembly, solve, step
// control, acceptance) and the checks on each step's result.
#include "dda/system.h"

#include "common/stopwatch.h"
#include "dda/system_helpers.h"

#include <algorithm>
#include <cmath>
#include <future>
#include <sstream>

namespace ddafem::dda
{
namespace
{
/// Step control on the solution: sets the status's largest vertex displacement [m] (given) and
/// penetration, and its outcome if one exceeds its limit (g2 w0; max_penetration, after raising
/// the penalties of the contacts too deep).
void check_motion_limits(double max_displacement, ContactSet& contact_set, const StepLabel& when,
                         StepStatus& status)
{
  status.max_displacement = max_displacement;
  if (status.max_displacement > contact_set.distances.max_step_displacement)
  {
    std::ostringstream m;
    m << "a vertex moves " << status.max_displacement << " m in one step, more than the "
      << contact_set.distances.max_step_displacement << " m allowed (g2 w0) " << when.text();
    status.outcome = StepOutcome::displacement_too_large;
    status.message = m.str();
    return;
  }
  const Contact* deepest = contact_set.deepest(status.max_penetration);
  if (status.max_penetration > contact_set.distances.max_penetration)
  {
    std::ostringstream m;
    m << "a contact (vertex " << deepest->vertex << " of block " << deepest->vertex_block
      << " on edge " << deepest->edge << " of block " << deepest->edge_block << ", gap "
      << deepest->gap << " m at the step's start) penetrates " << status.max_penetration
      << " m, deeper than the " << contact_set.distances.max_penetration << " m allowed "
      << when.text() << " (a stiffer joint normal_stiffness or a smaller dt reduces it)";
    status.penalty_raised = contact_set.raise_penalties();
    status.outcome = StepOutcome::penetration_too_large;
    status.message = m.str();
  }
}

/// A boundary beyond its stability limit feeds energy into the model: the status's outcome is
/// energy_growth when the stored energy (of the balance e at time t [s]) exceeds ten times all
/// the energy ever put in (the ledger's largest input, updated here).
void check_energy_growth(const EnergyBalance& e, EnergyLedger& ledger, double t, StepStatus& status)
{
  ledger.largest_input = std::max(ledger.largest_input, e.work_of_loads + e.work_of_supports);
  const double reference = e.initial + ledger.largest_input;
  if (!std::isfinite(e.stored()) || e.stored() > 10.0 * reference)
  {
    std::ostringstream m;
    m << "the stored energy grew to " << e.stored() << " J, more than 10 times the " << reference
      << " J put into the model, at t = " << format_time(t)
      << ": a boundary is feeding energy into the model (see `ddafem check` for each "
         "boundary's time-step limit)";
    status.outcome = StepOutcome::energy_growth;
    status.message = m.str();
  }
}

} // namespace

std::string StepLabel::text() const
{
  return "at t = " + format_time(time) + " (dt = " + format_time(dt) + ")";
}

StepStatus System::advance(double dt, const StepPart part)
{
  scheme.undo_friction_jumps(block_set.list); // each attempt starts from the accepted state
  return attempt_step(dt, part);
}

StepStatus System::attempt_step(double dt, const StepPart part)
{
  const StepLabel when{current_time, dt};
  ++timings.n_attempts;
  if (mode == StageMode::static_equilibrium)
  {
    block_set.set_at_rest();
    scheme.motion_starts = true;
  }
  scheme.choose(dt, part,
                mode == StageMode::dynamic); // 0. the integrator's form of this part of a step
  // A tied body begins its step (the far field's free response) on another thread while the
  // blocks find their contacts and assemble: the two touch no common data.
  std::future<StepResult> tied = tie_set.begin_step(dt, block_set, timings.tied_body);
  detect_contacts();                         // 1. candidates, 2. contacts
  const bool new_matrix = assemble_step(dt); // 3. assemble
  if (tie_set.has_body())
  {
    const StepResult begun = tied.get();
    if (!begun.taken)
      return {StepOutcome::solver_failure, begun.why + " " + when.text(), {}};
  }
  StepStatus status = solve_step(when, new_matrix); // 4. solve with the open-close iteration
  if (status.outcome != StepOutcome::success)
    return status;
  if (mode == StageMode::static_equilibrium)
    measure_balance(status);

  // Step control: no vertex may move farther than g2 w0, no contact penetrate too deep, no
  // slip reversal leave more than the tolerance.
  check_motion_limits(block_set.largest_vertex_displacement(equations.solution), contact_set, when,
                      status);
  if (status.outcome != StepOutcome::success)
    return status;
  if (contact_set.localises_reversals(mode == StageMode::dynamic))
  {
    const ContactSet::ReversalScan scan = contact_set.scan_reversals(
        {block_set.list, dt, scheme.coefficients, scheme.integrator == Integrator::bathe,
         scheme.start_force_lag(),
         [&](std::size_t i) { return scheme.start(block_set.list[i], i, dt); }});
    if (scan.earliest > 0.0)
    {
      status.reversal_fraction = scan.earliest;
      status.outcome = StepOutcome::slip_reversal;
      status.message = "a sliding contact reverses its slip " + format_time(scan.earliest * dt) +
                       " after the step's start " + when.text();
      return status;
    }
    // A step at which friction turns around is redone with the integrator restarted at the
    // jump (generalized-alpha; the trapezoidal rule and Bathe's first half, whose end velocity
    // takes the start's acceleration). The redo repeats phases 1 and 2 too: they reset the
    // trial contacts to the step's start (the restart leaves the geometry as it was), and it
    // is taken on few steps.
    if (!scan.friction_turns.empty() && scheme.start_force_lag() > 0.0 &&
        scheme.friction_jumps.empty())
    {
      restart_at_friction_jumps(scan.friction_turns);
      return attempt_step(dt, part);
    }
  }

  // 5. Update the tied body, blocks and contacts.
  const StepResult accepted = accept_step(dt);
  if (!accepted.taken)
    return {StepOutcome::solver_failure, accepted.why + " " + when.text(), status.solve};
  const std::string broken = bonded.break_beyond_strength(
      model, contact_set.tan_friction, block_set.small_displacement(), current_time);
  ++contact_set.geometry_epoch;
  if (!broken.empty())
    return {StepOutcome::joint_broken, broken, status.solve};
  if (!boundary_set.edges.empty() && mode == StageMode::dynamic)
    check_energy_growth(energy(), ledger, current_time, status);
  return status;
}

void System::detect_contacts()
{
  auto start = Clock::now();
  if (contact_set.detection_current())
  {
    // A retry from the same accepted state: the same contacts, frames and structure; only
    // their states are inherited again (penalties may have been raised).
    contact_set.inherit(parallel);
    timings.narrow_phase += seconds_since(start);
    return;
  }
  ContactSet::BlockPairs pairs =
      contact_set.enabled ? contact_set.candidates(block_set.list) : ContactSet::BlockPairs{};
  pairs.erase(std::remove_if(pairs.begin(), pairs.end(),
                             [&](const auto& p)
                             { return block_set.removed[p.first] || block_set.removed[p.second]; }),
              pairs.end());
  timings.broad_phase += seconds_since(start);
  start = Clock::now();
  const ContactSet::BlockPairs& joined = bonded.joined(element_kinds);
  const ContactSet::BlockPairs touching = contact_set.detect(
      {block_set.list, bonded.list, bonded.revision, mode == StageMode::static_equilibrium}, pairs,
      parallel);
  // The matrix couples joined blocks and blocks in contact (both lists sorted: merged).
  ContactSet::BlockPairs couplings(joined.size() + touching.size());
  std::merge(joined.begin(), joined.end(), touching.begin(), touching.end(), couplings.begin());
  set_matrix_structure(std::move(couplings));
  contact_set.set_frames(block_set.list, equations, parallel);
  contact_set.inherit(parallel);
  timings.narrow_phase += seconds_since(start);
}

bool System::assemble_step(double dt)
{
  // With updated geometry every step has its own matrix; a small-displacement analysis (no
  // contacts) keeps the matrix of the initial configuration while dt is unchanged.
  const auto start = Clock::now();
  // Elements whose stiffness changes with their state are assembled anew every step.
  const bool elements_change =
      std::any_of(element_kinds.begin(), element_kinds.end(),
                  [](const std::unique_ptr<ElementKind>& k) { return k->changes_stiffness(); });
  const bool new_matrix = !block_set.small_displacement() || elements_change ||
                          dt != equations.dt ||
                          scheme.coefficients.mass_factor(dt) != equations.mass_factor;
  assemble(dt, new_matrix);
  if (new_matrix) // held and removed blocks: a penalty of 1e8 x their own stiffness
    for (std::size_t i = 0; i < block_set.list.size(); ++i)
      if (block_set.is_held(i))
        equations.matrix.diagonal(i).diagonal() *= 1.0 + 1e8;
  equations.dt = dt;
  equations.mass_factor = scheme.coefficients.mass_factor(dt);
  timings.assemble += seconds_since(start);
  return new_matrix;
}

StepStatus System::solve_step(const StepLabel& when, bool new_matrix)
{
  const auto start = Clock::now();
  StepStatus status;
  if (contact_set.trial.empty() && !tie_set.has_body())
  {
    status.solve = solver.solve(equations.matrix, equations.rhs, equations.solution,
                                new_matrix ? MatrixChange::unknown : MatrixChange::unchanged,
                                equations.mass_factor);
    if (!status.solve.success)
    {
      status.outcome = StepOutcome::solver_failure;
      status.message = status.solve.message + " " + when.text();
    }
  }
  else
    status = solve_with_open_close(when, new_matrix);
  timings.solve += seconds_since(start);
  return status;
}

StepResult System::accept_step(double dt)
{
  auto start = Clock::now();
  if (tie_set.has_body())
  {
    const StepResult ended = tie_set.body->end_step(tie_set.increments(equations.solution));
    timings.tied_body += seconds_since(start);
    if (!ended.taken)
      return ended;
  }
  start = Clock::now();
  scheme.record_half(dt, equations.solution, block_set.list, mode == StageMode::dynamic);
  update_blocks(dt, equations.solution);
  contact_set.accept(dt);
  if (mode == StageMode::static_equilibrium)
  {
    block_set.set_at_rest();
    scheme.motion_starts = true;
  }
  else
  {
    current_time += dt;
    scheme.motion_starts = false;
    scheme.friction_jumps.clear(); // the restarted state is the accepted one
  }
  timings.update += seconds_since(start);
  ++timings.n_steps;
  return {};
}

void System::measure_balance(StepStatus& status)
{
  // With zero velocity the right-hand side's translational part is the resultant force at the
  // step start; the magnitudes of its terms, from the same step-start state, are the load.
  balances.assign(block_set.list.size(), {});
  for (std::size_t i = 0; i < block_set.list.size(); ++i)
  {
    balances[i].out_of_balance = equations.rhs.segment<2>(6 * i);
    balances[i].weight = balances[i].load = block_set.mass_of(i) * model.gravity.norm();
  }
  const auto add = [&](std::size_t block, double magnitude) { balances[block].load += magnitude; };
  point_set.add_loads(add, current_time);
  boundary_set.add_loads(add);
  for (const std::unique_ptr<ElementKind>& k : element_kinds)
    k->add_loads(add);
  bonded.add_loads(add);
  contact_set.add_loads(add);
  tie_set.add_loads(add);
  for (std::size_t i = 0; i < block_set.list.size(); ++i)
    if (!block_set.is_held(i) && balances[i].ratio() > status.unbalanced_force_ratio)
    {
      status.unbalanced_force_ratio = balances[i].ratio();
      status.unbalanced_block = i;
    }
}

} // namespace ddafem::dda
