// Linings in the System (dda/lining.h, docs/support.md "Lining"): their nodes on the blocks,
// their frame elements in the step's matrix and right-hand side, and their forces and breaks
// after each accepted step.
#include "dda/system.h"

#include "dda/submatrices.h"

#include <cmath>

namespace ddafem::dda
{
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
} // namespace

void System::attach_linings()
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
      n.point = attach(at[k], what + " node " + std::to_string(k));
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
      l.install(current_time);
    else
      for (LiningElement& e : l.elements)
        e.length0 = (l.nodes[e.b].installed - l.nodes[e.a].installed).norm();
    linings.push_back(l);
  }
}

void System::add_lining_terms(bool with_matrix)
{
  // Each intact element between two blocks: its forces at the step start on its nodes'
  // blocks, and G^T K G with G = [T; r0] of each node (the frame's linear stiffness in the
  // chord's current direction; small displacement: the installed one).
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
      const Vector2 e = small_displacement()
                            ? Vector2((nb.installed - na.installed).normalized())
                            : Vector2((nb.point.position - na.point.position).normalized());
      const std::size_t ba = na.point.block, bb = nb.point.block;
      const Matrix36 ga = node_matrix(point_matrix(na.point));
      const Matrix36 gb = node_matrix(point_matrix(nb.point));
      const Vector6 f = forces_on_nodes(el.forces, e);
      rhs.segment<6>(6 * ba).noalias() += ga.transpose() * f.head<3>();
      rhs.segment<6>(6 * bb).noalias() += gb.transpose() * f.tail<3>();
      if (!with_matrix)
        continue;
      const Matrix6 k = frame_stiffness_global(l.section, el.length0, e);
      matrix.diagonal(ba).noalias() += ga.transpose() * k.topLeftCorner<3, 3>() * ga;
      matrix.diagonal(bb).noalias() += gb.transpose() * k.bottomRightCorner<3, 3>() * gb;
      // The coupling block (i, j), i < j: row i's node against column j's.
      const std::size_t coupling = coupling_of(ba, bb);
      if (ba < bb)
        matrix.upper(coupling).noalias() += ga.transpose() * k.topRightCorner<3, 3>() * gb;
      else
        matrix.upper(coupling).noalias() += gb.transpose() * k.bottomLeftCorner<3, 3>() * ga;
    }
  }
}

void System::update_linings()
{
  // The clock of a static stage stands still: its events are recorded at the stage's time.
  for (Lining& l : linings)
  {
    if (!l.installed)
      continue;
    for (std::size_t k = 0; k < l.elements.size(); ++k)
    {
      LiningElement& e = l.elements[k];
      update_lining_element(e, l.section, l.nodes[e.a], l.nodes[e.b], current_time);
      if (e.check.utilisation > l.max_utilisation)
      {
        l.max_utilisation = e.check.utilisation;
        l.max_utilisation_time = current_time;
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

} // namespace ddafem::dda
