// The state of DistributedWaveModel, shared by its two files (private: only fem/ includes it):
// fem/distributed_wave_model.cc (set-up, assembly, solver set-up),
// fem/distributed_wave_step.cc (the Newmark step, monitors, energies, output) and
// fem/distributed_point_springs.cc (the ties to the blocks).
#pragma once

#include "common/recent_cache.h"
#include "fem/distributed_wave_model.h"
#include "fem/mumps_solver.h"

#include <deal.II/base/point.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <Epetra_MultiVector.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace ddafem::fem
{
using namespace dealii;

class DistributedWaveModel::Impl
{
public:
  Impl(const FarFieldDescription& description, MPI_Comm comm, DistributedSolver solver_kind);

  void set_material();
  void make_mesh();
  void make_constraints();
  void assemble();
  void assemble_domain();
  void assemble_boundary();
  void locate_monitors();
  /// The effective matrix for steps of dt and its solver (AMG, Jacobi or LU), set up on first
  /// use and kept: the current level (levels.front()) from then on.
  void use_level(double dt);
  /// M a0 = f(0) - K u0 - C v0 (zero from rest without input at t = 0).
  void compute_initial_acceleration();
  /// The Newmark right-hand side of a step of dt and its predictor solve into scratch.u_new.
  void prepare(double dt);
  /// u_new += P^-1 N^T q, then velocities, accelerations, energies; the state moves to t + dt.
  StepResult finish(const std::vector<double>& point_loads);
  /// Solves P x = rhs, x holding the initial guess; returns the iterations (0: direct).
  unsigned int solve(TrilinosWrappers::MPI::Vector& x, const TrilinosWrappers::MPI::Vector& rhs);
  /// Solves P X = B for all columns of B at once (zero initial guesses): MUMPS with every
  /// right-hand side in one pass over its factors, or Belos' pseudo-block CG (a CG per column,
  /// their products with P and preconditioner together: one pass over P an iteration for all
  /// columns; each column to the solver tolerance relative to its own norm); returns the iterations
  /// (0: direct). Throws if CG does not converge. (Belos' true block CG broke down on G's
  /// right-hand sides: their block loses rank as columns converge.)
  unsigned int solve_block(Epetra_MultiVector& x, const Epetra_MultiVector& b);
  /// The work of the input and the dashpots over a step, with mid-step forces.
  void add_work_of_step(const TrilinosWrappers::MPI::Vector& u_new,
                        const TrilinosWrappers::MPI::Vector& v_new,
                        const TrilinosWrappers::MPI::Vector& force_new);
  /// Free-field sides (fem/distributed_free_field.cc): the serial column, replicated, and a
  /// probe of it per quadrature point of this rank's free_field faces (in active-cell order).
  void make_free_field_column();
  bool is_free_field_face(const DoFHandler<2>::active_cell_iterator& cell, unsigned int f) const;
  /// Advances the column by dt, back to the step's start first if a step was abandoned;
  /// throws if it fails.
  void advance_column(double dt);
  /// f += integral(N^T (sigma_ff n + D v_ff)) over this rank's free_field faces.
  void add_free_field_load(TrilinosWrappers::MPI::Vector& f);
  /// x with its constrained entries (hanging nodes) set, in `ghosted` (owned and relevant).
  const TrilinosWrappers::MPI::Vector& ghosted_field(const TrilinosWrappers::MPI::Vector& x) const;
  /// N x at this rank's springs, zero at the others' [m] (2m).
  std::vector<double> springs_share_of(const TrilinosWrappers::MPI::Vector& x) const;
  /// N x at every spring, on every rank [m] (2m).
  std::vector<double> evaluate_at_springs(const TrilinosWrappers::MPI::Vector& x) const;
  /// rhs = N^T q: the owners' springs' point loads q [N] (2m) into the right-hand side.
  void set_spring_loads(const std::vector<double>& q, TrilinosWrappers::MPI::Vector& rhs) const;
  /// The work of the springs' forces F = q - K N u over a step (mid-step forces); stores F at
  /// t + dt.
  void add_work_of_springs(const TrilinosWrappers::MPI::Vector& u_new,
                           const std::vector<double>& point_loads);

  FarFieldDescription description;
  MPI_Comm comm;
  DistributedSolver solver_kind;
  double lambda = 0.0, mu = 0.0; ///< plane Lame constants [Pa]
  double vp = 0.0, vs = 0.0;     ///< [m/s]
  double beta = 0.25, gamma = 0.5;
  double h = 0.0; ///< element edge [m]

  parallel::distributed::Triangulation<2> mesh;
  FESystem<2> fe;
  DoFHandler<2> dof_handler;
  IndexSet owned, relevant;
  AffineConstraints<double> constraints;
  /// The springs' N^T K N (on the matrices' pattern) is added to P.
  TrilinosWrappers::SparseMatrix mass, stiffness, damping, springs_matrix;
  TrilinosWrappers::MPI::Vector input_shape; ///< the input traction per unit v_in [N s/m]
  double input_scale = 0.0;                  ///< 2 rho c [kg/(m^2 s)]

  /// The effective matrix P = K + gamma/(beta dt) C + 1/(beta dt^2) M (+ N^T K N) of one dt and
  /// the solver set up on it.
  struct Level
  {
    TrilinosWrappers::SparseMatrix matrix;
    std::unique_ptr<TrilinosWrappers::PreconditionAMG> amg;
    std::unique_ptr<TrilinosWrappers::PreconditionJacobi> jacobi;
    std::unique_ptr<DistributedMumps> direct;
  };
  /// By dt [s], the most recent first: coupled runs that cut dt step on the levels
  /// dt_max / 2^k and come back (16 kept, as ElasticWaveModel keeps its factorizations).
  RecentCache<double, Level> levels{16};
  /// Right-hand sides solved at once for G (docs/performance/far_field_scaling/condensation.md,
  /// 702 of them): MUMPS reads its factors once per block (64: 2-2.5x faster than one at a
  /// time); Belos' pseudo-block CG gains 8-21 % at 2 and loses beyond 4 (Epetra's products
  /// with many vectors stride over them).
  unsigned int condensation_width = solver_kind == DistributedSolver::mumps ? 64 : 2;

  TrilinosWrappers::MPI::Vector u, v, a, a_previous, force; ///< owned entries
  /// A step's work vectors, made once: a vector made in a step would make its Epetra map too.
  struct Scratch
  {
    TrilinosWrappers::MPI::Vector force_new, rhs, combination, product, u_new, a_new, v_new;
  } scratch;
  double t = 0.0;
  bool initial_acceleration_done = false;
  EnergyBalance energies;
  DistributedTimings timings;

  /// A monitor: its point and whether this rank owns the cell that holds it.
  struct MonitorPoint
  {
    Point<2> point;
    bool mine = false;
    DoFHandler<2>::active_cell_iterator cell;
    Point<2> reference; ///< the point in the cell's reference coordinates
  };
  std::vector<MonitorPoint> monitors;

  /// A point spring: every rank lists it; the rank that owns its cell (`mine`) has the cell's
  /// DOFs and the shape functions' values N there.
  struct SpringPoint
  {
    bool mine = false;
    std::vector<types::global_dof_index> dofs; ///< the cell's
    std::vector<double> phi;                   ///< N's entries, by cell DOF
    std::vector<unsigned int> component;       ///< by cell DOF
    double k[2][2] = {{0.0, 0.0}, {0.0, 0.0}}; ///< [N/m]
  };
  std::vector<SpringPoint> springs;
  std::vector<double> spring_force; ///< F on the far field at t [N] (2m)
  /// ghosted_field's work vectors: owned entries, then owned and relevant ones.
  mutable TrilinosWrappers::MPI::Vector distributed, ghosted;
  std::unique_ptr<ElasticWaveModel> column; ///< the free-field column, if any
  std::vector<std::size_t> column_probes;
  bool column_ahead = false; ///< the column has advanced into a step not finished yet
  TrilinosWrappers::MPI::Vector free_field_load;
  bool step_prepared = false;
  double prepared_dt = 0.0;                              ///< [s]
  std::vector<std::pair<double, std::string>> snapshots; ///< time [s], PVTU name
};

} // namespace ddafem::fem
