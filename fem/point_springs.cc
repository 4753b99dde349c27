// ElasticWaveModel point springs: ties of far-field points to outside bodies (coupling/), their
// shape functions and the flexibility G = N P^-1 N^T.
#include "fem/elastic_wave_model_impl.h"

#include <deal.II/base/quadrature.h>
#include <deal.II/fe/mapping_q1.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace ddafem::fem
{
using namespace far_field_detail;

std::vector<double> ElasticWaveModel::Impl::evaluate_at_springs(const Vector<double>& x) const
{
  std::vector<double> out(2 * springs.size(), 0.0);
  for (std::size_t k = 0; k < springs.size(); ++k)
  {
    const SpringPoint& sp = springs[k];
    for (std::size_t i = 0; i < sp.dofs.size(); ++i)
      out[2 * k + sp.component[i]] += sp.phi[i] * x(sp.dofs[i]);
  }
  return out;
}

void ElasticWaveModel::Impl::add_spring_loads(const std::vector<double>& q,
                                              Vector<double>& rhs) const
{
  for (std::size_t k = 0; k < springs.size(); ++k)
  {
    const SpringPoint& sp = springs[k];
    for (std::size_t i = 0; i < sp.dofs.size(); ++i)
      rhs(sp.dofs[i]) += sp.phi[i] * q[2 * k + sp.component[i]];
  }
}

std::vector<double> ElasticWaveModel::add_point_springs(const BoundaryPart part,
                                                        const std::vector<PointSpring>& new_springs)
{
  Impl& m = *impl;
  require(!m.description.static_stage.enabled,
          "point springs (ties to DDA blocks) with a far-field static stage are not supported: "
          "expected no `far_field.static_stage` in a coupled scene");
  // The faces of the part, with their cells.
  std::vector<std::pair<DoFHandler<2>::active_cell_iterator, unsigned int>> faces;
  for (const auto& cell : m.dof_handler.active_cell_iterators())
    for (const unsigned int f : cell->face_indices())
      if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == boundary_id_of(part))
        faces.emplace_back(cell, f);
  require(!faces.empty(),
          std::string("point springs: the far field has no boundary part '") + name_of(part) + "'");
  const MappingQ1<2> mapping;
  std::vector<double> distances;
  for (const PointSpring& ps : new_springs)
  {
    // The nearest point of the part's (straight, Q1-mapped) faces.
    const Point<2> p(ps.point[0], ps.point[1]);
    double best = std::numeric_limits<double>::infinity();
    Point<2> nearest;
    DoFHandler<2>::active_cell_iterator cell;
    for (const auto& [c, f] : faces)
    {
      const Point<2> a = c->face(f)->vertex(0), b = c->face(f)->vertex(1);
      const Tensor<1, 2> ab = b - a;
      const double s = std::clamp(((p - a) * ab) / ab.norm_square(), 0.0, 1.0);
      const Point<2> q = a + s * ab;
      if (q.distance(p) < best)
      {
        best = q.distance(p);
        nearest = q;
        cell = c;
      }
    }
    distances.push_back(best);
    const Point<2> reference =
        GeometryInfo<2>::project_to_unit_cell(mapping.transform_real_to_unit_cell(cell, nearest));
    FEValues<2> values(mapping, m.fe, Quadrature<2>(std::vector<Point<2>>{reference}),
                       update_values);
    values.reinit(cell);
    std::vector<types::global_dof_index> dofs(m.fe.n_dofs_per_cell());
    cell->get_dof_indices(dofs);
    Impl::SpringPoint sp;
    for (unsigned int i = 0; i < dofs.size(); ++i)
    {
      const double phi = values.shape_value(i, 0);
      if (std::abs(phi) < 1e-14)
        continue;
      sp.dofs.push_back(dofs[i]);
      sp.phi.push_back(phi);
      sp.component.push_back(m.fe.system_to_component_index(i).first);
    }
    sp.k[0][0] = ps.stiffness[0];
    sp.k[0][1] = ps.stiffness[1];
    sp.k[1][0] = ps.stiffness[2];
    sp.k[1][1] = ps.stiffness[3];
    m.springs.push_back(std::move(sp));
  }
  m.spring_force.assign(2 * m.springs.size(), 0.0);
  m.forget_factorizations(); // the effective matrix gains N^T K N
  return distances;
}

std::vector<std::vector<double>>
ElasticWaveModel::Impl::unit_load_responses(const std::vector<types::global_dof_index>& dofs,
                                            const bool by_dof)
{
  // Column j of the response: P^-1 applied to unit load j, restricted to `dofs`; solved a
  // batch of columns at a time (direct solvers read their factor once for several).
  const std::size_t n = 2 * springs.size();
  const std::size_t n_loads = by_dof ? dofs.size() : n;
  std::vector<std::vector<double>> response(n_loads, std::vector<double>(dofs.size()));
  constexpr std::size_t batch = 64;
  std::vector<double> unit(n, 0.0);
  std::vector<Vector<double>> rhs, x;
  for (std::size_t first = 0; first < n_loads; first += batch)
  {
    rhs.assign(std::min(batch, n_loads - first), Vector<double>(u.size()));
    for (std::size_t j = first; j < first + rhs.size(); ++j)
    {
      Vector<double>& r = rhs[j - first];
      if (by_dof)
        r(dofs[j]) = 1.0;
      else
      {
        unit[j] = 1.0;
        add_spring_loads(unit, r);
        unit[j] = 0.0;
      }
      condense_rhs(r);
    }
    solver().solve_columns(rhs, x);
    for (std::size_t j = first; j < first + rhs.size(); ++j)
    {
      constraints.distribute(x[j - first]);
      for (std::size_t b = 0; b < dofs.size(); ++b)
        response[j][b] = x[j - first](dofs[b]);
    }
  }
  return response;
}

std::vector<double> ElasticWaveModel::point_flexibility(const double dt)
{
  Impl& m = *impl;
  const auto start = Clock::now();
  m.ensure_factorized(dt);
  const std::size_t n = 2 * m.springs.size();
  // The DOFs the springs touch: G = N P^-1 N^T = N_D (P^-1)_DD N_D^T needs one solve per such
  // DOF, or one per spring component (unit point loads), whichever are fewer (3 springs per
  // FE_Q2 face touch about 4 DOFs per face against 6 spring components; more springs per face
  // when the blocks are smaller than the elements).
  std::vector<types::global_dof_index> dofs;
  for (const Impl::SpringPoint& sp : m.springs)
    dofs.insert(dofs.end(), sp.dofs.begin(), sp.dofs.end());
  std::sort(dofs.begin(), dofs.end());
  dofs.erase(std::unique(dofs.begin(), dofs.end()), dofs.end());
  const bool by_dof = dofs.size() < n;

  // Row i of N: (position in `dofs`, shape value) of spring i / 2, component i % 2.
  std::vector<std::vector<std::pair<std::size_t, double>>> rows(n);
  for (std::size_t k = 0; k < m.springs.size(); ++k)
  {
    const Impl::SpringPoint& sp = m.springs[k];
    for (std::size_t a = 0; a < sp.dofs.size(); ++a)
      rows[2 * k + sp.component[a]].emplace_back(
          static_cast<std::size_t>(std::lower_bound(dofs.begin(), dofs.end(), sp.dofs[a]) -
                                   dofs.begin()),
          sp.phi[a]);
  }

  const std::vector<std::vector<double>> response = m.unit_load_responses(dofs, by_dof);

  // G_ij = sum_a N_ia (response of load j)_a, with load j = sum_b N_jb e_b when by DOF.
  std::vector<double> g(n * n, 0.0);
  std::vector<double> column(dofs.size());
  for (std::size_t j = 0; j < n; ++j)
  {
    if (by_dof)
    {
      std::fill(column.begin(), column.end(), 0.0);
      for (const auto& [b, phi] : rows[j])
        for (std::size_t a = 0; a < dofs.size(); ++a)
          column[a] += phi * response[b][a];
    }
    else
      column = response[j];
    for (std::size_t i = 0; i < n; ++i)
      for (const auto& [a, phi] : rows[i])
        g[i * n + j] += phi * column[a];
  }
  m.timings.setup += seconds_since(start);
  return g;
}

} // namespace ddafem::fem
