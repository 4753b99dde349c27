#include "app/run/run_summary.h"

#include "app/run/element_outputs.h"
#include "app/run/run_support.h"

#include "common/format.h"

#include <algorithm>
#include <cmath>

namespace ddafem
{
namespace
{
nlohmann::json time_step_summary(const dda::TimeSettings& time, const StageTotals& stages,
                                 std::size_t n_attempts)
{
  std::size_t n_cuts = 0;
  nlohmann::json by_cause = nlohmann::json::object();
  for (const auto& [outcome, n] : stages.cuts_by_cause)
  {
    n_cuts += n;
    by_cause[name_of(outcome)] = n;
  }
  return {{"control", name_of(time.control)},
          {"dt_max_s", time.dt},
          {"smallest_dt_s", stages.smallest_dt},
          {"attempts", n_attempts},
          {"cuts", n_cuts},
          {"cuts_by_cause", by_cause},
          {"steps_cut", stages.n_cut_steps},
          {"penalty_raises", stages.n_penalty_raises},
          {"flips_ignored", stages.n_flips_ignored},
          {"slip_reversals", stages.n_reversals}};
}

nlohmann::json tunnel_summary(const TunnelPlan& plan)
{
  return {{"truncation", name_of(plan.truncation)},
          {"near_field_lower_m", {plan.near_lower.x(), plan.near_lower.y()}},
          {"near_field_upper_m", {plan.near_upper.x(), plan.near_upper.y()}},
          {"far_field", plan.far_field},
          {"margin_m", plan.margin},
          {"side_margin_m", plan.side_margin},
          {"outer_blocks", plan.n_outer_blocks},
          {"outer_block_size_m", plan.outer_block_size},
          {"rock_mass_modulus_pa", plan.rock_mass_modulus},
          {"arrival_time_s", plan.arrival_time},
          {"end_time_s", plan.end_time}};
}

/// The blocks' model, solver, contacts, energies and timings.
void add_blocks_summary(nlohmann::json& summary, const dda::System& system,
                        const RunOutputs& outputs)
{
  const dda::StepSolver& solver = system.get_solver();
  summary["solver"] = {{"name", solver.name()},
                       {"factorizations", solver.n_factorizations()},
                       {"solves", solver.n_solves()},
                       {"refinement_iterations", solver.n_refinements()}};
  if (solver.n_pcg_solves() > 0)
  {
    summary["solver"]["pcg_solves"] = solver.n_pcg_solves();
    summary["solver"]["pcg_iterations"] = solver.n_pcg_iterations();
    summary["solver"]["pcg_fallbacks"] = solver.n_fallbacks();
  }
  summary["model"] = {{"blocks", system.blocks().list.size()},
                      {"bonded_joints", system.bonded_joints().list.size()},
                      {"dofs", system.blocks().n_dofs()}};
  const dda::ContactCounts counts = system.contacts().counts();
  const dda::PhaseTimings& t = system.get_timings();
  summary["contacts"] = {
      {"open", counts.open},
      {"slide", counts.slide},
      {"lock", counts.lock},
      {"broken_joints", system.bonded_joints().n_broken},
      {"open_close_iterations", t.n_open_close_iterations},
      {"search_distance_m", system.contacts().distances.search_distance},
      {"max_step_displacement_m", system.contacts().distances.max_step_displacement}};
  summary["timings_s"] = {{"broad_phase", t.broad_phase}, {"narrow_phase", t.narrow_phase},
                          {"assemble", t.assemble},       {"solve", t.solve},
                          {"update", t.update},           {"output", outputs.seconds()},
                          {"tie_terms", t.tie_terms},     {"tied_body", t.tied_body}};
  // Parts of timings_s: the far field's VTU files within output.
  summary["timings_detail_s"] = {{"output_far_field_vtu", outputs.far_field_vtu_seconds()}};
  for (const std::unique_ptr<ElementOutputs>& o : make_element_outputs())
    o->add_summary(summary, system);
  const dda::EnergyBalance e = system.energy();
  summary["energy_J"] = {{"kinetic", e.kinetic},
                         {"strain", e.strain},
                         {"spring", e.spring},
                         {"work_of_loads", e.work_of_loads},
                         {"work_of_supports", e.work_of_supports},
                         {"work_of_boundaries", e.work_of_boundaries},
                         {"work_of_ties", e.work_of_ties},
                         {"work_of_damping", e.work_of_damping},
                         {"removed", e.removed},
                         {"initial", e.initial},
                         {"dissipated", e.dissipated}};
}
} // namespace

void mark_energy_source(nlohmann::json& summary, const dda::EnergyBalance& e)
{
  // A viscous boundary only takes energy out (its incident wave's input counts as a load): net
  // work in of more than 1 % of what the loads, supports and ties put in makes it a source.
  const double put_in =
      e.initial + e.work_of_loads + e.work_of_supports + std::max(e.work_of_ties, 0.0);
  if (!(e.work_of_boundaries > 0.01 * std::max(put_in, 0.0)))
    return;
  summary["status"] = "completed_energy_source";
  summary["energy_source"] =
      "the viscous boundaries fed " + format_significant(e.work_of_boundaries, 4) +
      " J into the model, against " + format_significant(put_in, 4) +
      " J put in by the loads, supports and ties: a boundary is an energy source at this dt "
      "(`ddafem check` gives each boundary's limit); the results are not physical";
}

nlohmann::json summary_head(const Scene& scene, bool failed, const std::string& failure,
                            double time_reached, double end_time, std::size_t n_steps, double dt)
{
  nlohmann::json summary;
  summary["scene"] = scene.file;
  summary["name"] = scene.name;
  summary["version"] = DDAFEM_VERSION;
  summary["status"] = failed ? "numerical_failure" : "completed";
  if (failed)
    summary["failure"] = failure;
  summary["time_reached_s"] = time_reached;
  summary["end_time_s"] = end_time;
  summary["steps"] = n_steps;
  summary["dt_s"] = dt;
  return summary;
}

void add_run_facts(nlohmann::json& summary, double wall_time,
                   const std::vector<std::string>& warnings)
{
  summary["wall_time_s"] = wall_time;
  summary["peak_memory_mb"] = run_support::peak_memory_mb();
  summary["warnings"] = warnings;
}

void StageTotals::add(const dda::StaticStageResult& result)
{
  n_cut_steps += result.n_cut_steps;
  n_penalty_raises += result.n_penalty_raises;
  for (const auto& [outcome, n] : result.cuts_by_cause)
    cuts_by_cause[outcome] += n;
  smallest_dt = std::min(smallest_dt, result.smallest_dt);
}

void StageTotals::add(const dda::DynamicStageResult& result)
{
  n_cut_steps += result.n_cut_steps;
  n_penalty_raises += result.n_penalty_raises;
  n_flips_ignored += result.n_flips_ignored;
  n_reversals += result.n_reversals;
  for (const auto& [outcome, n] : result.cuts_by_cause)
    cuts_by_cause[outcome] += n;
  smallest_dt = std::min(smallest_dt, result.smallest_dt);
}

nlohmann::json run_summary(const RunRecord& run)
{
  const dda::TimeSettings& time = run.scene.model.time;
  const dda::System& system = run.system;
  nlohmann::json summary = summary_head(run.scene, run.stages.failed(), run.stages.failure.message,
                                        system.time(), time.end_time, system.n_steps(), time.dt);
  summary["time_step"] = time_step_summary(time, run.stages, system.get_timings().n_attempts);
  summary["stages"] = run.stages.records;
  if (run.scene.tunnel)
    summary["tunnel"] = tunnel_summary(*run.scene.tunnel);
  summary["integrator"] = name_of(time.integrator);
  if (time.integrator == dda::Integrator::generalized_alpha)
    summary["spectral_radius"] = time.spectral_radius;
  add_blocks_summary(summary, system, run.outputs);
  if (!run.stages.failed())
    mark_energy_source(summary, system.energy());
  if (run.tied)
    run.tied->add_to_summary(summary);
  add_run_facts(summary, run.wall_time, run.warnings);
  if (!run.keyblocks.empty())
    summary["keyblocks"] = run.keyblocks.summary(system);
  summary["outputs"] = {{"histories", "histories.h5"},
                        {"model", "model.pvd"},
                        {"blocks", "blocks.pvd"},
                        {"contacts", "contacts.pvd"},
                        {"snapshots", run.outputs.n_snapshots()}};
  if (run.tied)
  {
    summary["outputs"]["far_field"] = "far_field.pvd";
    summary["outputs"]["ties"] = "ties.pvd";
  }
  return summary;
}

namespace
{
nlohmann::json record_json(const std::string& where, const RecordInfo& r)
{
  const MotionSummary& m = r.summary;
  return {{"where", where},
          {"file", r.file},
          {"motion", name_of(r.motion)},
          {"incident_factor", incident_factor(r.motion)},
          {"scale", r.scale},
          {"window_s", {r.window_from, r.window_to}},
          {"start_s", r.start},
          {"dt_s", r.dt},
          {"pga_m_s2", m.pga},
          {"pga_g", m.pga / standard_gravity},
          {"pgv_m_s", m.pgv},
          {"pgd_m", m.pgd},
          {"arias_intensity_m_s", m.arias_intensity},
          {"t5_s", m.t5},
          {"t95_s", m.t95},
          {"mean_frequency_hz", m.mean_frequency},
          {"f99_hz", m.f99},
          {"baseline",
           {{"end_velocity_before_m_s", r.scale * r.baseline.end_velocity_before},
            {"end_displacement_before_m", r.scale * r.baseline.end_displacement_before},
            {"end_displacement_after_m", r.scale * r.baseline.end_displacement_after}}}};
}
} // namespace

nlohmann::json records_summary(const Scene& scene)
{
  nlohmann::json records = nlohmann::json::array();
  const auto add = [&](const std::string& where, const TimeFunction& f)
  {
    if (const RecordInfo* r = f.record_info())
      records.push_back(record_json(where, *r));
  };
  if (scene.far_field)
    add("far_field.incident.velocity", scene.far_field->incident.velocity);
  const dda::ModelDescription& model = scene.model;
  for (std::size_t i = 0; i < model.boundaries.size(); ++i)
    if (model.boundaries[i].has_input)
      add("boundaries." + std::to_string(i) + ".input.velocity",
          model.boundaries[i].input.velocity);
  for (std::size_t i = 0; i < model.fixed_points.size(); ++i)
  {
    add("fixed_points." + std::to_string(i) + ".displacement_x",
        model.fixed_points[i].displacement_x);
    add("fixed_points." + std::to_string(i) + ".displacement_y",
        model.fixed_points[i].displacement_y);
  }
  return records;
}

} // namespace ddafem
