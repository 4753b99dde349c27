#include "dda/boundary_set.h"

#include "common/input_error.h"
#include "dda/block_materials.h"
#include "dda/linear_solver.h"
#include "dda/step_equations.h"

#include <map>
#include <string>
#include <utility>

namespace ddafem::dda
{
Vector2 boundary_normal(const BoundaryEdge& e, const std::vector<Block>& blocks,
                        bool small_displacement)
{
  const Block& b = blocks[e.block];
  const std::vector<Point>& v = small_displacement ? b.initial_vertices : b.vertices;
  const Vector2 t = (v[(e.edge + 1) % v.size()] - v[e.edge]).normalized();
  return Vector2(t.y(), -t.x());
}

void BoundarySet::select(const ModelDescription& model, const std::vector<Block>& blocks,
                         const std::vector<Joint>& joints, double tol)
{
  for (std::size_t k = 0; k < model.boundaries.size(); ++k)
  {
    const std::vector<BoundaryEdge> selected = select_boundary_edges(k, model, blocks, joints, tol);
    edges.insert(edges.end(), selected.begin(), selected.end());
  }
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> owner; // (block, edge) -> boundary
  for (const BoundaryEdge& e : edges)
  {
    const auto [it, inserted] = owner.emplace(std::make_pair(e.block, e.edge), e.boundary);
    if (!inserted)
      throw InputError(model.boundaries[e.boundary].origin + " selects block " +
                       std::to_string(e.block) + " edge " + std::to_string(e.edge) + ", which " +
                       model.boundaries[it->second].origin +
                       " already has: expected each edge in one boundary only");
  }
  steps.resize(edges.size());
}

void BoundarySet::set_up_supports(const ModelDescription& model, const std::vector<Block>& blocks,
                                  double default_stiffness, bool small_displacement)
{
  double ratio = 0.4;
  support_normal_stiffness = default_stiffness;
  if (model.default_joint_material < model.joint_materials.size())
  {
    const JointMaterial& jm = model.joint_materials[model.default_joint_material];
    support_normal_stiffness = jm.normal_stiffness;
    ratio = jm.shear_ratio;
  }
  for (const BoundaryEdge& e : edges)
  {
    if (model.boundaries[e.boundary].type == BoundaryType::free)
      continue;
    const std::vector<Point>& v = blocks[e.block].vertices;
    const Vector2 n = boundary_normal(e, blocks, small_displacement), t(-n.y(), n.x());
    const Eigen::Matrix2d k =
        support_normal_stiffness * (n * n.transpose() + ratio * (t * t.transpose()));
    const Point& x0 = v[e.edge];
    const Point& x1 = v[(e.edge + 1) % v.size()];
    const std::array<Vector2, 2> f = in_situ_end_forces(model.in_situ_stress, x0, x1, n, e.length);
    supports.push_back({{e.block, x0, x0}, k, f[0], x0});
    supports.push_back({{e.block, x1, x1}, k, f[1], x1});
  }
}

void BoundarySet::begin_stage(bool after_static, bool is_static)
{
  for (Support& s : supports)
  {
    if (after_static)
      s.load = s.force();
    if (is_static)
      s.anchor = s.point.position;
  }
}

Vector2 BoundarySet::input_force(const StepInput& in, const BoundaryEdge& e, double t) const
{
  const BoundaryDescription& b = in.model.boundaries[e.boundary];
  if (!b.has_input)
    return Vector2::Zero();
  const Vector2 n = boundary_normal(e, in.blocks, in.host.small_displacement());
  const Vector2 tangent(-n.y(), n.x());
  const double v = b.input.velocity.value(t);
  const Vector2 v_in = b.input.type == BoundaryInput::Type::p ? Vector2(0.0, v) : Vector2(v, 0.0);
  return 2.0 * (e.cn * n.dot(v_in) * n + e.ct * tangent.dot(v_in) * tangent);
}

void BoundarySet::assemble(const StepInput& in, const IntegratorCoefficients& integration,
                           double dt, const std::function<KinematicState(std::size_t)>& start,
                           StepEquations& step, bool with_matrix)
{
  for (std::size_t k = 0; k < edges.size(); ++k)
  {
    steps[k] = {};
    if (in.is_static)
      continue;
    const BoundaryEdge& e = edges[k];
    const KinematicState s = start(e.block);
    const Matrix26 t = in.host.point_matrix(e.midpoint);
    steps[k] = boundary_step(in.model.boundaries[e.boundary].type, e,
                             boundary_normal(e, in.blocks, in.host.small_displacement()),
                             block_mass(in.model, in.blocks[e.block]), dt, integration.beta,
                             integration.gamma, t * s.velocity, t * s.acceleration);
    if (with_matrix)
      step.matrix.diagonal(e.block).noalias() += t.transpose() * steps[k].k * t;
    step.rhs.segment<6>(6 * e.block).noalias() +=
        t.transpose() * (steps[k].f + input_force(in, e, in.t1));
  }
  for (const Support& s : supports)
  {
    const Matrix26 t = in.host.point_matrix(s.point);
    if (in.is_static && with_matrix)
      step.matrix.diagonal(s.point.block).noalias() += t.transpose() * s.stiffness * t;
    step.rhs.segment<6>(6 * s.point.block).noalias() +=
        t.transpose() * (in.is_static ? s.force() : s.load);
  }
}

void BoundarySet::add_work(const StepInput& in, const Eigen::VectorXd& d,
                           EnergyLedger& ledger) const
{
  for (std::size_t k = 0; k < edges.size(); ++k)
  {
    const BoundaryEdge& e = edges[k];
    const Vector2 du = in.host.point_displacement(e.midpoint, d.segment<6>(6 * e.block));
    ledger.boundaries += (steps[k].f - steps[k].k * du).dot(du);
    if (!in.is_static)
      ledger.loads += 0.5 * (input_force(in, e, in.t0) + input_force(in, e, in.t1)).dot(du);
  }
  if (!in.is_static)
    for (const Support& s : supports)
      ledger.loads +=
          s.load.dot(in.host.point_displacement(s.point, d.segment<6>(6 * s.point.block)));
}

void BoundarySet::move_points(const ElementHost& host, const Eigen::VectorXd& d)
{
  for (BoundaryEdge& e : edges)
    host.move_with_block(e.midpoint, d);
  for (Support& s : supports)
    host.move_with_block(s.point, d);
}

void BoundarySet::add_loads(const std::function<void(std::size_t, double)>& add) const
{
  for (const Support& s : supports)
    add(s.point.block, s.force().norm());
}

} // namespace ddafem::dda
