// The state of DistributedWaveModel, shared by its two files (private: only fem/ includes it):
// fem/distributed_wave_model.cc (set-up, assembly, solver set-up) and
// fem/distributed_wave_step.cc (the Newmark step, monitors, energies, output).
#pragma once

#include "fem/distributed_wave_model.h"

#include <deal.II/base/point.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

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
  /// The effective matrix for steps of dt and its solver (AMG or LU).
  void set_up_solver(double dt);
  /// M a0 = f(0) - K u0 - C v0 (zero from rest without input at t = 0).
  void compute_initial_acceleration();
  StepStatus step(double dt);
  /// Solves P x = rhs, x holding the initial guess; returns the iterations (0: direct).
  unsigned int solve(TrilinosWrappers::MPI::Vector& x, const TrilinosWrappers::MPI::Vector& rhs);
  /// The work of the input and the dashpots over a step, with mid-step forces.
  void add_work_of_step(const TrilinosWrappers::MPI::Vector& u_new,
                        const TrilinosWrappers::MPI::Vector& v_new,
                        const TrilinosWrappers::MPI::Vector& force_new);

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
  DynamicSparsityPattern sparsity_of_effective;
  TrilinosWrappers::SparseMatrix mass, stiffness, damping, effective;
  TrilinosWrappers::MPI::Vector input_shape; ///< the input traction per unit v_in [N s/m]
  double input_scale = 0.0;                  ///< 2 rho c [kg/(m^2 s)]

  SolverControl solver_control{100000, 1e-12};
  std::unique_ptr<TrilinosWrappers::PreconditionAMG> amg;
  std::unique_ptr<TrilinosWrappers::PreconditionJacobi> jacobi;
  std::unique_ptr<TrilinosWrappers::SolverDirect> direct;
  double solver_dt = 0.0; ///< the dt the solver is set up for [s]; 0: none

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
  std::vector<std::pair<double, std::string>> snapshots; ///< time [s], PVTU name
};

} // namespace ddafem::fem
