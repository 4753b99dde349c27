#include "dda/submatrices.h"

namespace ddafem::dda
{
Matrix6 mass_matrix(const PolygonMoments& moments, double density)
{
  // rho * integral of T^T T dA with T's rows r1 = (1, 0, -dy, dx, 0, dy/2) and
  // r2 = (0, 1, dx, 0, dy, dx/2), dx = x - x0, dy = y - y0. The first moments vanish about the
  // centroid, leaving S = area and the central second moments Sxx, Syy, Sxy.
  const double s = moments.area, sxx = moments.sxx, syy = moments.syy, sxy = moments.sxy;
  Matrix6 m;
  m << s, 0, 0, 0, 0, 0,                             //
      0, s, 0, 0, 0, 0,                              //
      0, 0, sxx + syy, -sxy, sxy, 0.5 * (sxx - syy), //
      0, 0, -sxy, sxx, 0, 0.5 * sxy,                 //
      0, 0, sxy, 0, syy, 0.5 * sxy,                  //
      0, 0, 0.5 * (sxx - syy), 0.5 * sxy, 0.5 * sxy, 0.25 * (sxx + syy);
  return density * m;
}

Eigen::Matrix3d elasticity_matrix(double youngs_modulus, double poisson_ratio, PlaneMode mode)
{
  const double e = youngs_modulus, nu = poisson_ratio;
  Eigen::Matrix3d c;
  if (mode == PlaneMode::stress)
  {
    const double f = e / (1.0 - nu * nu);
    c << f, f * nu, 0.0, //
        f * nu, f, 0.0,  //
        0.0, 0.0, f * 0.5 * (1.0 - nu);
  }
  else
  {
    const double f = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
    c << f * (1.0 - nu), f * nu, 0.0, //
        f * nu, f * (1.0 - nu), 0.0,  //
        0.0, 0.0, f * 0.5 * (1.0 - 2.0 * nu);
  }
  return c;
}

Matrix6 elastic_stiffness(double area, const Eigen::Matrix3d& elasticity)
{
  Matrix6 k = Matrix6::Zero();
  k.block<3, 3>(3, 3) = area * elasticity;
  return k;
}

Vector6 stress_force(double area, const Voigt& stress)
{
  Vector6 f = Vector6::Zero();
  f.segment<3>(3) = -area * stress;
  return f;
}

Vector6 body_force(double area, double density, const Vector2& gravity)
{
  Vector6 f = Vector6::Zero();
  f.head<2>() = density * area * gravity;
  return f;
}

Matrix6 point_spring_stiffness(const Matrix26& t, const Eigen::Matrix2d& k2)
{
  return t.transpose() * k2 * t;
}

} // namespace ddafem::dda
