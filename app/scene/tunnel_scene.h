// The `tunnel` scene section: a tunnel in jointed rock under a seismic wave, planned by
// app/scene/tunnel_plan.h and expanded here into the detailed sections (rock_mass, far_field,
// interface, boundaries, in_situ_stress, stages, monitors, time) that the scene reader then
// reads like any others.
#pragma once

#include "app/scene/tunnel_plan.h"

#include <yaml-cpp/yaml.h>

namespace ddafem
{
using dda::Point;

/// The user's YAML for the parts copied into the generated sections.
struct TunnelNodes
{
  YAML::Node opening;    ///< tunnel.opening
  YAML::Node joint_sets; ///< tunnel.joint_sets (may be undefined)
  YAML::Node joints;     ///< tunnel.joints (may be undefined)
  YAML::Node velocity;   ///< tunnel.wave.velocity
  YAML::Node lining;     ///< tunnel.lining (may be undefined)
};

/// Writes the generated sections into the scene's root: rock_mass, gravity, in_situ_stress,
/// analysis.plane, stages, monitors, time (keys the user gave in `time` win), output (likewise),
/// and for the hybrid and reference a far-field material `rock_mass_equivalent`, far_field and
/// interface; for vb1 and dashpot the block boundaries; for blocks the outer grids (`blocks`),
/// their material `outer_rock` and joint material `outer_bond` (with `joints.pairs` entries)
/// and the block boundaries; with tunnel.lining a `linings` entry `lining` around the opening,
/// installed after the excavation (after the user's linings). Throws InputError (without a
/// location) if the scene already has a section the tunnel generates.
void write_tunnel_sections(const TunnelDescription& tunnel, const TunnelPlan& plan,
                           const TunnelNodes& nodes, YAML::Node& root);

} // namespace ddafem
