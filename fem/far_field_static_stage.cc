// ElasticWaveModel static stage: gravity and in-situ stress solved on supports; the dynamic stage
// reports the displacement relative to it.
#include "fem/elastic_wave_model_impl.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/component_mask.h>
#include <deal.II/numerics/vector_tools.h>

#include <string>
#include <vector>

namespace ddafem::fem
{
using namespace far_field_detail;

std::array<double, 3> ElasticWaveModel::Impl::initial_stress(const double y) const
{
  const StaticStage& s = description.static_stage;
  if (!s.enabled)
    return {{0.0, 0.0, 0.0}};
  std::array<double, 3> sigma;
  for (unsigned int k = 0; k < 3; ++k)
    sigma[k] = s.stress[k] + s.stress_gradient[k] * (y - s.reference_y);
  return sigma;
}

Vector<double> ElasticWaveModel::Impl::relative_displacement() const
{
  Vector<double> w(u);
  if (static_displacement.size() == w.size())
    w -= static_displacement;
  return w;
}

double ElasticWaveModel::Impl::strain_energy() const
{
  return 0.5 * norm_square(stiffness, relative_displacement());
}

void ElasticWaveModel::Impl::solve_static_stage()
{
  const Vector<double> load = static_load();
  AffineConstraints<double> supports;
  const bool supported = make_static_supports(supports);
  require(supported, "static_stage: no part holds the model (all parts free), expected a "
                     "fixed, roller, lysmer or input part");

  SparseMatrix<double> k(sparsity);
  k.copy_from(stiffness);
  supports.condense(k);
  Vector<double> rhs(load);
  supports.condense(rhs);
  static_displacement.reinit(dof_handler.n_dofs());
  const auto direct = make_effective_solver(LinearSolver::direct, DirectSolver::klu, 0.0);
  try
  {
    direct->initialize(k);
    direct->solve(rhs, static_displacement);
  }
  catch (const std::exception& e)
  {
    throw InputError(std::string("far field: static_stage: the static problem is singular (") +
                     e.what() +
                     "): expected supports that stop rigid-body motion in both directions");
  }
  for (const double x : static_displacement)
    require(std::isfinite(x), "static_stage: the static problem is singular, expected supports "
                              "that stop rigid-body motion in both directions");
  supports.distribute(static_displacement);
  // The reactions stay as forces: K u_s is the load at free DOFs and load + reaction at the
  // supported ones, so the dynamic stage starts in equilibrium.
  static_force.reinit(dof_handler.n_dofs());
  stiffness.vmult(static_force, static_displacement);
  u = static_displacement;
}

Vector<double> ElasticWaveModel::Impl::static_load() const
{
  const StaticStage& s = description.static_stage;
  const QGauss<2> quadrature(fe.degree + 1);
  FEValues<2> fe_values(fe, quadrature,
                        update_values | update_gradients | update_quadrature_points |
                            update_JxW_values);
  const unsigned int n = fe.n_dofs_per_cell();
  Vector<double> cell_load(n), load(dof_handler.n_dofs());
  std::vector<types::global_dof_index> dofs(n);
  for (const auto& cell : dof_handler.active_cell_iterators())
  {
    fe_values.reinit(cell);
    cell_load = 0.0;
    for (const unsigned int q : fe_values.quadrature_point_indices())
    {
      const auto sigma = initial_stress(fe_values.quadrature_point(q)[1]);
      const double tensor[2][2] = {{sigma[0], sigma[2]}, {sigma[2], sigma[1]}};
      for (unsigned int i = 0; i < n; ++i)
      {
        const unsigned int c = fe.system_to_component_index(i).first;
        const Tensor<1, 2> grad = fe_values.shape_grad(i, q);
        cell_load(i) += (description.density * s.gravity[c] * fe_values.shape_value(i, q) -
                         (tensor[c][0] * grad[0] + tensor[c][1] * grad[1])) *
                        fe_values.JxW(q);
      }
    }
    cell->get_dof_indices(dofs);
    for (unsigned int i = 0; i < n; ++i)
      load(dofs[i]) += cell_load(i);
  }
  return load;
}

bool ElasticWaveModel::Impl::make_static_supports(AffineConstraints<double>& supports) const
{
  const StaticStage& s = description.static_stage;
  DoFTools::make_hanging_node_constraints(dof_handler, supports);
  const unsigned int roller_component = description.incident.type == IncidentWave::Type::sv ? 1 : 0;
  bool supported = false;
  for (const auto& bc : description.boundaries)
  {
    std::vector<bool> mask(2, true);
    if (bc.kind == BoundaryKind::free)
      continue;
    if (bc.kind == BoundaryKind::roller)
      mask[1 - roller_component] = false;
    if ((bc.kind == BoundaryKind::lysmer || bc.kind == BoundaryKind::input ||
         bc.kind == BoundaryKind::free_field) &&
        s.support == StaticSupport::roller && bc.part != BoundaryPart::hole)
      mask[bc.part == BoundaryPart::left || bc.part == BoundaryPart::right ? 1 : 0] = false;
    VectorTools::interpolate_boundary_values(dof_handler, boundary_id_of(bc.part),
                                             Functions::ZeroFunction<2>(2), supports,
                                             ComponentMask(mask));
    supported = true;
  }
  supports.close();
  return supported;
}

} // namespace ddafem::fem
