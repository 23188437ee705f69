#include "analysis/linear_part_condensation.h"

#include <fmt/format.h>

namespace impactfe {

std::optional<std::string> LinearPartCondensation::refusal(const Assembler& assembler) {
  const int n = assembler.dofs().n_free();
  if (assembler.n_nonlinear_elements() == 0) return "the model is linear";
  const auto m = static_cast<double>(assembler.nonlinear_free_dofs().size());
  if (m == 0) return "the nonlinear elements touch no free DOF";
  // Dense m × m work per iteration must stay small beside the sparse solve: at most a quarter of
  // the DOFs (any share below all of them in a small model).
  if (m >= n || m > kMaxCondensedDofs || (m > 0.25 * n && n > 256))
    return fmt::format("the nonlinear elements touch {:.0f} of {} free DOFs", m, n);
  if (sparse_solver_replaced() && 8.0 * n * m > kMaxTransferBytes)
    return fmt::format("the transfer matrix would take {:.0f} MB", 8.0 * n * m / 1048576.0);
  return std::nullopt;
}

LinearPartCondensation::LinearPartCondensation(const Assembler& assembler)
    : assembler_(assembler),
      c_(assembler.nonlinear_free_dofs()),
      position_(static_cast<std::size_t>(assembler.dofs().n_active()), -1),
      solver_(make_schur_solver(assembler.dofs().n_free(), c_)) {
  for (std::size_t k = 0; k < c_.size(); ++k)
    position_[static_cast<std::size_t>(c_[k])] = static_cast<int>(k);
}

bool LinearPartCondensation::prepared_for(const IntegrationCoefficients& coeff) const {
  return prepared_ && prepared_->cK == coeff.cK && prepared_->cC == coeff.cC &&
         prepared_->cM == coeff.cM;
}

void LinearPartCondensation::prepare(const IntegrationCoefficients& coeff) {
  if (prepared_for(coeff)) return;
  prepared_.reset();
  tangent_.reset();  // S changes with the coefficients
  assembler_.assemble_linear_part(coeff, effective_);
  if (solver_->counters().analyses == 0) solver_->analyze_pattern(effective_);
  solver_->factorize_and_release(effective_);  // formed again for another Δt
  prepared_ = coeff;
}

}  // namespace impactfe
