#include "assembly/element_adapters.h"

#include <fmt/format.h>

#include <map>

namespace impactfe {

NodalAxesElement::NodalAxesElement(std::unique_ptr<Element> inner, const Model& model,
                                   const SourceLocation& where)
    : Element(inner->id()), inner_(std::move(inner)), model_(model), where_(where) {
  set_material_damping(inner_->material_damping());  // the assembler reads it from here
  build_transformation();
}

void NodalAxesElement::build_transformation() {
  const auto& dofs = inner_->dofs();
  const int n = static_cast<int>(dofs.size());
  t_ = Eigen::MatrixXd::Identity(n, n);
  // Positions of each node's DOFs in the element: node -> dof component -> position.
  std::map<int, std::array<int, 6>> where_is;
  for (int i = 0; i < n; ++i) {
    auto [it, fresh] = where_is.try_emplace(dofs[static_cast<std::size_t>(i)].node);
    if (fresh) it->second.fill(-1);
    it->second[static_cast<std::size_t>(dofs[static_cast<std::size_t>(i)].dof)] = i;
  }
  for (const auto& [node, pos] : where_is) {
    const auto it = model_.nodes.find(node);
    if (it == model_.nodes.end() || !it->second.rotated()) continue;
    const Mat3 R = it->second.axes();
    for (int group = 0; group < 2; ++group) {
      int present = 0;
      for (int a = 0; a < 3; ++a)
        present += pos[static_cast<std::size_t>(3 * group + a)] >= 0 ? 1 : 0;
      if (present == 0) continue;
      if (present != 3)
        throw InputError(where_, fmt::format("element {} ({}): node {} has a rotated nodal "
                                             "coordinate system but the element carries only {} "
                                             "of its {} DOFs",
                                             id(), inner_->family(), node, present,
                                             group == 0 ? "UX/UY/UZ" : "ROTX/ROTY/ROTZ"));
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          t_(pos[static_cast<std::size_t>(3 * group + a)],
             pos[static_cast<std::size_t>(3 * group + b)]) = R(a, b);
    }
  }
}

bool NodalAxesElement::refresh_dofs(const Eigen::VectorXd& u, const NodePositions& positions) {
  auto* update = dynamic_cast<ConnectivityUpdate*>(inner_.get());
  if (update == nullptr || !update->refresh_dofs(t_ * u, positions)) return false;
  build_transformation();
  return true;
}

void NodalAxesElement::tangent(const ElementContext& ctx, const Eigen::VectorXd& u,
                               Eigen::MatrixXd& K, Eigen::VectorXd& f_int) const {
  inner_->tangent(ctx, t_ * u, K, f_int);
  K = t_.transpose() * K * t_;
  f_int = t_.transpose() * f_int;
}

void NodalAxesElement::mass(const ElementContext& ctx, Eigen::MatrixXd& M) const {
  inner_->mass(ctx, M);
  M = t_.transpose() * M * t_;
}

void NodalAxesElement::damping(const ElementContext& ctx, const Eigen::VectorXd& u,
                               Eigen::MatrixXd& C) const {
  inner_->damping(ctx, t_ * u, C);
  C = t_.transpose() * C * t_;
}

void NodalAxesElement::frame_acceleration_load(const ElementContext& ctx, const Eigen::Matrix3Xd& a,
                                               Eigen::MatrixXd& f) const {
  inner_->frame_acceleration_load(ctx, a, f);
  for (Eigen::Index k = 0; k < f.cols(); ++k) f.col(k) = (t_.transpose() * f.col(k)).eval();
}

void NodalAxesElement::pressure_load(const ElementContext& ctx, int face,
                                     const std::array<double, 4>& p, const Eigen::VectorXd& u,
                                     Eigen::VectorXd& f) const {
  inner_->pressure_load(ctx, face, p, t_ * u, f);
  f = t_.transpose() * f;
}

void NodalAxesElement::thermal_load(const ElementContext& ctx, Eigen::VectorXd& f) const {
  inner_->thermal_load(ctx, f);
  f = t_.transpose() * f;
}

void NodalAxesElement::results(const ElementContext& ctx, const Eigen::VectorXd& u,
                               const Eigen::VectorXd& v, ElementResultValues& out) const {
  inner_->results(ctx, t_ * u, t_ * v, out);
}

std::unique_ptr<Element> adapt_element(std::unique_ptr<Element> element, const Model& model,
                                       const ElementRecord& record) {
  const auto mat = model.materials.find(record.mat);
  if (mat != model.materials.end()) {
    const Material& m = mat->second;
    element->set_material_damping({m.get("ALPD", 0.0), m.get("BETD", 0.0)});
    // Secant coefficients of thermal expansion (MP,ALPX; ALPY and ALPZ default to ALPX).
    Element::ThermalExpansion thermal;
    const double ax = m.get("ALPX", 0.0);
    thermal.alpha = Vec3(ax, m.get("ALPY", ax), m.get("ALPZ", ax));
    if (m.has("REFT")) thermal.reference_temperature = m.get("REFT", 0.0);
    thermal.nodes = record.nodes;
    element->set_thermal_expansion(thermal);
  }
  bool rotated = false;
  for (const DofKey& k : element->dofs()) {
    const auto it = model.nodes.find(k.node);
    rotated = rotated || (it != model.nodes.end() && it->second.rotated());
  }
  if (rotated) {
    Element::ThermalExpansion thermal = element->thermal_expansion();
    element = std::make_unique<NodalAxesElement>(std::move(element), model, record.where);
    element->set_thermal_expansion(std::move(thermal));
  }
  return element;
}

}  // namespace impactfe
