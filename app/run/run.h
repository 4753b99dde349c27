// The `check` (app/scene/check_scene.cc) and `run` (app/run/run.cc) commands on a read scene.
#pragma once

#include "app/scene/scene.h"

#include <ostream>
#include <string>
#include <vector>

namespace ddafem
{
/// Model summary printed by `ddafem check` (blocks, joints, DOFs, mass, wave speeds, smallest
/// block, suggested dt range). Throws InputError for what only the engine can detect.
std::string check_scene(const Scene& scene);

struct RunOptions
{
  std::string output_directory; ///< empty: the scene's output.directory
  bool quiet = false;           ///< no progress line
  /// Run even if a boundary is an energy source at the scene's dt (to show the failure).
  bool allow_unstable = false;
  /// Threads of the blocks' iterative solver (solver.method block_pcg); 0: all cores. The
  /// results do not depend on it.
  unsigned threads = 0;
  /// Stop cleanly after the step at which the wall time reaches this [s] (exit code 3,
  /// status "stopped"); 0: no budget.
  double max_wall_time = 0.0;
  /// Stop cleanly after a step at which the resident memory exceeds this [bytes] (--max-memory,
  /// which also refuses a scene estimated beyond it); 0: no budget.
  double max_memory = 0.0;
  /// Stop cleanly (exit code 3, status "stopped") after the step at which a keyblock has fallen
  /// that the excavation did not release (--stop-at-first-fall; `ddafem sweep --find
  /// first_fall` asks for it: the verdict is known then).
  bool stop_at_first_fall = false;
  /// The --set overrides as given, kept in checkpoints so that `resume` reads the scene the
  /// same way.
  std::vector<std::string> settings;
};

class CheckpointReader;

/// Runs a scene (blocks alone, tied to a far field, or a far field alone) and writes
/// histories.h5, the snapshots (model.pvd, or far_field.pvd for a far field alone, + .vtu) and
/// summary.json into the output directory. Returns the process exit code: 0 on success, 1 on a
/// numerical failure (its reason and the time reached are printed to `log` and stored in
/// summary.json; everything written so far stays readable). Bad input throws InputError before
/// anything is written. A run stopped at a budget (max_wall_time, max_memory) writes its state
/// and summary.json with the status "stopped" and returns 3.
/// Every output.checkpoint_every of wall time, and when a budget stops it, the run writes a
/// checkpoint (app/run/checkpoint.h) between two steps of a stage. With `resume_from` (a
/// checkpoint of this scene in the output directory) the run continues from it instead of
/// starting: its outputs are reopened as they were then, and it goes on as the run that wrote it
/// would have, bit for bit.
int run_scene(const Scene& scene, const RunOptions& options, std::ostream& log,
              CheckpointReader* resume_from = nullptr);

} // namespace ddafem
