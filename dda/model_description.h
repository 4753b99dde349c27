// Input of a DDA model, as read from a scene: plain data, validated by the scene reader.
#pragma once

#include "common/elasticity.h"
#include "common/time_function.h"
#include "common/wave_type.h"
#include "dda/damping.h"
#include "dda/grouted_bolt.h"
#include "dda/integrator.h"
#include "dda/types.h"

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace ddafem::dda
{
/// 2D idealisation of the blocks' elasticity (common/elasticity.h).
using PlaneMode = ddafem::PlaneMode;

/// Which configuration each step is linearised about.
enum class GeometryMode
{
  /// Shi's DDA: vertices, centroids and moments move every step and every submatrix is
  /// recomputed from them (needed for large displacements, rotations and contacts).
  updated,
  /// Linear analysis about the initial configuration: T(x), the mass matrix and the joint
  /// directions stay those of t = 0, so the step matrix is assembled and factorized once for a
  /// fixed dt. Output positions still move. Valid while displacements and rotations are small
  /// against the block size (waves); cheaper by the assembly and refinement costs.
  small_displacement
};

constexpr std::array<EnumName<GeometryMode>, 2> enum_names(GeometryMode)
{
  return {{{GeometryMode::updated, "updated"},
           {GeometryMode::small_displacement, "small_displacement"}}};
}

/// Linear elastic, isotropic block material.
struct Material
{
  std::string name;
  double density = 0.0;        ///< rho [kg/m^3], > 0
  double youngs_modulus = 0.0; ///< E [Pa], > 0
  double poisson_ratio = 0.0;  ///< nu [-], in [0, 0.5)
  RockDamping damping = {};    ///< dashpots on the block's strain rates (dda/damping.h)
};

/// Properties of the joints (contacts) between blocks.
struct JointMaterial
{
  std::string name;
  double normal_stiffness = 0.0; ///< penalty spring p [N/m] at each contact point, > 0
  double shear_ratio = 0.4;      ///< shear spring / normal spring [-] (Shi: 1/2.5)
  double friction_angle = 0.0;   ///< phi [degrees], in [0, 90)
  double cohesion = 0.0;         ///< c [Pa], >= 0
  double tensile_strength = 0.0; ///< [Pa], >= 0
  /// true: joints along shared edges are glued springs until their strength is exceeded, then
  /// frictional contacts; false: every contact is a frictional contact from the start (with
  /// cohesion and tensile strength until it first slides or opens)
  bool bonded = true;
  /// Dashpots beside the bonded joints' springs and the closed contacts' normal (and, while
  /// they stick, shear) springs, from normal_stiffness and shear_ratio (dda/damping.h)
  RockDamping damping = {};
};

/// Which joint material applies between blocks of two given materials.
struct JointAssignment
{
  std::size_t material_a = 0; ///< index into ModelDescription::materials
  std::size_t material_b = 0;
  std::size_t joint_material = 0; ///< index into ModelDescription::joint_materials
};

/// One block: a simple polygon, anticlockwise, not closed (the last vertex is not repeated).
struct BlockDescription
{
  std::vector<Point> vertices;                ///< [m]
  std::size_t material = 0;                   ///< index into ModelDescription::materials
  Vector2 initial_velocity = Vector2::Zero(); ///< translational velocity at t = 0 [m/s]
  Voigt initial_stress = Voigt::Zero();       ///< (sxx, syy, sxy) [Pa], tension positive
  std::string origin;                         ///< where it came from, for messages ("blocks[3]")
  /// Empty, or one entry per edge (edge k runs from vertex k to vertex k + 1): the joint
  /// material of the joints and contacts along that edge (an index into
  /// ModelDescription::joint_materials), e.g. that of the joint set whose trace cut it; none:
  /// the one that applies to the two blocks' materials (joint_material_for).
  std::vector<std::optional<std::size_t>> edge_joint_materials;
};

/// A force applied at a material point of the block that contains it: F(t) = force * f(t).
struct PointLoad
{
  Point point = Point::Zero();     ///< [m], inside or on the boundary of exactly one block
  Vector2 force = Vector2::Zero(); ///< [N]
  TimeFunction time_function;
  std::string origin;
};

/// A material point tied by a stiff penalty spring to its initial position plus an optional
/// prescribed displacement (ux(t), uy(t)) [m] (for a moving rigid base).
struct FixedPoint
{
  Point point = Point::Zero(); ///< [m]
  double stiffness = 0.0;      ///< penalty spring [N/m]; 0 selects the default (see System)
  TimeFunction displacement_x = TimeFunction::constant(0.0);
  TimeFunction displacement_y = TimeFunction::constant(0.0);
  std::string origin;
};

/// An end-anchored rock bolt (dda/bolt.h): a steel tendon attached to the block containing
/// `head` and to the (other) block containing `anchor`, an axial spring between them.
struct BoltDescription
{
  std::string name;              ///< for outputs; unique
  Point head = Point::Zero();    ///< [m]
  Point anchor = Point::Zero();  ///< [m], in another block than the head
  double area = 0.0;             ///< steel cross-section A_s [m^2], > 0
  double youngs_modulus = 200e9; ///< E_s [Pa], > 0
  double yield_force = 0.0;      ///< [N], > 0
  double rupture_strain = 0.1;   ///< total elongation over L0 at which it breaks [-], > 0
  double pretension = 0.0;       ///< force at L = L0 as installed [N], in [0, yield_force)
  std::string origin;            ///< for messages, e.g. "bolts[0]"
  /// Grouted bolts (dda/grouted_bolt.h): bonded along their length, a spring at each crossing.
  BoltType type = BoltType::end_anchored;
  double grout_modulus = 10e9;         ///< foundation modulus K of grout and rock [Pa] (dowel)
  double debonded_length = 0.3;        ///< L_d: the bar's deformable length at a joint [m]
  double shear_capacity = 0.0;         ///< dowel capacity S_y [N], > 0
  std::vector<BoltCrossing> crossings; ///< found at t = 0 by the scene reader, from the head
};

/// A lining (dda/lining.h): frame elements between nodes along a polyline on the blocks'
/// surfaces, each node a material point of the block it lies on.
struct LiningDescription
{
  std::string name;                  ///< for outputs; unique
  std::vector<Point> points;         ///< the polyline [m], each node on or inside a block
  bool closed = false;               ///< the last point joins the first (a ring)
  double segment_length = 0.0;       ///< largest element length [m], > 0
  double thickness = 0.0;            ///< [m], > 0
  double youngs_modulus = 30e9;      ///< [Pa], > 0 (shotcrete or concrete)
  double compressive_strength = 0.0; ///< [Pa], > 0
  double tensile_strength = 0.0;     ///< [Pa], > 0
  double shear_strength = 0.0;       ///< [Pa]; 0: not checked
  /// Installed at the start of this stage (index into `stages`; 0: from the start).
  std::size_t install_stage = 0;
  std::string origin; ///< for messages, e.g. "linings[0]"
};

/// A measurement point: the history of the material point and of its block's stress.
struct Monitor
{
  std::string name;
  Point point = Point::Zero(); ///< [m], inside exactly one block
};

/// Treatment of the selected block edges (docs/reference/physics.md section 3).
enum class BoundaryType
{
  free,   ///< nothing: a traction-free edge (kept so that scenes can switch type with --set)
  vb1,    ///< Bao, Hatzor & Huang (2012) eq. 39: K += T^T R^T (C D / dt - C^2 / m) R T
  vb2,    ///< Jiao et al. (2007), eq. 40: K += (2 / dt) T^T R^T C R T
  dashpot ///< the consistent dashpot: the force -C v1 with the integrator's end-of-step velocity
};

constexpr std::array<EnumName<BoundaryType>, 4> enum_names(BoundaryType)
{
  return {{{BoundaryType::free, "free"},
           {BoundaryType::vb1, "vb1"},
           {BoundaryType::vb2, "vb2"},
           {BoundaryType::dashpot, "dashpot"}}};
}

/// Which wave speeds set the dashpot coefficients cn = a_n rho l0 VP, ct = a_t rho l0 VS.
enum class ImpedanceKind
{
  /// VP = sqrt(E (1-nu) / (rho (1+nu)(1-2nu))), VS = sqrt(E / (2 rho (1+nu)))
  /// (docs/reference/physics.md)
  textbook,
  /// The speeds the model actually carries across the boundary block: its P modulus (E for a
  /// plane-stress block whose side edges are free, E / (1-nu^2) in plane stress otherwise,
  /// lambda + 2 mu in plane strain) and G, each in series with the compliance of the joint
  /// behind the block (two springs per joint length) over the block's depth.
  effective
};

constexpr std::array<EnumName<ImpedanceKind>, 2> enum_names(ImpedanceKind)
{
  return {{{ImpedanceKind::textbook, "textbook"}, {ImpedanceKind::effective, "effective"}}};
}

/// An incident plane wave entering through a viscous boundary (Joyner & Chen 1975): the wave
/// travels up (+y) with particle velocity v_in(t) times (0, 1) for P and (1, 0) for SV, and
/// the boundary's edges receive the input force 2 C v_in, C = cn n n^T + ct t t^T their own
/// dashpots (on a horizontal base: 2 cn v_in up for P, 2 ct v_in along x for SV).
struct BoundaryInput
{
  using Type = WaveType; ///< p: vertical particle motion, sv: horizontal
  Type type = Type::sv;
  TimeFunction velocity = TimeFunction::constant(0.0); ///< v_in(t) [m/s]
};

/// An absorbing (or free) boundary: a type and the block edges it applies to. Exactly one
/// selector is used: explicit edges, every outer edge on a line, or every outer edge.
struct BoundaryDescription
{
  BoundaryType type = BoundaryType::free;
  ImpedanceKind impedance = ImpedanceKind::textbook;
  double a_n = 1.0; ///< normal coefficient [-]
  double a_t = 1.0; ///< tangential coefficient [-]
  /// Explicit edges: (block index, edge index), edge k runs from vertex k to vertex k + 1.
  std::vector<std::pair<std::size_t, std::size_t>> edges;
  bool on_line = false;             ///< select outer edges lying on the line below
  Point line_point = Point::Zero(); ///< a point of the line [m]
  Vector2 line_direction = Vector2(0.0, 1.0);
  bool outer = false;     ///< select every outer edge (not shared by a joint)
  bool has_input = false; ///< an incident wave enters through the edges (dynamic stages only)
  BoundaryInput input;
  std::string origin; ///< for messages, e.g. "boundaries[0]"
};

/// The in-situ (initial) stress of the rock mass: sigma0(y) = stress + stress_gradient (y -
/// reference_y) [Pa], (sxx, syy, sxy), tension positive. Blocks without an explicit initial
/// stress start with sigma0 at their centroid; bonded joints, ties to a far field and the static
/// supports of viscous boundaries carry the traction sigma0 n it puts across them.
struct InSituStress
{
  Voigt stress = Voigt::Zero();   ///< at reference_y [Pa]
  Voigt gradient = Voigt::Zero(); ///< d sigma0 / dy [Pa/m]
  double reference_y = 0.0;       ///< [m]

  Voigt at(const Point& p) const { return stress + gradient * (p.y() - reference_y); }
  /// The traction sigma0 n [Pa] on a surface of outward unit normal n at p: the force per unit
  /// length the surrounding rock puts on the body whose normal it is.
  Vector2 traction(const Point& p, const Vector2& n) const
  {
    const Voigt s = at(p);
    return Vector2(s[0] * n.x() + s[2] * n.y(), s[2] * n.x() + s[1] * n.y());
  }
};

/// Sparse direct solver for the step's symmetric positive definite system.
enum class SolverKind
{
  eigen_ldlt, ///< Eigen SimplicialLDLT (sparse Cholesky, AMD ordering)
  klu,        ///< SuiteSparse KLU (sparse LU)
  /// Sparse Cholesky on the 6x6 block structure (AMD ordering of the block graph, fixed-size
  /// dense block kernels); the fastest for DDA's block-sparse matrices
  block_ldlt
};

constexpr std::array<EnumName<SolverKind>, 3> enum_names(SolverKind)
{
  return {{{SolverKind::block_ldlt, "block_ldlt"},
           {SolverKind::eigen_ldlt, "eigen_ldlt"},
           {SolverKind::klu, "klu"}}};
}

/// How each step's system is solved.
enum class SolverMethod
{
  /// The sparse direct solver, its factors reused as a CG preconditioner while they serve
  /// (FactorizationReusingSolver)
  direct,
  /// Conjugate gradients preconditioned by the 6x6 diagonal blocks, warm-started from the
  /// last solution, no factorization; the direct solver when it does not converge
  block_pcg
};

constexpr std::array<EnumName<SolverMethod>, 2> enum_names(SolverMethod)
{
  return {{{SolverMethod::direct, "direct"}, {SolverMethod::block_pcg, "block_pcg"}}};
}

/// The step's linear solver.
struct SolverSettings
{
  SolverKind direct = SolverKind::block_ldlt; ///< also block_pcg's fallback
  SolverMethod method = SolverMethod::direct;
  /// block_pcg: relative residual in the block-diagonal norm at which it stops
  double tolerance = 1e-10;
  /// block_pcg: iterations before it falls back to the direct solver
  unsigned max_iterations = 200;
  /// Threads of contact detection and block_pcg (`ddafem run --threads`, not a scene key; 0:
  /// all cores). The results do not depend on it.
  unsigned threads = 1;
};

/// How the time step is chosen.
enum class TimeControl
{
  /// dt starts at TimeSettings::dt (its upper bound) and is cut when a step fails (open-close
  /// iteration not converged, a vertex moving more than the allowed step displacement, too deep
  /// a penetration), then grows back gradually
  adaptive,
  /// every step has dt; a step that would need a cut stops the run (wave problems)
  fixed
};

constexpr std::array<EnumName<TimeControl>, 2> enum_names(TimeControl)
{
  return {{{TimeControl::adaptive, "adaptive"}, {TimeControl::fixed, "fixed"}}};
}

struct TimeSettings
{
  double dt = 0.0;       ///< time step [s], > 0; the largest one with adaptive control
  double end_time = 0.0; ///< [s], >= dt
  Integrator integrator = Integrator::bathe;
  /// generalized_alpha: the spectral radius at infinite frequency rho_inf [-] in [0, 1] (1: no
  /// algorithmic damping; smaller damps stiff contact modes faster)
  double spectral_radius = 0.2;
  TimeControl control = TimeControl::adaptive;
  double dt_min = 0.0;        ///< smallest dt before the run stops [s]; 0: dt * 1e-4
  double cut_factor = 0.3;    ///< dt multiplier after a failed step (Shi: 0.3)
  double growth_factor = 1.2; ///< dt multiplier after a successful step, up to `dt`
  /// Adaptive control: the slip error [m] that a slip reversal within a step may leave, where
  /// the step's friction acted the wrong way for part of it (slip_error); a step with a larger
  /// one is redone to end just before the reversal (TimeStepper), and with generalized-alpha a
  /// slide of at least 10 steps whose friction turns around restarts it at the jump
  /// (System::restart_at_friction_jumps). 1e-6 (the default) makes two-way sliding exact; 0: no
  /// localisation (docs/design.md, Integrators).
  double reversal_tolerance = 1e-6;
};

/// Settings of contact detection and of the open-close iteration (Shi 1988, ch. 4).
struct ContactSettings
{
  /// Shi's g2: the largest vertex displacement allowed in one step, over half the model's size
  /// w0 [-]. A step beyond it is cut (adaptive control).
  double max_displacement_ratio = 0.01;
  /// Search distance d0 [m] of the narrow phase; 0: 2.5 g2 w0 (twice and a half the largest
  /// step displacement, so that no vertex crosses an edge unseen).
  double search_distance = 0.0;
  /// Largest penetration a converged step may leave [m]; 0: g2 w0 (the step displacement bound).
  double max_penetration = 0.0;
  unsigned max_open_close_iterations = 6; ///< Shi: 6, then the step is cut
  /// A contact that penetrates deeper than max_penetration has its penalty (normal and shear
  /// springs) raised x 10 and the step redone (ntdda), up to this multiple of the joint
  /// material's stiffness [-]; beyond it the step is cut.
  double max_penalty_factor = 100.0;
  /// From the third open-close iteration on, a contact whose forces before and after a state
  /// change stay below this fraction of the largest contact normal force of the step [-]
  /// changes without holding the iteration back (it carries almost nothing in either state, and
  /// would flip between slide and lock without end).
  double flip_force_ratio = 1e-3;
  double angle_tolerance_deg = 1.0; ///< parallel edges and straight vertices within this [deg]
};

/// Whether a stage integrates the motion or seeks static equilibrium.
enum class StageMode
{
  /// Shi's static analysis: velocities are reset to zero before each step, so each step moves
  /// the blocks towards equilibrium under the loads; the clock does not advance
  static_equilibrium,
  dynamic ///< the motion in time
};

constexpr std::array<EnumName<StageMode>, 2> enum_names(StageMode)
{
  return {{{StageMode::static_equilibrium, "static"}, {StageMode::dynamic, "dynamic"}}};
}

/// stages[i].mode of a dynamic stage that ends when every block is at rest (Stage::settle).
constexpr const char* settle_mode_name = "settle";

/// What a static stage does with a block it releases (one that cannot be in equilibrium, see
/// ReleaseCriterion in dda/static_stage.h).
enum class ReleaseAction
{
  /// Held where it was released for the rest of the static stage (System::hold_block), free in
  /// the dynamic stage that follows: it falls or slides onto whatever is below.
  fall,
  /// Inert for the rest of the run (System::remove_block): held, no joints, no contacts.
  remove
};

constexpr std::array<EnumName<ReleaseAction>, 2> enum_names(ReleaseAction)
{
  return {{{ReleaseAction::fall, "fall"}, {ReleaseAction::remove, "remove"}}};
}

/// When a settle stage (a dynamic stage without a fixed end, Stage::settle) ends: every block
/// is at rest or has fallen (dda/settle_stage.h).
struct SettleCriterion
{
  /// A block is at rest while the largest speed of its vertices is at most this [m/s] ...
  double rest_speed = 1e-3;
  /// ... for this long without a break [s].
  double rest_duration = 0.1;
  /// A block has fallen once its centroid moved this far along gravity from where the first
  /// dynamic stage found it [m]; 0: none counts as fallen, every block must come to rest.
  double fall_distance = 0.0;
  /// The stage ends after this long even if blocks still move [s] (a result, not a failure).
  double max_duration = 2.0;
  /// Fallen blocks that have left their place (no part of the block is still where it was when
  /// the first dynamic stage began, SettleDetector::out_of_place) are removed as debris
  /// (System::remove_block): their tumble on the floor of the opening is not followed, neither
  /// its steps nor its impacts on the blocks still standing. Needs fall_distance > 0.
  bool remove_fallen = false;
};

/// A stage of the analysis. Stages run in sequence; each starts from the state the previous one
/// left (a dynamic stage after a static one starts from the equilibrium, at rest, at t = 0).
struct Stage
{
  std::string name;
  StageMode mode = StageMode::dynamic;
  /// Time step [s] of a static stage (0: TimeSettings::dt). Dynamic stages use TimeSettings.
  double dt = 0.0;
  double end_time = 0.0;         ///< dynamic: the time it runs to [s]
  std::size_t max_steps = 10000; ///< static: stop (failed) after this many steps
  /// static: equilibrium when every block's out-of-balance force falls below tolerance x its
  /// own load (StepStatus::unbalanced_force_ratio, BlockBalance), released blocks excepted
  double tolerance = 1e-5;
  ReleaseAction release = ReleaseAction::fall; ///< static: what becomes of released blocks
  /// dynamic: a settle stage (YAML `mode: settle`), which runs from where the previous stage
  /// ended until every block is at rest or has fallen, at most settle->max_duration; end_time
  /// is then not used.
  std::optional<SettleCriterion> settle;
};

/// Everything the DDA engine needs to build and run a model.
struct ModelDescription
{
  PlaneMode plane_mode = PlaneMode::stress;
  GeometryMode geometry = GeometryMode::updated;
  std::vector<Material> materials;
  std::vector<JointMaterial> joint_materials;
  /// Joint material for block pairs not named in joint_assignments; npos if none given (then
  /// blocks sharing an edge are an error).
  std::size_t default_joint_material = static_cast<std::size_t>(-1);
  std::vector<JointAssignment> joint_assignments;
  std::vector<BlockDescription> blocks;
  std::vector<PointLoad> point_loads;
  std::vector<FixedPoint> fixed_points;
  std::vector<BoltDescription> bolts;
  std::vector<LiningDescription> linings;
  std::vector<Monitor> monitors;
  std::vector<BoundaryDescription> boundaries;
  Vector2 gravity = Vector2::Zero(); ///< body acceleration [m/s^2], e.g. (0, -9.81)
  InSituStress in_situ_stress;       ///< zero unless the scene gives one
  TimeSettings time;
  ContactSettings contacts;
  /// The stages in order; empty: one dynamic stage up to time.end_time.
  std::vector<Stage> stages;
  SolverSettings solver;
};

} // namespace ddafem::dda
