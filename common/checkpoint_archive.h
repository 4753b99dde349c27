// Checkpoints (issue 20): a run's whole state in one binary file, so that `ddafem resume`
// continues a killed or stopped run and its histories equal the uninterrupted run's bit for bit.
// The archive is Boost.Serialization's binary one (deal.II's own checkpoints use it, and its
// Vector<double> serializes into it): doubles are stored as their bytes, on the machine that
// wrote them. This header adds the helpers the models share (Eigen's matrices and tuples:
// dda/checkpoint_types.h; deal.II has its own tuples').
#pragma once

#include "common/checkpoint_fwd.h"

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/array.hpp>
#include <boost/serialization/array_wrapper.hpp>
#include <boost/serialization/map.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace ddafem
{
/// Stores or restores an optional: a flag, then the value if there is one.
template <class Archive, typename T>
void transfer_optional(Archive& archive, std::optional<T>& value)
{
  bool present = value.has_value();
  transfer_all(archive, present);
  if constexpr (Archive::is_loading::value)
  {
    if (present)
      value.emplace();
    else
      value.reset();
  }
  if (present)
    transfer_all(archive, *value);
}

/// A marker between the parts of a checkpoint: writing stores `name`; reading throws
/// std::runtime_error if another name is found, so that a checkpoint of another build or model
/// stops at the first part that differs instead of restoring garbage.
template <class Archive>
void transfer_marker(Archive& archive, const std::string& name)
{
  std::string found = name;
  transfer_all(archive, found);
  if (found != name)
    throw std::runtime_error("checkpoint: expected its part '" + name + "', found '" + found +
                             "' (a checkpoint of another version or scene)");
}

/// Stores or restores an object with its own `save(CheckpointOut&) const` and
/// `load(CheckpointIn&)`.
template <class Archive, typename T>
void transfer_object(Archive& archive, T& object)
{
  if constexpr (Archive::is_loading::value)
    object.load(archive);
  else
    object.save(archive);
}

/// Stores or restores the items of a vector whose length the model fixes (blocks, loads, edges):
/// the length, then `transfer(item)` for each in place. Reading throws std::runtime_error if the
/// checkpoint has another length.
template <class Archive, typename T, typename Transfer>
void transfer_in_place(Archive& archive, std::vector<T>& items, const std::string& what,
                       Transfer transfer)
{
  std::uint64_t n = items.size();
  transfer_all(archive, n);
  if (n != items.size())
    throw std::runtime_error("checkpoint: " + std::to_string(n) + " " + what +
                             " saved, the scene has " + std::to_string(items.size()) +
                             " (a checkpoint of another scene)");
  for (T& item : items)
    transfer(item);
}

/// Stores or restores a vector of default-constructible items that may change its length (the
/// contacts' frames, a Bathe pair's first halves): the length, then `transfer(item)` for each.
template <class Archive, typename T, typename Transfer>
void transfer_each(Archive& archive, std::vector<T>& items, Transfer transfer)
{
  std::uint64_t n = items.size();
  transfer_all(archive, n);
  if constexpr (Archive::is_loading::value)
    items.resize(n);
  for (T& item : items)
    transfer(item);
}

} // namespace ddafem
