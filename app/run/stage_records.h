// A scene's stages as the run records them: summary.json's stage records (the static stage's
// released blocks, a settle stage's verdict), and the failure that stops the run when a static
// stage does not reach equilibrium.
#pragma once

#include "app/run/keyblocks.h"
#include "dda/dynamic_stage.h"
#include "dda/static_stage.h"
#include "dda/system.h"

#include <nlohmann/json.hpp>

#include <string>

namespace ddafem
{
/// One line for `check`: what the stage does and when it ends.
std::string describe_stage(const dda::Stage& stage);

/// The stage's record in summary.json: name, mode, steps, converged, unbalanced_force_ratio,
/// tolerance, release (fall | remove) and `released`, one entry per released block:
/// {block, name, step, mass_kg, centroid_m [x, y], ratio, opening (index into the keyblocks'
/// openings, null without openings)}.
nlohmann::json static_stage_record(const dda::Stage& stage, const dda::StaticStageResult& result,
                                   const dda::System& system, const KeyblockRecorder& keyblocks);

/// A dynamic or settle stage's record in summary.json: name, mode (dynamic | settle), steps,
/// end_time_s (settle: its bound), time_reached_s; settle stages also settled (every block at
/// rest or fallen before the bound), rest_speed_m_s, rest_duration_s, fall_distance_m,
/// max_duration_s, moving (ids of the blocks still moving at the end), moving_speed_m_s (the
/// fastest of them) and fallen (ids, with the opening each is next to).
nlohmann::json dynamic_stage_record(const dda::Stage& stage, const dda::DynamicStageResult& result,
                                    const dda::System& system, const KeyblockRecorder& keyblocks);

/// What stops the run after the stage: the failed step, or not_converged with a message naming
/// the block farthest from balance; outcome success when the stage reached equilibrium.
dda::StepStatus static_stage_failure(const dda::Stage& stage, const dda::StaticStageResult& result,
                                     const dda::System& system);

} // namespace ddafem
