// The constraint equations of a structure (CE, CERIG, MPC184) and the checks of what they
// eliminate (assembly/constraint_equations.h).
#include <fmt/format.h>

#include <algorithm>
#include <set>

#include "analysis/structure.h"
#include "core/log.h"
#include "elements/kinematic_constraint.h"

namespace impactfe {

namespace {

/// CERIG: the slave DOFs that get an equation, by the master's DOFs (3-D: ROTX ROTY ROTZ;
/// 2-D: ROTZ alone, no UZ), as MAPDL's CERIG writes them. InputError when the master carries
/// no rotations (MAPDL's equations name them) or a label has no 2-D form.
std::vector<ConstraintEquation> rigid_region(const Model& model, const RigidRegion& region,
                                             const std::set<DofKey>& carried) {
  const auto has = [&](int node, Dof d) { return carried.count(DofKey{node, d}) != 0; };
  const int m = region.master;
  const bool three_d = has(m, Dof::ROTX) && has(m, Dof::ROTY) && has(m, Dof::ROTZ);
  const bool two_d =
      !three_d && has(m, Dof::ROTZ) && !has(m, Dof::ROTX) && !has(m, Dof::ROTY) && !has(m, Dof::UZ);
  if (!three_d && !two_d)
    throw InputError(region.where,
                     fmt::format("master node {} carries {} in the elements; a rigid region "
                                 "writes equations on the master's rotations (ROTX ROTY ROTZ in "
                                 "3-D, ROTZ with UX UY in 2-D): attach an element with rotations "
                                 "(a beam, MASS21 with rotary inertia) to the master",
                                 m, has(m, Dof::ROTZ) ? "only some rotations" : "no rotations"));
  std::vector<Dof> labels;
  if (!region.only.empty()) {
    for (Dof d : region.only) {
      if (two_d && (d == Dof::UZ || d == Dof::ROTX || d == Dof::ROTY))
        throw InputError(region.where,
                         fmt::format("{} has no 2-D form (master node {} carries UX UY "
                                     "ROTZ)",
                                     dof_name(d), m));
      labels.push_back(d);
    }
  } else {
    if (region.translations) {
      labels.push_back(Dof::UX);
      labels.push_back(Dof::UY);
      if (three_d) labels.push_back(Dof::UZ);
    }
    if (region.rotations) {
      if (three_d) {
        labels.push_back(Dof::ROTX);
        labels.push_back(Dof::ROTY);
      }
      labels.push_back(Dof::ROTZ);
    }
  }
  const auto node = [&](int id) -> const Node& {
    const auto it = model.nodes.find(id);
    if (it == model.nodes.end())
      throw InputError(region.where, fmt::format("node {} of the rigid region no longer exists "
                                                 "(deleted or renumbered after CERIG)",
                                                 id));
    return it->second;
  };
  const Node& master = node(m);
  std::vector<ConstraintEquation> out;
  for (int s : region.slaves) {
    if (s == m) continue;
    const Node& slave = node(s);
    if (slave.rotated() || master.rotated())
      throw InputError(region.where,
                       fmt::format("node {} has a rotated nodal coordinate system; rigid "
                                   "regions are written in global axes here",
                                   slave.rotated() ? s : m));
    // Only the DOFs the slave carries: an equation on a DOF no element has constrains nothing.
    std::vector<Dof> dofs;
    for (Dof d : labels)
      if (has(s, d)) dofs.push_back(d);
    for (auto& eq : rigid_region_equations(m, master.x, s, slave.x, three_d, dofs, region.where))
      out.push_back(std::move(eq));
  }
  return out;
}

}  // namespace

void Structure::eliminate_constraint_equations(const std::vector<LoadStep>* steps) {
  const Model& model = model_;
  std::vector<ConstraintEquation> equations;
  for (const auto& [id, eq] : model.constraint_equations) equations.push_back(eq);
  if (!model.rigid_regions.empty()) {
    if (options_.large_deflection)
      throw NotImplementedError(model.rigid_regions.front().where,
                                "CERIG under NLGEOM,ON: a rigid region needs large-rotation "
                                "constraints there, and its equations are those of small "
                                "rotations; solve with NLGEOM,OFF or model the region with "
                                "stiff beams");
    std::set<DofKey> carried;
    for (const auto& e : elements_) carried.insert(e->dofs().begin(), e->dofs().end());
    int next = equations.empty() ? 1 : equations.back().id + 1;
    for (const RigidRegion& region : model.rigid_regions)
      for (auto& eq : rigid_region(model, region, carried)) {
        eq.id = next++;
        equations.push_back(std::move(eq));
      }
  }
  for (const auto& e : elements_) {
    const auto* constraint = dynamic_cast<const KinematicConstraint*>(e.get());
    if (constraint == nullptr) continue;
    const auto own = constraint->constraint_equations();
    if (options_.large_deflection && constraint->is_rigid_body())
      throw NotImplementedError(own.empty() ? SourceLocation{} : own.front().where,
                                fmt::format("element {} ({}) under NLGEOM,ON: a rigid link needs "
                                            "large-rotation constraints there, and its equations "
                                            "are those of small rotations; solve with NLGEOM,OFF",
                                            e->id(), e->family()));
    for (const auto& eq : own) equations.push_back(eq);
  }
  if (equations.empty()) return;
  // A slave is eliminated onto its masters: it cannot also be held by D or be in a CP set, so
  // those DOFs are never chosen as slaves (MAPDL's "unique" DOF of an equation).
  std::set<DofKey> unavailable;
  if (steps != nullptr)
    for (const LoadStep& step : *steps)
      for (const auto& [key, value] : step.constraints) unavailable.insert(key);
  for (const auto& [id, set] : model.coupled_sets)
    for (int node : set.nodes) unavailable.insert(DofKey{node, set.dof});
  auto dependent = std::make_shared<DependentDofs>();
  dependent->add_all(equations, unavailable);
  dependent_ = std::move(dependent);
  if (steps != nullptr)
    for (const LoadStep& step : *steps) check_slaves_free(step);
  // A slave's motion follows its masters: an initial condition on it is not applied (the one on
  // its masters gives it), which is said rather than passed over.
  for (const auto& [key, ic] : model.initial_conditions)
    if (dependent_->find(key) != nullptr && (ic.displacement != 0.0 || ic.velocity != 0.0))
      Log::warn(
          "{}:{}: IC on {}, the slave of a constraint equation, is not applied: its motion "
          "follows its masters (give the IC there)",
          ic.where.file, ic.where.line, describe(key));
  Log::info("{} constraint equation(s) eliminate {} slave DOF(s)", equations.size(),
            dependent_->slaves().size());
}

void Structure::refuse_constraint_equations(const std::string& analysis) const {
  if (!dependent_) return;
  throw NotImplementedError(
      dependent_->slaves().begin()->second.where,
      fmt::format("constraint equations (CE, CERIG, MPC184 rigid links) in {} "
                  "are not implemented; they are applied in static, modal "
                  "and full transient analyses",
                  analysis));
}

void Structure::check_slaves_free(const LoadStep& step) const {
  if (!dependent_) return;
  for (const auto& [key, value] : step.constraints)
    if (const auto* dep = dependent_->find(key)) {
      throw InputError(
          step.where,
          fmt::format("load step {}: {} is held by D and is the slave (first DOF) of a constraint "
                      "equation ({}:{}); hold a master instead, or reorder the "
                      "equation's terms",
                      step.number, describe(key), dep->where.file, dep->where.line));
    }
}

}  // namespace impactfe
