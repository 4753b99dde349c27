// The far-field module's entry point (app/far_field_module/far_field_module.h):
// libddafem_far_field.so exports ddafem_far_field_module(), which the core looks up after dlopen;
// the test programs link these objects and reach it directly.
#include "app/far_field_module/distributed_support.h"
#include "app/far_field_module/far_field_parts.h"
#include "app/run/run_support.h"
#include "common/input_error.h"

#include <deal.II/base/multithread_info.h>

namespace ddafem
{
namespace
{
/// deal.II's own threads (its vector operations and sparse products run on TBB's global arena):
/// one, whatever the run's --threads. With as many as --threads, a run at --threads 1 and one at
/// 2 differed in their last bits from the first step (deal.II's threaded operations sum in
/// another order), so an ensemble's members under mpirun and with -j differed too; ddafem's
/// results must not depend on --threads. Left at deal.II's default (every core), TBB's idle
/// workers spun on an ensemble's other member's core. The far field's products are small (8396
/// DOFs on the default tunnel); the blocks' contact detection and solver take --threads.
void limit_deal_ii_threads()
{
  dealii::MultithreadInfo::set_thread_limit(1);
}

class FarFieldModuleImpl : public FarFieldModule
{
public:
  std::unique_ptr<TiedFarField> tie(const Scene& scene, dda::System& system) const override
  {
    limit_deal_ii_threads();
    if (!run_support::mpi_rank_from_environment())
      return make_tied_far_field(scene, system);
#ifdef DDAFEM_WITHOUT_DISTRIBUTED_FAR_FIELD
    throw InputError(scene.file + ": this build (the sanitizer build) has no distributed far "
                                  "field: run it without mpirun, or with the release build");
#else
    return make_distributed_tied_far_field(scene, system);
#endif
  }
  std::unique_ptr<Simulation> far_field_simulation(const Scene& scene) const override
  {
    limit_deal_ii_threads();
    return make_far_field_simulation(scene);
  }
  std::unique_ptr<Simulation> distributed_far_field_simulation(const Scene& scene) const override
  {
    limit_deal_ii_threads();
#ifdef DDAFEM_WITHOUT_DISTRIBUTED_FAR_FIELD
    throw InputError(scene.file + ": this build (the sanitizer build) has no distributed far "
                                  "field: run it without mpirun, or with the release build");
#else
    return make_distributed_far_field_simulation(scene);
#endif
  }
  std::string check_far_field(const Scene& scene) const override
  {
    return ddafem::check_far_field(scene);
  }
  void end_every_rank_after_error([[maybe_unused]] const int exit_code) const override
  {
#ifndef DDAFEM_WITHOUT_DISTRIBUTED_FAR_FIELD
    end_every_rank(exit_code);
#endif
  }
};
} // namespace
} // namespace ddafem

extern "C" const ddafem::FarFieldModule* ddafem_far_field_module()
{
  // Stateless: one constant object for the program's lifetime.
  static const ddafem::FarFieldModuleImpl module;
  return &module;
}
