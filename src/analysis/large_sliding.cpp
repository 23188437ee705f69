#include "analysis/large_sliding.h"

#include <fmt/format.h>

#include "elements/connectivity.h"

namespace impactfe {

bool LargeSliding::refresh(const Discretisation& disc, const VectorXd& u) {
  const auto& elements = structure_.elements();
  if (!members_) {
    members_.emplace();
    for (std::size_t e = 0; e < elements.size(); ++e)
      if (const auto* update = dynamic_cast<ConnectivityUpdate*>(elements[e].get());
          update != nullptr && update->updates_connectivity())
        members_->push_back(e);
  }
  if (members_->empty()) return false;
  const Model& model = structure_.model();
  const DofMap& dofs = disc.dofs();
  const NodePositions positions{[&](int node) -> Eigen::Vector3d {
                                  Eigen::Vector3d x = model.nodes.at(node).x;
                                  for (int d = 0; d < 3; ++d) {
                                    const int i = dofs.index({node, static_cast<Dof>(d)});
                                    if (i >= 0) x(d) += u(i);
                                  }
                                  return x;
                                },
                                ++passes_};
  bool changed = false;
  VectorXd ue;
  for (std::size_t e : *members_) {
    disc.assembler().gather(e, u, ue);
    changed = dynamic_cast<ConnectivityUpdate*>(elements[e].get())->refresh_dofs(ue, positions) ||
              changed;
  }
  if (changed) ++renumberings_;
  return changed;
}

std::string LargeSliding::summary() const {
  if (renumberings_ == 0) return {};
  return fmt::format(
      "large sliding: the contact DOF lists changed after {} of {} accepted steps (DOFs "
      "renumbered then)",
      renumberings_, passes_);
}

}  // namespace impactfe
