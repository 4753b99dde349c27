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

/// State of a contact point as written for ParaView (the VTU stores the integer values).
enum class ContactPointState
{
  open = 0,
  slide = 1,
  lock = 2,
  bonded = 3 ///< an end spring of an intact bonded joint
};

/// One contact point at one time: a vertex-edge contact, or an end of a bonded joint.
struct ContactSnapshot
{
  std::size_t id = 0;      ///< contact id (stable while it exists); for joint ends the joint id
  std::size_t block_a = 0; ///< the vertex's block (joint: its first block)
  std::size_t block_b = 0; ///< the edge's block (joint: its second block)
  ContactPointState state = ContactPointState::open;
  Point position = Point::Zero();   ///< the vertex (joint: the end point on block a) [m]
  Vector2 normal = Vector2::Zero(); ///< unit normal out of the edge's block (joint: out of a)
  double normal_force = 0.0;        ///< [N], compression positive
  double shear_force = 0.0;         ///< [N], along the edge tangent (see ContactForces)
  double gap = 0.0;                 ///< normal opening [m], negative: penetration
  double slip = 0.0;                ///< accumulated sliding [m]
};

} // namespace ddafem::dda
