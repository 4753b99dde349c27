// A scene: the YAML file a user writes, read into validated model descriptions.
#pragma once

#include "app/scene/tunnel_scene.h"
#include "common/resource_limits.h"
#include "coupling/far_field_ties.h"
#include "dda/model_description.h"
#include "dda/rock_mass.h"
#include "fem/far_field_description.h"

#include <optional>

#include <string>
#include <vector>

namespace ddafem
{
/// Where and how often results are written.
struct OutputSettings
{
  std::string directory = "results"; ///< relative to the working directory; `-o DIR` overrides
  double interval = 0.0; ///< simulated time between VTU snapshots [s]; 0: first and last only
  std::size_t history_every = 1; ///< steps between rows of the HDF5 histories, >= 1
  /// Wall-clock time between flushes of histories.h5 and the running summary.json to disk [s];
  /// a run killed at any moment keeps the rows up to its last flush. 0: after every step.
  double flush_interval = 2.0;
  /// Wall-clock time between checkpoints (checkpoint.bin, for `ddafem resume`) [s], written
  /// between two steps of a stage and when a budget stops the run; 0: none.
  double checkpoint_every = 60.0;
  fem::VtuCompression vtu_compression = fem::VtuCompression::best_speed; ///< far-field VTU zlib
};

/// What the `rock_mass` section generated (for `check` and the run's warnings).
struct RockMassReport
{
  std::size_t first_block = 0; ///< index of its first block in the model's blocks
  dda::RockMassStatistics statistics;
  std::vector<dda::Sliver> slivers; ///< kept slivers; `block` indexes the model's blocks
  std::vector<dda::JointSet> joint_sets;
  std::vector<dda::ExplicitJoint> joints;
  /// The `joint_material` of each joint set and each explicit joint, in their order: an index
  /// into the model's joint materials; none: `joints.default` (or `joints.pairs`).
  std::vector<std::optional<std::size_t>> joint_set_materials;
  std::vector<std::optional<std::size_t>> joint_materials;
  /// The openings as excavated: polygons, anticlockwise [m] (`linings[i].opening`).
  std::vector<std::vector<dda::Point>> openings;
};

/// A scene file, read and validated.
struct Scene
{
  std::string file;            ///< path of the scene file as given
  std::string name;            ///< `name:` key, or the file's stem
  std::string description;     ///< `description:` key (free text)
  dda::ModelDescription model; ///< the blocks (empty for a far-field-only scene)
  std::optional<fem::FarFieldDescription> far_field; ///< the `far_field` section, if any
  /// Blocks tied to the far field (both `blocks` and `far_field`): the `interface` section.
  std::optional<coupling::InterfaceDescription> interface;
  bool coupled() const { return far_field && !model.blocks.empty(); }
  std::optional<RockMassReport> rock_mass; ///< the `rock_mass` section's blocks, if any
  /// What a `tunnel` section chose, and the scene it expanded into (YAML), if any.
  std::optional<TunnelPlan> tunnel;
  std::string expanded_yaml;
  OutputSettings output;
  std::vector<std::string> warnings; ///< what the reader found worth saying (run, check print)
  ResourceLimits limits;             ///< what it was read against (check prints the estimate)
};

/// One `--set path.to.key=value` override; list items are addressed by index (blocks.0.material).
struct Override
{
  std::string path;
  std::string value; ///< parsed as a YAML scalar or flow sequence, e.g. "1e-4" or "[0, -9.81]"
};

/// Parses "path.to.key=value"; throws InputError on a malformed argument.
Override parse_override(const std::string& argument);

/// Reads, applies overrides to, and validates a scene file. Every problem throws InputError
/// naming the file, line, key, value and what was expected (unknown keys, wrong types, values
/// out of range, missing required keys, missing CSV files, unknown material names, polygons
/// that are not simple, overlapping blocks, points outside every block, ...).
/// The far field's element size away from its hole [m]: `element_size`, or
/// `points_per_wavelength` nodes per S wavelength at `max_frequency` (or the incident wave's);
/// 0 for a mesh file.
double far_field_element_size(const fem::FarFieldDescription& d);
/// About how many DOFs the far field's generated mesh will have, before it is made: the
/// rectangle and the ring graded from the hole (common/resource_limits.h); 0 for a mesh file.
double estimate_far_field_dofs(const fem::FarFieldDescription& d);

/// `limits`: a scene estimated to need more memory is refused (InputError naming the key that
/// drives it and the largest value that fits) before its blocks or far field are built.
Scene read_scene(const std::string& file, const std::vector<Override>& overrides = {},
                 const ResourceLimits& limits = ResourceLimits::of_this_machine());

/// read_scene for a scene given as `text`: `file` names it in messages and is where its
/// relative paths (CSV files, meshes) start; nothing is read from `file` itself.
Scene read_scene_text(const std::string& text, const std::string& file,
                      const std::vector<Override>& overrides = {},
                      const ResourceLimits& limits = ResourceLimits::of_this_machine());

/// Markdown reference of every scene key (type, unit, default, range, meaning), generated from
/// the same schema the reader validates against, so that it cannot drift.
std::string scene_reference_markdown();

} // namespace ddafem
