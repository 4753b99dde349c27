// What the bolts' VTU series draws of a bolt at one time (dda/vtu_writer.h, docs/support.md).
#pragma once

#include "dda/grouted_bolt.h"

#include <cstddef>
#include <vector>

namespace ddafem::dda
{
/// A bolt as a polyline through its current material points: head, for a grouted bolt each
/// crossing's point on the head side's block then on the anchor side's (apart once the joint
/// opens or slips), and anchor.
struct BoltSnapshot
{
  std::size_t id = 0; ///< the end-anchored bolts first, then the grouted ones, in scene order
  BoltType type = BoltType::end_anchored;
  std::vector<Point> points;            ///< current positions [m]
  std::vector<double> point_axial;      ///< per point: the axial force there [N], tension positive
  std::vector<double> point_shear;      ///< per point: the dowel force there [N] (0: end-anchored)
  double axial_force = 0.0;             ///< N (grouted: the largest of its crossings) [N]
  double shear_force = 0.0;             ///< grouted: the largest |S| of its crossings [N]
  BoltState state = BoltState::elastic; ///< grouted: ruptured if a crossing is, else yielding
                                        ///< if one is, else elastic if one is, else slack
};

/// The grouted bolt's summary state over its crossings (BoltSnapshot::state).
BoltState summary_state(const GroutedBolt& b);

/// Every bolt as a polyline for the bolts' VTU series: the end-anchored ones, then the grouted
/// ones, with their state at the last accepted step (dda/grouted_bolt.cc).
std::vector<BoltSnapshot> bolt_snapshot(const std::vector<Bolt>& bolts,
                                        const std::vector<GroutedBolt>& grouted_bolts);

} // namespace ddafem::dda
