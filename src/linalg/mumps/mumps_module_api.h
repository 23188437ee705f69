#pragma once
/// The C interface of the MUMPS module (libimpactfe_mumps.so, linalg/mumps/mumps_module.cpp) as
/// linalg/parallel_backend.cpp loads it with dlopen: plain C symbols, looked up by name. No C++
/// exception crosses it: the module is linked to the shared libstdc++ (through MUMPS and Open
/// MPI), impactfe to its own copy from the static archive (start-up, issue 11), and an
/// exception thrown by one copy cannot be caught by the other. A call that fails returns
/// nonzero and describes the exception in a MumpsModuleError, which impactfe throws again.
#include "linalg/sparse.h"

namespace impactfe {

struct SolverCounters;

/// Options of the MUMPS solvers (plain data: it crosses the module boundary).
struct MumpsModuleOptions {
  bool out_of_core = false;      // ICNTL(22) = 1: factors written to disk
  char ooc_directory[256] = {};  // where (empty: MUMPS's default, $TMPDIR or /tmp)
  bool refine = true;            // on several ranks: double-double refinement (bitwise repeatable)
};

/// What a failed call threw (plain data: it crosses the module boundary).
struct MumpsModuleError {
  enum Kind : int { kNone = 0, kSingular, kRuntime, kLogic, kOutOfMemory };
  int kind = kNone;
  int row = -1;  // kSingular: SingularMatrixError::column()
  char message[1024] = {};
};

}  // namespace impactfe

extern "C" {
/// MPI_Init (unless already initialised); 0 on success.
int impactfe_mumps_start(void);
int impactfe_mumps_rank(void);
int impactfe_mumps_size(void);
/// A new MUMPS solver (opaque); every rank creates its own and calls it in lockstep. Null when
/// it could not be made (*error says why).
void* impactfe_mumps_create(const impactfe::MumpsModuleOptions* options,
                            impactfe::MumpsModuleError* error);
/// Releases a solver; `unwinding`: the caller is unwinding an exception, so the other ranks may
/// not take part in a collective release (the module cannot see the caller's exceptions).
void impactfe_mumps_destroy(void* solver, int unwinding);
/// LinearSolver::analyze_pattern, factorize and solve (of `columns` right-hand sides of
/// `rows` values each, column-major, into x); 0 on success.
int impactfe_mumps_analyze(void* solver, const impactfe::SparseMatrix* lower,
                           impactfe::MumpsModuleError* error);
int impactfe_mumps_factorize(void* solver, const impactfe::SparseMatrix* lower,
                             impactfe::MumpsModuleError* error);
int impactfe_mumps_solve(void* solver, const double* b, double* x, long long rows,
                         long long columns, impactfe::MumpsModuleError* error);
/// LinearSolver::column_owners into owners[0 .. lower->cols()): 1 when it has them, 0 when every
/// column is read on this process, -1 on failure.
int impactfe_mumps_column_owners(void* solver, const impactfe::SparseMatrix* lower, int* owners,
                                 impactfe::MumpsModuleError* error);
/// The solver's counters and the negative pivots of its last factorization.
void impactfe_mumps_counters(const void* solver, impactfe::SolverCounters* counters,
                             int* negative_pivots, int* first_negative_row);
/// values[i] from rank owner[i] on every rank (collective; n and owner the same on all ranks):
/// each rank sends the entries it owns (MPI_Allgatherv), no arithmetic. 0 on success.
int impactfe_mumps_share_owned(double* values, int n, const int* owner);
/// Every rank's `value`, in rank order, into out[0 .. size) (collective). 0 on success.
int impactfe_mumps_all_doubles(double value, double* out);
/// The largest of `value` over all ranks (the ranks agree on the exit status).
int impactfe_mumps_max_int(int value);
void impactfe_mumps_abort(int code);
/// Broadcasts `bytes` bytes at `data` from rank `root` to every rank (collective); 0 on success.
int impactfe_mumps_broadcast(void* data, long long bytes, int root);
/// The exit agreement (its own communicator, so it never matches another collective): the
/// largest status over all ranks in *agreed and 0 once every rank has arrived. A rank with
/// status 0 waits as long as it takes; a failing rank waits at most `wait_seconds` and returns 1
/// when some rank has not arrived (it is elsewhere, e.g. inside a MUMPS call waiting for this
/// one): the caller then aborts all ranks.
int impactfe_mumps_agree(int status, double wait_seconds, int* agreed);
/// This rank has failed: MUMPS instances destroyed from now on are released without the
/// collective JOB = -2 (the other ranks may not be there to take part).
void impactfe_mumps_set_failing(void);
/// MPI_Finalize (after every solver is destroyed).
void impactfe_mumps_stop(void);
}
