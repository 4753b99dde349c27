#include "app/run_outputs.h"

#include "app/run_support.h"

#include "common/stopwatch.h"
#include "common/vtk_collection.h"

namespace ddafem
{
namespace
{

/// The blocks' values of a history row, in the order of history_channels.
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

/// The far field's monitors and energies and the ties' counts (after the blocks' values).
void append_coupled_row(std::vector<double>& row, const fem::ElasticWaveModel& far_field,
                        const coupling::FarFieldTies& ties, std::size_t n_monitors)
{
  append_far_field_monitors(row, far_field, n_monitors);
  const fem::EnergyBalance e = far_field.energy();
  row.insert(row.end(), {e.kinetic, e.strain, e.work_of_input, e.work_of_dashpots,
                         e.work_of_rayleigh, e.work_of_springs, e.dissipated, ties.tie_energy()});
  const coupling::TieCounts n = ties.counts();
  row.insert(row.end(), {static_cast<double>(n.intact), static_cast<double>(n.lock),
                         static_cast<double>(n.slide), static_cast<double>(n.open)});
}

/// The far field's channels in a run of it alone: its monitors and energies.
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

/// The blocks' channels, the coupled parts' and the keyblocks'.
std::vector<HistoryChannel> all_channels(const dda::ModelDescription& model,
                                         const CoupledParts& coupled,
                                         const KeyblockRecorder& keyblocks)
{
  std::vector<HistoryChannel> channels = history_channels(model);
  if (coupled.ties)
    add_coupled_channels(channels, *coupled.description);
  keyblocks.add_channels(channels);
  return channels;
}
} // namespace

void append_far_field_monitors(std::vector<double>& row, const fem::ElasticWaveModel& far_field,
                               std::size_t n_monitors)
{
  for (std::size_t k = 0; k < n_monitors; ++k)
  {
    const fem::MonitorSample s = far_field.sample_monitor(k);
    row.insert(row.end(), {s.displacement[0], s.displacement[1], s.velocity[0], s.velocity[1],
                           s.stress[0], s.stress[1], s.stress[2]});
  }
}

nlohmann::json far_field_timings(const fem::Timings& t)
{
  return {{"setup", t.setup}, {"assemble", t.assemble}, {"solve", t.solve}, {"update", t.update}};
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

RunOutputs::RunOutputs(const std::filesystem::path& dir_, const std::string& scene_file,
                       const dda::System& system_, CoupledParts coupled_,
                       KeyblockRecorder& keyblocks_, fem::VtuCompression vtu_compression_)
    : dir(dir_), system(system_), coupled(coupled_), keyblocks(keyblocks_),
      vtu_compression(vtu_compression_),
      history((dir / "histories.h5").string(),
              all_channels(system.get_model(), coupled, keyblocks)),
      blocks_vtu(dir.string(), "blocks"), contacts_vtu(dir.string(), "contacts"),
      ties_vtu(dir.string(), "ties")
{
  history.set_attribute("scene", scene_file);
  history.set_attribute("version", DDAFEM_VERSION);
}

void RunOutputs::write_state(bool snapshot, const LastStep& last)
{
  const auto start = Clock::now();
  std::vector<double> row = history_row(system, last);
  if (coupled.ties)
    append_coupled_row(row, *coupled.far_field, *coupled.ties,
                       coupled.description->monitors.size());
  keyblocks.append_row(system, row);
  history.append(system.time(), row);
  if (snapshot)
    write_snapshot();
  time_output += seconds_since(start);
}

void RunOutputs::write_snapshot()
{
  const auto name = [](const std::string& path)
  { return std::filesystem::path(path).filename().string(); };
  std::vector<std::string> files = {
      name(blocks_vtu.write(system.time(), system.snapshot())),
      name(contacts_vtu.write(system.time(), system.contact_snapshot()))};
  if (coupled.ties)
  {
    const auto far_field_start = Clock::now();
    files.push_back(coupled.far_field->write_snapshot(dir.string(), "far_field", vtu_compression));
    time_far_field += seconds_since(far_field_start);
    files.push_back(name(ties_vtu.write(system.time(), tie_snapshot(*coupled.ties, system))));
  }
  for (std::size_t part = 0; part < files.size(); ++part)
    model_data_sets.push_back({system.time(), static_cast<unsigned>(part), files[part]});
  CollectionStyle style;
  style.time_precision = 17;
  write_collection(dir / "model.pvd", model_data_sets, style);
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

void FarFieldOutputs::write_state(bool snapshot)
{
  const auto start = Clock::now();
  std::vector<double> row;
  append_far_field_monitors(row, model, n_monitors);
  const fem::EnergyBalance e = model.energy();
  row.insert(row.end(), {e.kinetic, e.strain, e.work_of_input, e.work_of_dashpots,
                         e.work_of_rayleigh, e.dissipated});
  history.append(model.time(), row);
  if (snapshot)
  {
    model.write_snapshot(dir.string(), "far_field", vtu_compression);
    ++n_written;
  }
  time_output += seconds_since(start);
}

} // namespace ddafem
