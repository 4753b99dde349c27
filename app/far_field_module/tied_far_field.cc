// A far field tied to the blocks (module side of app/far_field_module/far_field_module.h):
// fem::ElasticWaveModel and coupling::FarFieldTies behind TiedFarField, with the far field's and
// the interface's history channels, snapshots, summary and `check` lines.
#include "app/far_field_module/far_field_parts.h"
#include "app/run/run_support.h"

#include "common/checkpoint_archive.h"
#include "common/format.h"
#include "coupling/far_field_ties.h"
#include "coupling/interface_impedance.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace ddafem
{
namespace
{
/// Why the interface reflects and how to avoid it.
std::string impedance_message(const coupling::InterfaceImpedance& z)
{
  return "the far field (E = " + format_significant(z.far_field_modulus) +
         " Pa) and the tied blocks with their joints (E_eff = " +
         format_significant(z.blocks_modulus) +
         " Pa) differ in impedance: the interface reflects about " +
         format_significant(100 * z.reflection, 2) +
         "% of a normally incident wave; a far-field material of the rock mass (E_eff) avoids it";
}

class TiedFarFieldModel : public TiedFarFieldOf<fem::ElasticWaveModel>
{
public:
  TiedFarFieldModel(const Scene& scene_, dda::System& system_)
      : TiedFarFieldOf(scene_, system_, *scene_.far_field)
  {
  }

  std::string write_snapshot(const std::filesystem::path& dir,
                             fem::VtuCompression compression) override
  {
    return far_field.write_snapshot(dir.string(), "far_field", compression);
  }
  void add_to_summary(nlohmann::json& summary) const override;
  void describe(std::ostream& out) const override
  {
    describe_far_field(out);
    describe_interface(out);
  }
  void save(CheckpointOut& archive) const override
  {
    far_field.save(archive);
    ties.save(archive);
    arrival.save(archive);
  }
  void load(CheckpointIn& archive) override
  {
    far_field.load(archive);
    ties.load(archive);
    arrival.load(archive);
  }

private:
  std::optional<coupling::InterfaceImpedance> impedance() const
  {
    return coupling::interface_impedance(scene.model, system, ties,
                                         scene.far_field->youngs_modulus);
  }
  void describe_far_field(std::ostream& out) const;
  void describe_interface(std::ostream& out) const;
};

} // namespace

std::string tied_impedance_warning(const Scene& scene, const dda::System& system,
                                   const coupling::FarFieldTies& ties)
{
  const auto z =
      coupling::interface_impedance(scene.model, system, ties, scene.far_field->youngs_modulus);
  return z && z->reflection > 0.01 ? impedance_message(*z) : std::string();
}

void add_tied_channels(std::vector<HistoryChannel>& channels,
                       const fem::FarFieldDescription& description)
{
  for (const fem::Monitor& m : description.monitors)
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

void append_tied_energies(std::vector<double>& row, const fem::EnergyBalance& e,
                          const coupling::FarFieldTies& ties)
{
  row.insert(row.end(), {e.kinetic, e.strain, e.work_of_input, e.work_of_dashpots,
                         e.work_of_rayleigh, e.work_of_springs, e.dissipated, ties.tie_energy()});
  const coupling::TieCounts n = ties.counts();
  row.insert(row.end(), {static_cast<double>(n.intact), static_cast<double>(n.lock),
                         static_cast<double>(n.slide), static_cast<double>(n.open)});
}

std::vector<dda::ContactSnapshot> tie_contacts(const coupling::FarFieldTies& ties,
                                               const dda::System& system)
{
  std::vector<dda::ContactSnapshot> out;
  const std::vector<dda::MaterialPoint>& points = system.ties().points;
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

nlohmann::json far_field_energy_summary(const fem::EnergyBalance& fe)
{
  return {{"kinetic", fe.kinetic},
          {"strain", fe.strain},
          {"work_of_input", fe.work_of_input},
          {"work_of_dashpots", fe.work_of_dashpots},
          {"work_of_rayleigh", fe.work_of_rayleigh},
          {"work_of_ties", fe.work_of_springs},
          {"dissipated", fe.dissipated}};
}

nlohmann::json interface_summary(const coupling::FarFieldTies& ties, const fem::EnergyBalance& fe)
{
  const coupling::TieCounts n = ties.counts();
  return {
      {"ties", {{"intact", n.intact}, {"lock", n.lock}, {"slide", n.slide}, {"open", n.open}}},
      {"work_into_blocks_J", ties.work_on_blocks()},
      {"work_into_far_field_J", fe.work_of_springs},
      {"tie_energy_J", ties.tie_energy()},
      {"condensations", ties.n_condensations()},
      {"timings_s", {{"condensation", ties.condensation_seconds()}, {"ties", ties.tie_seconds()}}}};
}

namespace
{
void TiedFarFieldModel::add_to_summary(nlohmann::json& summary) const
{
  const fem::Timings& ft = far_field.timings();
  const fem::EnergyBalance fe = far_field.energy();
  add_model_summary(summary);
  summary["far_field"] = {{"solver", far_field.solver_name()},
                          {"factorizations", ft.n_factorizations},
                          {"timings_s", far_field_timings(ft)},
                          {"energy_J", far_field_energy_summary(fe)}};
  add_arrival_summary(summary);
  summary["interface"] = interface_summary(ties, fe);
}

/// The far field (mesh, solver, material, resolution).
void TiedFarFieldModel::describe_far_field(std::ostream& out) const
{
  const fem::FarFieldDescription& d = *scene.far_field;
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

/// The interface: ties, their springs and strength, the impedance contrast, the far field's
/// boundaries and monitors.
void TiedFarFieldModel::describe_interface(std::ostream& out) const
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
  if (const auto z = impedance())
  {
    out << "  rock mass at the interface: E_eff " << format_significant(z->blocks_modulus)
        << " Pa (blocks with their joints), far field E "
        << format_significant(z->far_field_modulus)
        << " Pa: reflection of a normally incident wave about "
        << format_significant(100 * z->reflection, 2) << "%\n";
    if (z->reflection > 0.01)
      out << "warning: " << impedance_message(*z) << "\n";
  }
  for (const fem::BoundaryCondition& b : scene.far_field->boundaries)
    out << "  far field " << fem::name_of(b.part) << ": " << fem::name_of(b.kind) << "\n";
  const fem::IncidentWave& incident = scene.far_field->incident;
  out << "  far field incident: " << name_of(incident.type) << ", v_in "
      << incident.velocity.describe() << "\n";
  out << "  far-field monitors: " << scene.far_field->monitors.size() << "\n";
}
} // namespace

std::unique_ptr<TiedFarField> make_tied_far_field(const Scene& scene, dda::System& system)
{
  return std::make_unique<TiedFarFieldModel>(scene, system);
}

BaseArrival::BaseArrival(const Scene& scene_, const dda::System& system) : scene(scene_)
{
  for (const dda::Block& b : system.blocks().list)
    for (const dda::Point& p : b.initial_vertices)
      base = std::min(base, p.y());
  const auto& sides = scene.far_field->boundaries;
  has_column = std::any_of(sides.begin(), sides.end(),
                           [](const fem::BoundaryCondition& b)
                           { return b.kind == fem::BoundaryKind::free_field; });
}

void BaseArrival::add_channel(std::vector<HistoryChannel>& channels) const
{
  if (has_column)
    channels.push_back({"free_field/base_velocity", 2, "m/s",
                        "(vx, vy) of the free-field column at the height of the blocks' lowest "
                        "point (the near field's base): the wave that arrives there"});
}

void BaseArrival::append(std::vector<double>& row, const std::array<double, 2>& v, double t)
{
  row.insert(row.end(), v.begin(), v.end());
  peak_at_base = std::max(peak_at_base, std::hypot(v[0], v[1]));
  peak_input = std::max(peak_input, std::abs(scene.far_field->incident.velocity.value(t)));
}

nlohmann::json BaseArrival::summary(const double p_wave_speed, const double s_wave_speed) const
{
  const bool p = scene.far_field->incident.type == WaveType::p;
  return {
      {"height_m", base},
      {"travel_m", base - scene.far_field->lower[1]},
      {"wave_speed_m_s", p ? p_wave_speed : s_wave_speed},
      {"pgv_m_s", peak_at_base},
      {"input_pgv_m_s", peak_input},
      {"ratio", peak_input > 0.0 ? nlohmann::json(peak_at_base / peak_input) : nlohmann::json()}};
}

void BaseArrival::save(CheckpointOut& archive) const
{
  double peaks[2] = {peak_at_base, peak_input};
  transfer_all(archive, peaks);
}

void BaseArrival::load(CheckpointIn& archive)
{
  double peaks[2] = {0.0, 0.0};
  transfer_all(archive, peaks);
  peak_at_base = peaks[0];
  peak_input = peaks[1];
}

} // namespace ddafem
