// Times one far-field model (not a test): a square of rock with Q2 elements, an SV pulse entering
// through the absorbing base, Lysmer sides, free top. Prints one JSON line.
//
//   build/bench/fem_bench --cells 112 --solver cg --steps 40
//
// --cells N: N x N elements of 4 m (Q2: about 8 N^2 DOFs); --solver klu | umfpack | cg;
// --steps S: timed steps after 5 warm-up steps; --hole: a graded circular hole in the middle.
#include "bench/bench_support.h"
#include "fem/elastic_wave_model.h"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

namespace
{
using namespace ddafem;
using namespace ddafem::fem;

using bench::peak_memory_mb;
using bench::seconds;
} // namespace

int main(int argc, char** argv)
{
  unsigned int cells = 32, steps = 20;
  std::string solver = "klu";
  bool hole = false;
  double tolerance = 0.0; // 0: the model's default
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--cells" && i + 1 < argc)
      cells = static_cast<unsigned int>(std::atoi(argv[++i]));
    else if (arg == "--steps" && i + 1 < argc)
      steps = static_cast<unsigned int>(std::atoi(argv[++i]));
    else if (arg == "--solver" && i + 1 < argc)
      solver = argv[++i];
    else if (arg == "--tolerance" && i + 1 < argc)
      tolerance = std::atof(argv[++i]);
    else if (arg == "--hole")
      hole = true;
    else
    {
      std::cerr << "usage: fem_bench [--cells N] [--steps S] [--solver klu|umfpack|cg] "
                   "[--tolerance T] [--hole]\n";
      return 2;
    }
  }

  // Rock of VS = 1000 m/s, VP = 1732 m/s; 4 m Q2 elements resolve 25 Hz with 10 nodes per S
  // wavelength; dt = 1 / (25 Hz x 20) = 2 ms, 20 steps per period at the highest frequency.
  const double h = 4.0;
  FarFieldDescription d;
  d.lower = {{0.0, 0.0}};
  d.upper = {{h * cells, h * cells}};
  d.element_size = h;
  d.degree = 2;
  d.density = 2000.0;
  d.youngs_modulus = 5e9;
  d.poisson_ratio = 0.25;
  d.boundaries = {{BoundaryPart::bottom, BoundaryKind::input, 1.0, 1.0, {}},
                  {BoundaryPart::left, BoundaryKind::lysmer, 1.0, 1.0, {}},
                  {BoundaryPart::right, BoundaryKind::lysmer, 1.0, 1.0, {}}};
  d.incident.type = IncidentWave::Type::sv;
  d.incident.velocity = TimeFunction::sine_pulse(0.1, 12.5, 1.0, 0.0);
  d.dt = 2e-3;
  d.solver = solver == "cg" ? LinearSolver::cg : LinearSolver::direct;
  if (tolerance > 0.0)
    d.solver_tolerance = tolerance;
  d.direct_solver = solver == "umfpack" ? DirectSolver::umfpack : DirectSolver::klu;
  if (hole)
  {
    d.hole.shape = HoleShape::circle;
    d.hole.center = {{0.5 * h * cells, 0.5 * h * cells}};
    d.hole.radius = 0.05 * h * cells;
    d.hole.element_size = 0.5;
  }

  const auto start = std::chrono::steady_clock::now();
  ElasticWaveModel model(d);
  model.advance(d.dt); // the first step also computes the initial acceleration
  const double setup = seconds(start);
  for (unsigned int s = 0; s < 4; ++s)
    model.advance(d.dt);
  const Timings before = model.timings();
  const auto run_start = std::chrono::steady_clock::now();
  for (unsigned int s = 0; s < steps; ++s)
    if (!model.advance(d.dt).taken)
    {
      std::cerr << "step failed\n";
      return 1;
    }
  const double run = seconds(run_start);
  const Timings& t = model.timings();
  const double solve = t.solve - before.solve;
  const double iterations =
      static_cast<double>(t.linear_iterations - before.linear_iterations) / steps;

  // Explicit central differences would need dt <= (h / p) / (VP sqrt 2) (node spacing h / p).
  const double dt_explicit =
      model.smallest_element_size() / d.degree / (model.p_wave_speed() * std::sqrt(2.0));
  std::cout.precision(6);
  std::cout << "{\"solver\": \"" << model.solver_name() << "\", \"cells\": " << model.n_cells()
            << ", \"dofs\": " << model.n_dofs() << ", \"hole\": " << (hole ? "true" : "false")
            << ", \"setup_s\": " << setup << ", \"step_s\": " << run / steps
            << ", \"solve_s\": " << solve / steps << ", \"iterations_per_step\": " << iterations
            << ", \"dt_s\": " << d.dt << ", \"dt_explicit_s\": " << dt_explicit
            << ", \"smallest_element_m\": " << model.smallest_element_size()
            << ", \"peak_memory_mb\": " << peak_memory_mb() << "}" << std::endl;
  return 0;
}
