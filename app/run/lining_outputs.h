// What a run reports of its linings (dda/lining.h, docs/support.md "Lining"): history channels
// and rows, summary.json's `linings`, and `check`'s listing.
#pragma once

#include "common/history_writer.h"
#include "dda/system.h"

#include <nlohmann/json.hpp>

#include <ostream>
#include <vector>

namespace ddafem
{
/// Per lining `linings/<name>/...`: the largest utilisation of the intact elements, that
/// element's index and forces, and the number of broken elements.
void add_lining_channels(std::vector<HistoryChannel>& channels, const dda::ModelDescription& model);
/// The values of add_lining_channels' channels for the System's current state.
void add_lining_row(std::vector<double>& row, const dda::System& system);
/// summary.json's `linings`: each lining's section, its extremes and first break, and its
/// elements between two blocks with their final forces.
nlohmann::json linings_summary(const dda::System& system);
/// `check`: each lining's nodes, elements and the blocks they couple.
void describe_linings(const dda::System& system, std::ostream& out);
} // namespace ddafem
