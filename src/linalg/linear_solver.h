#pragma once
/// Symmetric linear solver with separate symbolic analysis, numeric factorization and solves,
/// and counters of each (printed in the run summary).
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "linalg/sparse.h"

namespace impactfe {

/// Thrown when a factorization meets a zero or negative pivot. `column` is the 0-based row of
/// the (unpermuted) matrix where it happened, so the caller can name the node and DOF.
class SingularMatrixError : public std::runtime_error {
 public:
  SingularMatrixError(int column, const std::string& what)
      : std::runtime_error(what), column_(column) {}
  int column() const { return column_; }

 private:
  int column_;
};

struct SolverCounters {
  long analyses = 0;
  long factorizations = 0;
  long solves = 0;  // right-hand sides solved
  // Wall time spent in each phase (benchmark figures; the run summary prints them).
  double analyze_seconds = 0.0;
  double factorize_seconds = 0.0;
  double solve_seconds = 0.0;
  // Sizes of the last factorization: nonzeros of the factored matrix (lower triangle), of the
  // factor L (structural count, diagonal included), and the bytes of L a solve reads (stored
  // values and row indices, supernodal padding included). A solve streams L twice (forward and
  // backward substitution), so 2 * factor_bytes / memory bandwidth is its time floor.
  long matrix_nonzeros = 0;
  long factor_nonzeros = 0;
  long factor_bytes = 0;

  /// Adds counts and times; keeps the largest sizes (the counters of several DOF numberings).
  SolverCounters& operator+=(const SolverCounters& other);
};

class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  /// Symbolic analysis (fill-reducing ordering) of a lower-triangle symmetric pattern.
  virtual void analyze_pattern(const SparseMatrix& lower) = 0;
  /// Numeric factorization; the pattern must match the analyzed one. Throws SingularMatrixError.
  virtual void factorize(const SparseMatrix& lower) = 0;
  virtual VectorXd solve(const VectorXd& b) = 0;
  virtual MatrixXd solve(const MatrixXd& B) = 0;
  virtual std::string name() const = 0;
  const SolverCounters& counters() const { return counters_; }
  /// Negative pivots of the last factorization (an indefinite matrix factored as LDLᵀ) and the
  /// 0-based row of the (unpermuted) matrix where the first one is (-1 when none).
  int negative_pivots() const { return negative_pivots_; }
  int first_negative_pivot_row() const { return first_negative_row_; }
  /// Distributed input (MUMPS on N > 1 ranks, docs/scaling.md): the rank whose entries of each
  /// column of `lower`'s pattern this process's solver hands on. A caller may then fill on each
  /// rank only the columns that rank owns (the values elsewhere are never read). Empty: every
  /// column is read on this process (every other solver, and MUMPS on one rank).
  virtual std::vector<int> column_owners(const SparseMatrix& /*lower*/) const { return {}; }

 protected:
  SolverCounters counters_;
  int negative_pivots_ = 0;
  int first_negative_row_ = -1;
};

enum class LinearSolverKind { Auto, Cholmod, Dense };

/// Auto: CHOLMOD supernodal Cholesky (METIS ordering) for sparse systems, dense LDLᵀ for tiny
/// ones (n <= 64), where sparse bookkeeping costs more than it saves. With a sparse solver
/// factory set (the MUMPS backend, linalg/parallel_backend.h), Auto's sparse systems go to it.
std::unique_ptr<LinearSolver> make_linear_solver(int n,
                                                 LinearSolverKind kind = LinearSolverKind::Auto);

/// Replaces CHOLMOD for LinearSolverKind::Auto's sparse systems process-wide (nullptr restores
/// CHOLMOD). Every process of a distributed run sets the same factory.
using SparseSolverFactory = std::unique_ptr<LinearSolver> (*)();
void set_sparse_solver_factory(SparseSolverFactory factory);
/// Whether a sparse solver factory is set (a distributed run's MUMPS).
bool sparse_solver_replaced();

/// Finds the equation with the smallest relative pivot of a symmetric matrix (diagnosis of a
/// singular model): returns the 0-based row with D_jj / A_jj smallest, via a simplicial LDLᵀ.
int weakest_pivot_row(const SparseMatrix& lower);

}  // namespace impactfe
