#pragma once
/// Static condensation of a sparse symmetric positive definite matrix onto a set c of its
/// unknowns: the Schur complement and solves split at c (used by the condensed transient,
/// analysis/linear_part_condensation.h, thesis eqs. 4-16..4-20).
///
/// With the unknowns split into the rest i and c,
///   S = A_cc − A_ci A_ii⁻¹ A_ic = ((A⁻¹)_cc)⁻¹,
/// `condense(r)` returns y = (A⁻¹ r)_c, and `recover(x_c)` returns the x that takes the given
/// values x_c on c and satisfies the i rows of A x = r for the r of the last `condense`:
///   x_i = A_ii⁻¹ (r_i − A_ic x_c).
/// recover(condense(r)) is A⁻¹ r. A condensed step (linear part A, nonlinear forces on c) is
/// one `condense`, a small dense problem in S, and one `recover`.
#include <memory>
#include <vector>

#include "linalg/linear_solver.h"

namespace impactfe {

class SchurSolver {
 public:
  virtual ~SchurSolver() = default;
  /// Symbolic analysis of a lower-triangle pattern (n × n, n > size of c).
  virtual void analyze_pattern(const SparseMatrix& lower) = 0;
  /// Numeric factorization and S. Throws SingularMatrixError (the 0-based row) when A is not
  /// positive definite.
  virtual void factorize(const SparseMatrix& lower) = 0;
  /// The same for a matrix the caller no longer needs: the solver may free it (it is empty
  /// afterwards) as soon as it holds its own copy, before the factor's values are allocated,
  /// so that the two are never in memory together with the factor (issue 11).
  virtual void factorize_and_release(SparseMatrix& lower) {
    factorize(lower);
    SparseMatrix().swap(lower);  // Eigen's assignment of an empty matrix keeps the storage
  }
  /// y = (A⁻¹ r)_c, in the order of c; remembers what `recover` needs of r.
  virtual VectorXd condense(const Eigen::Ref<const VectorXd>& r) = 0;
  /// x (resized to n) with x_c on c and the i rows of A x = r satisfied (r of the last
  /// `condense`). Into the caller's vector: a condensed step allocates no vector of model size
  /// (issue 11; on large models each such allocation is a fresh mapping, faulted in page by
  /// page).
  virtual void recover(const VectorXd& x_c, VectorXd& x) = 0;
  VectorXd recover(const VectorXd& x_c) {
    VectorXd x;
    recover(x_c, x);
    return x;
  }
  virtual std::string name() const = 0;

  /// The Schur complement S (m × m, rows and columns in the order of c), symmetric.
  const MatrixXd& schur() const { return schur_; }
  const std::vector<int>& condensed() const { return c_; }
  const SolverCounters& counters() const { return counters_; }

 protected:
  explicit SchurSolver(std::vector<int> c) : c_(std::move(c)) {}
  std::vector<int> c_;
  MatrixXd schur_;
  SolverCounters counters_;
};

enum class SchurSolverKind {
  /// Factorization when the run's sparse solver is CHOLMOD, Transfer when it was replaced (MUMPS
  /// on several ranks).
  Auto,
  /// CHOLMOD supernodal LLᵀ with c ordered last: the trailing block L_cc of L gives
  /// S = L_cc L_ccᵀ, a forward substitution gives y, a back substitution with x_c put in gives
  /// x. Memory: the factor and S; a step: one solve.
  Factorization,
  /// Any LinearSolver: G = A⁻¹ E from one solve with m right-hand sides, S = (Eᵀ G)⁻¹, and
  /// x = A⁻¹ r − G S (y − x_c). Memory: the factor, G (n × m) and S.
  Transfer,
};

/// A solver of n × n matrices condensed onto the rows c (ascending, distinct, 0 < m < n).
std::unique_ptr<SchurSolver> make_schur_solver(int n, std::vector<int> c,
                                               SchurSolverKind kind = SchurSolverKind::Auto);

}  // namespace impactfe
