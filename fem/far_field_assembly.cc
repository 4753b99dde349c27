// ElasticWaveModel matrices: mass, stiffness, Lysmer damping, boundary springs, the input load
// shape, and the effective matrix P = K + gamma/(beta dt) C + 1/(beta dt^2) M factorized per dt.
#include "fem/elastic_wave_model_impl.h"

#include "common/newmark.h"
#include "fem/far_field_kernels.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace ddafem::fem
{
using namespace far_field_detail;

void ElasticWaveModel::Impl::assemble_matrices()
{
  DynamicSparsityPattern dsp(dof_handler.n_dofs());
  DoFTools::make_sparsity_pattern(dof_handler, dsp);
  constraints.condense(dsp); // room for the condensed effective matrix (hanging nodes)
  sparsity.copy_from(dsp);
  mass.reinit(sparsity);
  stiffness.reinit(sparsity);
  SparseMatrix<double> full_damping(sparsity);
  input_shape.reinit(dof_handler.n_dofs());
  assemble_domain();
  assemble_boundary(full_damping);
  store_damping(full_damping);
}

void ElasticWaveModel::Impl::assemble_domain()
{
  // Consistent mass and plane elastic stiffness (deal.II step-8 form).
  for_each_elastic_cell(dof_handler, description.density, elasticity.lambda, elasticity.mu, false,
                        [&](const std::vector<types::global_dof_index>& dofs,
                            const FullMatrix<double>& cell_mass,
                            const FullMatrix<double>& cell_stiffness)
                        {
                          mass.add(dofs, cell_mass);
                          stiffness.add(dofs, cell_stiffness);
                        });
}

void ElasticWaveModel::Impl::assemble_boundary(SparseMatrix<double>& full_damping)
{
  // Lysmer dashpots on lysmer, input and free_field parts (absorbing_face_matrices); the input
  // traction shape on input parts; boundary springs where a part has them.
  const auto absorbing = absorbing_parts(description);
  const double rho = description.density;
  const unsigned int component = input_component(description);
  input_scale = input_traction_scale(description, vp, vs);

  const unsigned int n = fe.n_dofs_per_cell();
  const QGauss<1> face_quadrature(fe.degree + 1);
  FEFaceValues<2> face_values(fe, face_quadrature,
                              update_values | update_normal_vectors | update_JxW_values);
  FEFaceValues<2> spring_values(fe, face_quadrature,
                                update_values | update_normal_vectors | update_JxW_values |
                                    update_quadrature_points);
  FullMatrix<double> cell_damping(n, n), cell_springs(n, n);
  Vector<double> cell_input(n);
  std::vector<types::global_dof_index> dofs(n);
  for (const auto& cell : dof_handler.active_cell_iterators())
    for (const unsigned int f : cell->face_indices())
    {
      if (!cell->face(f)->at_boundary())
        continue;
      const auto found = absorbing.find(cell->face(f)->boundary_id());
      if (found == absorbing.end())
        continue;
      const BoundaryCondition& bc = *found->second;
      face_values.reinit(cell, f);
      absorbing_face_matrices(face_values, bc, rho, vp, vs, component, cell_damping, cell_input);
      cell->get_dof_indices(dofs);
      full_damping.add(dofs, cell_damping);
      if (bc.springs.enabled)
      {
        spring_values.reinit(cell, f);
        assemble_face_springs(spring_values, bc, cell_springs);
        stiffness.add(dofs, cell_springs); // its energy counts as strain energy
      }
      for (unsigned int i = 0; i < n; ++i)
        input_shape(dofs[i]) += cell_input(i);
    }
}

void ElasticWaveModel::Impl::assemble_face_springs(const FEFaceValues<2>& values,
                                                   const BoundaryCondition& bc,
                                                   FullMatrix<double>& cell_springs) const
{
  cell_springs = 0.0;
  for (const unsigned int q : values.quadrature_point_indices())
  {
    const Point<2> x = values.quadrature_point(q);
    const double r = std::hypot(x[0] - bc.springs.center[0], x[1] - bc.springs.center[1]);
    require(r > 1e-6 * h, std::string("boundary part '") + name_of(bc.part) +
                              "': the springs' center lies on the part, expected the "
                              "wave source's position inside the far field");
    add_face_coupling(values, q,
                      normal_tangential(elasticity.mu / r, bc.springs.alpha_n, bc.springs.alpha_t,
                                        values.normal_vector(q)),
                      cell_springs);
  }
}

void ElasticWaveModel::Impl::store_damping(const SparseMatrix<double>& full_damping)
{
  // C lives on the boundary: a pattern of its own keeps its products cheap.
  DynamicSparsityPattern boundary_dsp(dof_handler.n_dofs());
  for (std::size_t row = 0; row < full_damping.m(); ++row)
    for (auto entry = full_damping.begin(row); entry != full_damping.end(row); ++entry)
      if (entry->value() != 0.0)
        boundary_dsp.add(row, entry->column());
  damping_sparsity.copy_from(boundary_dsp);
  damping.reinit(damping_sparsity);
  for (std::size_t row = 0; row < full_damping.m(); ++row)
    for (auto entry = full_damping.begin(row); entry != full_damping.end(row); ++entry)
      if (entry->value() != 0.0)
        damping.set(row, entry->column(), entry->value());
}

void ElasticWaveModel::Impl::input_force(const double time, Vector<double>& f) const
{
  f = input_shape;
  f *= input_scale * description.incident.velocity.value(time);
}

void ElasticWaveModel::Impl::condense_rhs(Vector<double>& rhs) const
{
  constraints.condense(rhs);
}

void ElasticWaveModel::Impl::damping_vmult(Vector<double>& out, const Vector<double>& x) const
{
  damping.vmult(out, x);
  const RayleighDamping& r = description.rayleigh;
  if (r.alpha == 0.0 && r.beta == 0.0)
    return;
  Vector<double> product(x.size());
  if (r.alpha > 0.0)
  {
    mass.vmult(product, x);
    out.add(r.alpha, product);
  }
  if (r.beta > 0.0)
  {
    stiffness.vmult(product, x);
    out.add(r.beta, product);
  }
}

void ElasticWaveModel::Impl::factorize(const double dt)
{
  const NewmarkCoefficients newmark = newmark_coefficients(beta, gamma, dt);
  const double c_mass = newmark.mass_u;
  const double c_damping = newmark.damping_u;
  auto f = std::make_unique<Factorization>();
  SparseMatrix<double>& effective = f->matrix;
  effective.reinit(sparsity);
  effective.copy_from(stiffness);
  effective.add(c_mass + c_damping * description.rayleigh.alpha, mass);
  if (description.rayleigh.beta > 0.0)
    effective.add(c_damping * description.rayleigh.beta, stiffness);
  for (std::size_t row = 0; row < damping.m(); ++row)
    for (auto entry = damping.begin(row); entry != damping.end(row); ++entry)
      effective.add(row, entry->column(), c_damping * entry->value());
  // Point springs: N^T K N couples the DOFs of each spring's cell.
  for (const SpringPoint& sp : springs)
    for (std::size_t i = 0; i < sp.dofs.size(); ++i)
      for (std::size_t j = 0; j < sp.dofs.size(); ++j)
        effective.add(sp.dofs[i], sp.dofs[j],
                      sp.phi[i] * sp.k[sp.component[i]][sp.component[j]] * sp.phi[j]);
  // Constrained rows and columns (fixed, roller, hanging nodes) condensed out; their rows keep
  // a diagonal entry and a zero right-hand side, and distribute() restores them.
  constraints.condense(effective);
  f->solver = make_effective_solver(description.solver, description.direct_solver,
                                    description.solver_tolerance);
  f->solver->initialize(effective);
  factorizations.insert(dt, std::move(f));
  ++timings.n_factorizations;
}

void ElasticWaveModel::Impl::forget_factorizations()
{
  factorizations.clear();
}

} // namespace ddafem::fem
