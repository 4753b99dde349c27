// Checkpoints of the keyblocks' tracks, references and marks.
#include "app/run/checkpoint_types.h"
#include "app/run/keyblocks.h"

#include <boost/serialization/unordered_set.hpp>

#include <cstdint>

namespace ddafem
{
namespace
{
template <class Archive, class Track>
void transfer_track(Archive& a, Track& t)
{
  transfer_all(a, t.reference, t.last, t.last_relative, t.peak, t.peak_time, t.peak_relative);
  transfer_all(a, t.peak_relative_time, t.row_slip, t.row_opening, t.max_slip, t.max_opening);
  transfer_all(a, t.thrown_out);
}

} // namespace

void KeyblockRecorder::save(CheckpointOut& a) const
{
  transfer_marker(a, "keyblocks");
  auto& self = const_cast<KeyblockRecorder&>(*this);
  transfer_in_place(a, self.tracks, "keyblocks", [&a](Track& t) { transfer_track(a, t); });
  a << released << ring_reference << block_reference << removed << referenced << closed_contacts;
}

void KeyblockRecorder::load(CheckpointIn& a)
{
  transfer_marker(a, "keyblocks");
  transfer_in_place(a, tracks, "keyblocks", [&a](Track& t) { transfer_track(a, t); });
  a >> released >> ring_reference >> block_reference >> removed >> referenced >> closed_contacts;
}

} // namespace ddafem
