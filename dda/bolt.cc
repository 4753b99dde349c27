#include "dda/bolt.h"

#include "common/input_error.h"
#include "dda/checkpoint_types.h"
#include "dda/linear_solver.h"
#include "dda/model_description.h"
#include "dda/step_equations.h"

#include <algorithm>
#include <cmath>

namespace ddafem::dda
{
BoltLaw make_bolt_law(const Point& head, const Point& anchor, double youngs_modulus, double area,
                      double pretension, double yield_force, double rupture_strain)
{
  BoltLaw law;
  law.free_length = (anchor - head).norm();
  law.stiffness = youngs_modulus * area / law.free_length;
  law.pretension = pretension;
  law.yield_force = yield_force;
  law.rupture_elongation = rupture_strain * law.free_length;
  return law;
}

BoltForces evaluate_bolt(const BoltLaw& law, const BoltForces& start, double length)
{
  BoltForces out;
  out.plastic_elongation = start.plastic_elongation;
  const double elongation = length - law.free_length;
  if (start.state == BoltState::ruptured || elongation > law.rupture_elongation)
  {
    out.state = BoltState::ruptured;
    return out;
  }
  const double trial = law.pretension + law.stiffness * (elongation - start.plastic_elongation);
  if (trial > law.yield_force)
  {
    out.state = BoltState::yielding;
    out.axial_force = law.yield_force;
    out.plastic_elongation = elongation - (law.yield_force - law.pretension) / law.stiffness;
  }
  else if (trial < 0.0)
    out.state = BoltState::slack;
  else
  {
    out.state = BoltState::elastic;
    out.axial_force = trial;
  }
  return out;
}

double bolt_tangent_stiffness(const BoltLaw& law, const BoltForces& forces)
{
  return forces.state == BoltState::elastic ? law.stiffness : 0.0;
}

double bolt_energy(const BoltLaw& law, const BoltForces& forces)
{
  return 0.5 * forces.axial_force * forces.axial_force / law.stiffness;
}

BoltRecord record_bolt(const BoltRecord& before, const BoltForces& forces, double elongation,
                       double t)
{
  if (!std::isnan(before.rupture_time))
    return before; // a broken bolt's ends move apart freely: its record ends at the rupture
  BoltRecord out = before;
  out.max_force = std::max(out.max_force, forces.axial_force);
  out.max_elongation = std::max(out.max_elongation, elongation);
  if (forces.state == BoltState::yielding && std::isnan(out.yield_time))
    out.yield_time = t;
  if (forces.state == BoltState::ruptured && std::isnan(out.rupture_time))
    out.rupture_time = t;
  return out;
}

double Bolt::length(bool initial) const
{
  return initial ? (anchor.initial - head.initial).norm()
                 : (anchor.position - head.position).norm();
}

Vector2 Bolt::direction(bool initial) const
{
  return initial ? (anchor.initial - head.initial).normalized()
                 : (anchor.position - head.position).normalized();
}

template <class Archive>
void serialize(Archive& a, BoltForces& f, const unsigned int /*version*/)
{
  transfer_all(a, f.state, f.axial_force, f.plastic_elongation);
}

template <class Archive>
void serialize(Archive& a, BoltRecord& r, const unsigned int /*version*/)
{
  transfer_all(a, r.max_force, r.max_elongation, r.yield_time, r.rupture_time);
}

namespace
{
template <class Archive>
void transfer_bolts(Archive& a, std::vector<Bolt>& bolts)
{
  transfer_in_place(a, bolts, "bolts",
                    [&a](Bolt& b) { transfer_all(a, b.head, b.anchor, b.forces, b.record); });
}
} // namespace

Bolts::Bolts(const ModelDescription& model, const ElementHost& host)
{
  for (const BoltDescription& d : model.bolts)
  {
    if (d.type == BoltType::grouted)
      continue;
    Bolt b;
    b.name = d.name;
    const std::string what = d.origin.empty() ? "bolt " + d.name : d.origin;
    b.head = host.attach(d.head, what + ".head");
    b.anchor = host.attach(d.anchor, what + ".anchor");
    if (b.head.block == b.anchor.block)
      throw InputError(what + ".anchor lies in the same block as its head (block " +
                       std::to_string(b.head.block) +
                       "): expected the anchor in another block than the head");
    b.law = make_bolt_law(d.head, d.anchor, d.youngs_modulus, d.area, d.pretension, d.yield_force,
                          d.rupture_strain);
    b.forces = evaluate_bolt(b.law, {}, b.law.free_length);
    bolts.push_back(b);
  }
}

void Bolts::add_couplings(std::vector<std::pair<std::size_t, std::size_t>>& pairs) const
{
  for (const Bolt& b : bolts)
    pairs.emplace_back(std::min(b.head.block, b.anchor.block),
                       std::max(b.head.block, b.anchor.block));
}

void Bolts::assemble(const ElementHost& host, StepEquations& step, bool with_matrix) const
{
  // e = unit(x_anchor - x_head) (dda/bolt.h).
  for (const Bolt& b : bolts)
  {
    const Vector2 e = b.direction(host.small_displacement());
    const Matrix26 th = host.point_matrix(b.head);
    const Matrix26 ta = host.point_matrix(b.anchor);
    step.rhs.segment<6>(6 * b.head.block).noalias() += th.transpose() * (b.forces.axial_force * e);
    step.rhs.segment<6>(6 * b.anchor.block).noalias() -=
        ta.transpose() * (b.forces.axial_force * e);
    const double k = bolt_tangent_stiffness(b.law, b.forces);
    if (!with_matrix || k == 0.0)
      continue;
    const Eigen::Matrix2d kee = k * (e * e.transpose());
    step.matrix.diagonal(b.head.block).noalias() += th.transpose() * kee * th;
    step.matrix.diagonal(b.anchor.block).noalias() += ta.transpose() * kee * ta;
    // The coupling block (i, j), i < j: row i's end against column j's.
    const std::size_t coupling = step.coupling_of(b.head.block, b.anchor.block);
    if (b.head.block < b.anchor.block)
      step.matrix.upper(coupling).noalias() -= th.transpose() * kee * ta;
    else
      step.matrix.upper(coupling).noalias() -= ta.transpose() * kee * th;
  }
}

void Bolts::add_loads(const std::function<void(std::size_t, double)>& add) const
{
  for (const Bolt& b : bolts)
  {
    add(b.head.block, b.forces.axial_force);
    add(b.anchor.block, b.forces.axial_force);
  }
}

void Bolts::move_points(const ElementHost& host, const Eigen::VectorXd& d)
{
  for (Bolt& b : bolts)
    for (MaterialPoint* p : {&b.head, &b.anchor})
      host.move_with_block(*p, d);
}

void Bolts::update(const ElementHost& /*host*/, double t)
{
  // The clock of a static stage stands still: its events are recorded at the stage's time.
  for (Bolt& b : bolts)
  {
    const double length = b.length();
    b.forces = evaluate_bolt(b.law, b.forces, length);
    b.record = record_bolt(b.record, b.forces, length - b.law.free_length, t);
  }
}

void Bolts::add_held_blocks(const std::function<void(std::size_t)>& hold) const
{
  for (const Bolt& b : bolts)
    if (b.forces.state != BoltState::ruptured)
    {
      hold(b.head.block);
      hold(b.anchor.block);
    }
}

void Bolts::add_energy(double& energy) const
{
  for (const Bolt& b : bolts)
    energy += bolt_energy(b.law, b.forces);
}

void Bolts::save(CheckpointOut& archive) const
{
  // One function stores and restores (Boost.Serialization's `&`); storing changes nothing.
  transfer_bolts(archive, const_cast<std::vector<Bolt>&>(bolts));
}

void Bolts::load(CheckpointIn& archive)
{
  transfer_bolts(archive, bolts);
}

} // namespace ddafem::dda
