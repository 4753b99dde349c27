#include "dda/step_scheme.h"

#include <Eigen/Cholesky>

#include <stdexcept>
#include <tuple>

namespace ddafem::dda
{
void StepScheme::set_up(const Integrator integrator_, const double spectral_radius)
{
  integrator = integrator_;
  integration = integrator_coefficients(integrator, spectral_radius);
}

void StepScheme::choose(double dt, const StepPart part, const bool dynamic)
{
  // A static stage has no motion to integrate: it takes every part as a full step.
  if (dynamic && (integrator == Integrator::bathe) == (part == StepPart::full))
    throw std::logic_error(part == StepPart::full
                               ? "Bathe's scheme takes half steps in a dynamic stage"
                               : "only Bathe's scheme takes half steps in a dynamic stage");
  if (dynamic && part == StepPart::second_half && open_half != dt)
    throw std::logic_error("a second half step without a first half of the same dt");
  second_half = false;
  // With a and r unknown, DDA's scheme (in which neither enters) starts the motion.
  if (motion_starts &&
      (integrator == Integrator::generalized_alpha || integrator == Integrator::bathe))
    coefficients = integrator_coefficients(Integrator::dda, 0.0);
  else if (dynamic && part == StepPart::second_half)
  {
    second_half = true;
    coefficients = backward_euler_half_coefficients();
  }
  else
    coefficients = integration;
}

KinematicState StepScheme::start(const Block& b, std::size_t i, double dt) const
{
  if (!second_half)
    return {b.velocity, b.acceleration, b.force};
  const FirstHalf& h = first_halves[i];
  KinematicState s;
  std::tie(s.velocity, s.acceleration) =
      backward_euler_start<Vector6>(dt, h.start_velocity, b.velocity, h.displacement);
  return s; // alpha_f = 0: r_n does not enter
}

Vector6 StepScheme::composite_acceleration(std::size_t i, const Matrix6& m,
                                           const KinematicState& end, const bool dynamic)
{
  if (integrator != Integrator::bathe || !dynamic)
    return end.acceleration;
  if (!second_half)
  {
    first_halves[i].mid_force = end.force;
    return end.acceleration;
  }
  const double alpha_f = integration.alpha_f;
  return m.ldlt().solve((1.0 - alpha_f) * end.force + alpha_f * first_halves[i].mid_force);
}

void StepScheme::record_half(double dt, const Eigen::VectorXd& d, const std::vector<Block>& blocks,
                             const bool dynamic)
{
  const bool opens = integrator == Integrator::bathe && dynamic && !second_half;
  open_half = opens ? dt : 0.0;
  if (!opens)
    return;
  first_halves.resize(blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i)
    first_halves[i] = {blocks[i].velocity, d.segment<6>(6 * i)};
}

double StepScheme::start_force_lag() const
{
  // Bathe's second half starts from velocities alone (backward_euler_start).
  return second_half ? 0.0 : coefficients.start_force_lag();
}

void StepScheme::undo_friction_jumps(std::vector<Block>& blocks)
{
  for (const StateBeforeJump& s : friction_jumps)
  {
    blocks[s.block].acceleration = s.acceleration;
    blocks[s.block].force = s.force;
  }
  friction_jumps.clear();
}

} // namespace ddafem::dda
