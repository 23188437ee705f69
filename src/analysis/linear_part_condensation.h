#pragma once
/// Condensation of the linear part of a transient onto the DOFs its nonlinear elements touch
/// (thesis eqs. 4-16..4-20; ../shared/DESIGN.md "Performance principles").
///
/// With the effective matrix split into the constant linear part A_L = cK K_L + cC C_L + cM M
/// (the linear elements' stiffness and damping and every element's mass) and the nonlinear
/// elements' share on the small set c of free DOFs they touch, the equations of a step are
///   A_L δ + E [φ(δ_c) − φ(0)] = r0,
/// E selecting the c DOFs and r0 the residual at the predictor. With the Schur complement
/// S = (Eᵀ A_L⁻¹ E)⁻¹ of A_L onto c, the c part obeys the small dense system
/// S (y − δ_c) − [φ(δ_c) − φ(0)] = 0,  y = (A_L⁻¹ r0)_c, whose Newton tangent is
/// S + (cK K_N + cC C_N). Its residual is the full residual on the c rows with every other row in
/// balance, so Newton on it makes the iterates of full Newton. The whole field is recovered once
/// per step from the other rows: δ_i = A_L,ii⁻¹ (r0_i − A_L,ic δ_c). linalg/schur_solver.h does
/// the linear algebra (with CHOLMOD: c ordered last in the factorization, so a step costs one
/// forward and one back substitution and nothing of size n × m is stored). A_L is factorized
/// once per set of integration coefficients (once per Δt).
#include <optional>
#include <string>
#include <vector>

#include "assembly/assembler.h"
#include "linalg/schur_solver.h"
#include "linalg/updatable_dense_factor.h"

namespace impactfe {

class LinearPartCondensation {
 public:
  /// Largest condensed set accepted (S is m × m, and its Newton tangent is factorized densely),
  /// and the largest G (n × m doubles) in bytes where the solver stores one (a distributed run).
  static constexpr int kMaxCondensedDofs = 2000;
  static constexpr double kMaxTransferBytes = 512.0 * 1024 * 1024;

  /// Why condensation does not apply to this model and DOF numbering, or nullopt when it does.
  static std::optional<std::string> refusal(const Assembler& assembler);

  explicit LinearPartCondensation(const Assembler& assembler);

  /// Free DOF indices of the condensed set c, ascending.
  const std::vector<int>& dofs() const { return c_; }
  int size() const { return static_cast<int>(c_.size()); }
  /// Active DOF index → position in c (−1 outside c).
  const std::vector<int>& position() const { return position_; }

  /// Factorizes A_L for these coefficients and forms G and S, unless already done for them.
  /// Throws SingularMatrixError when A_L is singular (a DOF held only by nonlinear elements).
  void prepare(const IntegrationCoefficients& coeff);
  bool prepared_for(const IntegrationCoefficients& coeff) const;

  /// y = (A_L⁻¹ r0)_c for the residual r0 over the free DOFs (the step's first half).
  VectorXd condense(const Eigen::Ref<const VectorXd>& r0_free) {
    return solver_->condense(r0_free);
  }
  /// δ over the free DOFs: δ_c on c, the other rows of A_L δ = r0 − E Δφ satisfied (the r0 of
  /// the last `condense`); into `delta`, which keeps its storage from step to step.
  void recover(const VectorXd& delta_c, VectorXd& delta) { solver_->recover(delta_c, delta); }
  VectorXd recover(const VectorXd& delta_c) { return solver_->recover(delta_c); }
  const MatrixXd& schur() const { return solver_->schur(); }  // S (m × m)
  const SolverCounters& counters() const { return solver_->counters(); }
  /// The factor of the condensed Newton tangent S + cK K_N + cC C_N, kept from step to step so
  /// that a status change updates it (rank one per changed DOF) instead of factoring anew.
  UpdatableDenseFactor& tangent_factor() { return tangent_; }

 private:
  const Assembler& assembler_;
  std::vector<int> c_;
  std::vector<int> position_;
  SparseMatrix effective_;  // A_L; empty once factored (the solver frees it: issue 11)
  std::unique_ptr<SchurSolver> solver_;
  std::optional<IntegrationCoefficients> prepared_;
  UpdatableDenseFactor tangent_;
};

}  // namespace impactfe
