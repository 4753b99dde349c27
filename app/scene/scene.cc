// Reading a scene: the file, the --set overrides, the tunnel's expansion, then every section in
// the order they depend on each other (the readers: app/scene/scene_readers.h).
#include "app/scene/scene.h"

#include "app/scene/scene_readers.h"
#include "app/schema/bound_sections.h"

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <optional>
#include <sstream>
#include <utility>

namespace ddafem
{
using namespace scene_reading;

namespace
{

Scene read_validated_scene(const std::string& file, const YAML::Node& root, const Context& context)
{
  if (!root.IsMap())
    throw context.locator.error(root, "", yaml_text(root),
                                "expected a map of scene sections (materials, blocks, time, ...)");
  const MapReader top(root, context.schema.section(SceneSchema::top_level), "", context);
  Scene scene;
  scene.file = file;
  scene.name = top.has("name") ? top.string("name") : std::filesystem::path(file).stem().string();
  schema::top_level_keys().fill(top, scene); // description, gravity
  dda::ModelDescription& model = scene.model;
  read_analysis(top, model);
  const SceneNames names = read_materials(top, model);
  if (top.has("far_field"))
    scene.far_field = read_far_field(top.section_reader("far_field"), model, names.materials);

  std::vector<BlockSource> sources;
  read_blocks(top, names, model, sources, scene.rock_mass);
  check_overlaps(model, sources, context.locator);
  if (top.has("in_situ_stress"))
    read_in_situ_stress(top, sources, model);
  const BlockBoxes boxes = block_boxes(model);
  read_point_loads(top, boxes, model);
  read_fixed_points(top, boxes, model);
  read_bolts(top, boxes, model);
  if (scene.far_field && scene.far_field->static_stage.enabled &&
      !top.section_reader("far_field").section_reader("static_stage").has("gravity"))
    scene.far_field->static_stage.gravity = {model.gravity.x(), model.gravity.y()};
  read_monitors(top, boxes, model, scene.far_field);
  for (const MapReader& r : top.section_list("boundaries"))
    model.boundaries.push_back(read_boundary(r, model));

  complete_damping(top, scene);
  read_time(top, model.time);
  read_contacts(top, model.contacts);
  read_stages(top, model);
  read_linings(top, scene.rock_mass, model);
  complete_far_field(top, names.joint_materials, scene);
  model.solver = read_solver(top);
  scene.output = read_output(top);
  return scene;
}

/// The overrides, the tunnel's expansion and every section, on the scene's YAML tree `root`.
Scene read_scene_tree(const std::string& file, YAML::Node& root,
                      const std::vector<Override>& overrides, const ResourceLimits& limits)
{
  const SceneSchema schema;
  Locator locator(file);
  try
  {
    for (const Override& o : overrides)
      locator.add_override(apply_override(root, o));
    const Context context{schema, locator, std::filesystem::path(file).parent_path(), limits};
    std::optional<TunnelPlan> tunnel;
    if (root.IsMap() && child(root, "tunnel").IsDefined())
      tunnel = expand_tunnel(root, context);
    Scene scene = read_validated_scene(file, root, context);
    scene.tunnel = std::move(tunnel);
    scene.limits = limits;
    if (scene.tunnel)
      scene.expanded_yaml = YAML::Dump(root);
    return scene;
  }
  catch (const YAML::Exception& e)
  {
    // Anything the YAML library objects to beyond syntax (aliases, conversions).
    throw InputError::at(file, e.mark.is_null() ? 0 : e.mark.line + 1, "", "",
                         "cannot read the YAML tree: " + e.msg);
  }
}
} // namespace

Override parse_override(const std::string& argument)
{
  const auto equals = argument.find('=');
  if (equals == std::string::npos || trim(argument.substr(0, equals)).empty())
    throw InputError::at(command_line_location(argument), 0, "", "",
                         "expected path.to.key=value, e.g. --set time.dt=1e-4 or --set "
                         "blocks.0.material=granite");
  return {trim(argument.substr(0, equals)), argument.substr(equals + 1)};
}

Scene read_scene(const std::string& file, const std::vector<Override>& overrides,
                 const ResourceLimits& limits)
{
  YAML::Node root = load_yaml(file);
  return read_scene_tree(file, root, overrides, limits);
}

Scene read_scene_text(const std::string& text, const std::string& file,
                      const std::vector<Override>& overrides, const ResourceLimits& limits)
{
  std::istringstream in(text);
  YAML::Node root = parse_yaml(in, file);
  return read_scene_tree(file, root, overrides, limits);
}

} // namespace ddafem
