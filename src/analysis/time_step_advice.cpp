#include "analysis/time_step_advice.h"

#include <cmath>
#include <functional>
#include <map>

namespace impactfe {

double ContactFrequency::period() const {
  return 2.0 * M_PI / omega;
}

ContactFrequencyEstimator::ContactFrequencyEstimator(
    const std::vector<std::unique_ptr<Element>>& elements, const DofMap& dofs,
    const VectorXd& mass_row_sums)
    : elements_(elements) {
  // Bodies: nodes joined through elements without a status (union-find on node ids).
  std::map<int, int> parent;
  std::function<int(int)> find = [&](int n) {
    auto it = parent.find(n);
    if (it == parent.end() || it->second == n) return parent[n] = n;
    return it->second = find(it->second);
  };
  for (const auto& element : elements) {
    if (element->has_status()) continue;
    const auto& keys = element->dofs();
    for (const auto& k : keys) parent[find(k.node)] = find(keys.front().node);
  }
  // Body mass per direction: row sums of M (exact for lumped, total mass for consistent).
  std::map<std::pair<int, int>, double> body_mass;
  for (int i = 0; i < dofs.n_active(); ++i) {
    const DofKey& key = dofs.key(i);
    body_mass[{find(key.node), static_cast<int>(key.dof)}] += mass_row_sums(i);
  }
  for (std::size_t e = 0; e < elements.size(); ++e) {
    if (!elements[e]->has_status()) continue;
    double flexibility = 0.0;  // 1/m_I + 1/m_J
    for (int index : dofs.element_indices(e)) {
      if (index >= dofs.n_free()) continue;  // ground
      const DofKey& key = dofs.key(index);
      const double m = body_mass[{find(key.node), static_cast<int>(key.dof)}];
      if (m > 0.0) flexibility += 1.0 / m;
    }
    if (flexibility > 0.0) members_.push_back({e, flexibility});
  }
}

std::optional<ContactFrequency> ContactFrequencyEstimator::highest(bool closed_only) const {
  std::optional<ContactFrequency> highest;
  for (const Member& m : members_) {
    if (closed_only && elements_[m.element]->status() == GapStatus::Open) continue;
    const double k = elements_[m.element]->contact_stiffness();
    if (k <= 0.0) continue;
    const double omega = std::sqrt(k * m.flexibility);
    if (!highest || omega > highest->omega)
      highest = ContactFrequency{omega, elements_[m.element]->id()};
  }
  return highest;
}

}  // namespace impactfe
