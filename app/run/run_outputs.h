// What a run writes while it runs. Blocks (alone or tied to a far field): histories.h5 (the
// blocks' monitors, energies, contact counts and steps, the far field's and the interface's,
// the keyblocks'), and the snapshots: blocks, contacts, far field and ties as VTU series, all
// of one time gathered in model.pvd. (A far field alone writes its own:
// app/far_field_module/far_field_parts.h.)
#pragma once

#include "app/far_field_module/far_field_module.h"
#include "app/run/element_outputs.h"
#include "app/run/keyblocks.h"

#include "common/checkpoint_fwd.h"
#include "common/history_writer.h"
#include "common/vtk_collection.h"
#include "dda/system.h"
#include "dda/vtu_writer.h"
#include "fem/far_field_description.h"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace ddafem
{
/// What the last accepted step did, for the histories.
struct LastStep
{
  double dt = 0.0; ///< [s]
  unsigned n_open_close_iterations = 0;
  std::size_t n_cuts = 0;
};

/// The channels of histories.h5 for the blocks (monitors, energy, contacts, steps).
std::vector<HistoryChannel> history_channels(const dda::ModelDescription& model);

/// Writes the histories and snapshots of a run into one directory, timing itself.
class RunOutputs
{
public:
  /// Opens DIR/histories.h5 with every channel (blocks, the far field tied to them if any,
  /// keyblocks) and the VTU series; `scene_file` goes into the history file's attributes.
  RunOutputs(const std::filesystem::path& dir, const std::string& scene_file,
             const dda::System& system, TiedFarField* tied, KeyblockRecorder& keyblocks,
             fem::VtuCompression vtu_compression);
  /// Reopens the outputs of a run resumed from a checkpoint (save): histories.h5 cut back to
  /// the rows it had then, the snapshot series to the snapshots it had.
  RunOutputs(const std::filesystem::path& dir, const dda::System& system, TiedFarField* tied,
             KeyblockRecorder& keyblocks, fem::VtuCompression vtu_compression,
             CheckpointIn& archive);
  /// Checkpoints: after flush(), the rows and snapshots written so far.
  void save(CheckpointOut& archive) const;

  /// A history row of the state now, and with `snapshot` the VTU files and model.pvd.
  void write_state(bool snapshot, const LastStep& last);
  void flush() { history.flush(); }

  double seconds() const { return time_output; }                  ///< all writing [s]
  double far_field_vtu_seconds() const { return time_far_field; } ///< of which far-field VTU [s]
  std::size_t n_snapshots() const { return blocks_vtu.n_written(); }

private:
  /// Writes the snapshot's parts and rewrites model.pvd.
  void write_snapshot();
  void write_model_pvd() const;

  std::filesystem::path dir;
  const dda::System& system;
  TiedFarField* tied; ///< null for blocks alone
  KeyblockRecorder& keyblocks;
  fem::VtuCompression vtu_compression;
  HistoryWriter history;
  dda::VtuSeriesWriter blocks_vtu, contacts_vtu, ties_vtu;
  /// The bolts' polylines (part 4 of model.pvd), if the model has bolts.
  dda::VtuSeriesWriter bolts_vtu;
  /// What the run reports of each element kind, with the kinds' own VTU series.
  std::vector<std::unique_ptr<ElementOutputs>> element_outputs;
  /// model.pvd's: every snapshot's parts (blocks, contacts, far field, ties) at their time, so
  /// that ParaView opens the whole model from one file.
  std::vector<CollectionDataSet> model_data_sets;
  double time_output = 0.0, time_far_field = 0.0;
  std::optional<double> last_row_time, last_snapshot_time; ///< [s]
};

} // namespace ddafem
