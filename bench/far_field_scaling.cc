// Times the distributed far field (fem/distributed_wave_model.h) on the ranks it is started on
// (not a test): the square of bench/fem_bench.cc (N x N Q2 elements of 4 m, an SV pulse entering
// through the absorbing base, Lysmer sides, free top). Rank 0 prints one JSON line.
//
//   mpirun -np 2 build/bench/far_field_scaling --cells 352 --steps 100 --solver cg_amg
//
// --cells N: N x N elements (2 (2N + 1)^2 DOFs); --steps S: timed steps after 5 warm-up steps;
// --solver cg_amg | cg_jacobi | mumps. Each timed step starts at a barrier and ends when the
// slowest rank has finished it; the median step is reported. --ties M: M point springs along the
// top, as the blocks' ties (2M right-hand sides), and the time of their condensation G =
// N P^-1 N^T; --width W: right-hand sides solved at once for it (1: one solve each; default: the
// model's).
#include "bench/bench_support.h"
#include "fem/distributed_wave_model.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace
{
using namespace ddafem;
using namespace ddafem::fem;

using bench::peak_memory_mb;
using bench::seconds;

FarFieldDescription square(const unsigned int cells)
{
  FarFieldDescription d;
  const double size = 4.0 * cells;
  d.lower = {{0.0, 0.0}};
  d.upper = {{size, size}};
  d.element_size = 4.0;
  d.degree = 2;
  d.density = 2650.0;
  d.youngs_modulus = 20e9;
  d.poisson_ratio = 0.25;
  d.boundaries = {{BoundaryPart::bottom, BoundaryKind::input, 1.0, 1.0, {}},
                  {BoundaryPart::left, BoundaryKind::lysmer, 1.0, 1.0, {}},
                  {BoundaryPart::right, BoundaryKind::lysmer, 1.0, 1.0, {}}};
  d.incident.type = IncidentWave::Type::sv;
  d.incident.velocity = TimeFunction::sine_pulse(0.5, 25.0, 1.0, 0.0);
  d.monitors = {{"surface", {{0.5 * size, size}}}};
  return d;
}

struct Options
{
  unsigned int cells = 32, steps = 20, ties = 0, width = 0; ///< width 0: the model's
  DistributedSolver solver = DistributedSolver::cg_amg;
};

bool parse(int argc, char** argv, Options& o)
{
  for (int i = 1; i + 1 < argc; i += 2)
  {
    const std::string arg = argv[i], value = argv[i + 1];
    if (arg == "--cells")
      o.cells = static_cast<unsigned int>(std::atoi(value.c_str()));
    else if (arg == "--steps")
      o.steps = static_cast<unsigned int>(std::atoi(value.c_str()));
    else if (arg == "--ties")
      o.ties = static_cast<unsigned int>(std::atoi(value.c_str()));
    else if (arg == "--width")
      o.width = static_cast<unsigned int>(std::atoi(value.c_str()));
    else if (arg == "--solver" && value_of<DistributedSolver>(value))
      o.solver = *value_of<DistributedSolver>(value);
    else
      return false;
  }
  return argc % 2 == 1 && o.cells > 0 && o.steps > 0;
}

int run(const Options& o)
{
  const MPI_Comm comm = MPI_COMM_WORLD;
  const double dt = 2e-4; // [s]: 4 m Q2 elements, VP 3000 m/s
  auto start = std::chrono::steady_clock::now();
  DistributedWaveModel model(square(o.cells), comm, o.solver);
  const double setup = dealii::Utilities::MPI::max(seconds(start), comm);
  double condensation = 0.0; // [s]
  if (o.ties > 0)
  {
    const double size = 4.0 * o.cells; // [m]
    std::vector<PointSpring> springs;
    for (unsigned int k = 0; k < o.ties; ++k) // 1 GPa/m normal, 0.4 GPa/m shear
      springs.push_back({{{(k + 0.5) * size / o.ties, size}}, {{0.4e9, 0.0, 0.0, 1e9}}});
    model.add_point_springs(BoundaryPart::top, springs);
    if (o.width > 0)
      model.set_condensation_width(o.width);
    MPI_Barrier(comm);
    start = std::chrono::steady_clock::now();
    model.point_flexibility(dt);
    condensation = dealii::Utilities::MPI::max(seconds(start), comm);
  }
  start = std::chrono::steady_clock::now();
  for (int k = 0; k < 5; ++k) // warm-up: the solver's set-up, caches
    if (!model.advance(dt).taken)
      return 1;
  const double warm_up = dealii::Utilities::MPI::max(seconds(start), comm);
  std::vector<double> step_s;
  for (unsigned int k = 0; k < o.steps; ++k)
  {
    MPI_Barrier(comm);
    start = std::chrono::steady_clock::now();
    if (!model.advance(dt).taken)
      return 1;
    step_s.push_back(dealii::Utilities::MPI::max(seconds(start), comm));
  }
  std::sort(step_s.begin(), step_s.end());
  const DistributedTimings& t = model.timings();
  const double surface = model.sample_monitor(0).velocity[0];
  const double memory = peak_memory_mb();
  const double memory_max = dealii::Utilities::MPI::max(memory, comm);
  const double memory_sum = dealii::Utilities::MPI::sum(memory, comm);
  const double solve = dealii::Utilities::MPI::max(t.solve, comm);
  const double solve_fastest = dealii::Utilities::MPI::min(t.solve, comm); // imbalance
  const std::size_t owned_max = dealii::Utilities::MPI::max(model.n_locally_owned_dofs(), comm);
  const double assemble = dealii::Utilities::MPI::max(t.assemble, comm);
  if (dealii::Utilities::MPI::this_mpi_process(comm) == 0)
    std::cout << "{\"ranks\": " << dealii::Utilities::MPI::n_mpi_processes(comm)
              << ", \"cells\": " << model.n_cells() << ", \"dofs\": " << model.n_dofs()
              << ", \"solver\": \"" << name_of(o.solver) << "\", \"setup_s\": " << setup
              << ", \"warm_up_s\": " << warm_up << ", \"factorize_s\": " << t.factorize
              << ", \"ties\": " << o.ties << ", \"condensation_width\": " << o.width
              << ", \"condensation_s\": " << condensation << ", \"steps\": " << o.steps
              << ", \"median_step_ms\": " << 1e3 * step_s[step_s.size() / 2]
              << ", \"solve_ms_per_step\": " << 1e3 * solve / t.n_steps
              << ", \"solve_ms_per_step_fastest_rank\": " << 1e3 * solve_fastest / t.n_steps
              << ", \"owned_dofs_per_rank_max\": " << owned_max
              << ", \"assemble_ms_per_step\": " << 1e3 * assemble / t.n_steps
              << ", \"iterations_per_step\": "
              << static_cast<double>(t.linear_iterations) / t.n_steps
              << ", \"peak_memory_mb_per_rank\": " << memory_max
              << ", \"peak_memory_mb_total\": " << memory_sum
              << ", \"surface_velocity_m_s\": " << surface << "}" << std::endl;
  return 0;
}
} // namespace

int main(int argc, char** argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  Options o;
  if (!parse(argc, argv, o))
  {
    std::cerr
        << "usage: far_field_scaling [--cells N] [--steps S] [--solver cg_amg|cg_jacobi|mumps] "
           "[--ties M] [--width W]\n";
    return 2;
  }
  try
  {
    return run(o);
  }
  catch (const std::exception& e)
  {
    std::cerr << "far_field_scaling: " << e.what() << "\n";
    return 1;
  }
}
