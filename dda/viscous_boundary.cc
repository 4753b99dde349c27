#include "dda/viscous_boundary.h"

#include "common/elasticity.h"
#include "common/input_error.h"
#include "common/newmark.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace ddafem::dda
{
double vb1_factor(double x)
{
  return 2.0 / (1.0 + std::exp(-x));
}

double vb1_source_threshold()
{
  // Newton on g(x) = D(x) - x, D' = 2 e^-x / (1 + e^-x)^2; g(1) > 0 > g(2), root near 1.688.
  double x = 1.7;
  for (int k = 0; k < 50; ++k)
  {
    const double e = std::exp(-x);
    const double g = vb1_factor(x) - x;
    const double dg = 2.0 * e / ((1.0 + e) * (1.0 + e)) - 1.0;
    const double step = g / dg;
    x -= step;
    if (std::abs(step) < 1e-15)
      break;
  }
  return x;
}

BoundaryWaveSpeeds textbook_wave_speeds(const Material& m)
{
  const double e = m.youngs_modulus, nu = m.poisson_ratio, rho = m.density;
  return {p_wave_speed(e, nu, rho), s_wave_speed(e, nu, rho)};
}

namespace
{
Vector2 edge_direction(const std::vector<Point>& v, std::size_t edge)
{
  return (v[(edge + 1) % v.size()] - v[edge]).normalized();
}

/// outer[block][edge]: no joint lies on that edge.
std::vector<std::vector<bool>> outer_edges(const std::vector<Block>& blocks,
                                           const std::vector<Joint>& joints)
{
  std::vector<std::vector<bool>> outer;
  for (const Block& b : blocks)
    outer.emplace_back(b.vertices.size(), true);
  for (const Joint& j : joints)
  {
    outer[j.block_a][j.edge_a] = false;
    outer[j.block_b][j.edge_b] = false;
  }
  return outer;
}

double distance_to_line(const Point& p, const Point& on_line, const Vector2& unit_direction)
{
  const Vector2 r = p - on_line;
  return std::abs(r.x() * unit_direction.y() - r.y() * unit_direction.x());
}
} // namespace

BoundaryWaveSpeeds effective_wave_speeds(const ModelDescription& model,
                                         const std::vector<Block>& blocks,
                                         const std::vector<Joint>& joints, std::size_t block,
                                         std::size_t edge, double tol)
{
  const Block& b = blocks[block];
  const Material& mat = model.materials[b.material];
  const double e = mat.youngs_modulus, nu = mat.poisson_ratio;
  const double g_modulus = shear_modulus(e, nu);
  const Vector2 t = edge_direction(b.vertices, edge);
  const Vector2 n(t.y(), -t.x());

  // Depth of the block along the normal.
  double lo = n.dot(b.vertices[0]), hi = lo;
  for (const Point& v : b.vertices)
  {
    lo = std::min(lo, n.dot(v));
    hi = std::max(hi, n.dot(v));
  }
  const double depth = hi - lo;

  // One pass over this block's joints: those on an edge parallel to the boundary edge lie behind
  // it (in series with the block); one on a side edge (direction along the normal) confines it.
  double springs_n = 0.0, springs_s = 0.0, joint_length = 0.0;
  bool sides_free = true;
  for (const Joint& j : joints)
  {
    if (j.block_a != block && j.block_b != block)
      continue;
    const std::size_t k = j.block_a == block ? j.edge_a : j.edge_b;
    if (k == edge)
      continue;
    const Vector2 tk = edge_direction(b.vertices, k);
    if (std::abs(tk.dot(n)) > 0.5)
      sides_free = false;
    if (std::abs(tk.x() * t.y() - tk.y() * t.x()) > tol)
      continue;
    const JointMaterial& jm = model.joint_materials[j.joint_material];
    springs_n += 2.0 * jm.normal_stiffness;
    springs_s += 2.0 * jm.shear_ratio * jm.normal_stiffness;
    joint_length += j.length;
  }

  // P modulus: plane strain, plane-stress plate, or a plane-stress bar (side edges free).
  double p_modulus = p_wave_modulus(e, nu);
  if (model.plane_mode == PlaneMode::stress)
    p_modulus = sides_free ? e : e / (1.0 - nu * nu);

  double p_eff = p_modulus, g_eff = g_modulus;
  if (joint_length > 0.0)
  {
    // Joint stiffness per unit area [Pa/m] times the depth it acts over gives a modulus.
    p_eff = 1.0 / (1.0 / p_modulus + 1.0 / (depth * springs_n / joint_length));
    g_eff = 1.0 / (1.0 / g_modulus + 1.0 / (depth * springs_s / joint_length));
  }
  return {std::sqrt(p_eff / mat.density), std::sqrt(g_eff / mat.density)};
}

std::vector<BoundaryEdge> select_boundary_edges(std::size_t boundary_index,
                                                const ModelDescription& model,
                                                const std::vector<Block>& blocks,
                                                const std::vector<Joint>& joints, double tol)
{
  const BoundaryDescription& bd = model.boundaries[boundary_index];
  const std::string name =
      bd.origin.empty() ? "boundary " + std::to_string(boundary_index) : bd.origin;
  const std::vector<std::vector<bool>> outer = outer_edges(blocks, joints);

  std::vector<std::pair<std::size_t, std::size_t>> selected;
  if (!bd.edges.empty())
  {
    for (const auto& [block, edge] : bd.edges)
    {
      if (block >= blocks.size() || edge >= blocks[block].vertices.size())
        throw InputError(name + ": edge [" + std::to_string(block) + ", " + std::to_string(edge) +
                         "] does not exist: expected a block index below " +
                         std::to_string(blocks.size()) +
                         " and an edge index below its vertex count");
      if (!outer[block][edge])
        throw InputError(name + ": edge [" + std::to_string(block) + ", " + std::to_string(edge) +
                         "] is shared with another block by a joint: expected an outer edge");
      selected.emplace_back(block, edge);
    }
  }
  else
  {
    const Vector2 direction = bd.line_direction.normalized();
    for (std::size_t i = 0; i < blocks.size(); ++i)
      for (std::size_t k = 0; k < blocks[i].vertices.size(); ++k)
      {
        if (!outer[i][k])
          continue;
        const Point& p = blocks[i].vertices[k];
        const Point& q = blocks[i].vertices[(k + 1) % blocks[i].vertices.size()];
        if (bd.on_line && (distance_to_line(p, bd.line_point, direction) > tol ||
                           distance_to_line(q, bd.line_point, direction) > tol))
          continue;
        selected.emplace_back(i, k);
      }
  }
  if (selected.empty())
  {
    std::ostringstream s;
    s << name << " selects no block edge";
    if (bd.on_line)
      s << ": no outer edge lies on the line through (" << bd.line_point.x() << ", "
        << bd.line_point.y() << ") with direction (" << bd.line_direction.x() << ", "
        << bd.line_direction.y() << ")";
    s << "; expected at least one outer block edge";
    throw InputError(s.str());
  }

  std::vector<BoundaryEdge> edges;
  for (const auto& [block, edge] : selected)
  {
    const Block& b = blocks[block];
    const Material& mat = model.materials[b.material];
    const Point& p = b.vertices[edge];
    const Point& q = b.vertices[(edge + 1) % b.vertices.size()];
    BoundaryEdge e;
    e.boundary = boundary_index;
    e.block = block;
    e.edge = edge;
    const Point mid = 0.5 * (p + q);
    e.midpoint = {block, mid, mid};
    e.length = (q - p).norm();
    e.textbook = textbook_wave_speeds(mat);
    e.effective = effective_wave_speeds(model, blocks, joints, block, edge, tol);
    e.speeds = bd.impedance == ImpedanceKind::effective ? e.effective : e.textbook;
    e.cn = bd.a_n * mat.density * e.length * e.speeds.p;
    e.ct = bd.a_t * mat.density * e.length * e.speeds.s;
    edges.push_back(e);
  }
  return edges;
}

BoundaryStability boundary_stability(BoundaryType type, const BoundaryEdge& edge, double mass,
                                     double dt)
{
  BoundaryStability s;
  s.mass = mass;
  s.x_n = edge.cn * dt / mass;
  s.x_t = edge.ct * dt / mass;
  if (type == BoundaryType::vb1)
  {
    const double c_max = std::max(edge.cn, edge.ct);
    s.dt_source = vb1_source_threshold() * mass / c_max;
    s.dt_paper_bound = mass / edge.cn;
    s.dt_paper_source = 2.0 * mass / edge.ct;
    s.is_source = dt > s.dt_source;
  }
  return s;
}

BoundaryStep boundary_step(BoundaryType type, const BoundaryEdge& edge, const Vector2& normal,
                           double mass, double dt, double beta, double gamma,
                           const Vector2& velocity0, const Vector2& acceleration0)
{
  // R has rows n and t (t = (-n_y, n_x) is the edge direction): (un, ut) = R u.
  Eigen::Matrix2d r;
  r.row(0) = normal.transpose();
  r.row(1) = Vector2(-normal.y(), normal.x()).transpose();
  const Eigen::Matrix2d c = Eigen::Vector2d(edge.cn, edge.ct).asDiagonal();
  BoundaryStep step;
  switch (type)
  {
  case BoundaryType::free:
    break;
  case BoundaryType::vb1:
  {
    // Eq. 39: (1/dt) C D - C^2 / m in (n, t) components.
    const Eigen::Matrix2d d =
        Eigen::Vector2d(vb1_factor(edge.cn * dt / mass), vb1_factor(edge.ct * dt / mass))
            .asDiagonal();
    step.k = r.transpose() * (c * d / dt - c * c / mass) * r;
    break;
  }
  case BoundaryType::vb2:
    step.k = (2.0 / dt) * r.transpose() * c * r;
    break;
  case BoundaryType::dashpot:
  {
    // Force -C v1 with Newmark's v1 = gamma / (beta dt) d + (1 - gamma / beta) v0
    // + dt (1 - gamma / (2 beta)) a0 (both integrators: 2 d / dt - v0).
    const Eigen::Matrix2d cg = r.transpose() * c * r;
    step.k = newmark_coefficients(beta, gamma, dt).damping_u * cg;
    step.f = -cg * newmark_velocity_offset<Vector2>(beta, gamma, dt, velocity0, acceleration0);
    break;
  }
  }
  return step;
}

} // namespace ddafem::dda
