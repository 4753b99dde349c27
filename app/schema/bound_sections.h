// The sections whose keys are bound to the fields they fill (app/schema/bound_keys.h): the schema
// lists their keys and the scene reader fills the structs by the same declarations.
#pragma once

#include "app/scene/scene.h"
#include "app/schema/bound_keys.h"
#include "dda/model_description.h"
#include "fem/far_field_description.h"

namespace ddafem::schema
{
// app/schema/schema_model.cc
BoundKeys<dda::Material> material_keys();
BoundKeys<dda::JointMaterial> joint_material_keys();
// app/schema/schema_far_field.cc
BoundKeys<fem::FarFieldDescription> far_field_keys();
BoundKeys<fem::BoundaryCondition> far_field_boundary_keys();
BoundKeys<fem::BoundarySprings> far_field_springs_keys();
BoundKeys<fem::HoleDescription> far_field_hole_keys();
// app/schema/schema_settings.cc
BoundKeys<dda::TimeSettings> time_keys();
BoundKeys<dda::ContactSettings> contacts_keys();
BoundKeys<dda::SolverSettings> solver_keys();
BoundKeys<OutputSettings> output_keys();
} // namespace ddafem::schema
