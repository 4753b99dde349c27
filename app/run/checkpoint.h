// Checkpoint files (issue 20): DIR/checkpoint.bin holds what `ddafem resume DIR` needs to
// continue a killed or stopped run: which scene, with which --set overrides, and the run's whole
// state at the end of an accepted step (Simulation::save_checkpoint).
#pragma once

#include "app/run/simulation.h"

#include "common/checkpoint_fwd.h"

#include <cstddef>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace ddafem
{
/// What a checkpoint says of the run it belongs to.
struct CheckpointHeader
{
  std::string version;               ///< ddafem's, which must match on resuming
  std::string scene_file;            ///< absolute path
  std::string scene_text;            ///< the scene file's text when the run started
  std::vector<std::string> settings; ///< --set key=value, as given
  bool allow_unstable = false;
};

/// The checkpoint file of an output directory.
std::filesystem::path checkpoint_path(const std::filesystem::path& dir);

/// The scene file's text (empty if it cannot be read).
std::string scene_file_text(const std::string& file);

/// Writes the header and the simulation's state to DIR/checkpoint.bin atomically (a .tmp file
/// renamed into place: a kill while writing leaves the previous checkpoint). Returns its size
/// [bytes].
std::size_t write_checkpoint(const std::filesystem::path& dir, const CheckpointHeader& header,
                             const Simulation& simulation);

/// An open checkpoint: its header, and the archive positioned at the simulation's state.
class CheckpointReader
{
public:
  /// Throws InputError naming the file if there is none, it is not a checkpoint, or ddafem's
  /// version differs from the one that wrote it.
  explicit CheckpointReader(const std::filesystem::path& dir);
  ~CheckpointReader();

  const CheckpointHeader& header() const { return head; }
  CheckpointIn& archive() { return *in; }
  const std::filesystem::path& file() const { return path; }

private:
  std::filesystem::path path;
  std::istringstream text;
  std::unique_ptr<CheckpointIn> in;
  CheckpointHeader head;
};

} // namespace ddafem
