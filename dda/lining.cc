#include "dda/lining.h"

#include "dda/checkpoint_types.h"
#include "dda/linear_solver.h"
#include "dda/model_description.h"
#include "dda/step_equations.h"

#include <algorithm>
#include <cmath>

namespace ddafem::dda
{
Matrix6 frame_stiffness_local(const LiningSection& section, double length0)
{
  const double l = length0;
  const double ea = section.axial_stiffness() / l;
  const double ei = section.bending_stiffness();
  const double k1 = 12.0 * ei / (l * l * l), k2 = 6.0 * ei / (l * l), k3 = 4.0 * ei / l,
               k4 = 2.0 * ei / l;
  Matrix6 k;
  k << ea, 0, 0, -ea, 0, 0,    //
      0, k1, k2, 0, -k1, k2,   //
      0, k2, k3, 0, -k2, k4,   //
      -ea, 0, 0, ea, 0, 0,     //
      0, -k1, -k2, 0, k1, -k2, //
      0, k2, k4, 0, -k2, k3;
  return k;
}

Matrix6 frame_stiffness_global(const LiningSection& section, double length0, const Vector2& e)
{
  // Local (u, v) = r (u_x, u_y) with r = [[e_x, e_y], [-e_y, e_x]]; rotations unchanged.
  Matrix6 r = Matrix6::Zero();
  for (int node = 0; node < 2; ++node)
  {
    const int o = 3 * node;
    r(o, o) = e.x();
    r(o, o + 1) = e.y();
    r(o + 1, o) = -e.y();
    r(o + 1, o + 1) = e.x();
    r(o + 2, o + 2) = 1.0;
  }
  return r.transpose() * frame_stiffness_local(section, length0) * r;
}

FrameDeformation frame_deformation(const Point& xa0, const Point& xb0, const Point& xa,
                                   const Point& xb, double theta_a, double theta_b)
{
  const Vector2 c0 = xb0 - xa0, c = xb - xa;
  // The chord's rotation in (-pi, pi]: atan2 of the cross and dot products of the two chords.
  const double chord = std::atan2(c0.x() * c.y() - c0.y() * c.x(), c0.dot(c));
  return {c.norm() - c0.norm(), theta_a - chord, theta_b - chord};
}

FrameForces frame_forces(const LiningSection& section, double length0, const FrameDeformation& q)
{
  const double ei_l = section.bending_stiffness() / length0;
  FrameForces f;
  f.axial_force = section.axial_stiffness() * q.elongation / length0;
  f.end_moment_a = ei_l * (4.0 * q.rotation_a + 2.0 * q.rotation_b);
  f.end_moment_b = ei_l * (2.0 * q.rotation_a + 4.0 * q.rotation_b);
  f.shear_force = (f.end_moment_a + f.end_moment_b) / length0;
  return f;
}

Vector6 forces_on_nodes(const FrameForces& f, const Vector2& e)
{
  const Vector2 n(-e.y(), e.x());
  const Vector2 on_a = f.axial_force * e - f.shear_force * n;
  Vector6 out;
  out << on_a, -f.end_moment_a, -on_a, -f.end_moment_b;
  return out;
}

double frame_energy(const LiningSection& section, double length0, const FrameDeformation& q)
{
  const double ta = q.rotation_a, tb = q.rotation_b;
  return 0.5 * section.axial_stiffness() * q.elongation * q.elongation / length0 +
         2.0 * section.bending_stiffness() / length0 * (ta * ta + ta * tb + tb * tb);
}

LiningCheck check_lining_section(const LiningSection& section, const FrameForces& f)
{
  const double t = section.thickness;
  LiningCheck out;
  const auto consider = [&out](double utilisation, LiningFailureMode mode)
  {
    if (utilisation > out.utilisation)
      out = {utilisation, mode};
  };
  for (const double m : {f.bending_moment_a(), f.bending_moment_b()})
  {
    const double axial = f.axial_force / t, bending = 6.0 * std::abs(m) / (t * t);
    consider((axial + bending) / section.tensile_strength, LiningFailureMode::tension);
    consider(-(axial - bending) / section.compressive_strength, LiningFailureMode::compression);
  }
  if (section.shear_strength > 0.0)
    consider(1.5 * std::abs(f.shear_force) / t / section.shear_strength, LiningFailureMode::shear);
  return out;
}

void update_lining_element(LiningElement& element, const LiningSection& section,
                           const LiningNode& a, const LiningNode& b, double t)
{
  if (element.state != LiningElementState::intact)
    return;
  const FrameDeformation q = frame_deformation(a.installed, b.installed, a.point.position,
                                               b.point.position, a.rotation, b.rotation);
  element.forces = frame_forces(section, element.length0, q);
  element.check = check_lining_section(section, element.forces);
  element.max_utilisation = std::max(element.max_utilisation, element.check.utilisation);
  if (element.check.utilisation <= 1.0)
    return;
  element.state = LiningElementState::broken;
  element.break_time = t;
  element.forces = {};
}

void Lining::install(double t)
{
  installed = true;
  install_time = t;
  for (LiningNode& n : nodes)
  {
    n.installed = n.point.position;
    n.rotation = 0.0;
  }
  for (LiningElement& e : elements)
  {
    e.length0 = (nodes[e.b].installed - nodes[e.a].installed).norm();
    e.forces = {};
    e.check = {};
  }
}

std::size_t Lining::worst_element() const
{
  std::size_t worst = 0;
  double largest = -1.0;
  for (std::size_t k = 0; k < elements.size(); ++k)
    if (elements[k].state == LiningElementState::intact && elements[k].check.utilisation > largest)
    {
      largest = elements[k].check.utilisation;
      worst = k;
    }
  return worst;
}

std::size_t Lining::n_broken() const
{
  return static_cast<std::size_t>(std::count_if(elements.begin(), elements.end(),
                                                [](const LiningElement& e)
                                                { return e.state == LiningElementState::broken; }));
}

std::vector<LiningElementSnapshot> lining_snapshot(const std::vector<Lining>& linings)
{
  std::vector<LiningElementSnapshot> out;
  for (std::size_t i = 0; i < linings.size(); ++i)
  {
    const Lining& l = linings[i];
    for (std::size_t k = 0; k < l.elements.size(); ++k)
    {
      const LiningElement& e = l.elements[k];
      out.push_back({l.nodes[e.a].point.position, l.nodes[e.b].point.position, i, k, e.state,
                     e.forces, e.check.utilisation});
    }
  }
  return out;
}

std::vector<Point> lining_node_positions(const std::vector<Point>& points, double segment_length,
                                         bool closed)
{
  std::vector<Point> out;
  const std::size_t n_legs = closed ? points.size() : points.size() - 1;
  for (std::size_t i = 0; i < n_legs; ++i)
  {
    const Point& p = points[i];
    const Point& q = points[(i + 1) % points.size()];
    const auto parts =
        static_cast<std::size_t>(std::max(1.0, std::ceil((q - p).norm() / segment_length - 1e-9)));
    for (std::size_t k = 0; k < parts; ++k)
      out.push_back(p + (q - p) * (static_cast<double>(k) / static_cast<double>(parts)));
  }
  if (!closed)
    out.push_back(points.back());
  return out;
}

template <class Archive>
void serialize(Archive& a, LiningNode& n, const unsigned int /*version*/)
{
  transfer_all(a, n.point, n.installed, n.rotation);
}

template <class Archive>
void serialize(Archive& a, LiningElement& e, const unsigned int /*version*/)
{
  transfer_all(a, e.a, e.b, e.length0, e.state, e.forces.axial_force, e.forces.shear_force);
  transfer_all(a, e.forces.end_moment_a, e.forces.end_moment_b, e.check.utilisation, e.check.mode,
               e.max_utilisation, e.break_time);
}

namespace
{
using Matrix36 = Eigen::Matrix<double, 3, 6>;

/// The node's (u_x, u_y, theta) from its block's unknowns: T at the point, and r0.
Matrix36 node_matrix(const Matrix26& t)
{
  Matrix36 g = Matrix36::Zero();
  g.topRows<2>() = t;
  g(2, 2) = 1.0;
  return g;
}

template <class Archive>
void transfer_linings(Archive& a, std::vector<Lining>& linings)
{
  transfer_in_place(a, linings, "linings",
                    [&a](Lining& l)
                    {
                      transfer_all(a, l.nodes, l.elements, l.installed, l.install_time);
                      transfer_all(a, l.max_utilisation, l.max_utilisation_time,
                                   l.max_utilisation_element, l.first_break_time,
                                   l.first_break_element);
                    });
}
} // namespace

Linings::Linings(const ModelDescription& model, const ElementHost& host)
{
  for (const LiningDescription& d : model.linings)
  {
    Lining l;
    l.name = d.name;
    l.section = {d.thickness, d.youngs_modulus, d.compressive_strength, d.tensile_strength,
                 d.shear_strength};
    l.install_stage = d.install_stage;
    const std::string what = d.origin.empty() ? "lining " + d.name : d.origin;
    const std::vector<Point> at = lining_node_positions(d.points, d.segment_length, d.closed);
    for (std::size_t k = 0; k < at.size(); ++k)
    {
      LiningNode n;
      n.point = host.attach(at[k], what + " node " + std::to_string(k));
      n.installed = at[k];
      l.nodes.push_back(n);
    }
    const std::size_t n_elements = d.closed ? at.size() : at.size() - 1;
    for (std::size_t k = 0; k < n_elements; ++k)
    {
      LiningElement e;
      e.a = k;
      e.b = (k + 1) % at.size();
      if (l.nodes[e.a].point.block == l.nodes[e.b].point.block)
        e.state = LiningElementState::on_one_block;
      l.elements.push_back(e);
    }
    if (l.install_stage == 0)
      l.install(0.0);
    else
      for (LiningElement& e : l.elements)
        e.length0 = (l.nodes[e.b].installed - l.nodes[e.a].installed).norm();
    linings.push_back(l);
  }
}

void Linings::begin_stage(std::size_t stage, double t)
{
  for (Lining& l : linings)
    if (!l.installed && l.install_stage == stage)
      l.install(t);
}

void Linings::add_couplings(std::vector<std::pair<std::size_t, std::size_t>>& pairs) const
{
  for (const Lining& l : linings)
    for (const LiningElement& e : l.elements)
      if (e.state != LiningElementState::on_one_block)
        pairs.emplace_back(std::minmax(l.nodes[e.a].point.block, l.nodes[e.b].point.block));
}

void Linings::assemble(const ElementHost& host, StepEquations& step, bool with_matrix) const
{
  for (const Lining& l : linings)
  {
    if (!l.installed)
      continue;
    for (const LiningElement& el : l.elements)
    {
      if (el.state != LiningElementState::intact)
        continue;
      const LiningNode& na = l.nodes[el.a];
      const LiningNode& nb = l.nodes[el.b];
      const Vector2 e = host.small_displacement()
                            ? Vector2((nb.installed - na.installed).normalized())
                            : Vector2((nb.point.position - na.point.position).normalized());
      const std::size_t ba = na.point.block, bb = nb.point.block;
      const Matrix36 ga = node_matrix(host.point_matrix(na.point));
      const Matrix36 gb = node_matrix(host.point_matrix(nb.point));
      const Vector6 f = forces_on_nodes(el.forces, e);
      step.rhs.segment<6>(6 * ba).noalias() += ga.transpose() * f.head<3>();
      step.rhs.segment<6>(6 * bb).noalias() += gb.transpose() * f.tail<3>();
      if (!with_matrix)
        continue;
      const Matrix6 k = frame_stiffness_global(l.section, el.length0, e);
      step.matrix.diagonal(ba).noalias() += ga.transpose() * k.topLeftCorner<3, 3>() * ga;
      step.matrix.diagonal(bb).noalias() += gb.transpose() * k.bottomRightCorner<3, 3>() * gb;
      // The coupling block (i, j), i < j: row i's node against column j's.
      const std::size_t coupling = step.coupling_of(ba, bb);
      if (ba < bb)
        step.matrix.upper(coupling).noalias() += ga.transpose() * k.topRightCorner<3, 3>() * gb;
      else
        step.matrix.upper(coupling).noalias() += gb.transpose() * k.bottomLeftCorner<3, 3>() * ga;
    }
  }
}

void Linings::add_loads(const std::function<void(std::size_t, double)>& add) const
{
  for (const Lining& l : linings)
    for (const LiningElement& e : l.elements)
    {
      const double f = std::hypot(e.forces.axial_force, e.forces.shear_force);
      add(l.nodes[e.a].point.block, f);
      add(l.nodes[e.b].point.block, f);
    }
}

void Linings::move_points(const ElementHost& host, const Eigen::VectorXd& d)
{
  for (Lining& l : linings)
    for (LiningNode& n : l.nodes)
    {
      host.move_with_block(n.point, d);
      n.rotation += d[static_cast<Eigen::Index>(6 * n.point.block + 2)];
    }
}

void Linings::update(const ElementHost& /*host*/, double t)
{
  // The clock of a static stage stands still: its events are recorded at the stage's time.
  for (Lining& l : linings)
  {
    if (!l.installed)
      continue;
    for (std::size_t k = 0; k < l.elements.size(); ++k)
    {
      LiningElement& e = l.elements[k];
      update_lining_element(e, l.section, l.nodes[e.a], l.nodes[e.b], t);
      if (e.check.utilisation > l.max_utilisation)
      {
        l.max_utilisation = e.check.utilisation;
        l.max_utilisation_time = t;
        l.max_utilisation_element = k;
      }
      if (e.state == LiningElementState::broken && std::isnan(l.first_break_time))
      {
        l.first_break_time = e.break_time;
        l.first_break_element = k;
      }
    }
  }
}

void Linings::add_held_blocks(const std::function<void(std::size_t)>& hold) const
{
  for (const Lining& l : linings)
    for (const LiningElement& e : l.elements)
      if (l.installed && e.state == LiningElementState::intact)
      {
        hold(l.nodes[e.a].point.block);
        hold(l.nodes[e.b].point.block);
      }
}

void Linings::add_energy(double& energy) const
{
  for (const Lining& l : linings)
    for (const LiningElement& el : l.elements)
      if (l.installed && el.state == LiningElementState::intact)
        energy += frame_energy(l.section, el.length0,
                               frame_deformation(l.nodes[el.a].installed, l.nodes[el.b].installed,
                                                 l.nodes[el.a].point.position,
                                                 l.nodes[el.b].point.position,
                                                 l.nodes[el.a].rotation, l.nodes[el.b].rotation));
}

void Linings::save(CheckpointOut& archive) const
{
  // One function stores and restores (Boost.Serialization's `&`); storing changes nothing.
  transfer_linings(archive, const_cast<std::vector<Lining>&>(linings));
}

void Linings::load(CheckpointIn& archive)
{
  transfer_linings(archive, linings);
}

} // namespace ddafem::dda
