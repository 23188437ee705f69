#include "assembly/constraint_equations.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace impactfe {

namespace {

/// Adds c·(dependence of `key`, or the DOF itself when retained) to the sum.
void add_term(std::map<DofKey, double>& sum, double& constant, const DofKey& key, double c,
              const std::map<DofKey, DofDependence>& slaves) {
  const auto it = slaves.find(key);
  if (it == slaves.end()) {
    sum[key] += c;
    return;
  }
  for (const auto& [master, a] : it->second.masters) sum[master] += c * a;
  constant += c * it->second.constant;
}

}  // namespace

void DependentDofs::add_all(const std::vector<ConstraintEquation>& equations,
                            const std::set<DofKey>& unavailable) {
  std::map<DofKey, int> occurrences;
  for (const auto& eq : equations) {
    std::set<DofKey> in_it;
    for (const auto& t : eq.terms)
      if (t.coefficient != 0.0) in_it.insert(t.dof);
    for (const auto& key : in_it) ++occurrences[key];
  }
  for (const auto& eq : equations) add(eq, unavailable, &occurrences);
}

void DependentDofs::add(const ConstraintEquation& eq, const std::set<DofKey>& unavailable,
                        const std::map<DofKey, int>* occurrences) {
  // Σ C_i u_i = CONST with the earlier slaves substituted: Σ b_j u_j = rhs over retained DOFs
  // (Gaussian elimination of the equations one by one, Felippa §8.3.4).
  std::map<DofKey, double> b;
  double lhs_constant = 0.0;
  double scale = 0.0;
  for (const auto& t : eq.terms) {
    if (t.coefficient == 0.0) continue;
    scale = std::max(scale, std::abs(t.coefficient));
    add_term(b, lhs_constant, t.dof, t.coefficient, slaves_);
  }
  if (scale == 0.0)
    throw InputError(eq.where, fmt::format("constraint equation {} has no term with a non-zero "
                                           "coefficient",
                                           eq.id));
  const double rhs = eq.constant - lhs_constant;
  const auto usable = [&](const DofKey& key) {
    const auto it = b.find(key);
    return it != b.end() && std::abs(it->second) > 1e-12 * scale && unavailable.count(key) == 0;
  };
  const auto unique = [&](const DofKey& key) {
    if (occurrences == nullptr) return true;
    const auto n = occurrences->find(key);
    return n == occurrences->end() || n->second <= 1;
  };
  // The slave: MAPDL's first unique DOF of the equation's terms; else its first usable term;
  // else any usable DOF the substitution brought in.
  std::optional<DofKey> slave;
  for (const auto& t : eq.terms)
    if (usable(t.dof) && unique(t.dof)) {
      slave = t.dof;
      break;
    }
  if (!slave)
    for (const auto& t : eq.terms)
      if (usable(t.dof)) {
        slave = t.dof;
        break;
      }
  if (!slave)
    for (const auto& [key, c] : b)
      if (usable(key)) {
        slave = key;
        break;
      }
  if (!slave) {
    bool any = false;
    for (const auto& [key, c] : b) any = any || std::abs(c) > 1e-12 * scale;
    throw InputError(
        eq.where,
        any ? fmt::format("constraint equation {}: every DOF left in it (the earlier equations "
                          "substituted) is held by D or in a coupled set: none is left for it to "
                          "eliminate",
                          eq.id)
            : fmt::format("constraint equation {} is redundant: with the earlier equations "
                          "substituted it reads 0 = {:g}",
                          eq.id, rhs));
  }
  // u_s = (rhs − Σ_{j≠s} b_j u_j) / b_s.
  const double bs = b.at(*slave);
  DofDependence dep;
  dep.where = eq.where;
  dep.constant = rhs / bs;
  for (const auto& [key, c] : b)
    if (key != *slave && c != 0.0) dep.masters.emplace_back(key, -c / bs);
  // The earlier slaves that name the new slave now depend on its masters instead.
  for (auto& [key, other] : slaves_) {
    const auto named = std::find_if(other.masters.begin(), other.masters.end(),
                                    [&](const auto& m) { return m.first == *slave; });
    if (named == other.masters.end()) continue;
    const double a = named->second;
    std::map<DofKey, double> resolved;
    for (const auto& [master, c] : other.masters)
      if (master != *slave) resolved[master] += c;
    for (const auto& [master, c] : dep.masters) resolved[master] += a * c;
    other.constant += a * dep.constant;
    other.masters.clear();
    for (const auto& [master, c] : resolved)
      if (c != 0.0) other.masters.emplace_back(master, c);
  }
  slaves_[*slave] = std::move(dep);
}

bool DependentDofs::has_constants() const {
  for (const auto& [key, dep] : slaves_)
    if (dep.constant != 0.0) return true;
  return false;
}

}  // namespace impactfe
