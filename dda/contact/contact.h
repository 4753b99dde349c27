// A contact between two blocks: a convex vertex of one against an edge of the other.
#pragma once

#include "dda/contact/contact_law.h"
#include "dda/contact/narrow_phase.h"
#include "dda/types.h"

#include <cstddef>
#include <tuple>

namespace ddafem::dda
{
/// A vertex-edge contact, kept from step to step while the vertex stays near the edge (Box2D's
/// persistent contact): its id, state and forces carry over.
struct Contact
{
  std::size_t id = 0;           ///< stable while the contact exists
  std::size_t vertex_block = 0; ///< block of the vertex
  std::size_t vertex = 0;       ///< vertex index in that block
  std::size_t edge_block = 0;   ///< block of the edge
  std::size_t edge = 0;         ///< edge index: from vertex `edge` to `edge` + 1 of edge_block
  ContactKind kind = ContactKind::vertex_edge;
  std::size_t joint_material = 0;
  /// Length of joint the contact stands for [m]: half the overlap of a parallel edge pair
  /// (edge-to-edge: each end carries half), 0 for a corner; scales cohesion and tensile strength.
  double length = 0.0;
  /// At the start of the step: where the vertex projects on the edge (0 at its start, 1 at its
  /// end) and its signed normal distance [m] (negative: penetration).
  double ratio = 0.0;
  double gap = 0.0;
  ContactForces forces; ///< state and forces of the last accepted step
  ContactForces trial;  ///< the open-close iteration's current state and forces
  /// Over the current step: normal distance at its end [m] and tangential motion of the vertex
  /// relative to the edge [m] (of the last trial).
  double end_gap = 0.0;
  double step_slip = 0.0;
  double total_slip = 0.0; ///< accumulated sliding since the contact formed [m], along t
  /// How long the contact has slid the same way, up to the last accepted step; while it sticks,
  /// how long the slide it ended lasted; 0 once it opens [s]
  double slide_duration = 0.0;
  /// Multiple of the joint material's springs this contact's penalty has been raised to after
  /// too deep a penetration [-]
  double penalty_factor = 1.0;
  std::size_t coupling = 0; ///< the block pair's coupling in the system matrix

  auto key() const { return std::make_tuple(vertex_block, vertex, edge_block, edge); }
};

} // namespace ddafem::dda
