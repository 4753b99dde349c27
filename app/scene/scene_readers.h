// The scene's section readers, one file per family (private to app/scene/scene*.cc):
// app/scene/scene_model_reader.cc   analysis, materials, joints, time functions, boundaries, time,
//                             contacts, stages, solver, output
// app/scene/scene_block_reader.cc   blocks, the overlap check, in-situ stress, loads, fixed points,
//                             monitors
// app/scene/scene_rock_mass_reader.cc  rock_mass (region, joint sets, joints, openings)
// app/scene/scene_far_field_reader.cc  far_field, interface and their checks against the model
// app/scene/scene_tunnel_reader.cc  the tunnel section and its expansion into a scene
// app/scene/scene.cc gathers them in the order the sections depend on each other.
#pragma once

#include "app/scene/map_reader.h"
#include "app/scene/record_reader.h"
#include "app/scene/scene.h"
#include "dda/model_description.h"
#include "dda/rock_mass.h"

#include <yaml-cpp/yaml.h>

#include <array>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace ddafem::scene_reading
{
/// The names defined by `materials` and `joint_materials`, in their order (indices into the
/// model's materials and joint materials).
struct SceneNames
{
  std::vector<std::string> materials;
  std::vector<std::string> joint_materials;
};

/// Where a block came from, for messages.
struct BlockSource
{
  YAML::Node node;
  std::string key_path;
  bool generated = false;      ///< by `rock_mass`: disjoint from the other generated blocks
  bool initial_stress = false; ///< has an explicit `initial_stress` (else the in-situ stress)
};

/// Axis-aligned bounding box [m].
struct Box
{
  Point lower = Point::Constant(std::numeric_limits<double>::max());
  Point upper = Point::Constant(std::numeric_limits<double>::lowest());

  explicit Box(const std::vector<Point>& vertices)
  {
    for (const Point& v : vertices)
    {
      lower = lower.cwiseMin(v);
      upper = upper.cwiseMax(v);
    }
  }
  bool contains(const Point& p, double tol) const
  {
    return p.x() >= lower.x() - tol && p.x() <= upper.x() + tol && p.y() >= lower.y() - tol &&
           p.y() <= upper.y() + tol;
  }
};

/// The blocks' boxes and the tolerance [m] for points on their boundaries (1e-9 of the diagonal
/// of the box around all blocks).
struct BlockBoxes
{
  std::vector<Box> boxes;
  double tolerance = 0.0;
};

// ---- Model (app/scene/scene_model_reader.cc)
// ------------------------------------------------------

/// The time function at key `name` of `parent`, giving what `use` says (a record needs to know).
TimeFunction read_time_function(const MapReader& parent, const std::string& name,
                                TimeFunctionUse use);
/// `analysis`: plane mode and geometry.
void read_analysis(const MapReader& top, dda::ModelDescription& model);
/// `materials`, `joint_materials` and `joints`.
SceneNames read_materials(const MapReader& top, dda::ModelDescription& model);
/// The damping frequencies not given (the dominant frequency of the scene's input; InputError
/// naming the key if none is known) and the far field's Rayleigh beta from its material's damping
/// (a warning where `far_field.rayleigh` is given instead); after the boundaries and far field.
void complete_damping(const MapReader& top, Scene& scene);
dda::BoundaryDescription read_boundary(const MapReader& r, const dda::ModelDescription& model);
void read_time(const MapReader& top, dda::TimeSettings& time);
void read_contacts(const MapReader& top, dda::ContactSettings& contacts);
void read_stages(const MapReader& top, dda::ModelDescription& model);
dda::SolverSettings read_solver(const MapReader& top);
OutputSettings read_output(const MapReader& top);

// ---- Blocks (app/scene/scene_block_reader.cc)
// -----------------------------------------------------

/// Drops a repeated closing vertex, checks that the polygon (at key `key` of r) is simple and
/// orders it anticlockwise.
std::vector<Point> clean_polygon(const MapReader& r, const std::string& key,
                                 std::vector<Point> vertices);
/// [[x, y], ...] as points [m].
std::vector<Point> points_of(const std::vector<std::array<double, 2>>& pairs);
/// `blocks` and `rock_mass`, appended to the model with their sources.
void read_blocks(const MapReader& top, const SceneNames& names, dda::ModelDescription& model,
                 std::vector<BlockSource>& sources, std::optional<RockMassReport>& rock_mass);
/// Overlapping blocks are an error.
void check_overlaps(const dda::ModelDescription& model, const std::vector<BlockSource>& sources,
                    const Locator& locator);
/// `in_situ_stress`: the initial stress of every block without its own.
void read_in_situ_stress(const MapReader& top, const std::vector<BlockSource>& sources,
                         dda::ModelDescription& model);
BlockBoxes block_boxes(const dda::ModelDescription& model);
/// `point_loads` and `fixed_points`, each inside some block.
void read_point_loads(const MapReader& top, const BlockBoxes& boxes, dda::ModelDescription& model);
void read_fixed_points(const MapReader& top, const BlockBoxes& boxes, dda::ModelDescription& model);
/// `bolts`: each end in a block, the two ends in different blocks, pretension below yield.
void read_bolts(const MapReader& top, const BlockBoxes& boxes, dda::ModelDescription& model);
/// `linings`: every node on or in a block, `installed_after` a stage's name (after `stages`);
/// `opening` an index into the rock mass's openings.
void read_linings(const MapReader& top, const std::optional<RockMassReport>& rock_mass,
                  dda::ModelDescription& model);
/// What `bolts[i].type` (already filled) asks: no grouted keys on an end-anchored bolt; a
/// grouted bolt's shear capacity and crossings (app/scene/scene_bolt_reader.cc).
void read_bolt_type(const MapReader& r, dda::BoltDescription& b,
                    const dda::ModelDescription& model);
/// A grouted bolt's crossings through the model's blocks (into b.crossings); empty, or what is
/// wrong with its line ("does not reach a second block ...", "runs through a void ...").
std::string find_grouted_crossings(dda::BoltDescription& b, const dda::ModelDescription& model);
/// `monitors`: in a coupled scene a monitor belongs to the block it lies in, else to the far
/// field.
void read_monitors(const MapReader& top, const BlockBoxes& boxes, dda::ModelDescription& model,
                   std::optional<fem::FarFieldDescription>& far_field);

// ---- Rock mass (app/scene/scene_rock_mass_reader.cc)
// ----------------------------------------------

dda::JointSet read_joint_set(const MapReader& r);
/// `rock_mass.openings[i]`, checked to lie inside the region (as the polygon excavated).
dda::Opening read_opening(const MapReader& r, const std::vector<Point>& region,
                          double chord_tolerance);
/// The `joint_material` of a joint set or explicit joint (an index into joint_names), if given.
std::optional<std::size_t> read_joint_material(const MapReader& r,
                                               const std::vector<std::string>& joint_names);
/// The `rock_mass` section: generates its blocks and appends them to the model.
RockMassReport read_rock_mass(const MapReader& r, const SceneNames& names,
                              dda::ModelDescription& model, std::vector<BlockSource>& sources);

// ---- Far field and interface (app/scene/scene_far_field_reader.cc)
// --------------------------------

/// Monitors of a far-field scene must lie in its rectangle.
void check_point_in_far_field(const MapReader& r, const std::string& key, const Point& p,
                              const fem::FarFieldDescription& far_field);
/// The `far_field` section (the plane mode, time step and integrator come from the scene).
fem::FarFieldDescription read_far_field(const MapReader& f, const dda::ModelDescription& model,
                                        const std::vector<std::string>& material_names);
/// What the far field takes from the rest of the scene (gravity, time step, integrator, the
/// `interface`), and the checks between them.
void complete_far_field(const MapReader& top, const std::vector<std::string>& joint_names,
                        Scene& scene);

// ---- Tunnel (app/scene/scene_tunnel_reader.cc)
// ----------------------------------------------------

/// The `tunnel` section: reads it, plans the model (app/scene/tunnel_scene.h) and writes the
/// sections it generates into `root`, which is then read like any scene.
TunnelPlan expand_tunnel(YAML::Node& root, const Context& context);

} // namespace ddafem::scene_reading
