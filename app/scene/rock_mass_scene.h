// Joint materials per joint set and explicit joint of a `rock_mass` section, and what `check`
// prints about its blocks.
#pragma once

#include "app/scene/scene.h"

#include <cstddef>
#include <optional>
#include <ostream>
#include <vector>

namespace ddafem
{
/// The joint material of each edge of a generated block (dda::BlockDescription::
/// edge_joint_materials): that of joint set i (report.joint_set_materials[i]) along its traces,
/// that of explicit joint j (report.joint_materials[j]) along it, none elsewhere (the region's
/// and the openings' boundaries, vertical cuts, sets without `joint_material`). Empty when no
/// edge has one.
std::vector<std::optional<std::size_t>> edge_joint_materials(const dda::RockMassBlock& block,
                                                             const RockMassReport& report);

/// `check`'s lines on the `rock_mass` section: counts, areas, merges, cuts, the slivers kept and
/// the joint material of each joint set and explicit joint.
void describe_rock_mass(const Scene& scene, std::ostream& out);

} // namespace ddafem
