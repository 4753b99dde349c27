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

#include <array>

namespace ddafem::fem
{
/// The element size [m] the generated meshes aim at: `element_size`, or (0) the nodes per S
/// wavelength at max_frequency (or the incident wave's frequency), an FE_Q(p) element spanning
/// p node intervals. Throws InputError when neither is given.
double target_element_size(const FarFieldDescription& description, double vs);

/// Elements of at most `size` along `length`: ceil(length / size), at least 1.
unsigned int element_intervals(double length, double size);

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

using Matrix2 = std::array<std::array<double, 2>, 2>;

/// scale (normal n n^T + tangential (I - n n^T)) for a unit normal n: Lysmer dashpots
/// (scale rho, normal a VP, tangential b VS) [N s/m^3] and boundary springs (scale G / R,
/// normal alpha_n, tangential alpha_t) [N/m^3].
Matrix2 normal_tangential(double scale, double normal, double tangential,
                          const dealii::Tensor<1, 2>& n);

/// cell(i, j) += N_i T[c_i][c_j] N_j JxW at face quadrature point q.
void add_face_coupling(const dealii::FEFaceValues<2>& values, unsigned int q, const Matrix2& t,
                       dealii::FullMatrix<double>& cell);

} // namespace ddafem::fem
