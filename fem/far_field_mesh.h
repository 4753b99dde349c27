// Meshes of the far field: a rectangle, a rectangle with a graded hole, or a Gmsh file.
#pragma once

#include "fem/far_field_description.h"

#include <deal.II/base/types.h>
#include <deal.II/grid/tria.h>

namespace ddafem::fem
{
/// Boundary id of a part in every far-field mesh (left 0, right 1, bottom 2, top 3, hole 4).
dealii::types::boundary_id boundary_id_of(BoundaryPart part);

/// Boundary id of boundary lines a Gmsh file leaves untagged or tags with no part name (free).
constexpr dealii::types::boundary_id untagged_boundary_id = 5;

/// Builds the far-field mesh into the empty `mesh`:
/// - no hole, no file: `subdivided_hyper_rectangle` with elements of at most `far_size`;
/// - a hole: an O-grid of quadrilaterals between the hole and a box about twice its size, a
///   Cartesian grid of elements of at most `far_size` outside the box, then local refinement
///   (hanging nodes; neighbours differ by at most one level at vertices) until every element's
///   longest edge is at most min(far_size, h_hole + (growth_ratio - 1) d), d the distance of its
///   centre from the hole;
/// - a Gmsh file (`description.mesh_file`): read with GridIn, physical line tags mapped to parts.
/// Boundary ids follow boundary_id_of(). Throws InputError for a hole that does not fit or a
/// file that cannot be read or names unknown tags. A parallel::distributed::Triangulation
/// (built with limit_level_difference_at_vertices for a hole) gets the same graded mesh: every
/// rank grades its own cells, collectively.
void make_far_field_mesh(const FarFieldDescription& description, double far_size,
                         dealii::Triangulation<2>& mesh);

/// Distance [m] of (x, y) from the boundary of the description's hole (negative inside it);
/// +infinity without a generated hole.
double distance_from_hole(const HoleDescription& hole, double x, double y);

} // namespace ddafem::fem
