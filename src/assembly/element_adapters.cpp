#include "assembly/element_adapters.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>

namespace impactfe {

TransformedElement::TransformedElement(std::unique_ptr<Element> inner)
    : Element(inner->id()), inner_(std::move(inner)) {
  set_material_damping(inner_->material_damping());  // the assembler reads it from here
}

NodalAxesElement::NodalAxesElement(std::unique_ptr<Element> inner, const Model& model,
                                   const SourceLocation& where)
    : TransformedElement(std::move(inner)), model_(model), where_(where) {
  build_transformation();
}

void NodalAxesElement::build_transformation() {
  dofs_ = inner_->dofs();
  const auto& dofs = dofs_;
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
      // An element with only some of the three DOFs (a plane element's UX UY, a 2-D beam's ROTZ)
      // takes a nodal rotation that maps their directions onto themselves (about Z, as NROTAT in
      // a cylindrical system gives in the XY plane): its block of R.
      // (A named reference: clang 14 cannot capture a structured binding.)
      const std::array<int, 6>& at = pos;
      const auto has = [&at, group](int a) {
        return at[static_cast<std::size_t>(3 * group + a)] >= 0;
      };
      bool closed = true;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          if (has(a) != has(b) && std::abs(R(a, b)) > 1e-12) closed = false;
      if (!closed)
        throw InputError(where_, fmt::format("element {} ({}): node {} has a rotated nodal "
                                             "coordinate system that mixes the element's {} of "
                                             "the {} DOFs with ones it does not carry (a 2-D "
                                             "element takes a rotation about Z only)",
                                             id(), inner_->family(), node, present,
                                             group == 0 ? "UX/UY/UZ" : "ROTX/ROTY/ROTZ"));
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          if (has(a) && has(b))
            t_(pos[static_cast<std::size_t>(3 * group + a)],
               pos[static_cast<std::size_t>(3 * group + b)]) = R(a, b);
    }
  }
}

ConstrainedElement::ConstrainedElement(std::unique_ptr<Element> inner,
                                       std::shared_ptr<const DependentDofs> dependent)
    : TransformedElement(std::move(inner)), dependent_(std::move(dependent)) {
  build_transformation();
}

void ConstrainedElement::build_transformation() {
  // The adapter's DOFs: the inner element's retained DOFs in its order, then the masters of its
  // slaves in order of first appearance. Row i of T: e_i for a retained DOF, the slave's
  // coefficients a_j for a slave (u_s = Σ a_j u_j + g_s).
  const auto& inner = inner_->dofs();
  dofs_.clear();
  std::map<DofKey, int> column;
  const auto column_of = [&](const DofKey& key) {
    const auto [it, fresh] = column.try_emplace(key, static_cast<int>(dofs_.size()));
    if (fresh) dofs_.push_back(key);
    return it->second;
  };
  for (const DofKey& key : inner)
    if (dependent_->find(key) == nullptr) column_of(key);
  for (const DofKey& key : inner)
    if (const auto* dep = dependent_->find(key))
      for (const auto& [master, a] : dep->masters) column_of(master);
  const int n_inner = static_cast<int>(inner.size());
  t_.setZero(n_inner, static_cast<int>(dofs_.size()));
  Eigen::VectorXd g = Eigen::VectorXd::Zero(n_inner);
  for (int i = 0; i < n_inner; ++i) {
    const DofKey& key = inner[static_cast<std::size_t>(i)];
    if (const auto* dep = dependent_->find(key)) {
      for (const auto& [master, a] : dep->masters) t_(i, column.at(master)) += a;
      g(i) = dep->constant;
    } else {
      t_(i, column.at(key)) = 1.0;
    }
  }
  if (g.cwiseAbs().maxCoeff() > 0.0)
    g_ = std::move(g);
  else
    g_.resize(0);
}

bool TransformedElement::refresh_dofs(const Eigen::VectorXd& u, const NodePositions& positions) {
  auto* update = dynamic_cast<ConnectivityUpdate*>(inner_.get());
  if (update == nullptr || !update->refresh_dofs(inner_values(u), positions)) return false;
  build_transformation();
  return true;
}

void TransformedElement::tangent(const ElementContext& ctx, const Eigen::VectorXd& u,
                                 Eigen::MatrixXd& K, Eigen::VectorXd& f_int) const {
  inner_->tangent(ctx, inner_values(u), K, f_int);
  K = t_.transpose() * K * t_;
  f_int = t_.transpose() * f_int;
}

void TransformedElement::mass(const ElementContext& ctx, Eigen::MatrixXd& M) const {
  inner_->mass(ctx, M);
  M = t_.transpose() * M * t_;
}

void TransformedElement::damping(const ElementContext& ctx, const Eigen::VectorXd& u,
                                 Eigen::MatrixXd& C) const {
  inner_->damping(ctx, inner_values(u), C);
  C = t_.transpose() * C * t_;
}

void TransformedElement::frame_acceleration_load(const ElementContext& ctx,
                                                 const Eigen::Matrix3Xd& a,
                                                 Eigen::MatrixXd& f) const {
  inner_->frame_acceleration_load(ctx, a, f);
  f = (t_.transpose() * f).eval();
}

void TransformedElement::acceleration_field_load(const ElementContext& ctx,
                                                 const std::vector<LinearAccelerationField>& fields,
                                                 const std::function<Vec3(int)>& position,
                                                 Eigen::MatrixXd& f) const {
  inner_->acceleration_field_load(ctx, fields, position, f);
  f = (t_.transpose() * f).eval();
}

void TransformedElement::pressure_load(const ElementContext& ctx, int face,
                                       const std::array<double, 4>& p, const Eigen::VectorXd& u,
                                       Eigen::VectorXd& f) const {
  inner_->pressure_load(ctx, face, p, inner_values(u), f);
  f = t_.transpose() * f;
}

void TransformedElement::thermal_load(const ElementContext& ctx, Eigen::VectorXd& f) const {
  inner_->thermal_load(ctx, f);
  f = t_.transpose() * f;
}

void TransformedElement::results(const ElementContext& ctx, const Eigen::VectorXd& u,
                                 const Eigen::VectorXd& v, ElementResultValues& out) const {
  inner_->results(ctx, inner_values(u), t_ * v, out);
}

std::unique_ptr<Element> adapt_element(std::unique_ptr<Element> element, const Model& model,
                                       const ElementRecord& record,
                                       const std::shared_ptr<const DependentDofs>& dependent) {
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
  if (dependent && !dependent->empty() &&
      std::any_of(element->dofs().begin(), element->dofs().end(),
                  [&](const DofKey& k) { return dependent->find(k) != nullptr; })) {
    Element::ThermalExpansion thermal = element->thermal_expansion();
    element = std::make_unique<ConstrainedElement>(std::move(element), dependent);
    element->set_thermal_expansion(std::move(thermal));
  }
  return element;
}

}  // namespace impactfe
