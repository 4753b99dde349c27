// DistributedWaveModel free-field sides: the serial 1D column of ElasticWaveModel
// (fem/free_field_column.cc), replicated on every rank (a strip one element wide), advanced
// alongside and sampled at the quadrature points of the rank's own free_field faces; its
// tractions sigma_ff n + D v_ff load the far field's sides, whose dashpots D take the outgoing
// part.
#include "fem/distributed_wave_model_impl.h"

#include "fem/far_field_kernels.h"
#include "fem/far_field_mesh.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <array>
#include <memory>
#include <stdexcept>
#include <vector>

namespace ddafem::fem
{
bool DistributedWaveModel::Impl::is_free_field_face(const DoFHandler<2>::active_cell_iterator& cell,
                                                    const unsigned int f) const
{
  return cell->is_locally_owned() && cell->face(f)->at_boundary() &&
         is_free_field_part(description, cell->face(f)->boundary_id());
}

void DistributedWaveModel::Impl::make_free_field_column()
{
  const FarFieldDescription& d = description;
  if (std::none_of(d.boundaries.begin(), d.boundaries.end(),
                   [](const BoundaryCondition& bc) { return bc.kind == BoundaryKind::free_field; }))
    return;
  column = std::make_unique<ElasticWaveModel>(free_field_column_description(d, h));
  FEFaceValues<2> values(fe, QGauss<1>(fe.degree + 1), update_quadrature_points);
  for (const auto& cell : dof_handler.active_cell_iterators())
    for (const unsigned int f : cell->face_indices())
      if (is_free_field_face(cell, f))
      {
        values.reinit(cell, f);
        for (const unsigned int q : values.quadrature_point_indices())
        {
          const auto [x, y] = free_field_column_point(d, h, values.quadrature_point(q)[1]);
          column_probes.push_back(column->add_probe(x, y));
        }
      }
  free_field_load.reinit(owned, comm);
}

void DistributedWaveModel::Impl::advance_column(const double dt)
{
  // A step prepared and not finished (the blocks cut dt) advanced the column: it goes back to
  // the step's start first.
  if (column_ahead)
    column->return_to_remembered_state();
  else
    column->remember_state();
  const StepResult status = column->advance(dt);
  column_ahead = true;
  if (!status.taken)
    throw std::runtime_error("free-field column: " + status.why);
}

void DistributedWaveModel::Impl::add_free_field_load(TrilinosWrappers::MPI::Vector& f)
{
  const double rho = description.density;
  FEFaceValues<2> values(fe, QGauss<1>(fe.degree + 1),
                         update_values | update_normal_vectors | update_JxW_values);
  const unsigned int n = fe.n_dofs_per_cell();
  Vector<double> cell_load(n);
  std::vector<types::global_dof_index> dofs(n);
  free_field_load = 0.0;
  free_field_load.compress(VectorOperation::insert); // every rank: see set_spring_loads
  std::size_t probe = 0;
  for (const auto& cell : dof_handler.active_cell_iterators())
    for (const unsigned int face : cell->face_indices())
    {
      if (!is_free_field_face(cell, face))
        continue;
      values.reinit(cell, face);
      cell_load = 0.0;
      for (const unsigned int q : values.quadrature_point_indices())
      {
        const MonitorSample ff = column->sample_probe(column_probes[probe++]);
        const std::array<double, 2> traction =
            free_field_traction(ff.stress, ff.velocity, values.normal_vector(q), rho, vp, vs);
        for (unsigned int i = 0; i < n; ++i)
          cell_load(i) += values.shape_value(i, q) *
                          traction[fe.system_to_component_index(i).first] * values.JxW(q);
      }
      cell->get_dof_indices(dofs);
      constraints.distribute_local_to_global(cell_load, dofs, free_field_load);
    }
  free_field_load.compress(VectorOperation::add);
  f += free_field_load;
}

std::array<double, 2> DistributedWaveModel::free_field_velocity(const double y) const
{
  AssertThrow(impl->column, ExcMessage("free_field_velocity: the model has no free_field side"));
  const auto [x, y_column] = free_field_column_point(impl->description, impl->h, y);
  return impl->column->velocity_at(x, y_column);
}

} // namespace ddafem::fem
