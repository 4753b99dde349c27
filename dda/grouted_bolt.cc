#include "dda/grouted_bolt.h"

#include "common/input_error.h"
#include "dda/bolt_snapshot.h"
#include "dda/checkpoint_types.h"
#include "dda/geometry.h"
#include "dda/linear_solver.h"
#include "dda/model_description.h"
#include "dda/step_equations.h"
#include "dda/system_helpers.h"

#include <algorithm>
#include <cmath>

namespace ddafem::dda
{
namespace
{
/// A stretch of the segment inside one polygon: its block and its distances from the head [m].
struct Stretch
{
  std::size_t block = 0;
  double start = 0.0;
  double end = 0.0;
};

/// The parameters s in [0, 1] where the segment p + s (q - p) meets the polygon's edges (0 and 1
/// included), sorted.
std::vector<double> edge_parameters(const std::vector<Point>& polygon, const Point& p,
                                    const Point& q)
{
  std::vector<double> s = {0.0, 1.0};
  const Vector2 d = q - p;
  for (std::size_t i = 0; i < polygon.size(); ++i)
  {
    const Point& a = polygon[i];
    const Vector2 e = polygon[(i + 1) % polygon.size()] - a;
    const double denominator = d.x() * e.y() - d.y() * e.x();
    if (denominator == 0.0)
      continue; // parallel: its ends are other edges' ends
    const Vector2 w = a - p;
    const double along = (w.x() * e.y() - w.y() * e.x()) / denominator;
    const double on_edge = (w.x() * d.y() - w.y() * d.x()) / denominator;
    if (along > 0.0 && along < 1.0 && on_edge >= 0.0 && on_edge <= 1.0)
      s.push_back(along);
  }
  std::sort(s.begin(), s.end());
  return s;
}

/// The stretches of the segment inside the polygon (sub-intervals between edge crossings whose
/// midpoint is inside, merged when consecutive).
void add_stretches(std::vector<Stretch>& out, std::size_t block, const std::vector<Point>& polygon,
                   const Point& p, const Point& q, double tol)
{
  const std::vector<double> s = edge_parameters(polygon, p, q);
  const double length = (q - p).norm();
  bool open = false;
  for (std::size_t i = 0; i + 1 < s.size(); ++i)
  {
    if (s[i + 1] - s[i] <= 0.0)
      continue;
    const Point mid = p + 0.5 * (s[i] + s[i + 1]) * (q - p);
    const bool inside = locate_point(polygon, mid, tol) == PointLocation::inside;
    if (inside && open)
      out.back().end = s[i + 1] * length;
    else if (inside)
      out.push_back({block, s[i] * length, s[i + 1] * length});
    open = inside;
  }
}
} // namespace

std::vector<BoltCrossing> find_bolt_crossings(const std::vector<std::vector<Point>>& polygons,
                                              const Point& head, const Point& anchor, double tol,
                                              std::array<double, 2>* gap)
{
  std::vector<Stretch> stretches;
  for (std::size_t b = 0; b < polygons.size(); ++b)
    add_stretches(stretches, b, polygons[b], head, anchor, tol);
  std::sort(stretches.begin(), stretches.end(),
            [](const Stretch& x, const Stretch& y) { return x.start < y.start; });
  if (gap)
    *gap = {0.0, 0.0};
  std::vector<BoltCrossing> crossings;
  const Vector2 e = (anchor - head).normalized();
  for (std::size_t i = 0; i + 1 < stretches.size(); ++i)
  {
    const Stretch& a = stretches[i];
    const Stretch& b = stretches[i + 1];
    if (b.start - a.end > tol)
    {
      if (gap && (*gap)[1] == 0.0)
        *gap = {a.end, b.start};
      continue;
    }
    if (a.block == b.block)
      continue;
    const double at = 0.5 * (a.end + b.start);
    crossings.push_back({a.block, b.block, head + at * e, at});
  }
  if (gap && (*gap)[1] == 0.0 && !stretches.empty())
  {
    // The segment's ends outside every block count as gaps too.
    const double length = (anchor - head).norm();
    if (stretches.front().start > tol)
      *gap = {0.0, stretches.front().start};
    else if (length - stretches.back().end > tol)
      *gap = {stretches.back().end, length};
  }
  return crossings;
}

double dowel_shear_stiffness(double youngs_modulus, double area, double foundation_modulus)
{
  const double pi = std::acos(-1.0);
  const double d = std::sqrt(4.0 * area / pi);
  const double inertia = pi * std::pow(d, 4) / 64.0;
  const double beta = std::pow(foundation_modulus / (4.0 * youngs_modulus * inertia), 0.25);
  return foundation_modulus / (4.0 * beta);
}

GroutedBoltLaw make_grouted_bolt_law(double youngs_modulus, double area, double foundation_modulus,
                                     double debonded_length, double pretension, double yield_force,
                                     double shear_capacity, double rupture_strain)
{
  GroutedBoltLaw law;
  law.axial_stiffness = youngs_modulus * area / debonded_length;
  law.shear_stiffness = dowel_shear_stiffness(youngs_modulus, area, foundation_modulus);
  law.pretension = pretension;
  law.yield_force = yield_force;
  law.shear_capacity = shear_capacity;
  law.debonded_length = debonded_length;
  law.rupture_elongation = rupture_strain * debonded_length;
  return law;
}

CrossingForces evaluate_crossing(const GroutedBoltLaw& law, const CrossingForces& start,
                                 double opening, double slip)
{
  CrossingForces out;
  out.plastic_opening = start.plastic_opening;
  out.plastic_slip = start.plastic_slip;
  const double stretch =
      std::hypot(law.debonded_length + opening, slip) - law.debonded_length; // [m]
  if (start.state == BoltState::ruptured || stretch > law.rupture_elongation)
  {
    out.state = BoltState::ruptured;
    out.axial_elastic = out.shear_elastic = false;
    return out;
  }
  const double axial = law.pretension + law.axial_stiffness * (opening - start.plastic_opening);
  bool axial_yield = false, slack = false;
  if (axial > law.yield_force)
  {
    axial_yield = true;
    out.axial_force = law.yield_force;
    out.plastic_opening = opening - (law.yield_force - law.pretension) / law.axial_stiffness;
  }
  else if (axial < 0.0)
    slack = true;
  else
    out.axial_force = axial;
  const double shear = law.shear_stiffness * (slip - start.plastic_slip);
  const bool shear_yield = std::abs(shear) > law.shear_capacity;
  if (shear_yield)
  {
    out.shear_force = std::copysign(law.shear_capacity, shear);
    out.plastic_slip = slip - out.shear_force / law.shear_stiffness;
  }
  else
    out.shear_force = shear;
  out.axial_elastic = !axial_yield && !slack;
  out.shear_elastic = !shear_yield;
  out.state = axial_yield || shear_yield        ? BoltState::yielding
              : slack && out.shear_force == 0.0 ? BoltState::slack
                                                : BoltState::elastic;
  return out;
}

double crossing_energy(const GroutedBoltLaw& law, const CrossingForces& forces)
{
  return 0.5 * forces.axial_force * forces.axial_force / law.axial_stiffness +
         0.5 * forces.shear_force * forces.shear_force / law.shear_stiffness;
}

CrossingRecord record_crossing(const CrossingRecord& before, const CrossingForces& forces,
                               double opening, double slip, double t)
{
  if (!std::isnan(before.rupture_time))
    return before;
  CrossingRecord out = before;
  out.max_axial_force = std::max(out.max_axial_force, forces.axial_force);
  out.max_shear_force = std::max(out.max_shear_force, std::abs(forces.shear_force));
  out.max_opening = std::max(out.max_opening, opening);
  out.max_slip = std::max(out.max_slip, std::abs(slip));
  if (forces.state == BoltState::yielding && std::isnan(out.yield_time))
    out.yield_time = t;
  if (forces.state == BoltState::ruptured && std::isnan(out.rupture_time))
    out.rupture_time = t;
  return out;
}

BoltState summary_state(const GroutedBolt& b)
{
  const auto any = [&b](BoltState s)
  {
    return std::any_of(b.crossings.begin(), b.crossings.end(),
                       [s](const GroutedCrossing& c) { return c.forces.state == s; });
  };
  for (const BoltState s : {BoltState::ruptured, BoltState::yielding, BoltState::elastic})
    if (any(s))
      return s;
  return BoltState::slack;
}

Vector2 GroutedBolt::direction(bool initial) const
{
  return initial ? (anchor.initial - head.initial).normalized()
                 : (anchor.position - head.position).normalized();
}

std::array<double, 2> GroutedBolt::opening_and_slip(const GroutedCrossing& c, bool initial) const
{
  const Vector2 e = direction(initial);
  const Vector2 t(-e.y(), e.x());
  const Vector2 delta = c.relative_displacement();
  return {delta.dot(e), delta.dot(t)};
}

template <class Archive>
void serialize(Archive& a, CrossingForces& f, const unsigned int /*version*/)
{
  transfer_all(a, f.state, f.axial_elastic, f.shear_elastic, f.axial_force, f.shear_force);
  transfer_all(a, f.plastic_opening, f.plastic_slip);
}

template <class Archive>
void serialize(Archive& a, CrossingRecord& r, const unsigned int /*version*/)
{
  transfer_all(a, r.max_axial_force, r.max_shear_force, r.max_opening, r.max_slip);
  transfer_all(a, r.yield_time, r.rupture_time);
}

namespace
{
/// A grouted bolt onto its blocks' material points at its crossings (InputError if none).
GroutedBolt attach_grouted_bolt(const BoltDescription& d)
{
  const std::string what = d.origin.empty() ? "bolt " + d.name : d.origin;
  if (d.crossings.empty())
    throw InputError(what + " crosses no block boundary between its head and its anchor: "
                            "expected a grouted bolt through at least two blocks");
  GroutedBolt b;
  b.name = d.name;
  // The ends belong to the first and the last block along the bolt (a head on the boundary of
  // two blocks, e.g. where a joint meets the opening, to the one the bolt enters).
  b.head = {d.crossings.front().block_a, d.head, d.head};
  b.anchor = {d.crossings.back().block_b, d.anchor, d.anchor};
  b.law = make_grouted_bolt_law(d.youngs_modulus, d.area, d.grout_modulus, d.debonded_length,
                                d.pretension, d.yield_force, d.shear_capacity, d.rupture_strain);
  for (const BoltCrossing& x : d.crossings)
  {
    GroutedCrossing c;
    c.on_a = {x.block_a, x.point, x.point};
    c.on_b = {x.block_b, x.point, x.point};
    c.forces = evaluate_crossing(b.law, {}, 0.0, 0.0);
    b.crossings.push_back(c);
  }
  return b;
}

template <class Archive>
void transfer_grouted_bolts(Archive& a, std::vector<GroutedBolt>& grouted_bolts)
{
  transfer_in_place(a, grouted_bolts, "grouted bolts",
                    [&a](GroutedBolt& b)
                    {
                      transfer_all(a, b.head, b.anchor);
                      transfer_in_place(a, b.crossings, "crossings",
                                        [&a](GroutedCrossing& c)
                                        { transfer_all(a, c.on_a, c.on_b, c.forces, c.record); });
                    });
}
} // namespace

GroutedBolts::GroutedBolts(const ModelDescription& model)
{
  for (const BoltDescription& d : model.bolts)
    if (d.type == BoltType::grouted)
      grouted_bolts.push_back(attach_grouted_bolt(d));
}

void GroutedBolts::add_couplings(std::vector<std::pair<std::size_t, std::size_t>>& pairs) const
{
  for (const GroutedBolt& b : grouted_bolts)
    for (const GroutedCrossing& c : b.crossings)
      pairs.emplace_back(std::min(c.on_a.block, c.on_b.block),
                         std::max(c.on_a.block, c.on_b.block));
}

void GroutedBolts::assemble(const ElementHost& host, StepEquations& step, bool with_matrix) const
{
  for (const GroutedBolt& b : grouted_bolts)
  {
    const Vector2 e = b.direction(host.small_displacement());
    const Vector2 t(-e.y(), e.x());
    for (const GroutedCrossing& c : b.crossings)
    {
      const CrossingForces& f = c.forces;
      const Vector2 force = f.axial_force * e + f.shear_force * t;
      const Matrix26 ta = host.point_matrix(c.on_a);
      const Matrix26 tb = host.point_matrix(c.on_b);
      if (!with_matrix)
      {
        step.rhs.segment<6>(6 * c.on_a.block).noalias() += ta.transpose() * force;
        step.rhs.segment<6>(6 * c.on_b.block).noalias() -= tb.transpose() * force;
        continue;
      }
      const Eigen::Matrix2d k =
          (f.axial_elastic ? b.law.axial_stiffness : 0.0) * (e * e.transpose()) +
          (f.shear_elastic ? b.law.shear_stiffness : 0.0) * (t * t.transpose());
      add_pair_spring(step.matrix, step.rhs, step.coupling_of(c.on_a.block, c.on_b.block),
                      c.on_a.block, ta, c.on_b.block, tb, k, force);
    }
  }
}

void GroutedBolts::add_loads(const std::function<void(std::size_t, double)>& add) const
{
  for (const GroutedBolt& b : grouted_bolts)
    for (const GroutedCrossing& c : b.crossings)
    {
      add(c.on_a.block, std::hypot(c.forces.axial_force, c.forces.shear_force));
      add(c.on_b.block, std::hypot(c.forces.axial_force, c.forces.shear_force));
    }
}

void GroutedBolts::move_points(const ElementHost& host, const Eigen::VectorXd& d)
{
  for (GroutedBolt& b : grouted_bolts)
  {
    host.move_with_block(b.head, d);
    host.move_with_block(b.anchor, d);
    for (GroutedCrossing& c : b.crossings)
    {
      host.move_with_block(c.on_a, d);
      host.move_with_block(c.on_b, d);
    }
  }
}

void GroutedBolts::update(const ElementHost& host, double t)
{
  // The clock of a static stage stands still: its events are recorded at the stage's time.
  for (GroutedBolt& b : grouted_bolts)
    for (GroutedCrossing& c : b.crossings)
    {
      const auto [opening, slip] = b.opening_and_slip(c, host.small_displacement());
      c.forces = evaluate_crossing(b.law, c.forces, opening, slip);
      c.record = record_crossing(c.record, c.forces, opening, slip, t);
    }
}

void GroutedBolts::add_held_blocks(const std::function<void(std::size_t)>& hold) const
{
  for (const GroutedBolt& b : grouted_bolts)
    for (const GroutedCrossing& c : b.crossings)
      if (c.forces.state != BoltState::ruptured)
      {
        hold(c.on_a.block);
        hold(c.on_b.block);
      }
}

void GroutedBolts::add_energy(double& energy) const
{
  for (const GroutedBolt& b : grouted_bolts)
    for (const GroutedCrossing& c : b.crossings)
      energy += crossing_energy(b.law, c.forces);
}

void GroutedBolts::save(CheckpointOut& archive) const
{
  // One function stores and restores (Boost.Serialization's `&`); storing changes nothing.
  transfer_grouted_bolts(archive, const_cast<std::vector<GroutedBolt>&>(grouted_bolts));
}

void GroutedBolts::load(CheckpointIn& archive)
{
  transfer_grouted_bolts(archive, grouted_bolts);
}

std::vector<BoltSnapshot> bolt_snapshot(const std::vector<Bolt>& bolts,
                                        const std::vector<GroutedBolt>& grouted_bolts)
{
  std::vector<BoltSnapshot> out;
  for (const Bolt& b : bolts)
  {
    BoltSnapshot s;
    s.id = out.size();
    s.points = {b.head.position, b.anchor.position};
    s.point_axial = {b.forces.axial_force, b.forces.axial_force};
    s.point_shear = {0.0, 0.0};
    s.axial_force = b.forces.axial_force;
    s.state = b.forces.state;
    out.push_back(s);
  }
  for (const GroutedBolt& b : grouted_bolts)
  {
    BoltSnapshot s;
    s.id = out.size();
    s.type = BoltType::grouted;
    s.points.push_back(b.head.position);
    s.point_axial.push_back(0.0);
    s.point_shear.push_back(0.0);
    for (const GroutedCrossing& c : b.crossings)
    {
      s.points.insert(s.points.end(), {c.on_a.position, c.on_b.position});
      s.point_axial.insert(s.point_axial.end(), 2, c.forces.axial_force);
      s.point_shear.insert(s.point_shear.end(), 2, c.forces.shear_force);
      s.axial_force = std::max(s.axial_force, c.forces.axial_force);
      s.shear_force = std::max(s.shear_force, std::abs(c.forces.shear_force));
    }
    s.points.push_back(b.anchor.position);
    s.point_axial.push_back(0.0);
    s.point_shear.push_back(0.0);
    s.state = summary_state(b);
    out.push_back(s);
  }
  return out;
}

} // namespace ddafem::dda
