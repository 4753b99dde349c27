// What a run writes while it runs. Blocks (alone or tied to a far field): histories.h5 (the
// blocks' monitors, energies, contact counts and steps, the far field's and the interface's,
// the keyblocks'), and the snapshots: blocks, contacts, far field and ties as VTU series, all
// of one time gathered in model.pvd. A far field alone: histories.h5 (its monitors and
// energies) and far_field.pvd.
#pragma once

#include "app/keyblocks.h"

#include "common/history_writer.h"
#include "common/vtk_collection.h"
#include "coupling/far_field_ties.h"
#include "dda/system.h"
#include "dda/vtu_writer.h"
#include "fem/elastic_wave_model.h"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <filesystem>
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

/// A coupled run's far field and ties (both null for blocks alone).
struct CoupledParts
{
  fem::ElasticWaveModel* far_field = nullptr; ///< writes its own snapshots
  const coupling::FarFieldTies* ties = nullptr;
  const fem::FarFieldDescription* description = nullptr;
};

/// Appends the displacement, velocity and stress of the far field's first `n_monitors` monitors
/// to a history row (the channels of run_support::add_monitor_channels).
void append_far_field_monitors(std::vector<double>& row, const fem::ElasticWaveModel& far_field,
                               std::size_t n_monitors);
/// The far field's timings for summary.json [s]: setup, assemble, solve, update.
nlohmann::json far_field_timings(const fem::Timings& timings);

/// The channels of histories.h5 for the blocks (monitors, energy, contacts, steps).
std::vector<HistoryChannel> history_channels(const dda::ModelDescription& model);
/// The far field's and the interface's channels of a coupled run (after the blocks').
void add_coupled_channels(std::vector<HistoryChannel>& channels,
                          const fem::FarFieldDescription& description);
/// The ties as contact points for VTU: state (bonded while intact), normal out of the block,
/// forces (normal compression positive, shear along the edge tangent), opening and slip.
std::vector<dda::ContactSnapshot> tie_snapshot(const coupling::FarFieldTies& ties,
                                               const dda::System& system);

/// Writes the histories and snapshots of a run into one directory, timing itself.
class RunOutputs
{
public:
  /// Opens DIR/histories.h5 with every channel (blocks, coupled parts, keyblocks) and the VTU
  /// series; `scene_file` goes into the history file's attributes.
  RunOutputs(const std::filesystem::path& dir, const std::string& scene_file,
             const dda::System& system, CoupledParts coupled, KeyblockRecorder& keyblocks,
             fem::VtuCompression vtu_compression);

  /// A history row of the state now, and with `snapshot` the VTU files and model.pvd.
  void write_state(bool snapshot, const LastStep& last);
  void flush() { history.flush(); }

  double seconds() const { return time_output; }                  ///< all writing [s]
  double far_field_vtu_seconds() const { return time_far_field; } ///< of which far-field VTU [s]
  std::size_t n_snapshots() const { return blocks_vtu.n_written(); }

private:
  /// Writes the snapshot's parts and rewrites model.pvd.
  void write_snapshot();

  std::filesystem::path dir;
  const dda::System& system;
  CoupledParts coupled;
  KeyblockRecorder& keyblocks;
  fem::VtuCompression vtu_compression;
  HistoryWriter history;
  dda::VtuSeriesWriter blocks_vtu, contacts_vtu, ties_vtu;
  /// model.pvd's: every snapshot's parts (blocks, contacts, far field, ties) at their time, so
  /// that ParaView opens the whole model from one file.
  std::vector<CollectionDataSet> model_data_sets;
  double time_output = 0.0, time_far_field = 0.0;
};

/// Writes the histories and snapshots of a far field alone into one directory, timing itself.
class FarFieldOutputs
{
public:
  /// Opens DIR/histories.h5 with the far field's monitors and energies; `scene_file` goes into
  /// its attributes.
  FarFieldOutputs(const std::filesystem::path& dir, const std::string& scene_file,
                  fem::ElasticWaveModel& model, const fem::FarFieldDescription& description,
                  fem::VtuCompression vtu_compression);

  /// A history row of the state now, and with `snapshot` far_field_NNNNN.vtu and far_field.pvd.
  void write_state(bool snapshot);
  void flush() { history.flush(); }

  double seconds() const { return time_output; } ///< all writing [s]
  std::size_t n_snapshots() const { return n_written; }

private:
  std::filesystem::path dir;
  fem::ElasticWaveModel& model;
  std::size_t n_monitors;
  fem::VtuCompression vtu_compression;
  HistoryWriter history;
  std::size_t n_written = 0;
  double time_output = 0.0;
};

} // namespace ddafem
