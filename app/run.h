// The `check` and `run` commands on a read scene.
#pragma once

#include "app/scene.h"

#include <ostream>
#include <string>

namespace ddafem
{
/// Wave speeds of an isotropic elastic material [m/s].
struct WaveSpeeds
{
  double p_body = 0.0;  ///< sqrt(E (1-nu) / (rho (1+nu)(1-2nu))), plane strain / 3D P wave
  double p_plate = 0.0; ///< sqrt(E / (rho (1-nu^2))), P wave in plane stress
  double p_bar = 0.0;   ///< sqrt(E / rho), one-block-high bar (free lateral faces)
  double s = 0.0;       ///< sqrt(E / (2 rho (1+nu)))
};
WaveSpeeds wave_speeds(const dda::Material& material);

/// Suggested time-step range [s] for a scene and why.
struct TimeStepAdvice
{
  double dt_min = 0.0;
  double dt_max = 0.0;
  std::string reason;
};
TimeStepAdvice suggest_time_step(const Scene& scene);

/// Model summary printed by `ddafem check` (blocks, joints, DOFs, mass, wave speeds, smallest
/// block, suggested dt range). Throws InputError for what only the engine can detect.
std::string check_scene(const Scene& scene);

struct RunOptions
{
  std::string output_directory; ///< empty: the scene's output.directory
  bool quiet = false;           ///< no progress line
  /// Run even if a boundary is an energy source at the scene's dt (to show the failure).
  bool allow_unstable = false;
};

/// Runs a scene and writes histories.h5, blocks.pvd (+ .vtu) and summary.json into the output
/// directory. Returns the process exit code: 0 on success, 1 on a numerical failure (its reason
/// and the time reached are printed to `log` and stored in summary.json; everything written so
/// far stays readable). Bad input throws InputError before anything is written.
int run_scene(const Scene& scene, const RunOptions& options, std::ostream& log);

/// `check` of a far-field-only scene: mesh, wave speeds, elements per wavelength, boundaries.
std::string check_far_field(const Scene& scene);

/// `run` of a far-field-only scene: histories.h5 (monitors and energies), far_field.pvd (+ .vtu)
/// and summary.json, with the exit codes of run_scene.
int run_far_field(const Scene& scene, const RunOptions& options, std::ostream& log);

} // namespace ddafem
