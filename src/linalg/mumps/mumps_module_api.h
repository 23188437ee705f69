#pragma once
/// The C interface of the MUMPS module (libimpactfe_mumps.so, linalg/mumps/mumps_module.cpp) as
/// linalg/parallel_backend.cpp loads it with dlopen: plain C symbols, looked up by name.
namespace impactfe {

class LinearSolver;

/// Options of the MUMPS solvers (plain data: it crosses the module boundary).
struct MumpsModuleOptions {
  bool out_of_core = false;      // ICNTL(22) = 1: factors written to disk
  char ooc_directory[256] = {};  // where (empty: MUMPS's default, $TMPDIR or /tmp)
  bool refine = true;            // on several ranks: double-double refinement (bitwise repeatable)
};

}  // namespace impactfe

extern "C" {
/// MPI_Init (unless already initialised); 0 on success.
int impactfe_mumps_start(void);
int impactfe_mumps_rank(void);
int impactfe_mumps_size(void);
/// A new MUMPS solver; every rank creates its own and calls it in lockstep.
impactfe::LinearSolver* impactfe_mumps_create(const impactfe::MumpsModuleOptions* options);
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
