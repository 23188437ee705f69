#pragma once
/// Equation numbering. Active DOFs are the union of the DOFs of the elements present; the free
/// ones come first (0 .. n_free-1), the constrained ones after them (n_free .. n_active-1), so
/// that constraints are eliminated, not penalised (thesis eq. 2-7/2-8).
#include <map>
#include <memory>
#include <set>
#include <vector>

#include "assembly/constraint_equations.h"
#include "core/dof.h"
#include "elements/element.h"

namespace impactfe {

class DofMap {
 public:
  DofMap() = default;
  /// `constrained`: DOFs held by D (and automatic constraints); those not active are ignored.
  /// `coupled`: sets of DOFs that share one value (CP): each set's first active DOF (the prime)
  /// carries the equation and the others are eliminated onto it (they get its index), so the
  /// element matrices of the set's DOFs add up in one row and column. A set with a held member
  /// is held as a whole.
  /// `dependent`: the slaves of constraint equations (CE, CERIG, MPC184), eliminated onto their
  /// masters by the element adapters (assembly/element_adapters.h), so no element carries them
  /// and they are not active; kept here for the loads (F on a slave acts as Tᵀ F on its masters)
  /// and the nodal results (u_s = Σ a_j u_j + g). CP is the special case u_s = u_prime, which
  /// needs no transformation: the coupled DOFs share an index (the aliases).
  DofMap(const std::vector<std::unique_ptr<Element>>& elements, const std::set<DofKey>& constrained,
         const std::vector<std::vector<DofKey>>& coupled = {},
         std::shared_ptr<const DependentDofs> dependent = nullptr);

  int n_active() const { return static_cast<int>(keys_.size()); }
  int n_free() const { return n_free_; }
  int n_constrained() const { return n_active() - n_free_; }
  /// Index of a DOF (free: < n_free), -1 when the DOF is not active.
  int index(const DofKey& key) const;
  bool is_active(const DofKey& key) const { return index(key) >= 0; }
  const DofKey& key(int index) const { return keys_[static_cast<std::size_t>(index)]; }
  const std::vector<DofKey>& keys() const { return keys_; }
  /// Global indices of element e's DOFs, in element DOF order.
  const std::vector<int>& element_indices(std::size_t e) const { return element_indices_[e]; }
  /// All DOFs the elements carry, as a set (for validation of loads, masters); the eliminated
  /// DOFs of coupled sets are not in it.
  std::set<DofKey> active_set() const { return {keys_.begin(), keys_.end()}; }
  /// The eliminated DOFs of coupled sets and the index of their prime DOF (nodal results).
  const std::vector<std::pair<DofKey, int>>& aliases() const { return aliases_; }
  /// The slaves of constraint equations (null: none).
  const DependentDofs* dependent() const { return dependent_.get(); }

 private:
  std::vector<DofKey> keys_;
  std::vector<DofKey> sorted_;     // the active DOFs in DofKey order
  std::vector<int> sorted_index_;  // sorted_index_[k]: the index of sorted_[k]
  std::vector<std::vector<int>> element_indices_;
  std::vector<std::pair<DofKey, int>> aliases_;
  int n_free_ = 0;
  std::shared_ptr<const DependentDofs> dependent_;
};

}  // namespace impactfe
