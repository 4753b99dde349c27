// ElasticWaveModel setup: input checks, the mesh and its element sizes, constraints, monitors.
#include "fem/elastic_wave_model_impl.h"

#include "fem/far_field_kernels.h"

#include <deal.II/base/quadrature.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/component_mask.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <limits>
#include <set>
#include <string>
#include <vector>

namespace ddafem::fem
{
using namespace far_field_detail;

void ElasticWaveModel::Impl::validate() const
{
  const auto& d = description;
  require(d.upper[0] > d.lower[0] && d.upper[1] > d.lower[1],
          "upper corner (" + format_number(d.upper[0]) + ", " + format_number(d.upper[1]) +
              ") must lie above and right of lower corner (" + format_number(d.lower[0]) + ", " +
              format_number(d.lower[1]) + ")");
  require(d.degree == 1 || d.degree == 2,
          "degree = " + std::to_string(d.degree) + ", expected 1 or 2");
  require(d.density > 0.0, "density = " + format_number(d.density) + ", expected > 0");
  require(d.youngs_modulus > 0.0,
          "youngs_modulus = " + format_number(d.youngs_modulus) + ", expected > 0");
  require(d.poisson_ratio >= 0.0 && d.poisson_ratio < 0.5,
          "poisson_ratio = " + format_number(d.poisson_ratio) + ", expected in [0, 0.5)");
  require(d.element_size >= 0.0,
          "element_size = " + format_number(d.element_size) + ", expected >= 0");
  require(d.dt >= 0.0, "dt = " + format_number(d.dt) + ", expected >= 0 (0: given to advance())");
  require(d.solver_tolerance > 0.0 && d.solver_tolerance < 1.0,
          "solver_tolerance = " + format_number(d.solver_tolerance) + ", expected in (0, 1)");
  const bool from_file = !d.mesh_file.file.empty();
  require(d.rayleigh.alpha >= 0.0 && d.rayleigh.beta >= 0.0,
          "rayleigh: alpha = " + format_number(d.rayleigh.alpha) +
              ", beta = " + format_number(d.rayleigh.beta) + ", expected both >= 0");
  if (d.element_size == 0.0 && !from_file)
  {
    const double f =
        d.max_frequency > 0.0 ? d.max_frequency : d.incident.velocity.characteristic_frequency();
    require(f > 0.0, "element_size = 0 needs max_frequency > 0 (or an incident wave with a "
                     "frequency) to choose the element size");
    require(d.points_per_wavelength > 0.0,
            "points_per_wavelength = " + format_number(d.points_per_wavelength) + ", expected > 0");
  }
  std::set<BoundaryPart> seen;
  for (const auto& bc : d.boundaries)
  {
    require(seen.insert(bc.part).second,
            std::string("boundary part '") + name_of(bc.part) + "' is listed twice");
    require(bc.a >= 0.0 && bc.b >= 0.0, std::string("boundary part '") + name_of(bc.part) +
                                            "': Lysmer coefficients a, b must be >= 0");
    if (bc.part == BoundaryPart::hole)
      require(d.hole.shape != HoleShape::none || d.mesh_file.parts.count(BoundaryPart::hole) > 0,
              "boundary part 'hole' is listed, but the far field has no hole (expected a `hole` "
              "section, or a Gmsh mesh with a `hole` tag in mesh.parts)");
    if (bc.kind == BoundaryKind::free_field)
    {
      require(bc.part == BoundaryPart::left || bc.part == BoundaryPart::right,
              std::string("boundary part '") + name_of(bc.part) +
                  "' is 'free_field', expected a lateral side (left or right)");
      require(!from_file, std::string("boundary part '") + name_of(bc.part) +
                              "' is 'free_field', which needs the generated rectangle (its "
                              "column spans [lower, upper] in y), not a mesh file");
    }
    if (bc.springs.enabled)
      require(bc.kind == BoundaryKind::lysmer && bc.springs.alpha_n >= 0.0 &&
                  bc.springs.alpha_t >= 0.0,
              std::string("boundary part '") + name_of(bc.part) +
                  "': springs need a lysmer part and alpha_n, alpha_t >= 0");
    if (bc.kind == BoundaryKind::input)
      require(bc.part == BoundaryPart::bottom || bc.part == BoundaryPart::top,
              std::string("boundary part '") + name_of(bc.part) +
                  "' is 'input', but a vertically incident wave enters through bottom or top");
  }
  for (const auto& m : d.monitors)
  {
    if (from_file)
      continue; // located in the mesh (locate_monitors)
    const double tol = 1e-9 * std::max(d.upper[0] - d.lower[0], d.upper[1] - d.lower[1]);
    require(m.point[0] >= d.lower[0] - tol && m.point[0] <= d.upper[0] + tol &&
                m.point[1] >= d.lower[1] - tol && m.point[1] <= d.upper[1] + tol,
            "monitor '" + m.name + "' at (" + format_number(m.point[0]) + ", " +
                format_number(m.point[1]) + ") lies outside the far field [" +
                format_number(d.lower[0]) + ", " + format_number(d.upper[0]) + "] x [" +
                format_number(d.lower[1]) + ", " + format_number(d.upper[1]) + "]");
  }
}

void ElasticWaveModel::Impl::make_mesh()
{
  const auto& d = description;
  const double target = d.mesh_file.file.empty() ? target_element_size(d, vs) : d.element_size;
  make_far_field_mesh(d, target, mesh);
  h = 0.0;
  h_min = std::numeric_limits<double>::infinity();
  for (const auto& cell : mesh.active_cell_iterators())
  {
    double longest = 0.0;
    for (const unsigned int f : cell->face_indices())
      longest = std::max(longest, cell->face(f)->diameter());
    h = std::max(h, longest);
    h_min = std::min(h_min, longest);
  }
}

void ElasticWaveModel::Impl::make_constraints()
{
  constraints.clear();
  DoFTools::make_hanging_node_constraints(dof_handler, constraints);
  add_support_constraints(dof_handler, description, constraints);
  constraints.close();
}

void ElasticWaveModel::Impl::locate_monitors()
{
  const MappingQ1<2> mapping;
  for (const auto& m : description.monitors)
  {
    const Point<2> p(m.point[0], m.point[1]);
    std::pair<DoFHandler<2>::active_cell_iterator, Point<2>> found;
    try
    {
      found = GridTools::find_active_cell_around_point(mapping, dof_handler, p);
    }
    catch (const std::exception&)
    {
      found.first = dof_handler.end();
    }
    require(found.first.state() == IteratorState::valid,
            "monitor '" + m.name + "' at (" + format_number(p[0]) + ", " + format_number(p[1]) +
                ") lies in no element, expected a point of the meshed far field (not in a hole)");
    const Point<2> reference = GeometryInfo<2>::project_to_unit_cell(found.second);
    MonitorPoint monitor;
    monitor.values =
        std::make_unique<FEValues<2>>(mapping, fe, Quadrature<2>(std::vector<Point<2>>{reference}),
                                      update_values | update_gradients);
    monitor.values->reinit(found.first);
    monitor.y = p[1];
    monitors.push_back(std::move(monitor));
  }
}

} // namespace ddafem::fem
