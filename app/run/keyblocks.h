// Keyblocks (issue 7): how far the blocks around the openings of a rock mass (found by
// dda::find_keyblocks) moved during the run and whether they detached or fell.
#pragma once

#include "common/checkpoint_fwd.h"
#include "common/history_writer.h"
#include "dda/keyblocks.h"
#include "dda/model_description.h"
#include "dda/system.h"
#include "dda/yield_acceleration.h"

#include <nlohmann/json_fwd.hpp>

#include <cstddef>
#include <optional>
#include <unordered_set>
#include <utility>
#include <vector>

namespace ddafem
{
using dda::FallCriterion;
using dda::KeyblockGeometry;
using dda::OpeningOutline;

/// Records the keyblocks of a run: their centroid displacement in every history row (measured,
/// like the monitors, from the start of the dynamic stage that follows a static one, else from
/// t = 0), absolute and relative to the surrounding rock (the area-weighted mean displacement
/// of the blocks, keyblocks excepted, whose centroid lies 0.75 to 1.5 opening sizes from the
/// opening's centre: the free field the wave moves the opening with), the peaks over the rows,
/// the joints' largest slip and opening per row and over the run, at the end whether each
/// detached or fell, and per opening the blocks that fell (any block within one opening size
/// of it whose centroid went down more than the fall threshold, and blocks a static stage
/// removed) and their area (volume per metre of tunnel). Does nothing for a model without
/// openings.
class KeyblockRecorder
{
public:
  explicit KeyblockRecorder(const dda::ModelDescription& model, FallCriterion fall = {});

  static constexpr std::size_t no_opening = static_cast<std::size_t>(-1);

  bool empty() const { return geometry.blocks.empty(); }
  /// The opening block `block` is next to: a keyblock's own, else the one whose boundary is
  /// nearest to `centroid` [m] (e.g. where a static stage released it); no_opening without
  /// openings.
  std::size_t opening_next_to(std::size_t block, const dda::Point& centroid) const;
  /// Marks a block a static stage released (dda::ReleasedBlock): the summary shows it.
  void mark_released(std::size_t block);
  const KeyblockGeometry& get_geometry() const { return geometry; }

  /// Marks a block a static stage removed (ReleaseAction::remove): it counts as fallen.
  void mark_removed(std::size_t block);

  /// Appends three channels per keyblock: `keyblocks/block_<id>/displacement` (ux, uy) and
  /// `relative_displacement` (ux, uy) [m], `joints` (largest |slip|, largest opening of its
  /// joints in that row) [m].
  void add_channels(std::vector<HistoryChannel>& channels) const;
  /// Appends the keyblocks' displacements to a history row (in the order of add_channels) and
  /// updates the peaks and the joints' extremes.
  void append_row(const dda::System& system, std::vector<double>& row);
  /// Newmark's yield acceleration of a keyblock (dda/yield_acceleration.h) for horizontal (SV)
  /// and vertical (P) shaking, from the model at t = 0.
  struct Yield
  {
    dda::YieldAcceleration horizontal, vertical;
  };
  /// Per keyblock, in the order of keyblock_ids().
  const std::vector<Yield>& yield_accelerations() const { return yields; }
  /// The keyblocks' block indices, ascending.
  const std::vector<std::size_t>& keyblock_ids() const { return geometry.blocks; }
  /// The first keyblock (its block index) that a static stage did not release and that in the
  /// last row has dropped by the fall threshold, or is detached and has left its place relative
  /// to the rock (dda::left_its_place: thrown out for good), if any (--stop-at-first-fall).
  std::optional<std::size_t> first_fallen() const;
  /// The `keyblocks` section of summary.json from the last row and the system's final state
  /// (null for a model without openings); see docs/outputs.md.
  nlohmann::json summary(const dda::System& system) const;

  /// Checkpoints (app/run/checkpoint.cc): the tracks, references and marks so far.
  void save(CheckpointOut& archive) const;
  void load(CheckpointIn& archive);

private:
  /// What a keyblock did over the rows so far.
  struct Track
  {
    dda::Vector2 reference = dda::Vector2::Zero(); ///< centroid displacement it is measured from
    dda::Vector2 last = dda::Vector2::Zero();      ///< displacement in the last row [m]
    dda::Vector2 last_relative = dda::Vector2::Zero(); ///< relative to the rock, last row [m]
    double peak = 0.0;                                 ///< largest |displacement| [m]
    double peak_time = 0.0;                            ///< [s]
    double peak_relative = 0.0;                        ///< largest |relative displacement| [m]
    double peak_relative_time = 0.0;                   ///< [s]
    double row_slip = 0.0, row_opening = 0.0;          ///< of its joints in the last row [m]
    /// Largest |slip| of its joints [m]: contacts' accumulated sliding, bonded joints' shear.
    double max_slip = 0.0;
    /// Largest normal opening of its joints [m]: bonded joints' stretch, gaps of contacts that
    /// were closed in an earlier row (contacts exist within the search distance only).
    double max_opening = 0.0;
    /// In the last row: detached and out of its place relative to the rock (left_its_place).
    bool thrown_out = false;
  };

  /// Slip and opening of every joint (contact or bonded joint) of a keyblock, into the tracks.
  void update_joints(const dda::System& system);
  /// Per opening, the area-weighted mean displacement of its ring of surrounding rock [m].
  std::vector<dda::Vector2> ring_displacements(const std::vector<dda::Block>& blocks) const;
  /// Per opening: {"fallen_blocks": [ids], "fallen_area_m2", "released_area_m2"} at the end
  /// (the second: the part of the first that a static stage released).
  nlohmann::json fallen_per_opening(const dda::System& system) const;
  /// Track::thrown_out of every keyblock after a row.
  void update_thrown_out(const dda::System& system);
  /// Per keyblock: held by an intact bonded joint, a closed contact or a support element that
  /// still ties it to another block (dda::ElementKind::add_held_blocks) at the end.
  std::vector<bool> held_keyblocks(const dda::System& system) const;
  /// Keyblock k's entry of the summary's `blocks`, with its verdicts.
  nlohmann::json keyblock_summary(std::size_t k, const dda::System& system, bool held) const;

  KeyblockGeometry geometry;
  std::vector<Yield> yields;
  FallCriterion criterion;
  dda::Vector2 down = dda::Vector2(0.0, -1.0); ///< unit vector along gravity
  double gravity = 9.81;                       ///< |g| [m/s^2] of the fall-speed criterion
  bool small_displacement = false;
  std::vector<std::size_t> slot; ///< per model block: its index in geometry.blocks, or npos
  std::vector<Track> tracks;
  std::vector<bool> released; ///< per keyblock: a static stage released it
  /// Per opening: the blocks of its ring of surrounding rock and their areas [m^2].
  std::vector<std::vector<std::pair<std::size_t, double>>> rings;
  std::vector<dda::Vector2> ring_reference;  ///< per opening: ring displacement at the reference
  std::vector<dda::Vector2> block_reference; ///< per model block: displacement at the reference
  std::vector<double> block_area;            ///< per model block [m^2]
  std::vector<dda::Point> keyblock_centroid; ///< per keyblock: its centroid at the start [m]
  std::vector<bool> removed;                 ///< per model block: a static stage removed it
  bool referenced = false;                   ///< the first row has set the references
  std::unordered_set<std::size_t> closed_contacts; ///< ids of contacts seen closed in some row
};

} // namespace ddafem
