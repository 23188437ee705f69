#pragma once
/// Element adapters that change how an element enters the equations without the element
/// knowing (decorators over the Element interface):
///
/// * NodalAxesElement — rotated nodal coordinate systems (N angles, NROTAT; APDL_MODELING §2.6):
///   the global DOF vector holds the DOFs of rotated nodes in their nodal axes, so D, F, IC and
///   the nodal results act in nodal axes. With u_global = T u_nodal (T block diagonal, the nodal
///   axes R of each rotated node on its translation and rotation triads): K_n = Tᵀ K T,
///   f_n = Tᵀ f, M_n = Tᵀ M T (Cook et al., "Concepts and Applications of FEA", §2.11).
/// * MaterialDampingElement — damping of the element's material (MP,ALPD / MP,BETD or DAMP;
///   APDL_MODELING §6.1): C_e += α M_e + β K_e.
#include <memory>
#include <vector>

#include "core/model.h"
#include "elements/element.h"
#include "elements/penetration_check.h"

namespace impactfe {

class NodalAxesElement final : public Element, public PenetrationCheck {
 public:
  /// Throws InputError (at the element's record location) when a rotated node carries only part
  /// of a translation or rotation triad in this element (the rotation would mix DOFs it lacks).
  NodalAxesElement(std::unique_ptr<Element> inner, const Model& model, const SourceLocation& where);

  const char* family() const override { return inner_->family(); }
  const std::vector<DofKey>& dofs() const override { return inner_->dofs(); }
  bool is_nonlinear(const ElementContext& ctx) const override { return inner_->is_nonlinear(ctx); }
  void tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
               Eigen::VectorXd& f_int) const override;
  void mass(const ElementContext& ctx, Eigen::MatrixXd& M) const override;
  bool has_damping() const override { return inner_->has_damping(); }
  void damping(const ElementContext& ctx, const Eigen::VectorXd& u,
               Eigen::MatrixXd& C) const override;
  void frame_acceleration_load(const ElementContext& ctx, const Eigen::Matrix3Xd& a,
                               Eigen::MatrixXd& f) const override;
  void pressure_load(const ElementContext& ctx, int face, const std::array<double, 4>& p,
                     const Eigen::VectorXd& u, Eigen::VectorXd& f) const override;
  bool has_history() const override { return inner_->has_history(); }
  double plastic_work() const override { return inner_->plastic_work(); }
  std::vector<double> history_state() const override { return inner_->history_state(); }
  void restore_history_state(const std::vector<double>& state) override {
    inner_->restore_history_state(state);
  }
  void commit_history(const ElementContext& ctx, const Eigen::VectorXd& u) override {
    inner_->commit_history(ctx, t_ * u);
  }
  bool has_status() const override { return inner_->has_status(); }
  bool update_status(const ElementContext& ctx, const Eigen::VectorXd& u) override {
    return inner_->update_status(ctx, t_ * u);
  }
  void commit(const Eigen::VectorXd& u) override { inner_->commit(t_ * u); }
  void revert() override { inner_->revert(); }
  void freeze_status(bool frozen) override { inner_->freeze_status(frozen); }
  GapStatus status() const override { return inner_->status(); }
  double contact_stiffness() const override { return inner_->contact_stiffness(); }
  const std::vector<std::string>& result_names() const override { return inner_->result_names(); }
  void results(const ElementContext& ctx, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
               ElementResultValues& out) const override;

  /// u_global = T u_nodal over the element DOFs.
  const Eigen::MatrixXd& transformation() const { return t_; }

  /// A contact element's KEYOPT(7) check (elements/penetration_check.h) on global displacements.
  bool checks_penetration() const override {
    const auto* check = dynamic_cast<const PenetrationCheck*>(inner_.get());
    return check != nullptr && check->checks_penetration();
  }
  double penetration_ratio(const Eigen::VectorXd& start, const Eigen::VectorXd& u) const override {
    return dynamic_cast<const PenetrationCheck&>(*inner_).penetration_ratio(t_ * start, t_ * u);
  }

 private:
  std::unique_ptr<Element> inner_;
  Eigen::MatrixXd t_;
};

class MaterialDampingElement final : public Element, public PenetrationCheck {
 public:
  MaterialDampingElement(std::unique_ptr<Element> inner, double alpha, double beta);

  const char* family() const override { return inner_->family(); }
  const std::vector<DofKey>& dofs() const override { return inner_->dofs(); }
  bool is_nonlinear(const ElementContext& ctx) const override { return inner_->is_nonlinear(ctx); }
  void tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
               Eigen::VectorXd& f_int) const override {
    inner_->tangent(ctx, u, K, f_int);
  }
  void mass(const ElementContext& ctx, Eigen::MatrixXd& M) const override { inner_->mass(ctx, M); }
  bool has_damping() const override { return true; }
  /// Inner damping + α M + β K_T(u).
  void damping(const ElementContext& ctx, const Eigen::VectorXd& u,
               Eigen::MatrixXd& C) const override;
  void frame_acceleration_load(const ElementContext& ctx, const Eigen::Matrix3Xd& a,
                               Eigen::MatrixXd& f) const override {
    inner_->frame_acceleration_load(ctx, a, f);
  }
  void pressure_load(const ElementContext& ctx, int face, const std::array<double, 4>& p,
                     const Eigen::VectorXd& u, Eigen::VectorXd& f) const override {
    inner_->pressure_load(ctx, face, p, u, f);
  }
  bool has_history() const override { return inner_->has_history(); }
  double plastic_work() const override { return inner_->plastic_work(); }
  std::vector<double> history_state() const override { return inner_->history_state(); }
  void restore_history_state(const std::vector<double>& state) override {
    inner_->restore_history_state(state);
  }
  void commit_history(const ElementContext& ctx, const Eigen::VectorXd& u) override {
    inner_->commit_history(ctx, u);
  }
  bool has_status() const override { return inner_->has_status(); }
  bool update_status(const ElementContext& ctx, const Eigen::VectorXd& u) override {
    return inner_->update_status(ctx, u);
  }
  void commit(const Eigen::VectorXd& u) override { inner_->commit(u); }
  void revert() override { inner_->revert(); }
  void freeze_status(bool frozen) override { inner_->freeze_status(frozen); }
  GapStatus status() const override { return inner_->status(); }
  double contact_stiffness() const override { return inner_->contact_stiffness(); }
  bool checks_penetration() const override {
    const auto* check = dynamic_cast<const PenetrationCheck*>(inner_.get());
    return check != nullptr && check->checks_penetration();
  }
  double penetration_ratio(const Eigen::VectorXd& start, const Eigen::VectorXd& u) const override {
    return dynamic_cast<const PenetrationCheck&>(*inner_).penetration_ratio(start, u);
  }
  const std::vector<std::string>& result_names() const override { return inner_->result_names(); }
  void results(const ElementContext& ctx, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
               ElementResultValues& out) const override {
    inner_->results(ctx, u, v, out);
  }

 private:
  std::unique_ptr<Element> inner_;
  double alpha_;
  double beta_;
};

/// Applies the adapters a record needs: material damping when its material has ALPD/BETD, nodal
/// axes when one of its nodes is rotated.
std::unique_ptr<Element> adapt_element(std::unique_ptr<Element> element, const Model& model,
                                       const ElementRecord& record);

}  // namespace impactfe
