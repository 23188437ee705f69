#pragma once
/// Convergence tests of the equilibrium iterations (CNVTOL semantics, APDL_SUBSET §9.4 and
/// spec §10.3): the force criterion ‖r‖ ≤ TOLER · max(reference, MINREF) with the reference the
/// largest of the load, inertia and internal-force norms of the step, and the optional
/// displacement criterion ‖Δu‖ ≤ TOLER_U · ‖u‖ (CNVTOL,U).
#include "core/model.h"

namespace impactfe {

class ConvergenceTest {
 public:
  explicit ConvergenceTest(const ConvergenceOptions& options) : options_(options) {}

  /// Force criterion: `residual_norm` (‖r‖ over the free DOFs) against `reference` (the largest
  /// force norm of the step; MINREF applies as its floor).
  bool force_converged(double residual_norm, double reference) const {
    return residual_norm <= options_.force_tolerance * std::max(reference, options_.force_minref);
  }
  /// Displacement criterion on the last increment; always met when CNVTOL,U is not given.
  bool displacement_converged(double increment_norm, double displacement_norm) const {
    return !options_.displacement_tolerance ||
           increment_norm <= *options_.displacement_tolerance * std::max(displacement_norm, 1e-30);
  }
  /// The reference with MINREF applied (reported in non-convergence messages).
  double reference(double reference) const { return std::max(reference, options_.force_minref); }
  const ConvergenceOptions& options() const { return options_; }

 private:
  ConvergenceOptions options_;
};

}  // namespace impactfe
