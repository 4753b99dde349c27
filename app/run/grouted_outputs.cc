// What a run reports of its grouted bolts (dda/grouted_bolt.h, docs/support.md): per crossing
// k (from the head) the history channels bolts/<name>/crossing<k>/{axial_force, shear_force,
// opening, slip, state}, summary.json's `grouted_bolts` (each bolt's law and per crossing its
// blocks, point, extremes, final state, yield and rupture times) and `check`'s lines.
#include "app/run/element_outputs.h"

#include "common/format.h"
#include "dda/grouted_bolt.h"

#include <cmath>
#include <string>

namespace ddafem
{
namespace
{
nlohmann::json crossing_summary(const dda::GroutedBolt& b, const dda::GroutedCrossing& c,
                                bool small_displacement)
{
  const auto [opening, slip] = b.opening_and_slip(c, small_displacement);
  return {{"blocks", {c.on_a.block, c.on_b.block}},
          {"point_m", point_json(c.on_a.initial)},
          {"distance_m", (c.on_a.initial - b.head.initial).norm()},
          {"max_axial_force_n", c.record.max_axial_force},
          {"max_shear_force_n", c.record.max_shear_force},
          {"max_opening_m", c.record.max_opening},
          {"max_slip_m", c.record.max_slip},
          {"final_axial_force_n", c.forces.axial_force},
          {"final_shear_force_n", c.forces.shear_force},
          {"final_opening_m", opening},
          {"final_slip_m", slip},
          {"plastic_opening_m", c.forces.plastic_opening},
          {"plastic_slip_m", c.forces.plastic_slip},
          {"final_state", name_of(c.forces.state)},
          {"yield_time_s", time_or_null(c.record.yield_time)},
          {"rupture_time_s", time_or_null(c.record.rupture_time)}};
}

/// The kind's outputs (app/run/element_outputs.h).
class GroutedBoltOutputs final : public ElementOutputs
{
public:
  void add_channels(std::vector<HistoryChannel>& channels,
                    const dda::ModelDescription& model) const override;
  void add_row(std::vector<double>& row, const dda::System& system) const override;
  void add_summary(nlohmann::json& summary, const dda::System& system) const override;
  void describe(const dda::System& system, std::ostream& out) const override;
};

void GroutedBoltOutputs::add_channels(std::vector<HistoryChannel>& channels,
                                      const dda::ModelDescription& model) const
{
  for (const dda::BoltDescription& b : model.bolts)
  {
    if (b.type != dda::BoltType::grouted)
      continue;
    for (std::size_t k = 0; k < b.crossings.size(); ++k)
    {
      const std::string at = "bolts/" + b.name + "/crossing" + std::to_string(k) + "/";
      const std::string where = " at the crossing from block " +
                                std::to_string(b.crossings[k].block_a) + " to block " +
                                std::to_string(b.crossings[k].block_b);
      channels.push_back({at + "axial_force", 1, "N", "tension positive" + where});
      channels.push_back({at + "shear_force", 1, "N",
                          "dowel force, positive when the slip is (t = (-e_y, e_x), e from "
                          "head to anchor)" +
                              where});
      channels.push_back({at + "opening", 1, "m", "relative displacement along the bolt" + where});
      channels.push_back({at + "slip", 1, "m", "relative displacement across the bolt" + where});
      channels.push_back(
          {at + "state", 1, "", "0 elastic, 1 yielding, 2 slack, 3 ruptured" + where});
    }
  }
}

void GroutedBoltOutputs::add_row(std::vector<double>& row, const dda::System& system) const
{
  const bool small = system.get_model().geometry == dda::GeometryMode::small_displacement;
  for (const dda::GroutedBolt& b : system.elements<dda::GroutedBolts>().all())
    for (const dda::GroutedCrossing& c : b.crossings)
    {
      const auto [opening, slip] = b.opening_and_slip(c, small);
      row.insert(row.end(), {c.forces.axial_force, c.forces.shear_force, opening, slip,
                             static_cast<double>(c.forces.state)});
    }
}

nlohmann::json grouted_bolts_summary(const dda::System& system)
{
  const bool small = system.get_model().geometry == dda::GeometryMode::small_displacement;
  nlohmann::json bolts = nlohmann::json::array();
  for (const dda::GroutedBolt& b : system.elements<dda::GroutedBolts>().all())
  {
    nlohmann::json crossings = nlohmann::json::array();
    for (const dda::GroutedCrossing& c : b.crossings)
      crossings.push_back(crossing_summary(b, c, small));
    bolts.push_back({{"name", b.name},
                     {"type", "grouted"},
                     {"head_m", point_json(b.head.initial)},
                     {"anchor_m", point_json(b.anchor.initial)},
                     {"final_head_m", point_json(b.head.position)},
                     {"final_anchor_m", point_json(b.anchor.position)},
                     {"axial_stiffness_n_per_m", b.law.axial_stiffness},
                     {"shear_stiffness_n_per_m", b.law.shear_stiffness},
                     {"debonded_length_m", b.law.debonded_length},
                     {"pretension_n", b.law.pretension},
                     {"yield_force_n", b.law.yield_force},
                     {"shear_capacity_n", b.law.shear_capacity},
                     {"crossings", crossings}});
  }
  return bolts;
}

void GroutedBoltOutputs::add_summary(nlohmann::json& summary, const dda::System& system) const
{
  if (!system.elements<dda::GroutedBolts>().all().empty())
    summary["grouted_bolts"] = grouted_bolts_summary(system);
}

void GroutedBoltOutputs::describe(const dda::System& system, std::ostream& out) const
{
  const std::vector<dda::GroutedBolt>& bolts = system.elements<dda::GroutedBolts>().all();
  if (!bolts.empty())
    out << "  grouted bolts: " << bolts.size() << "\n";
  for (const dda::GroutedBolt& b : bolts)
  {
    out << "  grouted bolt " << b.name << ": k_a " << format_significant(b.law.axial_stiffness, 5)
        << " N/m, k_s " << format_significant(b.law.shear_stiffness, 5) << " N/m, pretension "
        << format_significant(b.law.pretension, 5) << " N, yield force "
        << format_significant(b.law.yield_force, 5) << " N, shear capacity "
        << format_significant(b.law.shear_capacity, 5) << " N, crossings:";
    for (const dda::GroutedCrossing& c : b.crossings)
      out << " " << c.on_a.block << "->" << c.on_b.block << " at "
          << format_point(c.on_a.initial.x(), c.on_a.initial.y());
    out << "\n";
  }
}

} // namespace

std::unique_ptr<ElementOutputs> make_grouted_bolt_outputs()
{
  return std::make_unique<GroutedBoltOutputs>();
}

} // namespace ddafem
