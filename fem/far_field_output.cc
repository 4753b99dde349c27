// ElasticWaveModel output: monitor samples, VTU/PVD snapshots with stresses, L2 errors.
#include "fem/elastic_wave_model_impl.h"

#include "common/vtk_collection.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>
#include <deal.II/numerics/vector_tools.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

namespace ddafem::fem
{
using namespace far_field_detail;

namespace
{
/// Stress components and von Mises from the displacement field plus the in-situ stress, for
/// DataOut.
class StressPostprocessor : public DataPostprocessor<2>
{
public:
  StressPostprocessor(const PlaneElasticity& elasticity_,
                      std::function<std::array<double, 3>(double)> initial_)
      : elasticity(elasticity_), initial(std::move(initial_))
  {
  }

  void evaluate_vector_field(const DataPostprocessorInputs::Vector<2>& inputs,
                             std::vector<Vector<double>>& computed) const override
  {
    for (unsigned int q = 0; q < inputs.solution_gradients.size(); ++q)
    {
      auto s = elasticity.stress(inputs.solution_gradients[q][0], inputs.solution_gradients[q][1]);
      const auto s0 = initial(inputs.evaluation_points[q][1]);
      for (unsigned int k = 0; k < 3; ++k)
        s[k] += s0[k];
      computed[q](0) = s[0];
      computed[q](1) = s[1];
      computed[q](2) = s[2];
      computed[q](3) = elasticity.von_mises(s);
    }
  }

  std::vector<std::string> get_names() const override { return {"sxx", "syy", "sxy", "von_mises"}; }

  std::vector<DataComponentInterpretation::DataComponentInterpretation>
  get_data_component_interpretation() const override
  {
    return std::vector<DataComponentInterpretation::DataComponentInterpretation>(
        4, DataComponentInterpretation::component_is_scalar);
  }

  UpdateFlags get_needed_update_flags() const override
  {
    return update_gradients | update_quadrature_points;
  }

private:
  PlaneElasticity elasticity;
  std::function<std::array<double, 3>(double)> initial;
};
/// Writes `data_out` as VTU to `path` through a temporary file renamed into place (a run killed
/// meanwhile leaves the old file or the new one); a failed write (a full disk) throws
/// std::runtime_error naming the file and leaves no part behind.
void write_vtu_atomically(const DataOut<2>& data_out, const std::filesystem::path& path)
{
  std::filesystem::path temporary = path;
  temporary += ".tmp";
  bool written = false;
  try
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (out)
      data_out.write_vtu(out);
    out.close();
    written = static_cast<bool>(out);
  }
  catch (const std::exception&)
  {
    written = false; // deal.II's ExcIO on a failed stream
  }
  std::error_code ec;
  if (written)
    std::filesystem::rename(temporary, path, ec);
  if (!written || ec)
  {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw std::runtime_error("cannot write " + path.string() +
                             " (is the disk full or not writable?)");
  }
}
} // namespace

MonitorSample ElasticWaveModel::Impl::sample_monitor(const std::size_t monitor) const
{
  AssertThrow(monitor < monitors.size(),
              ExcMessage("monitor index " + std::to_string(monitor) + " out of range [0, " +
                         std::to_string(monitors.size()) + ")"));
  const FEValues<2>& values = *monitors[monitor].values;
  std::vector<Vector<double>> point_u(1, Vector<double>(2)), point_v(1, Vector<double>(2));
  std::vector<std::vector<Tensor<1, 2>>> grad_u(1, std::vector<Tensor<1, 2>>(2));
  values.get_function_values(u, point_u);
  if (static_displacement.size() == u.size())
  {
    std::vector<Vector<double>> point_static(1, Vector<double>(2));
    values.get_function_values(static_displacement, point_static);
    point_u[0] -= point_static[0];
  }
  values.get_function_values(v, point_v);
  values.get_function_gradients(u, grad_u);
  MonitorSample sample;
  sample.displacement = {{point_u[0](0), point_u[0](1)}};
  sample.velocity = {{point_v[0](0), point_v[0](1)}};
  sample.stress = elasticity.stress(grad_u[0][0], grad_u[0][1]);
  const auto s0 = initial_stress(monitors[monitor].y);
  for (unsigned int k = 0; k < 3; ++k)
    sample.stress[k] += s0[k];
  return sample;
}

std::string ElasticWaveModel::Impl::write_snapshot(const std::string& directory,
                                                   const std::string& basename,
                                                   const VtuCompression compression)
{
  std::filesystem::create_directories(directory);
  std::ostringstream name;
  name << basename << "_" << std::setw(5) << std::setfill('0') << snapshots.size() << ".vtu";

  const StressPostprocessor stress(elasticity,
                                   [this](const double y) { return initial_stress(y); });
  const Vector<double> w = relative_displacement();
  const std::vector<DataComponentInterpretation::DataComponentInterpretation> vector_field(
      2, DataComponentInterpretation::component_is_part_of_vector);
  DataOut<2> data_out;
  data_out.attach_dof_handler(dof_handler);
  data_out.add_data_vector(w, std::vector<std::string>(2, "displacement"),
                           DataOut<2>::type_dof_data, vector_field);
  data_out.add_data_vector(v, std::vector<std::string>(2, "velocity"), DataOut<2>::type_dof_data,
                           vector_field);
  data_out.add_data_vector(u, stress);
  data_out.build_patches(fe.degree);
  DataOutBase::VtkFlags flags;
  flags.time = t;
  flags.compression_level =
      compression == VtuCompression::none         ? DataOutBase::VtkFlags::no_compression
      : compression == VtuCompression::best_speed ? DataOutBase::VtkFlags::best_speed
                                                  : DataOutBase::VtkFlags::best_compression;
  data_out.set_flags(flags);
  write_vtu_atomically(data_out, std::filesystem::path(directory) / name.str());
  snapshots.emplace_back(t, name.str());
  // Spelt as DataOutBase::write_pvd_record spells it: its comment, 12 digits, "ByteOrder".
  std::vector<CollectionDataSet> data_sets;
  for (const auto& [when, file] : snapshots)
    data_sets.push_back({when, 0, file});
  CollectionStyle style;
  style.time_precision = 12;
  style.comment = "#This file was generated by the deal.II library on " +
                  Utilities::System::get_date() + " at " + Utilities::System::get_time();
  style.byte_order_attribute = "ByteOrder";
  write_collection(std::filesystem::path(directory) / (basename + ".pvd"), data_sets, style);
  return name.str();
}

double ElasticWaveModel::l2_error(const VectorField& exact_displacement) const
{
  Vector<float> per_cell(impl->mesh.n_active_cells());
  VectorTools::integrate_difference(impl->dof_handler, impl->relative_displacement(),
                                    FieldFunction(exact_displacement), per_cell,
                                    QGauss<2>(impl->fe.degree + 2), VectorTools::L2_norm);
  return VectorTools::compute_global_error(impl->mesh, per_cell, VectorTools::L2_norm);
}

} // namespace ddafem::fem
