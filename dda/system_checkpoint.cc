// Checkpoints of a System (issue 20): everything a later step reads, so that a System built anew
// from the same scene and loaded continues bit for bit as the one saved would have. What the
// constructor derives from the model alone (materials, convexity, tolerances, the tie runs) is
// not stored; what steps recompute from scratch before reading it (contact detection's
// features, the joints' sorted lists) is marked stale instead.
#include "common/checkpoint_archive.h"
#include "dda/checkpoint_types.h"
#include "dda/system.h"

#include <limits>

namespace ddafem::dda
{
template <class Archive>
void System::transfer_state(Archive& a)
{
  transfer_marker(a, "dda::System");
  transfer_in_place(a, block_set.list, "blocks",
                    [&a](Block& b)
                    {
                      transfer_all(a, b.vertices, b.moments, b.velocity, b.acceleration, b.force);
                      transfer_all(a, b.stress, b.strain);
                    });
  transfer_all(a, bonded.list, bonded.n_broken, bonded.revision, contact_set.jointed_vertices);
  transfer_in_place(a, point_set.loads, "loads",
                    [&a](AttachedLoad& l) { transfer_all(a, l.point); });
  transfer_in_place(a, point_set.fixed_points, "fixed points",
                    [&a](AttachedFixedPoint& p) { transfer_all(a, p.point); });
  for (std::unique_ptr<ElementKind>& k : element_kinds)
    transfer_object(a, *k);
  transfer_all(a, stages_begun, point_set.monitors, point_set.monitor_origins);
  transfer_in_place(a, boundary_set.edges, "boundary edges",
                    [&a](BoundaryEdge& e) { transfer_all(a, e.midpoint); });
  transfer_all(a, boundary_set.steps);
  transfer_in_place(a, boundary_set.supports, "supports",
                    [&a](Support& s) { transfer_all(a, s.point, s.stiffness, s.load, s.anchor); });
  transfer_all(a, boundary_set.support_normal_stiffness, tie_set.points, tie_set.origins,
               tie_set.matrices);
  transfer_all(a, contact_set.accepted, contact_set.trial);
  transfer_each(a, contact_set.frames,
                [&a](ContactFrame& f)
                { transfer_all(a, f.t_vertex, f.t_edge, f.normal, f.tangent); });
  transfer_all(a, contact_set.geometry_epoch, contact_set.detected.epoch,
               contact_set.detected.contacts, contact_set.detected.predecessors);
  transfer_all(a, contact_set.next_id, contact_set.raised_penalties);
  transfer_all(a, contact_set.reversal_tolerance, contact_set.enabled, mode, block_set.held,
               block_set.removed, balances, scheme.motion_starts);
  transfer_each(a, scheme.friction_jumps,
                [&a](StepScheme::StateBeforeJump& s)
                { transfer_all(a, s.block, s.acceleration, s.force); });
  transfer_all(a, scheme.coefficients, scheme.second_half, scheme.open_half);
  transfer_each(a, scheme.first_halves,
                [&a](StepScheme::FirstHalf& h)
                { transfer_all(a, h.start_velocity, h.displacement, h.mid_force); });
  transfer_all(a, equations.coupling_pairs, equations.coupling_rows, equations.matrix,
               equations.base_matrix, equations.base_rhs, tie_set.matrix);
  transfer_all(a, contact_set.terms.states, contact_set.terms.indexed,
               contact_set.terms.block_start);
  transfer_all(a, contact_set.terms.block_contacts, contact_set.terms.coupling_start);
  transfer_all(a, contact_set.terms.coupling_contacts, tie_set.rhs, equations.dt,
               equations.mass_factor, equations.masses);
  transfer_all(a, bonded.couplings_revision, equations.rhs, equations.solution);
  transfer_object(a, solver);
  transfer_all(a, current_time, ledger.loads, ledger.supports, ledger.boundaries, ledger.damping,
               ledger.removed);
  transfer_all(a, ledger.initial, ledger.largest_input, timings);
  // The joints' sorted lists are rebuilt at the next detection.
  bonded.lists.revision = std::numeric_limits<std::uint64_t>::max();
  contact_set.forget_joint_lists();
}

void System::save(CheckpointOut& archive) const
{
  // One function stores and restores (Boost.Serialization's `&`); storing changes nothing.
  const_cast<System&>(*this).transfer_state(archive);
}

void System::load(CheckpointIn& archive)
{
  transfer_state(archive);
}

} // namespace ddafem::dda
