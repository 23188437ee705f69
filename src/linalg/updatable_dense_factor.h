#pragma once
/// The factorization of a dense symmetric matrix that changes in a few rows and columns at a
/// time: the condensed transient's Newton tangent S + K_N (linear_part_condensation.h), where a
/// gap that opens or closes changes K_N on the DOFs it touches only.
///
/// When the new matrix differs from the one last factored in a set J of rows (and columns), the
/// difference D = A − A_prev is the small symmetric block D_JJ: with its eigenpairs (λ_k, q_k)
/// the Cholesky factor takes the rank-one updates (v_k = E_J q_k √|λ_k|, sign λ_k) instead of a
/// new factorization (Golub & Van Loan, "Matrix Computations", §6.5.4): |J| m² operations
/// against m³/3 (m = 1089 gap DOFs: 3.9·10⁸ flops per status change before). Updates first,
/// downdates last; a downdate that would lose positive definiteness, a change in more than
/// m/8 rows, or kMaxUpdates updates since the last factorization (round-off) factor anew.
/// Matrices that are not positive definite take Eigen's LDLᵀ each time.
#include <Eigen/Cholesky>

#include "linalg/sparse.h"

namespace impactfe {

class UpdatableDenseFactor {
 public:
  static constexpr int kMaxUpdates = 64;

  /// Factors A (symmetric, full storage), from the previous factor when that pays.
  void factorize(const MatrixXd& A);
  VectorXd solve(const VectorXd& b) const;
  /// Forgets the previous matrix (the next factorize starts afresh).
  void reset();

  long full_factorizations() const { return full_; }
  long rank_one_updates() const { return rank_one_; }

 private:
  void factorize_fully(const MatrixXd& A);
  bool update(const MatrixXd& A);

  MatrixXd last_;  // the matrix the factor belongs to
  Eigen::LLT<MatrixXd> llt_;
  Eigen::LDLT<MatrixXd> ldlt_;
  bool positive_definite_ = false;
  bool valid_ = false;
  int updates_since_full_ = 0;
  long full_ = 0, rank_one_ = 0;
};

}  // namespace impactfe
