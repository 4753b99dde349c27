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
  const Vector2 t = tangent(initial);
  return Vector2(t.y(), -t.x());
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
    if (shared.empty())
      continue;
    const std::size_t jm = joint_material_for(model, blocks[a].material, blocks[b].material);
    if (jm >= model.joint_materials.size())
      throw InputError("blocks " + block_names[a] + " and " + block_names[b] +
                       " share an edge but no joint material applies to materials '" +
                       model.materials[blocks[a].material].name + "' and '" +
                       model.materials[blocks[b].material].name +
                       "': expected `joints: {default: NAME}` or a `joints.pairs` entry");
    for (const SharedSegment& s : shared)
    {
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

} // namespace ddafem::dda
