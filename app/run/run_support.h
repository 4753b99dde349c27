// Small pieces shared by the run commands of the DDA and far-field models.
#pragma once

#include "common/history_writer.h"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace ddafem::run_support
{
/// Peak resident memory of this process [MB]: VmHWM from /proc/self/status (getrusage's
/// ru_maxrss would include the image of a parent that forked us, e.g. a Python driver); 0 where
/// /proc is not available.
double peak_memory_mb();
/// Resident memory of this process now [bytes]: VmRSS from /proc/self/status; 0 where /proc is
/// not available.
double resident_memory_bytes();

/// This process's rank when mpirun started it (Open MPI's OMPI_COMM_WORLD_RANK, or PMIX_RANK,
/// PMI_RANK); none otherwise: ddafem touches MPI only when started by mpirun.
std::optional<unsigned int> mpi_rank_from_environment();

/// The number of ranks mpirun started (OMPI_COMM_WORLD_SIZE, PMI_SIZE) and the job's name
/// (PMIX_NAMESPACE, OMPI_MCA_ess_base_jobid; "" if neither), when mpirun started this process
/// (mpi_rank_from_environment); none otherwise.
struct MpiJob
{
  unsigned int rank = 0, size = 1;
  std::string name;
};
std::optional<MpiJob> mpi_job_from_environment();

/// Creates the output directory (and parents); InputError naming it on failure.
void create_output_directory(const std::filesystem::path& directory);
/// Writes `text` to `path` through a temporary file (`path` + ".tmp") renamed into place: a
/// reader, or a run killed meanwhile, finds the old file or the new one, never a part. Throws
/// std::runtime_error naming the file if it cannot (a full disk), leaving the old file.
void write_text_file(const std::filesystem::path& path, const std::string& text);

/// Removes what an earlier run left in `dir`, by ddafem's own file names only (summary.json,
/// histories.h5, the PVD collections and their numbered VTU files, expanded_scene.yaml, the
/// report and its figures, temporary files of an interrupted write), so that no result of
/// another run stays beside this one's. Returns how many files it removed; throws
/// std::runtime_error naming a file it cannot remove.
std::size_t clear_earlier_results(const std::filesystem::path& dir);

/// Whether a snapshot is due at `time` with the given interval [s], advancing `next`;
/// interval 0 writes only where the caller asks (first and last).
bool snapshot_due(double time, double interval, double dt, double& next);

/// The displacement, velocity and stress channels of one monitor in histories.h5;
/// `where` says what the values belong to, e.g. "of the material point".
void add_monitor_channels(std::vector<HistoryChannel>& channels, const std::string& name,
                          const std::string& point_where, const std::string& stress_where);

/// Writes DIR/summary.json and reports the end of a run on `log`: on failure the reason and
/// where the results so far are (returns exit code 1), else the step count, wall time and the
/// result files with `view_file` (the PVD) first (returns 0); a run stopped at a budget
/// (status "stopped") returns 3.
int finish_run(const std::filesystem::path& dir, const nlohmann::json& summary,
               const std::string& failure, const std::string& steps, double time, double wall,
               const std::string& view_file, std::ostream& log);

/// One-line progress display on a terminal, at most five updates a second. The estimate of the
/// remaining wall time follows the simulated time [s] towards `end_time` (step counts do not
/// tell: adaptive control cuts dt, and bathe takes two half steps per step); beyond it (a settle
/// stage) it is not known.
class Progress
{
public:
  Progress(bool enabled_, double end_time_) : enabled(enabled_), end_time(end_time_) {}
  void update(std::size_t step, double time, double wall, bool force = false);
  void finish();

private:
  bool enabled;
  double end_time;
  double last = -1.0;
};

} // namespace ddafem::run_support
