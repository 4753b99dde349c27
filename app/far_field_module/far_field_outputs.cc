// A far field alone (module side): its outputs (histories.h5 and far_field.pvd), its
// summary.json and its `check`.
#include "app/far_field_module/far_field_parts.h"
#include "app/run/checkpoint_types.h"
#include "app/run/run_summary.h"
#include "app/run/run_support.h"

#include "common/format.h"
#include "common/stopwatch.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace ddafem
{
std::vector<HistoryChannel> far_field_channels(const fem::FarFieldDescription& d)
{
  std::vector<HistoryChannel> channels;
  for (const fem::Monitor& m : d.monitors)
    run_support::add_monitor_channels(channels, m.name, "at the point", "at the point");
  channels.push_back({"energy/kinetic", 1, "J", "v^T M v / 2 per unit thickness"});
  channels.push_back({"energy/strain", 1, "J", "u^T K u / 2 per unit thickness"});
  channels.push_back({"energy/work_of_input", 1, "J", "incident-wave tractions since t = 0"});
  channels.push_back(
      {"energy/work_of_dashpots", 1, "J", "Lysmer dashpots since t = 0 (negative: absorbed)"});
  channels.push_back(
      {"energy/work_of_rayleigh", 1, "J", "Rayleigh damping since t = 0 (negative: absorbed)"});
  channels.push_back({"energy/dissipated", 1, "J", "initial + work - stored: the integrator's"});
  return channels;
}

nlohmann::json far_field_timings(const fem::Timings& t)
{
  return {{"setup", t.setup}, {"assemble", t.assemble}, {"solve", t.solve}, {"update", t.update}};
}

FarFieldOutputs::FarFieldOutputs(const std::filesystem::path& dir_, const std::string& scene_file,
                                 fem::ElasticWaveModel& model_,
                                 const fem::FarFieldDescription& description,
                                 fem::VtuCompression vtu_compression_)
    : dir(dir_), model(model_), n_monitors(description.monitors.size()),
      vtu_compression(vtu_compression_),
      history((dir / "histories.h5").string(), far_field_channels(description))
{
  history.set_attribute("scene", scene_file);
  history.set_attribute("version", DDAFEM_VERSION);
}

FarFieldOutputs::FarFieldOutputs(const std::filesystem::path& dir_, fem::ElasticWaveModel& model_,
                                 const fem::FarFieldDescription& description,
                                 fem::VtuCompression vtu_compression_, CheckpointIn& a)
    : dir(dir_), model(model_), n_monitors(description.monitors.size()),
      vtu_compression(vtu_compression_),
      history((dir / "histories.h5").string(), far_field_channels(description),
              HistoryWriter::Reopen{load_history_rows(a, "far-field outputs")})
{
  a >> n_written >> time_output;
  transfer_optional(a, last_row_time);
  transfer_optional(a, last_snapshot_time);
}

void FarFieldOutputs::save(CheckpointOut& a) const
{
  save_history_rows(a, "far-field outputs", history.n_rows());
  a << n_written << time_output;
  transfer_optional(a, const_cast<std::optional<double>&>(last_row_time));
  transfer_optional(a, const_cast<std::optional<double>&>(last_snapshot_time));
}

void FarFieldOutputs::write_state(bool snapshot)
{
  // A state already written (a run stopped right after a step it wrote) is not written again.
  const auto start = Clock::now();
  if (last_row_time != model.time())
  {
    std::vector<double> row;
    append_far_field_monitors(row, model, n_monitors);
    const fem::EnergyBalance e = model.energy();
    row.insert(row.end(), {e.kinetic, e.strain, e.work_of_input, e.work_of_dashpots,
                           e.work_of_rayleigh, e.dissipated});
    history.append(model.time(), row);
    last_row_time = model.time();
  }
  if (snapshot && last_snapshot_time != model.time())
  {
    model.write_snapshot(dir.string(), "far_field", vtu_compression);
    ++n_written;
    last_snapshot_time = model.time();
  }
  time_output += seconds_since(start);
}

nlohmann::json far_field_run_summary(const FarFieldRunRecord& run)
{
  const fem::FarFieldDescription& d = *run.scene.far_field;
  const fem::ElasticWaveModel& model = run.model;
  const bool failed = !run.failure.taken;
  const fem::Timings& t = model.timings();
  const fem::EnergyBalance e = model.energy();
  nlohmann::json summary =
      summary_head(run.scene, failed, run.failure.why, model.time(), d.end_time, t.n_steps, d.dt);
  summary["integrator"] = fem::name_of(d.integrator);
  summary["solver"] = {{"name", model.solver_name()},
                       {"factorizations", t.n_factorizations},
                       {"linear_iterations", t.linear_iterations}};
  summary["model"] = {{"far_field_cells", model.n_cells()},
                      {"far_field_dofs", model.n_dofs()},
                      {"element_size_m", model.element_size()},
                      {"smallest_element_size_m", model.smallest_element_size()},
                      {"degree", d.degree},
                      {"blocks", 0}};
  add_run_facts(summary, run.wall_time, run.warnings);
  summary["timings_s"] = far_field_timings(t);
  summary["timings_s"]["output"] = run.outputs.seconds();
  summary["energy_J"] = {{"kinetic", e.kinetic},
                         {"strain", e.strain},
                         {"work_of_input", e.work_of_input},
                         {"work_of_dashpots", e.work_of_dashpots},
                         {"work_of_rayleigh", e.work_of_rayleigh},
                         {"initial", e.initial},
                         {"dissipated", e.dissipated}};
  summary["outputs"] = {{"histories", "histories.h5"},
                        {"far_field", "far_field.pvd"},
                        {"snapshots", run.outputs.n_snapshots()}};
  return summary;
}

std::string check_far_field(const Scene& scene)
{
  const fem::FarFieldDescription& d = *scene.far_field;
  const fem::ElasticWaveModel model(d);
  std::ostringstream out;
  out << "scene: " << scene.name << " (" << scene.file << "), far field only\n";
  out << "  domain: [" << d.lower[0] << ", " << d.upper[0] << "] x [" << d.lower[1] << ", "
      << d.upper[1] << "] m, plane " << name_of(d.plane_mode) << "\n";
  out << "  material: rho " << format_significant(d.density) << " kg/m^3, E "
      << format_significant(d.youngs_modulus) << " Pa, nu " << d.poisson_ratio << "; VP "
      << format_significant(model.p_wave_speed(), 5) << " m/s, VS "
      << format_significant(model.s_wave_speed(), 5) << " m/s\n";
  out << "  mesh: " << model.n_cells() << " cells of "
      << format_significant(model.smallest_element_size()) << " to "
      << format_significant(model.element_size()) << " m, FE_Q(" << d.degree << "), "
      << model.n_dofs() << " DOFs, " << model.n_constraints() << " constrained\n";
  if (!d.mesh_file.file.empty())
    out << "  mesh file: " << d.mesh_file.file << "\n";
  if (model.boundary_length(fem::BoundaryPart::hole) > 0.0)
    out << "  hole: perimeter "
        << format_significant(model.boundary_length(fem::BoundaryPart::hole)) << " m, meshed area "
        << format_significant(model.area()) << " m^2\n";
  out << "  solver: " << model.solver_name() << "\n";
  if (d.static_stage.enabled)
    out << "  static stage: gravity [" << d.static_stage.gravity[0] << ", "
        << d.static_stage.gravity[1] << "] m/s^2, in-situ stress [" << d.static_stage.stress[0]
        << ", " << d.static_stage.stress[1] << ", " << d.static_stage.stress[2] << "] Pa + ["
        << d.static_stage.stress_gradient[0] << ", " << d.static_stage.stress_gradient[1] << ", "
        << d.static_stage.stress_gradient[2] << "] Pa/m (y - " << d.static_stage.reference_y
        << " m), absorbing parts held "
        << (d.static_stage.support == fem::StaticSupport::roller ? "by rollers" : "fixed") << "\n";
  if (d.rayleigh.alpha > 0.0 || d.rayleigh.beta > 0.0)
    out << "  Rayleigh damping: alpha " << format_significant(d.rayleigh.alpha) << " 1/s, beta "
        << format_significant(d.rayleigh.beta) << " s\n";
  const double f = std::max(d.max_frequency, d.incident.velocity.characteristic_frequency());
  if (f > 0.0)
    out << "  resolution at " << format_significant(f) << " Hz: "
        << format_significant(model.s_wave_speed() / f / model.element_size() * d.degree, 3)
        << " nodes per S wavelength\n";
  for (const fem::BoundaryCondition& b : d.boundaries)
    out << "  " << fem::name_of(b.part) << ": " << fem::name_of(b.kind)
        << (b.kind == fem::BoundaryKind::lysmer || b.kind == fem::BoundaryKind::input
                ? " (a " + format_significant(b.a) + ", b " + format_significant(b.b) + ")"
                : "")
        << "\n";
  out << "  incident: " << (d.incident.type == fem::IncidentWave::Type::p ? "P" : "SV") << ", v_in "
      << d.incident.velocity.describe() << "\n";
  const auto n_steps = static_cast<std::size_t>(std::llround(d.end_time / d.dt));
  // An explicit scheme would need dt below about h / (VP p) (Courant); implicit Newmark is
  // unconditionally stable, accuracy asks for about 20 steps per period.
  out << "  time: dt " << format_significant(d.dt) << " s, end " << format_significant(d.end_time)
      << " s, " << n_steps << " steps, " << fem::name_of(d.integrator)
      << "; explicit Courant limit would be about "
      << format_significant(model.element_size() / (model.p_wave_speed() * d.degree), 3) << " s\n";
  out << "  monitors: " << d.monitors.size() << "\n";
  return out.str();
}
} // namespace ddafem
