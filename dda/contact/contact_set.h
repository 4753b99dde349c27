// The blocks' contacts and their persistence (issue 55): the contact distances and which blocks
// are convex (set up once), the contacts of the last accepted step, the trial contacts of the
// step being tried, each matched to its predecessor so that it keeps its id, state, forces and
// slip history from step to step, and the penalties a failed step raised for its retry.
// Detection (the broad phase `candidates`, the narrow phase `detect` with the vertices that intact
// joints tie, and the frames) fills `detected` when the geometry changed; `inherit` makes the
// trial contacts of it; `accept` makes them the accepted ones.
#pragma once

#include "common/parallel.h"
#include "dda/block.h"
#include "dda/contact/contact.h"
#include "dda/contact/contact_law.h"
#include "dda/contact/narrow_phase.h"
#include "dda/damping.h"
#include "dda/element.h"
#include "dda/integrator.h"
#include "dda/joints.h"
#include "dda/linear_solver.h"
#include "dda/model_description.h"
#include "dda/snapshot.h"
#include "dda/types.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <tuple>
#include <utility>
#include <vector>

namespace ddafem::dda
{
/// Shi's w0 and the contact distances that follow from it and the ContactSettings.
struct ContactDistances
{
  double w0 = 0.0;                    ///< half the model size [m]
  double max_step_displacement = 0.0; ///< g2 w0, at most a tenth of the shortest edge [m]
  double search_distance = 0.0;       ///< d0 [m]
  double max_penetration = 0.0;       ///< [m]
  double angle_tolerance = 0.0;       ///< [rad]
  double sin_angle_tolerance = 0.0;   ///< its sine [-]
};

/// Number of contacts in each state.
struct ContactCounts
{
  std::size_t open = 0, slide = 0, lock = 0;
};

/// Geometry of a contact over the step: T of the vertex and of its projection on the edge, the
/// edge's outward unit normal and unit tangent, in the configuration at the step start.
struct ContactFrame
{
  Matrix26 t_vertex, t_edge;
  Vector2 normal, tangent;
};

struct ContactSet
{
  using BlockPairs = std::vector<std::pair<std::size_t, std::size_t>>;
  /// What the narrow phase reads of the System.
  struct DetectionInput
  {
    const std::vector<Block>& blocks;
    const std::vector<Joint>& joints;   ///< the intact bonded joints
    std::uint64_t joint_revision = 0;   ///< counts the changes of `joints`
    bool initial_configuration = false; ///< a static stage: joints tie vertices as at t = 0
  };
  /// What the trial states read of the step being solved.
  struct TrialInput
  {
    const Eigen::VectorXd& solution; ///< the blocks' unknowns d of this iteration (6 per block)
    const StepDashpots& dashpots;
    double dt = 0.0;         ///< of the matrix [s] (the slide duration's unit)
    unsigned iteration = 0;  ///< of the open-close iteration, from 1
    bool localising = false; ///< slip reversals are localised: long slides that reverse lock
  };
  /// What the slip-reversal scan reads of the step being tried.
  struct ReversalInput
  {
    const std::vector<Block>& blocks;
    double dt = 0.0; ///< [s]
    const IntegratorCoefficients& integration;
    bool bathe = false;           ///< Bathe's scheme: only reversals of long slides count
    double start_force_lag = 0.0; ///< alpha_f of the step (0 in Bathe's second half) [-]
    /// Block i's velocity and acceleration the step's Newmark update starts from (Bathe's
    /// second half: an equivalent state)
    std::function<KinematicState(std::size_t)> step_start;
  };
  /// Slip reversals among the trial contacts that slid at the step's start and carry force.
  struct ReversalScan
  {
    /// the earliest reversal (SlipReversal::at, a fraction of the step) whose slip error
    /// (slip_error of its speed error) exceeds the reversal tolerance; 0 if there is none
    double earliest = 0.0;
    /// the trial contacts (indices) whose friction turned around from slide to slide in the
    /// step with a generalized-alpha velocity lag, alpha_f |v1 - v0|, whose slip error exceeds
    /// the reversal tolerance
    std::vector<std::size_t> friction_turns;
  };
  /// The contact terms in the matrix: each trial contact's state when they were added, and the
  /// contacts by block and by coupling (ascending) to sum a block again.
  struct TermsIndex
  {
    std::vector<ContactState> states;
    bool indexed = false;
    std::vector<std::size_t> block_start, block_contacts;       ///< CSR by block
    std::vector<std::size_t> coupling_start, coupling_contacts; ///< CSR by coupling
    std::vector<std::size_t> changed_blocks, changed_couplings; ///< scratch
  };

  /// The narrow phase's result at `epoch` (trial contacts before `inherit`, with their
  /// couplings; the System's contact frames and matrix structure go with it): a retried step
  /// (cut dt, slip reversal, raised penalties) starts from the same accepted state and reuses it.
  struct Detected
  {
    std::uint64_t epoch = std::numeric_limits<std::uint64_t>::max();
    std::vector<Contact> contacts;
    /// Per contact its predecessor's index in `accepted`, or the maximum std::size_t; empty
    /// until `inherit` searched them at `epoch`.
    std::vector<std::size_t> predecessors;
  };

  bool enabled = true; ///< false in a small-displacement analysis: blocks meet by joints only
  const ModelDescription* model = nullptr; ///< its joint materials and contact settings
  std::vector<double> tan_friction;        ///< tan(phi) per joint material
  ContactDistances distances;
  std::vector<bool> convex; ///< whether each block is convex (at t = 0)
  /// Counts the changes of what contact detection depends on (the blocks' geometry, removed
  /// blocks, joints, stage, ties, the accepted contacts): detection is redone only when it moved.
  std::uint64_t geometry_epoch = 0;
  std::vector<Contact> accepted; ///< of the last accepted step, in key order
  std::vector<Contact> trial;    ///< of the step being tried
  Detected detected;
  std::size_t next_id = 0; ///< the id of the next new contact
  /// Penalty factors raised by a failed step, by contact key, for the retry
  std::map<std::tuple<std::size_t, std::size_t, std::size_t, std::size_t>, double> raised_penalties;
  std::vector<ContactFrame> frames; ///< of `trial` (and detected.contacts)
  TermsIndex terms;                 ///< of the trial contacts in the step's matrix
  double reversal_tolerance = 0.0;  ///< slip error of a reversal that is localised [m]; 0: none
  /// Whether slip reversals are localised in a stage (a reversal tolerance, `dynamic`).
  bool localises_reversals(bool dynamic) const { return reversal_tolerance > 0.0 && dynamic; }
  /// Where a bonded joint ties a vertex to the other block: (vertex block, vertex, other block).
  std::vector<std::tuple<std::size_t, std::size_t, std::size_t>> jointed_vertices;

  /// Sets `enabled`, `model` (which must outlive the set: the System's own copy), tan(phi) per
  /// joint material, the distances from the model's size [m] and its ContactSettings, and
  /// `convex` per block; throws InputError if two blocks that may touch have materials no joint
  /// material applies to.
  void set_up(const ModelDescription& description, const std::vector<Block>& blocks, double size,
              bool contacts_enabled);
  /// Whether `detected` is of the current geometry (a retried step reuses it).
  bool detection_current() const { return detected.epoch == geometry_epoch; }

  /// Phase 1: block pairs whose boxes, inflated by d0, overlap.
  BlockPairs candidates(const std::vector<Block>& blocks) const;
  /// Phase 2, the narrow phase: the vertex-edge contacts of the candidate pairs, sorted by key,
  /// into detected.contacts (without state, at the current geometry_epoch; `inherit` makes them
  /// the trial contacts). Vertices tied by an intact joint to the other block make none.
  /// Returns the pairs with contacts, sorted (the matrix couples them).
  BlockPairs detect(const DetectionInput& in, const BlockPairs& pairs, const Parallel& parallel);
  /// Each detected contact's coupling in the step's matrix structure (`equations`, set after
  /// `detect`) and its frame at the step start.
  void set_frames(const std::vector<Block>& blocks, const StepEquations& equations,
                  const Parallel& parallel);
  /// Contact c's law: its joint material's springs (times its penalty factor), friction,
  /// cohesion and tensile strength over its length (none for a broken bonded joint's).
  ContactLaw law(const Contact& c) const;
  /// Adds every closed trial contact's terms to the matrix and right-hand side (an attempt's
  /// first open-close iteration, or after the tie terms changed).
  void add_terms(StepEquations& step, const StepDashpots& dashpots);
  /// A later iteration: `step.matrix` holds `start` plus the terms of the states last added; the
  /// blocks of contacts that changed state are summed again from `start`, and the contacts'
  /// forces are added to `step.rhs` (which holds the start's).
  void update_terms(StepEquations& step, const BlockSparseMatrix& start,
                    const StepDashpots& dashpots);
  /// Sets each trial from the solution; returns the number of state changes that hold the
  /// iteration back (from iteration 3 on, not those of contacts carrying almost nothing,
  /// which are counted in `n_ignored`).
  std::size_t update_trial_states(const TrialInput& in, std::size_t& n_ignored,
                                  const Parallel& parallel);
  /// The force below which a trial contact carries almost nothing [N]:
  /// ContactSettings::flip_force_ratio of the largest normal force of the trials.
  double negligible_force() const;
  /// Raises the penalty of the contacts that penetrate deeper than allowed; false if every one
  /// is at ContactSettings::max_penalty_factor already.
  bool raise_penalties();
  /// The trial contacts' dashpots' work on the step's d [J] (negative: absorbed), from `mean`,
  /// each block's mean velocity over the step, added term by term to `work`.
  void add_work_of_damping(double& work, const std::vector<Vector6>& mean, const Eigen::VectorXd& d,
                           const StepDashpots& dashpots) const;
  /// The slip reversals of the step being tried (in a dynamic stage with reversal_tolerance
  /// set).
  ReversalScan scan_reversals(const ReversalInput& in) const;
  /// Calls add(block, jump) with each friction jump's generalized force on a block [N, N m]
  /// (S acts on the vertex block as -S t, on the edge block as +S t), the trial contacts
  /// `turning` in order, each vertex block before its edge block.
  void add_friction_jumps(const std::vector<std::size_t>& turning,
                          const std::function<void(std::size_t, const Vector6&)>& add) const;
  /// The trial contact that penetrates deepest beyond `depth` [m] (the first of equals), which
  /// it then holds; null if none does.
  const Contact* deepest(double& depth) const;
  /// The accepted step: each trial contact's slip, slide duration and forces, which become the
  /// accepted contacts; the raised penalties are spent and the geometry moved.
  void accept(double dt);
  /// Static stages' balance: calls add(block, |force| [N]) with each closed contact's force on
  /// either block (the trial contacts' start forces).
  void add_loads(const std::function<void(std::size_t, double)>& add) const;
  /// The accepted closed contacts' spring energy [J], added term by term to `e`.
  void add_energy(double& e) const;
  /// The accepted contacts in each state.
  ContactCounts counts() const;
  /// The accepted contacts as snapshot points (at the vertex, the edge's outward normal, in
  /// the blocks' current configuration), appended to `out`.
  void add_snapshots(const std::vector<Block>& blocks, std::vector<ContactSnapshot>& out) const;
  /// Forgets the sorted lists of the joints (a checkpoint was read): the next detection
  /// rebuilds them.
  void forget_joint_lists() { exclusions.revision = std::numeric_limits<std::uint64_t>::max(); }

  /// trial: detected.contacts with the id, state, forces and slip history of the accepted
  /// contacts that persist; a new contact starts locked if its blocks touch (gap within
  /// 2e-9 w0, Shi's w0 of `distances` [m]), else open. The predecessors are searched for
  /// once per detection (kept in `detected`); a retry only copies the contacts and their states
  /// again. Ids do not depend on the number of threads of `parallel`.
  void inherit(const Parallel& parallel);

private:
  /// What detection needs of the intact joints, sorted once per joint revision instead of in
  /// every step.
  struct JointExclusions
  {
    std::uint64_t revision = std::numeric_limits<std::uint64_t>::max();
    /// Pairs of convex blocks joined by an intact joint (no contacts between them).
    BlockPairs bonded_pairs;
    /// The end vertices of each joint's edge on either block, which mark_jointed_vertices
    /// tests, sorted by (block, vertex, other block): its list comes out sorted.
    struct Candidate
    {
      std::size_t block = 0, vertex = 0, other = 0;
      std::size_t joint = 0; ///< index into the joints
    };
    std::vector<Candidate> candidates;
  };
  /// Each joint's start on a [m], unit tangent, length [m] (mark_jointed_vertices' scratch).
  struct JointFrame
  {
    Point start = Point::Zero();
    Vector2 tangent = Vector2::Zero();
    double length = 0.0;
  };
  /// The narrow phase's scratch per chunk of candidate pairs, kept from step to step (a cache
  /// line each: chunks run on different threads).
  struct alignas(64) NarrowPhaseChunk
  {
    std::vector<Contact> found;
    NarrowPhaseWorkspace work;
  };

  JointExclusions exclusions;
  std::vector<JointFrame> joint_frames;
  std::vector<NarrowPhaseChunk> narrow_chunks;
  /// The candidate pairs that need the narrow phase (not held by an intact joint), and the
  /// features of their blocks in the current configuration (a block is in about six pairs: its
  /// vertex shapes, legs and edges are computed once for all).
  BlockPairs narrow_pairs;
  std::vector<char> needs_features;
  std::vector<PolygonFeatures> block_features;

  /// Rebuilds `exclusions` if the joints changed since.
  void refresh_exclusions(const DetectionInput& in);
  /// The vertices tied by an intact joint to another block, (block, vertex, other block)
  /// sorted, into `jointed_vertices`: they make no contact with that block.
  void mark_jointed_vertices(const DetectionInput& in);
  bool jointed(std::size_t block, std::size_t vertex, std::size_t other) const;
  /// Whether vertex va of block a and vertex vb of block b are both tied by intact joints to a
  /// common third block (which keeps the two corners apart).
  bool held_by_common_block(std::size_t a, std::size_t va, std::size_t b, std::size_t vb) const;
  /// detect's narrow phase proper, after the jointed vertices are marked.
  BlockPairs find_trial_contacts(const DetectionInput& in, const BlockPairs& pairs,
                                 const Parallel& parallel);
  /// The contacts of candidate pair (a, b), a < b, not held by an intact joint, appended to
  /// `chunk.found` (in key order); block_features holds both blocks' features.
  void add_pair_contacts(const DetectionInput& in, std::size_t a, std::size_t b,
                         NarrowPhaseChunk& chunk) const;
  /// Trial contact k's springs K2 [N/m] and force on its vertex [N] (minus on its edge).
  void spring(std::size_t k, const StepDashpots& dashpots, Eigen::Matrix2d& k2,
              Vector2& force_on_vertex) const;
  /// A trial contact's dashpot C [N s/m] over this step, and its terms in k2 and the force on
  /// the vertex.
  Eigen::Matrix2d dashpot(const Contact& c, const ContactFrame& f,
                          const StepDashpots& dashpots) const;
  void add_dashpot(const Contact& c, const ContactFrame& f, const StepDashpots& dashpots,
                   Eigen::Matrix2d& k2, Vector2& force_on_vertex) const;
  /// Of trial contact k [N] (evaluate_contact), at the end velocity of `solution`.
  double viscous_shear(std::size_t k, const StepDashpots& dashpots,
                       const Eigen::VectorXd& solution) const;
  /// Per block and per coupling the trial contacts on it, once per attempt.
  void index_terms(std::size_t n_blocks, std::size_t n_couplings);
  /// Contact k's trial (update_trial_states, on the threads); a change that holds the iteration
  /// back counts in n[0], one that does not in n[1].
  void update_trial_state(std::size_t k, const TrialInput& in, double negligible,
                          std::array<std::size_t, 2>& n);
  /// Index in `accepted` of c's predecessor, or `none`; `at` is the first accepted contact
  /// whose key is not below c's.
  std::size_t find_predecessor(const Contact& c, std::vector<Contact>::const_iterator at,
                               std::size_t none) const;
  /// c's state from the accepted contact `previous` (or a new contact's first state and id
  /// `no_id` if `previous` is null), with a raised penalty.
  void inherit_state(Contact& c, const Contact* previous, std::size_t no_id) const;
};

} // namespace ddafem::dda
