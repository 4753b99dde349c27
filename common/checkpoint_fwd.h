// The checkpoint archives by name, for headers that declare save and load, and transfer_all (the
// archive itself: common/checkpoint_archive.h).
#pragma once

namespace boost::archive
{
class binary_oarchive;
class binary_iarchive;
} // namespace boost::archive

namespace ddafem
{
using CheckpointOut = boost::archive::binary_oarchive;
using CheckpointIn = boost::archive::binary_iarchive;

/// Stores or restores each of `items` in turn (Boost.Serialization's `archive & item`, which
/// stores into an output archive and restores from an input one: one function for both).
template <class Archive, typename... T>
void transfer_all(Archive& archive, T&... items)
{
  (archive & ... & items);
}
} // namespace ddafem
