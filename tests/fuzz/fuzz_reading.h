// What the libFuzzer harnesses (issue 20) share: the limits they read scenes against and what
// counts as a clear refusal.
#pragma once

#include "app/scene/scene.h"
#include "common/input_error.h"

#include <string>
#include <vector>

namespace ddafem::fuzz
{
/// Scenes are read against 200 MB: a scene beyond it (about 7,000 blocks, or a rock mass whose
/// arrangement has about 37,000 edges) is refused before its blocks are generated, so that one
/// input takes well under the harness's 30 s (7 s at most, measured); a far field (150 MB and
/// more) fits. An opening's chords are bounded apart (dda::max_opening_sides): CI timed out on a
/// circle of 38,500.
inline const ResourceLimits limits{200e6, "the fuzz harness's 200 MB"};

/// Reads the scene `text` (as if from `file`) with `overrides`. An InputError is the reader's
/// clear refusal and ends quietly; anything else (another exception, a crash, a sanitizer's
/// report, a hang) is left to libFuzzer as a finding.
inline void read_or_refuse(const std::string& text, const std::string& file,
                           const std::vector<Override>& overrides)
{
  try
  {
    read_scene_text(text, file, overrides, limits);
  }
  catch (const InputError&)
  {
  }
}

} // namespace ddafem::fuzz
