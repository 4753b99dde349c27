#include "dda/joints.h"

#include "common/input_error.h"
#include "dda/contact/broad_phase.h"

namespace ddafem::dda
{
Vector2 Joint::tangent(bool initial) const
{
  return initial ? (points[1].on_a.initial - points[0].on_a.initial).normalized()
                 : (points[1].on_a.position - points[0].on_a.position).normalized();
}

Vector2 Joint::normal(bool initial) const
{
  return normal_of(tangent(initial));
}

Eigen::Matrix2d joint_spring_matrix(const JointMaterial& jm, const Vector2& n, const Vector2& t)
{
  return jm.normal_stiffness * (n * n.transpose()) +
         jm.shear_ratio * jm.normal_stiffness * (t * t.transpose());
}

void update_joint_point_forces(JointPoint& p, const JointMaterial& jm, const Vector2& n,
                               const Vector2& t)
{
  const Vector2 gap = p.on_b.position - p.on_a.position;
  p.normal_force = p.normal_preload + jm.normal_stiffness * n.dot(gap);
  p.shear_force = p.shear_preload + jm.shear_ratio * jm.normal_stiffness * t.dot(gap);
}

double joint_point_energy(const JointPoint& p, const JointMaterial& jm)
{
  return 0.5 * (p.normal_force * p.normal_force / jm.normal_stiffness +
                p.shear_force * p.shear_force / (jm.shear_ratio * jm.normal_stiffness));
}

ContactLaw joint_point_law(const JointMaterial& jm, double tan_friction, double length)
{
  ContactLaw law;
  law.normal_stiffness = jm.normal_stiffness;
  law.shear_stiffness = jm.shear_ratio * jm.normal_stiffness;
  law.tan_friction = tan_friction;
  law.cohesive_force = jm.cohesion * length;
  law.tensile_capacity = jm.tensile_strength * length;
  return law;
}

std::size_t joint_material_for(const ModelDescription& model, std::size_t material_a,
                               std::size_t material_b)
{
  for (const JointAssignment& j : model.joint_assignments)
    if ((j.material_a == material_a && j.material_b == material_b) ||
        (j.material_a == material_b && j.material_b == material_a))
      return j.joint_material;
  return model.default_joint_material;
}

namespace
{
/// The edge's own joint material (BlockDescription::edge_joint_materials), if it has one.
std::optional<std::size_t> own_joint_material(const ModelDescription& model, std::size_t block,
                                              std::size_t edge)
{
  const std::vector<std::optional<std::size_t>>& own = model.blocks[block].edge_joint_materials;
  return edge < own.size() ? own[edge] : std::nullopt;
}

double edge_length(const Block& b, std::size_t edge)
{
  return (b.vertices[(edge + 1) % b.vertices.size()] - b.vertices[edge]).norm();
}

/// The joint material of the stretch s shared by blocks a and b: the shared edges' own (the
/// shorter edge's where both have one), else by the blocks' materials.
std::size_t shared_joint_material(const std::vector<Block>& blocks, const ModelDescription& model,
                                  std::size_t a, std::size_t b, const SharedSegment& s)
{
  const std::optional<std::size_t> own_a = own_joint_material(model, a, s.a_edge);
  const std::optional<std::size_t> own_b = own_joint_material(model, b, s.b_edge);
  if (own_a && own_b)
    return edge_length(blocks[b], s.b_edge) < edge_length(blocks[a], s.a_edge) ? *own_b : *own_a;
  if (own_a || own_b)
    return own_a ? *own_a : *own_b;
  return joint_material_for(model, blocks[a].material, blocks[b].material);
}
} // namespace

std::size_t joint_material_at_edge(const ModelDescription& model, std::size_t block,
                                   std::size_t edge, std::size_t other)
{
  return own_joint_material(model, block, edge)
      .value_or(
          joint_material_for(model, model.blocks[block].material, model.blocks[other].material));
}

std::vector<Joint> find_joints(const std::vector<Block>& blocks, const ModelDescription& model,
                               const std::vector<std::string>& block_names, double tol)
{
  // Candidates: blocks whose boxes, padded by tol, overlap (a superset of those sharing an edge).
  std::vector<BoundingBox> boxes;
  boxes.reserve(blocks.size());
  for (const Block& b : blocks)
    boxes.push_back(bounding_box(b.vertices, tol));
  const std::vector<std::pair<std::size_t, std::size_t>> candidate_pairs = overlapping_pairs(boxes);

  std::vector<Joint> joints;
  for (const auto& [a, b] : candidate_pairs)
  {
    const std::vector<SharedSegment> shared =
        shared_segments(blocks[a].vertices, blocks[b].vertices, tol);
    for (const SharedSegment& s : shared)
    {
      const std::size_t jm = shared_joint_material(blocks, model, a, b, s);
      if (jm >= model.joint_materials.size())
        throw InputError("blocks " + block_names[a] + " and " + block_names[b] +
                         " share an edge but no joint material applies to materials '" +
                         model.materials[blocks[a].material].name + "' and '" +
                         model.materials[blocks[b].material].name +
                         "': expected `joints: {default: NAME}` or a `joints.pairs` entry");
      Joint joint;
      joint.id = joints.size();
      joint.block_a = a;
      joint.block_b = b;
      joint.joint_material = jm;
      joint.edge_a = s.a_edge;
      joint.edge_b = s.b_edge;
      joint.length = (s.q - s.p).norm();
      const std::array<Point, 2> ends{s.p, s.q};
      for (std::size_t k = 0; k < 2; ++k)
      {
        joint.points[k].on_a = {a, ends[k], ends[k]};
        joint.points[k].on_b = {b, ends[k], ends[k]};
      }
      joints.push_back(joint);
    }
  }
  return joints;
}

std::array<Vector2, 2> in_situ_end_forces(const InSituStress& in_situ, const Point& x0,
                                          const Point& x1, const Vector2& n, double l)
{
  const Vector2 t0 = in_situ.traction(x0, n), t1 = in_situ.traction(x1, n);
  return std::array<Vector2, 2>{l / 6.0 * (2.0 * t0 + t1), l / 6.0 * (t0 + 2.0 * t1)};
}

} // namespace ddafem::dda
