#include "assembly/dof_map.h"

namespace impactfe {

DofMap::DofMap(const std::vector<std::unique_ptr<Element>>& elements,
               const std::set<DofKey>& constrained) {
  std::set<DofKey> active;
  for (const auto& e : elements)
    for (const auto& k : e->dofs()) active.insert(k);
  // Free DOFs in node order (a natural, locality-preserving order; CHOLMOD reorders anyway).
  for (const auto& k : active)
    if (!constrained.count(k)) keys_.push_back(k);
  n_free_ = static_cast<int>(keys_.size());
  for (const auto& k : active)
    if (constrained.count(k)) keys_.push_back(k);
  for (int i = 0; i < n_active(); ++i) index_[keys_[static_cast<std::size_t>(i)]] = i;
  element_indices_.reserve(elements.size());
  for (const auto& e : elements) {
    std::vector<int> idx;
    idx.reserve(e->dofs().size());
    for (const auto& k : e->dofs()) idx.push_back(index_.at(k));
    element_indices_.push_back(std::move(idx));
  }
}

int DofMap::index(const DofKey& key) const {
  auto it = index_.find(key);
  return it == index_.end() ? -1 : it->second;
}

}  // namespace impactfe
