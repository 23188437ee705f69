#pragma once
/// The C interface of the MUMPS module (libimpactfe_mumps.so, linalg/mumps/mumps_module.cpp) as
/// linalg/parallel_backend.cpp loads it with dlopen: plain C symbols, looked up by name.
namespace impactfe {

class LinearSolver;

/// Options of the MUMPS solvers (plain data: it crosses the module boundary).
struct MumpsModuleOptions {
  bool out_of_core = false;      // ICNTL(22) = 1: factors written to disk
  char ooc_directory[256] = {};  // where (empty: MUMPS's default, $TMPDIR or /tmp)
};

}  // namespace impactfe

extern "C" {
/// MPI_Init (unless already initialised); 0 on success.
int impactfe_mumps_start(void);
int impactfe_mumps_rank(void);
int impactfe_mumps_size(void);
/// A new MUMPS solver; every rank creates its own and calls it in lockstep.
impactfe::LinearSolver* impactfe_mumps_create(const impactfe::MumpsModuleOptions* options);
/// The largest of `value` over all ranks (the ranks agree on the exit status).
int impactfe_mumps_max_int(int value);
void impactfe_mumps_abort(int code);
/// MPI_Finalize (after every solver is destroyed).
void impactfe_mumps_stop(void);
}
