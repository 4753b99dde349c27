// The far field distributed over MPI ranks (issue 22): ElasticWaveModel's rectangle, with or
// without a graded hole, free-field sides and point springs to the blocks (no static stage
// yet), on deal.II's
// parallel::distributed::Triangulation
// (p4est) with Trilinos (Epetra) matrices and vectors. Every rank owns a part of the cells and
// of the degrees of freedom; the effective matrix is solved by CG preconditioned with ML's
// algebraic multigrid or with its diagonal (warm-started from Newmark's predictor), or by
// MUMPS (fem/mumps_solver.h) factorized once per dt. The same physics as ElasticWaveModel:
// consistent mass, plane elasticity, Lysmer dashpots, the Joyner-Chen input of a vertically
// incident wave, Newmark (trapezoidal or DDA's), so that both give the same histories
// (tests/fem/test_distributed_wave_model.cc).
#pragma once

#include "common/enum_names.h"
#include "fem/elastic_wave_model.h"
#include "fem/far_field_description.h"
#include "fem/point_spring_field.h"

#include <mpi.h>

#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace ddafem::fem
{
/// Solver of the distributed effective matrix K + gamma/(beta dt) C + 1/(beta dt^2) M.
enum class DistributedSolver
{
  cg_amg,    ///< CG preconditioned by ML AMG (set up once per dt), warm-started
  cg_jacobi, ///< CG preconditioned by the diagonal, warm-started: for a mass-dominated matrix
  mumps      ///< MUMPS: distributed LDL^T factorized once per dt, two substitutions a step
};

constexpr std::array<EnumName<DistributedSolver>, 3> enum_names(DistributedSolver)
{
  return {{{DistributedSolver::cg_amg, "cg_amg"},
           {DistributedSolver::cg_jacobi, "cg_jacobi"},
           {DistributedSolver::mumps, "mumps"}}};
}

/// Wall time and sizes of one rank.
struct DistributedTimings
{
  double setup = 0.0;       ///< mesh, dofs, matrices [s]
  double factorize = 0.0;   ///< effective matrices, AMG set-ups or LUs, G [s]
  std::size_t n_levels = 0; ///< effective matrices set up (one per dt, again if dropped)
  double assemble = 0.0;    ///< right-hand sides [s]
  double solve = 0.0;       ///< [s]
  double update = 0.0;      ///< velocities, accelerations, work [s]
  std::size_t n_steps = 0;
  std::size_t linear_iterations = 0; ///< CG iterations summed over steps (0 for MUMPS)
};

/// The far field of a FarFieldDescription distributed over the ranks of `comm`. Every call is
/// collective (all ranks call it, in the same order) unless it says otherwise. Its point springs
/// (PointSpringField) live on the rank that owns the cell of their point; every rank gets the
/// same point vectors and G, bit for bit (each entry is summed from one rank's value and zeros),
/// so that blocks replicated on every rank step alike.
class DistributedWaveModel final : public PointSpringField
{
public:
  /// Builds the mesh (the rectangle, or ElasticWaveModel's graded mesh around a hole, with its
  /// hanging nodes), distributes it and assembles the constant matrices; a free_field side gets
  /// the serial free-field column on every rank. Throws InputError for a description it cannot
  /// honour: a mesh file, a static stage or boundary springs (not distributed yet), and the
  /// checks of ElasticWaveModel.
  DistributedWaveModel(const FarFieldDescription& description, MPI_Comm comm,
                       DistributedSolver solver);
  ~DistributedWaveModel();
  DistributedWaveModel(const DistributedWaveModel&) = delete;
  DistributedWaveModel& operator=(const DistributedWaveModel&) = delete;

  /// Advances by dt [s] from rest at t = 0 (the solver of each dt is set up on its first use
  /// and kept, up to 16 of them): prepare_step() and finish_step() with zero point loads.
  StepResult advance(double dt);

  std::vector<double> add_point_springs(BoundaryPart part,
                                        const std::vector<PointSpring>& springs) override;
  /// Every rank's faces, in the order of their coordinates.
  std::vector<std::array<double, 4>> boundary_segments(BoundaryPart part) const override;
  /// 2m right-hand sides (one per spring component), solved `condensation_width` at a time
  /// (block solves; fewer if a block of the whole model would pass 128 MB), and one sum over the
  /// ranks.
  std::vector<double> point_flexibility(double dt) override;
  /// Right-hand sides solved at once in point_flexibility() (default 64 with MUMPS, 2 with CG;
  /// 1: one solve each, for comparison in bench/far_field_scaling).
  void set_condensation_width(unsigned int width);
  StepResult prepare_step(double dt, std::vector<double>& free_point_displacements) override;
  std::vector<double> point_displacements() const override;
  /// Takes rank 0's point loads, and fails on every rank if the ranks' loads differ (the blocks
  /// replicated on the ranks would have parted).
  StepResult finish_step(const std::vector<double>& point_loads) override;
  double work_of_springs() const override; ///< not collective
  double time() const;                     ///< not collective
  double p_wave_speed() const;             ///< [m/s] of the plane mode; not collective
  double s_wave_speed() const;             ///< [m/s]; not collective
  /// Velocity [m/s] of the free-field column at height y (a model with a free_field side; every
  /// rank has the column): not collective.
  std::array<double, 2> free_field_velocity(double y) const;
  std::size_t n_dofs() const;                ///< of the whole model; not collective
  std::size_t n_locally_owned_dofs() const;  ///< of this rank; not collective
  std::size_t n_cells() const;               ///< active cells of the whole model; not collective
  double element_size() const;               ///< longest element edge [m]; not collective
  const DistributedTimings& timings() const; ///< this rank's; not collective
  /// The sample at a monitor, from the rank that owns its cell, on every rank.
  MonitorSample sample_monitor(std::size_t monitor) const;
  /// The energy budget (EnergyBalance).
  EnergyBalance energy() const;
  /// Writes DIRECTORY/BASENAME_NNNNN.pvtu with one DIRECTORY/BASENAME_NNNNN.K.vtu piece per
  /// rank K (deal.II's write_vtu_with_pvtu_record: displacement, velocity, subdomain) and
  /// rewrites DIRECTORY/BASENAME.pvd (rank 0); returns the PVTU's file name.
  std::string write_snapshot(const std::string& directory, const std::string& basename);

private:
  class Impl;
  std::unique_ptr<Impl> impl;
};

} // namespace ddafem::fem
