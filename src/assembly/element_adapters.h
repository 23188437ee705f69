#pragma once
/// The element adapter that changes how an element enters the equations without the element
/// knowing (a decorator over the Element interface):
///
/// * NodalAxesElement — rotated nodal coordinate systems (N angles, NROTAT; APDL_MODELING §2.6):
///   the global DOF vector holds the DOFs of rotated nodes in their nodal axes, so D, F, IC and
///   the nodal results act in nodal axes. With u_global = T u_nodal (T block diagonal, the nodal
///   axes R of each rotated node on its translation and rotation triads): K_n = Tᵀ K T,
///   f_n = Tᵀ f, M_n = Tᵀ M T (Cook et al., "Concepts and Applications of FEA", §2.11).
///
/// * ConstrainedElement — the slaves of constraint equations (CE, CERIG, MPC184) eliminated:
///   u_inner = T u + g (assembly/constraint_equations.h).
///
/// Both are a TransformedElement. It implements every optional element interface
/// (elements/element_capabilities.h, asserted below) by forwarding it with the same transformation,
/// so it hides nothing the element can do. Material damping (MP,ALPD / MP,BETD) is no adapter: it
/// is data of the element (Element::material_damping) that the assembler applies where it scatters
/// the element.
#include <memory>
#include <vector>

#include "assembly/constraint_equations.h"
#include "core/model.h"
#include "elements/element.h"
#include "elements/element_capabilities.h"

namespace impactfe {

/// The common form of both adapters: the inner element's DOF values are an affine function of
/// the adapter's, u_inner = T u + g (g: the constants of constraint equations, zero for nodal
/// axes), so K = Tᵀ K_inner T, f = Tᵀ f_inner(T u + g), M = Tᵀ M_inner T, C = Tᵀ C_inner T and
/// every load vector is Tᵀ f_inner. Velocities and accelerations transform with T alone.
class TransformedElement : public Element, public PenetrationCheck, public ConnectivityUpdate {
 public:
  const char* family() const override { return inner_->family(); }
  const std::vector<DofKey>& dofs() const override { return dofs_; }
  /// A non-zero constant makes f_inner(T u + g) ≠ Tᵀ K T u: such an element is evaluated at
  /// every iterate, like a nonlinear one, so the constant acts on the total displacement.
  bool is_nonlinear(const ElementContext& ctx) const override {
    return inner_->is_nonlinear(ctx) || g_.size() > 0;
  }
  void tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
               Eigen::VectorXd& f_int) const override;
  void mass(const ElementContext& ctx, Eigen::MatrixXd& M) const override;
  bool has_damping() const override { return inner_->has_damping(); }
  void damping(const ElementContext& ctx, const Eigen::VectorXd& u,
               Eigen::MatrixXd& C) const override;
  void frame_acceleration_load(const ElementContext& ctx, const Eigen::Matrix3Xd& a,
                               Eigen::MatrixXd& f) const override;
  void acceleration_field_load(const ElementContext& ctx,
                               const std::vector<LinearAccelerationField>& fields,
                               const std::function<Vec3(int)>& position,
                               Eigen::MatrixXd& f) const override;
  void pressure_load(const ElementContext& ctx, int face, const std::array<double, 4>& p,
                     const Eigen::VectorXd& u, Eigen::VectorXd& f) const override;
  void set_temperature_change(std::vector<double> dT) override {
    inner_->set_temperature_change(dT);
    Element::set_temperature_change(std::move(dT));
  }
  void thermal_load(const ElementContext& ctx, Eigen::VectorXd& f) const override;
  bool has_history() const override { return inner_->has_history(); }
  double plastic_work() const override { return inner_->plastic_work(); }
  std::vector<double> history_state() const override { return inner_->history_state(); }
  void restore_history_state(const std::vector<double>& state) override {
    inner_->restore_history_state(state);
  }
  void commit_history(const ElementContext& ctx, const Eigen::VectorXd& u) override {
    inner_->commit_history(ctx, inner_values(u));
  }
  bool has_status() const override { return inner_->has_status(); }
  bool update_status(const ElementContext& ctx, const Eigen::VectorXd& u) override {
    return inner_->update_status(ctx, inner_values(u));
  }
  void commit(const Eigen::VectorXd& u) override { inner_->commit(inner_values(u)); }
  void revert() override { inner_->revert(); }
  void freeze_status(bool frozen) override { inner_->freeze_status(frozen); }
  GapStatus status() const override { return inner_->status(); }
  double contact_stiffness() const override { return inner_->contact_stiffness(); }
  const std::vector<std::string>& result_names() const override { return inner_->result_names(); }
  void results(const ElementContext& ctx, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
               ElementResultValues& out) const override;

  /// u_inner = T u + g over the element DOFs.
  const Eigen::MatrixXd& transformation() const { return t_; }
  const Element& inner() const { return *inner_; }

  /// A contact element's KEYOPT(7) check (elements/penetration_check.h) on the inner values.
  bool checks_penetration() const override {
    const auto* check = dynamic_cast<const PenetrationCheck*>(inner_.get());
    return check != nullptr && check->checks_penetration();
  }
  double penetration_ratio(const Eigen::VectorXd& start, const Eigen::VectorXd& u) const override {
    return dynamic_cast<const PenetrationCheck&>(*inner_).penetration_ratio(inner_values(start),
                                                                            inner_values(u));
  }

  /// A contact element's search update (elements/connectivity.h) on the inner values; when its
  /// DOFs change, T follows them.
  bool updates_connectivity() const override {
    const auto* update = dynamic_cast<const ConnectivityUpdate*>(inner_.get());
    return update != nullptr && update->updates_connectivity();
  }
  bool refresh_dofs(const Eigen::VectorXd& u, const NodePositions& positions) override;

 protected:
  explicit TransformedElement(std::unique_ptr<Element> inner);
  /// Sets dofs_, t_ and g_ for the inner element's current DOFs.
  virtual void build_transformation() = 0;
  Eigen::VectorXd inner_values(const Eigen::VectorXd& u) const {
    return g_.size() > 0 ? Eigen::VectorXd(t_ * u + g_) : Eigen::VectorXd(t_ * u);
  }

  std::unique_ptr<Element> inner_;
  std::vector<DofKey> dofs_;  // the adapter's DOFs
  Eigen::MatrixXd t_;         // n_inner × n_dofs
  Eigen::VectorXd g_;         // n_inner, or empty when zero
};

static_assert(implements_all<TransformedElement>(ElementCapabilities{}),
              "an element adapter must implement every optional element interface "
              "(elements/element_capabilities.h), or it hides it from the drivers");

class NodalAxesElement final : public TransformedElement {
 public:
  /// Throws InputError (at the element's record location) when a rotated node carries only part
  /// of a translation or rotation triad in this element and the rotation mixes those DOFs with
  /// ones the element lacks (a plane element's UX UY take a rotation about Z).
  NodalAxesElement(std::unique_ptr<Element> inner, const Model& model, const SourceLocation& where);

 private:
  void build_transformation() override;
  const Model& model_;
  SourceLocation where_;
};

/// An element at slave DOFs of constraint equations (assembly/constraint_equations.h): its
/// DOFs are its retained DOFs followed by the masters of its slaves, u_inner = T u + g.
class ConstrainedElement final : public TransformedElement {
 public:
  ConstrainedElement(std::unique_ptr<Element> inner,
                     std::shared_ptr<const DependentDofs> dependent);

 private:
  void build_transformation() override;
  std::shared_ptr<const DependentDofs> dependent_;
};

/// Makes an element of the model what the equations need: the damping of its material
/// (Element::material_damping from MP,ALPD / MP,BETD), nodal axes when one of its nodes is
/// rotated, the elimination of constraint equations' slaves when it carries one (`dependent`;
/// the equations act in nodal axes, so that adapter wraps the nodal-axes one).
std::unique_ptr<Element> adapt_element(
    std::unique_ptr<Element> element, const Model& model, const ElementRecord& record,
    const std::shared_ptr<const DependentDofs>& dependent = nullptr);

}  // namespace impactfe
