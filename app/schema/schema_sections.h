// The scene schema's sections, one function per section, in files by family
// (app/schema/scene_schema.cc gathers them in the order of docs/scene_reference.md).
#pragma once

#include "app/schema/schema_key_builder.h"

#include <string>

namespace ddafem::schema
{
/// `joint_material` of a joint set or an explicit joint of `rock_mass` (`along`: what it cuts).
Key joint_material_key(const std::string& along);
/// The `type` key of one time-function variant.
Key time_function_type(TimeFunctionType type);

// blocks, materials, joints, loads, boundaries, stages (app/schema/schema_model.cc)
Section top_level_section();
Section analysis_section();
Section materials_section();
Section joint_materials_section();
/// `damping` of a material, a joint material or a tunnel (app/schema/schema_damping.cc), its
/// section `section_id` and what it damps (for the key's meaning); the section of that id.
Key damping_key(const std::string& section_id, const std::string& what);
Section damping_section(const std::string& id);
Section joints_section();
Section joints_pairs_section();
Section blocks_section();
Section blocks_grid_section();
Section point_loads_section();
Section fixed_points_section();
Section monitors_section();
Section boundaries_section();
Section in_situ_stress_section();
Section boundaries_input_section();
Section boundaries_on_line_section();
Section stages_section();
// time, contacts, solver, output: keys bound to their fields (app/schema/schema_settings.cc)
Section time_section();
Section contacts_section();
Section solver_section();
Section output_section();

// rock support: bolts (app/schema/schema_support.cc)
Section bolts_section();
// the lining (app/schema/schema_lining.cc)
Section linings_section();
Section tunnel_lining_section();

// the generated rock mass: region, joint sets, explicit joints, openings
// (app/schema/schema_rock_mass.cc)
Section rock_mass_section();
Section rock_mass_region_section();
Section rock_mass_region_rectangle_section();
Section rock_mass_joint_sets_section();
Section rock_mass_joint_sets_perturbation_section();
Section rock_mass_joints_section();
Section rock_mass_openings_section();
Section rock_mass_openings_circle_section();
Section rock_mass_openings_horseshoe_section();

// the tunnel section and its stages, wave and near field (app/schema/schema_tunnel.cc)
Section tunnel_section();
Section tunnel_settle_section();
Section tunnel_wave_section();
Section tunnel_near_field_section();
Section tunnel_static_section();
// radial bolt patterns (app/schema/schema_tunnel_bolts.cc)
Section tunnel_bolts_section();

// the deal.II far field and its interface with the blocks (app/schema/schema_far_field.cc)
Section far_field_section();
Section interface_section();
Section far_field_boundaries_section();
Section far_field_boundaries_springs_section();
Section far_field_hole_section();
Section far_field_static_stage_section();
Section far_field_rayleigh_section();
Section far_field_mesh_section();
Section far_field_mesh_parts_section();
Section far_field_incident_section();

// the time functions' variants (app/schema/schema_time_functions.cc)
Section constant_time_function_section();
Section sine_pulse_time_function_section();
Section table_time_function_section();
Section csv_time_function_section();
Section record_time_function_section();

} // namespace ddafem::schema
