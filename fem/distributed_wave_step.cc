// DistributedWaveModel: the Newmark step (as fem/newmark_step.cc for ElasticWaveModel), the
// monitors, the energies and the parallel output.
#include "fem/distributed_wave_model_impl.h"

#include "common/format.h"
#include "common/input_error.h"
#include "common/newmark.h"
#include "common/stopwatch.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/utilities.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/lac/precondition.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/numerics/data_out.h>

#include <BelosEpetraAdapter.hpp>
#include <BelosLinearProblem.hpp>
#include <BelosPseudoBlockCGSolMgr.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_RCP.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

namespace ddafem::fem
{
void DistributedWaveModel::Impl::compute_initial_acceleration()
{
  initial_acceleration_done = true;
  force = input_shape;
  force *= input_scale * description.incident.velocity.value(t);
  TrilinosWrappers::MPI::Vector rhs(force), product(owned, comm);
  stiffness.vmult(product, u);
  rhs -= product;
  damping.vmult(product, v);
  rhs -= product;
  constraints.set_zero(rhs);
  a = 0.0;
  if (rhs.l2_norm() == 0.0)
    return;
  SolverControl control(std::max<std::size_t>(1000, rhs.size()), 1e-14 * rhs.l2_norm());
  SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
  TrilinosWrappers::PreconditionJacobi diagonal;
  diagonal.initialize(mass);
  cg.solve(mass, a, rhs, diagonal);
  constraints.set_zero(a);
}

unsigned int DistributedWaveModel::Impl::solve(TrilinosWrappers::MPI::Vector& x,
                                               const TrilinosWrappers::MPI::Vector& rhs)
{
  if (rhs.l2_norm() == 0.0) // at rest, before the wave
  {
    x = 0.0;
    return 0;
  }
  Level& level = levels.front();
  if (level.direct)
    return solve_block(x.trilinos_vector(), rhs.trilinos_vector());
  SolverControl control(1000, description.solver_tolerance * rhs.l2_norm());
  SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
  if (level.jacobi)
    cg.solve(level.matrix, x, rhs, *level.jacobi);
  else
    cg.solve(level.matrix, x, rhs, *level.amg);
  return control.last_step();
}

unsigned int DistributedWaveModel::Impl::solve_block(Epetra_MultiVector& x,
                                                     const Epetra_MultiVector& b)
{
  Level& level = levels.front();
  if (level.direct)
  {
    level.direct->solve(x, b);
    return 0;
  }
  using Problem = Belos::LinearProblem<double, Epetra_MultiVector, Epetra_Operator>;
  x.PutScalar(0.0);
  const auto problem = Teuchos::rcp(new Problem(Teuchos::rcpFromRef(level.matrix.trilinos_matrix()),
                                                Teuchos::rcpFromRef(x), Teuchos::rcpFromRef(b)));
  Epetra_Operator& preconditioner =
      level.jacobi ? level.jacobi->trilinos_operator() : level.amg->trilinos_operator();
  problem->setLeftPrec(Teuchos::rcp(new Belos::EpetraPrecOp(Teuchos::rcpFromRef(preconditioner))));
  problem->setProblem();
  // Each column converges to the tolerance relative to its initial residual, its own norm (the
  // zero guess): the criterion of solve().
  const auto parameters = Teuchos::parameterList();
  parameters->set("Maximum Iterations", 1000);
  parameters->set("Convergence Tolerance", description.solver_tolerance);
  Belos::PseudoBlockCGSolMgr<double, Epetra_MultiVector, Epetra_Operator> cg(problem, parameters);
  AssertThrow(cg.solve() == Belos::Converged,
              ExcMessage("CG did not converge in 1000 iterations on " +
                         std::to_string(b.NumVectors()) + " right-hand sides"));
  return static_cast<unsigned int>(cg.getNumIters());
}

void DistributedWaveModel::Impl::prepare(const double dt)
{
  if (!initial_acceleration_done)
    compute_initial_acceleration();
  use_level(dt);
  const NewmarkCoefficients newmark = newmark_coefficients(beta, gamma, dt);
  const double m_a = 1.0 / (2.0 * beta) - 1.0;
  const double c_v = gamma / beta - 1.0, c_a = dt * (gamma / (2.0 * beta) - 1.0);
  auto start = Clock::now();
  // rhs = f(t + dt) + M (m_u u + m_v v + m_a a) + C (c_u u + c_v v + c_a a)
  auto& [force_new, rhs, combination, product, u_new, a_new, v_new] = scratch;
  force_new.equ(input_scale * description.incident.velocity.value(t + dt), input_shape);
  if (column)
  {
    advance_column(dt);
    add_free_field_load(force_new);
  }
  rhs = force_new;
  combination.equ(newmark.mass_u, u);
  combination.add(newmark.mass_v, v, m_a, a);
  mass.vmult(product, combination);
  rhs += product;
  combination.equ(newmark.damping_u, u);
  combination.add(c_v, v, c_a, a);
  damping.vmult(product, combination);
  rhs += product;
  constraints.set_zero(rhs);
  timings.assemble += seconds_since(start);

  start = Clock::now();
  // The guess: Newmark's predictor with the acceleration extrapolated linearly.
  if (timings.n_steps == 0)
    a_previous = a;
  u_new = u;
  u_new.add(dt, v, dt * dt * (0.5 + beta), a);
  u_new.add(-dt * dt * beta, a_previous);
  constraints.set_zero(u_new);
  timings.linear_iterations += solve(u_new, rhs);
  timings.solve += seconds_since(start);
  step_prepared = true;
  prepared_dt = dt;
}

StepResult DistributedWaveModel::Impl::finish(const std::vector<double>& point_loads)
{
  AssertThrow(step_prepared, ExcMessage("finish_step() without prepare_step()"));
  step_prepared = false;
  column_ahead = false;
  const double dt = prepared_dt;
  const NewmarkCoefficients newmark = newmark_coefficients(beta, gamma, dt);
  const double m_a = 1.0 / (2.0 * beta) - 1.0;
  auto& [force_new, rhs, combination, product, u_new, a_new, v_new] = scratch;
  auto start = Clock::now();
  if (std::any_of(point_loads.begin(), point_loads.end(), [](double q) { return q != 0.0; }))
  {
    // u = y + P^-1 N^T q: one more solve with the same matrix.
    set_spring_loads(point_loads, rhs);
    combination = 0.0;
    timings.linear_iterations += solve(combination, rhs);
    u_new += combination;
  }
  timings.solve += seconds_since(start);

  start = Clock::now();
  a_new.equ(newmark.mass_u, u_new);
  a_new.add(-newmark.mass_u, u, -newmark.mass_v, v);
  a_new.add(-m_a, a);
  v_new = v;
  v_new.add(dt * (1.0 - gamma), a, dt * gamma, a_new);
  add_work_of_step(u_new, v_new, force_new);
  if (!springs.empty())
    add_work_of_springs(u_new, point_loads);
  a_previous.swap(a);
  a.swap(a_new);
  u.swap(u_new);
  v.swap(v_new);
  force = force_new;
  t += dt;
  ++timings.n_steps;
  timings.update += seconds_since(start);
  if (!std::isfinite(u.l2_norm()))
    return StepResult::failure("far field (distributed): non-finite displacement at t = " +
                               format_number(t));
  return {};
}

void DistributedWaveModel::Impl::add_work_of_step(const TrilinosWrappers::MPI::Vector& u_new,
                                                  const TrilinosWrappers::MPI::Vector& v_new,
                                                  const TrilinosWrappers::MPI::Vector& force_new)
{
  // Mid-step forces: an exact balance for the trapezoidal rule, whose du = dt (v0 + v1) / 2.
  TrilinosWrappers::MPI::Vector& du = scratch.rhs; // free once the step is solved
  TrilinosWrappers::MPI::Vector& mid = scratch.combination;
  TrilinosWrappers::MPI::Vector& product = scratch.product;
  du = u_new;
  du -= u;
  mid = v;
  mid += v_new;
  mid *= 0.5;
  damping.vmult(product, mid);
  energies.work_of_dashpots -= du * product;
  // Rayleigh's share of C (Impl::assemble), reported apart as ElasticWaveModel does.
  const RayleighDamping& r = description.rayleigh;
  for (const auto& [factor, matrix] : {std::pair{r.alpha, &mass}, std::pair{r.beta, &stiffness}})
    if (factor > 0.0)
    {
      matrix->vmult(product, mid);
      const double work = factor * (du * product);
      energies.work_of_rayleigh -= work;
      energies.work_of_dashpots += work;
    }
  mid = force;
  mid += force_new;
  mid *= 0.5;
  energies.work_of_input += du * mid;
}

const TrilinosWrappers::MPI::Vector&
DistributedWaveModel::Impl::ghosted_field(const TrilinosWrappers::MPI::Vector& x) const
{
  distributed = x;
  constraints.distribute(distributed);
  ghosted = distributed;
  return ghosted;
}

void DistributedWaveModel::Impl::locate_monitors()
{
  const MappingQ1<2> mapping;
  for (const Monitor& m : description.monitors)
  {
    MonitorPoint p;
    p.point = Point<2>(m.point[0], m.point[1]);
    // The rank that owns the first cell holding the point (in the cells' order) evaluates it.
    unsigned int owner = Utilities::MPI::n_mpi_processes(comm);
    for (const auto& cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned() && cell->point_inside(p.point))
      {
        p.cell = cell;
        p.reference = mapping.transform_real_to_unit_cell(cell, p.point);
        owner = Utilities::MPI::this_mpi_process(comm);
        break;
      }
    const unsigned int first = Utilities::MPI::min(owner, comm);
    if (first == Utilities::MPI::n_mpi_processes(comm))
      throw InputError("far field (distributed): monitor '" + m.name + "' at (" +
                       format_number(m.point[0]) + ", " + format_number(m.point[1]) +
                       ") lies outside the far field");
    p.mine = first == Utilities::MPI::this_mpi_process(comm);
    monitors.push_back(p);
  }
}

MonitorSample DistributedWaveModel::sample_monitor(const std::size_t monitor) const
{
  const Impl& m = *impl;
  TrilinosWrappers::MPI::Vector u(m.ghosted_field(m.u)), v(m.ghosted_field(m.v));
  const Impl::MonitorPoint& p = m.monitors.at(monitor);
  std::vector<double> values(7, 0.0); // ux, uy, vx, vy, sxx, syy, sxy; zero on other ranks
  if (p.mine)
  {
    FEValues<2> fe_values(m.fe, Quadrature<2>(p.reference), update_values | update_gradients);
    fe_values.reinit(p.cell);
    std::vector<Vector<double>> uq(1, Vector<double>(2)), vq(1, Vector<double>(2));
    std::vector<std::vector<Tensor<1, 2>>> grad(1, std::vector<Tensor<1, 2>>(2));
    fe_values.get_function_values(u, uq);
    fe_values.get_function_values(v, vq);
    fe_values.get_function_gradients(u, grad);
    const double exx = grad[0][0][0], eyy = grad[0][1][1];
    const double exy = 0.5 * (grad[0][0][1] + grad[0][1][0]);
    values = {uq[0](0),
              uq[0](1),
              vq[0](0),
              vq[0](1),
              m.lambda * (exx + eyy) + 2.0 * m.mu * exx,
              m.lambda * (exx + eyy) + 2.0 * m.mu * eyy,
              2.0 * m.mu * exy};
  }
  Utilities::MPI::sum(values, m.comm, values);
  MonitorSample s;
  s.displacement = {{values[0], values[1]}};
  s.velocity = {{values[2], values[3]}};
  s.stress = {{values[4], values[5], values[6]}};
  return s;
}

EnergyBalance DistributedWaveModel::energy() const
{
  const Impl& m = *impl;
  EnergyBalance e = m.energies;
  TrilinosWrappers::MPI::Vector product(m.owned, m.comm);
  m.mass.vmult(product, m.v);
  e.kinetic = 0.5 * (m.v * product);
  m.stiffness.vmult(product, m.u);
  e.strain = 0.5 * (m.u * product);
  e.dissipated = e.initial + e.work_of_input + e.work_of_dashpots + e.work_of_rayleigh +
                 e.work_of_springs - e.stored();
  return e;
}

StepResult DistributedWaveModel::advance(const double dt)
{
  std::vector<double> free;
  const StepResult status = prepare_step(dt, free);
  if (!status.taken)
    return status;
  return finish_step(std::vector<double>(2 * impl->springs.size(), 0.0));
}

std::string DistributedWaveModel::write_snapshot(const std::string& directory,
                                                 const std::string& basename)
{
  Impl& m = *impl;
  TrilinosWrappers::MPI::Vector u(m.ghosted_field(m.u)), v(m.ghosted_field(m.v));
  DataOut<2> out;
  out.attach_dof_handler(m.dof_handler);
  const std::vector<DataComponentInterpretation::DataComponentInterpretation> vector(
      2, DataComponentInterpretation::component_is_part_of_vector);
  out.add_data_vector(u, std::vector<std::string>(2, "displacement"), DataOut<2>::type_dof_data,
                      vector);
  out.add_data_vector(v, std::vector<std::string>(2, "velocity"), DataOut<2>::type_dof_data,
                      vector);
  Vector<float> subdomain(m.mesh.n_active_cells());
  subdomain = static_cast<float>(m.mesh.locally_owned_subdomain());
  out.add_data_vector(subdomain, "subdomain");
  out.build_patches(m.fe.degree);
  const std::string name = out.write_vtu_with_pvtu_record(
      directory + "/", basename, static_cast<unsigned int>(m.snapshots.size()), m.comm, 5);
  m.snapshots.emplace_back(m.t, name);
  if (Utilities::MPI::this_mpi_process(m.comm) == 0)
  {
    std::ofstream pvd(directory + "/" + basename + ".pvd");
    DataOutBase::write_pvd_record(pvd, m.snapshots);
  }
  return name;
}

} // namespace ddafem::fem
