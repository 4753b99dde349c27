// Plain records of the model state handed to writers (VTU, HDF5) and to the command line.
#pragma once

#include "dda/types.h"

#include <cstddef>
#include <vector>

namespace ddafem::dda
{
/// State of one block at one time, in the current (deformed) configuration.
struct BlockSnapshot
{
  std::size_t id = 0;                     ///< block index, stable over the run
  std::size_t material = 0;               ///< material index
  std::vector<Point> vertices;            ///< current vertices [m], anticlockwise
  Vector2 displacement = Vector2::Zero(); ///< total displacement of the centroid since t = 0 [m]
  Vector2 velocity = Vector2::Zero();     ///< velocity of the centroid [m/s]
  Voigt stress = Voigt::Zero();           ///< (sxx, syy, sxy) [Pa], tension positive
};

} // namespace ddafem::dda
