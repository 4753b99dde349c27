// The state and the steps of ElasticWaveModel, shared by the files that implement it (private:
// only fem/ includes it). One file per concern: setup and mesh (far_field_setup.cc), matrices
// and the effective matrix (far_field_assembly.cc), the static stage
// (far_field_static_stage.cc), the free-field column (free_field_column.cc), point springs
// (point_springs.cc), the Newmark step (newmark_step.cc), monitors and snapshots
// (far_field_output.cc); elastic_wave_model.cc builds the model and forwards the public calls.
#pragma once

#include "common/format.h"
#include "common/input_error.h"
#include "common/recent_cache.h"
#include "common/stopwatch.h"
#include "fem/elastic_wave_model.h"
#include "fem/far_field_mesh.h"
#include "fem/linear_solvers.h"

#include <deal.II/base/function.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace ddafem::fem
{
/// Small helpers of the ElasticWaveModel implementation files.
namespace far_field_detail
{
using namespace dealii;

inline void require(const bool condition, const std::string& message)
{
  if (!condition)
    throw InputError("far field: " + message);
}

/// x^T A x with the same bits whatever the threads do: SparseMatrix::matrix_norm_square sums
/// the row ranges that TBB hands out as it goes, so its last bits changed from run to run;
/// vmult computes each row alone and Vector's scalar product sums in fixed blocks.
inline double norm_square(const SparseMatrix<double>& a, const Vector<double>& x)
{
  Vector<double> ax(x.size());
  a.vmult(ax, x);
  return x * ax;
}

/// A point of the mesh with what sampling a field there needs, fixed with the mesh: the DOFs of
/// the cell around it and their shape functions' values, gradients [1/m] and components there.
/// values() and gradients() sum over the cell's DOFs in their order, as
/// FEValues::get_function_values and get_function_gradients do, without reading the DOF values
/// through the cell each time.
struct PointProbe
{
  std::vector<types::global_dof_index> dofs;
  std::vector<unsigned int> component;
  std::vector<double> value;
  std::vector<Tensor<1, 2>> gradient;

  /// The vector field x at the point.
  std::array<double, 2> values(const Vector<double>& x) const
  {
    std::array<double, 2> out{{0.0, 0.0}};
    for (std::size_t i = 0; i < dofs.size(); ++i)
      out[component[i]] += x(dofs[i]) * value[i];
    return out;
  }
  /// The gradients of x's two components at the point.
  std::array<Tensor<1, 2>, 2> gradients(const Vector<double>& x) const
  {
    std::array<Tensor<1, 2>, 2> out;
    for (std::size_t i = 0; i < dofs.size(); ++i)
      out[component[i]] += x(dofs[i]) * gradient[i];
    return out;
  }
};

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
} // namespace far_field_detail

// The implementation files work in deal.II's names, as the single file they come from did.
using namespace dealii;

using far_field_detail::PlaneElasticity;

class ElasticWaveModel::Impl
{
public:
  explicit Impl(const FarFieldDescription& description);

  StepResult prepare_step(double dt);
  StepResult finish_step(const std::vector<double>& point_loads);
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
  /// Checkpoints (fem/far_field_checkpoint.cc): save and load in one function.
  template <class Archive>
  void transfer_state(Archive& archive);

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
  /// P^-1 e_d at `dofs` for each d of `dofs` (by_dof), or P^-1 N^T e_j at `dofs` for each
  /// spring component j: the columns of (P^-1)_DD or of (P^-1 N^T)_D.
  std::vector<std::vector<double>>
  unit_load_responses(const std::vector<types::global_dof_index>& dofs, bool by_dof);
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
  std::vector<far_field_detail::PointProbe> column_probes;
  /// A quadrature point of a free_field face, with what its load needs at every step: the
  /// face's outward normal and, for each DOF of its cell, N_i JxW and N_i's component.
  struct FreeFieldPoint
  {
    Tensor<1, 2> normal;
    std::vector<types::global_dof_index> dofs;
    std::vector<double> weight;          ///< N_i(x_q) JxW_q [m]
    std::vector<unsigned int> component; ///< the component of N_i
  };
  std::vector<FreeFieldPoint> free_field_points; ///< one per column probe, in the same order
  State column_start;        ///< the column's state at the start of the step in progress
  bool column_ahead = false; ///< the column has advanced into a step not finished yet
  void make_free_field_column();
  /// Adds integral(N^T (sigma_ff n + D v_ff)) over the free_field faces to f.
  void add_free_field_load(Vector<double>& f) const;
  /// Column velocity and stress at a probe of the column.
  MonitorSample column_sample(const far_field_detail::PointProbe& probe) const;
  /// This model's velocity and stress at one of its probes.
  MonitorSample probe_sample(const far_field_detail::PointProbe& probe) const;
  /// As another model's free-field column (ElasticWaveModel::add_probe).
  std::vector<far_field_detail::PointProbe> probes;
  State remembered; ///< ElasticWaveModel::remember_state
  far_field_detail::PointProbe make_probe(double x, double y) const;
  bool is_free_field_face(const DoFHandler<2>::active_cell_iterator& cell, unsigned int f) const;

private:
  // Setup (far_field_setup.cc).
  void validate() const;
  void make_mesh();
  void make_constraints();
  void locate_monitors();

  // Matrices (far_field_assembly.cc).
  void assemble_matrices();
  /// M and K over the cells.
  void assemble_domain();
  /// C (into `full_damping`, on the domain's pattern), the boundary springs' part of K and the
  /// input load shape over the boundary faces.
  void assemble_boundary(SparseMatrix<double>& full_damping);
  /// The viscous-spring boundary's K = G / R (alpha_n n n^T + alpha_t (I - n n^T)) of one face.
  void assemble_face_springs(const FEFaceValues<2>& values, const BoundaryCondition& bc,
                             FullMatrix<double>& cell_springs) const;
  /// `damping` = the nonzero entries of `full_damping` on a boundary-only pattern.
  void store_damping(const SparseMatrix<double>& full_damping);
  void factorize(double dt);
  void input_force(double time, Vector<double>& f) const;
  /// out = C x with C = dashpots + Rayleigh (alpha M + beta K).
  void damping_vmult(Vector<double>& out, const Vector<double>& x) const;

  // Static stage (far_field_static_stage.cc).
  void solve_static_stage();
  /// Gravity rho g and the in-situ stress's internal force integral(B^T sigma0) [N].
  Vector<double> static_load() const;
  /// The static stage's supports: the dynamic stage's plus the absorbing parts held; false if
  /// no part holds the model.
  bool make_static_supports(AffineConstraints<double>& supports) const;

  // Newmark step (newmark_step.cc).
  void compute_initial_acceleration();
  /// A free-field column ahead of its model (a step prepared, not finished) goes back to the
  /// step's start; otherwise the start is saved.
  void rewind_column();
  /// f(t + dt) into pending.force_new (input and free-field loads; advances the column) and
  /// the condensed Newmark right-hand side into `rhs`; the column's status.
  StepResult newmark_rhs(double dt, Vector<double>& rhs);
  /// pending.u_new = P^-1 rhs, from Newmark's u1 with a1 extrapolated as a guess (for cg).
  void solve_predictor(double dt, const Vector<double>& rhs);
  /// u_new += P^-1 N^T q (the point loads' response, one more solve).
  void add_point_load_response(const std::vector<double>& point_loads, Vector<double>& u_new);
  /// Work of the dashpots, Rayleigh damping, input and springs over the step to u_new, v_new.
  void add_work_of_step(const Vector<double>& u_new, const Vector<double>& v_new,
                        const std::vector<double>& point_loads);
  /// Work of the point springs' forces F = q - K N u (mid-step forces); stores F at t + dt.
  void add_work_of_springs(const Vector<double>& u_new, const std::vector<double>& point_loads);

public:
  void condense_rhs(Vector<double>& rhs) const;
  /// u - u_s: the displacement the dynamic stage reports.
  Vector<double> relative_displacement() const;
  /// In-situ stress sigma0 at height y: (sxx, syy, sxy) [Pa].
  std::array<double, 3> initial_stress(double y) const;
  double strain_energy() const;
};

} // namespace ddafem::fem
