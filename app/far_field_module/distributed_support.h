// What the far-field module's distributed runs share (issue 22): the MPI communicator and the
// solver a scene's far_field.solver stands for across ranks. Module side, like
// app/far_field_module/far_field_parts.h.
#pragma once

#include "fem/distributed_wave_model.h"
#include "fem/far_field_description.h"

#include <mpi.h>

namespace ddafem
{
/// MPI_COMM_WORLD, with MPI (and p4est) started on first use and finished at exit.
MPI_Comm mpi_world();
/// Ends every rank with `exit_code` (MPI_Abort) if MPI runs on more than one rank; otherwise
/// returns (FarFieldModule::end_every_rank_after_error).
void end_every_rank(int exit_code);
/// The scene's far_field.solver on the ranks: direct as MUMPS, cg as CG with Jacobi.
fem::DistributedSolver distributed_solver(const fem::FarFieldDescription& description);
} // namespace ddafem
