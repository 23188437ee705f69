#pragma once
/// Linear constraint equations by master-slave elimination (CE, CERIG, the MPC184 rigid link and
/// beam). Each equation CONST = Σ C_i u_i eliminates its first term's DOF, the slave s, as
/// MAPDL does:  u_s = (CONST − Σ_{i≠s} C_i u_i) / C_s.
/// Written for all slaves at once, u = T u_r + g (u_r: the retained DOFs), the equations of
/// motion become Tᵀ K T u_r = Tᵀ (f − K g) and Tᵀ M T ü_r (Felippa, "Introduction to Finite
/// Element Methods", §8.3; Cook et al., "Concepts and Applications of FEA", §9.2). T acts DOF
/// by DOF, so it is applied element by element (assembly/element_adapters.h): an element at a
/// slave DOF enters with its matrices and forces transformed, and the DOF map, the assembler and
/// every driver see only retained DOFs. The constant g enters the element through its total
/// displacement, so it acts on the total (a Newton increment only corrects toward it).
///
/// Slaves depend on retained DOFs only: a slave that appears in a later equation, or an earlier
/// equation that names a later slave, is substituted out here.
#include <map>
#include <set>
#include <vector>

#include "core/model.h"

namespace impactfe {

/// u_s = Σ a_j u_j + g of one slave DOF, over retained DOFs.
struct DofDependence {
  std::vector<std::pair<DofKey, double>> masters;
  double constant = 0.0;
  SourceLocation where;  // the equation's command
};

class DependentDofs {
 public:
  DependentDofs() = default;
  /// Eliminates one DOF of the equation, the earlier slaves substituted into it first. The
  /// slave is MAPDL's "first unique DOF" (CE notes): the first term whose DOF is retained, not in
  /// `unavailable` (held by D, in a CP set) and in no other equation (`occurrences`: the number
  /// of equations each DOF appears in; null: all unique); when no term is unique, the first
  /// usable one, else any retained DOF the substitution brought in (the constraint is the same
  /// whichever DOF is eliminated, so is the solution). InputError at the equation's command when
  /// none is usable (all held) or the equation is redundant (0 = rhs after substitution).
  void add(const ConstraintEquation& equation, const std::set<DofKey>& unavailable = {},
           const std::map<DofKey, int>* occurrences = nullptr);
  /// All equations in order, with the occurrences counted over them.
  void add_all(const std::vector<ConstraintEquation>& equations,
               const std::set<DofKey>& unavailable);

  bool empty() const { return slaves_.empty(); }
  const std::map<DofKey, DofDependence>& slaves() const { return slaves_; }
  const DofDependence* find(const DofKey& key) const {
    const auto it = slaves_.find(key);
    return it == slaves_.end() ? nullptr : &it->second;
  }
  /// True when some slave's constant is not zero.
  bool has_constants() const;

 private:
  std::map<DofKey, DofDependence> slaves_;
};

}  // namespace impactfe
