// `check` and `run` of far-field-only scenes (deal.II continuum, issue 5).
#include "app/run.h"
#include "app/run_outputs.h"
#include "app/run_support.h"
#include "common/history_writer.h"
#include "fem/elastic_wave_model.h"

#include <nlohmann/json.hpp>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace ddafem
{
namespace
{
using run_support::Clock;
using run_support::elapsed;
using run_support::format;

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

std::vector<double> far_field_row(const fem::ElasticWaveModel& model, std::size_t n_monitors)
{
  std::vector<double> row;
  append_far_field_monitors(row, model, n_monitors);
  const fem::EnergyBalance e = model.energy();
  row.insert(row.end(), {e.kinetic, e.strain, e.work_of_input, e.work_of_dashpots,
                         e.work_of_rayleigh, e.dissipated});
  return row;
}
} // namespace

std::string check_far_field(const Scene& scene)
{
  const fem::FarFieldDescription& d = *scene.far_field;
  const fem::ElasticWaveModel model(d);
  std::ostringstream out;
  out << "scene: " << scene.name << " (" << scene.file << "), far field only\n";
  out << "  domain: [" << d.lower[0] << ", " << d.upper[0] << "] x [" << d.lower[1] << ", "
      << d.upper[1] << "] m, plane "
      << (d.plane_mode == fem::PlaneMode::strain ? "strain" : "stress") << "\n";
  out << "  material: rho " << format(d.density) << " kg/m^3, E " << format(d.youngs_modulus)
      << " Pa, nu " << d.poisson_ratio << "; VP " << format(model.p_wave_speed(), 5) << " m/s, VS "
      << format(model.s_wave_speed(), 5) << " m/s\n";
  out << "  mesh: " << model.n_cells() << " cells of " << format(model.smallest_element_size())
      << " to " << format(model.element_size()) << " m, FE_Q(" << d.degree << "), "
      << model.n_dofs() << " DOFs, " << model.n_constraints() << " constrained\n";
  if (!d.mesh_file.file.empty())
    out << "  mesh file: " << d.mesh_file.file << "\n";
  if (model.boundary_length(fem::BoundaryPart::hole) > 0.0)
    out << "  hole: perimeter " << format(model.boundary_length(fem::BoundaryPart::hole))
        << " m, meshed area " << format(model.area()) << " m^2\n";
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
    out << "  Rayleigh damping: alpha " << format(d.rayleigh.alpha) << " 1/s, beta "
        << format(d.rayleigh.beta) << " s\n";
  const double f = std::max(d.max_frequency, d.incident.velocity.characteristic_frequency());
  if (f > 0.0)
    out << "  resolution at " << format(f)
        << " Hz: " << format(model.s_wave_speed() / f / model.element_size() * d.degree, 3)
        << " nodes per S wavelength\n";
  for (const fem::BoundaryCondition& b : d.boundaries)
    out << "  " << fem::name_of(b.part) << ": " << fem::name_of(b.kind)
        << (b.kind == fem::BoundaryKind::lysmer || b.kind == fem::BoundaryKind::input
                ? " (a " + format(b.a) + ", b " + format(b.b) + ")"
                : "")
        << "\n";
  out << "  incident: " << (d.incident.type == fem::IncidentWave::Type::p ? "P" : "SV") << ", v_in "
      << d.incident.velocity.describe() << "\n";
  const auto n_steps = static_cast<std::size_t>(std::llround(d.end_time / d.dt));
  // An explicit scheme would need dt below about h / (VP p) (Courant); implicit Newmark is
  // unconditionally stable, accuracy asks for about 20 steps per period.
  out << "  time: dt " << format(d.dt) << " s, end " << format(d.end_time) << " s, " << n_steps
      << " steps, " << (d.integrator == fem::Integrator::dda ? "dda" : "newmark_trapezoidal")
      << "; explicit Courant limit would be about "
      << format(model.element_size() / (model.p_wave_speed() * d.degree), 3) << " s\n";
  out << "  monitors: " << d.monitors.size() << "\n";
  return out.str();
}

namespace
{
/// summary.json of a far-field run (without its warnings and outputs): `failure` empty when it
/// completed; wall and output times [s].
nlohmann::json far_field_summary(const Scene& scene, const fem::ElasticWaveModel& model,
                                 const std::string& failure, double wall, double output_time)
{
  const fem::FarFieldDescription& d = *scene.far_field;
  const bool failed = !failure.empty();
  const fem::Timings& t = model.timings();
  const fem::EnergyBalance e = model.energy();
  nlohmann::json summary;
  summary["scene"] = scene.file;
  summary["name"] = scene.name;
  summary["version"] = DDAFEM_VERSION;
  summary["status"] = failed ? "numerical_failure" : "completed";
  if (failed)
    summary["failure"] = failure;
  summary["time_reached_s"] = model.time();
  summary["end_time_s"] = d.end_time;
  summary["steps"] = t.n_steps;
  summary["dt_s"] = d.dt;
  summary["integrator"] = d.integrator == fem::Integrator::dda ? "dda" : "newmark_trapezoidal";
  summary["solver"] = {{"name", model.solver_name()},
                       {"factorizations", 1},
                       {"linear_iterations", t.linear_iterations}};
  summary["model"] = {{"far_field_cells", model.n_cells()},
                      {"far_field_dofs", model.n_dofs()},
                      {"element_size_m", model.element_size()},
                      {"smallest_element_size_m", model.smallest_element_size()},
                      {"degree", d.degree},
                      {"blocks", 0}};
  summary["wall_time_s"] = wall;
  summary["peak_memory_mb"] = run_support::peak_memory_mb();
  summary["timings_s"] = far_field_timings(t);
  summary["timings_s"]["output"] = output_time;
  summary["energy_J"] = {{"kinetic", e.kinetic},
                         {"strain", e.strain},
                         {"work_of_input", e.work_of_input},
                         {"work_of_dashpots", e.work_of_dashpots},
                         {"work_of_rayleigh", e.work_of_rayleigh},
                         {"initial", e.initial},
                         {"dissipated", e.dissipated}};
  return summary;
}

} // namespace

int run_far_field(const Scene& scene, const RunOptions& options, std::ostream& log)
{
  const auto wall_start = Clock::now();
  const fem::FarFieldDescription& d = *scene.far_field;
  fem::ElasticWaveModel model(d); // input errors surface here, before anything is written

  const std::filesystem::path dir =
      options.output_directory.empty() ? scene.output.directory : options.output_directory;
  run_support::create_output_directory(dir);

  const auto n_steps = static_cast<std::size_t>(std::llround(d.end_time / d.dt));
  HistoryWriter history((dir / "histories.h5").string(), far_field_channels(d));
  history.set_attribute("scene", scene.file);
  history.set_attribute("version", DDAFEM_VERSION);

  double output_time = 0.0;
  std::size_t n_snapshots = 0;
  const auto write_outputs = [&](bool snapshot)
  {
    const auto start = Clock::now();
    history.append(model.time(), far_field_row(model, d.monitors.size()));
    if (snapshot)
    {
      model.write_snapshot(dir.string(), "far_field", scene.output.vtu_compression);
      ++n_snapshots;
    }
    output_time += elapsed(start);
  };
  write_outputs(true);

  run_support::Progress progress(!options.quiet && isatty(fileno(stderr)), d.end_time);
  double next_snapshot = scene.output.interval;
  fem::StepStatus failure;
  for (std::size_t step = 1; step <= n_steps; ++step)
  {
    const fem::StepStatus status = model.advance(d.dt);
    if (status.outcome != fem::StepOutcome::success)
    {
      failure = status;
      break;
    }
    const bool last = step == n_steps;
    const bool snapshot =
        run_support::snapshot_due(model.time(), scene.output.interval, d.dt, next_snapshot) || last;
    if (step % scene.output.history_every == 0 || snapshot)
      write_outputs(snapshot);
    progress.update(step, model.time(), elapsed(wall_start));
  }
  progress.finish();
  const bool failed = failure.outcome != fem::StepOutcome::success;
  if (failed)
    write_outputs(true);
  history.flush();

  const double wall = elapsed(wall_start);
  nlohmann::json summary =
      far_field_summary(scene, model, failed ? failure.message : "", wall, output_time);
  summary["warnings"] = nlohmann::json::array();
  summary["outputs"] = {
      {"histories", "histories.h5"}, {"far_field", "far_field.pvd"}, {"snapshots", n_snapshots}};
  return run_support::finish_run(dir, summary, failed ? failure.message : std::string(),
                                 std::to_string(model.timings().n_steps) + " steps", model.time(),
                                 wall, "far_field.pvd", log);
}

} // namespace ddafem
