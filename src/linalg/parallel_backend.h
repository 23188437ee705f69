#pragma once
/// The distributed-memory backend (`--solver mumps`, docs/scaling.md): MPI and the MUMPS solver
/// live in a shared module (libimpactfe_mumps.so) loaded with dlopen only when asked, so a
/// default run neither maps the MPI libraries nor pays MPI_Init. Once started, every sparse
/// system of make_linear_solver (LinearSolverKind::Auto above the dense size) is solved by MUMPS,
/// collectively by all ranks in lockstep.
#include <string>

namespace impactfe {

struct ParallelSettings {
  bool out_of_core = false;   // MUMPS ICNTL(22): factors on disk (--mumps-ooc)
  std::string ooc_directory;  // where (empty: MUMPS's default)
};

/// Loads the module, calls MPI_Init and makes MUMPS the sparse solver. Throws std::runtime_error
/// with what is missing when the module or the MPI/MUMPS libraries cannot be loaded.
void start_parallel_backend(const ParallelSettings& settings);
/// True between start_parallel_backend and stop_parallel_backend.
bool parallel_backend_active();
/// This process's rank and the number of ranks (0 and 1 without the backend).
int process_rank();
int process_count();
/// The largest `value` over all ranks (identity without the backend).
int max_over_ranks(int value);
/// MPI_Abort: ends every rank (a failure on one rank that the others cannot see).
[[noreturn]] void abort_all_ranks(int code);
/// MPI_Finalize; every solver must be destroyed before.
void stop_parallel_backend();

}  // namespace impactfe
