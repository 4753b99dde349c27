#include "app/run/stage_records.h"

#include "common/format.h"

#include <string>

namespace ddafem
{
namespace
{
/// The index of the opening block `block` (centroid [m]) is next to, null without openings.
nlohmann::json opening_of(const KeyblockRecorder& keyblocks, std::size_t block,
                          const dda::Point& centroid)
{
  const std::size_t opening = keyblocks.opening_next_to(block, centroid);
  return opening == KeyblockRecorder::no_opening ? nlohmann::json(nullptr)
                                                 : nlohmann::json(opening);
}
} // namespace

std::string describe_stage(const dda::Stage& st)
{
  if (st.mode == dda::StageMode::static_equilibrium)
    return "static, dt " + format_significant(st.dt) + " s, up to " + std::to_string(st.max_steps) +
           " steps, equilibrium at an out-of-balance force ratio <= " +
           format_significant(st.tolerance) + " of each block's own load, released blocks " +
           (st.release == dda::ReleaseAction::remove ? "removed" : "fall");
  if (!st.settle)
    return "dynamic to t = " + format_significant(st.end_time) + " s";
  const dda::SettleCriterion& c = *st.settle;
  return "settle until every block moves slower than " + format_significant(c.rest_speed) +
         " m/s for " + format_significant(c.rest_duration) + " s" +
         (c.fall_distance > 0.0 ? " or has fallen " + format_significant(c.fall_distance) + " m"
                                : std::string()) +
         ", at most " + format_significant(c.max_duration) + " s";
}

nlohmann::json static_stage_record(const dda::Stage& stage, const dda::StaticStageResult& result,
                                   const dda::System& system, const KeyblockRecorder& keyblocks)
{
  nlohmann::json released = nlohmann::json::array();
  for (const dda::ReleasedBlock& r : result.released)
    released.push_back({{"block", r.block},
                        {"name", system.get_model().blocks[r.block].origin},
                        {"step", r.step},
                        {"mass_kg", r.mass},
                        {"centroid_m", {r.centroid.x(), r.centroid.y()}},
                        {"ratio", r.ratio},
                        {"opening", opening_of(keyblocks, r.block, r.centroid)}});
  return {{"name", stage.name},
          {"mode", name_of(dda::StageMode::static_equilibrium)},
          {"steps", result.n_steps},
          {"converged", result.outcome == dda::StaticOutcome::equilibrium},
          {"unbalanced_force_ratio", result.ratio},
          {"tolerance", stage.tolerance},
          {"release", name_of(stage.release)},
          {"released", released}};
}

nlohmann::json dynamic_stage_record(const dda::Stage& stage, const dda::DynamicStageResult& result,
                                    const dda::System& system, const KeyblockRecorder& keyblocks)
{
  nlohmann::json record = {
      {"name", stage.name},
      {"mode", stage.settle ? dda::settle_mode_name : name_of(dda::StageMode::dynamic)},
      {"steps", result.n_steps},
      {"end_time_s", result.end_time},
      {"time_reached_s", system.time()}};
  if (!stage.settle)
    return record;
  const dda::SettleCriterion& c = *stage.settle;
  nlohmann::json fallen = nlohmann::json::array();
  for (const std::size_t i : result.fallen)
    fallen.push_back(
        {{"block", i},
         {"name", system.get_model().blocks[i].origin},
         {"mass_kg", system.blocks().mass_of(i)},
         {"opening", opening_of(keyblocks, i, system.blocks().list[i].moments.centroid)}});
  record["settled"] = result.settled;
  record["rest_speed_m_s"] = c.rest_speed;
  record["rest_duration_s"] = c.rest_duration;
  record["fall_distance_m"] = c.fall_distance;
  record["max_duration_s"] = c.max_duration;
  record["moving"] = result.moving;
  record["moving_speed_m_s"] = result.moving_speed;
  record["fallen"] = fallen;
  record["remove_fallen"] = c.remove_fallen;
  nlohmann::json removed = nlohmann::json::array();
  for (const auto& [block, when] : result.removed)
    removed.push_back({{"block", block}, {"time_s", when}});
  record["removed"] = removed;
  return record;
}

dda::StepStatus static_stage_failure(const dda::Stage& stage, const dda::StaticStageResult& result,
                                     const dda::System& system)
{
  if (result.outcome == dda::StaticOutcome::step_failed)
    return result.failure;
  dda::StepStatus failure;
  if (result.outcome == dda::StaticOutcome::equilibrium)
    return failure;
  const dda::Block& b = system.blocks().list[result.block];
  failure.outcome = dda::StepOutcome::not_converged;
  failure.message =
      "static stage '" + stage.name + "' did not reach equilibrium in " +
      std::to_string(stage.max_steps) + " steps (" + std::to_string(result.released.size()) +
      " blocks released): the largest out-of-balance force ratio (against the block's own "
      "load) is " +
      format_significant(result.ratio) + ", above the tolerance " +
      format_significant(stage.tolerance) + ", on " +
      system.get_model().blocks[result.block].origin + ", which moved " +
      format_significant(b.displacement().norm()) +
      " m since t = 0 and converges too slowly to be released (expected a larger `max_steps` "
      "or `tolerance`, or a larger pseudo time step `dt`)";
  return failure;
}

} // namespace ddafem
