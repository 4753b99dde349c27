// The far field (deal.II continuum) and its ties to the blocks live in a module,
// libddafem_far_field.so, loaded when a scene has a far field: a blocks-only run starts without
// deal.II, Trilinos and their ~200 shared libraries (issue 19: 0.19 s and 150 MiB before). This
// header is all the core (the blocks, the scenes, the run driver) sees of it; the module's side
// is app/far_field_module/far_field_parts.h.
#pragma once

#include "app/run/simulation.h"
#include "app/scene/scene.h"

#include "common/checkpoint_fwd.h"
#include "common/history_writer.h"
#include "dda/system.h"
#include "dda/vtu_writer.h"
#include "fem/far_field_description.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace ddafem
{
/// A far field tied to the blocks of a System (the ties enter the System's steps through
/// dda::TiedBody), as the blocks' run, its outputs and `check` see it.
class TiedFarField
{
public:
  virtual ~TiedFarField() = default;

  /// Why the interface reflects more than 1 % of a normally incident wave; empty below.
  virtual std::string impedance_warning() const = 0;
  /// The far field's and the interface's history channels (after the blocks').
  virtual void add_channels(std::vector<HistoryChannel>& channels) const = 0;
  /// Their values now, in the order of add_channels (each accepted step; a far field may keep
  /// statistics of them for add_to_summary, e.g. peaks).
  virtual void append_row(std::vector<double>& row) = 0;
  /// Writes the far field's VTU snapshot into `dir`; returns its file name.
  virtual std::string write_snapshot(const std::filesystem::path& dir,
                                     fem::VtuCompression compression) = 0;
  /// The ties as contact points for VTU (state, normal, forces, opening and slip).
  virtual std::vector<dda::ContactSnapshot> tie_snapshot() const = 0;
  /// summary.json's far-field sizes (in "model"), "far_field" and "interface".
  virtual void add_to_summary(nlohmann::json& summary) const = 0;
  /// `check`'s lines on the far field and the interface.
  virtual void describe(std::ostream& out) const = 0;
  /// Checkpoints: the far field's and the ties' state between two steps.
  virtual void save(CheckpointOut& archive) const = 0;
  virtual void load(CheckpointIn& archive) = 0;
  /// Whether save() can write the far field (not yet across MPI ranks).
  virtual bool can_checkpoint() const { return true; }
  /// Whether the run goes on after this step: on one process `go` itself; across MPI ranks
  /// (collective) false if any rank's `go` is, so that a budget one rank reaches stops every
  /// rank after the same step.
  virtual bool all_go_on(bool go) const { return go; }
};

/// What the module offers.
class FarFieldModule
{
public:
  virtual ~FarFieldModule() = default;

  /// Builds the scene's far field and ties it to `system` (which must outlive the result).
  virtual std::unique_ptr<TiedFarField> tie(const Scene& scene, dda::System& system) const = 0;
  /// A run of a far field alone.
  virtual std::unique_ptr<Simulation> far_field_simulation(const Scene& scene) const = 0;
  /// A run of a far field alone distributed over the MPI ranks the process was started on by
  /// mpirun (issue 22): starts MPI. Every rank runs it; rank 0 writes the run's files.
  virtual std::unique_ptr<Simulation>
  distributed_far_field_simulation(const Scene& scene) const = 0;
  /// `check` of a far field alone.
  virtual std::string check_far_field(const Scene& scene) const = 0;
  /// After an error on this rank of a distributed run (MPI started, more than one rank): ends
  /// every rank with `exit_code` (MPI_Abort), since the others may be waiting for this one in a
  /// collective call and MPI's finalization would wait for them. Otherwise returns.
  virtual void end_every_rank_after_error(int exit_code) const = 0;
};

/// The module: linked in (the test programs) or loaded from libddafem_far_field.so beside the
/// executable on first use, and never unloaded. Throws InputError naming the file and the
/// loader's reason if it cannot be loaded.
const FarFieldModule& far_field_module();
/// After an error: FarFieldModule::end_every_rank_after_error if the module has been loaded
/// (only the module starts MPI); otherwise nothing.
void end_every_rank_after_error(int exit_code);

} // namespace ddafem

/// The module's one entry point (app/far_field_module/far_field_entry.cc).
extern "C" const ddafem::FarFieldModule* ddafem_far_field_module();
