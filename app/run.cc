#include "app/run.h"

#include "app/keyblocks.h"
#include "app/rock_mass_scene.h"
#include "app/run_outputs.h"
#include "app/run_summary.h"
#include "app/run_support.h"
#include "app/stage_records.h"

#include "common/elasticity.h"
#include "common/history_writer.h"
#include "common/input_error.h"
#include "coupling/far_field_ties.h"
#include "dda/dynamic_stage.h"
#include "dda/system.h"
#include "dda/time_stepper.h"
#include "dda/vtu_writer.h"
#include "fem/elastic_wave_model.h"

#include <nlohmann/json.hpp>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

namespace ddafem
{
namespace
{
using run_support::Clock;
using run_support::elapsed;
using run_support::format;
using run_support::Progress;

/// P-wave speed that governs the scene's blocks: plate speed in plane stress, body in strain.
double governing_p_speed(const Scene& scene, const dda::Material& m)
{
  const WaveSpeeds c = wave_speeds(m);
  return scene.model.plane_mode == dda::PlaneMode::stress ? c.p_plate : c.p_body;
}

/// Smallest block: index, area [m^2] and shortest edge [m].
struct SmallestBlock
{
  std::size_t index = 0;
  double area = std::numeric_limits<double>::max();
  double shortest_edge = std::numeric_limits<double>::max();
};

SmallestBlock smallest_block(const Scene& scene)
{
  SmallestBlock s;
  for (std::size_t i = 0; i < scene.model.blocks.size(); ++i)
  {
    const auto& v = scene.model.blocks[i].vertices;
    const double area = std::abs(dda::signed_area(v));
    if (area < s.area)
    {
      s.area = area;
      s.index = i;
    }
    for (std::size_t k = 0; k < v.size(); ++k)
      s.shortest_edge = std::min(s.shortest_edge, (v[(k + 1) % v.size()] - v[k]).norm());
  }
  return s;
}

/// The tied blocks with their joints as one continuum, against the far field's material.
struct InterfaceImpedance
{
  double blocks_modulus = 0.0;    ///< E_eff of the tied blocks and the joints behind them [Pa]
  double far_field_modulus = 0.0; ///< [Pa]
  double reflection = 0.0;        ///< of a normally incident plane wave [-]
};

/// E_eff (jointed_block_modulus) per tied block, averaged over the tied length: L the tied
/// length, p at each end of the joint behind it, d = area / L the block's depth behind it.
/// Densities are equal, so the impedance ratio is sqrt(E_eff / E_far) and the reflection |1 -
/// ratio| / (1 + ratio). Needs `joints.default` (else nothing is estimated).
std::optional<InterfaceImpedance> interface_impedance(const Scene& scene, const dda::System& system,
                                                      const coupling::FarFieldTies& ties)
{
  const dda::ModelDescription& m = scene.model;
  if (m.default_joint_material >= m.joint_materials.size())
    return std::nullopt;
  const double p = m.joint_materials[m.default_joint_material].normal_stiffness;
  // The tied length of each tied block.
  std::map<std::size_t, double> tied_length;
  for (const coupling::Tie& t : ties.get_ties())
    tied_length[t.block] += t.length;
  double sum = 0.0, weight = 0.0;
  for (const auto& [block, length] : tied_length)
  {
    const dda::Block& b = system.get_blocks()[block];
    sum += length *
           jointed_block_modulus(m.materials[b.material].youngs_modulus, p, b.moments.area, length);
    weight += length;
  }
  InterfaceImpedance z;
  z.blocks_modulus = sum / weight;
  z.far_field_modulus = scene.far_field->youngs_modulus;
  const double ratio = std::sqrt(z.blocks_modulus / z.far_field_modulus);
  z.reflection = std::abs(1.0 - ratio) / (1.0 + ratio);
  return z;
}

std::string impedance_warning(const InterfaceImpedance& z)
{
  return "the far field (E = " + format(z.far_field_modulus) +
         " Pa) and the tied blocks with their joints (E_eff = " + format(z.blocks_modulus) +
         " Pa) differ in impedance: the interface reflects about " + format(100 * z.reflection, 2) +
         "% of a normally incident wave; a far-field material of the rock mass (E_eff) avoids it";
}

const char* boundary_type_name(dda::BoundaryType t)
{
  switch (t)
  {
  case dda::BoundaryType::free:
    return "free";
  case dda::BoundaryType::vb1:
    return "vb1";
  case dda::BoundaryType::vb2:
    return "vb2";
  case dda::BoundaryType::dashpot:
    return "dashpot";
  }
  return "";
}

std::string boundary_name(const dda::ModelDescription& model, std::size_t k)
{
  const dda::BoundaryDescription& b = model.boundaries[k];
  return (b.origin.empty() ? "boundary " + std::to_string(k) : b.origin) + " (" +
         boundary_type_name(b.type) + ")";
}

/// Messages for every boundary whose edges are energy sources at the scene's dt.
std::vector<std::string> unstable_boundaries(const dda::System& system, double dt)
{
  const dda::ModelDescription& model = system.get_model();
  std::vector<std::string> messages;
  for (std::size_t b = 0; b < model.boundaries.size(); ++b)
  {
    std::size_t n_sources = 0;
    double dt_limit = std::numeric_limits<double>::infinity();
    double x_max = 0.0;
    for (std::size_t k = 0; k < system.get_boundary_edges().size(); ++k)
    {
      if (system.get_boundary_edges()[k].boundary != b)
        continue;
      const dda::BoundaryStability s = system.stability_of(k, dt);
      dt_limit = std::min(dt_limit, s.dt_source);
      x_max = std::max({x_max, s.x_n, s.x_t});
      n_sources += s.is_source ? 1 : 0;
    }
    if (n_sources > 0)
      messages.push_back("dt = " + format(dt) + " s makes " + boundary_name(model, b) +
                         " an energy source on " + std::to_string(n_sources) +
                         " edge(s): x = c dt / m reaches " + format(x_max, 4) + " > " +
                         format(dda::vb1_source_threshold(), 5) + "; it absorbs only for dt < " +
                         format(dt_limit, 4) + " s");
  }
  return messages;
}

/// The per-boundary lines of `check`: speeds, coefficients and stability of the worst edges.
void describe_boundaries(const dda::System& system, double dt, std::ostream& out)
{
  const dda::ModelDescription& model = system.get_model();
  const auto& edges = system.get_boundary_edges();
  out << "  boundaries: " << model.boundaries.size() << " (" << edges.size() << " edges)\n";
  for (std::size_t b = 0; b < model.boundaries.size(); ++b)
  {
    const dda::BoundaryDescription& bd = model.boundaries[b];
    std::vector<std::size_t> mine;
    for (std::size_t k = 0; k < edges.size(); ++k)
      if (edges[k].boundary == b)
        mine.push_back(k);
    // Worst (smallest limit) first.
    std::sort(mine.begin(), mine.end(),
              [&](std::size_t i, std::size_t j) {
                return system.stability_of(i, dt).dt_source < system.stability_of(j, dt).dt_source;
              });
    out << "    " << boundary_name(model, b) << ", "
        << (bd.impedance == dda::ImpedanceKind::effective ? "effective" : "textbook")
        << " impedance, a_n " << bd.a_n << ", a_t " << bd.a_t << ", " << mine.size() << " edge(s)"
        << (bd.has_input ? bd.input.type == dda::BoundaryInput::Type::p
                               ? ", incident P wave (2 cn v_in)"
                               : ", incident SV wave (2 ct v_in)"
                         : "")
        << "\n";
    const std::size_t shown = std::min<std::size_t>(mine.size(), 5);
    for (std::size_t i = 0; i < shown; ++i)
    {
      const dda::BoundaryEdge& e = edges[mine[i]];
      const dda::BoundaryStability s = system.stability_of(mine[i], dt);
      out << "      block " << e.block << " edge " << e.edge << ": l0 " << format(e.length)
          << " m, m " << format(s.mass) << " kg; VP/VS textbook " << format(e.textbook.p, 5) << "/"
          << format(e.textbook.s, 5) << ", effective " << format(e.effective.p, 5) << "/"
          << format(e.effective.s, 5) << " m/s; cn " << format(e.cn) << ", ct " << format(e.ct)
          << " N s/m; x = c dt / m: " << format(s.x_n, 3) << " (n), " << format(s.x_t, 3)
          << " (t)\n";
      if (bd.type == dda::BoundaryType::vb1)
        out << "        absorbs for dt < " << format(s.dt_source, 4)
            << " s (x = " << format(dda::vb1_source_threshold(), 5)
            << "), an energy source beyond; paper's "
            << "bounds: m/cn = " << format(s.dt_paper_bound, 4)
            << " s (eq. 44), 2m/ct = " << format(s.dt_paper_source, 4) << " s"
            << (s.is_source ? "  <-- dt is beyond" : "") << "\n";
      else if (bd.type != dda::BoundaryType::free)
        out << "        dissipative at every dt (positive semidefinite)\n";
    }
    if (mine.size() > shown)
      out << "      ... and " << mine.size() - shown << " more edge(s)\n";
  }
  if (system.n_supports() > 0)
    out << "  static supports: " << system.n_supports() << " edge ends held by springs of "
        << format(system.support_stiffness())
        << " N/m in static stages, their forces kept as edge loads in dynamic ones\n";
}
} // namespace

WaveSpeeds wave_speeds(const dda::Material& m)
{
  const double e = m.youngs_modulus, nu = m.poisson_ratio, rho = m.density;
  WaveSpeeds c;
  c.p_body = p_wave_speed(e, nu, rho);
  c.p_plate = std::sqrt(e / (rho * (1.0 - nu * nu)));
  c.p_bar = std::sqrt(e / rho);
  c.s = s_wave_speed(e, nu, rho);
  return c;
}

TimeStepAdvice suggest_time_step(const Scene& scene)
{
  double c_max = 0.0;
  for (const dda::Material& m : scene.model.materials)
    c_max = std::max(c_max, governing_p_speed(scene, m));
  const SmallestBlock small = smallest_block(scene);
  const double transit = std::sqrt(small.area) / c_max;

  double f_max = 0.0;
  for (const dda::PointLoad& l : scene.model.point_loads)
    f_max = std::max(f_max, l.time_function.characteristic_frequency());
  for (const dda::FixedPoint& f : scene.model.fixed_points)
    f_max = std::max({f_max, f.displacement_x.characteristic_frequency(),
                      f.displacement_y.characteristic_frequency()});
  for (const dda::BoundaryDescription& b : scene.model.boundaries)
    if (b.has_input)
      f_max = std::max(f_max, b.input.velocity.characteristic_frequency());

  TimeStepAdvice advice;
  advice.dt_max = transit;
  advice.reason = "a P wave crosses the smallest block in " + format(transit, 3) + " s";
  if (f_max > 0.0 && 1.0 / (20.0 * f_max) < advice.dt_max)
  {
    advice.dt_max = 1.0 / (20.0 * f_max);
    advice.reason =
        "20 steps per period of the highest load frequency (" + format(f_max, 4) + " Hz)";
  }
  if (f_max > 0.0 && scene.model.time.integrator == dda::Integrator::dda)
  {
    // DDA's scheme damps amplitude by about exp(-omega^2 dt t / 4) (physics.md section 2); keep
    // the loss over the time the wave needs to cross the model below 5%.
    double x_min = std::numeric_limits<double>::max(), x_max = -x_min;
    double y_min = x_min, y_max = x_max;
    for (const dda::BlockDescription& b : scene.model.blocks)
      for (const dda::Point& v : b.vertices)
      {
        x_min = std::min(x_min, v.x());
        x_max = std::max(x_max, v.x());
        y_min = std::min(y_min, v.y());
        y_max = std::max(y_max, v.y());
      }
    const double crossing = std::max(x_max - x_min, y_max - y_min) / c_max;
    const double omega = 2.0 * M_PI * f_max;
    const double dt_damping = -4.0 * std::log(0.95) / (omega * omega * crossing);
    if (dt_damping < advice.dt_max)
    {
      advice.dt_max = dt_damping;
      advice.reason = "DDA's algorithmic damping costs < 5% amplitude at " + format(f_max, 4) +
                      " Hz over a model crossing";
    }
  }
  advice.dt_min = advice.dt_max / 10.0;
  return advice;
}

namespace
{
/// Blocks, joints, DOFs, mass, the smallest block, materials and joint materials.
void describe_blocks(const Scene& scene, const dda::System& system, std::ostream& out)
{
  const dda::ModelDescription& model = scene.model;
  double total_mass = 0.0;
  for (const dda::BlockDescription& b : model.blocks)
    total_mass += model.materials[b.material].density * std::abs(dda::signed_area(b.vertices));
  std::size_t n_joint_points = 0;
  for (const dda::Joint& j : system.get_joints())
    n_joint_points += j.points.size();
  const SmallestBlock small = smallest_block(scene);
  out << "  analysis: plane " << (model.plane_mode == dda::PlaneMode::stress ? "stress" : "strain")
      << "\n";
  out << "  blocks: " << model.blocks.size() << ", bonded joints: " << system.get_joints().size()
      << " (" << n_joint_points << " spring points), DOFs: " << system.n_dofs() << "\n";
  out << "  total mass: " << format(total_mass, 6) << " kg\n";
  out << "  smallest block: " << model.blocks[small.index].origin << ", area " << format(small.area)
      << " m^2, shortest edge " << format(small.shortest_edge) << " m\n";
  if (scene.rock_mass)
    describe_rock_mass(scene, out);
  for (const dda::Material& m : model.materials)
  {
    const WaveSpeeds c = wave_speeds(m);
    out << "  material " << m.name << ": VP " << format(c.p_body, 5) << " m/s (body), "
        << format(c.p_plate, 5) << " m/s (plane stress), " << format(c.p_bar, 5)
        << " m/s (bar); VS " << format(c.s, 5) << " m/s\n";
  }
  for (const dda::JointMaterial& j : model.joint_materials)
    out << "  joint material " << j.name << ": p " << format(j.normal_stiffness) << " N/m, shear "
        << format(j.shear_ratio * j.normal_stiffness) << " N/m, phi " << j.friction_angle
        << " deg, c " << format(j.cohesion) << " Pa, tensile " << format(j.tensile_strength)
        << " Pa, " << (j.bonded ? "bonded" : "frictional") << "\n";
}

/// Loads, time stepping, contact settings, stages and the suggested dt.
void describe_stepping(const Scene& scene, const dda::System& system, std::ostream& out)
{
  const dda::ModelDescription& model = scene.model;
  out << "  loads: " << model.point_loads.size() << ", fixed points: " << model.fixed_points.size()
      << " (default penalty " << format(system.default_fixed_point_stiffness()) << " N/m)"
      << ", monitors: " << model.monitors.size() << "\n";
  const auto n_steps = static_cast<std::size_t>(std::llround(model.time.end_time / model.time.dt));
  out << "  time: dt " << format(model.time.dt) << " s, end " << format(model.time.end_time)
      << " s, " << n_steps << " steps, integrator " << dda::integrator_name(model.time.integrator)
      << "\n";
  out << "  time control: "
      << (model.time.control == dda::TimeControl::fixed ? "fixed" : "adaptive (dt is the largest)")
      << "\n";
  out << "  contacts: w0 " << format(system.half_model_size()) << " m, step displacement bound "
      << format(system.max_step_displacement()) << " m, search distance "
      << format(system.search_distance()) << " m, max penetration "
      << format(system.max_penetration()) << " m, up to "
      << model.contacts.max_open_close_iterations << " open-close iterations\n";
  for (const dda::Stage& st : model.stages)
    out << "  stage " << st.name << ": " << describe_stage(st) << "\n";
  const TimeStepAdvice advice = suggest_time_step(scene);
  out << "  suggested dt: " << format(advice.dt_min, 3) << " to " << format(advice.dt_max, 3)
      << " s (" << advice.reason << ")\n";
}

/// The far field (mesh, solver, material, resolution) of a coupled scene.
void describe_far_field(const fem::FarFieldDescription& d, const fem::ElasticWaveModel& far_field,
                        std::ostream& out)
{
  out << "  far field: " << far_field.n_cells() << " cells of "
      << format(far_field.smallest_element_size()) << " to " << format(far_field.element_size())
      << " m, FE_Q(" << d.degree << "), " << far_field.n_dofs() << " DOFs, solver "
      << far_field.solver_name() << ", integrator "
      << (d.integrator == fem::Integrator::dda ? "dda" : "newmark_trapezoidal") << "\n";
  out << "  far field material: VP " << format(far_field.p_wave_speed(), 5) << " m/s, VS "
      << format(far_field.s_wave_speed(), 5) << " m/s\n";
  const double f = std::max(d.max_frequency, d.incident.velocity.characteristic_frequency());
  if (f > 0.0)
    out << "  far-field resolution at " << format(f)
        << " Hz: " << format(far_field.s_wave_speed() / f / far_field.element_size() * d.degree, 3)
        << " nodes per S wavelength in the largest element\n";
}

/// The interface of a coupled scene: ties, their springs and strength, the impedance contrast,
/// the far field's boundaries and monitors.
void describe_interface(const Scene& scene, const dda::System& system,
                        const coupling::FarFieldTies& ties, std::ostream& out)
{
  const coupling::InterfaceDescription& i = *scene.interface;
  out << "  interface: part " << fem::name_of(i.part) << " (" << format(ties.part_length())
      << " m), " << ties.n_tied_edges() << " block edges of " << ties.n_tied_blocks() << " blocks, "
      << ties.n_ties() << " ties (" << 2 * ties.n_ties() << " condensed unknowns); p "
      << format(i.normal_stiffness) << " N/m, shear ratio " << i.shear_ratio << ", "
      << (std::isinf(i.cohesion) && std::isinf(i.tensile_strength)
              ? std::string("bonded (unlimited strength)")
              : "phi " + format(i.friction_angle) + " deg, c " + format(i.cohesion) +
                    " Pa, tensile " + format(i.tensile_strength) + " Pa")
      << "\n";
  if (const auto z = interface_impedance(scene, system, ties))
  {
    out << "  rock mass at the interface: E_eff " << format(z->blocks_modulus)
        << " Pa (blocks with their joints), far field E " << format(z->far_field_modulus)
        << " Pa: reflection of a normally incident wave about " << format(100 * z->reflection, 2)
        << "%\n";
    if (z->reflection > 0.01)
      out << "warning: " << impedance_warning(*z) << "\n";
  }
  for (const fem::BoundaryCondition& b : scene.far_field->boundaries)
    out << "  far field " << fem::name_of(b.part) << ": " << fem::name_of(b.kind) << "\n";
  out << "  far-field monitors: " << scene.far_field->monitors.size() << "\n";
}
} // namespace

std::string check_scene(const Scene& scene)
{
  if (scene.far_field && !scene.coupled())
    return check_far_field(scene);
  dda::System system(scene.model); // finds joints; throws InputError on engine-level issues
  std::unique_ptr<fem::ElasticWaveModel> far_field;
  std::unique_ptr<coupling::FarFieldTies> ties;
  if (scene.coupled())
  {
    far_field = std::make_unique<fem::ElasticWaveModel>(*scene.far_field);
    ties = std::make_unique<coupling::FarFieldTies>(system, *far_field, *scene.interface);
  }
  std::ostringstream out;
  out << "scene: " << scene.name << " (" << scene.file << ")\n";
  if (scene.tunnel)
  {
    out << "  tunnel, truncation " << name_of(scene.tunnel->truncation) << ": what it chose\n";
    for (const std::string& reason : scene.tunnel->reasons)
      out << "    " << reason << "\n";
  }
  describe_blocks(scene, system, out);
  describe_stepping(scene, system, out);
  if (!scene.model.boundaries.empty())
    describe_boundaries(system, scene.model.time.dt, out);
  if (ties)
  {
    describe_far_field(*scene.far_field, *far_field, out);
    describe_interface(scene, system, *ties, out);
  }
  for (const std::string& w : unstable_boundaries(system, scene.model.time.dt))
    out << "warning: " << w << " (`run` refuses it without --allow-unstable)\n";
  return out.str();
}

namespace
{
/// A run of blocks, alone or tied to a far field: set up, its stages in turn, the summary.
class BlocksRun
{
public:
  /// Builds the models (input errors surface here, before anything is written), creates the
  /// output directory and opens the outputs; refuses unstable boundaries unless allowed.
  BlocksRun(const Scene& scene, const RunOptions& options, std::ostream& log);
  /// Runs every stage until one fails; returns the exit code (run_scene).
  int run();

private:
  std::vector<std::string> collect_warnings(bool allow_unstable) const;
  void run_static_stage(const dda::Stage& stage);
  void run_dynamic_stage(const dda::Stage& stage);
  CoupledParts coupled_parts() const
  {
    return {far_field.get(), ties.get(), scene.far_field ? &*scene.far_field : nullptr};
  }
  void update_progress(bool force = false)
  {
    progress.update(system.n_steps(), system.time(), elapsed(wall_start), force);
  }

  const Scene& scene;
  std::ostream& log;
  const Clock::time_point wall_start = Clock::now();
  dda::System system;
  std::unique_ptr<fem::ElasticWaveModel> far_field;
  std::unique_ptr<coupling::FarFieldTies> ties;
  std::filesystem::path dir;
  std::vector<std::string> warnings;
  KeyblockRecorder keyblocks;
  std::optional<RunOutputs> outputs;
  Progress progress;
  StageTotals stages;
  LastStep last_step;
  bool initial_written = false;
  std::optional<std::vector<dda::Vector2>> fall_reference; ///< per block [m]
};

BlocksRun::BlocksRun(const Scene& scene_, const RunOptions& options, std::ostream& log_)
    : scene(scene_), log(log_), system(scene.model), keyblocks(scene.model),
      progress(!options.quiet && isatty(fileno(stderr)), scene.model.time.end_time)
{
  if (scene.coupled())
  {
    far_field = std::make_unique<fem::ElasticWaveModel>(*scene.far_field);
    ties = std::make_unique<coupling::FarFieldTies>(system, *far_field, *scene.interface);
  }
  dir = options.output_directory.empty() ? scene.output.directory : options.output_directory;
  run_support::create_output_directory(dir);
  if (scene.tunnel)
    run_support::write_text_file(dir / "expanded_scene.yaml",
                                 "# The scene " + scene.file +
                                     " as its `tunnel` section expanded it (ddafem check prints "
                                     "why)\n" +
                                     scene.expanded_yaml + "\n");
  warnings = collect_warnings(options.allow_unstable);
  for (const std::string& w : warnings)
    log << "warning: " << w << "\n";
  outputs.emplace(dir, scene.file, system, coupled_parts(), keyblocks,
                  scene.output.vtu_compression);
  stages.smallest_dt = scene.model.time.dt;
}

std::vector<std::string> BlocksRun::collect_warnings(bool allow_unstable) const
{
  const dda::TimeSettings& time = scene.model.time;
  std::vector<std::string> found;
  for (const std::string& w : unstable_boundaries(system, time.dt))
  {
    if (!allow_unstable)
      throw InputError(w + ": expected a smaller time.dt, or --allow-unstable to watch it fail");
    found.push_back(w + " (run with --allow-unstable)");
  }
  if (ties)
    if (const auto z = interface_impedance(scene, system, *ties); z && z->reflection > 0.01)
      found.push_back(impedance_warning(*z));
  const TimeStepAdvice advice = suggest_time_step(scene);
  if (time.dt > advice.dt_max)
    found.push_back("dt = " + format(time.dt) + " s exceeds the suggested " +
                    format(advice.dt_max, 3) + " s (" + advice.reason + ")");
  if (scene.rock_mass && !scene.rock_mass->slivers.empty())
    found.push_back("rock_mass: " + std::to_string(scene.rock_mass->slivers.size()) +
                    " blocks below the sliver threshold kept (`check` lists them)");
  return found;
}

void BlocksRun::run_static_stage(const dda::Stage& stage)
{
  const dda::StaticStageResult result =
      dda::run_static_stage(system, stage, scene.model.time, [&] { update_progress(); });
  stages.add(result);
  for (const dda::ReleasedBlock& r : result.released)
  {
    keyblocks.mark_released(r.block);
    if (stage.release == dda::ReleaseAction::remove)
      keyblocks.mark_removed(r.block);
  }
  stages.records.push_back(static_stage_record(stage, result, system, keyblocks));
  stages.failure = static_stage_failure(stage, result, system);
}

void BlocksRun::run_dynamic_stage(const dda::Stage& stage)
{
  system.begin_stage(dda::StageMode::dynamic);
  if (!fall_reference)
  {
    // Falls in settle stages are measured from the first dynamic stage's start.
    fall_reference.emplace();
    for (const dda::Block& b : system.get_blocks())
      fall_reference->push_back(b.displacement());
  }
  if (!initial_written)
  {
    outputs->write_state(true, last_step);
    initial_written = true;
  }
  const dda::TimeSettings& time = scene.model.time;
  // Steps of this stage as the user sets dt: with bathe one step is two System half steps.
  std::size_t stage_steps = 0;
  double next_snapshot = system.time() + scene.output.interval;
  const dda::DynamicStageResult result = dda::run_dynamic_stage(
      system, stage, time, *fall_reference,
      [&](const dda::TimeStepper& stepper, const dda::StepStatus& status, bool last)
      {
        last_step = {stepper.last_dt(), status.n_open_close_iterations, stepper.n_last_step_cuts()};
        const bool snapshot = run_support::snapshot_due(system.time(), scene.output.interval,
                                                        time.dt, next_snapshot) ||
                              last;
        ++stage_steps;
        if (stage_steps % scene.output.history_every == 0 || last || snapshot)
          outputs->write_state(snapshot, last_step);
        update_progress();
      });
  stages.add(result);
  for (const auto& [block, when] : result.removed)
    keyblocks.mark_removed(block);
  stages.records.push_back(dynamic_stage_record(stage, result, system, keyblocks));
  stages.failure = result.failure;
}

int BlocksRun::run()
{
  std::vector<dda::Stage> plan = scene.model.stages;
  if (plan.empty())
  {
    dda::Stage only;
    only.name = "dynamic";
    only.end_time = scene.model.time.end_time;
    plan.push_back(only);
  }
  for (const dda::Stage& stage : plan)
  {
    if (stage.mode == dda::StageMode::static_equilibrium)
      run_static_stage(stage);
    else
      run_dynamic_stage(stage);
    if (stages.failed())
      break;
  }
  update_progress(true);
  progress.finish();
  // Keep the state reached readable (a static-only analysis writes its equilibrium here).
  if (stages.failed() || !initial_written)
    outputs->write_state(true, last_step);
  outputs->flush();

  const double wall = elapsed(wall_start);
  const nlohmann::json summary =
      run_summary({scene, system, coupled_parts(), stages, *outputs, keyblocks, warnings, wall});
  const std::string steps =
      std::to_string(system.n_steps()) +
      (scene.model.time.integrator == dda::Integrator::bathe ? " half steps" : " steps");
  return run_support::finish_run(dir, summary,
                                 stages.failed() ? stages.failure.message : std::string(), steps,
                                 system.time(), wall, "model.pvd", log);
}
} // namespace

int run_scene(const Scene& scene, const RunOptions& options, std::ostream& log)
{
  if (scene.far_field && !scene.coupled())
    return run_far_field(scene, options, log);
  BlocksRun run(scene, options, log);
  return run.run();
}

} // namespace ddafem
