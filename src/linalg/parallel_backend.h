#pragma once
/// The distributed-memory backend (`--solver mumps`, docs/scaling.md): MPI and the MUMPS solver
/// live in a shared module (libimpactfe_mumps.so) loaded with dlopen only when asked, so a
/// default run neither maps the MPI libraries nor pays MPI_Init. Once started, every sparse
/// system of make_linear_solver (LinearSolverKind::Auto above the dense size) is solved by MUMPS,
/// collectively by all ranks in lockstep.
#include <optional>
#include <string>
#include <vector>

namespace impactfe {

struct ParallelSettings {
  bool out_of_core = false;   // MUMPS ICNTL(22): factors on disk (--mumps-ooc)
  std::string ooc_directory;  // where (empty: MUMPS's default)
  bool refine = true;         // on several ranks, refine every solve (--mumps-no-refine: off)
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
/// values[i] := rank owner[i]'s values[i] on every rank (collective; the same n and owner on
/// every rank). A copy, no arithmetic: the result does not depend on the rank count beyond what
/// each owner computed (distributed assembly, docs/scaling.md). No-op without the backend.
void share_owned_values(double* values, int n, const std::vector<int>& owner);
/// Every rank's `value` in rank order (collective; {value} without the backend).
std::vector<double> values_of_all_ranks(double value);
/// MPI_Abort: ends every rank (a failure on one rank that the others cannot see).
[[noreturn]] void abort_all_ranks(int code);
/// The exit status every rank agrees on (the largest), once all ranks have finished the run.
/// A rank with a non-zero `status` waits for the others at most `wait_seconds` and then returns
/// nullopt: some rank did not finish (it is waiting inside a collective call for this one), so
/// the caller must abort_all_ranks. Identity without the backend.
std::optional<int> agree_exit_status(int status, double wait_seconds);
/// This rank has failed: solvers destroyed from now on skip collective clean-up.
void note_local_failure();
/// Rank 0's `data` on every rank (collective; no-op without the backend or on one rank).
void broadcast_from_rank0(std::string& data);
/// Rank `root`'s `data` on every rank (collective; no-op without the backend or on one rank).
void broadcast_from_rank(std::string& data, int root);
/// Deck-level file reads (core/files.h) answered by rank 0's disk on every rank: rank 0 looks
/// the file up and broadcasts what it found, so the other ranks need not see the files (a deck
/// on a disk only rank 0 sees). Collective: every rank asks the same questions in the same
/// order, as SPMD guarantees. `on` false goes back to each rank's own disk.
void share_rank0_files(bool on);
/// Work this rank does alone while the others do something else (a superelement generation
/// owned by this rank, docs/scaling.md): for its lifetime the sparse solver is CHOLMOD on this
/// process and file lookups go to this process's disk, so nothing in it is collective.
/// `alone` false: nothing changes (one rank runs everything collectively anyway).
class RankLocalWork {
 public:
  explicit RankLocalWork(bool alone = true);
  ~RankLocalWork();
  RankLocalWork(const RankLocalWork&) = delete;
  RankLocalWork& operator=(const RankLocalWork&) = delete;

 private:
  bool active_;
  bool files_shared_;
};

/// MPI_Finalize; every solver must be destroyed before.
void stop_parallel_backend();

}  // namespace impactfe
