// ElasticWaveModel time stepping: the initial state, one Newmark step in two halves
// (prepare_step: predictor solve; finish_step: point loads, update, energies).
#include "fem/elastic_wave_model_impl.h"

#include "common/newmark.h"
#include "fem/far_field_kernels.h"

#include <deal.II/lac/precondition.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace ddafem::fem
{
using namespace far_field_detail;

namespace
{
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
} // namespace

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
  energies.kinetic = 0.5 * norm_square(mass, v);
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

StepResult ElasticWaveModel::Impl::prepare_step(const double dt)
{
  require(dt > 0.0 && std::isfinite(dt), "advance: dt = " + format_number(dt) + ", expected > 0");
  StepResult status;
  rewind_column();
  pending.active = false;
  try
  {
    ensure_factorized(dt);
    Vector<double> rhs;
    const StepResult column_status = newmark_rhs(dt, rhs);
    if (!column_status.taken)
      return column_status;
    solve_predictor(dt, rhs);
    pending.dt = dt;
    pending.active = true;
  }
  catch (const std::exception& e)
  {
    status = StepResult::failure(std::string("far field: solver failed: ") + e.what());
  }
  return status;
}

void ElasticWaveModel::Impl::rewind_column()
{
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
}

StepResult ElasticWaveModel::Impl::newmark_rhs(const double dt, Vector<double>& rhs)
{
  // Right-hand side of K_eff u1 = f1 + M (...) + C (...) (Newmark, displacement form).
  const auto start = Clock::now();
  const double t1 = t + dt;
  pending.force_new.reinit(force.size());
  input_force(t1, pending.force_new);
  if (column)
  {
    const StepResult column_status = column->advance(dt);
    column_ahead = true;
    if (!column_status.taken)
      return column_status;
    add_free_field_load(pending.force_new);
  }
  const NewmarkCoefficients newmark = newmark_coefficients(beta, gamma, dt);
  const double m_u = newmark.mass_u;
  const double m_v = newmark.mass_v;
  const double m_a = 1.0 / (2.0 * beta) - 1.0;
  const double c_u = newmark.damping_u;
  const double c_v = gamma / beta - 1.0;
  const double c_a = dt * (gamma / (2.0 * beta) - 1.0);
  Vector<double> combination(u.size()), product(u.size());
  rhs = pending.force_new;
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
  return {};
}

void ElasticWaveModel::Impl::solve_predictor(const double dt, const Vector<double>& rhs)
{
  // Initial guess (for cg): Newmark's u1 with a1 extrapolated linearly, 2 a0 - a_previous.
  const auto start = Clock::now();
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
}

StepResult ElasticWaveModel::Impl::finish_step(const std::vector<double>& point_loads)
{
  AssertThrow(pending.active, ExcMessage("finish_step() without prepare_step()"));
  AssertThrow(point_loads.size() == 2 * springs.size(),
              ExcMessage("finish_step(): " + std::to_string(point_loads.size()) +
                         " point loads for " + std::to_string(springs.size()) + " springs"));
  pending.active = false;
  column_ahead = false;
  StepResult status;
  const double dt = pending.dt;
  const double t1 = t + dt;
  Vector<double>& u_new = pending.u_new;
  try
  {
    add_point_load_response(point_loads, u_new);

    const auto start = Clock::now();
    if (!std::all_of(u_new.begin(), u_new.end(), [](double x) { return std::isfinite(x); }))
    {
      status =
          StepResult::failure("far field: non-finite displacement at t = " + format_number(t1));
      timings.update += seconds_since(start);
      return status;
    }
    const NewmarkCoefficients newmark = newmark_coefficients(beta, gamma, dt);
    const double m_u = newmark.mass_u;
    const double m_v = newmark.mass_v;
    const double m_a = 1.0 / (2.0 * beta) - 1.0;
    Vector<double> a_new(u.size()), v_new(v);
    a_new.equ(m_u, u_new);
    a_new.add(-m_u, u, -m_v, v);
    a_new.add(-m_a, a);
    v_new.add(dt * (1.0 - gamma), a, dt * gamma, a_new);
    add_work_of_step(u_new, v_new, point_loads);

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
    status = StepResult::failure(std::string("far field: solver failed: ") + e.what());
  }
  return status;
}

void ElasticWaveModel::Impl::add_point_load_response(const std::vector<double>& point_loads,
                                                     Vector<double>& u_new)
{
  const auto start = Clock::now();
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
}

void ElasticWaveModel::Impl::add_work_of_step(const Vector<double>& u_new,
                                              const Vector<double>& v_new,
                                              const std::vector<double>& point_loads)
{
  // Work over the step with mid-step forces (exact balance for the trapezoidal rule, whose
  // du = dt (v0 + v1) / 2).
  Vector<double> product(u.size());
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
    add_work_of_springs(u_new, point_loads);
}

void ElasticWaveModel::Impl::add_work_of_springs(const Vector<double>& u_new,
                                                 const std::vector<double>& point_loads)
{
  // F = q - K N u on the far field; its work with mid-step forces.
  const std::vector<double> w_old = evaluate_at_springs(u);
  const std::vector<double> w_new = evaluate_at_springs(u_new);
  add_spring_work_of_step(springs, point_loads, w_old, w_new, spring_force,
                          energies.work_of_springs);
}

} // namespace ddafem::fem
