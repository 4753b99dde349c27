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
  if (!damped || mode != StageMode::dynamic)
    return;
  const double beta = step_integration.beta, gamma = step_integration.gamma;
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

double System::dashpot_factor(const RockDamping& damping) const
{
  return dashpots.velocity_factor > 0.0 ? damping.stiffness_factor() : 0.0;
}

Eigen::Matrix2d System::contact_dashpot(const Contact& c, const ContactFrame& f) const
{
  // From the joint material's springs, not the penalty raised on penetration; normal while
  // closed, shear only while it sticks (never on a sliding contact's slip). Only over a step
  // that the contact spends in that state from its start: a contact that closes within the step
  // (an impact) would otherwise be stopped by its dashpot before it touches (the gap still
  // open at the end, the trial opening it again, the iteration never settling), and a
  // sliding contact that sticks within the step likewise.
  const JointMaterial& jm = model.joint_materials[c.joint_material];
  const double beta = dashpot_factor(jm.damping);
  Eigen::Matrix2d cd = Eigen::Matrix2d::Zero();
  if (beta == 0.0 || c.trial.state == ContactState::open || c.forces.state == ContactState::open)
    return cd;
  cd = beta * jm.normal_stiffness * (f.normal * f.normal.transpose());
  if (c.trial.state == ContactState::lock && c.forces.state == ContactState::lock)
    cd += beta * jm.shear_ratio * jm.normal_stiffness * (f.tangent * f.tangent.transpose());
  return cd;
}

void System::add_contact_dashpot(const Contact& c, const ContactFrame& f, Eigen::Matrix2d& k2,
                                 Vector2& force_on_vertex) const
{
  const Eigen::Matrix2d cd = contact_dashpot(c, f);
  if (cd.isZero(0.0))
    return;
  k2 += dashpots.velocity_factor * cd;
  force_on_vertex -= cd * (f.t_vertex * dashpots.offsets[c.vertex_block] -
                           f.t_edge * dashpots.offsets[c.edge_block]);
}

double System::viscous_shear(std::size_t k) const
{
  // The shear force of the dashpot a sticking contact has over this step (contact_dashpot's
  // rule: locked at the start), at the end velocity of the solution being tried.
  const Contact& c = contact_set.trial[k];
  if (c.forces.state != ContactState::lock)
    return 0.0;
  const JointMaterial& jm = model.joint_materials[c.joint_material];
  const double beta = dashpot_factor(jm.damping);
  if (beta == 0.0)
    return 0.0;
  const ContactFrame& f = contact_set.frames[k];
  const Vector2 velocity =
      f.t_vertex * (dashpots.velocity_factor * solution.segment<6>(6 * c.vertex_block) +
                    dashpots.offsets[c.vertex_block]) -
      f.t_edge * (dashpots.velocity_factor * solution.segment<6>(6 * c.edge_block) +
                  dashpots.offsets[c.edge_block]);
  return beta * jm.shear_ratio * jm.normal_stiffness * f.tangent.dot(velocity);
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
    const double beta = dashpot_factor(model.materials[blocks[i].material].damping);
    if (beta > 0.0)
      work_of_damping -= beta * (elastic_stiffness(linearisation_moments(blocks[i]).area,
                                                   elasticity[blocks[i].material]) *
                                 mean[i])
                                    .dot(d.segment<6>(6 * i));
  }
  for (const Joint& j : joints)
  {
    const JointMaterial& jm = model.joint_materials[j.joint_material];
    const double beta = dashpot_factor(jm.damping);
    if (beta == 0.0)
      continue;
    const Vector2 tangent = j.tangent(small_displacement());
    const Eigen::Matrix2d c = beta * joint_spring_matrix(jm, Joint::normal_of(tangent), tangent);
    for (const JointPoint& p : j.points)
    {
      const Vector2 v =
          point_displacement(p.on_b, mean[j.block_b]) - point_displacement(p.on_a, mean[j.block_a]);
      const Vector2 du = point_displacement(p.on_b, d.segment<6>(6 * j.block_b)) -
                         point_displacement(p.on_a, d.segment<6>(6 * j.block_a));
      work_of_damping -= (c * v).dot(du);
    }
  }
  for (std::size_t k = 0; k < contact_set.trial.size(); ++k)
  {
    const Contact& c = contact_set.trial[k];
    const ContactFrame& f = contact_set.frames[k];
    const Eigen::Matrix2d cd = contact_dashpot(c, f);
    if (cd.isZero(0.0))
      continue;
    const Vector2 v = f.t_vertex * mean[c.vertex_block] - f.t_edge * mean[c.edge_block];
    const Vector2 du =
        f.t_vertex * d.segment<6>(6 * c.vertex_block) - f.t_edge * d.segment<6>(6 * c.edge_block);
    work_of_damping -= (cd * v).dot(du);
  }
}

} // namespace ddafem::dda
