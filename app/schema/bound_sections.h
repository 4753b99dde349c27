// The sections whose keys are bound to the fields they fill (app/schema/bound_keys.h): the schema
// lists their keys and the scene reader fills the structs by the same declarations.
#pragma once

#include "app/scene/scene.h"
#include "app/scene/tunnel_plan.h"
#include "app/schema/bound_keys.h"
#include "dda/model_description.h"
#include "dda/rock_mass.h"
#include "fem/far_field_description.h"

namespace ddafem::schema
{
// app/schema/schema_model.cc
BoundKeys<dda::Material> material_keys();
BoundKeys<dda::JointMaterial> joint_material_keys();
BoundKeys<dda::BoundaryDescription> boundary_keys();
BoundKeys<dda::Stage> stage_keys();
BoundKeys<dda::SettleCriterion> settle_keys();
// app/schema/schema_far_field.cc
BoundKeys<fem::FarFieldDescription> far_field_keys();
BoundKeys<fem::BoundaryCondition> far_field_boundary_keys();
BoundKeys<fem::BoundarySprings> far_field_springs_keys();
BoundKeys<fem::HoleDescription> far_field_hole_keys();
// app/schema/schema_rock_mass.cc
BoundKeys<dda::RockMassDescription> rock_mass_keys();
BoundKeys<dda::JointSet> joint_set_keys();
BoundKeys<dda::JointPerturbation> perturbation_keys();
BoundKeys<dda::Opening> circle_keys();
BoundKeys<dda::Opening> horseshoe_keys();
// app/schema/schema_support.cc
BoundKeys<dda::BoltDescription> bolt_keys();
// app/schema/schema_lining.cc
BoundKeys<dda::LiningDescription> lining_section_keys();
// app/schema/schema_tunnel.cc
BoundKeys<TunnelDescription> tunnel_keys();
BoundKeys<TunnelDescription> tunnel_wave_keys();
BoundKeys<TunnelDescription> tunnel_near_field_keys();
BoundKeys<TunnelDescription> tunnel_static_keys();
BoundKeys<TunnelDescription> tunnel_settle_keys();
// app/schema/schema_settings.cc
BoundKeys<dda::TimeSettings> time_keys();
BoundKeys<dda::ContactSettings> contacts_keys();
BoundKeys<dda::SolverSettings> solver_keys();
BoundKeys<OutputSettings> output_keys();
} // namespace ddafem::schema
