// The DDA model in time: blocks, joints, loads and the implicit step. Implemented one phase per
// file: system.cc (construction, stages, ties, observers), system_step.cc (the step and its
// control), system_assembly.cc, system_open_close.cc, slip_reversals.cc, step_scheme.cc,
// system_update.cc, system_energy.cc; the contacts are a ContactSet (dda/contact/).
#pragma once

#include "common/checkpoint_fwd.h"
#include "common/parallel.h"
#include "dda/block.h"
#include "dda/block_set.h"
#include "dda/bonded_joints.h"
#include "dda/boundary_set.h"
#include "dda/contact/contact.h"
#include "dda/contact/contact_set.h"
#include "dda/contact/narrow_phase.h"
#include "dda/element.h"
#include "dda/energy_ledger.h"
#include "dda/joints.h"
#include "dda/linear_solver.h"
#include "dda/model_description.h"
#include "dda/point_set.h"
#include "dda/snapshot.h"
#include "dda/step_equations.h"
#include "dda/step_scheme.h"
#include "dda/step_solver.h"
#include "dda/tie_set.h"
#include "dda/viscous_boundary.h"

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace ddafem::dda
{
/// What a step did. On a failure the model is left as it was before the step; the caller acts
/// on it: cut dt and retry (see can_retry_with_smaller_step) or stop.
enum class StepOutcome
{
  success,
  solver_failure, ///< singular / indefinite matrix, or NaN in the solution
  /// the open-close iteration did not settle within ContactSettings::max_open_close_iterations
  not_converged,
  /// a vertex moved more than the allowed step displacement (g2 w0)
  displacement_too_large,
  /// a closed contact penetrates deeper than ContactSettings::max_penetration (its penalty has
  /// been raised for the retry when StepStatus::penalty_raised)
  penetration_too_large,
  /// a bonded joint broke in a small-displacement analysis, which cannot follow contacts
  joint_broken,
  energy_growth, ///< stored energy exceeds 10x the energy put in: something feeds the model
  /// a sliding contact reversed its slip within the step and its friction, acting the wrong
  /// way for part of it, left more than the tolerated slip error
  /// (System::localize_slip_reversals); the step is redone to end before the reversal
  /// (StepStatus::reversal_fraction)
  slip_reversal
};

constexpr std::array<EnumName<StepOutcome>, 8> enum_names(StepOutcome)
{
  return {{{StepOutcome::success, "success"},
           {StepOutcome::solver_failure, "solver_failure"},
           {StepOutcome::not_converged, "not_converged"},
           {StepOutcome::displacement_too_large, "displacement_too_large"},
           {StepOutcome::penetration_too_large, "penetration_too_large"},
           {StepOutcome::joint_broken, "joint_broken"},
           {StepOutcome::energy_growth, "energy_growth"},
           {StepOutcome::slip_reversal, "slip_reversal"}}};
}

/// Whether a smaller dt can cure the outcome.
bool can_retry_with_smaller_step(StepOutcome outcome);

/// Where a step attempt is, for its messages: formatted ("at t = ... (dt = ...)") only when a
/// message needs it, not in every attempt.
struct StepLabel
{
  double time = 0.0; ///< the step's start [s]
  double dt = 0.0;   ///< [s]
  std::string text() const;
};

struct StepStatus
{
  StepOutcome outcome = StepOutcome::success;
  std::string message; ///< why it failed, with the time reached
  SolveStatus solve;   ///< of the last solve
  unsigned n_open_close_iterations = 0;
  std::size_t n_state_changes = 0; ///< contact state changes over the iteration
  double max_displacement = 0.0;   ///< largest vertex displacement of the step [m]
  double max_penetration = 0.0;    ///< deepest closed contact at the end of the step [m]
  /// penetration_too_large: the penetrating contacts' penalty was raised x 10 (within
  /// ContactSettings::max_penalty_factor); retrying the same dt may cure it
  bool penalty_raised = false;
  /// Contacts whose state changes were let go as carrying almost nothing (flip_force_ratio)
  std::size_t n_flips_ignored = 0;
  /// Static stages: the largest BlockBalance::ratio() over the blocks not held [-], each
  /// block's out-of-balance force against its own load; 0 in dynamic stages.
  double unbalanced_force_ratio = 0.0;
  std::size_t unbalanced_block = 0; ///< static stages: the block with the largest of them
  /// slip_reversal: the fraction of the step before the earliest reversal [-], in (0, 1)
  double reversal_fraction = 0.0;
};

/// Static stages: the balance of one block at the start of a step.
struct BlockBalance
{
  /// The resultant force on the block [N] (global x, y): the translational part of the step's
  /// right-hand side at zero velocity, i.e. gravity + loads + the forces of fixed points,
  /// supports, bonded joints, contacts and ties at the step's start.
  Vector2 out_of_balance = Vector2::Zero();
  /// The block's own load [N]: the sum of the magnitudes of those forces, m |g| + sum |f_k|
  /// (each end spring of a bonded joint, each closed contact, each load, fixed point, support and
  /// tie point of the block counted once). |out_of_balance| <= load: a block in free fall has
  /// ratio 1, one held by in-situ joint forces of many times its weight is measured against
  /// them.
  double load = 0.0;
  double weight = 0.0; ///< m |g| [N]

  /// |out_of_balance| / load [-], in [0, 1]; 0 for a block without load.
  double ratio() const { return load > 0.0 ? out_of_balance.norm() / load : 0.0; }
};

/// Wall time spent in each phase of the step since construction [s], and work counters.
struct PhaseTimings
{
  double broad_phase = 0.0;  ///< candidate block pairs
  double narrow_phase = 0.0; ///< vertex-edge contacts of the pairs, matched to the previous ones
  double assemble = 0.0;     ///< the step's matrix and right-hand side without contacts
  double solve = 0.0;        ///< the open-close iteration: contact terms, solves, trial states
  double update = 0.0;
  double tie_terms = 0.0; ///< T^T H T and T^T g of a tied body (part of `solve`)
  /// The tied body's own work (begin_step, end_step: the far field's solves and the tie
  /// algebra), in no other phase.
  double tied_body = 0.0;
  std::size_t n_steps = 0;                 ///< accepted steps
  std::size_t n_attempts = 0;              ///< steps tried, accepted or not
  std::size_t n_open_close_iterations = 0; ///< over all attempts
};

/// History record of a monitor.
struct MonitorSample
{
  std::size_t block = 0;
  Vector2 displacement = Vector2::Zero(); ///< of the material point since t = 0 [m]
  Vector2 velocity = Vector2::Zero();     ///< of the material point [m/s]
  Voigt stress = Voigt::Zero();           ///< of its block [Pa], tension positive
};

/// A DDA model advancing in time with one implicit linear system per step:
/// (K + c M) d = f + inertia_force (dda/integrator.h: generalized-alpha, or Newmark with
/// (beta, gamma) = (1/2, 1) for DDA's scheme or (1/4, 1/2) for the trapezoidal rule).
/// With GeometryMode::updated (Shi) every step is linearised about the current vertices, moments
/// and material points; with small_displacement about the initial ones.
class System final
{
public:
  /// Builds blocks, finds joints, attaches loads, fixed points and monitors to their blocks.
  /// Throws InputError for what the scene reader cannot see (blocks sharing an edge with no joint
  /// material, a frictional joint material, a point outside every block).
  explicit System(const ModelDescription& model);

  /// One step of dt [s] in named phases: find contact candidates, update contacts, assemble,
  /// solve with the open-close iteration, update blocks (then bonded joints beyond their
  /// strength break). On a failure nothing changes (the caller may retry with a smaller dt).
  /// `part`: which part of the integrator's step this is (Bathe's composite scheme takes a
  /// first and a second half in a dynamic stage, TimeStepper::advance); a part the integrator
  /// and stage cannot take is a programming error (std::logic_error).
  StepStatus advance(double dt, StepPart part = StepPart::full);

  /// Dynamic steps from now on fail with StepOutcome::slip_reversal when a sliding contact that
  /// carries force (above ContactSettings::flip_force_ratio of the largest) reverses its slip
  /// within the step with a slip error (slip_error of SlipReversal::speed_error) above
  /// `tolerance` [m]: a step applies the end state's shear force throughout, so the friction
  /// acted the wrong way for part of it, an error that repeated reversals add up (two-way
  /// sliding). A step in which such a contact's friction turns around is redone from the
  /// right-hand limit of the start state (restart_at_friction_jumps). 0 (the
  /// default) accepts every step as it is.
  void localize_slip_reversals(double tolerance) { contact_set.reversal_tolerance = tolerance; }

  /// Ties m points, each on the boundary of its block, to `body`, which the System steps with
  /// itself from then on (see TiedBody). The body must outlive the System. Before the first
  /// step only; throws InputError for a point off its block.
  void tie(TiedBody& body, const std::vector<MaterialPoint>& points);
  /// The ties to a tied body (empty without one): the tie points at their current positions.
  const TieSet& ties() const { return tie_set; }

  /// Starts a stage. Static (Shi's static analysis): velocities are zeroed before every step and
  /// the clock stands still; the edges of viscous boundaries are held by their supports instead
  /// of the dashpots, and a tied body is held (TiedBody::begin_stage). A dynamic stage after a
  /// static one starts at rest from the state reached, with the energy balance, the monitors'
  /// and the ties' displacements measured from there; the supports' forces become constant
  /// edge loads (reaction transfer).
  void begin_stage(StageMode mode);
  StageMode stage_mode() const { return mode; }

  /// Holds block i where it is (each of its six unknowns gets a penalty spring of 1e8 x its own
  /// diagonal entry of the step's matrix, so it moves 1e-8 of what it would)
  /// until the next begin_stage: a static stage's released block, which cannot be in
  /// equilibrium, so that it keeps the rest from converging no more. Its balance no longer
  /// counts in StepStatus::unbalanced_force_ratio.
  void hold_block(std::size_t i);
  /// Makes block i inert for the rest of the run: held as by hold_block in every stage, its
  /// bonded joints removed and no contacts with it, so that it puts no force on the others.
  /// A moving block is stopped: its kinetic energy leaves the model (EnergyBalance::removed).
  void remove_block(std::size_t i);
  /// Static stages: every block's balance at the start of the last accepted step (empty before
  /// the first static step).
  const std::vector<BlockBalance>& block_balances() const { return balances; }

  double time() const { return current_time; }
  std::size_t n_steps() const { return timings.n_steps; }
  /// The intact bonded joints (broken ones are gone: their blocks meet through contacts).
  const BondedJoints& bonded_joints() const { return bonded; }
  /// The element kinds (dda/element.h), in the order the step takes them.
  const std::vector<std::unique_ptr<ElementKind>>& get_element_kinds() const
  {
    return element_kinds;
  }
  /// The element kind `Kind` (dda/element.h; e.g. Bolts), with its elements' state at the
  /// last accepted step. Every kind of make_element_kinds exists, with or without elements.
  template <class Kind>
  const Kind& elements() const
  {
    for (const std::unique_ptr<ElementKind>& k : element_kinds)
      if (const Kind* kind = dynamic_cast<const Kind*>(k.get()))
        return *kind;
    throw std::logic_error("System::elements: no such element kind");
  }
  /// The contacts: those of the last accepted step (`accepted`, ordered by vertex block,
  /// vertex, edge block, edge), their counts and distances (w0, g2 w0, d0, the penetration
  /// limit).
  const ContactSet& contacts() const { return contact_set; }
  const ModelDescription& get_model() const { return model; }
  /// The blocks (their geometry, state, mass; which are held or removed).
  const BlockSet& blocks() const { return block_set; }
  const PhaseTimings& get_timings() const { return timings; }
  const StepSolver& get_solver() const { return solver; }
  /// The viscous boundaries' edges and their static supports.
  const BoundarySet& boundaries() const { return boundary_set; }
  /// The point loads, fixed points (with their default penalty) and monitors.
  const PointSet& points() const { return point_set; }

  /// Checkpoints (dda/system_checkpoint.cc): stores everything later steps read; `load` into a
  /// System built from the same model restores it, so that it steps on bit for bit as the saved
  /// one would. Between accepted steps only. Loading throws std::runtime_error for a checkpoint
  /// of another model.
  void save(CheckpointOut& archive) const;
  void load(CheckpointIn& archive);

  MonitorSample sample_monitor(std::size_t monitor) const;
  EnergyBalance energy() const;

private:
  /// save and load: one function for both (Boost.Serialization's `&` stores or restores).
  template <class Archive>
  void transfer_state(Archive& archive);

  // The step's phases and their parts (system_step.cc, system_assembly.cc,
  // system_open_close.cc, system_update.cc, slip_reversals.cc).
  /// Static stages: each block's balance from the step's right-hand side (after the contact
  /// and tie terms), into `balances`; the status's largest ratio over the blocks not held.
  void measure_balance(StepStatus& status);
  /// Phase 4: solves with the contacts in their trial states until no state changes.
  /// `new_matrix`: the matrix was assembled for this step (else base_matrix holds it).
  StepStatus solve_with_open_close(const StepLabel& when, bool new_matrix);
  /// Friction that turns around in a step jumps by Delta S = S_end - S_start [N] along the
  /// contact's tangent. Generalized-alpha's (1 - alpha_f) r_{n+1} + alpha_f r_n would apply the
  /// jump only in part and leave the velocity alpha_f dt Delta r / m behind for as long as the
  /// new friction lasts (a first-order error at every reversal of two-way sliding); Newmark's
  /// v_{n+1} = v_n + dt ((1 - gamma) a_n + gamma a_{n+1}) leaves (1 - gamma) dt Delta a (the
  /// trapezoidal rule, Bathe's first half). Restarts the integrator at the jump instead, as at
  /// any discontinuous load: the start state of the blocks on each side takes its right-hand
  /// limit, r_n + Delta r and a_n + M^-1 Delta r (the displacements, hence every other force,
  /// are continuous); with the Newmark schemes, the translational part of Delta r only (see
  /// slip_reversals.cc). The state before is kept in
  /// `scheme.friction_jumps` until the step is accepted or StepScheme::undo_friction_jumps restores
  /// it.
  void restart_at_friction_jumps(const std::vector<std::size_t>& turning);
  /// One attempt at a step (advance() without undoing an earlier attempt's friction jumps).
  StepStatus attempt_step(double dt, StepPart part);
  /// Phases 1 and 2 of a step: the contact set's candidates among the blocks not removed, its
  /// narrow phase, the matrix structure (joined blocks and blocks in contact), the contacts'
  /// frames, and the trial contacts matched to the accepted ones to keep id, state and forces;
  /// a retry at the same contact_set.geometry_epoch reuses `detected`.
  void detect_contacts();
  /// Phase 3: the step's matrix and right-hand side; true if the matrix was assembled anew
  /// (a small-displacement analysis keeps it while dt is unchanged).
  bool assemble_step(double dt);
  /// Phase 4: the solution, with the open-close iteration if there are contacts or ties.
  StepStatus solve_step(const StepLabel& when, bool new_matrix);
  /// Phase 5: the tied body, blocks and contacts take the solution; time advances. The tied
  /// body's StepResult (when not taken, nothing else is updated).
  StepResult accept_step(double dt);
  /// The step's matrix couples the block pairs `couplings` (sorted) and those of the tied
  /// body's blocks; the bonded joints' coupling blocks are looked up again if it changed.
  void set_matrix_structure(std::vector<std::pair<std::size_t, std::size_t>> couplings);
  /// The step's right-hand side, and its matrix if `with_matrix`.
  void assemble(double dt, bool with_matrix);
  /// Each block's inertia c M and elasticity; its inertia force, stress and gravity [N, N m].
  void add_block_terms(double dt, bool with_matrix);
  /// The blocks and everything on them take the step's displacements d (6 per block).
  void update_blocks(double dt, const Eigen::VectorXd& d);
  /// Adds the step's work of loads and gravity, boundaries and moving supports [J] (before the
  /// material points move).
  void add_work_of_step(double dt, const Eigen::VectorXd& d);

  ModelDescription model;
  /// The blocks, their materials, which are held or removed; what the element kinds see of
  /// them (ElementHost).
  BlockSet block_set;
  BondedJoints bonded; ///< the intact bonded joints
  PointSet point_set;  ///< point loads, fixed points and monitors
  /// The element kinds (make_element_kinds), in the order the step takes them.
  std::vector<std::unique_ptr<ElementKind>> element_kinds;
  std::size_t stages_begun = 0; ///< begin_stage calls: the stage ElementKind::begin_stage gets
  BoundarySet boundary_set;     ///< the viscous boundaries' edges and their static supports
  TieSet tie_set;               ///< ties to a tied body (the far field)
  ContactSet contact_set;       ///< accepted and trial contacts, and their persistence
  StageMode mode = StageMode::dynamic;
  std::vector<BlockBalance> balances; ///< of the last accepted static step
  StepScheme scheme;                  ///< the integrator's form of the step being tried

  StepEquations equations; ///< the step's linear system, its structure and solution
  StepSolver solver;
  /// Threads of contact detection and of the contacts' trial states (the solver has its own;
  /// results do not depend on either).
  Parallel parallel;

  double current_time = 0.0;
  EnergyLedger ledger; ///< the works done on the blocks, the initial and removed energy
  StepDashpots dashpots;
  PhaseTimings timings;
};

/// Stability of boundary edge k of `system` at time step dt [s].
BoundaryStability stability_of(const System& system, std::size_t k, double dt);
/// The contacts of `system`'s last accepted step and the end springs of its intact bonded joints.
std::vector<ContactSnapshot> contact_snapshot(const System& system);

} // namespace ddafem::dda
