// What a run reports of its linings (dda/lining.h, docs/support.md "Lining"): per lining its
// history channels linings/<name>/... (the largest utilisation of the intact elements, that
// element's index and forces, the number of broken elements), summary.json's `linings` (each
// lining's section, extremes, first break and its elements between two blocks with their final
// forces) and `check`'s lines (nodes, elements and the blocks they couple).
#include "app/run/element_outputs.h"

#include "common/format.h"
#include "dda/lining.h"
#include "dda/vtu_text.h"
#include "dda/vtu_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <set>

namespace ddafem
{
namespace
{
/// The bending moment of larger magnitude of the two ends [N m/m], signed.
double governing_moment(const dda::FrameForces& f)
{
  return std::abs(f.bending_moment_a()) >= std::abs(f.bending_moment_b()) ? f.bending_moment_a()
                                                                          : f.bending_moment_b();
}

/// The .vtu text of the linings' elements at `time` [s]: one VTK_LINE cell per element with cell
/// data lining, element, state (Int32: 0 intact, 1 broken, 2 on one block), axial_force and
/// shear_force [N/m], moment (the end moment of larger magnitude, M(0) or M(L)) [N m/m] and
/// utilisation [-].
std::string lining_vtu_text(double time, const std::vector<dda::LiningElementSnapshot>& elements)
{
  using namespace dda::vtu;
  using E = dda::LiningElementSnapshot;
  std::string out;
  out.reserve(512 + 256 * elements.size());
  open_piece(out, time, 2 * elements.size(), elements.size());
  out += "      <Points>\n"
         "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const E& e : elements)
  {
    append_vector(out, e.a);
    append_vector(out, e.b);
  }
  out += close_array;
  out += "      </Points>\n"
         "      <Cells>\n";
  // One line cell per element with its own two points: connectivity 2k, 2k + 1.
  open_array(out, "Int64", "connectivity", 1);
  for (std::size_t k = 0; k < elements.size(); ++k)
  {
    out += "          ";
    append_integer(out, 2 * k);
    out += ' ';
    append_integer(out, 2 * k + 1);
    out += '\n';
  }
  out += close_array;
  open_array(out, "Int64", "offsets", 1);
  for (std::size_t k = 0; k < elements.size(); ++k)
  {
    out += "          ";
    append_integer(out, 2 * k + 2);
    out += '\n';
  }
  out += close_array;
  append_column<int>(out, elements, "UInt8", "types", [](const E&) { return vtk_line; });
  out += "      </Cells>\n"
         "      <CellData Scalars=\"utilisation\">\n";
  append_column<std::size_t>(out, elements, "Int64", "lining", [](const E& e) { return e.lining; });
  append_column<std::size_t>(out, elements, "Int64", "element",
                             [](const E& e) { return e.element; });
  append_column<int>(out, elements, "Int32", "state",
                     [](const E& e) { return static_cast<int>(e.state); });
  append_column<double>(out, elements, "Float64", "axial_force",
                        [](const E& e) { return e.forces.axial_force; });
  append_column<double>(out, elements, "Float64", "shear_force",
                        [](const E& e) { return e.forces.shear_force; });
  append_column<double>(out, elements, "Float64", "moment",
                        [](const E& e) { return governing_moment(e.forces); });
  append_column<double>(out, elements, "Float64", "utilisation",
                        [](const E& e) { return e.utilisation; });
  out += "      </CellData>\n";
  out += close_piece;
  return out;
}

nlohmann::json element_json(const dda::Lining& l, std::size_t k)
{
  const dda::LiningElement& e = l.elements[k];
  const dda::LiningNode& a = l.nodes[e.a];
  const dda::LiningNode& b = l.nodes[e.b];
  return {{"index", k},
          {"from_m", point_json(a.point.initial)},
          {"to_m", point_json(b.point.initial)},
          {"blocks", {a.point.block, b.point.block}},
          {"length_m", e.length0},
          {"state", name_of(e.state)},
          {"axial_force_n_per_m", e.forces.axial_force},
          {"shear_force_n_per_m", e.forces.shear_force},
          {"moment_a_nm_per_m", e.forces.bending_moment_a()},
          {"moment_b_nm_per_m", e.forces.bending_moment_b()},
          {"utilisation", e.check.utilisation},
          {"governing", name_of(e.check.mode)},
          {"max_utilisation", e.max_utilisation},
          {"break_time_s", time_or_null(e.break_time)}};
}

/// The kind's outputs (app/run/element_outputs.h).
class LiningOutputs final : public ElementOutputs
{
public:
  void add_channels(std::vector<HistoryChannel>& channels,
                    const dda::ModelDescription& model) const override;
  void add_row(std::vector<double>& row, const dda::System& system) const override;
  void add_summary(nlohmann::json& summary, const dda::System& system) const override;
  void describe(const dda::System& system, std::ostream& out) const override;
  /// lining.pvd: the linings' elements as lines (docs/support.md), apart from model.pvd.
  void open_series(const std::string& directory, const dda::System& system) override
  {
    if (!system.elements<dda::Linings>().all().empty())
      series.emplace(directory, "lining");
  }
  void write_series(const dda::System& system) override
  {
    if (series)
      series->write_text(
          system.time(),
          lining_vtu_text(system.time(),
                          dda::lining_snapshot(system.elements<dda::Linings>().all())));
  }
  void save_series(CheckpointOut& archive) const override
  {
    if (series)
      series->save(archive);
  }
  void load_series(CheckpointIn& archive) override
  {
    if (series)
      series->load(archive);
  }

private:
  std::optional<dda::VtuSeriesWriter> series;
};

void LiningOutputs::add_channels(std::vector<HistoryChannel>& channels,
                                 const dda::ModelDescription& model) const
{
  for (const dda::LiningDescription& l : model.linings)
  {
    const std::string p = "linings/" + l.name + "/";
    channels.push_back({p + "max_utilisation", 1, "",
                        "largest demand / capacity of the intact elements (0 before installed)"});
    channels.push_back({p + "worst_element", 1, "", "index of that element"});
    channels.push_back({p + "axial_force", 1, "N/m", "N of that element, tension positive"});
    channels.push_back({p + "shear_force", 1, "N/m", "V of that element"});
    channels.push_back(
        {p + "moment", 1, "N m/m", "the bending moment of larger magnitude at its ends"});
    channels.push_back({p + "broken_elements", 1, "", "elements broken so far"});
  }
}

void LiningOutputs::add_row(std::vector<double>& row, const dda::System& system) const
{
  for (const dda::Lining& l : system.elements<dda::Linings>().all())
  {
    const std::size_t k = l.worst_element();
    const dda::LiningElement& e = l.elements[k];
    const bool intact = e.state == dda::LiningElementState::intact;
    row.insert(row.end(), {intact ? e.check.utilisation : 0.0, static_cast<double>(k),
                           e.forces.axial_force, e.forces.shear_force, governing_moment(e.forces),
                           static_cast<double>(l.n_broken())});
  }
}

nlohmann::json linings_summary(const dda::System& system)
{
  nlohmann::json out = nlohmann::json::array();
  for (const dda::Lining& l : system.elements<dda::Linings>().all())
  {
    nlohmann::json elements = nlohmann::json::array();
    for (std::size_t k = 0; k < l.elements.size(); ++k)
      if (l.elements[k].state != dda::LiningElementState::on_one_block)
        elements.push_back(element_json(l, k));
    const bool broke = !std::isnan(l.first_break_time);
    out.push_back(
        {{"name", l.name},
         {"thickness_m", l.section.thickness},
         {"youngs_modulus_pa", l.section.youngs_modulus},
         {"compressive_strength_pa", l.section.compressive_strength},
         {"tensile_strength_pa", l.section.tensile_strength},
         {"shear_strength_pa", l.section.shear_strength},
         {"nodes", l.nodes.size()},
         {"elements", l.elements.size()},
         {"installed", l.installed},
         {"install_time_s", l.installed ? nlohmann::json(l.install_time) : nlohmann::json(nullptr)},
         {"max_utilisation", l.max_utilisation},
         {"max_utilisation_time_s", time_or_null(l.max_utilisation_time)},
         {"max_utilisation_element", l.max_utilisation_element},
         {"broken_elements", l.n_broken()},
         {"first_break_time_s", time_or_null(l.first_break_time)},
         {"first_break_element",
          broke ? nlohmann::json(l.first_break_element) : nlohmann::json(nullptr)},
         {"coupling_elements", elements}});
  }
  return out;
}

void LiningOutputs::add_summary(nlohmann::json& summary, const dda::System& system) const
{
  if (!system.elements<dda::Linings>().all().empty())
    summary["linings"] = linings_summary(system);
}

void LiningOutputs::describe(const dda::System& system, std::ostream& out) const
{
  for (const dda::Lining& l : system.elements<dda::Linings>().all())
  {
    std::set<std::pair<std::size_t, std::size_t>> pairs;
    std::size_t n_coupling = 0;
    for (const dda::LiningElement& e : l.elements)
      if (e.state != dda::LiningElementState::on_one_block)
      {
        ++n_coupling;
        pairs.insert(std::minmax(l.nodes[e.a].point.block, l.nodes[e.b].point.block));
      }
    const dda::LiningSection& s = l.section;
    out << "  lining " << l.name << ": " << l.nodes.size() << " nodes, " << l.elements.size()
        << " elements (" << n_coupling << " between two blocks), t "
        << format_significant(s.thickness, 5) << " m, E " << format_significant(s.youngs_modulus, 5)
        << " Pa, f_c " << format_significant(s.compressive_strength, 5) << " Pa, f_t "
        << format_significant(s.tensile_strength, 5) << " Pa, f_v "
        << (s.shear_strength > 0.0 ? format_significant(s.shear_strength, 5) + " Pa"
                                   : std::string("not checked"))
        << ", installed "
        << (l.install_stage == 0 ? std::string("from the start")
                                 : "at the start of stage " + std::to_string(l.install_stage))
        << "\n    couples blocks:";
    for (const auto& [a, b] : pairs)
      out << " " << a << "-" << b;
    out << "\n";
  }
}

} // namespace

std::unique_ptr<ElementOutputs> make_lining_outputs()
{
  return std::make_unique<LiningOutputs>();
}

} // namespace ddafem
