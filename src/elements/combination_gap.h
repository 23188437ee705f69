#pragma once
/// COMBIN40 combination element: spring K1 in series with a Coulomb slider, in parallel with
/// spring K2 and damper C, all in series with a gap; lumped mass M. One DOF per node.
/// Spec §11.4, thesis eqs. 3-5 (force), 3-6 (mass), 3-7 (stiffness).
#include <string>
#include <vector>

#include "elements/element.h"

namespace impactfe {

/// Constants of one COMBIN40 (real constants K1, C, M, GAP, FSLIDE, K2 and KEYOPTs).
struct CombinationGapData {
  double k1 = 0.0;        ///< spring 1 (in series with the slider), force/length
  double c = 0.0;         ///< damper, active only while closed
  double m = 0.0;         ///< element mass
  double gap = 0.0;       ///< initial gap: > 0 open, < 0 interference, 0 = no gap capability
  double fslide = 0.0;    ///< slide force limit: 0 no slider, < 0 break-away
  double k2 = 0.0;        ///< spring 2, parallel to the K1-slider branch
  bool lock_up = false;   ///< KEYOPT(1) = 1: once closed, stays closed
  int mass_location = 0;  ///< KEYOPT(6): 0 node I, 1 half each, 2 node J
};

/// Kinematics Δ = u_J − u_I along the chosen nodal DOF; closed when Δ + GAP ≤ 0 (GAP ≠ 0),
/// spring-system deflection δ = Δ + GAP (δ = Δ when GAP = 0: always closed).
/// F2 = K2 δ; F1 = K1(δ − u_sl) sticking, ±|FSLIDE| sliding; F = F1 + F2 (negative =
/// compression); f_int = F[−1, +1] (thesis eq. 3-5); K = (S1 + S2)[1 −1; −1 1] when closed
/// (eq. 3-7). The slider is integrated by a return map from the committed slip, so sliding →
/// sticking happens as soon as the slip increment would reverse. After slip the spring system
/// has a permanent set: an open gap re-closes only when Δ + GAP ≤ 0 and the sticking force
/// would be compressive (identical to Δ + GAP ≤ 0 without slip), which keeps the open/close
/// test consistent with the closed → open test F > 0.
/// Results: FORC (F), F1, F2, STAT (0 open, 1 closed, 2 sliding/broken), DELTA (δ), SLIDE (u_sl).
class CombinationGap final : public Element {
 public:
  /// No strain of its own: a thermal expansion of its material does not act on it (MAPDL
  /// applies thermal strain to the structural solids, shells, beams and links only).
  void thermal_load(const ElementContext&, Eigen::VectorXd& f) const override {
    f.setZero(n_dofs());
  }
  CombinationGap(int id, std::vector<DofKey> dofs, const CombinationGapData& data);

  const char* family() const override { return "CombinationGap"; }
  const std::vector<DofKey>& dofs() const override { return dofs_; }
  bool is_nonlinear(const ElementContext&) const override;
  void tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
               Eigen::VectorXd& f_int) const override;
  /// Thesis eq. 3-6: M diag(1,0), (M/2) diag(1,1) or M diag(0,1) by KEYOPT(6).
  void mass(const ElementContext& ctx, Eigen::MatrixXd& M) const override;
  bool has_damping() const override { return data_.c != 0.0; }
  /// C[1 −1; −1 1] while closed (or sliding), zero while open.
  void damping(const ElementContext& ctx, const Eigen::VectorXd& u,
               Eigen::MatrixXd& C) const override;

  bool has_status() const override;
  bool update_status(const ElementContext& ctx, const Eigen::VectorXd& u) override;
  void commit(const Eigen::VectorXd& u) override;
  /// Back to the committed state; also clears a freeze.
  void revert() override;
  std::vector<double> history_state() const override;
  void restore_history_state(const std::vector<double>& state) override;
  void freeze_status(bool frozen) override { frozen_ = frozen; }
  GapStatus status() const override { return trial_.status; }
  double contact_stiffness() const override { return data_.k1 + data_.k2; }

  const std::vector<std::string>& result_names() const override;
  void results(const ElementContext& ctx, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
               ElementResultValues& out) const override;

  const CombinationGapData& data() const { return data_; }
  /// Current trial slip u_sl.
  double slip() const { return trial_.slip; }

 private:
  struct State {
    GapStatus status = GapStatus::Open;
    double slip = 0.0;       // u_sl
    double direction = 1.0;  // sign of F1 while sliding
    bool broken = false;     // break-away slider has released (K1 branch carries nothing)
  };
  struct Forces {
    double f1 = 0.0, f2 = 0.0, s1 = 0.0, s2 = 0.0, delta = 0.0, slip = 0.0;
    bool closed = false;
  };

  double deflection(const Eigen::VectorXd& u) const;
  bool gap_capable() const { return data_.gap != 0.0; }
  /// Closed response at deflection δ with the slider return-mapped from the committed slip.
  State closed_state(double delta) const;
  /// Forces and stiffnesses for state `s` at u.
  Forces forces(const State& s, const Eigen::VectorXd& u) const;
  /// The state that the status rules give at u, starting from the trial status.
  State next_state(const Eigen::VectorXd& u) const;

  std::vector<DofKey> dofs_;
  CombinationGapData data_;
  State committed_;
  State trial_;
  bool frozen_ = false;
};

}  // namespace impactfe
