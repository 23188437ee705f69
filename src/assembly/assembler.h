#pragma once
/// Sparse assembly with the pattern built once. Forms the effective matrix
/// K_eff = cK K_T + cC C + cM M on the free DOFs (lower triangle, for the linear solver) and the
/// element force vectors on all active DOFs, in one pass over the elements
/// (the OpenSees/Chrono contract: the integrator supplies the coefficients).
#include <memory>
#include <vector>

#include "assembly/dof_map.h"
#include "elements/element.h"
#include "linalg/sparse.h"
#include "time/time_integrator.h"

namespace impactfe {

class Assembler {
 public:
  /// `alpha`, `beta`: Rayleigh damping C += alpha M + beta K (ALPHAD, BETAD), element by element
  /// with the current tangent.
  Assembler(const std::vector<std::unique_ptr<Element>>& elements, const DofMap& dofs,
            const ElementContext& ctx, double alpha = 0.0, double beta = 0.0);

  /// Stiffness-proportional damping of each element's material (MP,DAMP = BETD: C_e += β_e K_e,
  /// APDL_MODELING §6.1), added to the global beta; one value per element, in element order.
  void set_material_stiffness_damping(std::vector<double> beta);

  const DofMap& dofs() const { return dofs_; }
  const ElementContext& context() const { return ctx_; }

  /// What one pass computes. Pointers left null are skipped.
  struct Output {
    SparseMatrix* effective = nullptr;   // free-free lower triangle of cK K + cC C + cM M
    VectorXd* internal_force = nullptr;  // f_int(u) over all active DOFs
    VectorXd* damping_force = nullptr;   // C v over all active DOFs
  };
  /// u, v: total displacement and velocity over all active DOFs.
  void assemble(const IntegrationCoefficients& coeff, const VectorXd& u, const VectorXd& v,
                const Output& out) const;

  /// Mass matrix over all active DOFs (full symmetric storage), for inertia forces M a and the
  /// frame-acceleration load -M r a.
  SparseMatrix mass_matrix() const;
  /// Stiffness at u (full symmetric storage, all active DOFs): for energies and reduction.
  SparseMatrix stiffness_matrix(const VectorXd& u) const;
  /// Damping matrix at u (full symmetric storage, all active DOFs).
  SparseMatrix damping_matrix(const VectorXd& u) const;
  bool has_damping() const { return has_damping_; }
  /// True when some element's stiffness or internal force depends on u (or on a status).
  bool is_nonlinear() const;
  /// An empty matrix with the free-free lower pattern.
  const SparseMatrix& pattern() const { return pattern_; }

  /// Element DOF values gathered from a global vector.
  void gather(std::size_t e, const VectorXd& global, VectorXd& local) const;

 private:
  enum class Which { Stiffness, Mass, Damping };
  SparseMatrix full_matrix(Which which, const VectorXd& u) const;

  const std::vector<std::unique_ptr<Element>>& elements_;
  const DofMap& dofs_;
  ElementContext ctx_;
  SparseMatrix pattern_;
  /// For each element, the value slot of each (a, b) pair with a >= b in the lower pattern
  /// (-1 when a DOF is constrained): scatter is a plain indexed add.
  std::vector<std::vector<int>> slots_;
  std::vector<MatrixXd> mass_;              // constant element mass matrices
  std::vector<MatrixXd> linear_stiffness_;  // K_e of linear elements (evaluated once)
  std::vector<bool> is_linear_;
  std::vector<std::size_t> nonlinear_;  // indices of the nonlinear elements
  // Per-element results of the parallel tangent phase of assemble() (scratch, not state).
  mutable std::vector<MatrixXd> tangent_buffer_;
  mutable std::vector<VectorXd> force_buffer_;
  bool has_damping_ = false;
  double alpha_ = 0.0;                 // Rayleigh mass coefficient
  double beta_ = 0.0;                  // Rayleigh stiffness coefficient
  std::vector<double> material_beta_;  // per element (empty: none)
  double beta_of(std::size_t e) const {
    return material_beta_.empty() ? beta_ : beta_ + material_beta_[e];
  }
};

}  // namespace impactfe
