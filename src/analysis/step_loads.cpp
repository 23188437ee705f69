#include "analysis/step_loads.h"

#include <fmt/format.h>

namespace impactfe {

void StepLoads::resolve(const Discretisation& disc, const LoadStep& step,
                        const LoadStep* previous) {
  step_ = &step;
  previous_ = previous;
  thermal_ = step.gives_temperatures() || (previous != nullptr && previous->gives_temperatures());
  for (const auto& e : structure_.elements())
    thermal_ = thermal_ || (e->thermal_expansion().expands() &&
                            e->thermal_expansion().reference_temperature.has_value());
  resolve_again(disc);
}

void StepLoads::resolve_again(const Discretisation& disc) {
  rotation_force_.resize(0);  // a new numbering: formed again when needed
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
  if (at.current->rotation.any() || (at.previous != nullptr && at.previous->rotation.any()))
    add_rotational_forces(disc, at, f);
  if (at.current == step_) {
    forces_.add_to(at, f);
  } else {
    f += nodal_forces(dofs, at);
  }
  if (!at.current->pressures.empty())
    f += pressure_forces(structure_.elements(), dofs, structure_.context(), at, u);
  if (thermal_ || at.current->gives_temperatures()) add_thermal_forces(disc, at, f);
}

void StepLoads::add_rotational_forces(const Discretisation& disc, const LoadPoint& at,
                                      VectorXd& f) const {
  const RotationalLoads loads = rotational_loads(at);
  // The load acts on the initial geometry; under large deflection it would have to follow the
  // deformed one (and spin softening would enter the stiffness), which is not implemented.
  if (structure_.context().large_deflection)
    throw NotImplementedError(
        loads.where,
        "rotational inertia loads (OMEGA, DOMEGA, CGOMGA, DCGOMG) under large deflection "
        "(NLGEOM) are not implemented: the load would have to follow the deformed geometry");
  const DofMap& dofs = disc.dofs();
  if (rotation_force_.size() != dofs.n_active() || !(loads == rotation_)) {
    const Model& model = structure_.model();
    const auto position = [&model](int node) {
      const auto it = model.nodes.find(node);
      IMPACTFE_CHECK(it != model.nodes.end(),
                     fmt::format("node {} of an element is not in the model", node));
      return it->second.x;
    };
    rotation_force_ =
        rotational_inertia_load(structure_.elements(), dofs, structure_.context(), position, loads);
    rotation_ = loads;
  }
  f += rotation_force_;
}

void StepLoads::add_thermal_forces(const Discretisation& disc, const LoadPoint& at,
                                   VectorXd& f) const {
  // Nodal temperatures at the load point: the uniform temperature (TUNIF / BFUNIF, default
  // TREF) is stepped; a BF temperature ramps per KBC from the node's temperature at the end of
  // the previous step (the first step: from the uniform temperature).
  const LoadStep& cur = *at.current;
  const double uniform = cur.uniform_temperature.value_or(cur.reference_temperature);
  const auto temperature = [&](int node) {
    const bool given = cur.node_temperatures.count(node) != 0 ||
                       (at.previous != nullptr && at.previous->node_temperatures.count(node) != 0);
    if (!given) return uniform;
    const double before = at.previous != nullptr ? at.previous->temperature(node) : uniform;
    return interpolate(at, before, cur.temperature(node));
  };
  const ElementContext& ctx = structure_.context();
  const auto& elements = structure_.elements();
  VectorXd fe;
  for (std::size_t e = 0; e < elements.size(); ++e) {
    Element& element = *elements[e];
    const Element::ThermalExpansion& thermal = element.thermal_expansion();
    if (!thermal.expands()) continue;
    const double reference = thermal.reference_temperature.value_or(cur.reference_temperature);
    std::vector<double> dT;
    bool heated = false;
    for (int node : thermal.nodes) {
      dT.push_back(temperature(node) - reference);
      heated = heated || dT.back() != 0.0;
    }
    if (!heated) {
      element.set_temperature_change({});
      continue;
    }
    // The thermal strain enters as a load on the linear element: under large deflection or
    // plasticity it would have to enter the element's strain itself, which is not implemented.
    if (ctx.large_deflection)
      throw NotImplementedError(fmt::format(
          "element {} ({}): thermal strain under large deflection (NLGEOM) is not implemented",
          element.id(), element.family()));
    if (element.has_history())
      throw NotImplementedError(
          fmt::format("element {} ({}): thermal strain with a plastic material is not implemented",
                      element.id(), element.family()));
    element.set_temperature_change(std::move(dT));
    element.thermal_load(ctx, fe);
    const auto& idx = disc.dofs().element_indices(e);
    for (std::size_t a = 0; a < idx.size(); ++a)
      if (idx[a] >= 0) f(idx[a]) += fe(static_cast<Eigen::Index>(a));
  }
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
