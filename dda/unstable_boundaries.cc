#include "dda/unstable_boundaries.h"

#include <algorithm>
#include <limits>

namespace ddafem::dda
{
std::vector<UnstableBoundary> unstable_boundaries(const System& system, double dt)
{
  const ModelDescription& model = system.get_model();
  std::vector<UnstableBoundary> found;
  for (std::size_t b = 0; b < model.boundaries.size(); ++b)
  {
    UnstableBoundary u;
    u.boundary = b;
    u.dt_limit = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < system.boundaries().edges.size(); ++k)
    {
      if (system.boundaries().edges[k].boundary != b)
        continue;
      const BoundaryStability s = stability_of(system, k, dt);
      u.dt_limit = std::min(u.dt_limit, s.dt_source);
      u.x_max = std::max({u.x_max, s.x_n, s.x_t});
      u.n_sources += s.is_source ? 1 : 0;
    }
    if (u.n_sources > 0)
      found.push_back(u);
  }
  return found;
}

} // namespace ddafem::dda
