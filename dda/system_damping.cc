// The rock's dashpots in the step (dda/damping.h): each block's dashpot on its strain rates, the
// bonded joints' and the closed contacts' dashpots on the relative velocity, all on Newmark's end
// velocity v1 = velocity_factor d + offset (common/newmark.h), and the work they do.
#include "dda/system.h"

#include "common/newmark.h"
#include "dda/submatrices.h"

namespace ddafem::dda
{
void System::prepare_dashpots(double dt)
{
  dashpots.velocity_factor = 0.0;
  if (!materials.damped || mode != StageMode::dynamic)
    return;
  const double beta = scheme.coefficients.beta, gamma = scheme.coefficients.gamma;
  dashpots.velocity_factor = newmark_coefficients(beta, gamma, dt).damping_u;
  dashpots.offsets.resize(blocks.size());
  dashpots.start.resize(blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i)
  {
    // Bathe's second half: the equivalent start state of backward_euler_start.
    const KinematicState s = step_start(i, dt);
    dashpots.offsets[i] =
        newmark_velocity_offset<Vector6>(beta, gamma, dt, s.velocity, s.acceleration);
    dashpots.start[i] = blocks[i].velocity;
  }
}

void System::add_work_of_damping(const Eigen::VectorXd& d)
{
  // The dashpots' force -C v on the step's displacement, v the mean of the start and end
  // velocities (exact for the trapezoidal rule) [J]; negative: absorbed.
  if (dashpots.velocity_factor == 0.0)
    return;
  std::vector<Vector6> mean(blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i)
    mean[i] = 0.5 * (dashpots.start[i] + dashpots.velocity_factor * d.segment<6>(6 * i) +
                     dashpots.offsets[i]);
  for (std::size_t i = 0; i < blocks.size(); ++i)
  {
    const double beta = dashpot_factor(dashpots, model.materials[blocks[i].material].damping);
    if (beta > 0.0)
      ledger.damping -= beta * (elastic_stiffness(linearisation_moments(blocks[i]).area,
                                                  materials.elasticity[blocks[i].material]) *
                                mean[i])
                                   .dot(d.segment<6>(6 * i));
  }
  bonded.add_work_of_damping(*this, model, dashpots, mean, d, ledger.damping);
  contact_set.add_work_of_damping(ledger.damping, mean, d, dashpots);
}

} // namespace ddafem::dda
