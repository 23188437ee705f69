#pragma once
/// MASS21 structural point mass. Spec §11.3.
#include <string>
#include <vector>

#include "elements/element.h"

namespace impactfe {

/// Diagonal mass on the DOFs of one node: diag(MASSX, MASSY, MASSZ, IXX, IYY, IZZ) restricted
/// to the KEYOPT(3) DOF set (mass units of the deck, e.g. lbf·s²/in). No stiffness; its result
/// is its kinetic energy KENE = ½ vᵀ M v.
class PointMass final : public Element {
 public:
  /// No strain of its own: a thermal expansion of its material does not act on it (MAPDL
  /// applies thermal strain to the structural solids, shells, beams and links only).
  void thermal_load(const ElementContext&, Eigen::VectorXd& f) const override {
    f.setZero(n_dofs());
  }
  /// `diagonal` has one entry per DOF of `dofs`.
  PointMass(int id, std::vector<DofKey> dofs, Eigen::VectorXd diagonal);

  const char* family() const override { return "PointMass"; }
  const std::vector<DofKey>& dofs() const override { return dofs_; }
  bool is_nonlinear(const ElementContext&) const override { return false; }
  /// K = 0, f_int = 0.
  void tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
               Eigen::VectorXd& f_int) const override;
  void mass(const ElementContext& ctx, Eigen::MatrixXd& M) const override;
  const std::vector<std::string>& result_names() const override;
  void results(const ElementContext& ctx, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
               ElementResultValues& out) const override;

 private:
  std::vector<DofKey> dofs_;
  Eigen::VectorXd diagonal_;
};

}  // namespace impactfe
