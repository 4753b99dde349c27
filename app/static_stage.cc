#include "app/static_stage.h"

#include "app/run_support.h"

#include <string>

namespace ddafem
{
nlohmann::json static_stage_record(const dda::Stage& stage, const dda::StaticStageResult& result,
                                   const dda::System& system, const KeyblockRecorder& keyblocks)
{
  nlohmann::json released = nlohmann::json::array();
  for (const dda::ReleasedBlock& r : result.released)
  {
    const std::size_t opening = keyblocks.opening_next_to(r.block, r.centroid);
    released.push_back(
        {{"block", r.block},
         {"name", system.get_model().blocks[r.block].origin},
         {"step", r.step},
         {"mass_kg", r.mass},
         {"centroid_m", {r.centroid.x(), r.centroid.y()}},
         {"ratio", r.ratio},
         {"opening", opening == KeyblockRecorder::no_opening ? nlohmann::json(nullptr)
                                                             : nlohmann::json(opening)}});
  }
  return {{"name", stage.name},
          {"mode", "static"},
          {"steps", result.n_steps},
          {"converged", result.outcome == dda::StaticOutcome::equilibrium},
          {"unbalanced_force_ratio", result.ratio},
          {"tolerance", stage.tolerance},
          {"release", stage.release == dda::ReleaseAction::remove ? "remove" : "fall"},
          {"released", released}};
}

dda::StepStatus static_stage_failure(const dda::Stage& stage, const dda::StaticStageResult& result,
                                     const dda::System& system)
{
  using run_support::format;
  if (result.outcome == dda::StaticOutcome::step_failed)
    return result.failure;
  dda::StepStatus failure;
  if (result.outcome == dda::StaticOutcome::equilibrium)
    return failure;
  const dda::Block& b = system.get_blocks()[result.block];
  failure.outcome = dda::StepOutcome::not_converged;
  failure.message =
      "static stage '" + stage.name + "' did not reach equilibrium in " +
      std::to_string(stage.max_steps) + " steps (" + std::to_string(result.released.size()) +
      " blocks released): the largest out-of-balance force ratio (against the block's own "
      "load) is " +
      format(result.ratio) + ", above the tolerance " + format(stage.tolerance) + ", on " +
      system.get_model().blocks[result.block].origin + ", which moved " +
      format(b.displacement().norm()) +
      " m since t = 0 and converges too slowly to be released (expected a larger `max_steps` "
      "or `tolerance`, or a larger pseudo time step `dt`)";
  return failure;
}

} // namespace ddafem
