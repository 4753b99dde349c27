// deal.II elastodynamics of a rectangular far field (issue 5): mesh and matrices in the
// constructor, one Newmark step per advance() with a factorization reused across steps.
#include "fem/elastic_wave_model.h"

#include "common/input_error.h"
#include "common/recent_cache.h"
#include "fem/far_field_mesh.h"
#include "fem/linear_solvers.h"

#include <deal.II/base/function.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/component_mask.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/precondition.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>
#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

namespace ddafem::fem
{
using namespace dealii;

namespace
{
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Isotropic elastic constants of the plane mode.
struct PlaneElasticity
{
  double lambda = 0.0; ///< lambda (plane strain) or 2 lambda mu / (lambda + 2 mu) (plane stress)
  double mu = 0.0;
  double nu = 0.0;
  PlaneMode mode = PlaneMode::strain;

  /// (sxx, syy, sxy) from the displacement gradient, tension positive.
  std::array<double, 3> stress(const Tensor<1, 2>& grad_ux, const Tensor<1, 2>& grad_uy) const
  {
    const double exx = grad_ux[0];
    const double eyy = grad_uy[1];
    const double exy = 0.5 * (grad_ux[1] + grad_uy[0]);
    const double trace = exx + eyy;
    return {{lambda * trace + 2.0 * mu * exx, lambda * trace + 2.0 * mu * eyy, 2.0 * mu * exy}};
  }

  /// Von Mises stress; szz = nu (sxx + syy) in plane strain, 0 in plane stress.
  double von_mises(const std::array<double, 3>& s) const
  {
    const double szz = mode == PlaneMode::strain ? nu * (s[0] + s[1]) : 0.0;
    const double d =
        (s[0] - s[1]) * (s[0] - s[1]) + (s[1] - szz) * (s[1] - szz) + (szz - s[0]) * (szz - s[0]);
    return std::sqrt(0.5 * d + 3.0 * s[2] * s[2]);
  }
};

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

/// Sets entries below 1e-30 of the largest one to zero. Ahead of a wave front the discrete
/// solution decays exponentially into subnormal numbers, which make every solve many times
/// slower; the change is far below round-off of the field.
void flush_negligible(Vector<double>& x)
{
  const double threshold = 1e-30 * x.linfty_norm();
  for (double& entry : x)
    if (std::abs(entry) < threshold)
      entry = 0.0;
}

void require(const bool condition, const std::string& message)
{
  if (!condition)
    throw InputError("far field: " + message);
}

std::string str(const double x)
{
  std::ostringstream s;
  s << x;
  return s.str();
}

} // namespace

class ElasticWaveModel::Impl
{
public:
  explicit Impl(const FarFieldDescription& description);

  StepStatus prepare_step(double dt);
  StepStatus finish_step(const std::vector<double>& point_loads);
  MonitorSample sample_monitor(std::size_t monitor) const;
  std::string write_snapshot(const std::string& directory, const std::string& basename,
                             VtuCompression compression);
  void set_initial_state(const ElasticWaveModel::VectorField& displacement,
                         const ElasticWaveModel::VectorField& velocity);

  FarFieldDescription description;
  PlaneElasticity elasticity;
  double vp = 0.0;
  double vs = 0.0;
  double beta = 0.25;
  double gamma = 0.5;
  double h = 0.0;     ///< longest element edge [m]
  double h_min = 0.0; ///< shortest longest-edge of an element [m]

  Triangulation<2> mesh;
  FESystem<2> fe;
  DoFHandler<2> dof_handler;
  AffineConstraints<double> constraints;
  SparsityPattern sparsity;
  SparseMatrix<double> mass;        ///< M, unconstrained
  SparseMatrix<double> stiffness;   ///< K, unconstrained
  SparsityPattern damping_sparsity; ///< the boundary couplings only
  SparseMatrix<double> damping;     ///< C (Lysmer and input parts), unconstrained
  /// The effective matrix P = K + gamma/(beta dt) C + 1/(beta dt^2) M (+ the springs' N^T K N),
  /// constrained, and its solver for one dt. Coupled runs that cut dt step on levels
  /// dt_max / 2^k and come back: the last few are kept (most recently used first).
  struct Factorization
  {
    SparseMatrix<double> matrix;
    std::unique_ptr<EffectiveSolver> solver; ///< refers to `matrix`
  };
  ddafem::RecentCache<double, Factorization> factorizations{16}; ///< by dt [s]
  /// The solver of the dt last ensured (ensure_factorized), the cache's front.
  EffectiveSolver& solver() const { return *factorizations.front().solver; }
  /// Drops every factorization (the effective matrix changed).
  void forget_factorizations();

  /// f(t) = input_scale * v_in(t) * input_shape: the Joyner-Chen traction 2 rho c v_in on the
  /// incident wave's component, integrated over the input parts.
  Vector<double> input_shape;
  double input_scale = 0.0;

  /// The state a step starts from: what an abandoned step of the free-field column restores.
  struct State
  {
    Vector<double> u, v, a, a_previous, force;
    double t = 0.0;
    bool initial_acceleration_done = false;
    EnergyBalance energies;
    std::size_t n_steps = 0;
  };
  State save_state() const;
  void restore_state(const State& state);

  Vector<double> u, v, a;             ///< u: total displacement (static stage included)
  Vector<double> static_displacement; ///< u_s of the static stage (empty without one)
  Vector<double> static_force;        ///< K u_s: gravity, in-situ stress and reactions
  Vector<double> a_previous; ///< acceleration one step back (extrapolated for the CG guess)
  Vector<double> force;      ///< f at the current time
  double t = 0.0;
  bool initial_acceleration_done = false;

  EnergyBalance energies;
  Timings timings;

  struct MonitorPoint
  {
    std::unique_ptr<FEValues<2>> values; ///< reinit'd once on the cell holding the point
    double y = 0.0;                      ///< height of the point [m]
  };
  std::vector<MonitorPoint> monitors;

  std::vector<std::pair<double, std::string>> snapshots;

  /// A point spring: the shape functions of its cell at its point and K [N/m].
  struct SpringPoint
  {
    std::vector<types::global_dof_index> dofs; ///< the cell's DOFs with a nonzero shape value
    std::vector<double> phi;                   ///< shape value of each at the point
    std::vector<unsigned int> component;       ///< vector component of each
    double k[2][2] = {{0.0, 0.0}, {0.0, 0.0}};
  };
  std::vector<SpringPoint> springs;
  std::vector<double> spring_force; ///< F on the far field at the current time [N] (2m)
  /// out = N x (2m).
  std::vector<double> evaluate_at_springs(const Vector<double>& x) const;
  /// rhs += N^T q.
  void add_spring_loads(const std::vector<double>& q, Vector<double>& rhs) const;

  /// The step between prepare_step() and finish_step().
  struct PendingStep
  {
    bool active = false;
    double dt = 0.0;
    Vector<double> force_new; ///< f(t + dt): input and free-field loads
    Vector<double> u_new;     ///< P^-1 (Newmark right-hand side)
  };
  PendingStep pending;
  void ensure_factorized(double dt);

  /// Free-field boundaries: the 1D column and, per quadrature point of the free_field faces
  /// (in active-cell order), where it is evaluated in the column.
  std::unique_ptr<ElasticWaveModel> column;
  std::vector<std::unique_ptr<FEValues<2>>> column_probes;
  State column_start;        ///< the column's state at the start of the step in progress
  bool column_ahead = false; ///< the column has advanced into a step not finished yet
  void make_free_field_column();
  /// Adds integral(N^T (sigma_ff n + D v_ff)) over the free_field faces to f.
  void add_free_field_load(Vector<double>& f) const;
  /// Column velocity and stress at height y (a probe made on the fly).
  MonitorSample column_sample(const FEValues<2>& probe) const;
  std::unique_ptr<FEValues<2>> make_probe(double x, double y) const;
  bool is_free_field_face(const DoFHandler<2>::active_cell_iterator& cell, unsigned int f) const;

private:
  void validate() const;
  void make_mesh();
  void make_constraints();
  void assemble_matrices();
  void locate_monitors();
  void factorize(double dt);
  void compute_initial_acceleration();
  void input_force(double time, Vector<double>& f) const;
  void solve_static_stage();
  /// out = C x with C = dashpots + Rayleigh (alpha M + beta K).
  void damping_vmult(Vector<double>& out, const Vector<double>& x) const;

public:
  void condense_rhs(Vector<double>& rhs) const;
  /// u - u_s: the displacement the dynamic stage reports.
  Vector<double> relative_displacement() const;
  /// In-situ stress sigma0 at height y: (sxx, syy, sxy) [Pa].
  std::array<double, 3> initial_stress(double y) const;
  double strain_energy() const;
};

ElasticWaveModel::Impl::Impl(const FarFieldDescription& description_)
    : description(description_), fe(FE_Q<2>(std::max(1u, description_.degree)), 2),
      dof_handler(mesh)
{
  const auto start = Clock::now();
  validate();

  const double E = description.youngs_modulus;
  const double nu = description.poisson_ratio;
  const double rho = description.density;
  const double lambda = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  const double mu = E / (2.0 * (1.0 + nu));
  elasticity.mu = mu;
  elasticity.nu = nu;
  elasticity.mode = description.plane_mode;
  elasticity.lambda = description.plane_mode == PlaneMode::strain
                          ? lambda
                          : 2.0 * lambda * mu / (lambda + 2.0 * mu);
  vp = std::sqrt((elasticity.lambda + 2.0 * mu) / rho);
  vs = std::sqrt(mu / rho);
  if (description.integrator == Integrator::dda)
  {
    beta = 0.5;
    gamma = 1.0;
  }

  make_mesh();
  dof_handler.distribute_dofs(fe);
  make_constraints();
  assemble_matrices();
  locate_monitors();

  u.reinit(dof_handler.n_dofs());
  v.reinit(dof_handler.n_dofs());
  a.reinit(dof_handler.n_dofs());
  force.reinit(dof_handler.n_dofs());
  input_force(0.0, force);
  make_free_field_column();
  if (description.static_stage.enabled)
    solve_static_stage();

  if (description.dt > 0.0)
    factorize(description.dt);
  timings.setup += seconds_since(start);
}

void ElasticWaveModel::Impl::validate() const
{
  const auto& d = description;
  require(d.upper[0] > d.lower[0] && d.upper[1] > d.lower[1],
          "upper corner (" + str(d.upper[0]) + ", " + str(d.upper[1]) +
              ") must lie above and right of lower corner (" + str(d.lower[0]) + ", " +
              str(d.lower[1]) + ")");
  require(d.degree == 1 || d.degree == 2,
          "degree = " + std::to_string(d.degree) + ", expected 1 or 2");
  require(d.density > 0.0, "density = " + str(d.density) + ", expected > 0");
  require(d.youngs_modulus > 0.0, "youngs_modulus = " + str(d.youngs_modulus) + ", expected > 0");
  require(d.poisson_ratio >= 0.0 && d.poisson_ratio < 0.5,
          "poisson_ratio = " + str(d.poisson_ratio) + ", expected in [0, 0.5)");
  require(d.element_size >= 0.0, "element_size = " + str(d.element_size) + ", expected >= 0");
  require(d.dt >= 0.0, "dt = " + str(d.dt) + ", expected >= 0 (0: given to advance())");
  require(d.solver_tolerance > 0.0 && d.solver_tolerance < 1.0,
          "solver_tolerance = " + str(d.solver_tolerance) + ", expected in (0, 1)");
  const bool from_file = !d.mesh_file.file.empty();
  require(d.rayleigh.alpha >= 0.0 && d.rayleigh.beta >= 0.0,
          "rayleigh: alpha = " + str(d.rayleigh.alpha) + ", beta = " + str(d.rayleigh.beta) +
              ", expected both >= 0");
  if (d.element_size == 0.0 && !from_file)
  {
    const double f =
        d.max_frequency > 0.0 ? d.max_frequency : d.incident.velocity.characteristic_frequency();
    require(f > 0.0, "element_size = 0 needs max_frequency > 0 (or an incident wave with a "
                     "frequency) to choose the element size");
    require(d.points_per_wavelength > 0.0,
            "points_per_wavelength = " + str(d.points_per_wavelength) + ", expected > 0");
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
            "monitor '" + m.name + "' at (" + str(m.point[0]) + ", " + str(m.point[1]) +
                ") lies outside the far field [" + str(d.lower[0]) + ", " + str(d.upper[0]) +
                "] x [" + str(d.lower[1]) + ", " + str(d.upper[1]) + "]");
  }
}

void ElasticWaveModel::Impl::make_mesh()
{
  const auto& d = description;
  double target = d.element_size;
  if (target == 0.0 && d.mesh_file.file.empty())
  {
    const double f =
        d.max_frequency > 0.0 ? d.max_frequency : d.incident.velocity.characteristic_frequency();
    // points_per_wavelength counts nodes; an FE_Q(p) element spans p node intervals.
    target = vs / (f * d.points_per_wavelength) * d.degree;
  }
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
  // Roller: fix the component the incident wave does not move (see BoundaryKind::roller).
  const unsigned int roller_component = description.incident.type == IncidentWave::Type::sv ? 1 : 0;
  std::vector<bool> only(2, false);
  only[roller_component] = true;
  const ComponentMask roller_mask(only);
  for (const auto& bc : description.boundaries)
  {
    if (bc.kind == BoundaryKind::fixed)
      VectorTools::interpolate_boundary_values(dof_handler, boundary_id_of(bc.part),
                                               Functions::ZeroFunction<2>(2), constraints);
    else if (bc.kind == BoundaryKind::roller)
      VectorTools::interpolate_boundary_values(dof_handler, boundary_id_of(bc.part),
                                               Functions::ZeroFunction<2>(2), constraints,
                                               roller_mask);
  }
  constraints.close();
}

void ElasticWaveModel::Impl::assemble_matrices()
{
  DynamicSparsityPattern dsp(dof_handler.n_dofs());
  DoFTools::make_sparsity_pattern(dof_handler, dsp);
  constraints.condense(dsp); // room for the condensed effective matrix (hanging nodes)
  sparsity.copy_from(dsp);
  mass.reinit(sparsity);
  stiffness.reinit(sparsity);
  SparseMatrix<double> full_damping(sparsity);
  input_shape.reinit(dof_handler.n_dofs());

  const double rho = description.density;
  const double lambda = elasticity.lambda;
  const double mu = elasticity.mu;
  const unsigned int n = fe.n_dofs_per_cell();

  // Domain: consistent mass and plane elastic stiffness (deal.II step-8 form).
  const QGauss<2> quadrature(fe.degree + 1);
  FEValues<2> fe_values(fe, quadrature, update_values | update_gradients | update_JxW_values);
  FullMatrix<double> cell_mass(n, n), cell_stiffness(n, n);
  std::vector<types::global_dof_index> dofs(n);
  for (const auto& cell : dof_handler.active_cell_iterators())
  {
    fe_values.reinit(cell);
    cell_mass = 0.0;
    cell_stiffness = 0.0;
    for (unsigned int i = 0; i < n; ++i)
    {
      const unsigned int ci = fe.system_to_component_index(i).first;
      for (unsigned int j = 0; j < n; ++j)
      {
        const unsigned int cj = fe.system_to_component_index(j).first;
        for (const unsigned int q : fe_values.quadrature_point_indices())
        {
          const Tensor<1, 2> gi = fe_values.shape_grad(i, q);
          const Tensor<1, 2> gj = fe_values.shape_grad(j, q);
          double k = lambda * gi[ci] * gj[cj] + mu * gi[cj] * gj[ci];
          double m = 0.0;
          if (ci == cj)
          {
            k += mu * (gi * gj);
            m = rho * fe_values.shape_value(i, q) * fe_values.shape_value(j, q);
          }
          cell_stiffness(i, j) += k * fe_values.JxW(q);
          cell_mass(i, j) += m * fe_values.JxW(q);
        }
      }
    }
    cell->get_dof_indices(dofs);
    mass.add(dofs, cell_mass);
    stiffness.add(dofs, cell_stiffness);
  }

  // Boundary: Lysmer dashpots D = rho (a VP n n^T + b VS (I - n n^T)) on lysmer and input
  // parts; the input traction shape on input parts.
  std::map<types::boundary_id, const BoundaryCondition*> absorbing;
  for (const auto& bc : description.boundaries)
    if (bc.kind == BoundaryKind::lysmer || bc.kind == BoundaryKind::input ||
        bc.kind == BoundaryKind::free_field)
      absorbing[boundary_id_of(bc.part)] = &bc;
  const bool sv = description.incident.type == IncidentWave::Type::sv;
  const unsigned int input_component = sv ? 0 : 1;
  input_scale = 2.0 * rho * (sv ? vs : vp);

  const QGauss<1> face_quadrature(fe.degree + 1);
  FEFaceValues<2> face_values(fe, face_quadrature,
                              update_values | update_normal_vectors | update_JxW_values);
  FEFaceValues<2> spring_values(fe, face_quadrature,
                                update_values | update_normal_vectors | update_JxW_values |
                                    update_quadrature_points);
  FullMatrix<double> cell_damping(n, n), cell_springs(n, n);
  Vector<double> cell_input(n);
  for (const auto& cell : dof_handler.active_cell_iterators())
    for (const unsigned int f : cell->face_indices())
    {
      if (!cell->face(f)->at_boundary())
        continue;
      const auto found = absorbing.find(cell->face(f)->boundary_id());
      if (found == absorbing.end())
        continue;
      const BoundaryCondition& bc = *found->second;
      face_values.reinit(cell, f);
      cell_damping = 0.0;
      cell_input = 0.0;
      for (const unsigned int q : face_values.quadrature_point_indices())
      {
        const Tensor<1, 2> normal = face_values.normal_vector(q);
        double D[2][2];
        for (unsigned int r = 0; r < 2; ++r)
          for (unsigned int c = 0; c < 2; ++c)
            D[r][c] = rho * (bc.a * vp * normal[r] * normal[c] +
                             bc.b * vs * ((r == c ? 1.0 : 0.0) - normal[r] * normal[c]));
        for (unsigned int i = 0; i < n; ++i)
        {
          const unsigned int ci = fe.system_to_component_index(i).first;
          const double phi_i = face_values.shape_value(i, q);
          for (unsigned int j = 0; j < n; ++j)
          {
            const unsigned int cj = fe.system_to_component_index(j).first;
            cell_damping(i, j) +=
                phi_i * D[ci][cj] * face_values.shape_value(j, q) * face_values.JxW(q);
          }
          if (bc.kind == BoundaryKind::input && ci == input_component)
            cell_input(i) += phi_i * face_values.JxW(q);
        }
      }
      cell->get_dof_indices(dofs);
      full_damping.add(dofs, cell_damping);
      if (bc.springs.enabled)
      {
        // Viscous-spring boundary: K = G / R (alpha_n n n^T + alpha_t (I - n n^T)), part of the
        // stiffness (its energy counts as strain energy).
        spring_values.reinit(cell, f);
        cell_springs = 0.0;
        for (const unsigned int q : spring_values.quadrature_point_indices())
        {
          const Tensor<1, 2> normal = spring_values.normal_vector(q);
          const Point<2> x = spring_values.quadrature_point(q);
          const double r = std::hypot(x[0] - bc.springs.center[0], x[1] - bc.springs.center[1]);
          require(r > 1e-6 * h, std::string("boundary part '") + name_of(bc.part) +
                                    "': the springs' center lies on the part, expected the "
                                    "wave source's position inside the far field");
          double K[2][2];
          for (unsigned int row = 0; row < 2; ++row)
            for (unsigned int c = 0; c < 2; ++c)
              K[row][c] = mu / r *
                          (bc.springs.alpha_n * normal[row] * normal[c] +
                           bc.springs.alpha_t * ((row == c ? 1.0 : 0.0) - normal[row] * normal[c]));
          for (unsigned int i = 0; i < n; ++i)
          {
            const unsigned int ci = fe.system_to_component_index(i).first;
            for (unsigned int j = 0; j < n; ++j)
            {
              const unsigned int cj = fe.system_to_component_index(j).first;
              cell_springs(i, j) += spring_values.shape_value(i, q) * K[ci][cj] *
                                    spring_values.shape_value(j, q) * spring_values.JxW(q);
            }
          }
        }
        stiffness.add(dofs, cell_springs);
      }
      for (unsigned int i = 0; i < n; ++i)
        input_shape(dofs[i]) += cell_input(i);
    }

  // C lives on the boundary: a pattern of its own keeps its products cheap.
  DynamicSparsityPattern boundary_dsp(dof_handler.n_dofs());
  for (std::size_t row = 0; row < full_damping.m(); ++row)
    for (auto entry = full_damping.begin(row); entry != full_damping.end(row); ++entry)
      if (entry->value() != 0.0)
        boundary_dsp.add(row, entry->column());
  damping_sparsity.copy_from(boundary_dsp);
  damping.reinit(damping_sparsity);
  for (std::size_t row = 0; row < full_damping.m(); ++row)
    for (auto entry = full_damping.begin(row); entry != full_damping.end(row); ++entry)
      if (entry->value() != 0.0)
        damping.set(row, entry->column(), entry->value());
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
            "monitor '" + m.name + "' at (" + str(p[0]) + ", " + str(p[1]) +
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

void ElasticWaveModel::Impl::input_force(const double time, Vector<double>& f) const
{
  f = input_shape;
  f *= input_scale * description.incident.velocity.value(time);
}

void ElasticWaveModel::Impl::condense_rhs(Vector<double>& rhs) const
{
  constraints.condense(rhs);
}

std::array<double, 3> ElasticWaveModel::Impl::initial_stress(const double y) const
{
  const StaticStage& s = description.static_stage;
  if (!s.enabled)
    return {{0.0, 0.0, 0.0}};
  std::array<double, 3> sigma;
  for (unsigned int k = 0; k < 3; ++k)
    sigma[k] = s.stress[k] + s.stress_gradient[k] * (y - s.reference_y);
  return sigma;
}

Vector<double> ElasticWaveModel::Impl::relative_displacement() const
{
  Vector<double> w(u);
  if (static_displacement.size() == w.size())
    w -= static_displacement;
  return w;
}

double ElasticWaveModel::Impl::strain_energy() const
{
  return 0.5 * stiffness.matrix_norm_square(relative_displacement());
}

void ElasticWaveModel::Impl::damping_vmult(Vector<double>& out, const Vector<double>& x) const
{
  damping.vmult(out, x);
  const RayleighDamping& r = description.rayleigh;
  if (r.alpha == 0.0 && r.beta == 0.0)
    return;
  Vector<double> product(x.size());
  if (r.alpha > 0.0)
  {
    mass.vmult(product, x);
    out.add(r.alpha, product);
  }
  if (r.beta > 0.0)
  {
    stiffness.vmult(product, x);
    out.add(r.beta, product);
  }
}

void ElasticWaveModel::Impl::solve_static_stage()
{
  const StaticStage& s = description.static_stage;
  // Loads: gravity rho g and the in-situ stress's internal force integral(B^T sigma0).
  const QGauss<2> quadrature(fe.degree + 1);
  FEValues<2> fe_values(fe, quadrature,
                        update_values | update_gradients | update_quadrature_points |
                            update_JxW_values);
  const unsigned int n = fe.n_dofs_per_cell();
  Vector<double> cell_load(n), load(dof_handler.n_dofs());
  std::vector<types::global_dof_index> dofs(n);
  for (const auto& cell : dof_handler.active_cell_iterators())
  {
    fe_values.reinit(cell);
    cell_load = 0.0;
    for (const unsigned int q : fe_values.quadrature_point_indices())
    {
      const auto sigma = initial_stress(fe_values.quadrature_point(q)[1]);
      const double tensor[2][2] = {{sigma[0], sigma[2]}, {sigma[2], sigma[1]}};
      for (unsigned int i = 0; i < n; ++i)
      {
        const unsigned int c = fe.system_to_component_index(i).first;
        const Tensor<1, 2> grad = fe_values.shape_grad(i, q);
        cell_load(i) += (description.density * s.gravity[c] * fe_values.shape_value(i, q) -
                         (tensor[c][0] * grad[0] + tensor[c][1] * grad[1])) *
                        fe_values.JxW(q);
      }
    }
    cell->get_dof_indices(dofs);
    for (unsigned int i = 0; i < n; ++i)
      load(dofs[i]) += cell_load(i);
  }

  // Supports: the dynamic stage's constraints plus the absorbing parts held.
  AffineConstraints<double> supports;
  DoFTools::make_hanging_node_constraints(dof_handler, supports);
  const unsigned int roller_component = description.incident.type == IncidentWave::Type::sv ? 1 : 0;
  bool supported = false;
  for (const auto& bc : description.boundaries)
  {
    std::vector<bool> mask(2, true);
    if (bc.kind == BoundaryKind::free)
      continue;
    if (bc.kind == BoundaryKind::roller)
      mask[1 - roller_component] = false;
    if ((bc.kind == BoundaryKind::lysmer || bc.kind == BoundaryKind::input ||
         bc.kind == BoundaryKind::free_field) &&
        s.support == StaticSupport::roller && bc.part != BoundaryPart::hole)
      mask[bc.part == BoundaryPart::left || bc.part == BoundaryPart::right ? 1 : 0] = false;
    VectorTools::interpolate_boundary_values(dof_handler, boundary_id_of(bc.part),
                                             Functions::ZeroFunction<2>(2), supports,
                                             ComponentMask(mask));
    supported = true;
  }
  supports.close();
  require(supported, "static_stage: no part holds the model (all parts free), expected a "
                     "fixed, roller, lysmer or input part");

  SparseMatrix<double> k(sparsity);
  k.copy_from(stiffness);
  supports.condense(k);
  Vector<double> rhs(load);
  supports.condense(rhs);
  static_displacement.reinit(dof_handler.n_dofs());
  const auto direct = make_effective_solver(LinearSolver::direct, DirectSolver::klu, 0.0);
  try
  {
    direct->initialize(k);
    direct->solve(rhs, static_displacement);
  }
  catch (const std::exception& e)
  {
    throw InputError(std::string("far field: static_stage: the static problem is singular (") +
                     e.what() +
                     "): expected supports that stop rigid-body motion in both directions");
  }
  for (const double x : static_displacement)
    require(std::isfinite(x), "static_stage: the static problem is singular, expected supports "
                              "that stop rigid-body motion in both directions");
  supports.distribute(static_displacement);
  // The reactions stay as forces: K u_s is the load at free DOFs and load + reaction at the
  // supported ones, so the dynamic stage starts in equilibrium.
  static_force.reinit(dof_handler.n_dofs());
  stiffness.vmult(static_force, static_displacement);
  u = static_displacement;
}

void ElasticWaveModel::Impl::make_free_field_column()
{
  const auto& d = description;
  bool needed = false;
  for (const auto& bc : d.boundaries)
    needed = needed || bc.kind == BoundaryKind::free_field;
  if (!needed)
    return;
  // The column: one far-size element wide, the model's material, base and top, rollers.
  FarFieldDescription c;
  c.lower = d.lower;
  c.upper = {{d.lower[0] + h, d.upper[1]}};
  c.element_size = h;
  c.degree = d.degree;
  c.density = d.density;
  c.youngs_modulus = d.youngs_modulus;
  c.poisson_ratio = d.poisson_ratio;
  c.plane_mode = d.plane_mode;
  c.incident = d.incident;
  c.dt = d.dt;
  c.integrator = d.integrator;
  c.rayleigh = d.rayleigh;
  for (const auto& bc : d.boundaries)
    if (bc.part == BoundaryPart::bottom || bc.part == BoundaryPart::top)
      c.boundaries.push_back(bc);
  c.boundaries.push_back({BoundaryPart::left, BoundaryKind::roller, 1.0, 1.0, {}});
  c.boundaries.push_back({BoundaryPart::right, BoundaryKind::roller, 1.0, 1.0, {}});
  column = std::make_unique<ElasticWaveModel>(c);

  const Impl& col = *column->impl;
  const MappingQ1<2> mapping;
  const QGauss<1> face_quadrature(fe.degree + 1);
  FEFaceValues<2> face_values(fe, face_quadrature, update_quadrature_points);
  const double x = d.lower[0] + 0.5 * h;
  for (const auto& cell : dof_handler.active_cell_iterators())
    for (const unsigned int f : cell->face_indices())
    {
      if (!is_free_field_face(cell, f))
        continue;
      face_values.reinit(cell, f);
      for (const unsigned int q : face_values.quadrature_point_indices())
      {
        const double y = std::clamp(face_values.quadrature_point(q)[1], d.lower[1], d.upper[1]);
        column_probes.push_back(col.make_probe(x, y));
      }
    }
}

std::unique_ptr<FEValues<2>> ElasticWaveModel::Impl::make_probe(const double x,
                                                                const double y) const
{
  const MappingQ1<2> mapping;
  const auto found = GridTools::find_active_cell_around_point(mapping, dof_handler, Point<2>(x, y));
  const Point<2> reference = GeometryInfo<2>::project_to_unit_cell(found.second);
  auto probe =
      std::make_unique<FEValues<2>>(mapping, fe, Quadrature<2>(std::vector<Point<2>>{reference}),
                                    update_values | update_gradients);
  probe->reinit(found.first);
  return probe;
}

bool ElasticWaveModel::Impl::is_free_field_face(const DoFHandler<2>::active_cell_iterator& cell,
                                                const unsigned int f) const
{
  if (!cell->face(f)->at_boundary())
    return false;
  for (const auto& bc : description.boundaries)
    if (bc.kind == BoundaryKind::free_field &&
        cell->face(f)->boundary_id() == boundary_id_of(bc.part))
      return true;
  return false;
}

MonitorSample ElasticWaveModel::Impl::column_sample(const FEValues<2>& probe) const
{
  const Impl& col = *column->impl;
  std::vector<Vector<double>> point_v(1, Vector<double>(2));
  std::vector<std::vector<Tensor<1, 2>>> grad_u(1, std::vector<Tensor<1, 2>>(2));
  probe.get_function_values(col.v, point_v);
  probe.get_function_gradients(col.u, grad_u);
  MonitorSample sample;
  sample.velocity = {{point_v[0](0), point_v[0](1)}};
  sample.stress = col.elasticity.stress(grad_u[0][0], grad_u[0][1]);
  return sample;
}

void ElasticWaveModel::Impl::add_free_field_load(Vector<double>& f) const
{
  const double rho = description.density;
  const QGauss<1> face_quadrature(fe.degree + 1);
  FEFaceValues<2> face_values(fe, face_quadrature,
                              update_values | update_normal_vectors | update_JxW_values);
  const unsigned int n = fe.n_dofs_per_cell();
  Vector<double> cell_load(n);
  std::vector<types::global_dof_index> dofs(n);
  std::size_t probe = 0;
  for (const auto& cell : dof_handler.active_cell_iterators())
    for (const unsigned int face : cell->face_indices())
    {
      if (!is_free_field_face(cell, face))
        continue;
      face_values.reinit(cell, face);
      cell_load = 0.0;
      for (const unsigned int q : face_values.quadrature_point_indices())
      {
        const MonitorSample ff = column_sample(*column_probes[probe++]);
        const Tensor<1, 2> n_q = face_values.normal_vector(q);
        const double sigma[2][2] = {{ff.stress[0], ff.stress[2]}, {ff.stress[2], ff.stress[1]}};
        // t = sigma_ff n + D v_ff, D = rho (VP n n^T + VS (I - n n^T)) (a = b = 1).
        double traction[2];
        const double vn = ff.velocity[0] * n_q[0] + ff.velocity[1] * n_q[1];
        for (unsigned int c = 0; c < 2; ++c)
          traction[c] = sigma[c][0] * n_q[0] + sigma[c][1] * n_q[1] +
                        rho * (vp * vn * n_q[c] + vs * (ff.velocity[c] - vn * n_q[c]));
        for (unsigned int i = 0; i < n; ++i)
        {
          const unsigned int c = fe.system_to_component_index(i).first;
          cell_load(i) += face_values.shape_value(i, q) * traction[c] * face_values.JxW(q);
        }
      }
      cell->get_dof_indices(dofs);
      for (unsigned int i = 0; i < n; ++i)
        f(dofs[i]) += cell_load(i);
    }
}

void ElasticWaveModel::Impl::factorize(const double dt)
{
  const double c_mass = 1.0 / (beta * dt * dt);
  const double c_damping = gamma / (beta * dt);
  auto f = std::make_unique<Factorization>();
  SparseMatrix<double>& effective = f->matrix;
  effective.reinit(sparsity);
  effective.copy_from(stiffness);
  effective.add(c_mass + c_damping * description.rayleigh.alpha, mass);
  if (description.rayleigh.beta > 0.0)
    effective.add(c_damping * description.rayleigh.beta, stiffness);
  for (std::size_t row = 0; row < damping.m(); ++row)
    for (auto entry = damping.begin(row); entry != damping.end(row); ++entry)
      effective.add(row, entry->column(), c_damping * entry->value());
  // Point springs: N^T K N couples the DOFs of each spring's cell.
  for (const SpringPoint& sp : springs)
    for (std::size_t i = 0; i < sp.dofs.size(); ++i)
      for (std::size_t j = 0; j < sp.dofs.size(); ++j)
        effective.add(sp.dofs[i], sp.dofs[j],
                      sp.phi[i] * sp.k[sp.component[i]][sp.component[j]] * sp.phi[j]);
  // Constrained rows and columns (fixed, roller, hanging nodes) condensed out; their rows keep
  // a diagonal entry and a zero right-hand side, and distribute() restores them.
  constraints.condense(effective);
  f->solver = make_effective_solver(description.solver, description.direct_solver,
                                    description.solver_tolerance);
  f->solver->initialize(effective);
  factorizations.insert(dt, std::move(f));
}

void ElasticWaveModel::Impl::forget_factorizations()
{
  factorizations.clear();
}

ElasticWaveModel::Impl::State ElasticWaveModel::Impl::save_state() const
{
  return {u, v, a, a_previous, force, t, initial_acceleration_done, energies, timings.n_steps};
}

void ElasticWaveModel::Impl::restore_state(const State& s)
{
  u = s.u;
  v = s.v;
  a = s.a;
  a_previous = s.a_previous;
  force = s.force;
  t = s.t;
  initial_acceleration_done = s.initial_acceleration_done;
  energies = s.energies;
  timings.n_steps = s.n_steps;
}

void ElasticWaveModel::Impl::compute_initial_acceleration()
{
  // M a0 = f(t) - C v0 - K u0; nothing to solve for a state at rest without input.
  initial_acceleration_done = true;
  Vector<double> rhs(force), product(u.size());
  if (static_force.size() == rhs.size())
    rhs += static_force;
  stiffness.vmult(product, u);
  rhs -= product;
  damping_vmult(product, v);
  rhs -= product;
  if (!springs.empty())
  {
    // Springs to anchors at rest (the tied body has not moved yet): F = -K N u0.
    const std::vector<double> w = evaluate_at_springs(u);
    for (std::size_t k = 0; k < springs.size(); ++k)
      for (unsigned int r = 0; r < 2; ++r)
        spring_force[2 * k + r] =
            -(springs[k].k[r][0] * w[2 * k] + springs[k].k[r][1] * w[2 * k + 1]);
    add_spring_loads(spring_force, rhs);
  }
  condense_rhs(rhs);
  // At rest in equilibrium (K u_s = static force) the residual is round-off of u_s's size.
  if (rhs.l2_norm() <= 1e-14 * (static_force.size() == rhs.size() ? static_force.l2_norm() : 0.0))
  {
    a = 0.0;
    return;
  }
  SparseMatrix<double> constrained_mass(sparsity);
  constrained_mass.copy_from(mass);
  constraints.condense(constrained_mass);
  // The consistent mass matrix is well conditioned (Jacobi-scaled): CG to round-off.
  SolverControl control(std::max<std::size_t>(1000, rhs.size()), 1e-14 * rhs.l2_norm(), false,
                        false);
  SolverCG<Vector<double>> cg(control);
  PreconditionJacobi<SparseMatrix<double>> jacobi;
  jacobi.initialize(constrained_mass);
  a = 0.0;
  cg.solve(constrained_mass, a, rhs, jacobi);
  constraints.distribute(a);
}

namespace
{
/// A VectorField as a deal.II Function.
class FieldFunction : public Function<2>
{
public:
  explicit FieldFunction(const ElasticWaveModel::VectorField& f) : Function<2>(2), field(f) {}
  double value(const Point<2>& p, const unsigned int component) const override
  {
    return field(p[0], p[1])[component];
  }
  void vector_value(const Point<2>& p, Vector<double>& values) const override
  {
    const auto x = field(p[0], p[1]);
    values(0) = x[0];
    values(1) = x[1];
  }

private:
  const ElasticWaveModel::VectorField& field;
};
} // namespace

void ElasticWaveModel::Impl::set_initial_state(const ElasticWaveModel::VectorField& displacement,
                                               const ElasticWaveModel::VectorField& velocity)
{
  const auto start = Clock::now();
  VectorTools::interpolate(dof_handler, FieldFunction(displacement), u);
  VectorTools::interpolate(dof_handler, FieldFunction(velocity), v);
  constraints.distribute(u);
  constraints.distribute(v);
  if (static_displacement.size() == u.size())
    u += static_displacement;
  compute_initial_acceleration();
  a_previous.reinit(0);
  energies = EnergyBalance{};
  energies.kinetic = 0.5 * mass.matrix_norm_square(v);
  energies.strain = strain_energy();
  energies.initial = energies.stored();
  timings.setup += seconds_since(start);
}

void ElasticWaveModel::Impl::ensure_factorized(const double dt)
{
  if (!initial_acceleration_done)
  {
    const auto start = Clock::now();
    compute_initial_acceleration();
    timings.setup += seconds_since(start);
  }
  if (factorizations.use(dt))
    return;
  const auto start = Clock::now();
  factorize(dt);
  timings.setup += seconds_since(start);
}

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

StepStatus ElasticWaveModel::Impl::prepare_step(const double dt)
{
  require(dt > 0.0 && std::isfinite(dt), "advance: dt = " + str(dt) + ", expected > 0");
  StepStatus status;
  // A step prepared but not finished (the DDA side cut dt) has advanced the free-field column:
  // it goes back to the step's start and advances again with the new dt.
  if (column)
  {
    if (column_ahead)
      column->impl->restore_state(column_start);
    else
      column_start = column->impl->save_state();
    column_ahead = false;
  }
  pending.active = false;
  try
  {
    ensure_factorized(dt);

    // Right-hand side of K_eff u1 = f1 + M (...) + C (...) (Newmark, displacement form).
    auto start = Clock::now();
    const double t1 = t + dt;
    pending.force_new.reinit(force.size());
    input_force(t1, pending.force_new);
    if (column)
    {
      const StepStatus column_status = column->advance(dt);
      column_ahead = true;
      if (column_status.outcome != StepOutcome::success)
        return column_status;
      add_free_field_load(pending.force_new);
    }
    const double m_u = 1.0 / (beta * dt * dt);
    const double m_v = 1.0 / (beta * dt);
    const double m_a = 1.0 / (2.0 * beta) - 1.0;
    const double c_u = gamma / (beta * dt);
    const double c_v = gamma / beta - 1.0;
    const double c_a = dt * (gamma / (2.0 * beta) - 1.0);
    Vector<double> combination(u.size()), rhs(pending.force_new), product(u.size());
    if (static_force.size() == rhs.size())
      rhs += static_force; // the static stage's loads and reactions, held constant
    combination.equ(m_u, u);
    combination.add(m_v, v, m_a, a);
    mass.vmult(product, combination);
    rhs += product;
    combination.equ(c_u, u);
    combination.add(c_v, v, c_a, a);
    damping_vmult(product, combination);
    rhs += product;
    condense_rhs(rhs);
    timings.assemble += seconds_since(start);

    // Initial guess (for cg): Newmark's u1 with a1 extrapolated linearly, 2 a0 - a_previous.
    start = Clock::now();
    if (a_previous.size() != a.size())
      a_previous = a;
    pending.u_new = u;
    pending.u_new.add(dt, v, dt * dt * (0.5 + beta), a);
    pending.u_new.add(-dt * dt * beta, a_previous);
    constraints.set_zero(pending.u_new);
    solver().solve(rhs, pending.u_new);
    constraints.distribute(pending.u_new);
    timings.linear_iterations += solver().last_iterations();
    timings.solve += seconds_since(start);
    pending.dt = dt;
    pending.active = true;
  }
  catch (const std::exception& e)
  {
    status.outcome = StepOutcome::solver_failure;
    status.message = std::string("far field: solver failed: ") + e.what();
  }
  return status;
}

StepStatus ElasticWaveModel::Impl::finish_step(const std::vector<double>& point_loads)
{
  AssertThrow(pending.active, ExcMessage("finish_step() without prepare_step()"));
  AssertThrow(point_loads.size() == 2 * springs.size(),
              ExcMessage("finish_step(): " + std::to_string(point_loads.size()) +
                         " point loads for " + std::to_string(springs.size()) + " springs"));
  pending.active = false;
  column_ahead = false;
  StepStatus status;
  const double dt = pending.dt;
  const double t1 = t + dt;
  Vector<double>& u_new = pending.u_new;
  try
  {
    auto start = Clock::now();
    if (std::any_of(point_loads.begin(), point_loads.end(), [](double q) { return q != 0.0; }))
    {
      // u = y + P^-1 N^T q: one more solve with the same factorization.
      Vector<double> rhs(u.size()), x(u.size());
      add_spring_loads(point_loads, rhs);
      condense_rhs(rhs);
      solver().solve(rhs, x);
      constraints.distribute(x);
      u_new += x;
      timings.linear_iterations += solver().last_iterations();
    }
    timings.solve += seconds_since(start);

    start = Clock::now();
    for (double x : u_new)
      if (!std::isfinite(x))
      {
        status.outcome = StepOutcome::solver_failure;
        status.message = "far field: non-finite displacement at t = " + str(t1);
        timings.update += seconds_since(start);
        return status;
      }
    const double m_u = 1.0 / (beta * dt * dt);
    const double m_v = 1.0 / (beta * dt);
    const double m_a = 1.0 / (2.0 * beta) - 1.0;
    Vector<double> a_new(u.size()), v_new(v), product(u.size());
    a_new.equ(m_u, u_new);
    a_new.add(-m_u, u, -m_v, v);
    a_new.add(-m_a, a);
    v_new.add(dt * (1.0 - gamma), a, dt * gamma, a_new);

    // Energies: work over the step with mid-step forces (exact balance for the trapezoidal
    // rule, whose du = dt (v0 + v1) / 2).
    Vector<double> du(u_new);
    du -= u;
    Vector<double> v_mid(v);
    v_mid += v_new;
    v_mid *= 0.5;
    damping.vmult(product, v_mid);
    energies.work_of_dashpots -= du * product;
    if (description.rayleigh.alpha > 0.0 || description.rayleigh.beta > 0.0)
    {
      Vector<double> rayleigh(u.size());
      if (description.rayleigh.alpha > 0.0)
        mass.vmult(rayleigh, v_mid);
      rayleigh *= description.rayleigh.alpha;
      if (description.rayleigh.beta > 0.0)
      {
        stiffness.vmult(product, v_mid);
        rayleigh.add(description.rayleigh.beta, product);
      }
      energies.work_of_rayleigh -= du * rayleigh;
    }
    energies.work_of_input += 0.5 * (du * force + du * pending.force_new);
    if (!springs.empty())
    {
      // F = q - K N u on the far field; its work with mid-step forces.
      const std::vector<double> w_old = evaluate_at_springs(u);
      const std::vector<double> w_new = evaluate_at_springs(u_new);
      std::vector<double> f_new(point_loads);
      for (std::size_t k = 0; k < springs.size(); ++k)
        for (unsigned int r = 0; r < 2; ++r)
          for (unsigned int c = 0; c < 2; ++c)
            f_new[2 * k + r] -= springs[k].k[r][c] * w_new[2 * k + c];
      for (std::size_t i = 0; i < f_new.size(); ++i)
        energies.work_of_springs += 0.5 * (spring_force[i] + f_new[i]) * (w_new[i] - w_old[i]);
      spring_force = f_new;
    }

    u = u_new;
    v = v_new;
    a_previous = a;
    a = a_new;
    flush_negligible(u);
    flush_negligible(v);
    flush_negligible(a);
    force = pending.force_new;
    t = t1;
    ++timings.n_steps;
    timings.update += seconds_since(start);
  }
  catch (const std::exception& e)
  {
    status.outcome = StepOutcome::solver_failure;
    status.message = std::string("far field: solver failed: ") + e.what();
  }
  return status;
}

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
  {
    std::ofstream out(std::filesystem::path(directory) / name.str());
    AssertThrow(out, ExcMessage("cannot write " + directory + "/" + name.str()));
    data_out.write_vtu(out);
  }
  snapshots.emplace_back(t, name.str());
  std::ofstream pvd(std::filesystem::path(directory) / (basename + ".pvd"));
  AssertThrow(pvd, ExcMessage("cannot write " + directory + "/" + basename + ".pvd"));
  DataOutBase::write_pvd_record(pvd, snapshots);
  return name.str();
}

// ---- public interface ---------------------------------------------------------------------

ElasticWaveModel::ElasticWaveModel(const FarFieldDescription& description)
    : impl(std::make_unique<Impl>(description))
{
}

ElasticWaveModel::~ElasticWaveModel() = default;

void ElasticWaveModel::set_initial_state(const VectorField& displacement,
                                         const VectorField& velocity)
{
  impl->set_initial_state(displacement, velocity);
}

StepStatus ElasticWaveModel::advance(const double dt)
{
  StepStatus status = impl->prepare_step(dt);
  if (status.outcome != StepOutcome::success)
    return status;
  return impl->finish_step(std::vector<double>(2 * impl->springs.size(), 0.0));
}

StepStatus ElasticWaveModel::prepare_step(const double dt,
                                          std::vector<double>& free_point_displacements)
{
  StepStatus status = impl->prepare_step(dt);
  if (status.outcome == StepOutcome::success)
    free_point_displacements = impl->evaluate_at_springs(impl->pending.u_new);
  return status;
}

StepStatus ElasticWaveModel::finish_step(const std::vector<double>& point_loads)
{
  return impl->finish_step(point_loads);
}

std::vector<double> ElasticWaveModel::point_displacements() const
{
  return impl->evaluate_at_springs(impl->u);
}

std::vector<double> ElasticWaveModel::spring_forces() const
{
  return impl->spring_force;
}

std::size_t ElasticWaveModel::n_point_springs() const
{
  return impl->springs.size();
}

std::vector<std::array<double, 4>>
ElasticWaveModel::boundary_segments(const BoundaryPart part) const
{
  std::vector<std::array<double, 4>> segments;
  for (const auto& cell : impl->mesh.active_cell_iterators())
    for (const unsigned int f : cell->face_indices())
      if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == boundary_id_of(part))
      {
        const Point<2> a = cell->face(f)->vertex(0), b = cell->face(f)->vertex(1);
        segments.push_back({{a[0], a[1], b[0], b[1]}});
      }
  return segments;
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
  const std::size_t n_loads = by_dof ? dofs.size() : n;

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

  // Column j of the response: P^-1 applied to unit load j, restricted to `dofs`.
  std::vector<std::vector<double>> response(n_loads, std::vector<double>(dofs.size()));
  Vector<double> rhs(m.u.size()), x(m.u.size());
  std::vector<double> unit(n, 0.0);
  for (std::size_t j = 0; j < n_loads; ++j)
  {
    rhs = 0.0;
    if (by_dof)
      rhs(dofs[j]) = 1.0;
    else
    {
      unit[j] = 1.0;
      m.add_spring_loads(unit, rhs);
      unit[j] = 0.0;
    }
    m.condense_rhs(rhs);
    x = 0.0;
    m.solver().solve(rhs, x);
    m.constraints.distribute(x);
    for (std::size_t b = 0; b < dofs.size(); ++b)
      response[j][b] = x(dofs[b]);
  }

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

double ElasticWaveModel::time() const
{
  return impl->t;
}
std::size_t ElasticWaveModel::n_dofs() const
{
  return impl->dof_handler.n_dofs();
}
std::size_t ElasticWaveModel::n_cells() const
{
  return impl->mesh.n_active_cells();
}
double ElasticWaveModel::element_size() const
{
  return impl->h;
}
double ElasticWaveModel::smallest_element_size() const
{
  return impl->h_min;
}
double ElasticWaveModel::area() const
{
  return GridTools::volume(impl->mesh);
}
double ElasticWaveModel::boundary_length(const BoundaryPart part) const
{
  double length = 0.0;
  for (const auto& cell : impl->mesh.active_cell_iterators())
    for (const unsigned int f : cell->face_indices())
      if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == boundary_id_of(part))
        length += cell->face(f)->measure();
  return length;
}
std::size_t ElasticWaveModel::n_constraints() const
{
  return impl->constraints.n_constraints();
}
std::string ElasticWaveModel::solver_name() const
{
  return !impl->factorizations.empty()
             ? impl->solver().name()
             : make_effective_solver(impl->description.solver, impl->description.direct_solver,
                                     1e-10)
                   ->name();
}
double ElasticWaveModel::p_wave_speed() const
{
  return impl->vp;
}
double ElasticWaveModel::s_wave_speed() const
{
  return impl->vs;
}
const Timings& ElasticWaveModel::timings() const
{
  return impl->timings;
}

MonitorSample ElasticWaveModel::sample_monitor(const std::size_t monitor) const
{
  return impl->sample_monitor(monitor);
}

std::array<double, 2> ElasticWaveModel::free_field_velocity(const double y) const
{
  AssertThrow(impl->column, ExcMessage("free_field_velocity: the model has no free_field part"));
  const auto probe = impl->column->impl->make_probe(
      impl->description.lower[0] + 0.5 * impl->h,
      std::clamp(y, impl->description.lower[1], impl->description.upper[1]));
  return impl->column_sample(*probe).velocity;
}

double ElasticWaveModel::l2_error(const VectorField& exact_displacement) const
{
  Vector<float> per_cell(impl->mesh.n_active_cells());
  VectorTools::integrate_difference(impl->dof_handler, impl->relative_displacement(),
                                    FieldFunction(exact_displacement), per_cell,
                                    QGauss<2>(impl->fe.degree + 2), VectorTools::L2_norm);
  return VectorTools::compute_global_error(impl->mesh, per_cell, VectorTools::L2_norm);
}

EnergyBalance ElasticWaveModel::energy() const
{
  // Kinetic and strain energy on demand: two products with the global matrices, as costly as
  // a step's right-hand side.
  EnergyBalance e = impl->energies;
  e.kinetic = 0.5 * impl->mass.matrix_norm_square(impl->v);
  e.strain = impl->strain_energy();
  e.dissipated = e.initial + e.work_of_input + e.work_of_dashpots + e.work_of_rayleigh +
                 e.work_of_springs - e.stored();
  return e;
}

double ElasticWaveModel::work_of_springs() const
{
  return impl->energies.work_of_springs;
}

std::string ElasticWaveModel::write_snapshot(const std::string& directory,
                                             const std::string& basename,
                                             const VtuCompression compression)
{
  return impl->write_snapshot(directory, basename, compression);
}

} // namespace ddafem::fem
