// DistributedWaveModel point springs: the far field's side of the ties to the blocks
// (fem/point_spring_field.h) across MPI ranks. A spring lives on the rank that owns the cell of
// its point; what the blocks see (N y, G) is summed over the ranks from that rank's value and
// zeros, which gives every rank the same bits in any order of summation.
#include "fem/distributed_wave_model_impl.h"

#include "common/format.h"
#include "common/input_error.h"
#include "common/stopwatch.h"
#include "fem/far_field_kernels.h"
#include "fem/far_field_mesh.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/utilities.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace ddafem::fem
{
namespace
{
using Face = std::pair<DoFHandler<2>::active_cell_iterator, unsigned int>;

/// This rank's faces of a boundary part, with their cells.
std::vector<Face> owned_faces(const DoFHandler<2>& dof_handler, const BoundaryPart part)
{
  std::vector<Face> faces;
  for (const auto& cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == boundary_id_of(part))
          faces.emplace_back(cell, f);
  return faces;
}

/// The point of the faces nearest to p (straight, Q1-mapped faces), its cell and distance [m]
/// (infinite without faces).
std::pair<Point<2>, Face> nearest_on(const std::vector<Face>& faces, const Point<2>& p,
                                     double& distance)
{
  distance = std::numeric_limits<double>::infinity();
  std::pair<Point<2>, Face> best;
  for (const Face& face : faces)
  {
    const Point<2> a = face.first->face(face.second)->vertex(0);
    const Point<2> b = face.first->face(face.second)->vertex(1);
    const Tensor<1, 2> ab = b - a;
    const double s = std::clamp(((p - a) * ab) / ab.norm_square(), 0.0, 1.0);
    const Point<2> q = a + s * ab;
    if (q.distance(p) < distance)
    {
      distance = q.distance(p);
      best = {q, face};
    }
  }
  return best;
}
} // namespace

std::vector<double>
DistributedWaveModel::Impl::springs_share_of(const TrilinosWrappers::MPI::Vector& x) const
{
  const TrilinosWrappers::MPI::Vector& field = ghosted_field(x);
  std::vector<double> out(2 * springs.size(), 0.0);
  for (std::size_t k = 0; k < springs.size(); ++k)
    for (std::size_t i = 0; i < springs[k].dofs.size(); ++i)
      out[2 * k + springs[k].component[i]] += springs[k].phi[i] * field(springs[k].dofs[i]);
  return out;
}

std::vector<double>
DistributedWaveModel::Impl::evaluate_at_springs(const TrilinosWrappers::MPI::Vector& x) const
{
  std::vector<double> out = springs_share_of(x);
  Utilities::MPI::sum(out, comm, out);
  return out;
}

void DistributedWaveModel::Impl::set_spring_loads(const std::vector<double>& q,
                                                  TrilinosWrappers::MPI::Vector& rhs) const
{
  // Every rank flushes the vector's writes (compress), so that only the owners' additions follow:
  // a rank whose first addition found pending writes would flush them alone and wait.
  rhs = 0.0;
  rhs.compress(VectorOperation::insert);
  Vector<double> local;
  for (std::size_t k = 0; k < springs.size(); ++k)
  {
    const SpringPoint& sp = springs[k];
    if (!sp.mine)
      continue;
    local.reinit(sp.dofs.size());
    for (std::size_t i = 0; i < sp.dofs.size(); ++i)
      local(i) = sp.phi[i] * q[2 * k + sp.component[i]];
    constraints.distribute_local_to_global(local, sp.dofs, rhs);
  }
  rhs.compress(VectorOperation::add);
}

void DistributedWaveModel::Impl::add_work_of_springs(const TrilinosWrappers::MPI::Vector& u_new,
                                                     const std::vector<double>& point_loads)
{
  // F = q - K N u on the far field; its work with mid-step forces.
  const std::vector<double> w_old = evaluate_at_springs(u);
  const std::vector<double> w_new = evaluate_at_springs(u_new);
  add_spring_work_of_step(springs, point_loads, w_old, w_new, spring_force,
                          energies.work_of_springs);
}

std::vector<std::array<double, 4>>
DistributedWaveModel::boundary_segments(const BoundaryPart part) const
{
  std::vector<double> mine;
  for (const auto& [cell, f] : owned_faces(impl->dof_handler, part))
    for (const unsigned int v : {0u, 1u})
      for (const unsigned int d : {0u, 1u})
        mine.push_back(cell->face(f)->vertex(v)[d]);
  std::vector<std::array<double, 4>> segments;
  for (const std::vector<double>& theirs : Utilities::MPI::all_gather(impl->comm, mine))
    for (std::size_t i = 0; i + 3 < theirs.size(); i += 4)
      segments.push_back({theirs[i], theirs[i + 1], theirs[i + 2], theirs[i + 3]});
  std::sort(segments.begin(), segments.end());
  return segments;
}

std::vector<double>
DistributedWaveModel::add_point_springs(const BoundaryPart part,
                                        const std::vector<PointSpring>& new_springs)
{
  Impl& m = *impl;
  const std::vector<Face> faces = owned_faces(m.dof_handler, part);
  if (Utilities::MPI::sum(faces.size(), m.comm) == 0)
    throw InputError(std::string("far field (distributed): point springs: no boundary part '") +
                     name_of(part) + "'");
  const unsigned int rank = Utilities::MPI::this_mpi_process(m.comm);
  const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(m.comm);
  const MappingQ1<2> mapping;
  std::vector<double> distances;
  for (const PointSpring& ps : new_springs)
  {
    const Point<2> p(ps.point[0], ps.point[1]);
    double distance = 0.0;
    const auto [nearest, face] = nearest_on(faces, p, distance);
    // The nearest face's owner takes the spring; of equally near ones, the lowest rank.
    const double best = Utilities::MPI::min(distance, m.comm);
    const unsigned int owner = Utilities::MPI::min(distance == best ? rank : n_ranks, m.comm);
    distances.push_back(best);
    Impl::SpringPoint sp;
    sp.k[0][0] = ps.stiffness[0];
    sp.k[0][1] = ps.stiffness[1];
    sp.k[1][0] = ps.stiffness[2];
    sp.k[1][1] = ps.stiffness[3];
    sp.mine = owner == rank;
    if (sp.mine)
    {
      const Point<2> reference = GeometryInfo<2>::project_to_unit_cell(
          mapping.transform_real_to_unit_cell(face.first, nearest));
      FEValues<2> values(mapping, m.fe, Quadrature<2>(std::vector<Point<2>>{reference}),
                         update_values);
      values.reinit(face.first);
      sp.dofs.resize(m.fe.n_dofs_per_cell());
      face.first->get_dof_indices(sp.dofs);
      for (unsigned int i = 0; i < sp.dofs.size(); ++i)
      {
        sp.phi.push_back(values.shape_value(i, 0));
        sp.component.push_back(m.fe.system_to_component_index(i).first);
      }
    }
    m.springs.push_back(std::move(sp));
  }
  m.spring_force.assign(2 * m.springs.size(), 0.0);

  // N^T K N of every spring, on the matrices' pattern (a spring's cell is owned here).
  m.springs_matrix.reinit(m.stiffness);
  m.springs_matrix = 0.0;
  FullMatrix<double> local;
  for (const Impl::SpringPoint& sp : m.springs)
  {
    if (!sp.mine)
      continue;
    local.reinit(sp.dofs.size(), sp.dofs.size());
    for (std::size_t i = 0; i < sp.dofs.size(); ++i)
      for (std::size_t j = 0; j < sp.dofs.size(); ++j)
        local(i, j) = sp.phi[i] * sp.k[sp.component[i]][sp.component[j]] * sp.phi[j];
    m.constraints.distribute_local_to_global(local, sp.dofs, m.springs_matrix);
  }
  m.springs_matrix.compress(VectorOperation::add);
  m.levels.clear(); // P gains N^T K N at the next set-up
  return distances;
}

std::vector<double> DistributedWaveModel::point_flexibility(const double dt)
{
  Impl& m = *impl;
  const auto start = Clock::now();
  if (!m.initial_acceleration_done)
    m.compute_initial_acceleration();
  m.use_level(dt);
  // Column j of G: N P^-1 N^T e_j, the springs' displacements under unit point load j, solved
  // for `width` columns at a time (condensation_width, and at most 128 MB a block: MUMPS gathers
  // the block on rank 0).
  const std::size_t n = 2 * m.springs.size();
  TrilinosWrappers::MPI::Vector& rhs = m.scratch.rhs;
  TrilinosWrappers::MPI::Vector& x = m.scratch.combination;
  const std::size_t width = std::clamp<std::size_t>(
      std::size_t{16'000'000} / std::max<std::size_t>(rhs.size(), 1), 1, m.condensation_width);
  Epetra_MultiVector loads(rhs.trilinos_vector().Map(), static_cast<int>(std::min(width, n)));
  Epetra_MultiVector displacements(loads.Map(), loads.NumVectors());
  std::vector<double> g(n * n, 0.0), unit(n, 0.0);
  for (std::size_t first = 0; first < n; first += width)
  {
    const int columns = static_cast<int>(std::min(width, n - first));
    Epetra_MultiVector b(View, loads, 0, columns), y(View, displacements, 0, columns);
    for (int c = 0; c < columns; ++c)
    {
      unit[first + c] = 1.0;
      m.set_spring_loads(unit, rhs);
      unit[first + c] = 0.0;
      std::copy(rhs.begin(), rhs.end(), b[c]);
    }
    m.solve_block(y, b);
    for (int c = 0; c < columns; ++c)
    {
      std::copy(y[c], y[c] + y.MyLength(), x.begin());
      const std::vector<double> share = m.springs_share_of(x);
      for (std::size_t i = 0; i < n; ++i)
        g[i * n + first + c] = share[i];
    }
  }
  Utilities::MPI::sum(g, m.comm, g); // one nonzero term per entry: the same bits on every rank
  m.timings.factorize += seconds_since(start);
  return g;
}

StepResult DistributedWaveModel::prepare_step(const double dt,
                                              std::vector<double>& free_point_displacements)
{
  if (!(dt > 0.0 && std::isfinite(dt)))
    throw InputError("far field (distributed): advance: dt = " + format_number(dt) +
                     ", expected > 0");
  try
  {
    impl->prepare(dt);
    free_point_displacements = impl->evaluate_at_springs(impl->scratch.u_new);
  }
  catch (const std::exception& e) // a solver that did not converge, on every rank
  {
    impl->step_prepared = false;
    return StepResult::failure(std::string("far field (distributed): solver failed: ") + e.what());
  }
  return {};
}

StepResult DistributedWaveModel::finish_step(const std::vector<double>& point_loads)
{
  Impl& m = *impl;
  AssertThrow(point_loads.size() == 2 * m.springs.size(),
              ExcMessage("finish_step(): " + std::to_string(point_loads.size()) +
                         " point loads for " + std::to_string(m.springs.size()) + " springs"));
  // The blocks run on every rank: their loads must agree to the bit.
  std::vector<double> loads(point_loads);
  const int root = 0;
  MPI_Bcast(loads.data(), static_cast<int>(loads.size()), MPI_DOUBLE, root, m.comm);
  const bool same =
      std::memcmp(loads.data(), point_loads.data(), loads.size() * sizeof(double)) == 0;
  const int parted = Utilities::MPI::max(same ? 0 : 1, m.comm);
  if (parted != 0)
  {
    m.step_prepared = false;
    return StepResult::failure(
        "far field (distributed): the blocks' loads on the ties differ between the MPI "
        "ranks at t = " +
        format_number(m.t) + ": the blocks, replicated on every rank, have parted");
  }
  try
  {
    return m.finish(loads);
  }
  catch (const std::exception& e)
  {
    return StepResult::failure(std::string("far field (distributed): solver failed: ") + e.what());
  }
}

std::vector<double> DistributedWaveModel::point_displacements() const
{
  return impl->evaluate_at_springs(impl->u);
}

void DistributedWaveModel::set_condensation_width(const unsigned int width)
{
  AssertThrow(width > 0, ExcMessage("set_condensation_width(): width 0"));
  impl->condensation_width = width;
}

double DistributedWaveModel::work_of_springs() const
{
  return impl->energies.work_of_springs;
}

} // namespace ddafem::fem
