// Loops over fixed chunks on a set number of threads (TBB, linked directly), with results
// that do not depend on the thread count: the chunks are set by the problem size and a grain,
// never by the threads; each chunk writes only its own slots; sums are one partial per chunk,
// added in chunk order. One thread runs the same chunks in a plain loop.
#pragma once

#include <algorithm>
#include <cstddef>
#include <memory>
#include <vector>

namespace ddafem
{
class Parallel
{
public:
  /// n_threads 0: all cores (TBB's default concurrency).
  explicit Parallel(unsigned n_threads = 1);
  ~Parallel();
  Parallel(const Parallel&) = delete;
  Parallel& operator=(const Parallel&) = delete;

  unsigned n_threads() const { return threads; }

  /// f(begin, end) on the chunks [k grain, min((k + 1) grain, n)).
  template <typename F>
  void for_chunks(std::size_t n, std::size_t grain, const F& f) const
  {
    const std::size_t n_chunks = (n + grain - 1) / grain;
    run_chunks(n_chunks, [&](std::size_t k) { f(k * grain, std::min(n, (k + 1) * grain)); });
  }

  /// The sum over chunks of f(begin, end), added in chunk order.
  template <typename F>
  double sum_chunks(std::size_t n, std::size_t grain, const F& f) const
  {
    const std::size_t n_chunks = (n + grain - 1) / grain;
    partials.assign(n_chunks, 0.0);
    run_chunks(n_chunks,
               [&](std::size_t k) { partials[k] = f(k * grain, std::min(n, (k + 1) * grain)); });
    double sum = 0.0;
    for (const double p : partials)
      sum += p;
    return sum;
  }

private:
  /// A chunk body, type-erased so that TBB stays out of this header.
  class Body
  {
  public:
    virtual ~Body() = default;
    virtual void operator()(std::size_t chunk) const = 0;
  };
  template <typename G>
  class BodyOf final : public Body
  {
  public:
    explicit BodyOf(const G& g_) : g(g_) {}
    void operator()(std::size_t chunk) const override { g(chunk); }

  private:
    const G& g;
  };
  template <typename G>
  void run_chunks(std::size_t n_chunks, const G& g) const
  {
    if (threads <= 1 || n_chunks <= 1)
    {
      for (std::size_t k = 0; k < n_chunks; ++k)
        g(k);
      return;
    }
    run_in_arena(n_chunks, BodyOf<G>(g));
  }
  void run_in_arena(std::size_t n_chunks, const Body& body) const;

  unsigned threads;
  struct Arena;
  std::unique_ptr<Arena> arena;
  mutable std::vector<double> partials;
};

} // namespace ddafem
