// The rock's dashpots in the step (dda/damping.h): each block's dashpot on its strain rates, the
// bonded joints' and the closed contacts' dashpots on the relative velocity, all on Newmark's end
// velocity v1 = velocity_factor d + offset (common/newmark.h), and the work of the blocks' own.
#include "common/newmark.h"
#include "dda/block_set.h"
#include "dda/damping.h"
#include "dda/step_scheme.h"
#include "dda/submatrices.h"

namespace ddafem::dda
{
void StepDashpots::prepare(const BlockSet& blocks, const StepScheme& scheme, double dt, bool active)
{
  velocity_factor = 0.0;
  if (!active)
    return;
  const double beta = scheme.coefficients.beta, gamma = scheme.coefficients.gamma;
  velocity_factor = newmark_coefficients(beta, gamma, dt).damping_u;
  offsets.resize(blocks.list.size());
  start.resize(blocks.list.size());
  for (std::size_t i = 0; i < blocks.list.size(); ++i)
  {
    const KinematicState s = scheme.start(blocks.list[i], i, dt);
    offsets[i] = newmark_velocity_offset<Vector6>(beta, gamma, dt, s.velocity, s.acceleration);
    start[i] = blocks.list[i].velocity;
  }
}

std::vector<Vector6> StepDashpots::mean_velocities(const Eigen::VectorXd& d) const
{
  if (velocity_factor == 0.0)
    return {};
  std::vector<Vector6> mean(offsets.size());
  for (std::size_t i = 0; i < mean.size(); ++i)
    mean[i] = 0.5 * (start[i] + velocity_factor * d.segment<6>(6 * i) + offsets[i]);
  return mean;
}

void StepDashpots::add_work_of_blocks(const BlockSet& blocks, const ModelDescription& model,
                                      const std::vector<Vector6>& mean, const Eigen::VectorXd& d,
                                      double& work) const
{
  for (std::size_t i = 0; i < blocks.list.size(); ++i)
  {
    const Block& b = blocks.list[i];
    const double beta = dashpot_factor(*this, model.materials[b.material].damping);
    if (beta > 0.0)
      work -= beta * (elastic_stiffness(blocks.linearisation_moments(b).area,
                                        blocks.materials.elasticity[b.material]) *
                      mean[i])
                         .dot(d.segment<6>(6 * i));
  }
}

} // namespace ddafem::dda
