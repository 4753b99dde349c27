// Small fixed-size algebra types used throughout the DDA module (Eigen).
#pragma once

#include <Eigen/Core>

namespace ddafem::dda
{
using Point = Eigen::Vector2d;   ///< position (x, y) [m]
using Vector2 = Eigen::Vector2d; ///< a 2D vector (force [N], velocity [m/s], ...)
/// Block unknowns d = (u0, v0, r0, ex, ey, gxy): translation of the centroid [m], rotation
/// [rad], normal strains and engineering shear strain [-]. Also used for velocities (per s),
/// accelerations (per s^2) and generalized forces.
using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;
/// Shi's displacement matrix T(x, y): u(x, y) = T d.
using Matrix26 = Eigen::Matrix<double, 2, 6>;
/// Stress or strain in Voigt order (xx, yy, xy); stress [Pa], tension positive; strain uses the
/// engineering shear strain gamma_xy.
using Voigt = Eigen::Vector3d;

} // namespace ddafem::dda
