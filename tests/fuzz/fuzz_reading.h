// What the libFuzzer harnesses (issue 20) share: the limits they read scenes against and what
// counts as a clear refusal.
#pragma once

#include "app/scene/scene.h"
#include "common/input_error.h"

#include <string>
#include <vector>

namespace ddafem::fuzz
{
/// Scenes are read against 50 MB: a scene beyond it (about 830 blocks, or an arrangement of
/// about 4,400 edges: short traces, an opening's fine chords) is refused before its blocks are
/// generated, so that one input takes well under the harness's 10 s. The slowest such scenes
/// read in 0.2 s in the Release build, some ten times that with the sanitizers; at 200 MB a
/// circle of 37,000 chords took 8 s in Release (blocks of that many vertices are compared in
/// pairs) and timed out in CI.
inline const ResourceLimits limits{50e6, "the fuzz harness's 50 MB"};

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
