#include "common/parallel.h"

#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <algorithm>

namespace ddafem
{
struct Parallel::Arena
{
  explicit Arena(int n) : arena(n) {}
  tbb::task_arena arena;
};

Parallel::Parallel(const unsigned n_threads)
    : threads(n_threads > 0 ? n_threads
                            : static_cast<unsigned>(std::max(1, tbb::info::default_concurrency())))
{
  if (threads > 1)
    arena = std::make_unique<Arena>(static_cast<int>(threads));
}

Parallel::~Parallel() = default;

void Parallel::run_in_arena(const std::size_t n_chunks, const Body& body) const
{
  // One task per chunk (simple_partitioner, grain 1): which thread runs a chunk varies, what
  // the chunk computes does not.
  arena->arena.execute(
      [&]
      {
        tbb::parallel_for(
            tbb::blocked_range<std::size_t>(0, n_chunks, 1),
            [&](const tbb::blocked_range<std::size_t>& r)
            {
              for (std::size_t k = r.begin(); k != r.end(); ++k)
                body(k);
            },
            tbb::simple_partitioner());
      });
}

} // namespace ddafem
