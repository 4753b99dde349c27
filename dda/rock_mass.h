// Rock mass generation: the blocks of a region cut by joint sets and explicit joints, with
// openings excavated. Pure geometry (no model, no scene): a description in, block polygons out.
//
// The blocks are the bounded faces of a CGAL 2D arrangement (exact kernel) of the region's
// boundary, the openings' boundaries and every joint trace; a face is a block when it lies
// inside the region and outside every opening. Joint traces that end inside a face (the tips of
// non-persistent joints) are dangling edges of that face: they are left out of its polygon, so
// the rock between collinear traces (the bridge) stays intact.
//
// Exact arithmetic on rounded input keeps coincidences that hold only in real numbers apart: a
// joint through the centre of a circular opening passes a corner of its polygon at 1e-16 m
// (both were rounded to double), and the exact arrangement keeps the 2e-16 m edge between the
// corner and the crossing. Joints that cross close to each other, to a corner or to the region's
// boundary leave short edges too, and merged slivers leave nearly straight vertices. DDA bounds
// each step's displacement by a tenth of the shortest edge, so generate_blocks treats the
// arrangement before it makes blocks (min_edge_length, straight_angle): it collapses every edge
// shorter than min_edge_length by merging its two vertices into one (the vertex is shared by all
// the faces around it, so neighbours move together: no gap, no overlap), keeping the region's
// and the openings' boundaries in place (their corners stay, vertices on them slide along
// them), and it removes vertices where only two blocks meet and both are straight within
// straight_angle.
#pragma once

#include "common/enum_names.h"
#include "common/resource_limits.h"
#include "dda/types.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace ddafem::dda
{
/// Distribution of a random perturbation xi of mean 0.
enum class Distribution
{
  uniform, ///< xi uniform in [-1, 1]
  normal   ///< xi standard normal (mean 0, standard deviation 1)
};

constexpr std::array<EnumName<Distribution>, 2> enum_names(Distribution)
{
  return {{{Distribution::uniform, "uniform"}, {Distribution::normal, "normal"}}};
}

/// Random perturbation of a joint set by independent draws xi, one for each gap between
/// neighbouring lines and one for each line's traces.
struct JointPerturbation
{
  /// The gap between consecutive joint lines is spacing (1 + this xi) [-], in [0, 1). Gaps
  /// below 0.1 spacing are drawn again (a truncated normal distribution).
  double spacing = 0.0;
  /// Each line's pattern of traces and bridges is shifted along the line by this xi times its
  /// period (trace_length + bridge) [-], >= 0. No effect on persistent sets.
  double position = 0.0;
  Distribution distribution = Distribution::uniform;
};

/// A set of parallel joints. The traces run along d = (cos dip, sin dip); their normal is
/// n = (-sin dip, cos dip). Joint line k (k = 0, +-1, +-2, ...) is {x : n.x = c_k}, with
/// c_0 = offset and c_k - c_(k-1) = spacing (unperturbed). On line k, along t = d.x, trace j
/// covers [phase_k + j P, phase_k + j P + trace_length] with the period P = trace_length +
/// bridge and phase_k = (k mod 2) P / 2 (neighbouring lines staggered by half a period, like
/// brickwork), plus the position perturbation.
struct JointSet
{
  double dip = 0.0;     ///< angle of the traces from the +x axis, anticlockwise [deg]
  double spacing = 0.0; ///< mean normal distance between neighbouring lines [m], > 0
  /// Length of each trace [m], > 0; ignored for a persistent set (bridge = 0).
  double trace_length = std::numeric_limits<double>::infinity();
  /// Intact rock between collinear traces [m], >= 0; 0: persistent (traces cross the region).
  double bridge = 0.0;
  double offset = 0.0; ///< c_0: normal position of line 0 [m], n.x = offset
  JointPerturbation perturbation;

  /// Persistence, the jointed fraction of a line, is trace_length / (trace_length + bridge).
  bool persistent() const { return bridge == 0.0; }
};

/// A single joint: the segment from `from` to `to` [m].
struct ExplicitJoint
{
  Point from = Point::Zero();
  Point to = Point::Zero();
};

/// An opening to excavate: exactly one of the shapes, chosen by `shape`.
struct Opening
{
  enum class Shape
  {
    circle,    ///< centre, radius; a polygon inscribed in the circle
    horseshoe, ///< floor centre, width, wall height: straight walls and a semicircular roof
    polygon    ///< vertices
  };
  Shape shape = Shape::circle;
  Point center = Point::Zero(); ///< circle: its centre; horseshoe: middle of the floor [m]
  double radius = 0.0;          ///< circle [m], > 0
  double width = 0.0;           ///< horseshoe: floor width = roof diameter [m], > 0
  double wall_height = 0.0;     ///< horseshoe: straight walls from floor to roof springline [m]
  std::vector<Point> vertices;  ///< polygon: a simple polygon, either orientation [m]
};

/// What happens to blocks below the size threshold.
enum class SliverAction
{
  /// merged into the neighbouring block with which they share the longest boundary; a sliver
  /// without a neighbouring block is reported
  merge,
  report ///< kept and listed in RockMassResult::slivers
};

constexpr std::array<EnumName<SliverAction>, 2> enum_names(SliverAction)
{
  return {{{SliverAction::merge, "merge"}, {SliverAction::report, "report"}}};
}

/// When a block is a sliver: area below min_area, or 2 A / perimeter (the radius of the
/// inscribed circle of a triangle or a regular polygon, half the width of a long strip) below
/// min_inscribed_radius.
struct SliverSettings
{
  /// [m^2]; none: min_area_fraction x (mean spacing of the joint sets)^2 (0 without sets)
  std::optional<double> min_area;
  double min_area_fraction = 0.01;   ///< [-], see min_area
  double min_inscribed_radius = 0.0; ///< [m]; 0: no width criterion
  SliverAction action = SliverAction::merge;
};

/// A rock mass: region, joints, openings and how slivers are treated.
struct RockMassDescription
{
  std::vector<Point> region; ///< simple polygon, either orientation [m]
  std::vector<JointSet> joint_sets;
  std::vector<ExplicitJoint> joints;
  std::vector<Opening> openings; ///< may overlap one another; their union is excavated
  /// Largest distance between a circular arc and its chords [m], > 0 (circles, horseshoe roofs)
  double chord_tolerance = 0.01;
  std::uint64_t seed = 0; ///< of the random perturbations
  SliverSettings slivers;
  /// No block edge is shorter [m], >= 0 (see generate_blocks); none: 0.01 x the mean spacing of
  /// the joint sets, or chord_tolerance without sets. Never below 1e-9 x the region's extent:
  /// shorter edges are rounding artefacts.
  std::optional<double> min_edge_length;
  /// A vertex where only two blocks meet is removed when its angle is within this of 180
  /// degrees [deg], in [0, 90): the contacts' angle tolerance treats it as straight anyway.
  double straight_angle = 1.0;
};

/// The joint an edge of a generated block lies on.
struct EdgeJoint
{
  enum class Kind
  {
    /// on no joint: the region's or an opening's boundary (even where a joint runs along it),
    /// or an edge that is no trace (a vertical cut around an island)
    none,
    joint_set,     ///< a trace of RockMassDescription::joint_sets[index]
    explicit_joint ///< RockMassDescription::joints[index]
  };
  Kind kind = Kind::none;
  std::size_t index = 0;

  bool operator==(const EdgeJoint& other) const
  {
    return kind == other.kind && (kind == Kind::none || index == other.index);
  }
};

/// One generated block.
struct RockMassBlock
{
  /// Anticlockwise from the lowest vertex (smallest y, then x), not closed, no two consecutive
  /// edges collinear [m].
  std::vector<Point> vertices;
  double area = 0.0; ///< [m^2] (exact, then rounded)
  /// Indices of the joint sets with a trace along some edge of the block, ascending.
  std::vector<std::size_t> joint_sets;
  bool explicit_joint = false;  ///< an explicit joint along some edge
  bool region_boundary = false; ///< some edge on the region's boundary
  /// Indices of the openings whose boundary runs along some edge, ascending.
  std::vector<std::size_t> openings;
  /// One per edge (edge k from vertex k to vertex k + 1): the joint it lies on. An edge is one
  /// or more pieces of the arrangement (where a neighbour's vertex meets it, or a dropped
  /// vertex was straight to rounding), each on one joint (where joints overlap: explicit joints
  /// before sets, lower index first) or on none (on the region's or an opening's boundary, or
  /// no joint); the edge is on the one its pieces cover most of. Edges moved by the short-edge
  /// collapse or joined at a removed straight vertex keep the joints of the edges they came
  /// from.
  std::vector<EdgeJoint> edge_joints;
};

/// A block below the size threshold that was kept: reported, or could not be merged.
struct Sliver
{
  std::size_t block = 0; ///< index into RockMassResult::blocks
  Point centroid = Point::Zero();
  double area = 0.0;             ///< [m^2]
  double inscribed_radius = 0.0; ///< 2 A / perimeter [m]
};

struct RockMassStatistics
{
  std::size_t n_blocks = 0;
  double smallest_area = 0.0;  ///< [m^2]
  double mean_area = 0.0;      ///< [m^2]
  double total_area = 0.0;     ///< sum of the block areas [m^2]
  double region_area = 0.0;    ///< [m^2]
  double excavated_area = 0.0; ///< region inside some opening's polygon [m^2]
  double min_area = 0.0;       ///< the sliver threshold used [m^2]
  std::size_t n_traces = 0;    ///< joint segments inserted (sets and explicit joints)
  std::size_t n_merged = 0;    ///< slivers merged into a neighbour
  std::size_t n_reported = 0;  ///< slivers kept (the size of RockMassResult::slivers)
  /// Vertical cuts added so that no block encloses an opening or other blocks (a block must be
  /// a simple polygon): two per enclosed island, from its top and bottom to the block boundary.
  std::size_t n_island_cuts = 0;
  double min_edge_length = 0.0;        ///< the short-edge threshold used [m]
  double shortest_edge = 0.0;          ///< of all blocks, after rounding [m]
  std::size_t n_collapsed_edges = 0;   ///< short edges collapsed (their ends made one vertex)
  std::size_t n_straight_vertices = 0; ///< straight vertices between two blocks removed
  /// Block edges still shorter than min_edge_length (one count per block that has it): only
  /// where both ends are pinned to the region's or the openings' boundaries, e.g. a corner of an
  /// opening closer than min_edge_length to the region's boundary.
  std::size_t n_short_edges = 0;
};

struct RockMassResult
{
  std::vector<RockMassBlock> blocks; ///< ordered by centroid, bottom row first, then by x
  /// The openings as excavated: polygons (circles and roofs as chords), anticlockwise [m].
  std::vector<std::vector<Point>> openings;
  std::vector<Sliver> slivers;
  RockMassStatistics statistics;
};

/// The polygon of an opening, anticlockwise [m]: a circle becomes the inscribed regular polygon
/// with the fewest sides (at least 8) whose chords stay within chord_tolerance of the arc,
/// radius (1 - cos(pi / N)) <= chord_tolerance; the horseshoe's roof likewise (at least 4
/// chords).
std::vector<Point> opening_polygon(const Opening& opening, double chord_tolerance);

/// The most sides opening_polygon makes (it throws InputError beyond, and refuse_opening refuses
/// a tolerance that asks for more): 5000 chords miss a circle by 2e-7 of its radius (0.6
/// micrometres on 3 m; a rock engineer's 1 mm on a 20 m cavern takes 314). Beyond, the blocks
/// around the opening take seconds to set up (their joints and keyblocks compare vertices in
/// pairs: a circle of 38,500 chords took 8 s to check).
constexpr double max_opening_sides = 5000;

/// The number of vertices opening_polygon gives the opening, without making them.
double opening_side_count(const Opening& opening, double chord_tolerance);

/// The blocks of a rock mass (see the file comment). Throws InputError for a description that
/// cannot be generated (non-positive spacing, a region or opening that is not a simple polygon,
/// a block whose boundary touches itself, ...).
///
/// After the faces are classified and islands cut, rounds of (a) short-edge and straight-vertex
/// treatment and (b) sliver merging repeat until neither changes anything (a collapse can fold
/// a small face over, which the next round removes; a merge can leave a straight vertex):
/// 1. Each edge shorter than min_edge_length with a block on one side, shortest first, joins its
///    vertices into one cluster unless they are pinned apart: a corner of the region or an
///    opening (or where two boundaries cross) cannot move; a vertex on one boundary line moves
///    only along it. Each cluster moves to its member that satisfies its pin and is nearest to
///    the others; only the edges that moved are taken out of the arrangement and put in again,
///    exactly. The blocks' areas still add up to the region minus the openings.
/// 2. A vertex off the boundaries where only two faces meet, straight within straight_angle on
///    both sides, is removed: its two edges become one for both blocks.
/// Edges left shorter than the threshold (both ends pinned, e.g. an opening's corner near the
/// region's boundary) are counted in RockMassStatistics::n_short_edges. A vertex that a
/// rounding-sized move left straight to rounding (within 1e-14 of the region's extent) in one
/// block is dropped from that block only, as where a neighbour's vertex meets its edge.
RockMassResult generate_blocks(const RockMassDescription& description);

/// About how many blocks generate_blocks makes, without making them (to refuse a scene too large
/// for memory before the arrangement is built): a line arrangement has about one face per
/// crossing, and sets i and j cross A |sin(dip_i - dip_j)| k_i k_j / (s_i s_j) times in a region
/// of area A (spacings s, persistences k = trace_length / (trace_length + bridge)); plus a face
/// per trace and the region itself. Explicit joints and openings change it little. Within 1 %
/// of the count generated for two persistent sets (tested).
double estimate_block_count(const RockMassDescription& description);

/// About how large the arrangement generate_blocks builds is: its memory (and time) grow with its
/// edges, which traces of non-persistent sets and curved openings multiply without adding blocks
/// (a set of 2 mm traces and bridges in a 40 m square puts 80,000 traces in it).
struct ArrangementEstimate
{
  double listed = 0.0;        ///< the region's sides, polygon openings' sides, explicit joints
  double curved_sides = 0.0;  ///< the sides of the circles and horseshoes (chord_tolerance)
  std::vector<double> traces; ///< per joint set: lines across the region, and for a
                              ///< non-persistent set A / (s (trace_length + bridge)) more
  double crossings = 0.0;     ///< of traces of two sets, as in estimate_block_count
  /// The edges: every side, joint and trace, and two per crossing (each splits two edges).
  double edges() const;
};
ArrangementEstimate estimate_arrangement(const RockMassDescription& description);

/// A rock mass estimated to need more memory than `limits` allow (with `n_other_blocks` beside
/// it), and the key that drives the size: the blocks ("about N blocks would need ...: expected a
/// spacing of at least S m (with the other sets' spacings scaled alike)", from blocks ~ 1 /
/// spacing^2), or the arrangement's edges (the part of them that is largest: a set's traces ~ 1
/// / (trace_length + bridge), the curved openings' sides ~ 1 / sqrt(chord_tolerance), the
/// crossings ~ 1 / spacing^2, or the listed joints and vertices).
struct RockMassTooLarge
{
  enum class Key
  {
    spacing,         ///< joint_sets[joint_set].spacing
    trace_length,    ///< joint_sets[joint_set].trace_length (with its bridge)
    chord_tolerance, ///< the rock mass's chord_tolerance
    joints           ///< the explicit joints (or the polygons' vertices)
  };
  Key key = Key::spacing;
  std::size_t joint_set = 0;
  std::string message;
};
/// The scene keys a refusal names (spacing and trace_length within joint_sets[joint_set]).
constexpr std::array<EnumName<RockMassTooLarge::Key>, 4> enum_names(RockMassTooLarge::Key)
{
  using Key = RockMassTooLarge::Key;
  return {{{Key::spacing, "spacing"},
           {Key::trace_length, "trace_length"},
           {Key::chord_tolerance, "chord_tolerance"},
           {Key::joints, "joints"}}};
}
/// The refusal of a rock mass beyond `limits`, before it is generated; none if it fits.
std::optional<RockMassTooLarge> refuse_beyond(const RockMassDescription& description,
                                              std::size_t n_other_blocks,
                                              const ResourceLimits& limits);
/// The refusal of one circle or horseshoe whose polygon alone has more than max_opening_sides
/// sides or is beyond `limits` (before it is made): "within a chord tolerance of T m its arcs
/// have N sides, more than the 5000 an opening may have (...)" or "..., which would need ...",
/// then ": expected a chord_tolerance of at least T' m"; none if it fits, or for a polygon.
std::optional<std::string> refuse_opening(const Opening& opening, double chord_tolerance,
                                          const ResourceLimits& limits);

} // namespace ddafem::dda
