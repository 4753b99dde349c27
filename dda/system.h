// The DDA model in time: blocks, joints, loads and the implicit step.
#pragma once

#include "dda/block.h"
#include "dda/joints.h"
#include "dda/linear_solver.h"
#include "dda/model_description.h"
#include "dda/snapshot.h"
#include "dda/viscous_boundary.h"

#include <Eigen/Core>

#include <cstddef>
#include <string>
#include <vector>

namespace ddafem::dda
{
/// Energies of the model [J]. Conservation: kinetic + strain + spring = initial +
/// work_of_loads + work_of_supports + work_of_boundaries - dissipated, where `dissipated` is
/// the residual: the algorithmic damping of the integrator (zero for trapezoidal Newmark on a
/// linear model).
struct EnergyBalance
{
  double kinetic = 0.0;          ///< sum of v^T M v / 2
  double strain = 0.0;           ///< block elastic energy, sum of area sigma^T C^-1 sigma / 2
  double spring = 0.0;           ///< joint springs and fixed-point penalty springs
  double work_of_loads = 0.0;    ///< point loads and gravity, since t = 0
  double work_of_supports = 0.0; ///< done by prescribed motions of fixed points, since t = 0
  /// Done by the viscous boundaries on the blocks since t = 0: negative when they absorb.
  double work_of_boundaries = 0.0;
  double initial = 0.0;    ///< kinetic + strain + spring at t = 0
  double dissipated = 0.0; ///< initial + works - (kinetic + strain + spring)

  double stored() const { return kinetic + strain + spring; }
};

/// What a step did. The caller acts on failures (stop, or cut the step in later issues).
enum class StepOutcome
{
  success,
  solver_failure, ///< singular / indefinite matrix, or NaN in the solution
  joint_broken,   ///< a bonded joint exceeded its strength (contact mechanics: issue 4)
  energy_growth   ///< stored energy exceeds 10x the energy put in: something feeds the model
};

struct StepStatus
{
  StepOutcome outcome = StepOutcome::success;
  std::string message; ///< why it failed, with the time reached
  SolveStatus solve;
};

/// Wall time spent in each phase of the step since construction [s].
struct PhaseTimings
{
  double assemble = 0.0;
  double solve = 0.0;
  double update = 0.0;
  std::size_t n_steps = 0;
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
/// (K + M / (beta dt^2)) d = f + M (v0 / (beta dt) + (1 / (2 beta) - 1) a0),
/// Newmark with (beta, gamma) = (1/2, 1) for DDA's scheme or (1/4, 1/2) for the trapezoidal rule.
/// With GeometryMode::updated (Shi) every step is linearised about the current vertices, moments
/// and material points; with small_displacement about the initial ones.
class System
{
public:
  /// Builds blocks, finds joints, attaches loads, fixed points and monitors to their blocks.
  /// Throws InputError for what the scene reader cannot see (blocks sharing an edge with no joint
  /// material, a frictional joint material, a point outside every block).
  explicit System(const ModelDescription& model);

  /// Advances by dt [s]: assemble, solve, update blocks, check joint strength.
  StepStatus advance(double dt);

  double time() const { return current_time; }
  std::size_t n_steps() const { return timings.n_steps; }
  std::size_t n_dofs() const { return 6 * blocks.size(); }
  const std::vector<Block>& get_blocks() const { return blocks; }
  const std::vector<Joint>& get_joints() const { return joints; }
  const ModelDescription& get_model() const { return model; }
  const PhaseTimings& get_timings() const { return timings; }
  const FactorizationReusingSolver& get_solver() const { return solver; }
  const std::vector<BoundaryEdge>& get_boundary_edges() const { return boundary_edges; }
  /// Stability of boundary edge k at time step dt.
  BoundaryStability stability_of(std::size_t k, double dt) const;
  /// Penalty stiffness of fixed points without an explicit one [N/m].
  double default_fixed_point_stiffness() const { return default_fixed_stiffness; }

  std::vector<BlockSnapshot> snapshot() const;
  MonitorSample sample_monitor(std::size_t monitor) const;
  EnergyBalance energy() const;

private:
  struct AttachedLoad
  {
    MaterialPoint point;
    Vector2 force;
    TimeFunction function;
  };
  struct AttachedFixedPoint
  {
    MaterialPoint point;
    double stiffness;
    TimeFunction displacement_x, displacement_y;
    Point target(double t) const;
  };

  MaterialPoint attach(const Point& p, const std::string& what) const;
  bool small_displacement() const { return model.geometry == GeometryMode::small_displacement; }
  /// Moments of the configuration the step is linearised about (current or initial).
  const PolygonMoments& linearisation_moments(const Block& b) const;
  /// T at a material point, in the configuration the step is linearised about.
  Matrix26 point_matrix(const MaterialPoint& p) const;
  /// The step's right-hand side, and its matrix if `with_matrix`.
  void assemble(double dt, bool with_matrix);
  void update_blocks(double dt, const Eigen::VectorXd& d);
  StepStatus check_joint_strength() const;
  double stored_spring_energy() const;
  /// Outward unit normal of a boundary edge in the configuration the step is linearised about.
  Vector2 boundary_normal(const BoundaryEdge& e) const;
  double block_mass(const Block& b) const;

  ModelDescription model;
  std::vector<Eigen::Matrix3d> elasticity; ///< C per material [Pa]
  std::vector<Eigen::Matrix3d> compliance; ///< C^-1 per material [1/Pa]
  std::vector<double> tan_friction;        ///< tan(phi) per joint material
  std::vector<Block> blocks;
  std::vector<Joint> joints;
  std::vector<AttachedLoad> loads;
  std::vector<AttachedFixedPoint> fixed_points;
  std::vector<MaterialPoint> monitors;
  std::vector<BoundaryEdge> boundary_edges;
  /// Each boundary edge's stiffness and force in the current step (set by assemble, used for
  /// the boundary's work in update_blocks).
  std::vector<BoundaryStep> boundary_steps;
  double default_fixed_stiffness = 0.0;
  double beta = 0.5, gamma = 1.0; ///< Newmark parameters of the integrator

  BlockSparseMatrix matrix;
  double matrix_dt = 0.0; ///< dt the matrix was assembled for (small-displacement reuse)
  Eigen::VectorXd rhs;
  Eigen::VectorXd solution;
  FactorizationReusingSolver solver;

  double current_time = 0.0;
  double work_of_loads = 0.0;
  double work_of_supports = 0.0;
  double work_of_boundaries = 0.0;
  double initial_energy = 0.0;
  double largest_energy_input = 0.0; ///< max over time of work_of_loads + work_of_supports
  PhaseTimings timings;
};

} // namespace ddafem::dda
