#include "analysis/step_loads.h"

namespace impactfe {

void StepLoads::resolve(const Discretisation& disc, const LoadStep& step,
                        const LoadStep* previous) {
  step_ = &step;
  previous_ = previous;
  resolve_again(disc);
}

void StepLoads::resolve_again(const Discretisation& disc) {
  if (step_ == nullptr) return;
  forces_ = ResolvedDofLoads(disc.dofs(), *step_, previous_, ResolvedDofLoads::Kind::Forces);
  prescribed_ =
      ResolvedDofLoads(disc.dofs(), *step_, previous_, ResolvedDofLoads::Kind::Constraints);
}

LoadPoint StepLoads::at(double fraction, double time) const {
  return LoadPoint{step_, previous_, fraction, time, &structure_.model().time_functions};
}

void StepLoads::external_force(const Discretisation& disc, const LoadPoint& at, const VectorXd& u,
                               VectorXd& f) const {
  const DofMap& dofs = disc.dofs();
  disc.frame_load().assign(frame_acceleration(at), dofs.n_active(), f);
  if (at.current == step_) {
    forces_.add_to(at, f);
  } else {
    f += nodal_forces(dofs, at);
  }
  if (!at.current->pressures.empty())
    f += pressure_forces(structure_.elements(), dofs, structure_.context(), at, u);
}

void StepLoads::prescribe(const Discretisation& disc, const LoadPoint& at, VectorXd& u) const {
  const int nc = disc.dofs().n_constrained();
  u.tail(nc).setZero();  // automatically constrained DOFs (no D) stay at 0
  if (at.current == step_)
    prescribed_.add_to(at, u);
  else
    u.tail(nc) = prescribed_displacements(disc.dofs(), at).tail(nc);
}

}  // namespace impactfe
