#include "dda/lining.h"

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

} // namespace ddafem::dda
