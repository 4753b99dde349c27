// Grouted bolts in the System (dda/grouted_bolt.h, docs/support.md): each crossing is a spring
// between the two blocks' material points at the crossing, in the bolt's frame (e along the
// bolt from head to anchor, t = (-e_y, e_x)), linearised about the step start like the
// end-anchored bolts (dda/system_assembly.cc).
#include "dda/system.h"

#include "common/input_error.h"
#include "dda/submatrices.h"
#include "dda/system_helpers.h"

#include <sstream>

namespace ddafem::dda
{
void System::attach_grouted_bolt(const BoltDescription& d)
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
  grouted_bolts.push_back(b);
}

void System::add_grouted_bolt_terms(bool with_matrix)
{
  // Force F = N e + S t on the head side's block a, -F on the anchor side's b; while a part is
  // elastic its stiffness on the relative displacement T_b d_b - T_a d_a.
  for (const GroutedBolt& b : grouted_bolts)
  {
    const Vector2 e = b.direction(small_displacement());
    const Vector2 t(-e.y(), e.x());
    for (const GroutedCrossing& c : b.crossings)
    {
      const CrossingForces& f = c.forces;
      const Vector2 force = f.axial_force * e + f.shear_force * t;
      const Matrix26 ta = point_matrix(c.on_a);
      const Matrix26 tb = point_matrix(c.on_b);
      if (!with_matrix)
      {
        rhs.segment<6>(6 * c.on_a.block).noalias() += ta.transpose() * force;
        rhs.segment<6>(6 * c.on_b.block).noalias() -= tb.transpose() * force;
        continue;
      }
      const Eigen::Matrix2d k =
          (f.axial_elastic ? b.law.axial_stiffness : 0.0) * (e * e.transpose()) +
          (f.shear_elastic ? b.law.shear_stiffness : 0.0) * (t * t.transpose());
      add_pair_spring(matrix, rhs, coupling_of(c.on_a.block, c.on_b.block), c.on_a.block, ta,
                      c.on_b.block, tb, k, force);
    }
  }
}

std::vector<BoltSnapshot> System::bolt_snapshot() const
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

void System::update_grouted_bolts()
{
  // The clock of a static stage stands still: its events are recorded at the stage's time.
  for (GroutedBolt& b : grouted_bolts)
    for (GroutedCrossing& c : b.crossings)
    {
      const auto [opening, slip] = b.opening_and_slip(c, small_displacement());
      c.forces = evaluate_crossing(b.law, c.forces, opening, slip);
      c.record = record_crossing(c.record, c.forces, opening, slip, current_time);
    }
}

} // namespace ddafem::dda
