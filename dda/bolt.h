// End-anchored rock bolts (issue 21): a steel tendon attached to one block at its head and to
// another at its anchor, an axial spring between the two material points that yields and
// ruptures. The law is pure functions of the bolt's length, no geometry (docs/support.md);
// Bolts carries them on the blocks as an element kind (dda/element.h).
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
/// State of a bolt after a step.
enum class BoltState
{
  elastic,  ///< taut: N = pretension + k (L - L0 - plastic), 0 <= N < yield force
  yielding, ///< at the yield force: the plastic elongation grows as the bolt stretches
  slack,    ///< the spring would push (N < 0): a bolt carries no compression, N = 0
  ruptured  ///< broken for good: N = 0 from now on
};

constexpr std::array<EnumName<BoltState>, 4> enum_names(BoltState)
{
  return {{{BoltState::elastic, "elastic"},
           {BoltState::yielding, "yielding"},
           {BoltState::slack, "slack"},
           {BoltState::ruptured, "ruptured"}}};
}

/// Properties of one bolt.
struct BoltLaw
{
  double free_length = 0.0; ///< L0 = |anchor - head| at t = 0 [m], > 0
  double stiffness = 0.0;   ///< k = E_s A_s / L0 [N/m], > 0
  double pretension = 0.0;  ///< the force at L = L0 as installed [N], 0 <= pretension < yield
  double yield_force = 0.0; ///< [N], > 0: perfectly plastic beyond it
  /// The bolt ruptures when its total elongation L - L0 exceeds this [m]
  /// (rupture strain x L0).
  double rupture_elongation = 0.0;
};

/// A bolt's state and force. `axial_force` N is tension positive: it pulls the head's block
/// towards the anchor (+N e on it, e = unit(x_anchor - x_head)) and the anchor's block towards
/// the head (-N e).
struct BoltForces
{
  BoltState state = BoltState::elastic;
  double axial_force = 0.0;        ///< N [N], >= 0
  double plastic_elongation = 0.0; ///< accumulated plastic elongation [m], >= 0
};

/// The law of a bolt from head to anchor [m] with steel modulus E_s [Pa], area A_s [m^2],
/// pretension and yield force [N] and rupture strain [-] (of the free length).
BoltLaw make_bolt_law(const Point& head, const Point& anchor, double youngs_modulus, double area,
                      double pretension, double yield_force, double rupture_strain);

/// The bolt's state and force at length `length` [m], from its state before (`start`):
/// - ruptured stays ruptured; L - L0 > rupture_elongation ruptures it (N = 0);
/// - the trial N = pretension + k (L - L0 - plastic): above the yield force the bolt yields,
///   N = yield force and plastic = L - L0 - (yield force - pretension) / k; below zero it is
///   slack (N = 0, plastic unchanged); otherwise elastic.
BoltForces evaluate_bolt(const BoltLaw& law, const BoltForces& start, double length);

/// The stiffness [N/m] a step linearised at state `forces` gives the bolt along its axis: k
/// while elastic, 0 while yielding, slack or ruptured (then the force alone acts).
double bolt_tangent_stiffness(const BoltLaw& law, const BoltForces& forces);

/// Elastic energy stored in the bolt [J]: N^2 / (2 k) (the pretension's included; 0 when slack
/// or ruptured).
double bolt_energy(const BoltLaw& law, const BoltForces& forces);

/// Extremes and events of a bolt's history.
struct BoltRecord
{
  double max_force = 0.0;      ///< largest N [N]
  double max_elongation = 0.0; ///< largest L - L0 [m] (0 if it only shortened)
  /// Time of the first step that ended yielding, and of the rupture [s]; NaN if never.
  double yield_time = std::numeric_limits<double>::quiet_NaN();
  double rupture_time = std::numeric_limits<double>::quiet_NaN();
};

/// The record after a step that ended at time t [s] with `forces` and elongation L - L0 [m];
/// after the rupture it no longer changes (the step that ruptured it counts: its elongation is
/// the largest).
BoltRecord record_bolt(const BoltRecord& before, const BoltForces& forces, double elongation,
                       double t);

/// A bolt installed on the blocks: its two ends as material points of their blocks.
struct Bolt
{
  std::string name;
  MaterialPoint head;   ///< on the block containing the head point
  MaterialPoint anchor; ///< on the block containing the anchor point (another block)
  BoltLaw law;
  BoltForces forces; ///< at the last accepted step
  BoltRecord record;

  /// The current length |x_anchor - x_head| [m] (`initial`: L0's points).
  double length(bool initial = false) const;
  /// Unit vector from head to anchor, at the current positions or, with `initial`, at t = 0.
  Vector2 direction(bool initial = false) const;
};

/// The scene's end-anchored bolts as an element kind (dda/element.h): each one an axial spring
/// between its head's block and its anchor's.
class Bolts : public ElementKind
{
public:
  /// Attaches each end-anchored bolt of the model (ModelDescription::bolts); throws InputError
  /// for a bolt with both ends in one block.
  Bolts(const ModelDescription& model, const ElementHost& host);
  /// In scene order, with their state at the last accepted step.
  const std::vector<Bolt>& all() const { return bolts; }

  void add_couplings(std::vector<std::pair<std::size_t, std::size_t>>& pairs) const override;
  bool changes_stiffness() const override { return !bolts.empty(); }
  /// The force N at the step start, +N e on the head's block and -N e on the anchor's, and
  /// k e e^T on the relative displacement T_anchor d_anchor - T_head d_head while elastic.
  void assemble(const ElementHost& host, StepEquations& step, bool with_matrix) const override;
  void add_loads(const std::function<void(std::size_t, double)>& add) const override;
  void move_points(const ElementHost& host, const Eigen::VectorXd& d) override;
  /// Each bolt's state and record from its moved ends (evaluate_bolt, record_bolt).
  void update(const ElementHost& host, double t) override;
  void add_held_blocks(const std::function<void(std::size_t)>& hold) const override;
  void add_energy(double& energy) const override;
  void save(CheckpointOut& archive) const override;
  void load(CheckpointIn& archive) override;

private:
  std::vector<Bolt> bolts;
};

} // namespace ddafem::dda
