#pragma once
/// Helpers shared by the sparse solver back ends of src/linalg (CHOLMOD's LinearSolver and
/// SchurSolver): phase timers, the BLAS thread cap of a solver phase, the pivot thresholds and
/// CHOLMOD views of Eigen matrices.
#include <cholmod.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <stdexcept>

#include "core/errors.h"
#include "linalg/blas_library.h"
#include "linalg/sparse.h"
#include "linalg/supernodal_substitution.h"

namespace impactfe::solver_support {

/// Relative pivot below which a symmetric positive (semi)definite matrix is treated as singular.
constexpr double kSingularPivot = 1e-11;

/// Floating-point operations of a factorization above which its BLAS kernels (dsyrk, dgemm,
/// dpotrf on the supernodes) may run on several threads. Below it a factorization takes
/// milliseconds and every threaded kernel call pays a team wake-up that a busy machine turns
/// into a wait for a core.
constexpr double kParallelFactorFlops = 2.0e8;
constexpr int kAllThreads = std::numeric_limits<int>::max();

/// Adds the wall time of its scope to `total` (solver phase timers of SolverCounters).
class ScopedTimer {
 public:
  explicit ScopedTimer(double& total) : total_(total), start_(std::chrono::steady_clock::now()) {}
  ~ScopedTimer() {
    total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

 private:
  double& total_;
  std::chrono::steady_clock::time_point start_;
};

/// Caps the BLAS threads (blas_library.h) for one scope: how a solver phase chooses them.
class ScopedThreadLimit {
 public:
  explicit ScopedThreadLimit(int limit) : saved_(blas::threads()) {
    blas::set_threads(std::max(1, std::min(limit, saved_)));
  }
  ~ScopedThreadLimit() { blas::set_threads(saved_); }
  ScopedThreadLimit(const ScopedThreadLimit&) = delete;
  ScopedThreadLimit& operator=(const ScopedThreadLimit&) = delete;

 private:
  int saved_ = 1;
};

/// Loads BLAS and LAPACK before a supernodal CHOLMOD factor is computed or used (its kernels
/// call them; a simplicial factor needs neither). A missing library is a solution failure
/// naming it (exit status 2), not a crash inside CHOLMOD.
inline void require_blas_for(const cholmod_factor* factor) {
  if (factor == nullptr || !factor->is_super) return;
  try {
    blas::require();
  } catch (const std::runtime_error& e) {
    throw SolutionError(e.what());
  }
}

/// A CHOLMOD view (no copy) of a symmetric matrix stored as its lower triangle in compressed
/// columns; without values (x == nullptr) the pattern only.
inline cholmod_sparse cholmod_lower_view(std::size_t n, std::size_t nonzeros,
                                         const int* column_start, const int* row_index,
                                         const double* x) {
  cholmod_sparse a{};
  a.nrow = a.ncol = n;
  a.nzmax = nonzeros;
  a.p = const_cast<int*>(column_start);
  a.i = const_cast<int*>(row_index);
  a.x = const_cast<double*>(x);
  a.stype = -1;  // lower triangle stored
  a.itype = CHOLMOD_INT;
  a.xtype = x != nullptr ? CHOLMOD_REAL : CHOLMOD_PATTERN;
  a.dtype = CHOLMOD_DOUBLE;
  a.sorted = 1;
  a.packed = 1;
  return a;
}

inline cholmod_sparse cholmod_lower_view(const SparseMatrix& lower) {
  return cholmod_lower_view(static_cast<std::size_t>(lower.rows()),
                            static_cast<std::size_t>(lower.nonZeros()), lower.outerIndexPtr(),
                            lower.innerIndexPtr(), lower.valuePtr());
}

/// The substitution layout of a supernodal CHOLMOD factor (LLᵀ; its arrays, no copy).
inline SupernodalLayout supernodal_layout(const cholmod_factor* factor) {
  SupernodalLayout layout;
  layout.n_super = static_cast<int>(factor->nsuper);
  layout.super = static_cast<const int*>(factor->super);
  layout.row_start = static_cast<const int*>(factor->pi);
  layout.value_start = static_cast<const int*>(factor->px);
  layout.rows = static_cast<const int*>(factor->s);
  layout.values = static_cast<const double*>(factor->x);
  return layout;
}

}  // namespace impactfe::solver_support
