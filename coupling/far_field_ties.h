// Ties between the DDA region's outer block edges and the deal.II far field around it (issue 6):
// one implicit system per step, the far field condensed onto the tie points.
#pragma once

#include "common/checkpoint_fwd.h"
#include "common/recent_cache.h"
#include "dda/contact/contact_law.h"
#include "dda/system.h"
#include "dda/tied_body.h"
#include "fem/point_spring_field.h"

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace ddafem::coupling
{
/// How the blocks are tied to the far field.
struct InterfaceDescription
{
  fem::BoundaryPart part = fem::BoundaryPart::hole; ///< the far field's part the blocks fill
  /// Normal spring of a tied edge end [N/m], as a bonded joint's (Shi): an edge's tie points
  /// share 2 p by their Gauss weights.
  double normal_stiffness = 0.0;
  double shear_ratio = 0.4; ///< p_s / p [-]
  /// Mohr-Coulomb strength of the ties: cohesion and tensile strength [Pa] on each tie's share
  /// of the edge, friction angle [deg]. Infinite strength (the default): the ties never open
  /// or slide and the interface is linear.
  double cohesion = std::numeric_limits<double>::infinity();
  double tensile_strength = std::numeric_limits<double>::infinity();
  double friction_angle = 0.0;
  /// Gauss points per piece of a tied edge between far-field face ends (3: exact for the tie
  /// energy of a block edge against degree-2 faces).
  unsigned points_per_face = 3;
  /// Largest distance [m] of a tied block edge from the part; 0: 1e-6 of the model size.
  double tolerance = 0.0;
};

/// Number of ties in each state.
struct TieCounts
{
  std::size_t intact = 0; ///< locked with cohesion and tensile strength
  std::size_t lock = 0;   ///< locked, strength lost (residual friction)
  std::size_t slide = 0;
  std::size_t open = 0;
};

/// One tie: a Gauss point of a block edge on the far field's part (composite quadrature over the
/// pieces of the edge between the far-field face ends).
struct Tie
{
  std::size_t block = 0;
  dda::Point point = dda::Point::Zero();       ///< at t = 0 [m]
  dda::Vector2 normal = dda::Vector2::Zero();  ///< out of the block, into the far field
  dda::Vector2 tangent = dda::Vector2::Zero(); ///< normal rotated by +90 deg
  double length = 0.0;                         ///< the share of the edge the tie carries [m]
  dda::ContactLaw law;
  /// Accepted forces of the spring (without the preload, see FarFieldTies::total_force):
  /// normal_force compression positive; shear_force S acts on the block as -S t and on the far
  /// field as +S t (the block is the contact's vertex side).
  dda::ContactForces forces;
  dda::ContactForces trial;
  /// r = z - w: the block point's displacement minus the far field's at the tie [m], at the end
  /// of the last accepted step (the tie's elastic stretch plus any slip or opening).
  dda::Vector2 stretch = dda::Vector2::Zero();
};

/// The far field as a dda::TiedBody. With K the ties' bonded springs, P = A + N^T K N the far
/// field's effective matrix with the ties (factorized once), G = N P^-1 N^T (2m x 2m, 2m solves
/// per dt), w0 = N P^-1 f (one solve per step): in the ties' trial states (springs K', forces
/// F0, dK = K' - K) the far field's tie displacements are w = R w0 + M (K' z + F0) with
/// R = (I + G dK)^-1, M = R G, z the blocks' tie displacements; the ties' force on the far
/// field is F = K' (z - w) + F0 and on the blocks -F, which gives TiedBody's H and g. Bonded
/// ties (dK = 0) need no dense solve; a state change costs one dense LU of 2m x 2m.
///
/// Preloads (a perturbation decomposition, exact for the linear far field): each tie also puts
/// a constant force P_k on its block, sigma0(x_k) n_k times its share of the edge (the in-situ
/// stress's traction across the interface), and the far field carries only the increment: no
/// gravity, no in-situ stress. In a static stage the far field is held (w = 0: the ties are
/// springs to fixed ground, H = K, g = P - K c, no far-field solve); when the dynamic stage
/// starts, P - K z (each tie's whole force on its block) becomes the new P, z restarts at 0
/// and the far field at rest. Preloads require a linear interface (the scene reader refuses a
/// frictional one with in-situ stress or stages). See coupling/README.md.
class FarFieldTies final : public dda::TiedBody
{
public:
  /// Finds the block edges on the part, places the ties, attaches the springs to the far field
  /// and ties the points to the system. Throws InputError if the blocks do not fill the part.
  FarFieldTies(dda::System& system, fem::PointSpringField& far_field,
               const InterfaceDescription& description);

  void begin_stage(dda::StageMode mode) override;
  bool begins_step_on_any_thread() const override { return far_field.steps_on_any_thread(); }
  /// Held (static stage): H = K, one 2 x 2 spring per tie.
  bool stiffness_is_block_diagonal() const override { return held; }
  StepResult begin_step(double dt, const Eigen::VectorXd& displacements) override;
  const Eigen::MatrixXd& stiffness() const override { return *h; }
  /// Every tie bonded, the far field free: H is the condensation's for this dt, named by dt's
  /// bits.
  std::optional<std::uint64_t> stiffness_id() const override;
  const Eigen::VectorXd& force() const override { return g; }
  std::size_t update_trial_states(const Eigen::VectorXd& delta, unsigned iteration,
                                  double negligible, std::size_t& n_ignored) override;
  StepResult end_step(const Eigen::VectorXd& delta) override;
  double work_on_blocks() const override { return work_blocks; }

  std::size_t n_ties() const { return ties.size(); }
  std::size_t n_tied_edges() const { return tied_edges; }
  std::size_t n_tied_blocks() const;
  double tied_length() const { return length_tied; }    ///< [m]
  double part_length() const { return length_of_part; } ///< [m]
  const std::vector<Tie>& get_ties() const { return ties; }
  TieCounts counts() const;

  /// Checkpoints (coupling/ties_checkpoint.cc), between two steps; the far field is saved on
  /// its own.
  void save(CheckpointOut& archive) const;
  void load(CheckpointIn& archive);
  /// Work of the ties on the far field since t = 0 [J] (the energy that crossed into it).
  double work_on_far_field() const;
  /// Work of the preloads on the blocks [J] (part of work_on_blocks): a dead load standing for
  /// the far field's in-situ stress, which the far field does not model.
  double work_of_preloads() const { return work_preloads; }
  /// Energy held or dissipated by the tie springs: -(work on blocks without the preloads' +
  /// work on far field) [J].
  double tie_energy() const { return -(work_blocks - work_preloads + work_on_far_field()); }
  /// The ties' preloads P on the blocks (x, y per tie) [N].
  const Eigen::VectorXd& preloads() const { return preload; }
  /// Tie k's whole force on the far field's side [N]: its spring's minus its preload (which
  /// acts on the block), i.e. minus the whole force on the block.
  dda::Vector2 total_force(std::size_t k) const;
  /// Wall time [s]: G (once per dt), the tie algebra of the steps (H, g, states).
  double condensation_seconds() const { return time_condensation; }
  double tie_seconds() const { return time_ties; }
  /// Condensations G built (one per dt kept, rebuilds after the cache dropped one too).
  std::size_t n_condensations() const { return condensation_count; }

private:
  /// Ties along block `block`'s edge from a to b [m] (anticlockwise), lying on the far field's
  /// part: one per Gauss point of each piece between the part's face ends, appended to `ties`
  /// with the far field's spring at it (`springs`) and the block's material point (`points`).
  void tie_edge(std::size_t block, const dda::Point& a, const dda::Point& b,
                const std::vector<std::array<double, 4>>& segments, const InterfaceDescription& d,
                double tolerance, std::vector<fem::PointSpring>& springs,
                std::vector<dda::MaterialPoint>& points);
  /// K from the far field's springs, zero start forces and the in-situ stress's preloads P
  /// (InputError for a frictional interface with preloads).
  void set_bonded_state(const dda::ModelDescription& model,
                        const std::vector<fem::PointSpring>& springs);
  /// K', F0, R w0, M, H and g from the trial states.
  void build_terms();
  /// Accepts tie k's trial state with its stretch z - w [m] and spring force F on the far field
  /// [N].
  void set_accepted_forces(std::size_t k, const dda::Vector2& stretch,
                           const dda::Vector2& spring_force);
  /// K x [N], tie by tie (K is block diagonal).
  Eigen::VectorXd bonded_springs(const Eigen::VectorXd& x) const;
  /// w = R w0 + M (K' z + F0).
  Eigen::VectorXd far_field_displacements(const Eigen::VectorXd& z) const;

  template <class Archive>
  void transfer_state(Archive& archive);

  fem::PointSpringField& far_field;
  std::vector<Tie> ties;
  std::size_t tied_edges = 0;
  double length_tied = 0.0, length_of_part = 0.0;
  bool linear = true; ///< infinite strength: no state changes

  Eigen::MatrixXd k_bonded; ///< K, block diagonal (2 x 2 per tie) [N/m]
  /// The far field condensed onto the ties for one dt: coupled runs that cut dt step on levels
  /// dt_max / 2^k and come back, so the last few are kept (most recently used first), each
  /// (2m)^2 doubles twice.
  struct Condensation
  {
    Eigen::MatrixXd flexibility; ///< G [m/N]
    Eigen::MatrixXd bonded_h;    ///< H with every tie bonded, K - K G K [N/m]
  };
  ddafem::RecentCache<double, Condensation> condensations{16}; ///< by dt [s]
  /// Makes the condensation for dt the current one (the first of condensations), building it
  /// on first use.
  void select_condensation(double dt);
  const Eigen::MatrixXd& flexibility() const { return condensations.front().flexibility; }

  // The step in progress.
  Eigen::VectorXd w0;      ///< free far-field displacements at the ties [m]
  Eigen::VectorXd start;   ///< c: the blocks' tie displacements at the step start [m]
  Eigen::MatrixXd k_trial; ///< K' [N/m]
  Eigen::VectorXd f_trial; ///< F0 [N]
  Eigen::VectorXd r_w0;    ///< R w0 [m]
  /// M = R G [m/N] and H = K' - K' M K' [N/m]: the current condensation's G and all-bonded H
  /// while every tie is bonded (no copy of these (2m)^2 matrices per step), else m_trial and
  /// h_trial; K while the far field is held.
  const Eigen::MatrixXd* m_matrix = nullptr;
  const Eigen::MatrixXd* h = nullptr;
  Eigen::MatrixXd m_trial, h_trial;
  Eigen::VectorXd g;               ///< [N]
  bool bonded_terms_valid = false; ///< h holds the current condensation's all-bonded H

  /// The bonded chain: with every tie bonded, a step's H z0 = K z0 - K G K z0 needs G K z0 for
  /// the tie displacements z0 at its start. The last accepted step ended at z0 = its own z, and
  /// its far field moved the ties by G K z from their free displacements w0 (w = w0 + G q,
  /// q = K z): G K z0 = w - w0, read off the far field (N u) instead of two dense products of
  /// (2m)^2 per step. The steps of one dt that follow each other take the chain.
  struct BondedChain
  {
    bool valid = false;
    double dt = 0.0;       ///< of the step that left it [s]
    Eigen::VectorXd z;     ///< tie displacements at its end [m]
    Eigen::VectorXd g_k_z; ///< G K z = w - w0 [m]
  };
  BondedChain chain;
  double step_dt = 0.0; ///< of the step in progress [s]
  /// Whether the step in progress is bonded and linear on the current condensation (no dense
  /// terms of a trial state).
  bool bonded_step() const { return linear && !held && bonded_terms_valid; }
  /// H c for the step's start c: on the chain, without the dense product (and c := the chain's
  /// z).
  Eigen::VectorXd h_times_start();
  /// end_step of a bonded linear step: the far field first (q = K z needs no w), then w = N u.
  StepResult end_bonded_step(const Eigen::VectorXd& z, const Eigen::VectorXd& delta);
  Eigen::VectorXd preload;      ///< P: constant forces on the blocks (x, y per tie) [N]
  bool held = false;            ///< static stage: the far field is held, the ties are fixed springs
  bool dynamic_started = false; ///< the far field has taken a step
  Eigen::VectorXd previous_force; ///< F on the far field (spring part) at the step start [N]
  double work_blocks = 0.0;
  double work_preloads = 0.0;
  double time_condensation = 0.0, time_ties = 0.0;
  std::size_t condensation_count = 0;
};

} // namespace ddafem::coupling
