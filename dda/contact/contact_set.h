// The blocks' contacts and their persistence (issue 55): the contact distances and which blocks
// are convex (set up once), the contacts of the last accepted step, the trial contacts of the
// step being tried, each matched to its predecessor so that it keeps its id, state, forces and
// slip history from step to step, and the penalties a failed step raised for its retry.
// Detection (the System's narrow phase) fills `detected` when the geometry changed; `inherit`
// makes the trial contacts of it; the System's accept_step makes them the accepted ones.
#pragma once

#include "common/parallel.h"
#include "dda/block.h"
#include "dda/contact/contact.h"
#include "dda/model_description.h"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <tuple>
#include <vector>

namespace ddafem::dda
{
/// Shi's w0 and the contact distances that follow from it and the ContactSettings.
struct ContactDistances
{
  double w0 = 0.0;                    ///< half the model size [m]
  double max_step_displacement = 0.0; ///< g2 w0, at most a tenth of the shortest edge [m]
  double search_distance = 0.0;       ///< d0 [m]
  double max_penetration = 0.0;       ///< [m]
  double angle_tolerance = 0.0;       ///< [rad]
  double sin_angle_tolerance = 0.0;   ///< its sine [-]
};

struct ContactSet
{
  /// The narrow phase's result at `epoch` (trial contacts before `inherit`, with their
  /// couplings; the System's contact frames and matrix structure go with it): a retried step
  /// (cut dt, slip reversal, raised penalties) starts from the same accepted state and reuses it.
  struct Detected
  {
    std::uint64_t epoch = std::numeric_limits<std::uint64_t>::max();
    std::vector<Contact> contacts;
    /// Per contact its predecessor's index in `accepted`, or the maximum std::size_t; empty
    /// until `inherit` searched them at `epoch`.
    std::vector<std::size_t> predecessors;
  };

  bool enabled = true; ///< false in a small-displacement analysis: blocks meet by joints only
  ContactDistances distances;
  std::vector<bool> convex; ///< whether each block is convex (at t = 0)
  /// Counts the changes of what contact detection depends on (the blocks' geometry, removed
  /// blocks, joints, stage, ties, the accepted contacts): detection is redone only when it moved.
  std::uint64_t geometry_epoch = 0;
  std::vector<Contact> accepted; ///< of the last accepted step, in key order
  std::vector<Contact> trial;    ///< of the step being tried
  Detected detected;
  std::size_t next_id = 0; ///< the id of the next new contact
  /// Penalty factors raised by a failed step, by contact key, for the retry
  std::map<std::tuple<std::size_t, std::size_t, std::size_t, std::size_t>, double> raised_penalties;

  /// Sets `enabled`, the distances from the model's size [m] and its ContactSettings, and
  /// `convex` per block; throws InputError if two blocks that may touch have materials no joint
  /// material applies to.
  void set_up(const ModelDescription& model, const std::vector<Block>& blocks, double size,
              bool contacts_enabled);
  /// Whether `detected` is of the current geometry (a retried step reuses it).
  bool detection_current() const { return detected.epoch == geometry_epoch; }

  /// trial: detected.contacts with the id, state, forces and slip history of the accepted
  /// contacts that persist; a new contact starts locked if its blocks touch (gap within
  /// 2e-9 w0, `w0` half the model's size [m]), else open. The predecessors are searched for
  /// once per detection (kept in `detected`); a retry only copies the contacts and their states
  /// again. Ids do not depend on the number of threads of `parallel`.
  void inherit(const Parallel& parallel, double w0);

private:
  /// Index in `accepted` of c's predecessor, or `none`; `at` is the first accepted contact
  /// whose key is not below c's.
  std::size_t find_predecessor(const Contact& c, std::vector<Contact>::const_iterator at,
                               std::size_t none) const;
  /// c's state from the accepted contact `previous` (or a new contact's first state and id
  /// `no_id` if `previous` is null), with a raised penalty.
  void inherit_state(Contact& c, const Contact* previous, std::size_t no_id, double w0) const;
};

} // namespace ddafem::dda
