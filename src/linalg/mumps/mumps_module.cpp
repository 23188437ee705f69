/// The distributed-memory sparse solver: MPI (Open MPI) and the MUMPS multifrontal solver behind
/// the LinearSolver interface (docs/scaling.md). Built as a shared module (libimpactfe_mumps.so)
/// that impactfe loads with dlopen only for `--solver mumps` (linalg/parallel_backend.h), so a
/// run with the default CHOLMOD neither maps the MPI and MUMPS libraries nor pays MPI_Init.
///
/// Every rank runs the same deck and calls the solver in lockstep (SPMD) with the same matrix;
/// each rank hands MUMPS only the entries of the matrix columns it owns (distributed assembled
/// input, ICNTL(18) = 3), with column ownership from a METIS k-way partition of the matrix
/// graph, so each entry comes from exactly one rank and no sum depends on message order. The
/// fill-reducing ordering is METIS nested dissection computed here (the ordering CHOLMOD uses)
/// and given to MUMPS as a user permutation (ICNTL(7) = 1): the Debian MUMPS is built without
/// METIS. Right-hand sides and solutions are centralised on rank 0; the solution is broadcast so
/// that every rank holds the same vectors.
#include <dmumps_c.h>
#include <metis.h>
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "linalg/linear_solver.h"
#include "linalg/mumps/mumps_module_api.h"

namespace impactfe {

namespace {

constexpr int kUseCommWorld = -987654;  // MUMPS: the Fortran handle of MPI_COMM_WORLD

/// The communicator of the exit agreement only (impactfe_mumps_agree), duplicated at start.
MPI_Comm exit_comm = MPI_COMM_NULL;
/// Set when this rank has failed (impactfe_mumps_set_failing): no more collective clean-up.
bool failing = false;

/// Test hook (docs/scaling.md, tests/mpi/fail_one_rank.py): IMPACTFE_TEST_FAIL_RANK=r makes
/// rank r alone fail at its first factorization, as a failure the other ranks cannot see
/// (a full disk, a lost file) would: they are inside the MUMPS factorization waiting for it.
/// A plain runtime_error, which no driver catches (a SingularMatrixError would be, and the
/// driver's diagnosis would call MUMPS again on this rank alone).
/// Honoured only here, in the MPI module, so a one-process run never looks at it.
void test_failure_hook(int rank) {
  const char* env = std::getenv("IMPACTFE_TEST_FAIL_RANK");
  if (env && *env && std::atoi(env) == rank) {
    failing = true;
    throw std::runtime_error("test failure on rank " + std::to_string(rank) +
                             " only (IMPACTFE_TEST_FAIL_RANK)");
  }
}

/// After this rank has failed, no more collective MUMPS calls: a driver that retries (a
/// bisection after a failed step) would call MUMPS on this rank alone, mismatching the
/// collective calls the other ranks are in.
void check_not_failing() {
  if (failing) throw std::runtime_error("MUMPS: this rank has failed, no further solver calls");
}

int world_rank() {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}
int world_size() {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// The full symmetric adjacency (no diagonal) of a lower-triangle pattern, in METIS CSR form.
struct Graph {
  std::vector<idx_t> xadj, adjncy;
};
Graph adjacency(const SparseMatrix& lower) {
  const int n = static_cast<int>(lower.rows());
  std::vector<idx_t> degree(static_cast<std::size_t>(n), 0);
  for (int j = 0; j < n; ++j)
    for (SparseMatrix::InnerIterator it(lower, j); it; ++it)
      if (it.row() != j) {
        ++degree[static_cast<std::size_t>(j)];
        ++degree[static_cast<std::size_t>(it.row())];
      }
  Graph g;
  g.xadj.assign(static_cast<std::size_t>(n) + 1, 0);
  for (int i = 0; i < n; ++i) g.xadj[i + 1] = g.xadj[i] + degree[static_cast<std::size_t>(i)];
  g.adjncy.resize(static_cast<std::size_t>(g.xadj[n]));
  std::vector<idx_t> next(g.xadj.begin(), g.xadj.end() - 1);
  for (int j = 0; j < n; ++j)
    for (SparseMatrix::InnerIterator it(lower, j); it; ++it)
      if (it.row() != j) {
        g.adjncy[static_cast<std::size_t>(next[j]++)] = static_cast<idx_t>(it.row());
        g.adjncy[static_cast<std::size_t>(next[it.row()]++)] = j;
      }
  return g;
}

/// Owner rank of each column: a METIS k-way partition of the matrix graph (fixed seed, so every
/// rank computes the same one), or all on rank 0 for one rank.
std::vector<int> partition_columns(const SparseMatrix& lower, Graph& g, int parts) {
  const int n = static_cast<int>(lower.rows());
  std::vector<int> owner(static_cast<std::size_t>(n), 0);
  if (parts <= 1 || n < parts) return owner;
  idx_t nvtx = n, ncon = 1, nparts = parts, cut = 0;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 7;
  options[METIS_OPTION_NUMBERING] = 0;
  std::vector<idx_t> part(static_cast<std::size_t>(n), 0);
  if (METIS_PartGraphKway(&nvtx, &ncon, g.xadj.data(), g.adjncy.data(), nullptr, nullptr, nullptr,
                          &nparts, nullptr, nullptr, options, &cut, part.data()) != METIS_OK)
    throw std::runtime_error("MUMPS backend: the METIS partition of the matrix graph failed");
  for (int i = 0; i < n; ++i) owner[static_cast<std::size_t>(i)] = static_cast<int>(part[i]);
  return owner;
}

/// METIS nested-dissection ordering as MUMPS's 1-based PERM_IN (PERM_IN(i) = position of i).
std::vector<int> nested_dissection(Graph& g, int n) {
  std::vector<int> position(static_cast<std::size_t>(n));
  if (g.adjncy.empty()) {
    for (int i = 0; i < n; ++i) position[static_cast<std::size_t>(i)] = i + 1;
    return position;
  }
  idx_t nvtx = n;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 7;
  options[METIS_OPTION_NUMBERING] = 0;
  std::vector<idx_t> perm(static_cast<std::size_t>(n)), iperm(static_cast<std::size_t>(n));
  if (METIS_NodeND(&nvtx, g.xadj.data(), g.adjncy.data(), nullptr, options, perm.data(),
                   iperm.data()) != METIS_OK)
    throw std::runtime_error("MUMPS backend: the METIS ordering failed");
  for (int i = 0; i < n; ++i)
    position[static_cast<std::size_t>(i)] = static_cast<int>(iperm[i]) + 1;
  return position;
}

/// Runs `f`; an exception it throws is described in *error (kind, row, message) and the call
/// returns -1, so that it never leaves the module (mumps_module_api.h).
template <class F>
int guarded(MumpsModuleError* error, F&& f) {
  *error = MumpsModuleError{};
  const auto fill = [&](int kind, int row, const char* what) {
    error->kind = kind;
    error->row = row;
    std::snprintf(error->message, sizeof(error->message), "%s", what);
    return -1;
  };
  try {
    f();
    return 0;
  } catch (const SingularMatrixError& e) {
    return fill(MumpsModuleError::kSingular, e.column(), e.what());
  } catch (const std::bad_alloc& e) {
    return fill(MumpsModuleError::kOutOfMemory, -1, e.what());
  } catch (const std::logic_error& e) {
    return fill(MumpsModuleError::kLogic, -1, e.what());
  } catch (const std::exception& e) {
    return fill(MumpsModuleError::kRuntime, -1, e.what());
  } catch (...) {
    return fill(MumpsModuleError::kRuntime, -1, "MUMPS module: an unknown exception");
  }
}

class MumpsSolver final : public LinearSolver {
 public:
  explicit MumpsSolver(const MumpsModuleOptions& options)
      : options_(options), rank_(world_rank()), size_(world_size()) {}
  ~MumpsSolver() override { terminate(); }
  MumpsSolver(const MumpsSolver&) = delete;
  MumpsSolver& operator=(const MumpsSolver&) = delete;

  std::string name() const override { return "MUMPS"; }
  /// The next release skips the collective JOB = -2 (see terminate).
  void release_locally() { release_locally_ = true; }

  void analyze_pattern(const SparseMatrix& lower) override {
    check_not_failing();
    const auto start = std::chrono::steady_clock::now();
    n_ = static_cast<int>(lower.rows());
    Graph g = adjacency(lower);
    owner_ = partition_columns(lower, g, size_);
    const std::vector<int>& owner = owner_;
    // This rank's entries (1-based) and their positions in the value array of `lower`.
    rows_.clear();
    cols_.clear();
    slots_.clear();
    for (int j = 0; j < n_; ++j) {
      if (owner[static_cast<std::size_t>(j)] != rank_) continue;
      for (int k = lower.outerIndexPtr()[j]; k < lower.outerIndexPtr()[j + 1]; ++k) {
        rows_.push_back(lower.innerIndexPtr()[k] + 1);
        cols_.push_back(j + 1);
        slots_.push_back(k);
      }
    }
    values_.assign(slots_.size(), 0.0);
    if (rank_ == 0) permutation_ = nested_dissection(g, n_);
    pattern_nonzeros_ = lower.nonZeros();
    analyze(positive_definite_ ? 1 : 2);
    ++counters_.analyses;
    counters_.analyze_seconds += seconds_since(start);
  }

  void factorize(const SparseMatrix& lower) override {
    check_not_failing();
    if (!initialized_ || lower.nonZeros() != pattern_nonzeros_) analyze_pattern(lower);
    test_failure_hook(rank_);
    const auto start = std::chrono::steady_clock::now();
    run_factorization(lower);
    // A matrix that is not positive definite (compressive stress stiffening, a shift above the
    // lowest eigenvalue) is factored again as general symmetric LDLᵀ with pivoting, as the
    // CHOLMOD backend falls back to LDLᵀ; the instance stays in that mode.
    if (positive_definite_ && (id_.infog[0] == -10 || id_.infog[11] > 0)) {
      positive_definite_ = false;
      analyze(2);
      run_factorization(lower);
    }
    ++counters_.factorizations;
    counters_.factorize_seconds += seconds_since(start);
    // refine()'s residuals are of the whole matrix; this rank may hold only its own columns
    // (distributed assembly: column_owners), so each column comes from its owner.
    if (size_ > 1 && options_.refine) factored_ = gather_columns(lower);
    if (id_.infog[0] == -10) throw SingularMatrixError(-1, "zero pivot in the factorization");
    check(id_.infog[0], "factorization");
    // Null pivots (ICNTL(24)): the first one's 0-based row, from rank 0 to every rank.
    int null_row = -1;
    if (rank_ == 0 && id_.infog[27] > 0) null_row = id_.pivnul_list[0] - 1;
    MPI_Bcast(&null_row, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (id_.infog[27] > 0) throw SingularMatrixError(null_row, "zero pivot in the factorization");
    negative_pivots_ = positive_definite_ ? 0 : id_.infog[11];
    first_negative_row_ = -1;  // MUMPS does not say which row (only the count)
    counters_.matrix_nonzeros = static_cast<long>(lower.nonZeros());
    // INFOG(29): entries in the factors (all ranks); 8 bytes each plus MUMPS's integer indices.
    counters_.factor_nonzeros =
        static_cast<long>(id_.infog[28] < 0 ? -id_.infog[28] * 1000000L : id_.infog[28]);
    counters_.factor_bytes = counters_.factor_nonzeros * static_cast<long>(sizeof(double));
  }

  std::vector<int> column_owners(const SparseMatrix& lower) const override {
    if (size_ <= 1) return {};
    Graph g = adjacency(lower);
    return partition_columns(lower, g, size_);
  }

  VectorXd solve(const VectorXd& b) override {
    MatrixXd B = b;
    return solve(B).col(0);
  }

  MatrixXd solve(const MatrixXd& B) override {
    if (!initialized_) throw std::logic_error("MUMPS: solve before factorize");
    check_not_failing();
    const auto start = std::chrono::steady_clock::now();
    // Centralised right-hand sides and solution (ICNTL(20) = ICNTL(21) = 0) on rank 0. Every
    // rank holds B (SPMD); rank 0's copy is the one MUMPS reads.
    MatrixXd X = mumps_solve(B);
    if (size_ > 1 && options_.refine) X = refine(B, X);
    counters_.solves += B.cols();
    counters_.solve_seconds += seconds_since(start);
    return X;
  }

 private:
  void terminate() {
    if (!initialized_) return;
    // JOB = -2 is collective. Unwinding an exception (here, or in impactfe: release_locally,
    // impactfe_mumps_destroy), or after this rank failed, the other
    // ranks may be elsewhere (a failure only this rank saw): release nothing rather than wait
    // for them (the process ends soon: abort or MPI_Finalize; ranks that fail together all
    // skip it alike). A solver dropped inside a catch handler (a fallback after a singular
    // matrix, which every rank takes) is released normally.
    if (failing || release_locally_ || std::uncaught_exceptions() > 0) {
      initialized_ = false;
      return;
    }
    id_.job = -2;
    dmumps_c(&id_);
    initialized_ = false;
  }

  void analyze(int sym) {
    terminate();
    std::memset(&id_, 0, sizeof(id_));
    id_.comm_fortran = kUseCommWorld;
    id_.par = 1;  // rank 0 works too
    id_.sym = sym;
    id_.job = -1;
    dmumps_c(&id_);
    check(id_.infog[0], "initialisation");
    initialized_ = true;
    // Silent (rank 0 reports errors through exceptions).
    id_.icntl[0] = -1;
    id_.icntl[1] = -1;
    id_.icntl[2] = -1;
    id_.icntl[3] = 0;
    id_.icntl[4] = 0;   // ICNTL(5): assembled matrix
    id_.icntl[6] = 1;   // ICNTL(7): user ordering (METIS nested dissection, PERM_IN)
    id_.icntl[17] = 3;  // ICNTL(18): distributed assembled input
    id_.icntl[23] = 1;  // ICNTL(24): null pivot detection (a mechanism is reported, not solved)
    id_.icntl[21] = options_.out_of_core ? 1 : 0;  // ICNTL(22): factors on disk
    if (options_.out_of_core && options_.ooc_directory[0] != '\0')
      std::snprintf(id_.ooc_tmpdir, sizeof(id_.ooc_tmpdir), "%s", options_.ooc_directory);
    id_.n = n_;
    id_.nnz_loc = static_cast<MUMPS_INT8>(rows_.size());
    id_.irn_loc = rows_.data();
    id_.jcn_loc = cols_.data();
    id_.perm_in = rank_ == 0 ? permutation_.data() : nullptr;
    id_.job = 1;
    dmumps_c(&id_);
    check(id_.infog[0], "analysis");
  }

  void run_factorization(const SparseMatrix& lower) {
    for (std::size_t k = 0; k < slots_.size(); ++k)
      values_[k] = lower.valuePtr()[static_cast<std::size_t>(slots_[k])];
    id_.a_loc = values_.data();
    id_.job = 2;
    dmumps_c(&id_);
  }

  /// One MUMPS solve of the columns of B; every rank gets the solution.
  MatrixXd mumps_solve(const MatrixXd& B) {
    MatrixXd X = B;
    id_.nrhs = static_cast<int>(B.cols());
    id_.lrhs = n_;
    id_.rhs = rank_ == 0 ? X.data() : nullptr;
    id_.job = 3;
    dmumps_c(&id_);
    check(id_.infog[0], "solve");
    MPI_Bcast(X.data(), static_cast<int>(X.size()), MPI_DOUBLE, 0, MPI_COMM_WORLD);
    return X;
  }

  /// `lower` with every column's values from the rank that owns it (values_ holds this rank's,
  /// in column order): the matrix every rank handed MUMPS a part of.
  SparseMatrix gather_columns(const SparseMatrix& lower) const {
    const int* start = lower.outerIndexPtr();
    std::vector<int> counts(static_cast<std::size_t>(size_), 0), first(counts);
    for (int j = 0; j < n_; ++j)
      counts[static_cast<std::size_t>(owner_[static_cast<std::size_t>(j)])] +=
          start[j + 1] - start[j];
    for (int r = 1; r < size_; ++r)
      first[static_cast<std::size_t>(r)] =
          first[static_cast<std::size_t>(r - 1)] + counts[static_cast<std::size_t>(r - 1)];
    std::vector<double> all(static_cast<std::size_t>(lower.nonZeros()));
    MPI_Allgatherv(values_.data(), static_cast<int>(values_.size()), MPI_DOUBLE, all.data(),
                   counts.data(), first.data(), MPI_DOUBLE, MPI_COMM_WORLD);
    SparseMatrix out = lower;
    for (int j = 0; j < n_; ++j) {
      int& next = first[static_cast<std::size_t>(owner_[static_cast<std::size_t>(j)])];
      for (int k = start[j]; k < start[j + 1]; ++k)
        out.valuePtr()[k] = all[static_cast<std::size_t>(next++)];
    }
    return out;
  }

  /// On several ranks MUMPS is not bitwise repeatable: the order in which contribution blocks
  /// from other ranks are summed, and the dynamic choice of the ranks that share a large front,
  /// change the round-off from run to run (at the 1e-17 level here). So the solution is refined
  /// to far below its last bit and then rounded onto a fixed grid, which removes that round-off:
  /// iterative refinement (Higham, Accuracy and Stability of Numerical Algorithms, §12.1) with
  /// the residual b − A x in double-double arithmetic (Dekker's two-sum and an fma
  /// two-product) and x kept as an unevaluated sum hi + lo. Each step divides the error by about
  /// 1/(κ ε) down to the double-double floor, about κ 1e-32 of the largest entry. Every entry is
  /// then rounded to a multiple of 2^-56 of its column's largest entry (1/16 of that entry's last
  /// bit, so large entries keep every bit; small ones lose what no direct solver resolves):
  /// the same grid point in every run unless an entry lies within the refinement's remainder of
  /// a midpoint.
  MatrixXd refine(const MatrixXd& B, MatrixXd X) {
    const int n = n_;
    const int m = static_cast<int>(B.cols());
    MatrixXd low = MatrixXd::Zero(n, m), residual(n, m);
    std::vector<double> rh(static_cast<std::size_t>(n)), rl(static_cast<std::size_t>(n));
    constexpr int kMaxSteps = 6;
    for (int step = 0; step < kMaxSteps; ++step) {
      for (int c = 0; c < m; ++c) {
        for (int i = 0; i < n; ++i) {
          rh[static_cast<std::size_t>(i)] = B(i, c);
          rl[static_cast<std::size_t>(i)] = 0.0;
        }
        for (int j = 0; j < n; ++j)
          for (SparseMatrix::InnerIterator it(factored_, j); it; ++it) {
            const int i = static_cast<int>(it.row());
            subtract_product(it.value(), X(j, c), low(j, c), rh[static_cast<std::size_t>(i)],
                             rl[static_cast<std::size_t>(i)]);
            if (i != j)
              subtract_product(it.value(), X(i, c), low(i, c), rh[static_cast<std::size_t>(j)],
                               rl[static_cast<std::size_t>(j)]);
          }
        for (int i = 0; i < n; ++i)
          residual(i, c) = rh[static_cast<std::size_t>(i)] + rl[static_cast<std::size_t>(i)];
      }
      const MatrixXd D = mumps_solve(residual);
      for (int c = 0; c < m; ++c)
        for (int i = 0; i < n; ++i) add_to(X(i, c), low(i, c), D(i, c));
      if (!(D.cwiseAbs().maxCoeff() > 0x1p-72 * X.cwiseAbs().maxCoeff())) break;
    }
    for (int c = 0; c < m; ++c) {
      const double largest = X.col(c).cwiseAbs().maxCoeff();
      if (!(largest > 0.0) || !std::isfinite(largest)) continue;
      const int quantum = std::ilogb(largest) - 56;  // the grid is 2^quantum
      for (int i = 0; i < n; ++i)
        X(i, c) = std::ldexp(
            std::nearbyint(std::ldexp(X(i, c), -quantum) + std::ldexp(low(i, c), -quantum)),
            quantum);
    }
    return X;
  }

  /// (sh, sl) −= a (xh + xl) in double-double arithmetic.
  static void subtract_product(double a, double xh, double xl, double& sh, double& sl) {
    const double p = -a * xh;
    const double pe = std::fma(-a, xh, -p);  // p + pe = −a xh exactly
    const double s = sh + p;
    const double bb = s - sh;
    const double se = (sh - (s - bb)) + (p - bb);  // s + se = sh + p exactly
    const double t = se + sl + pe - a * xl;
    sh = s + t;
    sl = t - (sh - s);
  }

  /// (xh, xl) += d, renormalised so that xh is the double nearest to the sum.
  static void add_to(double& xh, double& xl, double d) {
    const double s = xh + d;
    const double bb = s - xh;
    const double e = (xh - (s - bb)) + (d - bb) + xl;
    xh = s + e;
    xl = e - (xh - s);
  }

  /// INFOG(1) is the same on every rank, so every rank throws the same error together.
  static void check(int infog1, const char* phase) {
    if (infog1 >= 0) return;
    if (infog1 == -9 || infog1 == -13)
      throw std::runtime_error(std::string("MUMPS ") + phase +
                               ": out of memory (INFOG(1) = " + std::to_string(infog1) +
                               "); run on more ranks or with --mumps-ooc (factors on disk)");
    throw std::runtime_error(std::string("MUMPS ") + phase +
                             " failed (INFOG(1) = " + std::to_string(infog1) + ")");
  }

  MumpsModuleOptions options_;
  int rank_ = 0;
  int size_ = 1;
  DMUMPS_STRUC_C id_{};
  bool initialized_ = false;
  bool release_locally_ = false;  // release_locally
  bool positive_definite_ = true;
  int n_ = 0;
  long pattern_nonzeros_ = -1;
  std::vector<int> rows_, cols_, slots_, permutation_;
  std::vector<int> owner_;  // owner rank of each column (analyze_pattern)
  std::vector<double> values_;
  SparseMatrix factored_;  // the matrix last factored (on several ranks, for refine())
};

}  // namespace

}  // namespace impactfe

extern "C" {

int impactfe_mumps_start(void) {
  int started = 0;
  MPI_Initialized(&started);
  if (!started && MPI_Init(nullptr, nullptr) != MPI_SUCCESS) return -1;
  if (impactfe::exit_comm == MPI_COMM_NULL &&
      MPI_Comm_dup(MPI_COMM_WORLD, &impactfe::exit_comm) != MPI_SUCCESS)
    return -1;
  return 0;
}

int impactfe_mumps_broadcast(void* data, long long bytes, int root) {
  // In pieces of at most 1 GiB: MPI counts are int.
  constexpr long long kPiece = 1LL << 30;
  auto* p = static_cast<char*>(data);
  for (long long done = 0; done < bytes; done += kPiece) {
    const int count = static_cast<int>(std::min(kPiece, bytes - done));
    if (MPI_Bcast(p + done, count, MPI_BYTE, root, MPI_COMM_WORLD) != MPI_SUCCESS) return -1;
  }
  return 0;
}

int impactfe_mumps_agree(int status, double wait_seconds, int* agreed) {
  // Static buffers: a request abandoned after the time-out must not point into a dead frame.
  static int send = 0, receive = 0;
  static MPI_Request request;
  send = status;
  receive = status;
  MPI_Iallreduce(&send, &receive, 1, MPI_INT, MPI_MAX, impactfe::exit_comm, &request);
  if (status == 0) {
    MPI_Wait(&request, MPI_STATUS_IGNORE);
    *agreed = receive;
    return 0;
  }
  const auto start = std::chrono::steady_clock::now();
  for (;;) {
    int done = 0;
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) {
      *agreed = receive;
      return 0;
    }
    if (impactfe::seconds_since(start) > wait_seconds) return 1;  // the request is abandoned
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

void impactfe_mumps_set_failing(void) {
  impactfe::failing = true;
}

int impactfe_mumps_rank(void) {
  return impactfe::world_rank();
}
int impactfe_mumps_size(void) {
  return impactfe::world_size();
}

void* impactfe_mumps_create(const impactfe::MumpsModuleOptions* options,
                            impactfe::MumpsModuleError* error) {
  impactfe::MumpsSolver* solver = nullptr;
  impactfe::guarded(error, [&] { solver = new impactfe::MumpsSolver(*options); });
  return solver;
}

void impactfe_mumps_destroy(void* solver, int unwinding) {
  auto* s = static_cast<impactfe::MumpsSolver*>(solver);
  if (s == nullptr) return;
  if (unwinding) s->release_locally();
  delete s;
}

int impactfe_mumps_analyze(void* solver, const impactfe::SparseMatrix* lower,
                           impactfe::MumpsModuleError* error) {
  return impactfe::guarded(
      error, [&] { static_cast<impactfe::MumpsSolver*>(solver)->analyze_pattern(*lower); });
}

int impactfe_mumps_factorize(void* solver, const impactfe::SparseMatrix* lower,
                             impactfe::MumpsModuleError* error) {
  return impactfe::guarded(error,
                           [&] { static_cast<impactfe::MumpsSolver*>(solver)->factorize(*lower); });
}

int impactfe_mumps_solve(void* solver, const double* b, double* x, long long rows,
                         long long columns, impactfe::MumpsModuleError* error) {
  return impactfe::guarded(error, [&] {
    const Eigen::Map<const impactfe::MatrixXd> B(b, rows, columns);
    Eigen::Map<impactfe::MatrixXd>(x, rows, columns) =
        static_cast<impactfe::MumpsSolver*>(solver)->solve(impactfe::MatrixXd(B));
  });
}

int impactfe_mumps_column_owners(void* solver, const impactfe::SparseMatrix* lower, int* owners,
                                 impactfe::MumpsModuleError* error) {
  int found = 0;
  const int status = impactfe::guarded(error, [&] {
    const std::vector<int> o = static_cast<impactfe::MumpsSolver*>(solver)->column_owners(*lower);
    if (o.empty()) return;
    if (static_cast<long long>(o.size()) != static_cast<long long>(lower->cols()))
      throw std::logic_error("MUMPS: an owner for every column expected");
    std::copy(o.begin(), o.end(), owners);
    found = 1;
  });
  return status != 0 ? -1 : found;
}

void impactfe_mumps_counters(const void* solver, impactfe::SolverCounters* counters,
                             int* negative_pivots, int* first_negative_row) {
  const auto* s = static_cast<const impactfe::MumpsSolver*>(solver);
  *counters = s->counters();
  *negative_pivots = s->negative_pivots();
  *first_negative_row = s->first_negative_pivot_row();
}

int impactfe_mumps_share_owned(double* values, int n, const int* owner) {
  const int size = impactfe::world_size(), rank = impactfe::world_rank();
  std::vector<int> counts(static_cast<std::size_t>(size), 0), first(counts);
  for (int i = 0; i < n; ++i) ++counts[static_cast<std::size_t>(owner[i])];
  for (int r = 1; r < size; ++r)
    first[static_cast<std::size_t>(r)] =
        first[static_cast<std::size_t>(r - 1)] + counts[static_cast<std::size_t>(r - 1)];
  std::vector<double> mine, all(static_cast<std::size_t>(n));
  mine.reserve(static_cast<std::size_t>(counts[static_cast<std::size_t>(rank)]));
  for (int i = 0; i < n; ++i)
    if (owner[i] == rank) mine.push_back(values[i]);
  if (MPI_Allgatherv(mine.data(), static_cast<int>(mine.size()), MPI_DOUBLE, all.data(),
                     counts.data(), first.data(), MPI_DOUBLE, MPI_COMM_WORLD) != MPI_SUCCESS)
    return -1;
  for (int i = 0; i < n; ++i)
    values[i] = all[static_cast<std::size_t>(first[static_cast<std::size_t>(owner[i])]++)];
  return 0;
}

int impactfe_mumps_all_doubles(double value, double* out) {
  return MPI_Allgather(&value, 1, MPI_DOUBLE, out, 1, MPI_DOUBLE, MPI_COMM_WORLD) == MPI_SUCCESS
             ? 0
             : -1;
}

int impactfe_mumps_max_int(int value) {
  int out = value;
  MPI_Allreduce(&value, &out, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return out;
}

void impactfe_mumps_abort(int code) {
  MPI_Abort(MPI_COMM_WORLD, code);
}

void impactfe_mumps_stop(void) {
  int finished = 0;
  MPI_Finalized(&finished);
  if (finished) return;
  if (impactfe::exit_comm != MPI_COMM_NULL) MPI_Comm_free(&impactfe::exit_comm);
  MPI_Finalize();
}

}  // extern "C"
