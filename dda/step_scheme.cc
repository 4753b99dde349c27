// The integrator's form of each step (System::choose_step_scheme): generalized-alpha and the
// Newmark schemes take one form throughout; Bathe's composite scheme alternates a
// generalized-alpha first half and a three-point backward Euler second half (dda/integrator.h).
#include "dda/system.h"

#include <Eigen/Cholesky>

#include <stdexcept>
#include <tuple>

namespace ddafem::dda
{
void System::choose_step_scheme(double dt, const StepPart part)
{
  const Integrator integrator = model.time.integrator;
  // A static stage has no motion to integrate: it takes every part as a full step.
  const bool dynamic = mode == StageMode::dynamic;
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
    step_integration = integrator_coefficients(Integrator::dda, 0.0);
  else if (dynamic && part == StepPart::second_half)
  {
    second_half = true;
    step_integration = backward_euler_half_coefficients();
  }
  else
    step_integration = integration;
}

KinematicState System::step_start(std::size_t i, double dt) const
{
  const Block& b = blocks[i];
  if (!second_half)
    return {b.velocity, b.acceleration, b.force};
  const FirstHalf& h = first_halves[i];
  KinematicState s;
  std::tie(s.velocity, s.acceleration) =
      backward_euler_start<Vector6>(dt, h.start_velocity, b.velocity, h.displacement);
  return s; // alpha_f = 0: r_n does not enter
}

Vector6 System::composite_acceleration(std::size_t i, const Matrix6& m, const KinematicState& end)
{
  if (model.time.integrator != Integrator::bathe || mode != StageMode::dynamic)
    return end.acceleration;
  if (!second_half)
  {
    first_halves[i].mid_force = end.force;
    return end.acceleration;
  }
  const double alpha_f = integration.alpha_f;
  return m.ldlt().solve((1.0 - alpha_f) * end.force + alpha_f * first_halves[i].mid_force);
}

void System::record_half(double dt, const Eigen::VectorXd& d)
{
  const bool opens =
      model.time.integrator == Integrator::bathe && mode == StageMode::dynamic && !second_half;
  open_half = opens ? dt : 0.0;
  if (!opens)
    return;
  first_halves.resize(blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i)
    first_halves[i] = {blocks[i].velocity, d.segment<6>(6 * i)};
}

} // namespace ddafem::dda
