#pragma once
/// COMBIN14 spring-damper: 3-D / 2-D longitudinal, 3-D torsional, or 1-D on one nodal DOF.
/// Spec §11.2.
#include <string>
#include <vector>

#include "elements/corotational.h"
#include "elements/element.h"

namespace impactfe {

/// How a COMBIN14 acts (KEYOPT(2), KEYOPT(3)).
enum class SpringMode {
  Longitudinal3D,  ///< KEYOPT(2)=0, KEYOPT(3)=0: UX UY UZ along the node-to-node line
  Torsional3D,     ///< KEYOPT(2)=0, KEYOPT(3)=1: ROTX ROTY ROTZ about the node-to-node line
  Longitudinal2D,  ///< KEYOPT(2)=0, KEYOPT(3)=2: UX UY in an X-Y plane
  Scalar,          ///< KEYOPT(2)=1..6: one nodal DOF per node (UX..ROTZ)
};

/// Linear spring k and viscous damper CV1 in parallel: K = k blk(nnᵀ), C = CV1 blk(nnᵀ)
/// (n = 1 for the scalar mode). Longitudinal modes follow the co-rotational kinematics under
/// large deflection, N = k(ℓ − L0). No mass. Results: FORC (spring force, tension +),
/// STRETCH (extension: ℓ − L0, or the relative displacement/rotation along n).
class SpringDamper final : public Element {
 public:
  /// No strain of its own: a thermal expansion of its material does not act on it (MAPDL
  /// applies thermal strain to the structural solids, shells, beams and links only).
  void thermal_load(const ElementContext&, Eigen::VectorXd& f) const override {
    f.setZero(n_dofs());
  }
  SpringDamper(int id, SpringMode mode, std::vector<DofKey> dofs, corotational::AxialMember member,
               double stiffness, double damping);

  const char* family() const override { return "SpringDamper"; }
  const std::vector<DofKey>& dofs() const override { return dofs_; }
  bool is_nonlinear(const ElementContext& ctx) const override;
  void tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
               Eigen::VectorXd& f_int) const override;
  /// Zero (COMBIN14 has no mass).
  void mass(const ElementContext& ctx, Eigen::MatrixXd& M) const override;
  bool has_damping() const override { return damping_ != 0.0; }
  /// CV1 blk(nnᵀ), n along the current line under large deflection.
  void damping(const ElementContext& ctx, const Eigen::VectorXd& u,
               Eigen::MatrixXd& C) const override;
  const std::vector<std::string>& result_names() const override;
  void results(const ElementContext& ctx, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
               ElementResultValues& out) const override;

  SpringMode mode() const { return mode_; }

 private:
  corotational::AxialKinematics kinematics(const ElementContext& ctx) const;
  bool longitudinal() const {
    return mode_ == SpringMode::Longitudinal3D || mode_ == SpringMode::Longitudinal2D;
  }

  SpringMode mode_;
  std::vector<DofKey> dofs_;
  corotational::AxialMember member_;
  double stiffness_;
  double damping_;
};

}  // namespace impactfe
