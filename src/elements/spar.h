#pragma once
/// Two-node axial spar: LINK1 (2-D, UX UY), LINK8 / LINK180 (3-D, UX UY UZ). Spec §11.1.
#include <optional>
#include <string>
#include <vector>

#include "elements/corotational.h"
#include "elements/element.h"
#include "materials/j2_plasticity.h"

namespace impactfe {

/// Pin-jointed bar with axial stiffness EA/L, optional initial strain ISTRN (LINK1, LINK8),
/// added mass per length ADDMAS and tension-/compression-only behaviour TENSKEY (LINK180),
/// stress stiffening and co-rotational large deflection. With a TB plasticity table (BISO, BKIN,
/// MISO) the axial stress follows the uniaxial J2 return (materials/j2_plasticity.h) of the axial
/// strain e/L + ISTRN, one material point per element, committed on converged steps. Results: FORC
/// (axial force N, tension +), SAXL (N/A), EPEL (elastic strain), LENGTH (current length), EPPL
/// (axial plastic strain), EPEQ (accumulated equivalent plastic strain), SEPL (yield stress on
/// the hardening curve at EPEQ), SRAT (|σ − β| / SEPL: 1 on the yield surface), PLWK (plastic
/// work per volume).
class Spar final : public Element {
 public:
  /// Which axial forces the member carries (LINK180 TENSKEY, R3; MAPDL's 0, 1, -1).
  enum class Carries { Both = 0, TensionOnly = 1, CompressionOnly = -1 };

  /// `member` holds the reference direction (2 or 3 components) and length L > 0.
  /// `added_mass`: mass per unit length beyond ρA (LINK180 ADDMAS, R2).
  Spar(int id, std::vector<DofKey> dofs, corotational::AxialMember member, double area,
       double youngs_modulus, double density, double initial_strain,
       std::optional<J2Plasticity> plasticity = std::nullopt, double added_mass = 0.0,
       Carries carries = Carries::Both);

  const char* family() const override { return "Spar"; }
  const std::vector<DofKey>& dofs() const override { return dofs_; }
  bool is_nonlinear(const ElementContext& ctx) const override;
  void tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
               Eigen::VectorXd& f_int) const override;
  /// Consistent ((ρA + m)L/6)[2I I; I 2I] or lumped ((ρA + m)L/2) I per node, m = ADDMAS.
  void mass(const ElementContext& ctx, Eigen::MatrixXd& M) const override;

  /// A tension-only or compression-only member (TENSKEY ≠ 0) is a status element: slack
  /// (GapStatus::Open: no stiffness, no force) while the force it would carry has the sign it
  /// cannot take, taut (Closed) otherwise; the status loop iterates it like a gap.
  bool has_status() const override { return carries_ != Carries::Both; }
  bool update_status(const ElementContext& ctx, const Eigen::VectorXd& u) override;
  void commit(const Eigen::VectorXd& u) override;
  void revert() override;
  void freeze_status(bool frozen) override { frozen_ = frozen; }
  GapStatus status() const override { return slack_ ? GapStatus::Open : GapStatus::Closed; }
  const std::vector<std::string>& result_names() const override;
  void results(const ElementContext& ctx, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
               ElementResultValues& out) const override;

  bool has_history() const override { return plasticity_.has_value(); }
  double plastic_work() const override { return committed_.plastic_work * *volume(); }
  void commit_history(const ElementContext& ctx, const Eigen::VectorXd& u) override;
  std::vector<double> history_state() const override;
  void restore_history_state(const std::vector<double>& state) override;

  void thermal_load(const ElementContext& ctx, Eigen::VectorXd& f) const override;

  std::optional<double> volume() const override { return area_ * member_.length; }
  double area() const { return area_; }
  double length() const { return member_.length; }

 private:
  corotational::AxialKinematics kinematics(const ElementContext& ctx) const;
  /// E A ε_th: the axial force of the thermal strain at the temperature change set last.
  double thermal_axial_force() const;
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
  double added_mass_;
  Carries carries_;
  bool slack_ = false;            // trial status
  bool committed_slack_ = false;  // status of the last converged step
  bool frozen_ = false;
};

}  // namespace impactfe
