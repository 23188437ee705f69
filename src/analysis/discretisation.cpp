#include "analysis/discretisation.h"

#include <fmt/format.h>

#include <algorithm>

namespace impactfe {

Discretisation::Discretisation(const Structure& structure, std::set<DofKey> constrained,
                               bool condense)
    : structure_(structure),
      constrained_(std::move(constrained)),
      dofs_(std::make_unique<DofMap>(structure.elements(), constrained_, structure.coupled_dofs(),
                                     structure.dependent_dofs())) {
  const auto& elements = structure.elements();
  assembler_ = std::make_unique<Assembler>(elements, *dofs_, structure.context(),
                                           structure.options().alpha_damping,
                                           structure.options().beta_damping);
  assembler_->set_material_stiffness_damping(structure.material_stiffness_damping());
  status_loop_ = std::make_unique<StatusLoop>(elements, *assembler_);
  for (std::size_t e = 0; e < elements.size(); ++e)
    if (const auto* check = dynamic_cast<const PenetrationCheck*>(elements[e].get());
        check != nullptr && check->checks_penetration())
      penetration_checks_.emplace_back(e, check);
  frame_load_ = FrameAccelerationLoad(elements, *dofs_, structure.context());
  solver_ = make_linear_solver(dofs_->n_free());
  // A solver that reads only some columns on this rank (MUMPS on several ranks): the assembler
  // then evaluates only the elements at them (docs/scaling.md, "Element assembly split by rank").
  assembler_->distribute(solver_->column_owners(assembler_->pattern().zero_matrix()));
  if (!status_loop_->empty())
    contact_frequency_ = std::make_unique<ContactFrequencyEstimator>(
        elements, *dofs_, assembler_->inertia_force(VectorXd::Ones(dofs_->n_active())));
  if (condense && assembler_->n_nonlinear_elements() > 0) {
    if (const auto why = LinearPartCondensation::refusal(*assembler_)) {
      condensation_note_ = "condensed transient not used: " + *why;
    } else {
      condensation_ = std::make_unique<LinearPartCondensation>(*assembler_);
      condensation_note_ = fmt::format(
          "condensed transient: the linear part ({} free DOFs) is factorized once per time step "
          "size and condensed onto the {} DOFs of the {} nonlinear elements",
          dofs_->n_free(), condensation_->size(), assembler_->n_nonlinear_elements());
    }
  }
}

SolverCounters Discretisation::counters() const {
  SolverCounters c = solver_->counters();
  if (condensation_) c += condensation_->counters();
  return c;
}

void Discretisation::factorize(const IntegrationCoefficients& coeff, const VectorXd& u,
                               const VectorXd& v) {
  assembler_->assemble(coeff, u, v, Assembler::Output{&effective_, nullptr, nullptr});
  if (!factor_valid_ && solver_->counters().analyses == 0) solver_->analyze_pattern(effective_);
  solver_->factorize(effective_);
  factor_valid_ = true;
  factored_ = coeff;
}

bool Discretisation::factor_valid_for(const IntegrationCoefficients& coeff) const {
  return factor_valid_ && coeff.cK == factored_.cK && coeff.cC == factored_.cC &&
         coeff.cM == factored_.cM;
}

std::string Discretisation::excessive_penetration(const VectorXd& u_start,
                                                  const VectorXd& u) const {
  double worst = 1.0;
  std::size_t at = 0;
  VectorXd ue, start;
  for (const auto& [e, check] : penetration_checks_) {
    assembler_->gather(e, u, ue);
    assembler_->gather(e, u_start, start);
    const double ratio = check->penetration_ratio(start, ue);
    if (ratio > worst) {
      worst = ratio;
      at = e;
    }
  }
  if (worst <= 1.0) return {};
  return fmt::format(
      "contact element {} penetrated {:.3g} x FTOLN x depth further in one substep (KEYOPT(7) = 1)",
      structure_.elements()[at]->id(), worst);
}

std::string Discretisation::elements_at(int index) const {
  std::string list;
  int shown = 0;
  for (std::size_t e = 0; e < structure_.elements().size(); ++e) {
    const auto& idx = dofs_->element_indices(e);
    if (std::find(idx.begin(), idx.end(), index) == idx.end()) continue;
    if (shown++ < 8)
      list += fmt::format("{}{}", shown > 1 ? ", " : "", structure_.elements()[e]->id());
  }
  if (shown > 8) list += ", ...";
  return shown == 0 ? std::string("no element") : (shown == 1 ? "element " : "elements ") + list;
}

}  // namespace impactfe
