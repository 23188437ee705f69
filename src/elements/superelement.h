#pragma once
/// MATRIX50 superelement (spec §11.7, §10.6 use pass): the reduced matrices of a generation pass
/// acting on its master DOFs at the master nodes. Linear: the matrices are constant, also under
/// large deflection.
#include <memory>
#include <string>
#include <vector>

#include "elements/element.h"
#include "io/superelement_file.h"

namespace impactfe {

class Superelement final : public Element {
 public:
  /// `data`: the superelement file content; its masters become the element DOFs in file order.
  Superelement(int id, std::string path, std::shared_ptr<const SuperelementData> data);

  const char* family() const override { return "Superelement"; }
  const std::vector<DofKey>& dofs() const override { return dofs_; }
  bool is_nonlinear(const ElementContext&) const override { return false; }
  /// K = K_r, f_int = K_r u.
  void tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
               Eigen::VectorXd& f_int) const override;
  /// M = M_r (zero when the file has no mass matrix).
  void mass(const ElementContext& ctx, Eigen::MatrixXd& M) const override;
  bool has_damping() const override { return data_->damping.has_value(); }
  /// C = C_r.
  void damping(const ElementContext& ctx, const Eigen::VectorXd& u,
               Eigen::MatrixXd& C) const override;
  /// f = −Σ_d a_d g_d: exact reduced inertia load of the whole substructure (spec §10.6, U25).
  void frame_acceleration_load(const ElementContext& ctx, const Eigen::Matrix3Xd& a,
                               Eigen::MatrixXd& f) const override;
  /// Refused (NotImplementedError): the file has no load vectors of rotational loads.
  void acceleration_field_load(const ElementContext& ctx,
                               const std::vector<LinearAccelerationField>& fields,
                               const std::function<Vec3(int)>& position,
                               Eigen::MatrixXd& f) const override;
  /// None: internal results come from the expansion pass (spec §11.7).
  const std::vector<std::string>& result_names() const override;
  void results(const ElementContext& ctx, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
               ElementResultValues& out) const override;

  const SuperelementData& data() const { return *data_; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::shared_ptr<const SuperelementData> data_;
  std::vector<DofKey> dofs_;
};

}  // namespace impactfe
