#include "dda/bonded_joints.h"

#include "common/format.h"
#include "common/input_error.h"
#include "dda/contact/contact_law.h"
#include "dda/linear_solver.h"
#include "dda/step_equations.h"

#include <algorithm>
#include <cmath>

namespace ddafem::dda
{
void BondedJoints::find(const ModelDescription& model, const std::vector<Block>& blocks,
                        const std::vector<std::string>& names, double tol, bool small_displacement)
{
  // Blocks that share an edge through a frictional joint material meet through contacts.
  std::vector<Joint> found = find_joints(blocks, model, names, tol);
  for (const Joint& j : found)
    if (model.joint_materials[j.joint_material].bonded)
      list.push_back(j);
  if (small_displacement)
    for (const Joint& j : found)
      if (!model.joint_materials[j.joint_material].bonded)
        throw InputError("joint material '" + model.joint_materials[j.joint_material].name +
                         "' (between " + names[j.block_a] + " and " + names[j.block_b] +
                         ") is frictional (`bonded: false`), but `analysis.geometry: "
                         "small_displacement` cannot follow contacts: expected `geometry: "
                         "updated` or a bonded joint material");
}

void BondedJoints::apply_in_situ_stress(const InSituStress& in_situ)
{
  for (Joint& j : list)
  {
    const Vector2 n = j.normal(), t = j.tangent();
    const std::array<Vector2, 2> f = in_situ_end_forces(in_situ, j.points[0].on_a.position,
                                                        j.points[1].on_a.position, n, j.length);
    for (std::size_t e = 0; e < 2; ++e)
    {
      JointPoint& p = j.points[e];
      p.normal_preload = p.normal_force = n.dot(f[e]);
      p.shear_preload = p.shear_force = t.dot(f[e]);
    }
  }
}

const BondedJoints::BlockPairs&
BondedJoints::joined(const std::vector<std::unique_ptr<ElementKind>>& kinds)
{
  if (lists.revision == revision)
    return lists.joined;
  lists.revision = revision;
  lists.joined.clear();
  for (const Joint& j : list)
    lists.joined.emplace_back(j.block_a, j.block_b);
  // An element between two blocks (a bolt, a frame) couples them in the matrix like a joint
  // (not in contact detection).
  for (const std::unique_ptr<ElementKind>& k : kinds)
    k->add_couplings(lists.joined);
  std::sort(lists.joined.begin(), lists.joined.end());
  return lists.joined;
}

void BondedJoints::find_couplings(const StepEquations& equations, bool structure_changed)
{
  if (!structure_changed && couplings_revision == revision)
    return; // the joints' couplings are where they were
  for (Joint& j : list)
    j.coupling = equations.coupling_of(j.block_a, j.block_b);
  couplings_revision = revision;
}

void BondedJoints::assemble(const ElementHost& host, const ModelDescription& model,
                            const StepDashpots& dashpots, StepEquations& step,
                            bool with_matrix) const
{
  for (const Joint& j : list)
  {
    const Vector2 tangent = j.tangent(host.small_displacement());
    const Vector2 n = Joint::normal_of(tangent);
    const JointMaterial& jm = model.joint_materials[j.joint_material];
    const Eigen::Matrix2d springs = joint_spring_matrix(jm, n, tangent);
    const double beta = dashpot_factor(dashpots, jm.damping);
    const Eigen::Matrix2d ks =
        beta > 0.0 ? Eigen::Matrix2d((1.0 + dashpots.velocity_factor * beta) * springs) : springs;
    for (const JointPoint& p : j.points)
    {
      const Matrix26 ta = host.point_matrix(p.on_a);
      const Matrix26 tb = host.point_matrix(p.on_b);
      if (beta > 0.0)
      {
        const Vector2 offset = host.point_displacement(p.on_b, dashpots.offsets[j.block_b]) -
                               host.point_displacement(p.on_a, dashpots.offsets[j.block_a]);
        const Vector2 force = beta * (springs * offset);
        step.rhs.segment<6>(6 * j.block_a).noalias() += ta.transpose() * force;
        step.rhs.segment<6>(6 * j.block_b).noalias() -= tb.transpose() * force;
      }
      if (with_matrix)
      {
        const Matrix26 ks_ta = ks * ta;
        const Matrix26 ks_tb = ks * tb;
        step.matrix.diagonal(j.block_a).noalias() += ta.transpose() * ks_ta;
        step.matrix.diagonal(j.block_b).noalias() += tb.transpose() * ks_tb;
        step.matrix.upper(j.coupling).noalias() -= ta.transpose() * ks_tb;
      }
      const Vector2 force = springs * (p.on_b.position - p.on_a.position) + p.normal_preload * n +
                            p.shear_preload * tangent;
      step.rhs.segment<6>(6 * j.block_a).noalias() += ta.transpose() * force;
      step.rhs.segment<6>(6 * j.block_b).noalias() -= tb.transpose() * force;
    }
  }
}

void BondedJoints::add_work_of_damping(const ElementHost& host, const ModelDescription& model,
                                       const StepDashpots& dashpots,
                                       const std::vector<Vector6>& mean, const Eigen::VectorXd& d,
                                       double& work) const
{
  for (const Joint& j : list)
  {
    const JointMaterial& jm = model.joint_materials[j.joint_material];
    const double beta = dashpot_factor(dashpots, jm.damping);
    if (beta == 0.0)
      continue;
    const Vector2 tangent = j.tangent(host.small_displacement());
    const Eigen::Matrix2d c = beta * joint_spring_matrix(jm, Joint::normal_of(tangent), tangent);
    for (const JointPoint& p : j.points)
    {
      const Vector2 v = host.point_displacement(p.on_b, mean[j.block_b]) -
                        host.point_displacement(p.on_a, mean[j.block_a]);
      const Vector2 du = host.point_displacement(p.on_b, d.segment<6>(6 * j.block_b)) -
                         host.point_displacement(p.on_a, d.segment<6>(6 * j.block_a));
      work -= (c * v).dot(du);
    }
  }
}

void BondedJoints::move_points(const ElementHost& host, const Eigen::VectorXd& d)
{
  for (Joint& j : list)
    for (JointPoint& p : j.points)
    {
      host.move_with_block(p.on_a, d);
      host.move_with_block(p.on_b, d);
    }
}

void BondedJoints::update_forces(const ModelDescription& model, bool small_displacement)
{
  for (Joint& j : list)
  {
    const JointMaterial& jm = model.joint_materials[j.joint_material];
    const Vector2 t = j.tangent(small_displacement);
    const Vector2 n = Joint::normal_of(t);
    for (JointPoint& p : j.points)
      update_joint_point_forces(p, jm, n, t);
  }
}

std::string BondedJoints::break_beyond_strength(const ModelDescription& model,
                                                const std::vector<double>& tan_friction,
                                                bool small_displacement, double t)
{
  // The intact joints move forward over the broken ones, in order (nothing moves while none
  // broke).
  std::string failure;
  std::size_t n_intact = 0;
  for (std::size_t k = 0; k < list.size(); ++k)
  {
    const Joint& j = list[k];
    // Each end spring carries half of the joint's length.
    const ContactLaw law = joint_point_law(model.joint_materials[j.joint_material],
                                           tan_friction[j.joint_material], 0.5 * j.length);
    bool broken = false;
    for (const JointPoint& p : j.points)
      broken = broken || exceeds_strength(law, -p.normal_force, p.shear_force);
    if (!broken)
    {
      if (n_intact != k)
        list[n_intact] = list[k];
      ++n_intact;
      continue;
    }
    ++n_broken;
    if (small_displacement && failure.empty())
      failure = "bonded joint " + std::to_string(j.id) + " between blocks " +
                std::to_string(j.block_a) + " and " + std::to_string(j.block_b) +
                " exceeded its strength at t = " + format_time(t) +
                "; a broken joint becomes a frictional contact, which a small-displacement "
                "analysis cannot follow: expected `analysis.geometry: updated`";
  }
  if (n_intact != list.size())
  {
    list.resize(n_intact);
    ++revision;
  }
  return failure;
}

void BondedJoints::remove_block(std::size_t i)
{
  ++revision;
  list.erase(std::remove_if(list.begin(), list.end(),
                            [&](const Joint& j) { return j.block_a == i || j.block_b == i; }),
             list.end());
}

void BondedJoints::add_energy(const ModelDescription& model, double& energy) const
{
  for (const Joint& j : list)
  {
    const JointMaterial& jm = model.joint_materials[j.joint_material];
    for (const JointPoint& p : j.points)
      energy += joint_point_energy(p, jm);
  }
}

void BondedJoints::add_loads(const std::function<void(std::size_t, double)>& add) const
{
  for (const Joint& j : list)
    for (const JointPoint& p : j.points)
    {
      const double magnitude = std::hypot(p.normal_force, p.shear_force);
      add(j.block_a, magnitude);
      add(j.block_b, magnitude);
    }
}

void BondedJoints::add_snapshots(bool small_displacement, std::vector<ContactSnapshot>& out) const
{
  for (const Joint& j : list)
    for (const JointPoint& p : j.points)
    {
      ContactSnapshot s;
      s.id = j.id;
      s.block_a = j.block_a;
      s.block_b = j.block_b;
      s.state = ContactPointState::bonded;
      s.position = p.on_a.position;
      s.normal = j.normal(small_displacement);
      s.normal_force = -p.normal_force;
      s.shear_force = p.shear_force;
      s.gap = s.normal.dot(p.on_b.position - p.on_a.position);
      out.push_back(s);
    }
}

} // namespace ddafem::dda
