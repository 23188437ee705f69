#include "assembly/dof_map.h"

#include <algorithm>

namespace impactfe {

DofMap::DofMap(const std::vector<std::unique_ptr<Element>>& elements,
               const std::set<DofKey>& constrained, const std::vector<std::vector<DofKey>>& coupled,
               std::shared_ptr<const DependentDofs> dependent)
    : dependent_(std::move(dependent)) {
  // The active DOFs, sorted (node, then direction): a sort of the element DOF lists instead of
  // a tree insertion per entry (at 6·10⁵ DOFs that tree was a second of the set-up).
  std::vector<DofKey> active;
  for (const auto& e : elements) active.insert(active.end(), e->dofs().begin(), e->dofs().end());
  std::sort(active.begin(), active.end());
  active.erase(std::unique(active.begin(), active.end()), active.end());
  // Free DOFs in node order (a natural, locality-preserving order; CHOLMOD reorders anyway).
  std::vector<bool> held(active.size());
  for (std::size_t i = 0; i < active.size(); ++i) held[i] = constrained.count(active[i]) > 0;
  // Coupled sets: prime_of[i] is the position of the DOF that DOF i is eliminated onto (-1: none).
  std::vector<long> prime_of(active.size(), -1);
  for (const auto& set : coupled) {
    long prime = -1;
    bool set_held = false;
    std::vector<long> members;
    for (const DofKey& k : set) {
      const auto it = std::lower_bound(active.begin(), active.end(), k);
      if (it == active.end() || *it != k) continue;  // a DOF no element carries
      const long pos = it - active.begin();
      if (prime_of[static_cast<std::size_t>(pos)] >= 0 || pos == prime) continue;
      set_held = set_held || held[static_cast<std::size_t>(pos)];
      if (prime < 0)
        prime = pos;
      else
        members.push_back(pos);
    }
    if (prime < 0) continue;
    held[static_cast<std::size_t>(prime)] = set_held;
    for (long m : members) prime_of[static_cast<std::size_t>(m)] = prime;
  }
  keys_.reserve(active.size());
  for (std::size_t i = 0; i < active.size(); ++i)
    if (!held[i] && prime_of[i] < 0) keys_.push_back(active[i]);
  n_free_ = static_cast<int>(keys_.size());
  for (std::size_t i = 0; i < active.size(); ++i)
    if (held[i] && prime_of[i] < 0) keys_.push_back(active[i]);
  sorted_index_.resize(active.size());
  int next_free = 0, next_held = n_free_;
  for (std::size_t i = 0; i < active.size(); ++i)
    if (prime_of[i] < 0) sorted_index_[i] = held[i] ? next_held++ : next_free++;
  for (std::size_t i = 0; i < active.size(); ++i)
    if (prime_of[i] >= 0) {
      sorted_index_[i] = sorted_index_[static_cast<std::size_t>(prime_of[i])];
      aliases_.emplace_back(active[i], sorted_index_[i]);
    }
  // A copy, not a move: `active` holds every element's DOF list (four times the active DOFs on
  // a shell mesh) in its capacity (issue 11: 7 MB on the 155 522-DOF dome).
  sorted_.assign(active.begin(), active.end());
  std::vector<DofKey>().swap(active);
  element_indices_.reserve(elements.size());
  for (const auto& e : elements) {
    std::vector<int> idx;
    idx.reserve(e->dofs().size());
    for (const auto& k : e->dofs()) idx.push_back(index(k));
    element_indices_.push_back(std::move(idx));
  }
}

int DofMap::index(const DofKey& key) const {
  const auto it = std::lower_bound(sorted_.begin(), sorted_.end(), key);
  if (it == sorted_.end() || *it != key) return -1;
  return sorted_index_[static_cast<std::size_t>(it - sorted_.begin())];
}

}  // namespace impactfe
