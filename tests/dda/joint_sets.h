// Shared test helper: joint sets for the rock-mass generator.
#pragma once

#include "dda/rock_mass.h"

namespace ddafem::dda::test_models
{
/// A persistent set of parallel joints: dip [deg], spacing [m], offset of the first trace [m].
inline JointSet persistent_set(double dip, double spacing, double offset = 0.0)
{
  JointSet set;
  set.dip = dip;
  set.spacing = spacing;
  set.offset = offset;
  return set;
}

} // namespace ddafem::dda::test_models
