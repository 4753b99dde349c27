// The `far_field` section (rectangle or Gmsh mesh, hole, static stage, damping, boundaries,
// incident wave), the `interface` that ties blocks to it, and the checks between them and the rest
// of the scene.
#include "app/scene/scene_readers.h"
#include "app/schema/bound_sections.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

namespace ddafem::scene_reading
{
namespace
{
/// `far_field.rayleigh`: {alpha, beta} or {ratio, frequencies}.
fem::RayleighDamping read_rayleigh(const MapReader& r)
{
  fem::RayleighDamping rayleigh;
  const bool factors = r.has("alpha") || r.has("beta");
  const bool ratio = r.has("ratio") || r.has("frequencies");
  if (factors == ratio)
    throw r.error(factors ? "ratio" : "alpha",
                  "expected either `alpha` and/or `beta`, or `ratio` with `frequencies`");
  if (factors)
  {
    rayleigh.alpha = r.has("alpha") ? r.number("alpha") : 0.0;
    rayleigh.beta = r.has("beta") ? r.number("beta") : 0.0;
    return rayleigh;
  }
  for (const char* k : {"ratio", "frequencies"})
    if (!r.has(k))
      throw r.error(k, "missing required key: `ratio` needs `frequencies` [f1, f2] and back");
  const double zeta = r.number("ratio");
  const Vector2 f = r.vector2("frequencies");
  if (!(f.y() > f.x()))
    throw r.error("frequencies", "expected f1 < f2");
  const double w1 = 2.0 * M_PI * f.x(), w2 = 2.0 * M_PI * f.y();
  rayleigh.alpha = 2.0 * zeta * w1 * w2 / (w1 + w2);
  rayleigh.beta = 2.0 * zeta / (w1 + w2);
  return rayleigh;
}

/// `far_field.mesh`: the Gmsh file (relative to the scene) and its tags.
fem::MeshFile read_mesh_file(const MapReader& f)
{
  for (const char* corner : {"lower", "upper"})
    if (f.has(corner))
      throw f.error(corner, "expected no rectangle corners with a `mesh` file (the mesh is the "
                            "file's)");
  if (f.has("hole"))
    throw f.error("hole", "expected no `hole` with a `mesh` file (the file brings its own)");
  const MapReader r = f.section_reader("mesh");
  fem::MeshFile mesh;
  std::filesystem::path path(r.string("file"));
  if (path.is_relative())
    path = r.ctx().scene_directory / path;
  mesh.file = path.lexically_normal().string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw r.error("file", "cannot open mesh file '" + mesh.file + "': expected a Gmsh .msh file");
  const MapReader parts = r.section_reader("parts");
  std::map<long long, std::string> seen;
  for (const auto& [value, part] : enum_names(fem::BoundaryPart{}))
    if (parts.has(part))
    {
      const long long tag = parts.integer(part);
      const auto [it, inserted] = seen.emplace(tag, part);
      if (!inserted)
        throw parts.error(part, "the tag is also given to `" + it->second +
                                    "`: expected one physical tag per part");
      mesh.parts[value] = static_cast<unsigned int>(tag);
    }
  return mesh;
}

/// `far_field.hole`: the keys of its shape, no others.
fem::HoleDescription read_hole(const MapReader& r, const fem::FarFieldDescription& d)
{
  fem::HoleDescription hole;
  const std::string shape = r.choice("shape");
  const std::map<std::string, std::vector<std::string>> keys = {{"rectangle", {"lower", "upper"}},
                                                                {"polygon", {"vertices"}},
                                                                {"circle", {"center", "radius"}}};
  for (const auto& [other, names] : keys)
    for (const std::string& name : names)
    {
      const bool mine = other == shape;
      if (mine && !r.has(name))
        throw r.error(name, "missing required key for shape " + shape);
      if (!mine && r.has(name) &&
          std::find(keys.at(shape).begin(), keys.at(shape).end(), name) == keys.at(shape).end())
        throw r.error(name, "expected only the keys of shape " + shape + " (" +
                                join(keys.at(shape), ", ") + ")");
    }
  hole.shape = *value_of<fem::HoleShape>(shape);
  std::array<double, 4> box{}; // x0, x1, y0, y1 of the hole
  if (hole.shape == fem::HoleShape::rectangle)
  {
    const Vector2 lower = r.vector2("lower"), upper = r.vector2("upper");
    if (!(upper.x() > lower.x() && upper.y() > lower.y()))
      throw r.error("upper",
                    "expected upper > lower in both x and y, lower = " + format_point(lower));
    hole.lower = {lower.x(), lower.y()};
    hole.upper = {upper.x(), upper.y()};
    box = {lower.x(), upper.x(), lower.y(), upper.y()};
  }
  else if (hole.shape == fem::HoleShape::polygon)
  {
    hole.vertices = r.pair_list("vertices");
    if (hole.vertices.size() < 3)
      throw r.error("vertices", "expected at least 3 vertices");
    box = {hole.vertices[0][0], hole.vertices[0][0], hole.vertices[0][1], hole.vertices[0][1]};
    for (const auto& v : hole.vertices)
      box = {std::min(box[0], v[0]), std::max(box[1], v[0]), std::min(box[2], v[1]),
             std::max(box[3], v[1])};
  }
  else
  {
    const Vector2 c = r.vector2("center");
    hole.center = {c.x(), c.y()};
    hole.radius = r.number("radius");
    box = {c.x() - hole.radius, c.x() + hole.radius, c.y() - hole.radius, c.y() + hole.radius};
  }
  if (!(box[0] > d.lower[0] && box[1] < d.upper[0] && box[2] > d.lower[1] && box[3] < d.upper[1]))
    throw r.error("shape",
                  "the hole spans [" + format_number(box[0]) + ", " + format_number(box[1]) +
                      "] x [" + format_number(box[2]) + ", " + format_number(box[3]) +
                      "]: expected it strictly inside the far field [" + format_number(d.lower[0]) +
                      ", " + format_number(d.upper[0]) + "] x [" + format_number(d.lower[1]) +
                      ", " + format_number(d.upper[1]) + "]");
  schema::far_field_hole_keys().fill(r, hole);
  return hole;
}

/// `far_field.static_stage`: gravity (else the scene's), the in-situ stress and the support.
fem::StaticStage read_static_stage(const MapReader& r, const fem::FarFieldDescription& d)
{
  fem::StaticStage s = d.static_stage; // gravity: the scene's unless the stage gives its own
  s.enabled = true;
  s.reference_y = d.upper[1];
  schema::far_field_static_stage_keys().fill(r, s);
  return s;
}

/// One `far_field.boundaries[i]` item; `parts` are the sides listed before it.
fem::BoundaryCondition read_far_field_boundary(const MapReader& r,
                                               const fem::FarFieldDescription& d,
                                               std::set<std::string>& parts)
{
  fem::BoundaryCondition bc;
  const std::string part = r.choice("part");
  if (!parts.insert(part).second)
    throw r.error("part", "side '" + part + "' is listed twice: expected each side once");
  bc.part = *value_of<fem::BoundaryPart>(part);
  if (bc.part == fem::BoundaryPart::hole && d.hole.shape == fem::HoleShape::none &&
      d.mesh_file.parts.count(fem::BoundaryPart::hole) == 0)
    throw r.error("part", "the far field has no hole: expected a `far_field.hole` section or "
                          "a `hole` tag in `far_field.mesh.parts`");
  schema::far_field_boundary_keys().fill(r, bc);
  if (r.has("springs"))
  {
    if (bc.kind != fem::BoundaryKind::lysmer)
      throw r.error("springs", "springs stand beside Lysmer dashpots: expected `type: lysmer`");
    const MapReader sr = r.section_reader("springs");
    bc.springs.enabled = true;
    schema::far_field_springs_keys().fill(sr, bc.springs);
  }
  return bc;
}

/// Stages of blocks tied to a far field: static stages hold the far field (the ties are
/// springs to fixed ground) and the far field starts at rest from the first dynamic stage, so
/// every static stage must come before it; a static stage cannot carry a frictional interface
/// (its ties would need Mohr-Coulomb on the preload plus the spring force).
void check_coupled_stages(const MapReader& top, const dda::ModelDescription& model)
{
  const std::vector<MapReader> items = top.section_list("stages");
  bool dynamic_seen = false;
  for (std::size_t i = 0; i < model.stages.size(); ++i)
  {
    if (model.stages[i].mode == dda::StageMode::dynamic)
    {
      dynamic_seen = true;
      continue;
    }
    if (dynamic_seen)
      throw items[i].error("mode", "a static stage after a dynamic one in a coupled scene: the "
                                   "far field carries only the dynamic increment from the first "
                                   "dynamic stage on and cannot be held again; expected every "
                                   "static stage before the dynamic ones");
    if (top.section_reader("interface").has("joint_material"))
      throw top.section_reader("interface")
          .error("joint_material",
                 "static stages hold the ties as springs to fixed ground and do not follow a "
                 "frictional interface: expected no `interface.joint_material` (a linear "
                 "interface) with the static stage " +
                     items[i].key_path());
  }
}

/// The `interface` section: ties between the blocks and the far field's part they fill.
coupling::InterfaceDescription read_interface(const MapReader& r,
                                              const dda::ModelDescription& model,
                                              const std::vector<std::string>& joint_names)
{
  coupling::InterfaceDescription d;
  // Springs from the named joint material (and its strength), else from joints.default.
  const dda::JointMaterial* source = nullptr;
  if (r.has("joint_material"))
  {
    source = &model.joint_materials[find_name(r, "joint_material", r.string("joint_material"),
                                              joint_names, "joint material")];
    d.cohesion = source->cohesion;
    d.tensile_strength = source->tensile_strength;
    d.friction_angle = source->friction_angle;
  }
  else if (model.default_joint_material < model.joint_materials.size())
    source = &model.joint_materials[model.default_joint_material];
  if (source)
  {
    d.normal_stiffness = source->normal_stiffness;
    d.shear_ratio = source->shear_ratio;
  }
  schema::interface_keys().fill(r, d); // part, the springs given, points per face, tolerance
  if (!(d.normal_stiffness > 0.0))
    throw r.error("normal_stiffness", "no spring for the ties: expected `normal_stiffness` [N/m], "
                                      "a `joint_material`, or `joints.default`");
  return d;
}
} // namespace

/// Monitors of a far-field scene must lie in its rectangle.
void check_point_in_far_field(const MapReader& r, const std::string& key, const Point& p,
                              const fem::FarFieldDescription& far_field)
{
  const double tol = 1e-9 * std::hypot(far_field.upper[0] - far_field.lower[0],
                                       far_field.upper[1] - far_field.lower[1]);
  if (p.x() < far_field.lower[0] - tol || p.x() > far_field.upper[0] + tol ||
      p.y() < far_field.lower[1] - tol || p.y() > far_field.upper[1] + tol)
    throw r.error(
        key, "the point " + format_point(p) + " lies outside the far field; expected a point in [" +
                 format_number(far_field.lower[0]) + ", " + format_number(far_field.upper[0]) +
                 "] x [" + format_number(far_field.lower[1]) + ", " +
                 format_number(far_field.upper[1]) + "]");
}

namespace
{
/// Perimeter of the hole [m] (0 without one).
double hole_perimeter(const fem::HoleDescription& h)
{
  switch (h.shape)
  {
  case fem::HoleShape::circle:
    return 2.0 * M_PI * h.radius;
  case fem::HoleShape::rectangle:
    return 2.0 * ((h.upper[0] - h.lower[0]) + (h.upper[1] - h.lower[1]));
  case fem::HoleShape::polygon:
  {
    double p = 0.0;
    for (std::size_t k = 0; k < h.vertices.size(); ++k)
    {
      const auto& a = h.vertices[k];
      const auto& b = h.vertices[(k + 1) % h.vertices.size()];
      p += std::hypot(b[0] - a[0], b[1] - a[1]);
    }
    return p;
  }
  case fem::HoleShape::none:
    break;
  }
  return 0.0;
}

/// Refuses a generated far field estimated beyond the memory limit before its mesh is made
/// (estimate_far_field_dofs). The error names the key that drives the larger part, the
/// rectangle or the ring graded from the hole, and the value at which the estimate fits.
void require_far_field_fits(const MapReader& f, const fem::FarFieldDescription& d)
{
  const double dofs = estimate_far_field_dofs(d);
  const ResourceLimits& limits = f.ctx().limits;
  if (dofs == 0.0 || limits.fits(MemoryModel::of_far_field(dofs)))
    return;
  const double h = far_field_element_size(d);
  const double h0 = d.hole.element_size;
  const double area = (d.upper[0] - d.lower[0]) * (d.upper[1] - d.lower[1]);
  const double ring_dofs = dofs - estimate_far_field_dofs(area, h, 0.0, 0.0, 1.0, d.degree);
  const double dofs_fit = std::max(MemoryModel::far_field_dofs_within(limits.memory), 0.0);
  const std::string need = "about " + format_number(std::round(dofs)) +
                           " far-field DOFs would need " +
                           limits.too_much(MemoryModel::of_far_field(dofs)) + ": expected ";
  if (2.0 * ring_dofs > dofs)
    throw f.section_reader("hole").error(
        "element_size", need + "an element size at the hole of at least " +
                            format_significant(h0 * dofs / std::max(dofs_fit, 1.0), 3) + " m");
  const double scale = std::sqrt(dofs / std::max(dofs_fit, 1.0)); // DOFs ~ 1 / h^2
  if (d.element_size > 0.0)
    throw f.error("element_size",
                  need + "an element size of at least " + format_significant(h * scale, 3) + " m");
  const double frequency =
      d.max_frequency > 0.0 ? d.max_frequency : d.incident.velocity.characteristic_frequency();
  throw f.error(d.max_frequency > 0.0 ? "max_frequency" : "incident",
                need + "a highest frequency of at most " +
                    format_significant(frequency / scale, 3) +
                    " Hz (or fewer points_per_wavelength)");
}
} // namespace

/// The `far_field` section (the plane mode, time step and integrator come from the scene).
namespace
{
/// A `within` record is the motion at depth, the ground surface's reflection included: taken as
/// the incident wave it is right only where nothing above the base reflects. Refused under a
/// free top.
void require_no_within_record_under_surface(const MapReader& inc, const fem::FarFieldDescription& d)
{
  const RecordInfo* record = d.incident.velocity.record_info();
  if (record == nullptr || record->motion != RecordMotion::within)
    return;
  for (const fem::BoundaryCondition& b : d.boundaries)
    if (b.part == fem::BoundaryPart::top && b.kind == fem::BoundaryKind::free)
      throw inc.error("velocity",
                      "a record taken `within` (at depth) already holds the ground surface's "
                      "reflection, and the far field's free top would add it again: expected "
                      "motion outcrop (the incident wave is half of it) or incident (a record "
                      "deconvolved to the upgoing wave, e.g. by a site-response code)");
}
} // namespace

fem::FarFieldDescription read_far_field(const MapReader& f, const dda::ModelDescription& model,
                                        const std::vector<std::string>& material_names)
{
  fem::FarFieldDescription d;
  const dda::Material& m =
      model.materials[find_name(f, "material", f.string("material"), material_names, "material")];
  d.density = m.density;
  d.youngs_modulus = m.youngs_modulus;
  d.poisson_ratio = m.poisson_ratio;
  if (f.has("mesh"))
    d.mesh_file = read_mesh_file(f);
  else
  {
    for (const char* corner : {"lower", "upper"})
      if (!f.has(corner))
        throw f.error(corner, "missing required key: expected [x, y] in m (or a `mesh` file)");
    const Vector2 lower = f.vector2("lower"), upper = f.vector2("upper");
    if (!(upper.x() > lower.x() && upper.y() > lower.y()))
      throw f.error("upper",
                    "expected upper > lower in both x and y, lower = " + format_point(lower));
    d.lower = {lower.x(), lower.y()};
    d.upper = {upper.x(), upper.y()};
  }
  schema::far_field_keys().fill(f, d); // element size, frequency, degree, solver, tolerance
  if (d.degree != 1 && d.degree != 2)
    throw f.error("degree", "expected 1 or 2");
  if (f.has("incident"))
  {
    const MapReader inc = f.section_reader("incident");
    d.incident.type = inc.choice_of<WaveType>("type");
    d.incident.velocity = read_time_function(inc, "velocity", TimeFunctionUse::velocity);
  }
  // A record's spectrum gives the highest frequency (MotionSummary::f99) when none is given.
  if (d.element_size == 0.0 && d.max_frequency == 0.0 && !f.has("mesh") &&
      d.incident.velocity.record_info() == nullptr)
    throw f.error("element_size", "expected element_size > 0, or max_frequency > 0 to choose it "
                                  "(or an incident record, whose spectrum chooses it)");
  if (f.has("hole"))
    d.hole = read_hole(f.section_reader("hole"), d);
  if (f.has("static_stage"))
    d.static_stage = read_static_stage(f.section_reader("static_stage"), d);
  if (f.has("rayleigh"))
    d.rayleigh = read_rayleigh(f.section_reader("rayleigh"));
  d.plane_mode = model.plane_mode;
  std::set<std::string> parts;
  for (const MapReader& r : f.section_list("boundaries"))
    d.boundaries.push_back(read_far_field_boundary(r, d, parts));
  if (f.has("incident"))
    require_no_within_record_under_surface(f.section_reader("incident"), d);
  require_far_field_fits(f, d);
  return d;
}

void complete_far_field(const MapReader& top, const std::vector<std::string>& joint_names,
                        Scene& scene)
{
  const dda::ModelDescription& model = scene.model;
  if (scene.far_field && !model.blocks.empty() && !model.stages.empty())
    check_coupled_stages(top, model);
  else if (scene.far_field && !model.stages.empty())
    throw top.error("stages", "stages apply to block models: expected no `stages` in a "
                              "far-field-only scene (its own static stage is "
                              "`far_field.static_stage`)");
  if (scene.far_field)
  {
    // Blocks tied to a far field keep their integrator (Bathe's by default: frictional sliding
    // right); the far field takes the trapezoidal rule for each of the blocks' steps (each half
    // of a composite step), or DDA's scheme with the blocks' (coupling/README.md).
    scene.far_field->dt = model.time.dt;
    scene.far_field->end_time = model.time.end_time;
    const MapReader f = top.section_reader("far_field");
    scene.far_field->integrator = f.has("integrator") ? f.choice_of<fem::Integrator>("integrator")
                                  : model.time.integrator == dda::Integrator::dda
                                      ? fem::Integrator::dda
                                      : fem::Integrator::newmark_trapezoidal;
  }
  if (scene.coupled())
  {
    scene.interface = read_interface(top.section_reader("interface"), model, joint_names);
    if (top.has("in_situ_stress") && top.section_reader("interface").has("joint_material"))
      throw top.section_reader("interface")
          .error("joint_material",
                 "a frictional interface cannot carry the in-situ stress's preloads "
                 "(Mohr-Coulomb would see only the dynamic increment of the tie forces): "
                 "expected no `interface.joint_material` (a linear interface) with "
                 "`in_situ_stress`");
    // The far field carries only the dynamic increment; gravity and the in-situ stress reach
    // the blocks as the ties' preloads (top-level `in_situ_stress`, coupling/README.md).
    if (scene.far_field->static_stage.enabled)
      throw top.section_reader("far_field")
          .error("static_stage",
                 "blocks tied to a far field: the far field carries only the dynamic increment "
                 "(no gravity, no in-situ stress, at rest when the dynamic stage starts), and "
                 "the in-situ stress reaches the blocks through the ties' preloads: expected a "
                 "top-level `in_situ_stress` section and `stages` instead");
  }
}

} // namespace ddafem::scene_reading

namespace ddafem
{
double far_field_element_size(const fem::FarFieldDescription& d)
{
  if (!d.mesh_file.file.empty())
    return 0.0;
  if (d.element_size > 0.0)
    return d.element_size;
  const double frequency =
      d.max_frequency > 0.0 ? d.max_frequency : d.incident.velocity.characteristic_frequency();
  // points_per_wavelength counts nodes; an FE_Q(p) element spans p node intervals.
  return s_wave_speed(d.youngs_modulus, d.poisson_ratio, d.density) /
         (frequency * d.points_per_wavelength) * d.degree;
}

double estimate_far_field_dofs(const fem::FarFieldDescription& d)
{
  const double h = far_field_element_size(d);
  if (!(h > 0.0))
    return 0.0;
  return estimate_far_field_dofs((d.upper[0] - d.lower[0]) * (d.upper[1] - d.lower[1]), h,
                                 scene_reading::hole_perimeter(d.hole), d.hole.element_size,
                                 d.hole.growth_ratio, d.degree);
}
} // namespace ddafem
