// How the run driver's own records are stored in a checkpoint (only the checkpoint code
// includes this).
#pragma once

#include "app/run/run_summary.h"

#include "common/checkpoint_archive.h"
#include "common/vtk_collection.h"
#include "dda/checkpoint_types.h"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <string>

namespace ddafem
{
template <class Archive>
void serialize(Archive& a, CollectionDataSet& d, const unsigned int /*version*/)
{
  transfer_all(a, d.time, d.part, d.file);
}

/// The stages' totals; their records as JSON text (summary.json's numbers, which the text keeps
/// exactly: nlohmann::json writes the shortest digits that read back to the same double).
template <class Archive>
void transfer_stage_totals(Archive& a, StageTotals& t)
{
  transfer_all(a, t.n_cut_steps, t.n_penalty_raises, t.n_flips_ignored, t.n_reversals,
               t.cuts_by_cause);
  transfer_all(a, t.smallest_dt, t.failure);
  std::string records = t.records.dump();
  transfer_all(a, records);
  if constexpr (Archive::is_loading::value)
    t.records = nlohmann::json::parse(records);
}

/// The start of an outputs' part of a checkpoint: its name and the rows of histories.h5 then,
/// which the reopened outputs need before anything else.
inline void save_history_rows(CheckpointOut& a, const std::string& part, std::size_t rows)
{
  transfer_marker(a, part);
  const std::uint64_t n = rows;
  a << n;
}

inline std::size_t load_history_rows(CheckpointIn& a, const std::string& part)
{
  transfer_marker(a, part);
  std::uint64_t n = 0;
  a >> n;
  return n;
}

} // namespace ddafem
