// docs/scene_reference.md, rendered from the schema (`ddafem scene-reference`).
#include "app/scene/scene.h"
#include "app/schema/scene_schema.h"

#include <sstream>
#include <string>

namespace ddafem
{
namespace
{
using schema::Key;
using schema::SceneSchema;
using schema::Section;
using schema::ValueType;

std::string table_cell(std::string text)
{
  std::string escaped;
  for (const char c : text)
    escaped += c == '|' ? std::string("\\|") : std::string(1, c);
  return escaped;
}

std::string section_heading(const Section& s)
{
  if (s.id == SceneSchema::top_level)
    return "Top level";
  return "`" + s.id + "`";
}

std::string type_cell(const Key& k)
{
  switch (k.type)
  {
  case ValueType::section:
  case ValueType::section_map:
  case ValueType::section_list:
    return std::string(name_of(k.type)) + ", see `" + k.section + "`";
  case ValueType::time_function:
    return "time function, see below";
  default:
    return name_of(k.type);
  }
}

std::string default_cell(const Key& k)
{
  if (k.required)
    return "**required**";
  if (!k.default_yaml.empty())
    return "`" + (k.default_yaml == "''" ? std::string("\"\"") : k.default_yaml) + "`";
  return k.default_note;
}

std::string allowed_cell(const Key& k)
{
  if (k.type == ValueType::choice)
  {
    std::string choices;
    for (const std::string& c : k.choices)
      choices += (choices.empty() ? "`" : ", `") + c + "`";
    return choices;
  }
  const std::string r = k.range.describe();
  const bool vector = k.type == ValueType::vector2 || k.type == ValueType::integer_pair ||
                      k.type == ValueType::integer_pair_list || k.type == ValueType::voigt;
  return r.empty() ? "" : (vector ? "each " : "") + r;
}
} // namespace

std::string scene_reference_markdown()
{
  const SceneSchema schema;
  // A small scene using most sections; a test reads it, so it stays valid.
  const char* const example = R"(name: two_blocks
materials:
  rock: {density: 2650, youngs_modulus: 50e9, poisson_ratio: 0.25}
joint_materials:
  glued: {normal_stiffness: 5e10, friction_angle: 30}
joints: {default: glued}
blocks:
  - material: rock
    vertices: [[0, 0], [2, 0], [2, 1], [0, 1]]
  - material: rock
    grid: {origin: [0, 1], cell_size: [1, 1], count: [2, 1]}
fixed_points:
  - {point: [1, 0]}
point_loads:
  - point: [0.5, 2]
    force: [0, -1e6]
    time_function: {type: sine_pulse, frequency: 100}
gravity: [0, -9.81]
monitors:
  - {name: top, point: [1.5, 1.5]}
boundaries:
  - {type: vb1, on_line: {point: [2, 0], direction: [0, 1]}}
time: {dt: 1e-4, end_time: 0.05}
output: {directory: results/two_blocks, interval: 0.001}
)";
  std::ostringstream md;
  md << "# Scene file reference\n\n"
     << "This file is generated from the schema that the scene reader validates against "
        "(`app/schema/scene_schema.cc` and `app/schema/schema_*.cc`).\nDo not edit it; regenerate "
        "it with\n\n"
     << "    build/ddafem scene-reference > docs/scene_reference.md\n\n"
     << "## Conventions\n\n"
     << "- A scene is a YAML file. Units are SI: m, s, kg, N, Pa; angles in degrees.\n"
     << "- Every map rejects keys that are not listed here, and suggests the closest allowed "
        "key.\n"
     << "- `blocks[i]` is item `i` (from 0) of the list `blocks`; `materials.<name>` is an entry "
        "of the map `materials` under a name you choose.\n"
     << "- Points of point loads, fixed points and monitors must lie inside or on the boundary "
        "of a block.\n"
     << "- Every key can be overridden on the command line without editing the file: "
        "`--set time.dt=1e-4`, `--set gravity=[0,-9.81]`, `--set blocks.0.material=granite`. "
        "Path components are separated by `.`, list items are addressed by their index, and "
        "the value is read as YAML.\n"
     << "- A time function is a map whose `type` selects one of the kinds at the end of this "
        "page.\n\n"
     << "## Example\n\n```yaml\n"
     << example << "```\n";
  for (const Section& s : schema.sections())
  {
    md << "\n## " << section_heading(s) << "\n\n"
       << s.meaning << "\n\n"
       << "| key | type | unit | default | allowed | meaning |\n"
       << "|---|---|---|---|---|---|\n";
    for (const Key& k : s.keys)
      md << "| `" << k.name << "` | " << table_cell(type_cell(k)) << " | "
         << table_cell(k.unit.empty() ? "-" : k.unit) << " | " << table_cell(default_cell(k))
         << " | " << table_cell(allowed_cell(k)) << " | " << table_cell(k.meaning) << " |\n";
  }
  return md.str();
}

} // namespace ddafem
