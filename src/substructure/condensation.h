#pragma once
/// Static (Guyan) condensation of full-model matrices to master DOFs for the superelement
/// generation pass (spec §10.4 step 2, §10.6; thesis eq. 4-21 corrected).
///
/// u = T u_m with T = [I; T_sm], T_sm = −K_ss⁻¹ K_sm computed by one factorization of K_ss and a
/// multi-right-hand-side solve (never an explicit inverse). Reduced matrices are TᵀKT, TᵀMT, TᵀCT
/// and a reduced load is Tᵀf.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "linalg/linear_solver.h"
#include "linalg/sparse.h"

namespace impactfe {

class StaticCondensation {
 public:
  /// `K`: stiffness in full symmetric storage over some DOF numbering; `masters`, `slaves`:
  /// disjoint index lists into that numbering (the remaining indices, e.g. constrained DOFs,
  /// are dropped). `describe` names an index in error messages. Throws ModelError when K_ss is
  /// singular (slaves not restrained by the masters and constraints).
  StaticCondensation(const SparseMatrix& K, std::vector<int> masters, std::vector<int> slaves,
                     const std::function<std::string(int)>& describe);

  int n_masters() const { return static_cast<int>(masters_.size()); }
  int n_slaves() const { return static_cast<int>(slaves_.size()); }
  /// T_sm = −K_ss⁻¹ K_sm (n_slaves x n_masters): slave displacements per unit master motion.
  const MatrixXd& transformation() const { return t_sm_; }
  /// Tᵀ A T for a symmetric matrix A (full storage, same numbering as K); symmetrised.
  MatrixXd reduce_matrix(const SparseMatrix& A) const;
  /// Tᵀ f for a vector f over the full numbering.
  VectorXd reduce_vector(const VectorXd& f) const;
  /// K_ss⁻¹ f_s: the slave displacements of f with the masters held (static correction).
  VectorXd slave_response(const VectorXd& f) const;
  /// Counters of the K_ss factorization and solves.
  const SolverCounters& counters() const { return solver_->counters(); }

 private:
  MatrixXd block(const SparseMatrix& A, const std::vector<int>& rows,
                 const std::vector<int>& cols) const;

  std::vector<int> masters_, slaves_;
  std::unique_ptr<LinearSolver> solver_;
  MatrixXd t_sm_;
};

}  // namespace impactfe
