// A lining (issue 21): shotcrete or concrete on an opening's surface as 2D Euler-Bernoulli frame
// elements between nodes that are material points of the blocks they lie on (docs/support.md,
// "Lining"). The law is pure functions of the nodes' positions and rotations, no System;
// Linings carries them on the blocks as an element kind (dda/element.h).
//
// Units SI, per metre out of plane: forces [N/m], moments [N m/m], stresses [Pa]. An element
// runs from node a to node b; e = unit(x_b - x_a) is its chord and n = (-e_y, e_x) its left
// normal. Signs:
// - axial force N: tension positive;
// - end moments m_a, m_b: the anticlockwise moments the nodes apply to the element;
// - bending moment M(x) = EI v'' along the chord, M(0) = -m_a, M(L) = m_b; the fibre on the
//   +n side has the stress N / t - 6 M / t^2, the fibre on the -n side N / t + 6 M / t^2;
// - shear force V = dM/dx = (m_a + m_b) / L: the force along +n node a applies to the element.
#pragma once

#include "common/enum_names.h"
#include "dda/block.h"
#include "dda/element.h"

#include <array>
#include <limits>
#include <string>
#include <vector>

namespace ddafem::dda
{
/// The lining's section and strength (a rectangle of thickness t and unit width).
struct LiningSection
{
  double thickness = 0.0;            ///< t [m], > 0
  double youngs_modulus = 0.0;       ///< E [Pa], > 0
  double compressive_strength = 0.0; ///< f_c [Pa], > 0: the fibre stress may not fall below -f_c
  double tensile_strength = 0.0;     ///< f_t [Pa], > 0: the fibre stress may not exceed f_t
  /// f_v [Pa]: the largest shear stress 1.5 |V| / t may not exceed it; 0: not checked.
  double shear_strength = 0.0;

  double axial_stiffness() const { return youngs_modulus * thickness; } ///< EA [N/m]
  double bending_stiffness() const                                      ///< EI [N m]
  {
    return youngs_modulus * thickness * thickness * thickness / 12.0;
  }
};

/// What an element's capacity check found governing.
enum class LiningFailureMode
{
  tension,     ///< a fibre at the tensile strength
  compression, ///< a fibre at the compressive strength
  shear        ///< the section's shear stress at the shear strength
};

constexpr std::array<EnumName<LiningFailureMode>, 3> enum_names(LiningFailureMode)
{
  return {{{LiningFailureMode::tension, "tension"},
           {LiningFailureMode::compression, "compression"},
           {LiningFailureMode::shear, "shear"}}};
}

/// An element's deformation from its installed state in its chord's frame (co-rotational).
struct FrameDeformation
{
  double elongation = 0.0; ///< L - L0 [m]
  double rotation_a = 0.0; ///< node a's rotation relative to the chord's rotation [rad]
  double rotation_b = 0.0; ///< node b's rotation relative to the chord's rotation [rad]
};

/// An element's forces (see the signs at the top).
struct FrameForces
{
  double axial_force = 0.0;  ///< N [N/m]
  double shear_force = 0.0;  ///< V [N/m]
  double end_moment_a = 0.0; ///< m_a [N m/m]
  double end_moment_b = 0.0; ///< m_b [N m/m]

  double bending_moment_a() const { return -end_moment_a; } ///< M(0) [N m/m]
  double bending_moment_b() const { return end_moment_b; }  ///< M(L) [N m/m]
};

/// The textbook 2D Euler-Bernoulli frame stiffness [N/m, N, N m] of length L0 [m] in its local
/// dofs (u_a, v_a, theta_a, u_b, v_b, theta_b), u along the chord.
Matrix6 frame_stiffness_local(const LiningSection& section, double length0);

/// The same in global dofs (u_x, u_y, theta per node) for the chord direction `e`: R^T k R.
Matrix6 frame_stiffness_global(const LiningSection& section, double length0, const Vector2& e);

/// The co-rotational deformation of an element installed between xa0 and xb0 [m], now between
/// xa and xb, its nodes rotated by theta_a and theta_b [rad] since the installation.
FrameDeformation frame_deformation(const Point& xa0, const Point& xb0, const Point& xa,
                                   const Point& xb, double theta_a, double theta_b);

/// The forces of the deformation: N = EA u / L0, m_a = EI / L0 (4 theta_a + 2 theta_b),
/// m_b = EI / L0 (2 theta_a + 4 theta_b), V = (m_a + m_b) / L0.
FrameForces frame_forces(const LiningSection& section, double length0, const FrameDeformation& q);

/// The forces the element applies to its nodes in global dofs (f_x, f_y, m per node), for the
/// chord direction `e`: the negated end forces -N e + V n, m_a at a and N e - V n, m_b at b.
Vector6 forces_on_nodes(const FrameForces& f, const Vector2& e);

/// Elastic energy of the element [J/m]: EA u^2 / (2 L0) + 2 EI / L0 (theta_a^2 + theta_a theta_b
/// + theta_b^2).
double frame_energy(const LiningSection& section, double length0, const FrameDeformation& q);

/// The capacity check of a section: the utilisation is the largest of the extreme-fibre
/// stress N / t +- 6 M / t^2 at either end over f_t (tension) or -f_c (compression), and of
/// 1.5 |V| / t over f_v if f_v > 0.
struct LiningCheck
{
  double utilisation = 0.0;                            ///< demand / capacity [-]
  LiningFailureMode mode = LiningFailureMode::tension; ///< the governing check
};

LiningCheck check_lining_section(const LiningSection& section, const FrameForces& f);

/// State of an element.
enum class LiningElementState
{
  intact,      ///< elastic, utilisation <= 1
  broken,      ///< cracked through for good after its utilisation exceeded 1: carries nothing
  on_one_block ///< both nodes on one block: moves with it, carries nothing of its own
};

constexpr std::array<EnumName<LiningElementState>, 3> enum_names(LiningElementState)
{
  return {{{LiningElementState::intact, "intact"},
           {LiningElementState::broken, "broken"},
           {LiningElementState::on_one_block, "on_one_block"}}};
}

/// A node: a material point of the block it lies on, with that block's rotation since the
/// lining was installed.
struct LiningNode
{
  MaterialPoint point;
  Point installed = Point::Zero(); ///< position at the installation [m]
  double rotation = 0.0;           ///< [rad], anticlockwise, 0 at the installation
};

/// An element between nodes a and b (indices into Lining::nodes).
struct LiningElement
{
  std::size_t a = 0, b = 0;
  double length0 = 0.0; ///< chord length at the installation [m]
  LiningElementState state = LiningElementState::intact;
  FrameForces forces; ///< at the last accepted step
  LiningCheck check;  ///< of `forces`
  double max_utilisation = 0.0;
  double break_time = std::numeric_limits<double>::quiet_NaN(); ///< [s]; NaN while intact
};

/// The element's state, forces and check after a step that ended at time t [s] with the nodes
/// `a` and `b`: an intact element whose utilisation exceeds 1 breaks for good (forces 0).
void update_lining_element(LiningElement& element, const LiningSection& section,
                           const LiningNode& a, const LiningNode& b, double t);

/// A lining: nodes along a polyline and the elements between consecutive ones.
struct Lining
{
  std::string name;
  LiningSection section;
  std::vector<LiningNode> nodes;
  std::vector<LiningElement> elements;
  /// Installed at the start of this stage (0: from the start); before it carries nothing.
  std::size_t install_stage = 0;
  bool installed = false;
  double install_time = 0.0; ///< [s]
  /// The largest utilisation reached, when and where (element index) [-, s].
  double max_utilisation = 0.0;
  double max_utilisation_time = std::numeric_limits<double>::quiet_NaN();
  std::size_t max_utilisation_element = 0;
  /// The first element to break, when (NaN if none) and which.
  double first_break_time = std::numeric_limits<double>::quiet_NaN();
  std::size_t first_break_element = 0;

  /// Sets the reference of every node and element to the nodes' current positions.
  void install(double t);
  /// The element (index) of the largest current utilisation among the intact ones (0 if none).
  std::size_t worst_element() const;
  std::size_t n_broken() const;
};

/// One element of a lining in a snapshot (VTU): its nodes' current positions and its forces.
struct LiningElementSnapshot
{
  Point a = Point::Zero(), b = Point::Zero(); ///< [m]
  std::size_t lining = 0, element = 0;        ///< indices
  LiningElementState state = LiningElementState::intact;
  FrameForces forces;
  double utilisation = 0.0;
};

/// Every element of every lining (installed or not), in order.
std::vector<LiningElementSnapshot> lining_snapshot(const std::vector<Lining>& linings);

/// Nodes of a polyline: each leg from points[i] to points[i + 1] split into
/// ceil(leg / segment_length) equal parts [m].
std::vector<Point> lining_node_positions(const std::vector<Point>& points, double segment_length,
                                         bool closed);

/// The scene's linings as an element kind (dda/element.h): their nodes are material points of
/// the blocks they lie on, their intact elements frames between two blocks.
class Linings : public ElementKind
{
public:
  /// Attaches each lining's nodes (ModelDescription::linings) to their blocks; those of
  /// install_stage 0 are installed at t = 0. Throws InputError for a node outside every block.
  Linings(const ModelDescription& model, const ElementHost& host);
  /// In scene order, with their elements' state at the last accepted step.
  const std::vector<Lining>& all() const { return linings; }

  /// A lining installed at the start of this stage carries what happens from now on.
  void begin_stage(std::size_t stage, double t) override;
  void add_couplings(std::vector<std::pair<std::size_t, std::size_t>>& pairs) const override;
  bool changes_stiffness() const override { return !linings.empty(); }
  /// Each intact element between two blocks: its forces at the step start on its nodes' blocks
  /// and G^T K G with G = [T; r0] of each node (the frame's linear stiffness in the chord's
  /// current direction; small displacement: the installed one).
  void assemble(const ElementHost& host, StepEquations& step, bool with_matrix) const override;
  void add_loads(const std::function<void(std::size_t, double)>& add) const override;
  /// A node moves and turns with its block (r0).
  void move_points(const ElementHost& host, const Eigen::VectorXd& d) override;
  /// Each installed lining's elements from the moved nodes (update_lining_element), and its
  /// largest utilisation and first break.
  void update(const ElementHost& host, double t) override;
  void add_held_blocks(const std::function<void(std::size_t)>& hold) const override;
  void add_energy(double& energy) const override;
  void save(CheckpointOut& archive) const override;
  void load(CheckpointIn& archive) override;

private:
  std::vector<Lining> linings;
};

} // namespace ddafem::dda
