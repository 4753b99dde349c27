// A far field tied to the blocks and distributed over the MPI ranks (issue 22; module side of
// app/far_field_module/far_field_module.h): `mpirun -np N ddafem run SCENE` of a coupled scene.
// Every rank runs the whole blocks' run (the blocks are replicated: the same steps, contacts and dt
// cuts on every rank), and the far field's calls in it are collective. The ties
// (coupling::FarFieldTies) see the far field through fem::PointSpringField, which
// DistributedWaveModel gives every rank bit for bit (its point vectors and G are summed from the
// owning rank's values and zeros), and finish_step() takes rank 0's tie loads and stops the run if
// another rank's differ. Rank 0 writes the run's files; rank K > 0 writes its copy of the blocks'
// outputs in DIR/ranks/rank_K (app/run/run.cc) and its piece of each far-field snapshot in DIR.
#include "app/far_field_module/distributed_support.h"
#include "app/far_field_module/far_field_parts.h"
#include "app/run/run_support.h"

#include "common/format.h"
#include "common/input_error.h"

#include <deal.II/base/mpi.h>

namespace ddafem
{
namespace
{
class DistributedTiedFarField : public TiedFarFieldOf<fem::DistributedWaveModel>
{
public:
  DistributedTiedFarField(const Scene& scene_, dda::System& system_)
      : TiedFarFieldOf(scene_, system_, *scene_.far_field, mpi_world(),
                       distributed_solver(*scene_.far_field)),
        comm(mpi_world()), rank(dealii::Utilities::MPI::this_mpi_process(comm))
  {
  }

  std::string write_snapshot(const std::filesystem::path& dir, fem::VtuCompression) override
  {
    if (!snapshot_written) // rank 0 has cleared an earlier run's pieces before any rank writes
      MPI_Barrier(comm);
    snapshot_written = true;
    // The pieces and the .pvtu records go to rank 0's directory; rank K's is DIR/ranks/rank_K.
    const std::filesystem::path out = rank == 0 ? dir : dir.parent_path().parent_path();
    return far_field.write_snapshot(out.string(), "far_field");
  }
  void add_to_summary(nlohmann::json& summary) const override;
  void describe(std::ostream& out) const override;
  void save(CheckpointOut&) const override
  {
    throw InputError("a run distributed with mpirun cannot write checkpoints yet");
  }
  void load(CheckpointIn&) override
  {
    throw InputError("a run distributed with mpirun cannot be resumed yet: run it again");
  }
  bool can_checkpoint() const override { return false; }
  bool all_go_on(const bool go) const override
  {
    return dealii::Utilities::MPI::max(go ? 0 : 1, comm) == 0;
  }

private:
  MPI_Comm comm;
  unsigned int rank = 0;
  bool snapshot_written = false;
};

void DistributedTiedFarField::add_to_summary(nlohmann::json& summary) const
{
  const fem::DistributedTimings& t = far_field.timings();
  const fem::EnergyBalance fe = far_field.energy();
  add_model_summary(summary);
  summary["far_field"] = {{"solver", name_of(distributed_solver(*scene.far_field))},
                          {"linear_iterations", t.linear_iterations},
                          {"levels", t.n_levels},
                          {"timings_s",
                           {{"setup", t.setup},
                            {"factorize", t.factorize},
                            {"assemble", t.assemble},
                            {"solve", t.solve},
                            {"update", t.update}}},
                          {"energy_J", far_field_energy_summary(fe)}};
  add_arrival_summary(summary);
  summary["interface"] = interface_summary(ties, fe);
  summary["mpi"] = {{"ranks", dealii::Utilities::MPI::n_mpi_processes(comm)},
                    {"rank", rank},
                    {"locally_owned_far_field_dofs", far_field.n_locally_owned_dofs()}};
}

void DistributedTiedFarField::describe(std::ostream& out) const
{
  out << "  far field (distributed over " << dealii::Utilities::MPI::n_mpi_processes(comm)
      << " MPI ranks): " << far_field.n_cells() << " cells of "
      << format_significant(far_field.element_size()) << " m, FE_Q(" << scene.far_field->degree
      << "), " << far_field.n_dofs() << " DOFs, solver "
      << name_of(distributed_solver(*scene.far_field)) << "\n";
  out << "  interface: part " << fem::name_of(scene.interface->part) << ", " << ties.n_ties()
      << " ties on " << ties.n_tied_blocks() << " blocks\n";
}
} // namespace

std::unique_ptr<TiedFarField> make_distributed_tied_far_field(const Scene& scene,
                                                              dda::System& system)
{
  return std::make_unique<DistributedTiedFarField>(scene, system);
}

} // namespace ddafem
