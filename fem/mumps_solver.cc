// DistributedMumps: MUMPS' C interface (dmumps_c.h) on an Epetra matrix.
#include "fem/mumps_solver.h"

#include <dmumps_c.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace ddafem::fem
{
namespace
{
// MUMPS' jobs (its user guide, section 5.1) and the controls set here (1-based, as documented).
constexpr MUMPS_INT initialize = -1, finish = -2, analyse = 1, factorize = 2, solve_job = 3;
constexpr MUMPS_INT general_symmetric = 2; ///< LDL^T with pivoting: symmetric, any sign
constexpr MUMPS_INT host_works = 1;        ///< rank 0 also factorizes and solves

/// Every rank's rows of `matrix`, lower triangle only (MUMPS sums (i, j) and (j, i) of a
/// symmetric matrix), as 1-based triplets.
struct Triplets
{
  std::vector<MUMPS_INT> rows, columns;
  std::vector<double> values;
};

Triplets lower_triangle(const Epetra_CrsMatrix& matrix)
{
  Triplets t;
  for (int i = 0; i < matrix.NumMyRows(); ++i)
  {
    int n = 0;
    double* values = nullptr;
    int* columns = nullptr;
    matrix.ExtractMyRowView(i, n, values, columns);
    const int row = matrix.GRID(i);
    for (int k = 0; k < n; ++k)
    {
      const int column = matrix.GCID(columns[k]);
      if (column > row)
        continue;
      t.rows.push_back(row + 1);
      t.columns.push_back(column + 1);
      t.values.push_back(values[k]);
    }
  }
  return t;
}
} // namespace

struct DistributedMumps::Instance
{
  DMUMPS_STRUC_C id{};
  Triplets entries; ///< MUMPS keeps pointers to them until the factorization
  bool started = false;

  Instance() = default;
  Instance(const Instance&) = delete;
  Instance& operator=(const Instance&) = delete;
  /// MUMPS frees its factors: also when the constructor of DistributedMumps threw.
  ~Instance()
  {
    if (!started)
      return;
    id.job = finish;
    dmumps_c(&id);
  }

  /// Runs a job; throws naming it and MUMPS' error code if it failed on any rank.
  void run(const MUMPS_INT job, const char* what)
  {
    id.job = job;
    dmumps_c(&id);
    if (id.infog[0] < 0) // INFOG(1): the same on every rank
      throw std::runtime_error(std::string("MUMPS: ") + what +
                               " failed (INFOG(1) = " + std::to_string(id.infog[0]) +
                               ", INFOG(2) = " + std::to_string(id.infog[1]) + ")");
  }
};

DistributedMumps::DistributedMumps(const Epetra_CrsMatrix& matrix, MPI_Comm comm)
    : mumps(std::make_unique<Instance>()),
      all_on_first(-1, matrix.Comm().MyPID() == 0 ? matrix.NumGlobalRows() : 0, 0, matrix.Comm()),
      gather(all_on_first, matrix.RowMap())
{
  DMUMPS_STRUC_C& id = mumps->id;
  id.comm_fortran = static_cast<MUMPS_INT>(MPI_Comm_c2f(comm));
  id.par = host_works;
  id.sym = general_symmetric;
  mumps->run(initialize, "initialization");
  mumps->started = true;
  id.icntl[0] = -1; // ICNTL(1-4): no messages
  id.icntl[1] = -1;
  id.icntl[2] = -1;
  id.icntl[3] = 0;
  id.icntl[13] = 50; // ICNTL(14): 50 % more working space than the analysis estimates
  id.icntl[17] = 3;  // ICNTL(18): the matrix distributed, each rank its own entries
  mumps->entries = lower_triangle(matrix);
  id.n = matrix.NumGlobalRows();
  id.nnz_loc = static_cast<MUMPS_INT8>(mumps->entries.values.size());
  id.irn_loc = mumps->entries.rows.data();
  id.jcn_loc = mumps->entries.columns.data();
  id.a_loc = mumps->entries.values.data();
  mumps->run(analyse, "the analysis");
  mumps->run(factorize, "the factorization");
  mumps->entries = Triplets(); // the factors hold what MUMPS needs
}

DistributedMumps::~DistributedMumps() = default;

void DistributedMumps::solve(Epetra_MultiVector& x, const Epetra_MultiVector& b)
{
  // The right-hand sides gathered on rank 0, one column after another (stride n), solved in
  // place and scattered back.
  Epetra_MultiVector on_first(all_on_first, b.NumVectors());
  on_first.Import(b, gather, Insert);
  DMUMPS_STRUC_C& id = mumps->id;
  id.nrhs = b.NumVectors();
  id.lrhs = id.n;
  id.rhs = on_first.Values(); // constant stride: made here with all columns in one block
  mumps->run(solve_job, "the solve");
  id.rhs = nullptr;
  x.Export(on_first, gather, Insert);
}
} // namespace ddafem::fem
