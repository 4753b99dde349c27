// The static stage of the support tests (bolts, linings): a block settles into its support.
#pragma once

#include "dda/model_description.h"

namespace ddafem::dda
{
/// "install": static, dt 0.1 s, at most 3000 steps, balance tolerance 1e-9.
inline Stage hanging_static_stage()
{
  Stage s;
  s.name = "install";
  s.mode = StageMode::static_equilibrium;
  s.dt = 0.1;
  s.max_steps = 3000;
  s.tolerance = 1e-9;
  return s;
}
} // namespace ddafem::dda
