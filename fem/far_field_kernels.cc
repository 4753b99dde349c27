#include "fem/far_field_kernels.h"

#include "common/format.h"
#include "common/input_error.h"
#include "fem/far_field_mesh.h"

#include <deal.II/base/function.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/component_mask.h>
#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace ddafem::fem
{
using namespace dealii;

double target_element_size(const FarFieldDescription& d, const double vs)
{
  if (d.element_size > 0.0)
    return d.element_size;
  const double f =
      d.max_frequency > 0.0 ? d.max_frequency : d.incident.velocity.characteristic_frequency();
  if (!(f > 0.0 && d.points_per_wavelength > 0.0))
    throw InputError("far field: element_size = 0 needs max_frequency > 0 (or an incident wave "
                     "with a frequency) and points_per_wavelength > 0 to choose the element "
                     "size");
  // points_per_wavelength counts nodes; an FE_Q(p) element spans p node intervals.
  return vs / (f * d.points_per_wavelength) * d.degree;
}

unsigned int element_intervals(const double length, const double size)
{
  return static_cast<unsigned int>(std::max(1.0, std::ceil(length / size - 1e-9)));
}

std::array<double, 2> free_field_column_point(const FarFieldDescription& d, const double h,
                                              const double y)
{
  return {{d.lower[0] + 0.5 * h, std::clamp(y, d.lower[1], d.upper[1])}};
}

FarFieldDescription free_field_column_description(const FarFieldDescription& d, const double h)
{
  FarFieldDescription c;
  c.lower = d.lower;
  c.upper = {{d.lower[0] + h, d.upper[1]}};
  c.element_size = h;
  c.degree = d.degree;
  c.density = d.density;
  c.youngs_modulus = d.youngs_modulus;
  c.poisson_ratio = d.poisson_ratio;
  c.plane_mode = d.plane_mode;
  c.incident = d.incident;
  c.dt = d.dt;
  c.integrator = d.integrator;
  c.rayleigh = d.rayleigh;
  for (const auto& bc : d.boundaries)
    if (bc.part == BoundaryPart::bottom || bc.part == BoundaryPart::top)
      c.boundaries.push_back(bc);
  c.boundaries.push_back({BoundaryPart::left, BoundaryKind::roller, 1.0, 1.0, {}});
  c.boundaries.push_back({BoundaryPart::right, BoundaryKind::roller, 1.0, 1.0, {}});
  return c;
}

void add_support_constraints(const DoFHandler<2>& dof_handler, const FarFieldDescription& d,
                             AffineConstraints<double>& constraints)
{
  // Roller: fix the component the incident wave does not move (see BoundaryKind::roller).
  const unsigned int roller_component = d.incident.type == IncidentWave::Type::sv ? 1 : 0;
  std::vector<bool> only(2, false);
  only[roller_component] = true;
  const ComponentMask roller_mask(only);
  for (const auto& bc : d.boundaries)
  {
    if (bc.kind == BoundaryKind::fixed)
      VectorTools::interpolate_boundary_values(dof_handler, boundary_id_of(bc.part),
                                               Functions::ZeroFunction<2>(2), constraints);
    else if (bc.kind == BoundaryKind::roller)
      VectorTools::interpolate_boundary_values(dof_handler, boundary_id_of(bc.part),
                                               Functions::ZeroFunction<2>(2), constraints,
                                               roller_mask);
  }
}

void elastic_cell_matrices(const FEValues<2>& values, const double rho, const double lambda,
                           const double mu, FullMatrix<double>& cell_mass,
                           FullMatrix<double>& cell_stiffness)
{
  const FiniteElement<2>& fe = values.get_fe();
  const unsigned int n = fe.n_dofs_per_cell();
  cell_mass = 0.0;
  cell_stiffness = 0.0;
  for (unsigned int i = 0; i < n; ++i)
  {
    const unsigned int ci = fe.system_to_component_index(i).first;
    for (unsigned int j = 0; j < n; ++j)
    {
      const unsigned int cj = fe.system_to_component_index(j).first;
      for (const unsigned int q : values.quadrature_point_indices())
      {
        const Tensor<1, 2> gi = values.shape_grad(i, q);
        const Tensor<1, 2> gj = values.shape_grad(j, q);
        double k = lambda * gi[ci] * gj[cj] + mu * gi[cj] * gj[ci];
        double m = 0.0;
        if (ci == cj)
        {
          k += mu * (gi * gj);
          m = rho * values.shape_value(i, q) * values.shape_value(j, q);
        }
        cell_stiffness(i, j) += k * values.JxW(q);
        cell_mass(i, j) += m * values.JxW(q);
      }
    }
  }
}

void for_each_elastic_cell(
    const DoFHandler<2>& dof_handler, const double rho, const double lambda, const double mu,
    const bool owned_only,
    const std::function<void(const std::vector<types::global_dof_index>&, const FullMatrix<double>&,
                             const FullMatrix<double>&)>& add)
{
  const FiniteElement<2>& fe = dof_handler.get_fe();
  const unsigned int n = fe.n_dofs_per_cell();
  const QGauss<2> quadrature(fe.degree + 1);
  FEValues<2> values(fe, quadrature, update_values | update_gradients | update_JxW_values);
  FullMatrix<double> cell_mass(n, n), cell_stiffness(n, n);
  std::vector<types::global_dof_index> dofs(n);
  for (const auto& cell : dof_handler.active_cell_iterators())
  {
    if (owned_only && !cell->is_locally_owned())
      continue;
    values.reinit(cell);
    elastic_cell_matrices(values, rho, lambda, mu, cell_mass, cell_stiffness);
    cell->get_dof_indices(dofs);
    add(dofs, cell_mass, cell_stiffness);
  }
}

Matrix2 normal_tangential(const double scale, const double normal, const double tangential,
                          const Tensor<1, 2>& n)
{
  Matrix2 t;
  for (unsigned int r = 0; r < 2; ++r)
    for (unsigned int c = 0; c < 2; ++c)
      t[r][c] = scale * (normal * n[r] * n[c] + tangential * ((r == c ? 1.0 : 0.0) - n[r] * n[c]));
  return t;
}

void add_face_coupling(const FEFaceValues<2>& values, const unsigned int q, const Matrix2& t,
                       FullMatrix<double>& cell)
{
  const FiniteElement<2>& fe = values.get_fe();
  for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
  {
    const unsigned int ci = fe.system_to_component_index(i).first;
    for (unsigned int j = 0; j < fe.n_dofs_per_cell(); ++j)
    {
      const unsigned int cj = fe.system_to_component_index(j).first;
      cell(i, j) += values.shape_value(i, q) * t[ci][cj] * values.shape_value(j, q) * values.JxW(q);
    }
  }
}

} // namespace ddafem::fem

namespace ddafem::fem
{
std::array<double, 2> free_field_traction(const std::array<double, 3>& stress,
                                          const std::array<double, 2>& velocity,
                                          const Tensor<1, 2>& n, const double rho, const double vp,
                                          const double vs)
{
  const double sigma[2][2] = {{stress[0], stress[2]}, {stress[2], stress[1]}};
  const double vn = velocity[0] * n[0] + velocity[1] * n[1];
  std::array<double, 2> traction{};
  for (unsigned int c = 0; c < 2; ++c)
    traction[c] = sigma[c][0] * n[0] + sigma[c][1] * n[1] +
                  rho * (vp * vn * n[c] + vs * (velocity[c] - vn * n[c]));
  return traction;
}
std::map<types::boundary_id, const BoundaryCondition*>
absorbing_parts(const FarFieldDescription& description)
{
  std::map<types::boundary_id, const BoundaryCondition*> absorbing;
  for (const BoundaryCondition& bc : description.boundaries)
    if (bc.kind == BoundaryKind::lysmer || bc.kind == BoundaryKind::input ||
        bc.kind == BoundaryKind::free_field)
      absorbing[boundary_id_of(bc.part)] = &bc;
  return absorbing;
}

bool is_free_field_part(const FarFieldDescription& description, const types::boundary_id id)
{
  return std::any_of(description.boundaries.begin(), description.boundaries.end(),
                     [id](const BoundaryCondition& bc) {
                       return bc.kind == BoundaryKind::free_field && id == boundary_id_of(bc.part);
                     });
}

unsigned int input_component(const FarFieldDescription& description)
{
  return description.incident.type == IncidentWave::Type::sv ? 0 : 1;
}

double input_traction_scale(const FarFieldDescription& description, const double vp,
                            const double vs)
{
  const bool sv = description.incident.type == IncidentWave::Type::sv;
  return 2.0 * description.density * (sv ? vs : vp);
}

void absorbing_face_matrices(const FEFaceValues<2>& values, const BoundaryCondition& bc,
                             const double rho, const double vp, const double vs,
                             const unsigned int input_component, FullMatrix<double>& cell_damping,
                             Vector<double>& cell_input)
{
  const FiniteElement<2>& fe = values.get_fe();
  cell_damping = 0.0;
  cell_input = 0.0;
  for (const unsigned int q : values.quadrature_point_indices())
  {
    add_face_coupling(values, q,
                      normal_tangential(rho, bc.a * vp, bc.b * vs, values.normal_vector(q)),
                      cell_damping);
    for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
      if (bc.kind == BoundaryKind::input &&
          fe.system_to_component_index(i).first == input_component)
        cell_input(i) += values.shape_value(i, q) * values.JxW(q);
  }
}

} // namespace ddafem::fem
