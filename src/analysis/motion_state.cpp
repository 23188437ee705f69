#include "analysis/motion_state.h"

#include "time/integrator_history.h"

namespace impactfe {

VectorXd remap_by_key(const VectorXd& values, const DofMap& from, const DofMap& to) {
  VectorXd out = VectorXd::Zero(to.n_active());
  if (values.size() != from.n_active()) return out;
  for (int i = 0; i < to.n_active(); ++i) {
    const int j = from.index(to.key(i));
    if (j >= 0) out(i) = values(j);
  }
  return out;
}

void MotionState::start(const DofMap& dofs, const Model& model) {
  u = VectorXd::Zero(dofs.n_active());
  v = VectorXd::Zero(dofs.n_active());
  a = VectorXd::Zero(dofs.n_active());
  for (const auto& [key, ic] : model.initial_conditions) {
    const int i = dofs.index(key);
    if (i < 0) continue;
    u(i) = ic.displacement;
    v(i) = ic.velocity;
  }
  f_ext_old = f_int_old = f_damp_old = VectorXd::Zero(dofs.n_active());
}

void MotionState::remap(const DofMap& from, const DofMap& to) {
  for (VectorXd* x : {&u, &v, &a, &f_ext_old, &f_int_old, &f_damp_old, &reactions})
    *x = remap_by_key(*x, from, to);
}

bool remap_integrator_history(TimeIntegrator& integrator, const DofMap& from, const DofMap& to) {
  auto* history = dynamic_cast<IntegratorHistory*>(&integrator);
  if (history == nullptr) return false;
  std::vector<VectorXd> remapped;
  for (const VectorXd& h : history->history()) remapped.push_back(remap_by_key(h, from, to));
  history->restore(remapped, integrator.step());
  return true;
}

}  // namespace impactfe
