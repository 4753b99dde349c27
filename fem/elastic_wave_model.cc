// deal.II elastodynamics of a rectangular far field (issue 5): the model is built in the
// constructor (mesh, matrices, static stage, factorization) and the public calls forward to
// ElasticWaveModel::Impl (fem/elastic_wave_model_impl.h lists the files of each concern).
#include "fem/elastic_wave_model_impl.h"

#include "common/elasticity.h"

#include <deal.II/fe/fe_q.h>
#include <deal.II/grid/grid_tools.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace ddafem::fem
{
using namespace far_field_detail;

ElasticWaveModel::Impl::Impl(const FarFieldDescription& description_)
    : description(description_), fe(FE_Q<2>(std::max(1u, description_.degree)), 2),
      dof_handler(mesh)
{
  const auto start = Clock::now();
  validate();

  const double E = description.youngs_modulus;
  const double nu = description.poisson_ratio;
  const double rho = description.density;
  const double lambda = lame_lambda(E, nu);
  const double mu = shear_modulus(E, nu);
  elasticity.mu = mu;
  elasticity.nu = nu;
  elasticity.mode = description.plane_mode;
  elasticity.lambda = description.plane_mode == PlaneMode::strain
                          ? lambda
                          : 2.0 * lambda * mu / (lambda + 2.0 * mu);
  vp = std::sqrt((elasticity.lambda + 2.0 * mu) / rho);
  vs = std::sqrt(mu / rho);
  if (description.integrator == Integrator::dda)
  {
    beta = 0.5;
    gamma = 1.0;
  }

  make_mesh();
  dof_handler.distribute_dofs(fe);
  make_constraints();
  assemble_matrices();
  locate_monitors();

  u.reinit(dof_handler.n_dofs());
  v.reinit(dof_handler.n_dofs());
  a.reinit(dof_handler.n_dofs());
  force.reinit(dof_handler.n_dofs());
  input_force(0.0, force);
  make_free_field_column();
  if (description.static_stage.enabled)
    solve_static_stage();

  if (description.dt > 0.0)
    factorize(description.dt);
  timings.setup += seconds_since(start);
}

// ---- public interface ---------------------------------------------------------------------

ElasticWaveModel::ElasticWaveModel(const FarFieldDescription& description)
    : impl(std::make_unique<Impl>(description))
{
}

ElasticWaveModel::~ElasticWaveModel() = default;

void ElasticWaveModel::set_initial_state(const VectorField& displacement,
                                         const VectorField& velocity)
{
  impl->set_initial_state(displacement, velocity);
}

StepResult ElasticWaveModel::advance(const double dt)
{
  StepResult status = impl->prepare_step(dt);
  if (!status.taken)
    return status;
  return impl->finish_step(std::vector<double>(2 * impl->springs.size(), 0.0));
}

StepResult ElasticWaveModel::prepare_step(const double dt,
                                          std::vector<double>& free_point_displacements)
{
  StepResult status = impl->prepare_step(dt);
  if (status.taken)
    free_point_displacements = impl->evaluate_at_springs(impl->pending.u_new);
  return status;
}

StepResult ElasticWaveModel::finish_step(const std::vector<double>& point_loads)
{
  return impl->finish_step(point_loads);
}

std::vector<double> ElasticWaveModel::point_displacements() const
{
  return impl->evaluate_at_springs(impl->u);
}

std::vector<double> ElasticWaveModel::spring_forces() const
{
  return impl->spring_force;
}

std::size_t ElasticWaveModel::n_point_springs() const
{
  return impl->springs.size();
}

std::vector<std::array<double, 4>>
ElasticWaveModel::boundary_segments(const BoundaryPart part) const
{
  std::vector<std::array<double, 4>> segments;
  for (const auto& cell : impl->mesh.active_cell_iterators())
    for (const unsigned int f : cell->face_indices())
      if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == boundary_id_of(part))
      {
        const Point<2> a = cell->face(f)->vertex(0), b = cell->face(f)->vertex(1);
        segments.push_back({{a[0], a[1], b[0], b[1]}});
      }
  return segments;
}

double ElasticWaveModel::time() const
{
  return impl->t;
}
std::size_t ElasticWaveModel::n_dofs() const
{
  return impl->dof_handler.n_dofs();
}
std::size_t ElasticWaveModel::n_cells() const
{
  return impl->mesh.n_active_cells();
}
double ElasticWaveModel::element_size() const
{
  return impl->h;
}
double ElasticWaveModel::smallest_element_size() const
{
  return impl->h_min;
}
double ElasticWaveModel::area() const
{
  return GridTools::volume(impl->mesh);
}
double ElasticWaveModel::boundary_length(const BoundaryPart part) const
{
  double length = 0.0;
  for (const auto& cell : impl->mesh.active_cell_iterators())
    for (const unsigned int f : cell->face_indices())
      if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == boundary_id_of(part))
        length += cell->face(f)->measure();
  return length;
}
std::size_t ElasticWaveModel::n_constraints() const
{
  return impl->constraints.n_constraints();
}
std::string ElasticWaveModel::solver_name() const
{
  return !impl->factorizations.empty()
             ? impl->solver().name()
             : make_effective_solver(impl->description.solver, impl->description.direct_solver,
                                     1e-10)
                   ->name();
}
double ElasticWaveModel::p_wave_speed() const
{
  return impl->vp;
}
double ElasticWaveModel::s_wave_speed() const
{
  return impl->vs;
}
const Timings& ElasticWaveModel::timings() const
{
  return impl->timings;
}

MonitorSample ElasticWaveModel::sample_monitor(const std::size_t monitor) const
{
  return impl->sample_monitor(monitor);
}

EnergyBalance ElasticWaveModel::energy() const
{
  // Kinetic and strain energy on demand: two products with the global matrices, as costly as
  // a step's right-hand side.
  EnergyBalance e = impl->energies;
  e.kinetic = 0.5 * norm_square(impl->mass, impl->v);
  e.strain = impl->strain_energy();
  e.dissipated = e.initial + e.work_of_input + e.work_of_dashpots + e.work_of_rayleigh +
                 e.work_of_springs - e.stored();
  return e;
}

double ElasticWaveModel::work_of_springs() const
{
  return impl->energies.work_of_springs;
}

std::string ElasticWaveModel::write_snapshot(const std::string& directory,
                                             const std::string& basename,
                                             const VtuCompression compression)
{
  return impl->write_snapshot(directory, basename, compression);
}

} // namespace ddafem::fem
