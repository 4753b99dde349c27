// Shi's DDA submatrices as pure functions of block geometry and material (Shi 1988;
// docs/reference/physics.md section 1). All are 6x6 in the block unknowns
// d = (u0, v0, r0, ex, ey, gxy) about the block centroid.
#pragma once

#include "dda/geometry.h"
#include "dda/model_description.h"
#include "dda/types.h"

namespace ddafem::dda
{
/// Shi's displacement matrix at (x, y) for a block with centroid c:
/// T = [1 0 -(y-y0) (x-x0) 0 (y-y0)/2; 0 1 (x-x0) 0 (y-y0) (x-x0)/2]. Inline: it sits in the
/// loops over every vertex and joint point of every step.
inline Matrix26 displacement_matrix(const Point& centroid, const Point& x)
{
  const double dx = x.x() - centroid.x();
  const double dy = x.y() - centroid.y();
  Matrix26 t;
  t << 1.0, 0.0, -dy, dx, 0.0, 0.5 * dy, //
      0.0, 1.0, dx, 0.0, dy, 0.5 * dx;
  return t;
}

/// T(x) d without forming T [m]: the additions of displacement_matrix(centroid, x) * d in its
/// order, its zero terms left out (the same bits; tests/dda/test_submatrices.cc).
inline Vector2 displacement_at(const Point& centroid, const Point& x, const Vector6& d)
{
  const double dx = x.x() - centroid.x();
  const double dy = x.y() - centroid.y();
  return Vector2(((d[0] + (-dy) * d[2]) + dx * d[3]) + (0.5 * dy) * d[5],
                 ((d[1] + dx * d[2]) + dy * d[4]) + (0.5 * dx) * d[5]);
}

/// Consistent mass matrix rho * integral of T^T T dA [kg, kg m, kg m^2], exact from the polygon's
/// area and central second moments (first moments vanish about the centroid).
Matrix6 mass_matrix(const PolygonMoments& moments, double density);

/// Plane stress or plane strain elasticity matrix C [Pa] in Voigt order (xx, yy, xy) with
/// engineering shear strain: sigma = C epsilon.
Eigen::Matrix3d elasticity_matrix(double youngs_modulus, double poisson_ratio, PlaneMode mode);

/// Elastic stiffness: area * C on the strain unknowns (ex, ey, gxy) [N/m]; zero elsewhere.
Matrix6 elastic_stiffness(double area, const Eigen::Matrix3d& elasticity);

/// Generalized force of a stress already in the block: -area * sigma on the strain unknowns
/// [N m] (the block's internal force that the step must balance).
Vector6 stress_force(double area, const Voigt& stress);

/// Generalized force of a uniform body acceleration g [m/s^2]: rho * area * g on (u0, v0).
Vector6 body_force(double area, double density, const Vector2& gravity);

/// Stiffness of a spring matrix k2 (2x2, [N/m]) that acts on the displacement T d of a point:
/// T^T k2 T.
Matrix6 point_spring_stiffness(const Matrix26& t, const Eigen::Matrix2d& k2);

} // namespace ddafem::dda
