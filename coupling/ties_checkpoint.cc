// Checkpoints of the ties between two steps: their accepted and trial states, stretches, the
// preloads and the interface's work. What a step builds before it reads it (the condensations
// for its dt, the trial terms) is not stored: the next step makes it again from the same inputs.
#include "common/checkpoint_archive.h"
#include "coupling/far_field_ties.h"
#include "dda/checkpoint_types.h"

namespace ddafem::coupling
{
template <class Archive>
void FarFieldTies::transfer_state(Archive& a)
{
  transfer_marker(a, "coupling::FarFieldTies");
  transfer_in_place(a, ties, "ties",
                    [&a](Tie& t) { transfer_all(a, t.forces, t.trial, t.stretch); });
  transfer_all(a, preload, held, dynamic_started, previous_force, work_blocks, work_preloads);
  transfer_all(a, time_condensation, time_ties, condensation_count);
  transfer_all(a, chain.valid, chain.dt, chain.z, chain.g_k_z);
  if constexpr (Archive::is_loading::value)
    bonded_terms_valid = false;
}

void FarFieldTies::save(CheckpointOut& archive) const
{
  // One function stores and restores (Boost.Serialization's `&`); storing changes nothing.
  const_cast<FarFieldTies&>(*this).transfer_state(archive);
}

void FarFieldTies::load(CheckpointIn& archive)
{
  transfer_state(archive);
}

} // namespace ddafem::coupling
