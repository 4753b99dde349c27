#include "dda/integrator.h"

#include <algorithm>
#include <tuple>

namespace ddafem::dda
{
IntegratorCoefficients integrator_coefficients(Integrator integrator, double spectral_radius)
{
  IntegratorCoefficients c;
  switch (integrator)
  {
  case Integrator::dda:
    break;
  case Integrator::newmark_trapezoidal:
    c.beta = 0.25;
    c.gamma = 0.5;
    break;
  case Integrator::bathe: // its first half step
  case Integrator::generalized_alpha:
  {
    const double rho = std::clamp(integrator == Integrator::bathe ? bathe_first_half_spectral_radius
                                                                  : spectral_radius,
                                  0.0, 1.0);
    c.alpha_m = (2.0 * rho - 1.0) / (rho + 1.0);
    c.alpha_f = rho / (rho + 1.0);
    c.gamma = 0.5 - c.alpha_m + c.alpha_f;
    c.beta = 0.25 * (1.0 - c.alpha_m + c.alpha_f) * (1.0 - c.alpha_m + c.alpha_f);
    break;
  }
  }
  return c;
}

IntegratorCoefficients backward_euler_half_coefficients()
{
  IntegratorCoefficients c;
  c.beta = 4.0 / 9.0;
  c.gamma = 2.0 / 3.0;
  return c;
}

Vector6 inertia_force(const IntegratorCoefficients& c, const Matrix6& mass,
                      const KinematicState& start, double dt)
{
  const Vector6 predictor = (1.0 - c.alpha_m) * (start.velocity / (c.beta * dt) +
                                                 (0.5 / c.beta - 1.0) * start.acceleration) -
                            c.alpha_m * start.acceleration;
  return (mass * predictor + c.alpha_f * start.force) / (1.0 - c.alpha_f);
}

KinematicState advance_state(const IntegratorCoefficients& c, const Matrix6& mass,
                             const KinematicState& start, const Vector6& d, double dt)
{
  KinematicState end;
  std::tie(end.acceleration, end.velocity) =
      newmark_end<Vector6>(c, dt, d, start.velocity, start.acceleration);
  const Vector6 inertia =
      mass * ((1.0 - c.alpha_m) * end.acceleration + c.alpha_m * start.acceleration);
  end.force = (inertia - c.alpha_f * start.force) / (1.0 - c.alpha_f);
  return end;
}

} // namespace ddafem::dda
