#pragma once
/// Symmetric linear solver with separate symbolic analysis, numeric factorization and solves,
/// and counters of each (printed in the run summary).
#include <memory>
#include <stdexcept>
#include <string>

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

 protected:
  SolverCounters counters_;
  int negative_pivots_ = 0;
  int first_negative_row_ = -1;
};

enum class LinearSolverKind { Auto, Cholmod, Dense };

/// Auto: CHOLMOD supernodal Cholesky (METIS ordering) for sparse systems, dense LDLᵀ for tiny
/// ones (n <= 64), where sparse bookkeeping costs more than it saves.
std::unique_ptr<LinearSolver> make_linear_solver(int n,
                                                 LinearSolverKind kind = LinearSolverKind::Auto);

/// Finds the equation with the smallest relative pivot of a symmetric matrix (diagnosis of a
/// singular model): returns the 0-based row with D_jj / A_jj smallest, via a simplicial LDLᵀ.
int weakest_pivot_row(const SparseMatrix& lower);

}  // namespace impactfe
