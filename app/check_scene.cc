// `ddafem check`: what a scene builds into (blocks, joints, boundaries, the far field and the
// interface, or a far field alone), the engineering rules' findings and the suggested dt.
#include "app/rock_mass_scene.h"
#include "app/run.h"
#include "app/run_warnings.h"
#include "app/stage_records.h"

#include "common/format.h"

#include "coupling/far_field_ties.h"
#include "coupling/interface_impedance.h"
#include "dda/system.h"
#include "dda/time_step_advice.h"
#include "fem/elastic_wave_model.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

namespace ddafem
{
namespace
{

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
    out << "    " << boundary_name(model, b) << ", " << name_of(bd.impedance) << " impedance, a_n "
        << bd.a_n << ", a_t " << bd.a_t << ", " << mine.size() << " edge(s)"
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
      out << "      block " << e.block << " edge " << e.edge << ": l0 "
          << format_significant(e.length) << " m, m " << format_significant(s.mass)
          << " kg; VP/VS textbook " << format_significant(e.textbook.p, 5) << "/"
          << format_significant(e.textbook.s, 5) << ", effective "
          << format_significant(e.effective.p, 5) << "/" << format_significant(e.effective.s, 5)
          << " m/s; cn " << format_significant(e.cn) << ", ct " << format_significant(e.ct)
          << " N s/m; x = c dt / m: " << format_significant(s.x_n, 3) << " (n), "
          << format_significant(s.x_t, 3) << " (t)\n";
      if (bd.type == dda::BoundaryType::vb1)
        out << "        absorbs for dt < " << format_significant(s.dt_source, 4)
            << " s (x = " << format_significant(dda::vb1_source_threshold(), 5)
            << "), an energy source beyond; paper's "
            << "bounds: m/cn = " << format_significant(s.dt_paper_bound, 4)
            << " s (eq. 44), 2m/ct = " << format_significant(s.dt_paper_source, 4) << " s"
            << (s.is_source ? "  <-- dt is beyond" : "") << "\n";
      else if (bd.type != dda::BoundaryType::free)
        out << "        dissipative at every dt (positive semidefinite)\n";
    }
    if (mine.size() > shown)
      out << "      ... and " << mine.size() - shown << " more edge(s)\n";
  }
  if (system.n_supports() > 0)
    out << "  static supports: " << system.n_supports() << " edge ends held by springs of "
        << format_significant(system.support_stiffness())
        << " N/m in static stages, their forces kept as edge loads in dynamic ones\n";
}

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
  const dda::SmallestBlock small = dda::smallest_block(model.blocks);
  out << "  analysis: plane " << name_of(model.plane_mode) << "\n";
  out << "  blocks: " << model.blocks.size() << ", bonded joints: " << system.get_joints().size()
      << " (" << n_joint_points << " spring points), DOFs: " << system.n_dofs() << "\n";
  out << "  total mass: " << format_significant(total_mass, 6) << " kg\n";
  out << "  smallest block: " << model.blocks[small.index].origin << ", area "
      << format_significant(small.area) << " m^2, shortest edge "
      << format_significant(small.shortest_edge) << " m\n";
  if (scene.rock_mass)
    describe_rock_mass(scene, out);
  for (const dda::Material& m : model.materials)
  {
    const dda::WaveSpeeds c = dda::wave_speeds(m);
    out << "  material " << m.name << ": VP " << format_significant(c.p_body, 5) << " m/s (body), "
        << format_significant(c.p_plate, 5) << " m/s (plane stress), "
        << format_significant(c.p_bar, 5) << " m/s (bar); VS " << format_significant(c.s, 5)
        << " m/s\n";
  }
  for (const dda::JointMaterial& j : model.joint_materials)
    out << "  joint material " << j.name << ": p " << format_significant(j.normal_stiffness)
        << " N/m, shear " << format_significant(j.shear_ratio * j.normal_stiffness) << " N/m, phi "
        << j.friction_angle << " deg, c " << format_significant(j.cohesion) << " Pa, tensile "
        << format_significant(j.tensile_strength) << " Pa, " << (j.bonded ? "bonded" : "frictional")
        << "\n";
}

/// Loads, time stepping, contact settings, stages and the suggested dt.
void describe_stepping(const Scene& scene, const dda::System& system, std::ostream& out)
{
  const dda::ModelDescription& model = scene.model;
  out << "  loads: " << model.point_loads.size() << ", fixed points: " << model.fixed_points.size()
      << " (default penalty " << format_significant(system.default_fixed_point_stiffness())
      << " N/m)"
      << ", monitors: " << model.monitors.size() << "\n";
  const auto n_steps = static_cast<std::size_t>(std::llround(model.time.end_time / model.time.dt));
  out << "  time: dt " << format_significant(model.time.dt) << " s, end "
      << format_significant(model.time.end_time) << " s, " << n_steps << " steps, integrator "
      << name_of(model.time.integrator) << "\n";
  out << "  time control: " << name_of(model.time.control)
      << (model.time.control == dda::TimeControl::adaptive ? " (dt is the largest)" : "") << "\n";
  out << "  contacts: w0 " << format_significant(system.half_model_size())
      << " m, step displacement bound " << format_significant(system.max_step_displacement())
      << " m, search distance " << format_significant(system.search_distance())
      << " m, max penetration " << format_significant(system.max_penetration()) << " m, up to "
      << model.contacts.max_open_close_iterations << " open-close iterations\n";
  for (const dda::Stage& st : model.stages)
    out << "  stage " << st.name << ": " << describe_stage(st) << "\n";
  const dda::TimeStepAdvice advice = dda::suggest_time_step(model);
  out << "  suggested dt: " << format_significant(advice.dt_min, 3) << " to "
      << format_significant(advice.dt_max, 3) << " s (" << time_step_reason(advice) << ")\n";
}

/// The far field (mesh, solver, material, resolution) of a coupled scene.
void describe_far_field(const fem::FarFieldDescription& d, const fem::ElasticWaveModel& far_field,
                        std::ostream& out)
{
  out << "  far field: " << far_field.n_cells() << " cells of "
      << format_significant(far_field.smallest_element_size()) << " to "
      << format_significant(far_field.element_size()) << " m, FE_Q(" << d.degree << "), "
      << far_field.n_dofs() << " DOFs, solver " << far_field.solver_name() << ", integrator "
      << fem::name_of(d.integrator) << "\n";
  out << "  far field material: VP " << format_significant(far_field.p_wave_speed(), 5)
      << " m/s, VS " << format_significant(far_field.s_wave_speed(), 5) << " m/s\n";
  const double f = std::max(d.max_frequency, d.incident.velocity.characteristic_frequency());
  if (f > 0.0)
    out << "  far-field resolution at " << format_significant(f) << " Hz: "
        << format_significant(far_field.s_wave_speed() / f / far_field.element_size() * d.degree, 3)
        << " nodes per S wavelength in the largest element\n";
}

/// The interface of a coupled scene: ties, their springs and strength, the impedance contrast,
/// the far field's boundaries and monitors.
void describe_interface(const Scene& scene, const dda::System& system,
                        const coupling::FarFieldTies& ties, std::ostream& out)
{
  const coupling::InterfaceDescription& i = *scene.interface;
  out << "  interface: part " << fem::name_of(i.part) << " ("
      << format_significant(ties.part_length()) << " m), " << ties.n_tied_edges()
      << " block edges of " << ties.n_tied_blocks() << " blocks, " << ties.n_ties() << " ties ("
      << 2 * ties.n_ties() << " condensed unknowns); p " << format_significant(i.normal_stiffness)
      << " N/m, shear ratio " << i.shear_ratio << ", "
      << (std::isinf(i.cohesion) && std::isinf(i.tensile_strength)
              ? std::string("bonded (unlimited strength)")
              : "phi " + format_significant(i.friction_angle) + " deg, c " +
                    format_significant(i.cohesion) + " Pa, tensile " +
                    format_significant(i.tensile_strength) + " Pa")
      << "\n";
  if (const auto z =
          coupling::interface_impedance(scene.model, system, ties, scene.far_field->youngs_modulus))
  {
    out << "  rock mass at the interface: E_eff " << format_significant(z->blocks_modulus)
        << " Pa (blocks with their joints), far field E "
        << format_significant(z->far_field_modulus)
        << " Pa: reflection of a normally incident wave about "
        << format_significant(100 * z->reflection, 2) << "%\n";
    if (z->reflection > 0.01)
      out << "warning: " << impedance_warning(*z) << "\n";
  }
  for (const fem::BoundaryCondition& b : scene.far_field->boundaries)
    out << "  far field " << fem::name_of(b.part) << ": " << fem::name_of(b.kind) << "\n";
  out << "  far-field monitors: " << scene.far_field->monitors.size() << "\n";
}

/// `check` of a far-field-only scene: mesh, wave speeds, elements per wavelength, boundaries.
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
  for (const std::string& w : unstable_boundary_messages(system, scene.model.time.dt))
    out << "warning: " << w << " (`run` refuses it without --allow-unstable)\n";
  return out.str();
}

} // namespace ddafem
