// ElasticWaveModel free-field sides: a 1D column advanced alongside, sampled at the side faces
// (fem/README.md, free_field).
#include "fem/elastic_wave_model_impl.h"
#include "fem/far_field_kernels.h"

#include <deal.II/base/quadrature.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_tools.h>

#include <algorithm>
#include <memory>
#include <vector>

namespace ddafem::fem
{
using namespace far_field_detail;

void ElasticWaveModel::Impl::make_free_field_column()
{
  const auto& d = description;
  bool needed = false;
  for (const auto& bc : d.boundaries)
    needed = needed || bc.kind == BoundaryKind::free_field;
  if (!needed)
    return;
  // The column: one far-size element wide, the model's material, base and top, rollers.
  column = std::make_unique<ElasticWaveModel>(free_field_column_description(d, h));

  // The faces' shape values, weights and normals are the same at every step: kept with the
  // probes instead of an FEFaceValues built and reinit'd per face each step.
  const Impl& col = *column->impl;
  const QGauss<1> face_quadrature(fe.degree + 1);
  FEFaceValues<2> face_values(fe, face_quadrature,
                              update_values | update_quadrature_points | update_normal_vectors |
                                  update_JxW_values);
  const unsigned int n = fe.n_dofs_per_cell();
  std::vector<types::global_dof_index> dofs(n);
  for (const auto& cell : dof_handler.active_cell_iterators())
    for (const unsigned int f : cell->face_indices())
    {
      if (!is_free_field_face(cell, f))
        continue;
      face_values.reinit(cell, f);
      cell->get_dof_indices(dofs);
      for (const unsigned int q : face_values.quadrature_point_indices())
      {
        const auto [x, y] = free_field_column_point(d, h, face_values.quadrature_point(q)[1]);
        column_probes.push_back(col.make_probe(x, y));
        FreeFieldPoint point;
        point.normal = face_values.normal_vector(q);
        for (unsigned int i = 0; i < n; ++i)
        {
          const double weight = face_values.shape_value(i, q) * face_values.JxW(q);
          if (weight == 0.0)
            continue;
          point.dofs.push_back(dofs[i]);
          point.weight.push_back(weight);
          point.component.push_back(fe.system_to_component_index(i).first);
        }
        free_field_points.push_back(std::move(point));
      }
    }
}

PointProbe ElasticWaveModel::Impl::make_probe(const double x, const double y) const
{
  const MappingQ1<2> mapping;
  const auto found = GridTools::find_active_cell_around_point(mapping, dof_handler, Point<2>(x, y));
  const Point<2> reference = GeometryInfo<2>::project_to_unit_cell(found.second);
  FEValues<2> values(mapping, fe, Quadrature<2>(std::vector<Point<2>>{reference}),
                     update_values | update_gradients);
  values.reinit(found.first);
  PointProbe probe;
  probe.dofs.resize(fe.n_dofs_per_cell());
  found.first->get_dof_indices(probe.dofs);
  for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
  {
    probe.component.push_back(fe.system_to_component_index(i).first);
    probe.value.push_back(values.shape_value(i, 0));
    probe.gradient.push_back(values.shape_grad(i, 0));
  }
  return probe;
}

bool ElasticWaveModel::Impl::is_free_field_face(const DoFHandler<2>::active_cell_iterator& cell,
                                                const unsigned int f) const
{
  return cell->face(f)->at_boundary() &&
         is_free_field_part(description, cell->face(f)->boundary_id());
}

MonitorSample ElasticWaveModel::Impl::column_sample(const PointProbe& probe) const
{
  return column->impl->probe_sample(probe);
}

MonitorSample ElasticWaveModel::Impl::probe_sample(const PointProbe& probe) const
{
  const std::array<double, 2> velocity = probe.values(v);
  const std::array<Tensor<1, 2>, 2> grad_u = probe.gradients(u);
  MonitorSample sample;
  sample.velocity = velocity;
  sample.stress = elasticity.stress(grad_u[0], grad_u[1]);
  return sample;
}

std::size_t ElasticWaveModel::add_probe(const double x, const double y)
{
  impl->probes.push_back(impl->make_probe(x, y));
  return impl->probes.size() - 1;
}

MonitorSample ElasticWaveModel::sample_probe(const std::size_t k) const
{
  return impl->probe_sample(impl->probes.at(k));
}

void ElasticWaveModel::remember_state()
{
  impl->remembered = impl->save_state();
}

void ElasticWaveModel::return_to_remembered_state()
{
  impl->restore_state(impl->remembered);
}

void ElasticWaveModel::Impl::add_free_field_load(Vector<double>& f) const
{
  // The points in the order of the cells and faces, each added to f on its own (the faces used
  // to be summed per cell first: the last bits of f changed with that).
  const double rho = description.density;
  for (std::size_t k = 0; k < free_field_points.size(); ++k)
  {
    const FreeFieldPoint& point = free_field_points[k];
    const MonitorSample ff = column_sample(column_probes[k]);
    const std::array<double, 2> traction =
        free_field_traction(ff.stress, ff.velocity, point.normal, rho, vp, vs);
    for (std::size_t i = 0; i < point.dofs.size(); ++i)
      f(point.dofs[i]) += point.weight[i] * traction[point.component[i]];
  }
}

std::array<double, 2> ElasticWaveModel::free_field_velocity(const double y) const
{
  AssertThrow(impl->column, ExcMessage("free_field_velocity: the model has no free_field part"));
  const auto [x, y_column] = free_field_column_point(impl->description, impl->h, y);
  return impl->column->velocity_at(x, y_column);
}

std::array<double, 2> ElasticWaveModel::velocity_at(const double x, const double y) const
{
  return impl->probe_sample(impl->make_probe(x, y)).velocity;
}

} // namespace ddafem::fem
