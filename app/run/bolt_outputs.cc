// What a run reports of its end-anchored bolts (dda/bolt.h, docs/support.md): per bolt its
// history channels bolts/<name>/{axial_force, elongation, state}, summary.json's `bolts` and
// `check`'s lines.
#include "app/run/element_outputs.h"

#include "common/format.h"
#include "dda/bolt.h"

#include <cmath>
#include <string>

namespace ddafem
{
namespace
{
class BoltOutputs final : public ElementOutputs
{
public:
  void add_channels(std::vector<HistoryChannel>& channels,
                    const dda::ModelDescription& model) const override
  {
    for (const dda::BoltDescription& b : model.bolts)
    {
      if (b.type == dda::BoltType::grouted)
        continue; // grouted_outputs.cc
      channels.push_back({"bolts/" + b.name + "/axial_force", 1, "N", "tension positive"});
      channels.push_back({"bolts/" + b.name + "/elongation", 1, "m", "L - L0"});
      channels.push_back(
          {"bolts/" + b.name + "/state", 1, "", "0 elastic, 1 yielding, 2 slack, 3 ruptured"});
    }
  }

  void add_row(std::vector<double>& row, const dda::System& system) const override
  {
    for (const dda::Bolt& b : system.elements<dda::Bolts>().all())
      row.insert(row.end(), {b.forces.axial_force, b.length() - b.law.free_length,
                             static_cast<double>(b.forces.state)});
  }

  /// Each bolt: where it is, its law, its extremes and final state, when it yielded and broke.
  void add_summary(nlohmann::json& summary, const dda::System& system) const override
  {
    const std::vector<dda::Bolt>& all = system.elements<dda::Bolts>().all();
    if (all.empty())
      return;
    nlohmann::json bolts = nlohmann::json::array();
    for (const dda::Bolt& b : all)
      bolts.push_back({{"name", b.name},
                       {"head_m", point_json(b.head.initial)},
                       {"anchor_m", point_json(b.anchor.initial)},
                       {"free_length_m", b.law.free_length},
                       {"stiffness_n_per_m", b.law.stiffness},
                       {"pretension_n", b.law.pretension},
                       {"yield_force_n", b.law.yield_force},
                       {"max_force_n", b.record.max_force},
                       {"max_elongation_m", b.record.max_elongation},
                       {"final_head_m", point_json(b.head.position)},
                       {"final_anchor_m", point_json(b.anchor.position)},
                       {"final_force_n", b.forces.axial_force},
                       {"final_elongation_m", b.length() - b.law.free_length},
                       {"plastic_elongation_m", b.forces.plastic_elongation},
                       {"final_state", name_of(b.forces.state)},
                       {"yield_time_s", time_or_null(b.record.yield_time)},
                       {"rupture_time_s", time_or_null(b.record.rupture_time)}});
    summary["bolts"] = bolts;
  }

  void describe(const dda::System& system, std::ostream& out) const override
  {
    const std::vector<dda::Bolt>& all = system.elements<dda::Bolts>().all();
    if (!all.empty())
      out << "  bolts: " << all.size() << "\n";
    for (const dda::Bolt& b : all)
      out << "  bolt " << b.name << ": blocks " << b.head.block << " to " << b.anchor.block
          << ", L0 " << format_significant(b.law.free_length, 5) << " m, k "
          << format_significant(b.law.stiffness, 5) << " N/m, pretension "
          << format_significant(b.law.pretension, 5) << " N, yield force "
          << format_significant(b.law.yield_force, 5) << " N, ruptures beyond "
          << format_significant(b.law.rupture_elongation, 5) << " m\n";
  }
};
} // namespace

std::unique_ptr<ElementOutputs> make_bolt_outputs()
{
  return std::make_unique<BoltOutputs>();
}

} // namespace ddafem
