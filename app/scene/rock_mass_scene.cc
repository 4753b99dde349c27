#include "app/scene/rock_mass_scene.h"

#include "common/format.h"

#include <algorithm>

namespace ddafem
{
namespace
{

/// The name of a `joint_material` as read (an index into the model's), or what applies instead.
std::string joint_material_name(const dda::ModelDescription& model,
                                const std::optional<std::size_t>& material)
{
  if (material)
    return model.joint_materials[*material].name;
  if (model.default_joint_material < model.joint_materials.size())
    return model.joint_materials[model.default_joint_material].name + " (joints.default)";
  return "that of joints.pairs";
}
} // namespace

std::vector<std::optional<std::size_t>> edge_joint_materials(const dda::RockMassBlock& block,
                                                             const RockMassReport& report)
{
  std::vector<std::optional<std::size_t>> materials;
  for (const dda::EdgeJoint& e : block.edge_joints)
    switch (e.kind)
    {
    case dda::EdgeJoint::Kind::none:
      materials.emplace_back();
      break;
    case dda::EdgeJoint::Kind::joint_set:
      materials.push_back(report.joint_set_materials[e.index]);
      break;
    case dda::EdgeJoint::Kind::explicit_joint:
      materials.push_back(report.joint_materials[e.index]);
      break;
    }
  if (std::none_of(materials.begin(), materials.end(), [](const auto& m) { return m.has_value(); }))
    materials.clear();
  return materials;
}

void describe_rock_mass(const Scene& scene, std::ostream& out)
{
  const RockMassReport& r = *scene.rock_mass;
  const dda::RockMassStatistics& s = r.statistics;
  out << "  rock mass: " << s.n_blocks << " blocks from block " << r.first_block << ", smallest "
      << format_significant(s.smallest_area) << " m^2, mean " << format_significant(s.mean_area)
      << " m^2; total " << format_significant(s.total_area, 6) << " m^2 = region "
      << format_significant(s.region_area, 6) << " - excavated "
      << format_significant(s.excavated_area, 6) << " m^2\n";
  out << "  rock mass: " << s.n_traces << " joint traces, sliver threshold "
      << format_significant(s.min_area) << " m^2, " << s.n_merged << " slivers merged, "
      << s.n_reported << " kept, " << s.n_island_cuts << " vertical cuts around enclosed islands\n";
  out << "  rock mass: shortest edge " << format_significant(s.shortest_edge) << " m (edges below "
      << format_significant(s.min_edge_length) << " m collapsed: " << s.n_collapsed_edges
      << ", left: " << s.n_short_edges << "), " << s.n_straight_vertices
      << " straight vertices removed\n";
  for (std::size_t i = 0; i < r.joint_sets.size(); ++i)
    out << "  rock mass: joint set " << i << " (dip " << format_significant(r.joint_sets[i].dip)
        << " deg, spacing " << format_significant(r.joint_sets[i].spacing) << " m): joint material "
        << joint_material_name(scene.model, r.joint_set_materials[i]) << "\n";
  for (std::size_t j = 0; j < r.joints.size(); ++j)
    out << "  rock mass: joint " << j << " from (" << format_significant(r.joints[j].from.x())
        << ", " << format_significant(r.joints[j].from.y()) << ") to ("
        << format_significant(r.joints[j].to.x()) << ", " << format_significant(r.joints[j].to.y())
        << ") m: joint material " << joint_material_name(scene.model, r.joint_materials[j]) << "\n";
  for (const dda::Sliver& sliver : r.slivers)
    out << "  sliver kept: " << scene.model.blocks[sliver.block].origin << " at ("
        << format_significant(sliver.centroid.x()) << ", "
        << format_significant(sliver.centroid.y()) << ") m, area "
        << format_significant(sliver.area) << " m^2, 2 area / perimeter "
        << format_significant(sliver.inscribed_radius) << " m\n";
}

} // namespace ddafem
