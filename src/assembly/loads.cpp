#include "assembly/loads.h"

namespace impactfe {

namespace {
double lookup(const std::map<DofKey, double>* table, const DofKey& key) {
  if (!table) return 0.0;
  auto it = table->find(key);
  return it == table->end() ? 0.0 : it->second;
}
}  // namespace

double interpolate(const LoadPoint& at, double previous_value, double current_value) {
  if (at.current->stepped) return current_value;
  return previous_value + at.fraction * (current_value - previous_value);
}

VectorXd nodal_forces(const DofMap& dofs, const LoadPoint& at) {
  VectorXd f = VectorXd::Zero(dofs.n_active());
  for (const auto& [key, value] : at.current->forces) {
    const int i = dofs.index(key);
    if (i < 0 || i >= dofs.n_free()) continue;
    const double before = lookup(at.previous ? &at.previous->forces : nullptr, key);
    f(i) = interpolate(at, before, value);
  }
  return f;
}

Vec3 frame_acceleration(const LoadPoint& at) {
  const Vec3 before = at.previous ? at.previous->acel : Vec3::Zero();
  Vec3 a;
  for (int d = 0; d < 3; ++d) a(d) = interpolate(at, before(d), at.current->acel(d));
  return a;
}

VectorXd inertia_load(const std::vector<std::unique_ptr<Element>>& elements, const DofMap& dofs,
                      const ElementContext& ctx, const Vec3& acel) {
  VectorXd f = VectorXd::Zero(dofs.n_active());
  if (acel.squaredNorm() == 0.0) return f;
  VectorXd fe;
  for (std::size_t e = 0; e < elements.size(); ++e) {
    elements[e]->frame_acceleration_load(ctx, acel, fe);
    const auto& idx = dofs.element_indices(e);
    for (std::size_t a = 0; a < idx.size(); ++a)
      if (idx[a] >= 0) f(idx[a]) += fe(static_cast<int>(a));
  }
  return f;
}

FrameAccelerationLoad::FrameAccelerationLoad(const std::vector<std::unique_ptr<Element>>& elements,
                                             const DofMap& dofs, const ElementContext& ctx) {
  for (int d = 0; d < 3; ++d)
    unit_[static_cast<std::size_t>(d)] = inertia_load(elements, dofs, ctx, Vec3::Unit(d));
}

VectorXd FrameAccelerationLoad::operator()(const Vec3& acel) const {
  VectorXd f = VectorXd::Zero(unit_[0].size());
  for (int d = 0; d < 3; ++d)
    if (acel(d) != 0.0) f += acel(d) * unit_[static_cast<std::size_t>(d)];
  return f;
}

VectorXd prescribed_displacements(const DofMap& dofs, const LoadPoint& at) {
  VectorXd u = VectorXd::Zero(dofs.n_active());
  for (const auto& [key, value] : at.current->constraints) {
    const int i = dofs.index(key);
    if (i < dofs.n_free()) continue;  // inactive DOFs are -1 < n_free as well
    const double before = lookup(at.previous ? &at.previous->constraints : nullptr, key);
    u(i) = interpolate(at, before, value);
  }
  return u;
}

std::set<DofKey> constrained_set(const LoadStep& step) {
  std::set<DofKey> out;
  for (const auto& entry : step.constraints) out.insert(entry.first);
  return out;
}

}  // namespace impactfe
