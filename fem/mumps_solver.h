// MUMPS on a distributed Trilinos matrix, called directly (issue 22): Trilinos' Amesos_Mumps
// hands MUMPS one right-hand side at a time, so the ties' condensation G = N P^-1 N^T (hundreds
// of right-hand sides) read the factors once per column; MUMPS itself solves a block of
// right-hand sides in one pass over its factors (level-3 BLAS).
#pragma once

#include <Epetra_CrsMatrix.h>
#include <Epetra_Import.h>
#include <Epetra_Map.h>
#include <Epetra_MultiVector.h>
#include <mpi.h>

#include <memory>

namespace ddafem::fem
{
/// The LDL^T factorization of a symmetric matrix distributed over the ranks of `comm` (each
/// rank gives its rows' lower triangle), and solves with it. Every call is collective; the
/// factors live where MUMPS puts them, the right-hand sides and solutions are gathered to and
/// scattered from rank 0 (MUMPS' centralized dense right-hand side).
class DistributedMumps
{
public:
  /// Analyses and factorizes `matrix` (square, symmetric, with a global numbering 0..n-1).
  /// Throws std::runtime_error naming MUMPS' error code (INFOG(1)) if it fails.
  DistributedMumps(const Epetra_CrsMatrix& matrix, MPI_Comm comm);
  ~DistributedMumps();
  DistributedMumps(const DistributedMumps&) = delete;
  DistributedMumps& operator=(const DistributedMumps&) = delete;

  /// x = A^-1 b for every column at once (x and b on the matrix's row map). Throws
  /// std::runtime_error if MUMPS fails.
  void solve(Epetra_MultiVector& x, const Epetra_MultiVector& b);

private:
  struct Instance; ///< MUMPS' own structure (dmumps_c.h stays in mumps_solver.cc)
  std::unique_ptr<Instance> mumps;
  Epetra_Map all_on_first; ///< every row on rank 0
  Epetra_Import gather;    ///< from the matrix's rows to all_on_first
};
} // namespace ddafem::fem
