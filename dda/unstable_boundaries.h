// Which viscous boundaries of a system are energy sources at a time step: VB I absorbs only while
// x = c dt / m stays below vb1_source_threshold() on each of its edges (viscous_boundary.h);
// `run` refuses such a dt unless allowed, `check` warns.
#pragma once

#include "dda/system.h"

#include <cstddef>
#include <vector>

namespace ddafem::dda
{
/// A boundary with edges that feed energy into the model at the time step asked about.
struct UnstableBoundary
{
  std::size_t boundary = 0;  ///< index in ModelDescription::boundaries
  std::size_t n_sources = 0; ///< its edges that are energy sources
  double x_max = 0.0;        ///< largest x = c dt / m over its edges (normal and tangential) [-]
  double dt_limit = 0.0;     ///< it absorbs on every edge only for dt below this [s]
};

/// Every boundary of `system` with at least one edge that is an energy source at `dt` [s], in
/// the order of the model's boundaries; empty when all absorb.
std::vector<UnstableBoundary> unstable_boundaries(const System& system, double dt);

} // namespace ddafem::dda
