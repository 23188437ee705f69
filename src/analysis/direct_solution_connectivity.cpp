/// Elements whose DOF list follows the deformation (elements/connectivity.h: contact nodes on a
/// deformable target with large sliding): after an accepted step they re-find their DOFs, and
/// when a list changed the DOFs are renumbered before the next step.
///
/// Why a renumbering between steps and not a fixed superset: the facets a sliding node may meet
/// are not known when the model is built (the whole target, in general), and a superset that
/// large would couple every contact node to every target node. Within a step the lists are
/// fixed, so Newton iterates on a static pattern; a contact node keeps a margin of candidates
/// (1.5 × its pinball, target_surface.h) and changes its list once per half pinball of travel.
/// The renumbering is the one a change of the constraint set makes at a load step (DofMap,
/// Assembler, status loop, solver, condensation), except that the integrator continues: its
/// history is remapped by DOF key, so the time scheme (Houbolt's past displacements included)
/// carries on as if nothing happened; the linear part of a condensed transient is factorized
/// again for the new contact DOF set (its cost is the price of a change, not of a step).
#include <fmt/format.h>

#include "analysis/direct_solution.h"
#include "core/log.h"
#include "elements/connectivity.h"
#include "time/integrator_history.h"

namespace impactfe {

namespace {

VectorXd remap_keys(const VectorXd& values, const DofMap& from, const DofMap& to) {
  VectorXd out = VectorXd::Zero(to.n_active());
  if (values.size() != from.n_active()) return out;
  for (int i = 0; i < to.n_active(); ++i) {
    const int j = from.index(to.key(i));
    if (j >= 0) out(i) = values(j);
  }
  return out;
}

}  // namespace

void DirectSolution::remap_integrator(const DofMap& from, const DofMap& to) {
  auto* history = dynamic_cast<IntegratorHistory*>(integrator_.get());
  if (history == nullptr) {
    dynamics_started_ = false;
    return;
  }
  std::vector<VectorXd> remapped;
  for (const VectorXd& h : history->history()) remapped.push_back(remap_keys(h, from, to));
  history->restore(remapped, integrator_->step());
}

void DirectSolution::refresh_connectivity() {
  const auto& elements = structure_.elements();
  if (!connectivity_) {
    connectivity_.emplace();
    for (std::size_t e = 0; e < elements.size(); ++e)
      if (const auto* update = dynamic_cast<ConnectivityUpdate*>(elements[e].get());
          update != nullptr && update->updates_connectivity())
        connectivity_->push_back(e);
  }
  if (connectivity_->empty() || !dofs_) return;
  const Model& model = structure_.model();
  const NodePositions positions{[&](int node) -> Eigen::Vector3d {
                                  Eigen::Vector3d x = model.nodes.at(node).x;
                                  for (int d = 0; d < 3; ++d) {
                                    const int i = dofs_->index({node, static_cast<Dof>(d)});
                                    if (i >= 0) x(d) += u_(i);
                                  }
                                  return x;
                                },
                                ++refresh_passes_};
  bool changed = false;
  VectorXd ue;
  for (std::size_t e : *connectivity_) {
    assembler_->gather(e, u_, ue);
    changed = dynamic_cast<ConnectivityUpdate*>(elements[e].get())->refresh_dofs(ue, positions) ||
              changed;
  }
  if (!changed) return;
  ++renumberings_;
  Log::debug("t = {:g}: contact DOF lists changed (large sliding), DOFs renumbered", time_);
  renumber(constrained_, true);
  if (resolved_step_ != nullptr) {
    forces_ = ResolvedDofLoads(*dofs_, *resolved_step_, resolved_previous_,
                               ResolvedDofLoads::Kind::Forces);
    prescribed_ = ResolvedDofLoads(*dofs_, *resolved_step_, resolved_previous_,
                                   ResolvedDofLoads::Kind::Constraints);
  }
}

}  // namespace impactfe
