// DistributedWaveModel: set-up and assembly here, the step, monitors and output in
// fem/distributed_wave_step.cc. Names follow deal.II's step-40 (locally owned / relevant sets,
// ghosted copies for evaluation).
#include "fem/distributed_wave_model_impl.h"

#include "common/elasticity.h"
#include "common/format.h"
#include "common/input_error.h"
#include "common/stopwatch.h"
#include "fem/far_field_kernels.h"
#include "fem/far_field_mesh.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace ddafem::fem
{
namespace
{
void require(const bool condition, const std::string& message)
{
  if (!condition)
    throw InputError("far field (distributed): " + message);
}

/// The features ElasticWaveModel has that the distributed model does not have yet.
void check_distributable(const FarFieldDescription& d)
{
  require(d.mesh_file.file.empty(),
          "a mesh file is not distributed yet: expected the rectangle, with or without a hole");
  require(!d.static_stage.enabled, "a static stage is not distributed yet");
  for (const BoundaryCondition& bc : d.boundaries)
    require(!bc.springs.enabled, std::string("boundary part '") + name_of(bc.part) +
                                     "': boundary springs are not distributed yet");
}

/// The largest k with 2^k dividing both counts and at least `minimum` coarse cells left.
unsigned int common_refinements(unsigned int nx, unsigned int ny, const unsigned int minimum)
{
  unsigned int k = 0;
  while (nx % 2 == 0 && ny % 2 == 0 && (nx / 2) * (ny / 2) >= minimum)
  {
    nx /= 2;
    ny /= 2;
    ++k;
  }
  return k;
}

} // namespace

DistributedWaveModel::Impl::Impl(const FarFieldDescription& d, MPI_Comm comm_,
                                 DistributedSolver solver_kind_)
    : description(d), comm(comm_), solver_kind(solver_kind_),
      mesh(comm_, d.hole.shape == HoleShape::none
                      ? Triangulation<2>::none
                      : Triangulation<2>::limit_level_difference_at_vertices),
      fe(FE_Q<2>(std::max(1u, d.degree)), 2), dof_handler(mesh)
{
  const auto start = Clock::now();
  require(d.upper[0] > d.lower[0] && d.upper[1] > d.lower[1],
          "upper corner must lie above and right of the lower corner");
  require(d.degree == 1 || d.degree == 2,
          "degree = " + std::to_string(d.degree) + ", expected 1 or 2");
  require(d.density > 0.0 && d.youngs_modulus > 0.0 && d.poisson_ratio >= 0.0 &&
              d.poisson_ratio < 0.5,
          "expected density > 0, youngs_modulus > 0, poisson_ratio in [0, 0.5)");
  check_distributable(d);
  set_material();
  make_mesh();
  dof_handler.distribute_dofs(fe);
  owned = dof_handler.locally_owned_dofs();
  DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
  make_constraints();
  assemble();
  locate_monitors();
  make_free_field_column();
  for (TrilinosWrappers::MPI::Vector* x :
       {&u, &v, &a, &a_previous, &force, &scratch.force_new, &scratch.rhs, &scratch.combination,
        &scratch.product, &scratch.u_new, &scratch.a_new, &scratch.v_new})
    x->reinit(owned, comm);
  distributed.reinit(owned, comm);
  ghosted.reinit(owned, relevant, comm);
  timings.setup += seconds_since(start);
}

void DistributedWaveModel::Impl::set_material()
{
  const FarFieldDescription& d = description;
  mu = shear_modulus(d.youngs_modulus, d.poisson_ratio);
  lambda = lame_lambda(d.youngs_modulus, d.poisson_ratio);
  if (d.plane_mode == PlaneMode::stress)
    lambda = 2.0 * lambda * mu / (lambda + 2.0 * mu);
  vp = std::sqrt((lambda + 2.0 * mu) / d.density);
  vs = std::sqrt(mu / d.density);
  if (d.integrator == Integrator::dda) // beta = 1/2, gamma = 1
  {
    beta = 0.5;
    gamma = 1.0;
  }
}

void DistributedWaveModel::Impl::make_mesh()
{
  const FarFieldDescription& d = description;
  const double size = target_element_size(d, vs);
  if (d.hole.shape != HoleShape::none)
  {
    // The serial model's graded mesh: its O-grid and Cartesian cells are the coarse mesh on
    // every rank; each rank grades its own.
    make_far_field_mesh(d, size, mesh);
    double longest = 0.0;
    for (const auto& cell : mesh.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          longest = std::max(longest, cell->face(f)->diameter());
    h = Utilities::MPI::max(longest, comm);
    return;
  }
  const unsigned int nx = element_intervals(d.upper[0] - d.lower[0], size);
  const unsigned int ny = element_intervals(d.upper[1] - d.lower[1], size);
  // p4est keeps the coarse mesh on every rank: coarsest cells that refine to the serial mesh
  // (at least 16 per rank, so that the partition can balance them).
  const unsigned int k = common_refinements(nx, ny, 16 * Utilities::MPI::n_mpi_processes(comm));
  GridGenerator::subdivided_hyper_rectangle(mesh, {nx >> k, ny >> k},
                                            Point<2>(d.lower[0], d.lower[1]),
                                            Point<2>(d.upper[0], d.upper[1]), true);
  mesh.refine_global(k);
  h = std::max((d.upper[0] - d.lower[0]) / nx, (d.upper[1] - d.lower[1]) / ny);
}

void DistributedWaveModel::Impl::make_constraints()
{
  constraints.clear();
  constraints.reinit(relevant);
  DoFTools::make_hanging_node_constraints(dof_handler, constraints);
  add_support_constraints(dof_handler, description, constraints);
  constraints.close();
}

// M, K and C are assembled with the constrained (fixed, roller, hanging) rows and columns
// eliminated: the algebra runs on the unconstrained DOFs, the constrained entries of u, v and a
// stay zero, products and energies are those of ElasticWaveModel's, and the effective matrix
// needs no condensing. Evaluating the field (monitors, springs, output) distributes the
// constraints first (Impl::ghosted_field).
void DistributedWaveModel::Impl::assemble()
{
  DynamicSparsityPattern dsp(relevant);
  DoFTools::make_sparsity_pattern(dof_handler, dsp, constraints, true);
  SparsityTools::distribute_sparsity_pattern(dsp, owned, comm, relevant);
  for (TrilinosWrappers::SparseMatrix* m : {&mass, &stiffness, &damping})
    m->reinit(owned, owned, dsp, comm);
  input_shape.reinit(owned, comm);
  assemble_domain();
  assemble_boundary();
  for (TrilinosWrappers::SparseMatrix* m : {&mass, &stiffness, &damping})
    m->compress(VectorOperation::add);
  input_shape.compress(VectorOperation::add);
  // Rayleigh damping joins the dashpots: C = dashpots + alpha M + beta K (one pattern for all).
  if (description.rayleigh.alpha > 0.0)
    damping.add(description.rayleigh.alpha, mass);
  if (description.rayleigh.beta > 0.0)
    damping.add(description.rayleigh.beta, stiffness);
}

void DistributedWaveModel::Impl::assemble_domain()
{
  for_each_elastic_cell(dof_handler, description.density, lambda, mu, true,
                        [&](const std::vector<types::global_dof_index>& dofs,
                            const FullMatrix<double>& cell_mass,
                            const FullMatrix<double>& cell_stiffness)
                        {
                          constraints.distribute_local_to_global(cell_mass, dofs, mass);
                          constraints.distribute_local_to_global(cell_stiffness, dofs, stiffness);
                        });
}

void DistributedWaveModel::Impl::assemble_boundary()
{
  // Lysmer dashpots on lysmer, input and free_field parts; the input traction's shape on input
  // parts.
  const auto absorbing = absorbing_parts(description);
  const unsigned int component = input_component(description);
  input_scale = input_traction_scale(description, vp, vs);
  const unsigned int n = fe.n_dofs_per_cell();
  FEFaceValues<2> values(fe, QGauss<1>(fe.degree + 1),
                         update_values | update_normal_vectors | update_JxW_values);
  FullMatrix<double> cell_damping(n, n);
  Vector<double> cell_input(n);
  std::vector<types::global_dof_index> dofs(n);
  for (const auto& cell : dof_handler.active_cell_iterators())
    for (const unsigned int f : cell->face_indices())
    {
      if (!cell->is_locally_owned() || !cell->face(f)->at_boundary())
        continue;
      const auto found = absorbing.find(cell->face(f)->boundary_id());
      if (found == absorbing.end())
        continue;
      values.reinit(cell, f);
      absorbing_face_matrices(values, *found->second, description.density, vp, vs, component,
                              cell_damping, cell_input);
      cell->get_dof_indices(dofs);
      constraints.distribute_local_to_global(cell_damping, dofs, damping);
      constraints.distribute_local_to_global(cell_input, dofs, input_shape);
    }
}

void DistributedWaveModel::Impl::use_level(const double dt)
{
  if (levels.use(dt))
    return;
  const auto start = Clock::now();
  const double c_mass = 1.0 / (beta * dt * dt), c_damping = gamma / (beta * dt);
  // P = K + c_damping C + c_mass M; the three were assembled with the constrained rows and
  // columns eliminated, and so is P.
  auto level = std::make_unique<Level>();
  TrilinosWrappers::SparseMatrix& p = level->matrix;
  p.reinit(stiffness); // the layout
  p.copy_from(stiffness);
  p.add(c_mass, mass);
  p.add(c_damping, damping);
  if (!springs.empty())
    p.add(1.0, springs_matrix);
  if (solver_kind == DistributedSolver::mumps)
  {
    level->direct = std::make_unique<DistributedMumps>(p.trilinos_matrix(), comm);
  }
  else if (solver_kind == DistributedSolver::cg_jacobi)
  {
    level->jacobi = std::make_unique<TrilinosWrappers::PreconditionJacobi>();
    level->jacobi->initialize(p);
  }
  else
  {
    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    data.elliptic = true;
    data.higher_order_elements = fe.degree > 1;
    data.smoother_sweeps = 2;
    data.aggregation_threshold = 0.02;
    DoFTools::extract_constant_modes(dof_handler, ComponentMask(), data.constant_modes);
    level->amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
    level->amg->initialize(p, data);
  }
  levels.insert(dt, std::move(level));
  ++timings.n_levels;
  timings.factorize += seconds_since(start);
}

DistributedWaveModel::DistributedWaveModel(const FarFieldDescription& description, MPI_Comm comm,
                                           DistributedSolver solver)
    : impl(std::make_unique<Impl>(description, comm, solver))
{
}

DistributedWaveModel::~DistributedWaveModel() = default;

double DistributedWaveModel::time() const
{
  return impl->t;
}

double DistributedWaveModel::p_wave_speed() const
{
  return impl->vp;
}

double DistributedWaveModel::s_wave_speed() const
{
  return impl->vs;
}

std::size_t DistributedWaveModel::n_dofs() const
{
  return impl->dof_handler.n_dofs();
}

std::size_t DistributedWaveModel::n_locally_owned_dofs() const
{
  return impl->owned.n_elements();
}

std::size_t DistributedWaveModel::n_cells() const
{
  return impl->mesh.n_global_active_cells();
}

double DistributedWaveModel::element_size() const
{
  return impl->h;
}

const DistributedTimings& DistributedWaveModel::timings() const
{
  return impl->timings;
}

} // namespace ddafem::fem
