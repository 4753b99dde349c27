// The model's sections: analysis, materials and joints, time functions, boundaries, time,
// contacts, stages, solver and output.
#include "app/scene/scene_readers.h"
#include "app/schema/bound_sections.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <filesystem>
#include <fstream>

namespace ddafem::scene_reading
{
namespace
{
/// A table from a CSV file; every problem names the file, row and the scene key.
TimeFunction read_csv_table(const MapReader& r)
{
  const std::string file = r.string("file");
  schema::TableColumns columns;
  schema::csv_keys().fill(r, columns);
  const long long time_column = columns.time_column, value_column = columns.value_column;
  const long long skip_rows = columns.skip_rows;
  const std::filesystem::path csv_path = scene_file(r, "file", "CSV file");
  const std::string shown = csv_path.lexically_normal().string();
  std::ifstream in(csv_path);
  if (!in)
    throw r.error("file", "cannot open CSV file '" + shown + "'");

  std::vector<double> times, values;
  std::string line;
  long long row = 0;
  const std::size_t n_needed = static_cast<std::size_t>(std::max(time_column, value_column)) + 1;
  while (std::getline(in, line))
  {
    ++row;
    if (row <= skip_rows || trim(line).empty())
      continue;
    const std::vector<std::string> cells = split(line, ',');
    const std::string at_row = "CSV file '" + shown + "' row " + std::to_string(row) + ": ";
    if (cells.size() < n_needed)
      throw r.error("file", at_row + "found " + std::to_string(cells.size()) +
                                " column(s), expected at least " + std::to_string(n_needed));
    const auto cell = [&](long long column)
    {
      const std::string text = trim(cells[static_cast<std::size_t>(column)]);
      const std::optional<double> x = parse_double(text);
      if (!x)
        throw r.error("file", at_row + "column " + std::to_string(column) + " is '" + text +
                                  "', expected a number");
      return *x;
    };
    const double t = cell(time_column);
    const double v = cell(value_column);
    if (!times.empty() && t <= times.back())
      throw r.error("file", at_row + "time " + format_number(t) +
                                " does not increase strictly (previous " +
                                format_number(times.back()) + ")");
    times.push_back(t);
    values.push_back(v);
  }
  if (times.empty())
    throw r.error("file", "CSV file '" + shown + "' has no data rows (after skipping " +
                              std::to_string(skip_rows) + ")");
  return TimeFunction::table(std::move(times), std::move(values));
}

/// The `edges` of a `boundaries[i]` item: block and edge indices in range, each edge once.
void read_boundary_edges(const MapReader& r, const dda::ModelDescription& model,
                         dda::BoundaryDescription& b)
{
  const std::vector<std::array<long long, 2>> edges = r.integer_pair_list("edges");
  const std::size_t n_blocks = model.blocks.size();
  for (std::size_t i = 0; i < edges.size(); ++i)
  {
    const auto block = static_cast<std::size_t>(edges[i][0]);
    const auto edge = static_cast<std::size_t>(edges[i][1]);
    if (block >= n_blocks)
      throw r.item_error("edges", i,
                         "block index " + std::to_string(block) +
                             " is out of range: expected 0 to " + std::to_string(n_blocks - 1) +
                             " (the " + std::to_string(n_blocks) +
                             " blocks of the scene, grid cells counted one by one)");
    const std::size_t n_edges = model.blocks[block].vertices.size();
    if (edge >= n_edges)
      throw r.item_error("edges", i,
                         "edge index " + std::to_string(edge) + " is out of range: block " +
                             std::to_string(block) + " (" + model.blocks[block].origin + ") has " +
                             std::to_string(n_edges) + " edges, expected 0 to " +
                             std::to_string(n_edges - 1));
    const std::pair<std::size_t, std::size_t> e(block, edge);
    const auto previous = std::find(b.edges.begin(), b.edges.end(), e);
    if (previous != b.edges.end())
      throw r.item_error("edges", i,
                         "duplicate edge (also edges[" +
                             std::to_string(previous - b.edges.begin()) +
                             "]): expected each edge once");
    b.edges.push_back(e);
  }
}

/// A boundary selects its edges by exactly one of `edges`, `on_line` and `outer`.
void check_boundary_selector(const MapReader& r, bool outer)
{
  std::vector<std::string> selectors;
  if (r.has("edges"))
    selectors.push_back("'edges'");
  if (r.has("on_line"))
    selectors.push_back("'on_line'");
  if (outer)
    selectors.push_back("'outer: true'");
  if (selectors.size() != 1)
    throw r.ctx().locator.error(
        r.yaml(), r.key_path(), "",
        (selectors.empty() ? std::string("no edges selected")
                           : "more than one selector (" + join(selectors, ", ") + ")") +
            ": expected exactly one of 'edges: [[block, edge], ...]', 'on_line: {point: [x, y], "
            "direction: [dx, dy]}' or 'outer: true'. Allowed keys here: " +
            join(r.ctx().schema.section("boundaries[i]").key_names(), ", "));
}

/// A `stages[i]` item with `mode: settle`: its SettleCriterion (no `dt`, no `end_time`: it runs
/// with time.dt from where the previous stage ended, to rest or its max_duration).
dda::SettleCriterion read_settle_criterion(const MapReader& r)
{
  for (const char* key : {"dt", "end_time", "max_steps", "tolerance", "release"})
    if (r.has(key))
      throw r.error(key, std::string("a settle stage runs with time.dt until its blocks are at "
                                     "rest or max_duration: expected no `") +
                             key + "` here");
  dda::SettleCriterion c;
  schema::settle_keys().fill(r, c);
  if (c.remove_fallen && c.fall_distance <= 0.0)
    throw r.error("remove_fallen",
                  "fallen blocks are removed once they have fallen: expected fall_distance > 0 "
                  "with remove_fallen true");
  return c;
}

/// The time at which the last dynamic stage before the new one ended [s] (0 for none).
double previous_dynamic_end(const dda::ModelDescription& model)
{
  for (auto it = model.stages.rbegin(); it != model.stages.rend(); ++it)
    if (it->mode == dda::StageMode::dynamic)
      return it->end_time;
  return 0.0;
}

/// One `stages[i]` item, after the stages before it (time.dt and time.end_time by default).
dda::Stage read_stage(const MapReader& r, const dda::ModelDescription& model)
{
  if (!model.stages.empty() && model.stages.back().settle)
    throw r.error("mode", "a stage after the settle stage " + model.stages.back().name +
                              ", whose end is not known before the run: expected the settle "
                              "stage last");
  dda::Stage stage;
  stage.name = r.string("name");
  const std::string mode = r.choice("mode");
  stage.mode = value_of<dda::StageMode>(mode).value_or(dda::StageMode::dynamic);
  if (mode == dda::settle_mode_name)
    stage.settle = read_settle_criterion(r);
  stage.dt = r.has("dt") ? r.number("dt") : model.time.dt;
  stage.end_time = r.has("end_time") ? r.number("end_time") : model.time.end_time;
  schema::stage_keys().fill(r, stage); // max_steps, tolerance, release
  if (stage.mode == dda::StageMode::dynamic && !stage.settle)
  {
    if (r.has("dt"))
      throw r.error("dt", "a dynamic stage steps with time.dt: expected no `dt` here");
    const double start = previous_dynamic_end(model);
    if (stage.end_time <= start)
      throw r.error("end_time", "expected a time after the previous dynamic stage's end (" +
                                    format_number(start) + " s)");
  }
  return stage;
}
} // namespace

TimeFunction read_time_function(const MapReader& parent, const std::string& name,
                                TimeFunctionUse use)
{
  const MapReader r = parent.time_function_reader(name);
  switch (r.choice_of<schema::TimeFunctionType>("type"))
  {
  case schema::TimeFunctionType::record:
    if (use == TimeFunctionUse::factor)
      throw r.error("type", "a record is a ground motion: expected it where a velocity or a "
                            "displacement is given, not as a load's factor");
    return read_record(r, use);
  case schema::TimeFunctionType::constant:
    return TimeFunction::constant(r.number("value"));
  case schema::TimeFunctionType::sine_pulse:
  {
    schema::SinePulseParameters p;
    schema::sine_pulse_keys().fill(r, p);
    return TimeFunction::sine_pulse(p.amplitude, p.frequency, p.cycles, p.start);
  }
  case schema::TimeFunctionType::table:
  {
    std::vector<double> times, values;
    for (const auto& [t, v] : r.pair_list("points"))
    {
      if (!times.empty() && t <= times.back())
        throw r.error("points", "expected strictly increasing times; found " + format_number(t) +
                                    " after " + format_number(times.back()));
      times.push_back(t);
      values.push_back(v);
    }
    return TimeFunction::table(std::move(times), std::move(values));
  }
  case schema::TimeFunctionType::csv:
    break;
  }
  return read_csv_table(r);
}

void read_analysis(const MapReader& top, dda::ModelDescription& model)
{
  const MapReader analysis = top.section_reader("analysis");
  schema::analysis_keys().fill(analysis, model);
}

/// The `damping` of a material or joint material, if any: its ratio and its frequency (0 when
/// not given: the scene input's, set by complete_damping).
dda::RockDamping read_damping(const MapReader& parent)
{
  dda::RockDamping d;
  if (!parent.has("damping"))
    return d;
  const MapReader r = parent.section_reader("damping");
  if (!r.has("ratio"))
    throw r.error("ratio", "missing required key: the fraction of critical damping, e.g. 0.02");
  d.ratio = r.number("ratio");
  if (r.has("frequency"))
    d.frequency = r.number("frequency");
  return d;
}

/// The dominant frequency of the scene's input [Hz]: the first boundary's input wave, else the
/// far field's incident wave that has one; 0 if none is known.
double input_frequency(const Scene& scene)
{
  for (const dda::BoundaryDescription& b : scene.model.boundaries)
    if (b.has_input && b.input.velocity.dominant_frequency() > 0.0)
      return b.input.velocity.dominant_frequency();
  if (scene.far_field)
    return scene.far_field->incident.velocity.dominant_frequency();
  return 0.0;
}

void complete_damping(const MapReader& top, Scene& scene)
{
  const double frequency = input_frequency(scene);
  const auto complete = [&](const MapReader& r, dda::RockDamping& d)
  {
    if (!d.active() || d.frequency > 0.0)
      return;
    if (!(frequency > 0.0))
      throw r.section_reader("damping").error(
          "frequency", "missing key: the frequency [Hz] where the damping ratio holds (the scene "
                       "has no input motion whose dominant frequency could set it)");
    d.frequency = frequency;
  };
  std::size_t i = 0;
  for (const auto& named : top.section_map("materials"))
    complete(named.second, scene.model.materials[i++].damping);
  i = 0;
  for (const auto& named : top.section_map("joint_materials"))
    complete(named.second, scene.model.joint_materials[i++].damping);
  const auto damped = [](const auto& m) { return m.damping.active(); };
  const dda::ModelDescription& model = scene.model;
  if (std::any_of(model.boundaries.begin(), model.boundaries.end(),
                  [](const dda::BoundaryDescription& b)
                  { return b.type == dda::BoundaryType::vb1; }) &&
      (std::any_of(model.materials.begin(), model.materials.end(), damped) ||
       std::any_of(model.joint_materials.begin(), model.joint_materials.end(), damped)))
    scene.warnings.push_back(
        "vb1 boundaries with the rock's damping: VB I's coefficients (Bao et al. 2012, eq. 39) "
        "are derived for undamped boundary blocks; with dashpots on them a model may keep a "
        "period-2 oscillation at the boundary and not settle (docs/damping.md): the dashpot "
        "boundary, or the far field, is the tested choice");
  if (!scene.far_field)
    return;
  // The far field carries its material's damping as Rayleigh's beta (same ratio, same
  // frequency); an explicit `far_field.rayleigh` wins.
  const MapReader f = top.section_reader("far_field");
  const std::string material = f.string("material");
  for (const dda::Material& m : scene.model.materials)
    if (m.name == material && m.damping.active())
    {
      if (f.has("rayleigh"))
        scene.warnings.push_back(
            "far_field.rayleigh is given: it damps the far field instead of its material `" +
            material + "`'s damping (ratio " + format_significant(m.damping.ratio) + " at " +
            format_significant(m.damping.frequency) + " Hz)");
      else
        scene.far_field->rayleigh = {0.0, m.damping.stiffness_factor()};
    }
}

SceneNames read_materials(const MapReader& top, dda::ModelDescription& model)
{
  SceneNames names;
  std::vector<std::string>& material_names = names.materials;
  for (const auto& [name, r] : top.section_map("materials"))
  {
    dda::Material m;
    m.name = name;
    schema::material_keys().fill(r, m);
    m.damping = read_damping(r);
    model.materials.push_back(m);
    material_names.push_back(name);
  }
  if (model.materials.empty())
    throw top.error("materials", "expected at least one material");

  std::vector<std::string>& joint_names = names.joint_materials;
  for (const auto& [name, r] : top.section_map("joint_materials"))
  {
    dda::JointMaterial j;
    j.name = name;
    schema::joint_material_keys().fill(r, j);
    j.damping = read_damping(r);
    model.joint_materials.push_back(j);
    joint_names.push_back(name);
  }

  const MapReader joints = top.section_reader("joints");
  if (joints.has("default"))
    model.default_joint_material =
        find_name(joints, "default", joints.string("default"), joint_names, "joint material");
  for (const MapReader& r : joints.section_list("pairs"))
  {
    const std::array<std::string, 2> pair = r.name_pair("materials");
    dda::JointAssignment a;
    a.material_a = find_name(r, "materials", pair[0], material_names, "material");
    a.material_b = find_name(r, "materials", pair[1], material_names, "material");
    a.joint_material = find_name(r, "joint", r.string("joint"), joint_names, "joint material");
    model.joint_assignments.push_back(a);
  }

  return names;
}

/// One `boundaries[i]` item. Only what the text can tell is checked here (types, ranges, one
/// selector, block and edge indices); which edges a line or `outer` selects, and whether an edge
/// is outer at all, is for the engine, which sees the geometry.
dda::BoundaryDescription read_boundary(const MapReader& r, const dda::ModelDescription& model)
{
  dda::BoundaryDescription b;
  b.origin = r.key_path();
  schema::boundary_keys().fill(r, b);
  if (r.has("input"))
  {
    if (b.type == dda::BoundaryType::free)
      throw r.error("input", "an incident wave enters through the dashpots of a viscous "
                             "boundary: expected `type: vb1`, `vb2` or `dashpot`");
    const MapReader in = r.section_reader("input");
    b.has_input = true;
    b.input.type = in.choice_of<WaveType>("type");
    b.input.velocity = read_time_function(in, "velocity", TimeFunctionUse::velocity);
  }
  check_boundary_selector(r, b.outer);
  if (r.has("edges"))
    read_boundary_edges(r, model, b);
  if (r.has("on_line"))
  {
    const MapReader line = r.section_reader("on_line");
    b.on_line = true;
    b.line_point = line.vector2("point");
    const Vector2 direction = line.vector2("direction");
    const double scale = direction.cwiseAbs().maxCoeff();
    if (scale == 0.0)
      throw line.error("direction", "expected a non-zero direction [dx, dy]");
    b.line_direction = (direction / scale).normalized(); // a unit vector
  }
  return b;
}

void read_time(const MapReader& top, dda::TimeSettings& time_settings)
{
  if (!top.has("time"))
    throw top.error("time", "expected a `time` section (dt, end_time) or a `tunnel`");
  const MapReader time = top.section_reader("time");
  schema::time_keys().fill(time, time_settings);
  if (time_settings.end_time < time_settings.dt)
    throw time.error("end_time",
                     "expected end_time >= dt = " + format_number(time_settings.dt) + " s");
  if (time.has("dt_min") && time_settings.dt_min > time_settings.dt)
    throw time.error("dt_min", "expected dt_min <= dt = " + format_number(time_settings.dt) + " s");
}

void read_contacts(const MapReader& top, dda::ContactSettings& contact_settings)
{
  schema::contacts_keys().fill(top.section_reader("contacts"), contact_settings);
}

void read_stages(const MapReader& top, dda::ModelDescription& model)
{
  for (const MapReader& r : top.section_list("stages"))
    model.stages.push_back(read_stage(r, model));
}

dda::SolverSettings read_solver(const MapReader& top)
{
  dda::SolverSettings s;
  schema::solver_keys().fill(top.section_reader("solver"), s);
  return s;
}

OutputSettings read_output(const MapReader& top)
{
  OutputSettings settings;
  const MapReader output = top.section_reader("output");
  schema::output_keys().fill(output, settings);
  if (trim(settings.directory).empty())
    throw output.error("directory", "expected a non-empty directory name");
  return settings;
}

} // namespace ddafem::scene_reading
