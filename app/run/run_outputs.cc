#include "app/run/run_outputs.h"

#include "app/run/checkpoint_types.h"
#include "app/run/element_outputs.h"
#include "app/run/run_support.h"
#include "dda/bolt_snapshot.h"

#include "common/stopwatch.h"
#include "common/vtk_collection.h"

namespace ddafem
{
namespace
{

/// The blocks' values of a history row, in the order of history_channels.
std::vector<double> history_row(const dda::System& system,
                                const std::vector<std::unique_ptr<ElementOutputs>>& elements,
                                const LastStep& last)
{
  std::vector<double> row;
  for (std::size_t k = 0; k < system.get_model().monitors.size(); ++k)
  {
    const dda::MonitorSample s = system.sample_monitor(k);
    row.insert(row.end(), {s.displacement.x(), s.displacement.y(), s.velocity.x(), s.velocity.y(),
                           s.stress[0], s.stress[1], s.stress[2]});
  }
  for (const std::unique_ptr<ElementOutputs>& o : elements)
    o->add_row(row, system);
  const dda::EnergyBalance e = system.energy();
  row.insert(row.end(),
             {e.kinetic, e.strain, e.spring, e.work_of_loads, e.work_of_supports,
              e.work_of_boundaries, e.work_of_ties, e.work_of_damping, e.removed, e.dissipated});
  const dda::ContactCounts n = system.contacts().counts();
  row.insert(row.end(),
             {static_cast<double>(n.open), static_cast<double>(n.slide),
              static_cast<double>(n.lock), static_cast<double>(system.bonded_joints().list.size()),
              last.dt, static_cast<double>(last.n_open_close_iterations),
              static_cast<double>(last.n_cuts)});
  return row;
}

/// The blocks' channels, the tied far field's and the keyblocks'.
std::vector<HistoryChannel> all_channels(const dda::ModelDescription& model,
                                         const TiedFarField* tied,
                                         const KeyblockRecorder& keyblocks)
{
  std::vector<HistoryChannel> channels = history_channels(model);
  if (tied)
    tied->add_channels(channels);
  keyblocks.add_channels(channels);
  return channels;
}

} // namespace

std::vector<HistoryChannel> history_channels(const dda::ModelDescription& model)
{
  std::vector<HistoryChannel> channels;
  for (const dda::Monitor& m : model.monitors)
    run_support::add_monitor_channels(channels, m.name, "of the material point", "of its block");
  for (const std::unique_ptr<ElementOutputs>& o : make_element_outputs())
    o->add_channels(channels, model);
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
  channels.push_back({"energy/work_of_damping", 1, "J",
                      "the rock's dashpots (materials' and joint materials' `damping`) since t = "
                      "0 (negative: absorbed)"});
  channels.push_back(
      {"energy/removed", 1, "J", "kinetic energy of fallen blocks removed as debris since t = 0"});
  channels.push_back({"energy/dissipated", 1, "J",
                      "initial + work - stored: algorithmic damping of the integrator, friction "
                      "and contact impacts (the rock's dashpots: work_of_damping)"});
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

RunOutputs::RunOutputs(const std::filesystem::path& dir_, const std::string& scene_file,
                       const dda::System& system_, TiedFarField* tied_,
                       KeyblockRecorder& keyblocks_, fem::VtuCompression vtu_compression_)
    : dir(dir_), system(system_), tied(tied_), keyblocks(keyblocks_),
      vtu_compression(vtu_compression_),
      history((dir / "histories.h5").string(), all_channels(system.get_model(), tied, keyblocks)),
      blocks_vtu(dir.string(), "blocks"), contacts_vtu(dir.string(), "contacts"),
      ties_vtu(dir.string(), "ties"), bolts_vtu(dir.string(), "bolts"),
      element_outputs(make_element_outputs())
{
  history.set_attribute("scene", scene_file);
  history.set_attribute("version", DDAFEM_VERSION);
  for (const std::unique_ptr<ElementOutputs>& o : element_outputs)
    o->open_series(dir.string(), system);
}

void RunOutputs::write_state(bool snapshot, const LastStep& last)
{
  // A state already written (a run stopped right after a step it wrote) is not written again.
  const auto start = Clock::now();
  if (last_row_time != system.time())
  {
    std::vector<double> row = history_row(system, element_outputs, last);
    if (tied)
      tied->append_row(row);
    keyblocks.append_row(system, row);
    history.append(system.time(), row);
    last_row_time = system.time();
  }
  if (snapshot && last_snapshot_time != system.time())
  {
    write_snapshot();
    last_snapshot_time = system.time();
  }
  time_output += seconds_since(start);
}

void RunOutputs::write_snapshot()
{
  const auto name = [](const std::string& path)
  { return std::filesystem::path(path).filename().string(); };
  std::vector<std::string> files = {
      name(blocks_vtu.write(system.time(), system.blocks().snapshot())),
      name(contacts_vtu.write(system.time(), dda::contact_snapshot(system)))};
  if (tied)
  {
    const auto far_field_start = Clock::now();
    files.push_back(tied->write_snapshot(dir, vtu_compression));
    time_far_field += seconds_since(far_field_start);
    files.push_back(name(ties_vtu.write(system.time(), tied->tie_snapshot())));
  }
  for (const std::unique_ptr<ElementOutputs>& o : element_outputs)
    o->write_series(system);
  for (std::size_t part = 0; part < files.size(); ++part)
    model_data_sets.push_back({system.time(), static_cast<unsigned>(part), files[part]});
  // Part 4 whether or not a far field and ties come before (tools/paraview_open.py's PARTS).
  if (!system.get_model().bolts.empty())
    model_data_sets.push_back(
        {system.time(), 4u,
         name(bolts_vtu.write(system.time(),
                              dda::bolt_snapshot(system.elements<dda::Bolts>().all(),
                                                 system.elements<dda::GroutedBolts>().all())))});
  write_model_pvd();
}

void RunOutputs::write_model_pvd() const
{
  CollectionStyle style;
  style.time_precision = 17;
  write_collection(dir / "model.pvd", model_data_sets, style);
}

void RunOutputs::save(CheckpointOut& a) const
{
  save_history_rows(a, "outputs", history.n_rows());
  blocks_vtu.save(a);
  contacts_vtu.save(a);
  ties_vtu.save(a);
  for (const std::unique_ptr<ElementOutputs>& o : element_outputs)
    o->save_series(a);
  if (!system.get_model().bolts.empty())
    bolts_vtu.save(a);
  a << model_data_sets << time_output << time_far_field;
  transfer_optional(a, const_cast<std::optional<double>&>(last_row_time));
  transfer_optional(a, const_cast<std::optional<double>&>(last_snapshot_time));
}

RunOutputs::RunOutputs(const std::filesystem::path& dir_, const dda::System& system_,
                       TiedFarField* tied_, KeyblockRecorder& keyblocks_,
                       fem::VtuCompression vtu_compression_, CheckpointIn& a)
    : dir(dir_), system(system_), tied(tied_), keyblocks(keyblocks_),
      vtu_compression(vtu_compression_),
      history((dir / "histories.h5").string(), all_channels(system.get_model(), tied, keyblocks),
              HistoryWriter::Reopen{load_history_rows(a, "outputs")}),
      blocks_vtu(dir.string(), "blocks"), contacts_vtu(dir.string(), "contacts"),
      ties_vtu(dir.string(), "ties"), bolts_vtu(dir.string(), "bolts"),
      element_outputs(make_element_outputs())
{
  blocks_vtu.load(a);
  contacts_vtu.load(a);
  ties_vtu.load(a);
  for (const std::unique_ptr<ElementOutputs>& o : element_outputs)
  {
    o->open_series(dir.string(), system); // the same scene resumes: the same series
    o->load_series(a);
  }
  if (!system.get_model().bolts.empty())
    bolts_vtu.load(a);
  a >> model_data_sets >> time_output >> time_far_field;
  transfer_optional(a, last_row_time);
  transfer_optional(a, last_snapshot_time);
  write_model_pvd();
}

} // namespace ddafem
