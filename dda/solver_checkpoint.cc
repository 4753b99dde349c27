// Checkpoints of the step's linear solver: what decides the next solutions' bits is which
// factors are kept (a refinement with older factors differs from a new factorization in the
// last bits), so their matrices are stored and factorized again on loading.
#include "dda/checkpoint_types.h"
#include "dda/step_solver.h"

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <vector>

namespace ddafem::dda
{
void FactorizationReusingSolver::save(CheckpointOut& a) const
{
  a << last_call_used_own_factors << factorization_count << solve_count << refinement_count;
  std::uint64_t n = kept.size();
  a << n;
  kept.for_each(
      [&a](const double key, const Factored& f)
      {
        const bool factored = f.matrix != nullptr;
        a << key << factored;
        if (factored)
          a << *f.matrix;
      });
}

void FactorizationReusingSolver::load(CheckpointIn& a)
{
  a >> last_call_used_own_factors >> factorization_count >> solve_count >> refinement_count;
  std::uint64_t n = 0;
  a >> n;
  std::vector<std::pair<double, std::unique_ptr<Factored>>> entries;
  for (std::uint64_t k = 0; k < n; ++k)
  {
    double key = 0.0;
    bool factored = false;
    a >> key >> factored;
    auto f = std::make_unique<Factored>();
    f->solver = make_sparse_direct_solver(kind);
    if (factored)
    {
      f->matrix = std::make_unique<BlockSparseMatrix>(
          0, std::vector<std::pair<std::size_t, std::size_t>>());
      a >> *f->matrix;
      f->solver->analyze_pattern(*f->matrix);
      if (!f->solver->factorize(*f->matrix))
        throw std::runtime_error("checkpoint: a kept step matrix no longer factorizes");
    }
    entries.emplace_back(key, std::move(f));
  }
  // Inserted from the least recently used, so that the cache's order is the saved one.
  kept.clear();
  for (auto e = entries.rbegin(); e != entries.rend(); ++e)
    kept.insert(e->first, std::move(e->second));
}

void StepSolver::save(CheckpointOut& a) const
{
  a << direct_key << direct_solves_left << previous_call_direct << pcg_solve_count;
  a << pcg_iteration_count << fallback_count;
  direct.save(a);
}

void StepSolver::load(CheckpointIn& a)
{
  a >> direct_key >> direct_solves_left >> previous_call_direct >> pcg_solve_count;
  a >> pcg_iteration_count >> fallback_count;
  direct.load(a);
}

} // namespace ddafem::dda
