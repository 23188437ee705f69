#pragma once
/// Two-node axial spar: LINK1 (2-D, UX UY), LINK8 / LINK180 (3-D, UX UY UZ). Spec §11.1.
#include <optional>
#include <string>
#include <vector>

#include "elements/corotational.h"
#include "elements/element.h"
#include "materials/j2_plasticity.h"

namespace impactfe {

/// Pin-jointed bar with axial stiffness EA/L, optional initial strain ISTRN, stress stiffening
/// and co-rotational large deflection. With a TB plasticity table (BISO, BKIN, MISO) the axial
/// stress follows the uniaxial J2 return (materials/j2_plasticity.h) of the axial strain
/// e/L + ISTRN, one material point per element, committed on converged steps. Results: FORC
/// (axial force N, tension +), SAXL (N/A), EPEL (elastic strain), LENGTH (current length), EPPL
/// (axial plastic strain), EPEQ (accumulated equivalent plastic strain), SEPL (yield stress on
/// the hardening curve at EPEQ), SRAT (|σ − β| / SEPL: 1 on the yield surface), PLWK (plastic
/// work per volume).
class Spar final : public Element {
 public:
  /// `member` holds the reference direction (2 or 3 components) and length L > 0.
  Spar(int id, std::vector<DofKey> dofs, corotational::AxialMember member, double area,
       double youngs_modulus, double density, double initial_strain,
       std::optional<J2Plasticity> plasticity = std::nullopt);

  const char* family() const override { return "Spar"; }
  const std::vector<DofKey>& dofs() const override { return dofs_; }
  bool is_nonlinear(const ElementContext& ctx) const override;
  void tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
               Eigen::VectorXd& f_int) const override;
  /// Consistent (ρAL/6)[2I I; I 2I] or lumped (ρAL/2) I per node.
  void mass(const ElementContext& ctx, Eigen::MatrixXd& M) const override;
  const std::vector<std::string>& result_names() const override;
  void results(const ElementContext& ctx, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
               ElementResultValues& out) const override;

  bool has_history() const override { return plasticity_.has_value(); }
  double plastic_work() const override { return committed_.plastic_work * *volume(); }
  void commit_history(const ElementContext& ctx, const Eigen::VectorXd& u) override;
  std::vector<double> history_state() const override;
  void restore_history_state(const std::vector<double>& state) override;

  std::optional<double> volume() const override { return area_ * member_.length; }
  double area() const { return area_; }
  double length() const { return member_.length; }

 private:
  corotational::AxialKinematics kinematics(const ElementContext& ctx) const;
  /// Axial response at u; with plasticity, the return from the committed state (`updated`
  /// receives the new state when given).
  corotational::AxialState respond(const ElementContext& ctx, const Eigen::VectorXd& u,
                                   Eigen::MatrixXd& K, Eigen::VectorXd& f,
                                   UniaxialPlasticState* updated) const;

  std::vector<DofKey> dofs_;
  corotational::AxialMember member_;
  double area_;
  double youngs_modulus_;
  double density_;
  double initial_strain_;
  std::optional<J2Plasticity> plasticity_;
  UniaxialPlasticState committed_;
};

}  // namespace impactfe
