#include "app/run.h"

#include "app/keyblocks.h"
#include "app/rock_mass_scene.h"
#include "app/run_support.h"
#include "app/stage_records.h"

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

std::vector<HistoryChannel> history_channels(const dda::ModelDescription& model)
{
  std::vector<HistoryChannel> channels;
  for (const dda::Monitor& m : model.monitors)
    run_support::add_monitor_channels(channels, m.name, "of the material point", "of its block");
  channels.push_back({"energy/kinetic", 1, "J", "sum of v^T M v / 2"});
  channels.push_back({"energy/strain", 1, "J", "elastic energy of the blocks"});
  channels.push_back({"energy/spring", 1, "J", "joint and fixed-point penalty springs"});
  channels.push_back({"energy/work_of_loads", 1, "J", "point loads and gravity since t = 0"});
  channels.push_back({"energy/work_of_supports", 1, "J", "prescribed support motion since t = 0"});
  channels.push_back({"energy/work_of_boundaries", 1, "J",
                      "viscous boundaries on the model since t = 0 (negative: absorbed)"});
  channels.push_back({"energy/work_of_ties", 1, "J",
                      "ties to the far field on the blocks since t = 0 (the energy that crossed "
                      "the interface into the blocks; 0 without a far field)"});
  channels.push_back(
      {"energy/removed", 1, "J", "kinetic energy of fallen blocks removed as debris since t = 0"});
  channels.push_back({"energy/dissipated", 1, "J",
                      "initial + work - stored: algorithmic damping of the integrator, friction "
                      "and contact impacts"});
  channels.push_back({"contacts/open", 1, "", "number of open contacts"});
  channels.push_back({"contacts/slide", 1, "", "number of sliding contacts"});
  channels.push_back({"contacts/lock", 1, "", "number of locked contacts"});
  channels.push_back({"contacts/bonded_joints", 1, "", "number of intact bonded joints"});
  channels.push_back({"steps/dt", 1, "s", "time step of the last step"});
  channels.push_back(
      {"steps/open_close_iterations", 1, "", "open-close iterations of the last step"});
  channels.push_back({"steps/cuts", 1, "", "dt cuts before the last step was accepted"});
  return channels;
}

/// What the last accepted step did, for the histories.
struct LastStep
{
  double dt = 0.0;
  unsigned n_open_close_iterations = 0;
  std::size_t n_cuts = 0;
};

std::vector<double> history_row(const dda::System& system, const LastStep& last)
{
  std::vector<double> row;
  for (std::size_t k = 0; k < system.get_model().monitors.size(); ++k)
  {
    const dda::MonitorSample s = system.sample_monitor(k);
    row.insert(row.end(), {s.displacement.x(), s.displacement.y(), s.velocity.x(), s.velocity.y(),
                           s.stress[0], s.stress[1], s.stress[2]});
  }
  const dda::EnergyBalance e = system.energy();
  row.insert(row.end(), {e.kinetic, e.strain, e.spring, e.work_of_loads, e.work_of_supports,
                         e.work_of_boundaries, e.work_of_ties, e.removed, e.dissipated});
  const dda::ContactCounts n = system.contact_counts();
  row.insert(row.end(),
             {static_cast<double>(n.open), static_cast<double>(n.slide),
              static_cast<double>(n.lock), static_cast<double>(system.get_joints().size()), last.dt,
              static_cast<double>(last.n_open_close_iterations), static_cast<double>(last.n_cuts)});
  return row;
}

/// The far field and the interface of a coupled run (after the blocks' channels).
void add_coupled_channels(std::vector<HistoryChannel>& channels, const fem::FarFieldDescription& d)
{
  for (const fem::Monitor& m : d.monitors)
    run_support::add_monitor_channels(channels, m.name, "of the far field at the point",
                                      "of the far field at the point");
  const std::string ff = "far_field/energy/";
  channels.push_back({ff + "kinetic", 1, "J", "v^T M v / 2 of the far field"});
  channels.push_back({ff + "strain", 1, "J", "u^T K u / 2 of the far field"});
  channels.push_back({ff + "work_of_input", 1, "J", "incident-wave tractions since t = 0"});
  channels.push_back(
      {ff + "work_of_dashpots", 1, "J", "Lysmer dashpots since t = 0 (negative: absorbed)"});
  channels.push_back(
      {ff + "work_of_rayleigh", 1, "J", "Rayleigh damping since t = 0 (negative: absorbed)"});
  channels.push_back({ff + "work_of_ties", 1, "J",
                      "ties on the far field since t = 0: the energy that crossed the interface "
                      "into it"});
  channels.push_back({ff + "dissipated", 1, "J", "initial + work - stored: the integrator's"});
  channels.push_back({"interface/tie_energy", 1, "J",
                      "held in or dissipated by the tie springs: -(work of the ties on the "
                      "blocks without their preloads' + on the far field)"});
  channels.push_back({"interface/ties", 4, "", "number of ties (intact, locked, sliding, open)"});
}

void append_coupled_row(std::vector<double>& row, const fem::ElasticWaveModel& far_field,
                        const coupling::FarFieldTies& ties, std::size_t n_monitors)
{
  for (std::size_t k = 0; k < n_monitors; ++k)
  {
    const fem::MonitorSample s = far_field.sample_monitor(k);
    row.insert(row.end(), {s.displacement[0], s.displacement[1], s.velocity[0], s.velocity[1],
                           s.stress[0], s.stress[1], s.stress[2]});
  }
  const fem::EnergyBalance e = far_field.energy();
  row.insert(row.end(), {e.kinetic, e.strain, e.work_of_input, e.work_of_dashpots,
                         e.work_of_rayleigh, e.work_of_springs, e.dissipated, ties.tie_energy()});
  const coupling::TieCounts n = ties.counts();
  row.insert(row.end(), {static_cast<double>(n.intact), static_cast<double>(n.lock),
                         static_cast<double>(n.slide), static_cast<double>(n.open)});
}

/// The ties as contact points for VTU: state (bonded while intact), normal out of the block,
/// forces (normal compression positive, shear along the edge tangent), opening and slip.
std::vector<dda::ContactSnapshot> tie_snapshot(const coupling::FarFieldTies& ties,
                                               const dda::System& system)
{
  std::vector<dda::ContactSnapshot> out;
  const std::vector<dda::MaterialPoint>& points = system.get_tie_points();
  for (std::size_t k = 0; k < ties.n_ties(); ++k)
  {
    const coupling::Tie& t = ties.get_ties()[k];
    dda::ContactSnapshot c;
    c.id = k;
    c.block_a = c.block_b = t.block;
    switch (t.forces.state)
    {
    case dda::ContactState::lock:
      c.state = t.forces.intact ? dda::ContactPointState::bonded : dda::ContactPointState::lock;
      break;
    case dda::ContactState::slide:
      c.state = dda::ContactPointState::slide;
      break;
    case dda::ContactState::open:
      c.state = dda::ContactPointState::open;
      break;
    }
    c.position = points[k].position;
    c.normal = t.normal;
    const dda::Vector2 f = ties.total_force(k); // preload included
    c.normal_force = t.normal.dot(f);
    c.shear_force = t.tangent.dot(f);
    c.gap = -t.normal.dot(t.stretch);
    c.slip = t.tangent.dot(t.stretch);
    out.push_back(c);
  }
  return out;
}

/// DIR/model.pvd: every snapshot's parts (blocks, far field, contacts, ties) at one time, so
/// that ParaView opens the whole model from one file.
void write_model_pvd(const std::filesystem::path& dir,
                     const std::vector<std::pair<double, std::vector<std::string>>>& snapshots)
{
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "  <Collection>\n";
  out.precision(17);
  for (const auto& [time, files] : snapshots)
    for (std::size_t part = 0; part < files.size(); ++part)
      out << "    <DataSet timestep=\"" << time << "\" group=\"\" part=\"" << part << "\" file=\""
          << files[part] << "\"/>\n";
  out << "  </Collection>\n</VTKFile>\n";
  run_support::write_text_file(dir / "model.pvd", out.str());
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
  c.p_body = std::sqrt(e * (1.0 - nu) / (rho * (1.0 + nu) * (1.0 - 2.0 * nu)));
  c.p_plate = std::sqrt(e / (rho * (1.0 - nu * nu)));
  c.p_bar = std::sqrt(e / rho);
  c.s = std::sqrt(e / (2.0 * rho * (1.0 + nu)));
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
  const dda::ModelDescription& model = scene.model;
  std::ostringstream out;
  out << "scene: " << scene.name << " (" << scene.file << ")\n";
  if (scene.tunnel)
  {
    out << "  tunnel, truncation " << name_of(scene.tunnel->truncation) << ": what it chose\n";
    for (const std::string& reason : scene.tunnel->reasons)
      out << "    " << reason << "\n";
  }
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
  if (!model.boundaries.empty())
    describe_boundaries(system, model.time.dt, out);
  if (ties)
  {
    const fem::FarFieldDescription& d = *scene.far_field;
    out << "  far field: " << far_field->n_cells() << " cells of "
        << format(far_field->smallest_element_size()) << " to " << format(far_field->element_size())
        << " m, FE_Q(" << d.degree << "), " << far_field->n_dofs() << " DOFs, solver "
        << far_field->solver_name() << ", integrator "
        << (d.integrator == fem::Integrator::dda ? "dda" : "newmark_trapezoidal") << "\n";
    out << "  far field material: VP " << format(far_field->p_wave_speed(), 5) << " m/s, VS "
        << format(far_field->s_wave_speed(), 5) << " m/s\n";
    const double f = std::max(d.max_frequency, d.incident.velocity.characteristic_frequency());
    if (f > 0.0)
      out << "  far-field resolution at " << format(f) << " Hz: "
          << format(far_field->s_wave_speed() / f / far_field->element_size() * d.degree, 3)
          << " nodes per S wavelength in the largest element\n";
    const coupling::InterfaceDescription& i = *scene.interface;
    out << "  interface: part " << fem::name_of(i.part) << " (" << format(ties->part_length())
        << " m), " << ties->n_tied_edges() << " block edges of " << ties->n_tied_blocks()
        << " blocks, " << ties->n_ties() << " ties (" << 2 * ties->n_ties()
        << " condensed unknowns); p " << format(i.normal_stiffness) << " N/m, shear ratio "
        << i.shear_ratio << ", "
        << (std::isinf(i.cohesion) && std::isinf(i.tensile_strength)
                ? std::string("bonded (unlimited strength)")
                : "phi " + format(i.friction_angle) + " deg, c " + format(i.cohesion) +
                      " Pa, tensile " + format(i.tensile_strength) + " Pa")
        << "\n";
    if (const auto z = interface_impedance(scene, system, *ties))
    {
      out << "  rock mass at the interface: E_eff " << format(z->blocks_modulus)
          << " Pa (blocks with their joints), far field E " << format(z->far_field_modulus)
          << " Pa: reflection of a normally incident wave about " << format(100 * z->reflection, 2)
          << "%\n";
      if (z->reflection > 0.01)
        out << "warning: " << impedance_warning(*z) << "\n";
    }
    for (const fem::BoundaryCondition& b : d.boundaries)
      out << "  far field " << fem::name_of(b.part) << ": " << fem::name_of(b.kind) << "\n";
    out << "  far-field monitors: " << d.monitors.size() << "\n";
  }
  for (const std::string& w : unstable_boundaries(system, model.time.dt))
    out << "warning: " << w << " (`run` refuses it without --allow-unstable)\n";
  return out.str();
}

int run_scene(const Scene& scene, const RunOptions& options, std::ostream& log)
{
  if (scene.far_field && !scene.coupled())
    return run_far_field(scene, options, log);
  const auto wall_start = Clock::now();
  dda::System system(scene.model); // input errors surface here, before anything is written
  std::unique_ptr<fem::ElasticWaveModel> far_field;
  std::unique_ptr<coupling::FarFieldTies> ties;
  if (scene.coupled())
  {
    far_field = std::make_unique<fem::ElasticWaveModel>(*scene.far_field);
    ties = std::make_unique<coupling::FarFieldTies>(system, *far_field, *scene.interface);
  }

  const std::filesystem::path dir =
      options.output_directory.empty() ? scene.output.directory : options.output_directory;
  run_support::create_output_directory(dir);
  if (scene.tunnel)
    run_support::write_text_file(dir / "expanded_scene.yaml",
                                 "# The scene " + scene.file +
                                     " as its `tunnel` section expanded it (ddafem check prints "
                                     "why)\n" +
                                     scene.expanded_yaml + "\n");

  const dda::TimeSettings& time = scene.model.time;
  const TimeStepAdvice advice = suggest_time_step(scene);
  std::vector<std::string> warnings;
  for (const std::string& w : unstable_boundaries(system, time.dt))
  {
    if (!options.allow_unstable)
      throw InputError(w + ": expected a smaller time.dt, or --allow-unstable to watch it fail");
    warnings.push_back(w + " (run with --allow-unstable)");
  }
  if (ties)
    if (const auto z = interface_impedance(scene, system, *ties); z && z->reflection > 0.01)
      warnings.push_back(impedance_warning(*z));
  if (time.dt > advice.dt_max)
    warnings.push_back("dt = " + format(time.dt) + " s exceeds the suggested " +
                       format(advice.dt_max, 3) + " s (" + advice.reason + ")");
  if (scene.rock_mass && !scene.rock_mass->slivers.empty())
    warnings.push_back("rock_mass: " + std::to_string(scene.rock_mass->slivers.size()) +
                       " blocks below the sliver threshold kept (`check` lists them)");
  for (const std::string& w : warnings)
    log << "warning: " << w << "\n";

  std::vector<HistoryChannel> channels = history_channels(scene.model);
  if (ties)
    add_coupled_channels(channels, *scene.far_field);
  KeyblockRecorder keyblocks(scene.model);
  keyblocks.add_channels(channels);
  HistoryWriter history((dir / "histories.h5").string(), channels);
  history.set_attribute("scene", scene.file);
  history.set_attribute("version", DDAFEM_VERSION);
  dda::VtuSeriesWriter vtu(dir.string(), "blocks");
  dda::VtuSeriesWriter contact_vtu(dir.string(), "contacts");
  dda::VtuSeriesWriter tie_vtu(dir.string(), "ties");
  std::vector<std::pair<double, std::vector<std::string>>> model_snapshots;

  std::vector<dda::Stage> stages = scene.model.stages;
  if (stages.empty())
  {
    dda::Stage only;
    only.name = "dynamic";
    only.end_time = time.end_time;
    stages.push_back(only);
  }

  double output_time = 0.0;        // [s] histories and snapshots
  double far_field_vtu_time = 0.0; // [s] of which the far field's VTU files
  LastStep last_step;
  const auto write_state = [&](bool snapshot)
  {
    const auto start = Clock::now();
    std::vector<double> row = history_row(system, last_step);
    if (ties)
      append_coupled_row(row, *far_field, *ties, scene.far_field->monitors.size());
    keyblocks.append_row(system, row);
    history.append(system.time(), row);
    if (snapshot)
    {
      const auto name = [](const std::string& path)
      { return std::filesystem::path(path).filename().string(); };
      std::vector<std::string> files = {
          name(vtu.write(system.time(), system.snapshot())),
          name(contact_vtu.write(system.time(), system.contact_snapshot()))};
      if (ties)
      {
        const auto far_field_start = Clock::now();
        files.push_back(
            far_field->write_snapshot(dir.string(), "far_field", scene.output.vtu_compression));
        far_field_vtu_time += elapsed(far_field_start);
        files.push_back(name(tie_vtu.write(system.time(), tie_snapshot(*ties, system))));
      }
      model_snapshots.emplace_back(system.time(), files);
      write_model_pvd(dir, model_snapshots);
    }
    output_time += elapsed(start);
  };

  Progress progress(!options.quiet && isatty(fileno(stderr)), time.end_time);
  dda::StepStatus failure;
  nlohmann::json stage_records = nlohmann::json::array();
  bool initial_written = false;
  std::size_t n_cut_steps = 0, n_penalty_raises = 0, n_flips_ignored = 0;
  std::size_t n_reversals = 0;
  std::map<dda::StepOutcome, std::size_t> cuts_by_cause; // of every stage's TimeStepper
  const auto add_cuts = [&](const std::map<dda::StepOutcome, std::size_t>& causes)
  {
    for (const auto& [outcome, n] : causes)
      cuts_by_cause[outcome] += n;
  };
  double smallest_dt = time.dt;
  std::optional<std::vector<dda::Vector2>> fall_reference; // per block [m]
  for (const dda::Stage& stage : stages)
  {
    if (stage.mode == dda::StageMode::static_equilibrium)
    {
      const dda::StaticStageResult result = dda::run_static_stage(
          system, stage, time,
          [&] { progress.update(system.n_steps(), system.time(), elapsed(wall_start)); });
      n_cut_steps += result.n_cut_steps;
      n_penalty_raises += result.n_penalty_raises;
      add_cuts(result.cuts_by_cause);
      smallest_dt = std::min(smallest_dt, result.smallest_dt);
      for (const dda::ReleasedBlock& r : result.released)
      {
        keyblocks.mark_released(r.block);
        if (stage.release == dda::ReleaseAction::remove)
          keyblocks.mark_removed(r.block);
      }
      stage_records.push_back(static_stage_record(stage, result, system, keyblocks));
      failure = static_stage_failure(stage, result, system);
      if (failure.outcome != dda::StepOutcome::success)
        break;
      continue;
    }

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
      write_state(true);
      initial_written = true;
    }
    // Steps of this stage as the user sets dt: with bathe one step is two System half steps.
    std::size_t stage_steps = 0;
    double next_snapshot = system.time() + scene.output.interval;
    const dda::DynamicStageResult result = dda::run_dynamic_stage(
        system, stage, time, *fall_reference,
        [&](const dda::TimeStepper& stepper, const dda::StepStatus& status, bool last)
        {
          last_step = {stepper.last_dt(), status.n_open_close_iterations,
                       stepper.n_last_step_cuts()};
          const bool snapshot = run_support::snapshot_due(system.time(), scene.output.interval,
                                                          time.dt, next_snapshot) ||
                                last;
          ++stage_steps;
          if (stage_steps % scene.output.history_every == 0 || last || snapshot)
            write_state(snapshot);
          progress.update(system.n_steps(), system.time(), elapsed(wall_start));
        });
    n_cut_steps += result.n_cut_steps;
    n_penalty_raises += result.n_penalty_raises;
    n_flips_ignored += result.n_flips_ignored;
    n_reversals += result.n_reversals;
    add_cuts(result.cuts_by_cause);
    smallest_dt = std::min(smallest_dt, result.smallest_dt);
    for (const auto& [block, when] : result.removed)
      keyblocks.mark_removed(block);
    stage_records.push_back(dynamic_stage_record(stage, result, system, keyblocks));
    failure = result.failure;
    if (failure.outcome != dda::StepOutcome::success)
      break;
  }
  progress.update(system.n_steps(), system.time(), elapsed(wall_start), true);
  progress.finish();

  const bool failed = failure.outcome != dda::StepOutcome::success;
  // Keep the state reached readable (a static-only analysis writes its equilibrium here).
  if (failed || !initial_written)
    write_state(true);
  history.flush();

  const dda::PhaseTimings& t = system.get_timings();
  const dda::EnergyBalance e = system.energy();
  const double wall = elapsed(wall_start);
  nlohmann::json summary;
  summary["scene"] = scene.file;
  summary["name"] = scene.name;
  summary["version"] = DDAFEM_VERSION;
  summary["status"] = failed ? "numerical_failure" : "completed";
  if (failed)
    summary["failure"] = failure.message;
  summary["time_reached_s"] = system.time();
  summary["end_time_s"] = time.end_time;
  summary["steps"] = system.n_steps();
  summary["dt_s"] = time.dt;
  std::size_t n_cuts = 0;
  nlohmann::json cuts_by_cause_json = nlohmann::json::object();
  for (const auto& [outcome, n] : cuts_by_cause)
  {
    n_cuts += n;
    cuts_by_cause_json[dda::outcome_name(outcome)] = n;
  }
  summary["time_step"] = {
      {"control", time.control == dda::TimeControl::fixed ? "fixed" : "adaptive"},
      {"dt_max_s", time.dt},
      {"smallest_dt_s", smallest_dt},
      {"attempts", system.get_timings().n_attempts},
      {"cuts", n_cuts},
      {"cuts_by_cause", cuts_by_cause_json},
      {"steps_cut", n_cut_steps},
      {"penalty_raises", n_penalty_raises},
      {"flips_ignored", n_flips_ignored},
      {"slip_reversals", n_reversals}};
  summary["stages"] = stage_records;
  if (scene.tunnel)
  {
    const TunnelPlan& plan = *scene.tunnel;
    summary["tunnel"] = {{"truncation", name_of(plan.truncation)},
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
  summary["integrator"] = dda::integrator_name(time.integrator);
  if (time.integrator == dda::Integrator::generalized_alpha)
    summary["spectral_radius"] = time.spectral_radius;
  summary["solver"] = {{"name", system.get_solver().name()},
                       {"factorizations", system.get_solver().n_factorizations()},
                       {"solves", system.get_solver().n_solves()},
                       {"refinement_iterations", system.get_solver().n_refinements()}};
  summary["model"] = {{"blocks", system.get_blocks().size()},
                      {"bonded_joints", system.get_joints().size()},
                      {"dofs", system.n_dofs()}};
  if (ties)
  {
    const fem::Timings& ft = far_field->timings();
    const fem::EnergyBalance fe = far_field->energy();
    summary["model"]["far_field_cells"] = far_field->n_cells();
    summary["model"]["far_field_dofs"] = far_field->n_dofs();
    summary["model"]["element_size_m"] = far_field->element_size();
    summary["model"]["ties"] = ties->n_ties();
    summary["model"]["tied_edges"] = ties->n_tied_edges();
    summary["model"]["tied_blocks"] = ties->n_tied_blocks();
    summary["far_field"] = {{"solver", far_field->solver_name()},
                            {"timings_s",
                             {{"setup", ft.setup},
                              {"assemble", ft.assemble},
                              {"solve", ft.solve},
                              {"update", ft.update}}},
                            {"energy_J",
                             {{"kinetic", fe.kinetic},
                              {"strain", fe.strain},
                              {"work_of_input", fe.work_of_input},
                              {"work_of_dashpots", fe.work_of_dashpots},
                              {"work_of_rayleigh", fe.work_of_rayleigh},
                              {"work_of_ties", fe.work_of_springs},
                              {"dissipated", fe.dissipated}}}};
    const coupling::TieCounts n = ties->counts();
    summary["interface"] = {
        {"ties", {{"intact", n.intact}, {"lock", n.lock}, {"slide", n.slide}, {"open", n.open}}},
        {"work_into_blocks_J", ties->work_on_blocks()},
        {"work_into_far_field_J", fe.work_of_springs},
        {"tie_energy_J", ties->tie_energy()},
        {"timings_s",
         {{"condensation", ties->condensation_seconds()}, {"ties", ties->tie_seconds()}}}};
  }
  const dda::ContactCounts counts = system.contact_counts();
  summary["contacts"] = {{"open", counts.open},
                         {"slide", counts.slide},
                         {"lock", counts.lock},
                         {"broken_joints", system.n_broken_joints()},
                         {"open_close_iterations", system.get_timings().n_open_close_iterations},
                         {"search_distance_m", system.search_distance()},
                         {"max_step_displacement_m", system.max_step_displacement()}};
  summary["wall_time_s"] = wall;
  summary["peak_memory_mb"] = run_support::peak_memory_mb();
  summary["timings_s"] = {{"broad_phase", t.broad_phase}, {"narrow_phase", t.narrow_phase},
                          {"assemble", t.assemble},       {"solve", t.solve},
                          {"update", t.update},           {"output", output_time},
                          {"tie_terms", t.tie_terms},     {"tied_body", t.tied_body}};
  // Parts of timings_s: the far field's VTU files within output.
  summary["timings_detail_s"] = {{"output_far_field_vtu", far_field_vtu_time}};
  summary["energy_J"] = {{"kinetic", e.kinetic},
                         {"strain", e.strain},
                         {"spring", e.spring},
                         {"work_of_loads", e.work_of_loads},
                         {"work_of_supports", e.work_of_supports},
                         {"work_of_boundaries", e.work_of_boundaries},
                         {"work_of_ties", e.work_of_ties},
                         {"removed", e.removed},
                         {"initial", e.initial},
                         {"dissipated", e.dissipated}};
  if (!keyblocks.empty())
    summary["keyblocks"] = keyblocks.summary(system);
  summary["warnings"] = warnings;
  summary["outputs"] = {{"histories", "histories.h5"},
                        {"model", "model.pvd"},
                        {"blocks", "blocks.pvd"},
                        {"contacts", "contacts.pvd"},
                        {"snapshots", vtu.n_written()}};
  if (ties)
  {
    summary["outputs"]["far_field"] = "far_field.pvd";
    summary["outputs"]["ties"] = "ties.pvd";
  }
  const std::string steps = std::to_string(system.n_steps()) +
                            (time.integrator == dda::Integrator::bathe ? " half steps" : " steps");
  return run_support::finish_run(dir, summary, failed ? failure.message : std::string(), steps,
                                 system.time(), wall, "model.pvd", log);
}

} // namespace ddafem
