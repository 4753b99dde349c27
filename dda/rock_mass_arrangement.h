// Private to the rock mass generator (dda/rock_mass*.cc): the exact CGAL arrangement whose
// bounded faces become the blocks, and the steps of generate_blocks that work on it. Not part of
// the public API (dda/rock_mass.h); nothing outside dda/rock_mass*.cc includes it.
//
// The steps, in the order generate_blocks calls them:
// - dda/rock_mass_joint_traces.cc: joint_curves, append_polygon (the curves put in);
// - dda/rock_mass_faces.cc: settle (faces classified, islands cut), the boundary loops of a face;
// - dda/rock_mass_tidy.cc: tidy (short edges collapsed, straight vertices removed);
// - dda/rock_mass_slivers.cc: merge_pass (slivers merged into a neighbour);
// - dda/rock_mass_blocks.cc: make_block (a block face as a RockMassBlock).
// Before: dda/rock_mass_size.cc, the estimates that refuse a rock mass too large to generate.
#pragma once

#include "common/format.h"
#include "dda/rock_mass.h"

#include <CGAL/Arr_consolidated_curve_data_traits_2.h>
#include <CGAL/Arr_extended_dcel.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

#include <cstddef>
#include <string>
#include <vector>

namespace ddafem::dda::rock_mass_internal
{
using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using ExactPoint = Kernel::Point_2;
using Segment = Kernel::Segment_2;

/// What an arrangement edge lies on. Where curves overlap (a joint along the region's boundary,
/// an opening touching a joint), the edge carries all of them.
struct CurveSource
{
  enum class Kind
  {
    region,
    opening,
    joint_set,
    explicit_joint,
    island_cut ///< added so that no block encloses an island (see settle)
  };
  Kind kind = Kind::region;
  std::size_t index = 0; ///< of the opening, joint set or explicit joint

  bool operator==(const CurveSource& other) const
  {
    return kind == other.kind && index == other.index;
  }
};

/// Classification of a face by the walk in settle().
struct FaceInfo
{
  bool visited = false;
  bool in_region = false;
  std::vector<bool> in_opening; ///< one flag per opening
  bool block = false;           ///< in the region and in no opening
  std::size_t index = 0;        ///< position in the arrangement's face list (tie breaks)
};

using SegmentTraits = CGAL::Arr_segment_traits_2<Kernel>;
using Traits = CGAL::Arr_consolidated_curve_data_traits_2<SegmentTraits, CurveSource>;
using Arrangement = CGAL::Arrangement_2<Traits, CGAL::Arr_face_extended_dcel<Traits, FaceInfo>>;
using Face = Arrangement::Face_handle;
using Halfedge = Arrangement::Halfedge_handle;
using Ccb = Arrangement::Ccb_halfedge_circulator;

// ---- Points, numbers and edges (dda/rock_mass_arrangement.cc) ----------------------------------

ExactPoint exact_point(const Point& p);
/// The point in double (within an ulp); blocks that share a vertex get the same one.
Point rounded(const ExactPoint& p);
/// The point in double from its interval approximation, without computing it exactly: for
/// tolerances far above rounding.
Point approximate(const ExactPoint& p);

/// An axis-aligned box [m].
struct Box
{
  Point lower = Point::Zero(); ///< smallest x and y
  Point upper = Point::Zero(); ///< largest x and y
};

/// The smallest box around the points (at least one).
Box bounding_box(const std::vector<Point>& points);
/// The region's extent in x or y, the larger [m].
double extent(const std::vector<Point>& region);

/// Length of an edge [m], in double.
double length(Halfedge h);
/// Whether an edge lies on the region's or an opening's boundary: those stay where they are.
bool on_boundary(Halfedge h);
/// What the edge lies on.
std::vector<CurveSource> sources(Halfedge h);

// ---- Curves (dda/rock_mass_joint_traces.cc) ----------------------------------------------------

/// Every trace of every joint set and every explicit joint, clipped to the region's bounding
/// box. (Pieces inside the box but outside a polygonal region bound only faces outside it.)
std::vector<Traits::Curve_2> joint_curves(const RockMassDescription& d);

/// Appends the closed polygon's edges as curves.
void append_polygon(const std::vector<Point>& polygon, CurveSource source,
                    std::vector<Traits::Curve_2>& curves);

// ---- Faces (dda/rock_mass_faces.cc) ------------------------------------------------------------

/// Calls visit(h) for every halfedge on the boundary of f (outer and inner boundaries), with
/// f on its left.
template <typename Visit>
void for_each_halfedge(Face f, Visit&& visit)
{
  const auto visit_ccb = [&](Ccb first)
  {
    Ccb h = first;
    do
      visit(Halfedge(h));
    while (++h != first);
  };
  if (f->has_outer_ccb())
    visit_ccb(f->outer_ccb());
  for (auto inner = f->inner_ccbs_begin(); inner != f->inner_ccbs_end(); ++inner)
    visit_ccb(*inner);
}

/// Area of a face [m^2], exact: its outer boundary minus what its inner boundaries enclose.
Kernel::FT face_area(Face f);

/// The halfedges on f's boundaries that separate it from other faces (not the dangling joint
/// traces and the bridges to islands, which have f on both sides).
std::vector<Halfedge> separating_halfedges(Face f);

/// The boundary of f as simple loops of separating halfedges: the outer loop (anticlockwise)
/// and a loop around each island (clockwise).
std::vector<std::vector<Halfedge>> boundary_loops(Face f);

/// Classifies the faces (FaceInfo) and cuts islands until every block face is simple; returns
/// the number of island cuts (RockMassStatistics::n_island_cuts).
std::size_t settle(Arrangement& arrangement, std::size_t n_openings);

// ---- Slivers (dda/rock_mass_slivers.cc) --------------------------------------------------------

/// The size criteria of a sliver.
struct SliverCriteria
{
  double min_area = 0.0;             ///< [m^2]
  double min_inscribed_radius = 0.0; ///< [m]

  /// area [m^2], perimeter [m]
  bool is_sliver(double area, double perimeter) const
  {
    return area < min_area || 2.0 * area / perimeter < min_inscribed_radius;
  }
};

/// One pass of merging: each sliver (smallest first) whose neighbouring block with the longest
/// shared boundary was not involved in a merge of this pass is joined to it by removing the
/// edges they share. Returns the number of merges; the faces must be classified again after one.
std::size_t merge_pass(Arrangement& arrangement, const SliverCriteria& criteria);

// ---- Short edges and straight vertices (dda/rock_mass_tidy.cc) ---------------------------------

/// The thresholds of tidy().
struct EdgeCriteria
{
  double min_length = 0.0;     ///< edges shorter than this are collapsed [m]
  double straight_angle = 0.0; ///< vertices within this of 180 degrees are straight [rad]
};

/// What one tidy() did.
struct TidyCounts
{
  std::size_t n_collapsed = 0; ///< short edges collapsed
  std::size_t n_straight = 0;  ///< straight vertices removed
  bool changed() const { return n_collapsed + n_straight > 0; }
};

/// Moves vertices of the arrangement so that no block edge is shorter than min_length, and
/// removes the straight vertices where only two faces meet (see the file comment of
/// dda/rock_mass_tidy.cc). The faces must be classified; they must be again if anything changed.
TidyCounts tidy(Arrangement& arrangement, const EdgeCriteria& criteria);

// ---- Blocks (dda/rock_mass_blocks.cc) ----------------------------------------------------------

/// The block of a block face whose boundary is one simple loop (as settle() leaves them);
/// vertices within straight_tolerance [m] of the line between their neighbours are dropped.
/// Throws InputError if the face's boundary is not one simple loop.
RockMassBlock make_block(Face f, double straight_tolerance);

} // namespace ddafem::dda::rock_mass_internal
