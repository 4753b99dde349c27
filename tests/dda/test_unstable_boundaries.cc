// VB I is an energy source beyond x = c dt / m = vb1_source_threshold() (docs/reference/physics.md
// section 6); unstable_boundaries reports it per boundary with the dt limit computed by hand.
#include "dda/system.h"
#include "dda/unstable_boundaries.h"
#include "dda/viscous_boundary.h"
#include "row_of_blocks.h"

#include <gtest/gtest.h>

using namespace ddafem;
using namespace ddafem::dda;

namespace
{
BoundaryDescription boundary_on_line_x(double x, BoundaryType type)
{
  BoundaryDescription b;
  b.type = type;
  b.impedance = ImpedanceKind::textbook;
  b.on_line = true;
  b.line_point = Point(x, 0.0);
  b.line_direction = Vector2(0.0, 1.0);
  return b;
}

/// Two unit blocks of the paper's rock with VB I on the right end (boundary 0) and VB II on the
/// left (boundary 1).
ModelDescription two_blocks_between_boundaries()
{
  ModelDescription m = test_models::row_of_blocks(2, 2.5e12);
  m.boundaries.push_back(boundary_on_line_x(2.0, BoundaryType::vb1));
  m.boundaries.push_back(boundary_on_line_x(0.0, BoundaryType::vb2));
  m.time = {1e-4, 0.1, Integrator::dda};
  return m;
}
} // namespace

TEST(UnstableBoundaries, Vb1LimitIsThresholdOverTextbookPSpeed)
{
  const System system(two_blocks_between_boundaries());
  // A 1 m x 1 m block: m = rho (1 m^2), cn = rho (1 m) VP with VP = 4758.31 m/s (body speed,
  // textbook impedance), ct = rho (1 m) VS < cn: x = cn dt / m = VP dt, and VB I absorbs only
  // for dt < x0 / VP = 1.68789 / 4758.31 = 3.5472e-4 s.
  EXPECT_TRUE(unstable_boundaries(system, 3e-4).empty());
  const std::vector<UnstableBoundary> found = unstable_boundaries(system, 4e-4);
  ASSERT_EQ(found.size(), 1u); // VB II is dissipative at every dt
  EXPECT_EQ(found[0].boundary, 0u);
  EXPECT_EQ(found[0].n_sources, 1u);
  EXPECT_NEAR(found[0].x_max, 4758.3095 * 4e-4, 1e-6);
  EXPECT_NEAR(found[0].dt_limit, 3.5472e-4, 1e-8);
  EXPECT_NEAR(found[0].dt_limit, vb1_source_threshold() / 4758.3095143, 1e-13);
}
