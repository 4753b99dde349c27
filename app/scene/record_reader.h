// Recorded ground motions in scenes: the `record` time function (docs/ground_motions.md).
// Reads a PEER NGA file (.AT2, .VT2, .DT2) or a table of acceleration, velocity or displacement,
// cuts, tapers, baseline-corrects and scales it (common/ground_motion.h) and gives the velocity
// or displacement a scene key asks for, as the incident wave (half an outcrop record).
#pragma once

#include "app/scene/map_reader.h"
#include "common/time_function.h"

#include <filesystem>
#include <string>

namespace ddafem::scene_reading
{
/// What a scene key's time function gives.
enum class TimeFunctionUse
{
  factor,      ///< a dimensionless factor or a load's value: no record
  velocity,    ///< a velocity [m/s] (an incident wave, a boundary input)
  displacement ///< a displacement [m] (a fixed point's motion)
};

/// The path of the file named by key `key` of `r` (relative to the scene's directory), which
/// must be a regular file: opening a named pipe or a device would wait for a writer. `what`
/// names the file in messages ("CSV file").
std::filesystem::path scene_file(const MapReader& r, const std::string& key,
                                 const std::string& what);

/// A `record` time function's map (`r`), as the quantity `use` asks for (not `factor`).
TimeFunction read_record(const MapReader& r, TimeFunctionUse use);

} // namespace ddafem::scene_reading
