#pragma once
/// Master-DOF selection and Guyan (static) condensation (thesis eq. 4-21 with the damping term
/// corrected as spec §10.4 says; Cook et al. §11.8).
///
/// With the free DOFs split into masters m and slaves s, u_s = T u_m + K_ss⁻¹ f_s where
/// T = −K_ss⁻¹ K_sm (one factorization of K_ss, one multi-right-hand-side solve; no inverse is
/// ever formed). The reduced matrices are Tᵀ A T with the full transformation [I; T]:
///   K_r = K_mm + K_ms T,   M_r = M_mm + M_ms T + Tᵀ M_sm + Tᵀ M_ss T,   C_r likewise,
///   f_r = f_m + Tᵀ f_s.
#include <memory>
#include <optional>
#include <vector>

#include "assembly/dof_map.h"
#include "core/model.h"
#include "linalg/linear_solver.h"
#include "linalg/sparse.h"

namespace impactfe {

/// Outcome of the master selection over the free DOFs of a DofMap.
struct MasterSelection {
  std::vector<int> indices;       // free DOF indices of the masters, in selection order
  std::vector<DofKey> ignored;    // M entries on constrained or absent DOFs (ignored, logged)
  std::vector<DofKey> automatic;  // masters added by TOTAL (smallest K_ii / M_ii first)
};

/// Masters from the M list (input order) plus automatic ones up to `total` (TOTAL,NTOT,NRMDF:
/// candidates are free non-master DOFs with mass, ranked by K_ii / M_ii ascending, spec
/// APDL_SCRIPTING §E.12). `k_diag`, `m_diag`: diagonals over the free DOFs.
MasterSelection select_masters(const std::vector<DofKey>& requested, const DofMap& dofs,
                               const VectorXd& k_diag, const VectorXd& m_diag,
                               std::optional<int> total, bool exclude_rotations);

/// Guyan condensation of the free-free blocks of K, M (and optionally C) onto the masters.
class GuyanReduction {
 public:
  /// `k`, `m`, `c`: full symmetric storage over the active DOFs (only the leading `n_free`
  /// rows/columns are used); `c` may be null. `masters`: free DOF indices. Throws ModelError
  /// naming the slave DOF when K_ss is singular (a slave the masters cannot restrain).
  GuyanReduction(const SparseMatrix& k, const SparseMatrix& m, const SparseMatrix* c, int n_free,
                 std::vector<int> masters, const DofMap* names = nullptr);

  int n_free() const { return n_free_; }
  int n_masters() const { return static_cast<int>(masters_.size()); }
  int n_slaves() const { return static_cast<int>(slaves_.size()); }
  const std::vector<int>& masters() const { return masters_; }
  const std::vector<int>& slaves() const { return slaves_; }

  const MatrixXd& k() const { return k_r_; }  // K_r (n_m x n_m)
  const MatrixXd& m() const { return m_r_; }  // M_r
  const MatrixXd& c() const { return c_r_; }  // C_r (zero when no damping)
  /// T = −K_ss⁻¹ K_sm (n_s x n_m).
  const MatrixXd& transformation() const { return t_; }

  /// f_r = f_m + Tᵀ f_s from a vector over (at least) the free DOFs.
  VectorXd reduce_force(const VectorXd& f) const;
  /// Free-DOF vector from master values: u_s = T u_m (+ K_ss⁻¹ f_s when `f` is given: the
  /// static correction of the slave loads, spec §10.5).
  VectorXd expand(const VectorXd& u_m, const VectorXd* f = nullptr) const;

 private:
  MatrixXd reduce_matrix(const SparseMatrix& a) const;

  int n_free_ = 0;
  std::vector<int> masters_, slaves_;
  std::vector<int> slave_position_;  // free index -> slave row (-1 for masters)
  std::unique_ptr<LinearSolver> kss_;
  MatrixXd t_, k_r_, m_r_, c_r_;
};

}  // namespace impactfe
