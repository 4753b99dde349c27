// The far field (issue 5) builds on deal.II with Trilinos, HDF5 and UMFPACK from Debian; check
// that the configured stack is the one the design needs and that a mesh can be made.
#include <deal.II/base/config.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <gtest/gtest.h>

#ifndef DEAL_II_WITH_TRILINOS
#error "deal.II must be built with Trilinos (Amesos KLU, ML)"
#endif
#ifndef DEAL_II_WITH_HDF5
#error "deal.II must be built with HDF5"
#endif
#ifndef DEAL_II_WITH_UMFPACK
#error "deal.II must be built with UMFPACK"
#endif

TEST(DealIIStack, VersionAndMesh)
{
  EXPECT_EQ(DEAL_II_VERSION_MAJOR, 9);
  EXPECT_GE(DEAL_II_VERSION_MINOR, 4);
  dealii::Triangulation<2> mesh;
  dealii::GridGenerator::hyper_rectangle(mesh, dealii::Point<2>(0, 0), dealii::Point<2>(100, 50));
  mesh.refine_global(3);
  EXPECT_EQ(mesh.n_active_cells(), 64u);
}
