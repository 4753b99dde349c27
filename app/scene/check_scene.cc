// `ddafem check`: what a scene builds into (blocks, joints, boundaries, the far field and the
// interface, or a far field alone), the engineering rules' findings and the suggested dt.
#include "app/far_field_module/far_field_module.h"
#include "app/run/element_outputs.h"
#include "app/run/keyblocks.h"
#include "app/run/run.h"
#include "app/run/run_warnings.h"
#include "app/run/stage_records.h"
#include "app/scene/rock_mass_scene.h"

#include "common/format.h"
#include "common/resource_limits.h"

#include "dda/system.h"
#include "dda/time_step_advice.h"

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
  const auto& edges = system.boundaries().edges;
  out << "  boundaries: " << model.boundaries.size() << " (" << edges.size() << " edges)\n";
  for (std::size_t b = 0; b < model.boundaries.size(); ++b)
  {
    const dda::BoundaryDescription& bd = model.boundaries[b];
    std::vector<std::size_t> mine;
    for (std::size_t k = 0; k < edges.size(); ++k)
      if (edges[k].boundary == b)
        mine.push_back(k);
    // Worst (smallest limit) first.
    std::sort(
        mine.begin(), mine.end(),
        [&](std::size_t i, std::size_t j)
        { return stability_of(system, i, dt).dt_source < stability_of(system, j, dt).dt_source; });
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
      const dda::BoundaryStability s = stability_of(system, mine[i], dt);
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
  if (system.boundaries().supports.size() > 0)
    out << "  static supports: " << system.boundaries().supports.size()
        << " edge ends held by springs of "
        << format_significant(system.boundaries().support_normal_stiffness)
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
  for (const dda::Joint& j : system.bonded_joints().list)
    n_joint_points += j.points.size();
  const dda::SmallestBlock small = dda::smallest_block(model.blocks);
  out << "  analysis: plane " << name_of(model.plane_mode) << "\n";
  out << "  blocks: " << model.blocks.size()
      << ", bonded joints: " << system.bonded_joints().list.size() << " (" << n_joint_points
      << " spring points), DOFs: " << system.blocks().n_dofs() << "\n";
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
      << " (default penalty " << format_significant(system.points().default_stiffness) << " N/m)"
      << ", monitors: " << model.monitors.size() << "\n";
  for (const std::unique_ptr<ElementOutputs>& o : make_element_outputs())
    o->describe(system, out);
  const auto n_steps = static_cast<std::size_t>(std::llround(model.time.end_time / model.time.dt));
  out << "  time: dt " << format_significant(model.time.dt) << " s, end "
      << format_significant(model.time.end_time) << " s, " << n_steps << " steps, integrator "
      << name_of(model.time.integrator) << "\n";
  out << "  time control: " << name_of(model.time.control)
      << (model.time.control == dda::TimeControl::adaptive ? " (dt is the largest)" : "") << "\n";
  out << "  contacts: w0 " << format_significant(system.contacts().distances.w0)
      << " m, step displacement bound "
      << format_significant(system.contacts().distances.max_step_displacement)
      << " m, search distance " << format_significant(system.contacts().distances.search_distance)
      << " m, max penetration " << format_significant(system.contacts().distances.max_penetration)
      << " m, up to " << model.contacts.max_open_close_iterations << " open-close iterations\n";
  for (const dda::Stage& st : model.stages)
    out << "  stage " << st.name << ": " << describe_stage(st) << "\n";
  const dda::TimeStepAdvice advice = dda::suggest_time_step(model);
  out << "  suggested dt: " << format_significant(advice.dt_min, 3) << " to "
      << format_significant(advice.dt_max, 3) << " s (" << time_step_reason(advice) << ")\n";
}

/// One yield acceleration: "2.1 m/s^2 (0.21 g), slides on edge 3".
std::string describe_yield(const dda::YieldAcceleration& y)
{
  if (y.mode == dda::YieldMode::none)
    return "none (this shaking alone cannot move it without rotating it)";
  if (y.a_y == 0.0)
    return "0 (gravity alone moves it: " +
           std::string(y.mode == dda::YieldMode::slide ? "slides" : "falls") + ")";
  std::string text =
      format_significant(y.a_y, 3) + " m/s^2 (" + format_significant(y.a_y / 9.80665, 3) + " g), ";
  return text + (y.mode == dda::YieldMode::slide ? "slides on edge " + std::to_string(y.edge)
                                                 : std::string("lifts off"));
}

/// Newmark's yield acceleration of each keyblock (app/run/keyblocks.h), if the blocks enclose an
/// opening.
void describe_keyblocks(const Scene& scene, std::ostream& out)
{
  const KeyblockRecorder keyblocks(scene.model);
  if (keyblocks.empty())
    return;
  out << "  keyblocks: " << keyblocks.keyblock_ids().size()
      << "; Newmark's yield acceleration a_y of each, rigid on the joints of its edges with "
         "their friction (no cohesion, tension or clamping by the in-situ stress: a lower "
         "bound), horizontal | vertical ground acceleration:\n";
  for (std::size_t k = 0; k < keyblocks.keyblock_ids().size(); ++k)
  {
    const KeyblockRecorder::Yield& y = keyblocks.yield_accelerations()[k];
    out << "    block " << keyblocks.keyblock_ids()[k] << ": " << describe_yield(y.horizontal)
        << " | " << describe_yield(y.vertical) << "\n";
  }
}

/// The estimate that read_scene checked against the memory limit, for the model as read.
std::string describe_resources(const Scene& scene)
{
  const double dofs = scene.far_field ? estimate_far_field_dofs(*scene.far_field) : 0.0;
  const auto n_blocks = static_cast<double>(scene.model.blocks.size());
  const double bytes =
      MemoryModel::of_blocks(n_blocks) + (scene.far_field ? MemoryModel::of_far_field(dofs) : 0.0);
  std::ostringstream out;
  out << "resources: " << scene.model.blocks.size() << " blocks";
  if (scene.far_field)
    out << ", far field about " << format_number(std::round(dofs)) << " DOFs";
  out << "; estimated peak memory " << format_bytes(bytes) << ", limit "
      << (scene.limits.memory > 0.0
              ? format_bytes(scene.limits.memory) + " (" + scene.limits.source + ")"
              : std::string("none"))
      << "\n";
  return out.str();
}
/// The rock's damping (dda/damping.h): each damped material's and joint material's ratio, the
/// frequency where it holds and beta; the far field's Rayleigh factors.
void describe_damping(const Scene& scene, std::ostream& out)
{
  const auto line = [&](const std::string& what, const dda::RockDamping& d)
  {
    if (d.active())
      out << "  damping of " << what << ": " << format_significant(100.0 * d.ratio) << " % at "
          << format_significant(d.frequency) << " Hz, beta "
          << format_significant(d.stiffness_factor()) << " s (stiffness-proportional)\n";
  };
  for (const dda::Material& m : scene.model.materials)
    line("material " + m.name, m.damping);
  for (const dda::JointMaterial& j : scene.model.joint_materials)
    line("joint material " + j.name, j.damping);
  if (scene.far_field &&
      (scene.far_field->rayleigh.alpha > 0.0 || scene.far_field->rayleigh.beta > 0.0))
    out << "  damping of the far field: Rayleigh alpha "
        << format_significant(scene.far_field->rayleigh.alpha) << " 1/s, beta "
        << format_significant(scene.far_field->rayleigh.beta) << " s\n";
}

} // namespace

std::string check_scene(const Scene& scene)
{
  if (scene.far_field && !scene.coupled())
    return far_field_module().check_far_field(scene) + describe_resources(scene);
  dda::System system(scene.model); // finds joints; throws InputError on engine-level issues
  const std::unique_ptr<TiedFarField> tied =
      scene.coupled() ? far_field_module().tie(scene, system) : nullptr;
  std::ostringstream out;
  out << "scene: " << scene.name << " (" << scene.file << ")\n";
  if (scene.tunnel)
  {
    out << "  tunnel, truncation " << name_of(scene.tunnel->truncation) << ": what it chose\n";
    for (const std::string& reason : scene.tunnel->reasons)
      out << "    " << reason << "\n";
  }
  describe_blocks(scene, system, out);
  describe_keyblocks(scene, out);
  describe_stepping(scene, system, out);
  describe_damping(scene, out);
  if (!scene.model.boundaries.empty())
    describe_boundaries(system, scene.model.time.dt, out);
  if (tied)
    tied->describe(out);
  for (const std::string& w : unstable_boundary_messages(system, scene.model.time.dt))
    out << "warning: " << w << " (`run` refuses it without --allow-unstable)\n";
  for (const std::string& w : scene.warnings)
    out << "warning: " << w << "\n";
  out << describe_resources(scene);
  return out.str();
}

} // namespace ddafem
