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
