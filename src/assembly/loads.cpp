#include "assembly/loads.h"

#include <fmt/format.h>

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

double table_value(const LoadPoint& at, const std::string& name) {
  IMPACTFE_CHECK(at.tables != nullptr && at.tables->count(name) != 0,
                 fmt::format("time function {} is not available at the load point", name));
  return at.tables->at(name).at(at.time);
}

bool has_tabular_loads(const LoadStep& step) {
  bool acel = false;
  for (const auto& t : step.acel_tables) acel = acel || !t.empty();
  bool pressures = false;
  for (const auto& [face, load] : step.pressures) pressures = pressures || load.tabular();
  return acel || pressures || !step.constraint_tables.empty() || !step.force_tables.empty();
}

ResolvedDofLoads::ResolvedDofLoads(const DofMap& dofs, const LoadStep& current,
                                   const LoadStep* previous, Kind kind) {
  const bool forces = kind == Kind::Forces;
  const auto& values = forces ? current.forces : current.constraints;
  const auto& tables = forces ? current.force_tables : current.constraint_tables;
  const std::map<DofKey, double>* before =
      previous ? (forces ? &previous->forces : &previous->constraints) : nullptr;
  for (const auto& [key, value] : values) {
    // A force on a slave of a constraint equation acts on its masters, Tᵀ F: a_j F on master j
    // (virtual work: F δu_s = Σ a_j F δu_j). Prescribed values on slaves are refused when the
    // structure is built.
    const DofDependence* slave = dofs.dependent() ? dofs.dependent()->find(key) : nullptr;
    if (slave != nullptr && forces) {
      const auto t = tables.find(key);
      for (const auto& [master, a] : slave->masters) {
        const int m = dofs.index(master);
        if (m < 0 || m >= dofs.n_free()) continue;
        entries_.push_back(
            {m, a * lookup(before, key), a * value, t == tables.end() ? "" : t->second, a});
      }
      continue;
    }
    const int i = dofs.index(key);
    // Forces act on free DOFs, prescribed values on constrained ones (inactive DOFs are -1).
    if (forces ? (i < 0 || i >= dofs.n_free()) : i < dofs.n_free()) continue;
    const auto t = tables.find(key);
    entries_.push_back({i, lookup(before, key), value, t == tables.end() ? "" : t->second});
  }
}

void ResolvedDofLoads::add_to(const LoadPoint& at, VectorXd& v) const {
  // A table's value at the point's time, else the KBC interpolation from the previous step.
  for (const Entry& e : entries_)
    v(e.index) += e.table.empty() ? interpolate(at, e.previous, e.value)
                                  : e.weight * table_value(at, e.table);
}

VectorXd nodal_forces(const DofMap& dofs, const LoadPoint& at) {
  VectorXd f = VectorXd::Zero(dofs.n_active());
  ResolvedDofLoads(dofs, *at.current, at.previous, ResolvedDofLoads::Kind::Forces).add_to(at, f);
  return f;
}

Vec3 frame_acceleration(const LoadPoint& at) {
  const Vec3 before = at.previous ? at.previous->acel : Vec3::Zero();
  Vec3 a;
  for (int d = 0; d < 3; ++d) {
    const std::string& table = at.current->acel_tables[static_cast<std::size_t>(d)];
    a(d) = table.empty() ? interpolate(at, before(d), at.current->acel(d)) : table_value(at, table);
  }
  return a;
}

RotationalLoads rotational_loads(const LoadPoint& at) {
  const RotationalLoads& now = at.current->rotation;
  const RotationalLoads before = at.previous ? at.previous->rotation : RotationalLoads{};
  RotationalLoads out;
  const auto ramp = [&](Vec3 RotationalLoads::*v) {
    for (int d = 0; d < 3; ++d) (out.*v)(d) = interpolate(at, (before.*v)(d), (now.*v)(d));
  };
  for (auto v : {&RotationalLoads::omega, &RotationalLoads::domega, &RotationalLoads::cg_location,
                 &RotationalLoads::cg_omega, &RotationalLoads::cg_domega})
    ramp(v);
  out.where = now.any() ? now.where : before.where;
  return out;
}

VectorXd rotational_inertia_load(const std::vector<std::unique_ptr<Element>>& elements,
                                 const DofMap& dofs, const ElementContext& ctx,
                                 const std::function<Vec3(int)>& position,
                                 const RotationalLoads& loads) {
  VectorXd f = VectorXd::Zero(dofs.n_active());
  const std::vector<LinearAccelerationField> fields{rotational_acceleration(loads)};
  if (fields.front().zero()) return f;
  Eigen::MatrixXd fe;
  for (std::size_t e = 0; e < elements.size(); ++e) {
    try {
      elements[e]->acceleration_field_load(ctx, fields, position, fe);
    } catch (...) {
      rethrow_at(loads.where);
    }
    const auto& idx = dofs.element_indices(e);
    for (std::size_t a = 0; a < idx.size(); ++a)
      if (idx[a] >= 0) f(idx[a]) += fe(static_cast<int>(a), 0);
  }
  return f;
}

VectorXd pressure_forces(const std::vector<std::unique_ptr<Element>>& elements, const DofMap& dofs,
                         const ElementContext& ctx, const LoadPoint& at, const VectorXd& u) {
  VectorXd f = VectorXd::Zero(dofs.n_active());
  if (at.current->pressures.empty()) return f;
  std::map<int, std::size_t> index;
  for (std::size_t e = 0; e < elements.size(); ++e) index[elements[e]->id()] = e;
  VectorXd ue, fe;
  for (const auto& [face, load] : at.current->pressures) {
    const auto it = index.find(face.element);
    if (it == index.end()) continue;
    std::array<double, 4> p = load.values;
    if (load.tabular()) {
      p.fill(table_value(at, load.table));
    } else {
      const SurfaceLoad* before = nullptr;
      if (at.previous) {
        const auto prev = at.previous->pressures.find(face);
        if (prev != at.previous->pressures.end() && !prev->second.tabular()) before = &prev->second;
      }
      for (std::size_t k = 0; k < 4; ++k)
        p[k] = interpolate(at, before ? before->values[k] : 0.0, load.values[k]);
    }
    const auto& idx = dofs.element_indices(it->second);
    ue.resize(static_cast<int>(idx.size()));
    for (std::size_t a = 0; a < idx.size(); ++a)
      ue(static_cast<int>(a)) = idx[a] >= 0 ? u(idx[a]) : 0.0;
    elements[it->second]->pressure_load(ctx, face.face, p, ue, fe);
    for (std::size_t a = 0; a < idx.size(); ++a)
      if (idx[a] >= 0) f(idx[a]) += fe(static_cast<int>(a));
  }
  return f;
}

VectorXd inertia_load(const std::vector<std::unique_ptr<Element>>& elements, const DofMap& dofs,
                      const ElementContext& ctx, const Vec3& acel) {
  if (acel.squaredNorm() == 0.0) return VectorXd::Zero(dofs.n_active());
  return inertia_loads(elements, dofs, ctx, acel).col(0);
}

Eigen::MatrixXd inertia_loads(const std::vector<std::unique_ptr<Element>>& elements,
                              const DofMap& dofs, const ElementContext& ctx,
                              const Eigen::Matrix3Xd& accelerations) {
  Eigen::MatrixXd f = Eigen::MatrixXd::Zero(dofs.n_active(), accelerations.cols());
  Eigen::MatrixXd fe;
  for (std::size_t e = 0; e < elements.size(); ++e) {
    elements[e]->frame_acceleration_load(ctx, accelerations, fe);
    const auto& idx = dofs.element_indices(e);
    for (std::size_t a = 0; a < idx.size(); ++a)
      if (idx[a] >= 0) f.row(idx[a]) += fe.row(static_cast<int>(a));
  }
  return f;
}

FrameAccelerationLoad::FrameAccelerationLoad(const std::vector<std::unique_ptr<Element>>& elements,
                                             const DofMap& dofs, const ElementContext& ctx) {
  // The three unit loads in one pass: each element's mass once, not once per direction (the
  // shells' consistent mass was 2 % of the thesis helmet's run, issue 11).
  const Eigen::MatrixXd unit = inertia_loads(elements, dofs, ctx, Eigen::Matrix3d::Identity());
  for (int d = 0; d < 3; ++d) unit_[static_cast<std::size_t>(d)] = unit.col(d);
}

VectorXd FrameAccelerationLoad::operator()(const Vec3& acel) const {
  VectorXd f;
  assign(acel, unit_[0].size(), f);
  return f;
}

void FrameAccelerationLoad::assign(const Vec3& acel, Eigen::Index n, VectorXd& f) const {
  f.setZero(unit_[0].size() == n ? unit_[0].size() : n);
  if (unit_[0].size() != n) return;
  for (int d = 0; d < 3; ++d)
    if (acel(d) != 0.0) f += acel(d) * unit_[static_cast<std::size_t>(d)];
}

VectorXd prescribed_displacements(const DofMap& dofs, const LoadPoint& at) {
  VectorXd u = VectorXd::Zero(dofs.n_active());
  ResolvedDofLoads(dofs, *at.current, at.previous, ResolvedDofLoads::Kind::Constraints)
      .add_to(at, u);
  return u;
}

std::set<DofKey> constrained_set(const LoadStep& step) {
  std::set<DofKey> out;
  for (const auto& entry : step.constraints) out.insert(entry.first);
  return out;
}

}  // namespace impactfe
