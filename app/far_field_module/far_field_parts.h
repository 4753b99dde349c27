// The module's side of app/far_field_module/far_field_module.h: what libddafem_far_field.so builds
// from fem::ElasticWaveModel and coupling::FarFieldTies. Only the module's files and the test
// programs include this header; the core reaches these through FarFieldModule.
#pragma once

#include "app/far_field_module/far_field_module.h"
#include "app/run/run_outputs.h"

#include "coupling/far_field_ties.h"
#include "fem/elastic_wave_model.h"

#include <nlohmann/json.hpp>

#include <array>
#include <cstddef>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace ddafem
{
/// The scene's far field, tied to `system` (app/far_field_module/tied_far_field.cc).
std::unique_ptr<TiedFarField> make_tied_far_field(const Scene& scene, dda::System& system);
/// A far field alone behind the driver's interface (app/far_field_module/far_field_simulation.cc).
std::unique_ptr<Simulation> make_far_field_simulation(const Scene& scene);
/// The same distributed over the MPI ranks (app/far_field_module/distributed_far_field.cc).
std::unique_ptr<Simulation> make_distributed_far_field_simulation(const Scene& scene);
/// The scene's far field distributed over the MPI ranks, tied to `system`, which every rank
/// runs (app/far_field_module/distributed_tied_far_field.cc).
std::unique_ptr<TiedFarField> make_distributed_tied_far_field(const Scene& scene,
                                                              dda::System& system);

// ---- the parts of a tied far field's outputs its serial and distributed kinds share
// (app/far_field_module/tied_far_field.cc) ----

/// Why the interface reflects more than 1 % of a normally incident wave; empty below.
std::string tied_impedance_warning(const Scene& scene, const dda::System& system,
                                   const coupling::FarFieldTies& ties);
/// The far field's monitors and energies and the interface's channels.
void add_tied_channels(std::vector<HistoryChannel>& channels,
                       const fem::FarFieldDescription& description);
/// Their values after the monitors' (append_far_field_monitors).
void append_tied_energies(std::vector<double>& row, const fem::EnergyBalance& energy,
                          const coupling::FarFieldTies& ties);
/// The ties as contact points for VTU.
std::vector<dda::ContactSnapshot> tie_contacts(const coupling::FarFieldTies& ties,
                                               const dda::System& system);
/// summary.json's "interface", and the far field's energies for its "far_field".
nlohmann::json interface_summary(const coupling::FarFieldTies& ties,
                                 const fem::EnergyBalance& energy);
nlohmann::json far_field_energy_summary(const fem::EnergyBalance& energy);
/// The channels of a run of a far field alone: its monitors and energies.
std::vector<HistoryChannel> far_field_channels(const fem::FarFieldDescription& description);
/// `check` of a far-field-only scene: mesh, wave speeds, elements per wavelength, boundaries
/// (app/far_field_module/far_field_outputs.cc).
std::string check_far_field(const Scene& scene);

/// The wave arriving at the near field's base beside the input's (issue 53), where the far field
/// has a free_field side: the velocity of its free-field column (no opening, no blocks) at the
/// blocks' lowest initial height, a history channel, and its peak against the peak of the
/// incident wave's v_in at the far field's base over the rows. The column's motion there is the
/// upgoing wave, damped on its way, plus what the ground surface sends back down (apart in time
/// where the wave is shorter than twice the depth).
class BaseArrival
{
public:
  BaseArrival(const Scene& scene, const dda::System& system);
  bool recorded() const { return has_column; }
  double height() const { return base; } ///< the near field's base [m]
  void add_channel(std::vector<HistoryChannel>& channels) const;
  /// A row's values: the column's velocity `v` at height() [m/s] at time `t` [s].
  void append(std::vector<double>& row, const std::array<double, 2>& v, double t);
  /// summary.json's far_field.free_field_at_base, with the far field's wave speeds [m/s].
  nlohmann::json summary(double p_wave_speed, double s_wave_speed) const;
  void save(CheckpointOut& archive) const; ///< the peaks
  void load(CheckpointIn& archive);

private:
  const Scene& scene;
  double base = std::numeric_limits<double>::infinity();
  bool has_column = false;
  double peak_at_base = 0.0, peak_input = 0.0; ///< [m/s]
};

/// Appends the displacement, velocity and stress of the far field's first `n_monitors` monitors
/// to a history row (the channels of run_support::add_monitor_channels); Model is
/// fem::ElasticWaveModel or fem::DistributedWaveModel (collective).
template <class Model>
void append_far_field_monitors(std::vector<double>& row, const Model& far_field,
                               std::size_t n_monitors)
{
  for (std::size_t k = 0; k < n_monitors; ++k)
  {
    const fem::MonitorSample s = far_field.sample_monitor(k);
    row.insert(row.end(), {s.displacement[0], s.displacement[1], s.velocity[0], s.velocity[1],
                           s.stress[0], s.stress[1], s.stress[2]});
  }
}
/// What a far field tied to the blocks does the same way whatever its model (Model:
/// fem::ElasticWaveModel, or fem::DistributedWaveModel whose calls here are collective): its
/// channels and rows, the ties' snapshot, the impedance warning and summary.json's "model".
template <class Model>
class TiedFarFieldOf : public TiedFarField
{
public:
  /// `arguments` make the far field.
  template <class... ModelArguments>
  TiedFarFieldOf(const Scene& scene_, dda::System& system_, ModelArguments&&... arguments)
      : scene(scene_), system(system_), far_field(std::forward<ModelArguments>(arguments)...),
        ties(system, far_field, *scene.interface), arrival(scene_, system_)
  {
  }

  std::string impedance_warning() const override
  {
    return tied_impedance_warning(scene, system, ties);
  }
  void add_channels(std::vector<HistoryChannel>& channels) const override
  {
    add_tied_channels(channels, *scene.far_field);
    arrival.add_channel(channels);
  }
  void append_row(std::vector<double>& row) override
  {
    append_far_field_monitors(row, far_field, scene.far_field->monitors.size());
    append_tied_energies(row, far_field.energy(), ties);
    if (arrival.recorded())
      arrival.append(row, far_field.free_field_velocity(arrival.height()), far_field.time());
  }
  std::vector<dda::ContactSnapshot> tie_snapshot() const override
  {
    return tie_contacts(ties, system);
  }

protected:
  /// summary.json's far_field.free_field_at_base, where recorded.
  void add_arrival_summary(nlohmann::json& summary) const
  {
    if (arrival.recorded())
      summary["far_field"]["free_field_at_base"] =
          arrival.summary(far_field.p_wave_speed(), far_field.s_wave_speed());
  }
  /// summary.json's "model": the far field's mesh and the ties.
  void add_model_summary(nlohmann::json& summary) const
  {
    summary["model"]["far_field_cells"] = far_field.n_cells();
    summary["model"]["far_field_dofs"] = far_field.n_dofs();
    summary["model"]["element_size_m"] = far_field.element_size();
    summary["model"]["ties"] = ties.n_ties();
    summary["model"]["tied_edges"] = ties.n_tied_edges();
    summary["model"]["tied_blocks"] = ties.n_tied_blocks();
  }

  const Scene& scene;
  dda::System& system;
  Model far_field;
  coupling::FarFieldTies ties; ///< after far_field: it holds a reference to it
  BaseArrival arrival;
};

/// The far field's timings for summary.json [s]: setup, assemble, solve, update.
nlohmann::json far_field_timings(const fem::Timings& timings);

/// Writes the histories and snapshots of a far field alone into one directory, timing itself.
class FarFieldOutputs
{
public:
  /// Opens DIR/histories.h5 with the far field's monitors and energies; `scene_file` goes into
  /// its attributes.
  FarFieldOutputs(const std::filesystem::path& dir, const std::string& scene_file,
                  fem::ElasticWaveModel& model, const fem::FarFieldDescription& description,
                  fem::VtuCompression vtu_compression);
  /// Reopens the outputs of a run resumed from a checkpoint (save): histories.h5 cut back to
  /// the rows it had then.
  FarFieldOutputs(const std::filesystem::path& dir, fem::ElasticWaveModel& model,
                  const fem::FarFieldDescription& description, fem::VtuCompression vtu_compression,
                  CheckpointIn& archive);
  /// Checkpoints: after flush(), the rows and snapshots written so far.
  void save(CheckpointOut& archive) const;

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
  std::optional<double> last_row_time, last_snapshot_time; ///< [s]
};

/// Everything summary.json says about a run of a far field alone that has ended.
struct FarFieldRunRecord
{
  const Scene& scene;
  const fem::ElasticWaveModel& model;
  const StepResult& failure; ///< outcome success if the run completed
  const FarFieldOutputs& outputs;
  const std::vector<std::string>& warnings;
  double wall_time = 0.0; ///< [s]
};

nlohmann::json far_field_run_summary(const FarFieldRunRecord& run);

} // namespace ddafem
