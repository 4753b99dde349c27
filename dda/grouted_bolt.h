// Grouted (fully bonded) rock bolts (issue 21): a steel bar bonded along its length to every
// block it crosses. Where it crosses a block boundary it acts as a spring between the two
// blocks' material points at the crossing, axial (along the bar) and shear/dowel (across it),
// each perfectly plastic, and ruptures. The law is pure functions of the crossing's relative
// displacement; the crossings are found geometrically at t = 0 (docs/support.md). GroutedBolts
// carries them on the blocks as an element kind (dda/element.h).
#pragma once

#include "common/enum_names.h"
#include "dda/block.h"
#include "dda/bolt.h"
#include "dda/element.h"

#include <array>
#include <limits>
#include <string>
#include <vector>

namespace ddafem::dda
{
/// How a bolt is attached to the rock.
enum class BoltType
{
  end_anchored, ///< at its head and anchor only: an axial spring between them (dda/bolt.h)
  grouted       ///< bonded along its length: a spring at every block boundary it crosses
};

constexpr std::array<EnumName<BoltType>, 2> enum_names(BoltType)
{
  return {{{BoltType::end_anchored, "end_anchored"}, {BoltType::grouted, "grouted"}}};
}

/// Where a bolt's line from head to anchor passes from one block into the next, at t = 0.
struct BoltCrossing
{
  std::size_t block_a = 0;     ///< the block on the head's side
  std::size_t block_b = 0;     ///< the block on the anchor's side
  Point point = Point::Zero(); ///< on the common boundary [m]
  double distance = 0.0;       ///< from the head along the bolt [m]
};

/// The crossings of the segment head -> anchor through the polygons (anticlockwise, the blocks
/// at t = 0), in order from the head: the stretches of the segment inside each polygon are
/// sorted along it, and each two consecutive stretches of different blocks that meet (within
/// `tol` [m]) make a crossing. `gap` returns the first stretch of the segment between head and
/// anchor that lies in no block (its start and end distance from the head [m]), or [0, 0]
/// if there is none; the segment's parts outside every block are not crossings.
std::vector<BoltCrossing> find_bolt_crossings(const std::vector<std::vector<Point>>& polygons,
                                              const Point& head, const Point& anchor, double tol,
                                              std::array<double, 2>* gap = nullptr);

/// Properties of one grouted bolt's crossings (all crossings of a bolt share them).
struct GroutedBoltLaw
{
  double axial_stiffness = 0.0; ///< k_a = E_s A_s / L_d [N/m]
  double shear_stiffness = 0.0; ///< k_s = K / (4 beta), the dowel's (dowel_shear_stiffness) [N/m]
  double pretension = 0.0;      ///< N at zero opening as installed [N], in [0, yield_force)
  double yield_force = 0.0;     ///< axial capacity Y [N]
  double shear_capacity = 0.0;  ///< dowel capacity S_y [N]
  double debonded_length = 0.0; ///< L_d: the bar's deformable length across the joint [m]
  /// The bar ruptures when the steel over L_d stretches by more than this [m] (rupture strain
  /// x L_d).
  double rupture_elongation = 0.0;
};

/// The dowel stiffness [N/m] of a bar of modulus E_s [Pa] and area A_s [m^2] (a solid round
/// bar: d = sqrt(4 A_s / pi), I = pi d^4 / 64) in grout and rock of foundation modulus K [Pa]
/// (force per unit length per unit deflection): each side of the joint is a semi-infinite beam
/// on an elastic foundation (Hetényi) loaded at its end by the shear force S and free to
/// rotate there (the joint is the antisymmetric bar's inflection point), which deflects
/// 2 S beta / K, beta = (K / (4 E_s I))^(1/4); the two sides together: k_s = K / (4 beta).
double dowel_shear_stiffness(double youngs_modulus, double area, double foundation_modulus);

/// The law of a grouted bolt's crossings: k_a = E_s A_s / L_d and k_s = dowel_shear_stiffness.
GroutedBoltLaw make_grouted_bolt_law(double youngs_modulus, double area, double foundation_modulus,
                                     double debonded_length, double pretension, double yield_force,
                                     double shear_capacity, double rupture_strain);

/// A crossing's state and forces. With e the bolt's unit direction from head to anchor and
/// t = (-e_y, e_x), the relative displacement of the anchor side's material point from the head
/// side's is delta = opening e + slip t. The axial force N (tension positive) and the shear
/// force S (positive when slip is) act +N e + S t on the head side's block and -N e - S t on
/// the anchor side's: they resist the opening and the slip.
struct CrossingForces
{
  BoltState state = BoltState::elastic; ///< ruptured, else yielding if either part is, else
                                        ///< slack if it carries nothing (axial part slack,
                                        ///< S = 0), else elastic
  bool axial_elastic = true;            ///< 0 < N < Y: the axial part has its stiffness
  bool shear_elastic = true;            ///< |S| < S_y: the shear part has its stiffness
  double axial_force = 0.0;             ///< N [N], >= 0
  double shear_force = 0.0;             ///< S [N], signed like the slip
  double plastic_opening = 0.0;         ///< accumulated axial plastic displacement [m]
  double plastic_slip = 0.0;            ///< accumulated shear plastic displacement [m]
};

/// The crossing's forces at opening and slip [m] (total, since t = 0), from its state before:
/// - ruptured stays ruptured; hypot(L_d + opening, slip) - L_d > rupture_elongation ruptures
///   it (the steel over L_d stretched as the hypotenuse): N = S = 0;
/// - axial: trial N = P + k_a (opening - plastic_opening); above Y it yields (N = Y, the plastic
///   opening grows), below 0 it is slack (N = 0: the grout and the joint's faces take
///   compression), else elastic;
/// - shear: trial S = k_s (slip - plastic_slip); beyond +-S_y it yields (S = +-S_y), else elastic.
/// The state: ruptured; else yielding if either part yields; else slack if it carries nothing
/// (the axial part slack and S = 0); else elastic (a closing joint's dowel: N = 0, S acts).
/// The two parts are independent (no interaction surface).
CrossingForces evaluate_crossing(const GroutedBoltLaw& law, const CrossingForces& start,
                                 double opening, double slip);

/// Elastic energy stored at a crossing [J]: N^2 / (2 k_a) + S^2 / (2 k_s).
double crossing_energy(const GroutedBoltLaw& law, const CrossingForces& forces);

/// Extremes and events of a crossing's history.
struct CrossingRecord
{
  double max_axial_force = 0.0; ///< largest N [N]
  double max_shear_force = 0.0; ///< largest |S| [N]
  double max_opening = 0.0;     ///< largest opening [m] (0 if it only closed)
  double max_slip = 0.0;        ///< largest |slip| [m]
  /// Time of the first step that ended yielding, and of the rupture [s]; NaN if never.
  double yield_time = std::numeric_limits<double>::quiet_NaN();
  double rupture_time = std::numeric_limits<double>::quiet_NaN();
};

/// The record after a step that ended at time t [s]; frozen after the rupture.
CrossingRecord record_crossing(const CrossingRecord& before, const CrossingForces& forces,
                               double opening, double slip, double t);

/// One crossing of a grouted bolt installed on the blocks.
struct GroutedCrossing
{
  MaterialPoint on_a; ///< the crossing point as a material point of the head side's block
  MaterialPoint on_b; ///< the same point as a material point of the anchor side's block
  CrossingForces forces;
  CrossingRecord record;

  /// The relative displacement x_b - x_a [m] (zero at t = 0).
  Vector2 relative_displacement() const { return on_b.position - on_a.position; }
};

/// A grouted bolt installed on the blocks: its ends (for its direction and its drawing) and its
/// crossings in order from the head.
struct GroutedBolt
{
  std::string name;
  MaterialPoint head;
  MaterialPoint anchor;
  GroutedBoltLaw law;
  std::vector<GroutedCrossing> crossings;

  /// Unit vector from head to anchor, at the current positions or, with `initial`, at t = 0.
  Vector2 direction(bool initial = false) const;
  /// A crossing's (opening, slip) [m] along the bolt's direction (`initial`: of t = 0).
  std::array<double, 2> opening_and_slip(const GroutedCrossing& c, bool initial = false) const;
};

/// The scene's grouted bolts as an element kind (dda/element.h): each crossing a spring between
/// the two blocks' material points at the crossing, in the bolt's frame (e along the bolt from
/// head to anchor, t = (-e_y, e_x)), linearised about the step start like the end-anchored bolts.
class GroutedBolts : public ElementKind
{
public:
  /// Each grouted bolt of the model (ModelDescription::bolts) onto its blocks' material points
  /// at its crossings; throws InputError for one that crosses no block boundary.
  explicit GroutedBolts(const ModelDescription& model);
  /// In scene order, with their crossings' state at the last accepted step.
  const std::vector<GroutedBolt>& all() const { return grouted_bolts; }

  void add_couplings(std::vector<std::pair<std::size_t, std::size_t>>& pairs) const override;
  bool changes_stiffness() const override { return !grouted_bolts.empty(); }
  /// Force F = N e + S t on the head side's block a, -F on the anchor side's b; while a part is
  /// elastic its stiffness on the relative displacement T_b d_b - T_a d_a.
  void assemble(const ElementHost& host, StepEquations& step, bool with_matrix) const override;
  void add_loads(const std::function<void(std::size_t, double)>& add) const override;
  void move_points(const ElementHost& host, const Eigen::VectorXd& d) override;
  /// Each crossing's state and record (evaluate_crossing, record_crossing).
  void update(const ElementHost& host, double t) override;
  void add_held_blocks(const std::function<void(std::size_t)>& hold) const override;
  void add_energy(double& energy) const override;
  void save(CheckpointOut& archive) const override;
  void load(CheckpointIn& archive) override;

private:
  std::vector<GroutedBolt> grouted_bolts;
};

} // namespace ddafem::dda
