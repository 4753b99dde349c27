// deal.II elastodynamics of a rectangular far field with Lysmer-Kuhlemeyer dashpots and an
// incident plane wave (issue 5).
#pragma once

#include "common/checkpoint_fwd.h"
#include "fem/far_field_description.h"
#include "fem/point_spring_field.h"

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace ddafem::fem
{
/// Energies [J] per unit thickness. Balance: kinetic + strain = initial + work_of_input +
/// work_of_dashpots + work_of_rayleigh - dissipated (dissipated: the integrator's algorithmic
/// loss, ~0 for the trapezoidal rule). After a static stage, strain is that of the displacement
/// relative to the static one (the static loads' work and the static strain energy cancel).
struct EnergyBalance
{
  double kinetic = 0.0;
  double strain = 0.0;
  double work_of_input = 0.0;    ///< work of the incident-wave tractions since t = 0
  double work_of_dashpots = 0.0; ///< work of the dashpot tractions since t = 0 (negative)
  double initial = 0.0;
  double dissipated = 0.0;
  double work_of_rayleigh = 0.0; ///< work of the Rayleigh damping forces since t = 0 (negative)
  /// Work of the point springs (ties to DDA blocks) on the far field since t = 0: the energy
  /// that crossed the interface into the far field.
  double work_of_springs = 0.0;
  double stored() const { return kinetic + strain; }
};

struct MonitorSample
{
  std::array<double, 2> displacement{{0.0, 0.0}}; ///< [m]
  std::array<double, 2> velocity{{0.0, 0.0}};     ///< [m/s]
  std::array<double, 3> stress{{0.0, 0.0, 0.0}};  ///< (sxx, syy, sxy) [Pa], tension positive
};

/// Wall time per phase since construction [s].
struct Timings
{
  double setup = 0.0;    ///< mesh, dofs, matrices, factorization
  double assemble = 0.0; ///< right-hand sides
  double solve = 0.0;
  double update = 0.0;
  std::size_t n_steps = 0;
  std::size_t linear_iterations = 0; ///< summed over steps (iterative solver; 0 for direct)
  std::size_t n_factorizations = 0;  ///< of the effective matrix (one per dt kept, rebuilds too)
};

/// A far field in time (a rectangle, optionally with a graded hole, or a Gmsh mesh). The
/// effective matrix K + gamma/(beta dt) C + 1/(beta dt^2) M is set up once (factorized, or a
/// preconditioner for CG) and each step is one solve (fem/linear_solvers.h).
class ElasticWaveModel final : public PointSpringField
{
public:
  /// Builds the mesh, the FE space and the constant matrices. Throws InputError for settings it
  /// cannot honour (e.g. a monitor outside the domain).
  explicit ElasticWaveModel(const FarFieldDescription& description);
  ~ElasticWaveModel();
  ElasticWaveModel(const ElasticWaveModel&) = delete;
  ElasticWaveModel& operator=(const ElasticWaveModel&) = delete;

  /// A displacement or velocity field u(x, y) = {u_x, u_y}.
  using VectorField = std::function<std::array<double, 2>(double x, double y)>;

  /// Replaces the state at the current time by the nodal interpolants of `displacement` and
  /// `velocity` (constrained components set to zero) and the consistent acceleration
  /// M a0 = f(t) - K u0 - C v0. Resets the energy balance (initial = kinetic + strain).
  void set_initial_state(const VectorField& displacement, const VectorField& velocity);

  /// Advances by dt [s] (a dt other than the last one refactorizes): prepare_step() and
  /// finish_step() with zero point loads.
  StepResult advance(double dt);

  double time() const;
  std::size_t n_dofs() const;
  std::size_t n_cells() const;
  double element_size() const;          ///< longest element edge [m]
  double smallest_element_size() const; ///< shortest longest-edge of an element [m] (graded)
  double area() const;                  ///< meshed area [m^2] (the rectangle less any hole)
  /// Length [m] of the boundary faces of a part (0 if the mesh has none).
  double boundary_length(BoundaryPart part) const;
  std::size_t n_constraints() const; ///< constrained DOFs: fixed, roller, hanging nodes
  std::string solver_name() const;   ///< "umfpack", "klu" or "cg_jacobi"
  double p_wave_speed() const;       ///< [m/s] of the plane mode
  double s_wave_speed() const;       ///< [m/s]
  const Timings& timings() const;

  MonitorSample sample_monitor(std::size_t monitor) const;
  /// Velocity [m/s] of the free-field column at height y (a model with a free_field part).
  std::array<double, 2> free_field_velocity(double y) const;
  /// Velocity [m/s] at the point (x, y) of the mesh.
  std::array<double, 2> velocity_at(double x, double y) const;
  /// L2 norm over the far field of (displacement - exact) [m^2 per unit thickness, square
  /// rooted: m^2], the displacement relative to any static stage; Gauss quadrature of degree + 2
  /// points per direction.
  double l2_error(const VectorField& exact_displacement) const;
  /// The energy budget; kinetic and strain energy from two products with the global matrices.
  EnergyBalance energy() const;
  /// EnergyBalance::work_of_springs alone, without energy()'s products [J].
  double work_of_springs() const override;

  // ---- point springs: the far field's side of the DDA coupling (fem/point_spring_field.h);
  // advance() uses q = 0 (springs to fixed anchors) ----

  /// Also refuses a model with a static stage (the springs would take part in it); the
  /// effective matrix is refactorized at the next step.
  std::vector<double> add_point_springs(BoundaryPart part,
                                        const std::vector<PointSpring>& springs) override;
  std::size_t n_point_springs() const;
  std::vector<std::array<double, 4>> boundary_segments(BoundaryPart part) const override;
  /// 2m solves, or one per far-field DOF the springs touch if fewer.
  std::vector<double> point_flexibility(double dt) override;
  StepResult prepare_step(double dt, std::vector<double>& free_point_displacements) override;
  StepResult finish_step(const std::vector<double>& point_loads) override;
  /// N u: displacements at the spring points [m] (2m).
  std::vector<double> point_displacements() const override;
  /// The springs' forces F on the far field at the current time [N] (2m).
  std::vector<double> spring_forces() const;

  // ---- as the free-field column of a distributed far field (fem/distributed_wave_model.h) --
  /// Places a probe at (x, y), clamped into the mesh; returns its index.
  std::size_t add_probe(double x, double y);
  /// Velocity and stress at probe k (displacement left zero).
  MonitorSample sample_probe(std::size_t k) const;
  /// Remembers the state now; return_to_remembered_state() goes back to it (a step abandoned).
  void remember_state();
  void return_to_remembered_state();

  /// Writes DIRECTORY/BASENAME_NNNNN.vtu (deal.II DataOut: displacement, velocity, stress
  /// components, von Mises), zlib-compressed at `compression`, and rewrites
  /// DIRECTORY/BASENAME.pvd with all snapshots so far; returns the VTU's file name (without the
  /// directory).
  std::string write_snapshot(const std::string& directory, const std::string& basename,
                             VtuCompression compression = VtuCompression::best_speed);

  /// Checkpoints (fem/far_field_checkpoint.cc): the state between two steps; `load` into a
  /// model built from the same description restores it, so that it steps on bit for bit.
  void save(CheckpointOut& archive) const;
  void load(CheckpointIn& archive);

private:
  class Impl;
  std::unique_ptr<Impl> impl;
};

} // namespace ddafem::fem
