#pragma once

#include <algorithm>
#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

namespace ddafem
{
/// A few values kept by key, the most recently used first; the least recently used is dropped
/// when a new one would exceed the capacity. Coupled runs that cut dt step on levels
/// dt_max / 2^k and come back: the far field keeps one factorization, the ties one condensation,
/// per level. Keys are compared exactly (the levels are exact binary fractions of dt_max).
template <typename Key, typename Value>
class RecentCache
{
public:
  explicit RecentCache(const std::size_t capacity) : max_size(std::max<std::size_t>(capacity, 1)) {}

  /// Makes the value of `key` the most recent one and returns it, or nullptr if none is kept.
  Value* use(const Key& key)
  {
    const auto kept = std::find_if(entries.begin(), entries.end(),
                                   [&key](const Entry& e) { return e.first == key; });
    if (kept == entries.end())
      return nullptr;
    std::rotate(entries.begin(), kept, kept + 1);
    return entries.front().second.get();
  }

  /// Keeps `value` for `key` as the most recent one (drops the least recent beyond the capacity)
  /// and returns it.
  Value& insert(const Key& key, std::unique_ptr<Value> value)
  {
    entries.insert(entries.begin(), Entry(key, std::move(value)));
    if (entries.size() > max_size)
      entries.pop_back();
    return *entries.front().second;
  }

  bool empty() const { return entries.empty(); }
  std::size_t size() const { return entries.size(); }
  /// The most recently used key and value; the cache must not be empty.
  const Key& front_key() const { return entries.front().first; }
  Value& front() const { return *entries.front().second; }
  void clear() { entries.clear(); }
  /// Calls visit(key, value) for each entry, the most recently used first (checkpoints).
  template <typename Visit>
  void for_each(Visit visit) const
  {
    for (const Entry& e : entries)
      visit(e.first, *e.second);
  }

private:
  using Entry = std::pair<Key, std::unique_ptr<Value>>;
  std::size_t max_size;
  std::vector<Entry> entries;
};

} // namespace ddafem
