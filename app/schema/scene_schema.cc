#include "app/schema/scene_schema.h"

#include "app/schema/schema_sections.h"

#include "common/format.h"

#include <cassert>
#include <utility>

namespace ddafem::schema
{
bool Range::contains(double value) const
{
  if (min && (min_inclusive ? value < *min : value <= *min))
    return false;
  if (max && (max_inclusive ? value > *max : value >= *max))
    return false;
  return true;
}

std::string Range::describe() const
{
  if (min && max)
    return std::string(min_inclusive ? "[" : "(") + format_number(*min) + ", " +
           format_number(*max) + (max_inclusive ? "]" : ")");
  if (min)
    return std::string(min_inclusive ? ">= " : "> ") + format_number(*min);
  if (max)
    return std::string(max_inclusive ? "<= " : "< ") + format_number(*max);
  return "";
}

const Key* Section::find(const std::string& name) const
{
  for (const Key& k : keys)
    if (k.name == name)
      return &k;
  return nullptr;
}

const Key& Section::key(const std::string& name) const
{
  const Key* k = find(name);
  assert(k != nullptr && "the reader asked for a key that is not in the schema");
  return *k;
}

std::vector<std::string> Section::key_names() const
{
  std::vector<std::string> names;
  for (const Key& k : keys)
    names.push_back(k.name);
  return names;
}

std::string SceneSchema::time_function_section(const TimeFunctionType type)
{
  return std::string("time function: ") + name_of(type);
}

const Section& SceneSchema::section(const std::string& id) const
{
  for (const Section& s : all_sections)
    if (s.id == id)
      return s;
  assert(false && "unknown schema section");
  return all_sections.front();
}

SceneSchema::SceneSchema()
{
  all_sections = {top_level_section(),
                  analysis_section(),
                  materials_section(),
                  joint_materials_section(),
                  damping_section("materials.<name>.damping"),
                  damping_section("joint_materials.<name>.damping"),
                  damping_section("tunnel.damping"),
                  joints_section(),
                  joints_pairs_section(),
                  blocks_section(),
                  blocks_grid_section(),
                  rock_mass_section(),
                  rock_mass_region_section(),
                  rock_mass_region_rectangle_section(),
                  tunnel_section(),
                  tunnel_settle_section(),
                  tunnel_wave_section(),
                  tunnel_near_field_section(),
                  tunnel_static_section(),
                  tunnel_lining_section(),
                  tunnel_bolts_section(),
                  rock_mass_joint_sets_section(),
                  rock_mass_joint_sets_perturbation_section(),
                  rock_mass_joints_section(),
                  rock_mass_openings_section(),
                  rock_mass_openings_circle_section(),
                  rock_mass_openings_horseshoe_section(),
                  point_loads_section(),
                  fixed_points_section(),
                  bolts_section(),
                  linings_section(),
                  monitors_section(),
                  far_field_section(),
                  interface_section(),
                  far_field_boundaries_section(),
                  far_field_boundaries_springs_section(),
                  far_field_hole_section(),
                  far_field_static_stage_section(),
                  far_field_rayleigh_section(),
                  far_field_mesh_section(),
                  far_field_mesh_parts_section(),
                  far_field_incident_section(),
                  boundaries_section(),
                  in_situ_stress_section(),
                  boundaries_input_section(),
                  boundaries_on_line_section(),
                  time_section(),
                  contacts_section(),
                  stages_section(),
                  solver_section(),
                  output_section(),
                  constant_time_function_section(),
                  sine_pulse_time_function_section(),
                  table_time_function_section(),
                  csv_time_function_section(),
                  record_time_function_section()};
}

} // namespace ddafem::schema
