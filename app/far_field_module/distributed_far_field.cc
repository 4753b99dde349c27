// A run of a far field alone distributed over the MPI ranks it was started on (issue 22; module
// side): `mpirun -np N ddafem run SCENE`. Every rank runs the driver and this simulation; the
// model's calls are collective, in the same order on every rank. Rank 0 writes the run's files
// in the output directory (histories.h5, summary.json, far_field.pvd and the .pvtu records);
// every rank writes its .vtu piece of each snapshot there, and the driver's files of rank K > 0
// go to DIR/ranks/rank_K (app/run/run.cc).
#include "app/far_field_module/distributed_support.h"
#include "app/far_field_module/far_field_parts.h"
#include "app/run/run_summary.h"
#include "app/run/run_support.h"

#include "common/format.h"
#include "common/input_error.h"
#include "common/stopwatch.h"
#include "fem/distributed_wave_model.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <cmath>
#include <optional>

namespace ddafem
{
namespace
{
class DistributedFarFieldSimulation : public Simulation
{
public:
  explicit DistributedFarFieldSimulation(const Scene& scene_)
      : scene(scene_), description(*scene.far_field), comm(mpi_world()),
        rank(dealii::Utilities::MPI::this_mpi_process(comm)),
        model(description, comm, distributed_solver(description))
  {
  }

  std::vector<std::string> collect_warnings(bool) const override { return {}; }
  void open_outputs(const std::filesystem::path& dir) override;
  std::size_t n_stages() const override { return 1; }
  bool run_stage(std::size_t k, const std::function<bool()>& report) override;
  void close_outputs() override
  {
    if (failed() || stopped)
      write_state(true);
    flush_outputs();
  }
  void flush_outputs() override
  {
    if (history)
      history->flush();
  }
  bool can_checkpoint() const override { return false; }
  void save_checkpoint(CheckpointOut&) const override {}
  std::size_t resume(CheckpointIn&, const std::filesystem::path&) override
  {
    throw InputError("a run distributed with mpirun cannot be resumed yet: run it again");
  }
  std::size_t n_steps() const override { return model.timings().n_steps; }
  double time() const override { return model.time(); }
  double end_time() const override { return description.end_time; }
  nlohmann::json summary(const std::vector<std::string>& warnings, double wall_time) const override;
  RunEnd end() const override
  {
    return {failed() ? failure.why : std::string(),
            std::to_string(model.timings().n_steps) + " steps", model.time(), "far_field.pvd"};
  }

private:
  bool failed() const { return !failure.taken; }
  /// A history row (rank 0) and with `snapshot` a .pvtu record; collective.
  void write_state(bool snapshot);

  const Scene& scene;
  const fem::FarFieldDescription& description;
  MPI_Comm comm;
  unsigned int rank = 0;
  fem::DistributedWaveModel model;
  std::filesystem::path snapshot_dir;   ///< rank 0's output directory
  std::optional<HistoryWriter> history; ///< rank 0 only
  StepResult failure;
  bool stopped = false;
  std::size_t n_snapshots = 0;
  double output_s = 0.0;
  std::optional<double> last_row_time, last_snapshot_time; ///< [s]
};

void DistributedFarFieldSimulation::open_outputs(const std::filesystem::path& dir)
{
  snapshot_dir = rank == 0 ? dir : dir.parent_path().parent_path(); // DIR/ranks/rank_K
  if (rank == 0)
  {
    history.emplace((dir / "histories.h5").string(), far_field_channels(description));
    history->set_attribute("scene", scene.file);
    history->set_attribute("version", DDAFEM_VERSION);
    history->set_attribute("mpi_ranks",
                           std::to_string(dealii::Utilities::MPI::n_mpi_processes(comm)));
  }
  MPI_Barrier(comm); // rank 0 has cleared an earlier run's pieces before any rank writes one
  write_state(true);
}

void DistributedFarFieldSimulation::write_state(const bool snapshot)
{
  const auto start = Clock::now();
  if (last_row_time != model.time())
  {
    std::vector<double> row;
    append_far_field_monitors(row, model, description.monitors.size());
    const fem::EnergyBalance e = model.energy();
    row.insert(row.end(), {e.kinetic, e.strain, e.work_of_input, e.work_of_dashpots,
                           e.work_of_rayleigh, e.dissipated});
    if (history)
      history->append(model.time(), row);
    last_row_time = model.time();
  }
  if (snapshot && last_snapshot_time != model.time())
  {
    model.write_snapshot(snapshot_dir.string(), "far_field");
    ++n_snapshots;
    last_snapshot_time = model.time();
  }
  output_s += seconds_since(start);
}

bool DistributedFarFieldSimulation::run_stage(std::size_t, const std::function<bool()>& report)
{
  const double dt = description.dt;
  const auto n_steps = static_cast<std::size_t>(std::llround(description.end_time / dt));
  double next_snapshot = scene.output.interval;
  for (std::size_t step = 1; step <= n_steps; ++step)
  {
    failure = model.advance(dt);
    if (failed())
      return false;
    const bool last = step == n_steps;
    const bool snapshot =
        run_support::snapshot_due(model.time(), scene.output.interval, dt, next_snapshot) || last;
    if (step % scene.output.history_every == 0 || snapshot)
      write_state(snapshot);
    // A budget one rank reaches stops them all after the same step.
    const int stop = report() ? 0 : 1;
    if (dealii::Utilities::MPI::max(stop, comm) == 1)
    {
      stopped = !last;
      return last;
    }
  }
  return true;
}

nlohmann::json DistributedFarFieldSimulation::summary(const std::vector<std::string>& warnings,
                                                      double wall_time) const
{
  const fem::DistributedTimings& t = model.timings();
  nlohmann::json s = summary_head(scene, failed(), failure.why, model.time(), description.end_time,
                                  t.n_steps, description.dt);
  s["integrator"] = fem::name_of(description.integrator);
  s["solver"] = {{"name", name_of(distributed_solver(description))},
                 {"linear_iterations", t.linear_iterations}};
  s["mpi"] = {{"ranks", dealii::Utilities::MPI::n_mpi_processes(comm)},
              {"rank", rank},
              {"locally_owned_dofs", model.n_locally_owned_dofs()}};
  s["model"] = {{"far_field_cells", model.n_cells()},
                {"far_field_dofs", model.n_dofs()},
                {"element_size_m", model.element_size()},
                {"degree", description.degree},
                {"blocks", 0}};
  add_run_facts(s, wall_time, warnings);
  s["timings_s"] = {{"setup", t.setup + t.factorize},
                    {"assemble", t.assemble},
                    {"solve", t.solve},
                    {"update", t.update},
                    {"output", output_s}};
  s["outputs"] = {
      {"histories", "histories.h5"}, {"far_field", "far_field.pvd"}, {"snapshots", n_snapshots}};
  return s;
}
} // namespace

MPI_Comm mpi_world()
{
  static int argc = 0;
  static char** argv = nullptr;
  static dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  return MPI_COMM_WORLD;
}

void end_every_rank(const int exit_code)
{
  int started = 0, finished = 0, size = 1;
  MPI_Initialized(&started);
  MPI_Finalized(&finished);
  if (started && !finished)
    MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size > 1)
    MPI_Abort(MPI_COMM_WORLD, exit_code);
}

fem::DistributedSolver distributed_solver(const fem::FarFieldDescription& d)
{
  return d.solver == fem::LinearSolver::direct ? fem::DistributedSolver::mumps
                                               : fem::DistributedSolver::cg_jacobi;
}

std::unique_ptr<Simulation> make_distributed_far_field_simulation(const Scene& scene)
{
  return std::make_unique<DistributedFarFieldSimulation>(scene);
}

} // namespace ddafem
