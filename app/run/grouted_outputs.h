// What a run writes of its grouted bolts (docs/support.md): per crossing, history channels and
// rows (histories.h5), and the summary.json list `grouted_bolts`.
#pragma once

#include "common/history_writer.h"
#include "dda/model_description.h"
#include "dda/system.h"

#include <nlohmann/json.hpp>

#include <ostream>
#include <vector>

namespace ddafem
{
/// Appends, per grouted bolt of the model and per crossing k (from the head),
/// bolts/<name>/crossing<k>/{axial_force, shear_force, opening, slip, state}.
void add_grouted_bolt_channels(std::vector<HistoryChannel>& channels,
                               const dda::ModelDescription& model);

/// Appends the values of add_grouted_bolt_channels' channels, in their order.
void append_grouted_bolt_row(std::vector<double>& row, const dda::System& system);

/// Each grouted bolt: its law, and per crossing its blocks, point, extremes, final state and
/// when it yielded and ruptured.
nlohmann::json grouted_bolts_summary(const dda::System& system);

/// `check`'s lines: the number of grouted bolts, each one's law and its crossings.
void describe_grouted_bolts(const dda::System& system, std::ostream& out);

} // namespace ddafem
