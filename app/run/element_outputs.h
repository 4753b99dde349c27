// What a run reports of each element kind of the blocks (dda/element.h): history channels and
// rows (histories.h5), its own VTU series if it has one, its section of summary.json and
// `check`'s lines. One ElementOutputs per
// kind, each in its own file (app/run/<kind>_outputs.cc); make_element_outputs orders them as the
// histories' channels.
#pragma once

#include "common/checkpoint_fwd.h"
#include "common/history_writer.h"
#include "dda/system.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace ddafem
{
/// summary.json's time of an event [s], or null for one that never happened (NaN).
inline nlohmann::json time_or_null(double t)
{
  return std::isnan(t) ? nlohmann::json(nullptr) : nlohmann::json(t);
}

/// summary.json's point: [x, y] [m].
inline nlohmann::json point_json(const dda::Point& p)
{
  return {p.x(), p.y()};
}

class ElementOutputs
{
public:
  virtual ~ElementOutputs() = default;
  /// Appends the history channels of the scene's elements of its kind.
  virtual void add_channels(std::vector<HistoryChannel>& channels,
                            const dda::ModelDescription& model) const = 0;
  /// Appends the values of its channels, in their order, for the System's current state.
  virtual void add_row(std::vector<double>& row, const dda::System& system) const = 0;
  /// Adds its section to summary.json if the scene has elements of its kind.
  virtual void add_summary(nlohmann::json& summary, const dda::System& system) const = 0;
  /// `check`'s lines on its elements (none if the scene has none).
  virtual void describe(const dda::System& system, std::ostream& out) const = 0;

  /// A kind with a VTU series of its own beside model.pvd (e.g. lining.pvd) opens it in
  /// `directory` if the scene has elements of its kind; the others have none (the default).
  virtual void open_series(const std::string& /*directory*/, const dda::System& /*system*/) {}
  /// A snapshot of its series at the System's time.
  virtual void write_series(const dda::System& /*system*/) {}
  /// Checkpoints of its series: the files written so far (load: of the same scene).
  virtual void save_series(CheckpointOut& /*archive*/) const {}
  virtual void load_series(CheckpointIn& /*archive*/) {}
};

/// End-anchored bolts (app/run/bolt_outputs.cc): bolts/<name>/..., summary.json's `bolts`.
std::unique_ptr<ElementOutputs> make_bolt_outputs();
/// Linings (app/run/lining_outputs.cc): linings/<name>/..., summary.json's `linings`.
std::unique_ptr<ElementOutputs> make_lining_outputs();
/// Grouted bolts (app/run/grouted_outputs.cc): bolts/<name>/crossing<k>/...,
/// summary.json's `grouted_bolts`.
std::unique_ptr<ElementOutputs> make_grouted_bolt_outputs();

/// Every kind's outputs in the order of their history channels: end-anchored bolts, linings,
/// grouted bolts (as dda::make_element_kinds steps them).
inline std::vector<std::unique_ptr<ElementOutputs>> make_element_outputs()
{
  std::vector<std::unique_ptr<ElementOutputs>> outputs;
  outputs.push_back(make_bolt_outputs());
  outputs.push_back(make_lining_outputs());
  outputs.push_back(make_grouted_bolt_outputs());
  return outputs;
}

} // namespace ddafem
