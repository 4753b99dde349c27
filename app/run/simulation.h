// What the run driver (app/run/run.cc) needs of a model: blocks (alone or tied to a far field) and
// a far field alone are two simulations behind one interface, so that every run reads `setup(); for
// each stage run_stage(); write_summary();`.
#pragma once

#include "app/scene/scene.h"

#include "common/checkpoint_fwd.h"

#include <nlohmann/json.hpp>

#include <optional>

#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace ddafem
{
/// How a run ended, for its last lines on the log.
struct RunEnd
{
  std::string failure;   ///< the numerical failure that stopped the run; empty if it completed
  std::string steps;     ///< e.g. "300 steps" or "600 half steps"
  double time = 0.0;     ///< simulated time reached [s]
  std::string view_file; ///< the PVD file that opens the results in ParaView
};

/// A model the driver runs stage by stage. Constructing one builds the models: input errors
/// surface there, before anything is written.
class Simulation
{
public:
  virtual ~Simulation() = default;

  /// The run's warnings; throws InputError for what `run` refuses (a boundary that is an energy
  /// source at the scene's dt, unless `allow_unstable`).
  virtual std::vector<std::string> collect_warnings(bool allow_unstable) const = 0;
  /// Opens histories.h5 and the snapshot series in `dir`.
  virtual void open_outputs(const std::filesystem::path& dir) = 0;

  virtual std::size_t n_stages() const = 0;
  /// Runs stage k, calling `report` after every step; false if it failed or `report` returned
  /// false (a budget: the stage stops after that step), and the run stops.
  virtual bool run_stage(std::size_t k, const std::function<bool()>& report) = 0;
  /// Writes the state reached where it is not yet a snapshot and flushes the outputs.
  virtual void close_outputs() = 0;
  /// Writes the buffered history rows and flushes histories.h5 to disk: a run killed after this
  /// leaves every row so far readable.
  virtual void flush_outputs() = 0;

  /// Checkpoints (app/run/checkpoint.h). Whether one can be taken now: between two steps of a
  /// stage (not before the first step).
  virtual bool can_checkpoint() const = 0;
  /// Stores the run's whole state (when can_checkpoint(), after flush_outputs()).
  virtual void save_checkpoint(CheckpointOut& archive) const = 0;
  /// Restores a checkpoint into a simulation built from the same scene, in place of
  /// open_outputs: the outputs in `dir` are reopened as they were at the checkpoint. Returns the
  /// stage to go on with: its run_stage continues it from the step saved.
  virtual std::size_t resume(CheckpointIn& archive, const std::filesystem::path& dir) = 0;

  /// A keyblock that has fallen (not one a static stage released), if any: blocks only.
  virtual std::optional<std::size_t> fallen_keyblock() const { return std::nullopt; }
  virtual std::size_t n_steps() const = 0; ///< steps taken so far
  virtual double time() const = 0;         ///< simulated time reached [s]
  virtual double end_time() const = 0;     ///< the scene's end time [s]

  /// summary.json of the ended run, with its `warnings` and wall time [s].
  virtual nlohmann::json summary(const std::vector<std::string>& warnings,
                                 double wall_time) const = 0;
  virtual RunEnd end() const = 0;
};

/// Blocks alone or tied to a far field (app/run/blocks_simulation.cc).
std::unique_ptr<Simulation> make_blocks_simulation(const Scene& scene);

} // namespace ddafem
