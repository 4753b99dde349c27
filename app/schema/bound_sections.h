// The sections whose keys are bound to the fields they fill (app/schema/bound_keys.h): the schema
// lists their keys and the scene reader fills the structs by the same declarations.
#pragma once

#include "app/scene/scene.h"
#include "app/scene/tunnel_bolts.h"
#include "app/scene/tunnel_plan.h"
#include "app/schema/bound_keys.h"
#include "app/schema/scene_schema.h"
#include "coupling/far_field_ties.h"
#include "dda/model_description.h"
#include "dda/rock_mass.h"
#include "fem/far_field_description.h"

namespace ddafem::schema
{
/// The parameters of a sine pulse (TimeFunction::sine_pulse), as the scene gives them.
struct SinePulseParameters
{
  double frequency = 0.0; ///< [Hz]
  double cycles = 1.0;
  double amplitude = 1.0; ///< peak value, in the unit of the quantity
  double start = 0.0;     ///< [s]
};

/// Where a table's numbers are in a CSV file or a record's table (columns counted from 0).
struct TableColumns
{
  long long time_column = 0;
  long long value_column = 1;
  long long skip_rows = 0; ///< header rows
};

/// How a record's table is read, corrected and placed in the model's time (the rest of its
/// processing: app/scene/record_reader.cc).
struct RecordProcessing
{
  TableColumns columns;
  BaselineMethod baseline = BaselineMethod::polynomial;
  long long baseline_degree = 3; ///< highest power of t in the displacement's baseline
  double start = 0.0;            ///< model time of the first sample used [s]
};

/// `stress` and `stress_gradient` of an in-situ stress sigma0(y) = stress + stress_gradient (y -
/// reference_y) (`in_situ_stress`, `far_field.static_stage`), filling `stress` and `gradient`.
template <typename Target, typename Stress>
void add_in_situ_keys(BoundKeys<Target>& k, Stress Target::*stress, Stress Target::*gradient)
{
  k.field("stress", stress)
      .unit("Pa")
      .meaning("in-situ stress [sxx, syy, sxy] at reference_y, tension positive");
  k.field("stress_gradient", gradient)
      .unit("Pa/m")
      .meaning("d/dy of the in-situ stress, e.g. [K0 rho g, rho g, 0] for lithostatic stress "
               "with reference_y at the surface");
}

// app/schema/schema_time_functions.cc
BoundKeys<SinePulseParameters> sine_pulse_keys();
BoundKeys<TableColumns> csv_keys();
BoundKeys<RecordProcessing> record_keys();
// app/schema/schema_model.cc
BoundKeys<Scene> top_level_keys();
BoundKeys<dda::ModelDescription> analysis_keys();
BoundKeys<dda::BlockDescription> block_keys();
BoundKeys<dda::PointLoad> point_load_keys();
BoundKeys<dda::FixedPoint> fixed_point_keys();
BoundKeys<dda::Monitor> monitor_keys();
BoundKeys<dda::InSituStress> in_situ_stress_keys();
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
BoundKeys<fem::StaticStage> far_field_static_stage_keys();
BoundKeys<coupling::InterfaceDescription> interface_keys();
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
BoundKeys<dda::LiningDescription> lining_path_keys();
// app/schema/schema_tunnel.cc
BoundKeys<TunnelDescription> tunnel_keys();
BoundKeys<TunnelDescription> tunnel_wave_keys();
BoundKeys<TunnelDescription> tunnel_near_field_keys();
BoundKeys<TunnelDescription> tunnel_static_keys();
BoundKeys<TunnelDescription> tunnel_settle_keys();
// app/schema/schema_tunnel_bolts.cc
BoundKeys<BoltPattern> tunnel_bolt_pattern_keys();
// app/schema/schema_settings.cc
BoundKeys<dda::TimeSettings> time_keys();
BoundKeys<dda::ContactSettings> contacts_keys();
BoundKeys<dda::SolverSettings> solver_keys();
BoundKeys<OutputSettings> output_keys();
} // namespace ddafem::schema
