// Pieces both far fields build from, the serial ElasticWaveModel and the distributed
// DistributedWaveModel (issue 22), so that they assemble the same numbers: the element size, the
// supports' constraints, the cell matrices of plane elasticity and the boundary couplings of
// Lysmer dashpots and springs.
#pragma once

#include "fem/far_field_description.h"

#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <array>
#include <cstddef>
#include <functional>
#include <map>
#include <utility>
#include <vector>

namespace ddafem::fem
{
/// The element size [m] the generated meshes aim at: `element_size`, or (0) the nodes per S
/// wavelength at max_frequency (or the incident wave's frequency), an FE_Q(p) element spanning
/// p node intervals. Throws InputError when neither is given.
double target_element_size(const FarFieldDescription& description, double vs);

/// Elements of at most `size` along `length`: ceil(length / size), at least 1.
unsigned int element_intervals(double length, double size);

/// The 1D free-field column beside a far field with free_field sides: one element of h [m]
/// wide, the far field's material, base and top, rollers on its sides.
FarFieldDescription free_field_column_description(const FarFieldDescription& description, double h);

/// Where the column of free_field_column_description(description, h) is read for height y [m]:
/// its middle, x = lower x + h / 2, at y within the model's base and top.
std::array<double, 2> free_field_column_point(const FarFieldDescription& description, double h,
                                              double y);

/// The constraints of the supports: `fixed` parts both components zero, `roller` parts the
/// component the incident wave does not move (BoundaryKind::roller). `constraints` is not closed.
void add_support_constraints(const dealii::DoFHandler<2>& dof_handler,
                             const FarFieldDescription& description,
                             dealii::AffineConstraints<double>& constraints);

/// Consistent mass (density rho [kg/m^3]) and plane elastic stiffness (Lame lambda, mu [Pa]) of
/// the cell `values` was reinit'd on (deal.II step-8 form); both are overwritten.
void elastic_cell_matrices(const dealii::FEValues<2>& values, double rho, double lambda, double mu,
                           dealii::FullMatrix<double>& cell_mass,
                           dealii::FullMatrix<double>& cell_stiffness);

/// Calls add(dofs, cell_mass, cell_stiffness) for each active cell of `dof_handler` (only the
/// locally owned ones if `owned_only`) with its elastic_cell_matrices (rho [kg/m^3], Lame lambda,
/// mu [Pa]; Gauss quadrature of degree + 1 points) and its dof indices, cell after cell.
void for_each_elastic_cell(
    const dealii::DoFHandler<2>& dof_handler, double rho, double lambda, double mu, bool owned_only,
    const std::function<void(const std::vector<dealii::types::global_dof_index>&,
                             const dealii::FullMatrix<double>&, const dealii::FullMatrix<double>&)>&
        add);

using Matrix2 = std::array<std::array<double, 2>, 2>;

/// scale (normal n n^T + tangential (I - n n^T)) for a unit normal n: Lysmer dashpots
/// (scale rho, normal a VP, tangential b VS) [N s/m^3] and boundary springs (scale G / R,
/// normal alpha_n, tangential alpha_t) [N/m^3].
Matrix2 normal_tangential(double scale, double normal, double tangential,
                          const dealii::Tensor<1, 2>& n);

/// cell(i, j) += N_i T[c_i][c_j] N_j JxW at face quadrature point q.
void add_face_coupling(const dealii::FEFaceValues<2>& values, unsigned int q, const Matrix2& t,
                       dealii::FullMatrix<double>& cell);

/// The boundary parts Lysmer dashpots absorb on (lysmer, input and free_field), by boundary id.
std::map<dealii::types::boundary_id, const BoundaryCondition*>
absorbing_parts(const FarFieldDescription& description);

/// Whether a face with this boundary id lies on a free_field part of `description`.
bool is_free_field_part(const FarFieldDescription& description, dealii::types::boundary_id id);

/// The displacement component the incident wave drives: x (0) for an SV wave, y (1) for P.
unsigned int input_component(const FarFieldDescription& description);

/// The scale of the input traction on input parts, 2 rho V [N s/m^3] with V the incident wave's
/// speed (VS for an SV wave, VP for P): times the incident velocity [m/s] it gives the traction
/// [Pa] that sends the wave in through Lysmer's dashpots. Density rho [kg/m^3], speeds [m/s].
double input_traction_scale(const FarFieldDescription& description, double vp, double vs);

/// A face of an absorbing part (`values` reinit'd on it): its Lysmer dashpots
/// D = rho (a VP n n^T + b VS (I - n n^T)) [N s/m^3] in `cell_damping`, and on an input part the
/// shape of the input traction, int N_i dS over the input component's shape functions, in
/// `cell_input` [m]; both are overwritten. Density rho [kg/m^3], wave speeds [m/s].
void absorbing_face_matrices(const dealii::FEFaceValues<2>& values, const BoundaryCondition& bc,
                             double rho, double vp, double vs, unsigned int input_component,
                             dealii::FullMatrix<double>& cell_damping,
                             dealii::Vector<double>& cell_input);

/// The free-field traction on a side with outward unit normal n: sigma_ff n + D v_ff,
/// D = rho (VP n n^T + VS (I - n n^T)), from the column's stress (sxx, syy, sxy) [Pa] and
/// velocity [m/s] there; density rho [kg/m^3], wave speeds [m/s]. [Pa]
std::array<double, 2> free_field_traction(const std::array<double, 3>& stress,
                                          const std::array<double, 2>& velocity,
                                          const dealii::Tensor<1, 2>& n, double rho, double vp,
                                          double vs);

/// Adds to `work` [J] the work of point springs' forces on the far field over a step, with
/// mid-step forces: F = q - K w, K = springs[k].k (2 x 2 [N/m]) per spring, w the displacements
/// at the springs at the step's start (w_old) and end (w_new) [m], q the point loads [N] (2m
/// each). `force` holds F at the step's start and gets F at its end.
template <class Springs>
void add_spring_work_of_step(const Springs& springs, const std::vector<double>& q,
                             const std::vector<double>& w_old, const std::vector<double>& w_new,
                             std::vector<double>& force, double& work)
{
  std::vector<double> f_new(q);
  for (std::size_t k = 0; k < springs.size(); ++k)
    for (unsigned int r = 0; r < 2; ++r)
      for (unsigned int c = 0; c < 2; ++c)
        f_new[2 * k + r] -= springs[k].k[r][c] * w_new[2 * k + c];
  for (std::size_t i = 0; i < f_new.size(); ++i)
    work += 0.5 * (force[i] + f_new[i]) * (w_new[i] - w_old[i]);
  force = std::move(f_new);
}

} // namespace ddafem::fem
