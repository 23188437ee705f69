// The condensed transient's increment (linear_part_condensation.h): Newton on the nonlinear
// elements' DOFs c with the linear part condensed onto them, the whole field recovered once per
// step; EquilibriumIncrement falls back to full Newton when the recovered state fails the full
// criterion.
#include <fmt/format.h>

#include "analysis/equilibrium_increment.h"

namespace impactfe {

namespace {

/// The c part of a step of the condensed transient (linear_part_condensation.h): unknowns δ_c,
/// residual ρ = S (y − δ_c) − [φ(δ_c) − φ(0)], tangent S + cK K_N + cC C_N. The nonlinear elements
/// see the full state u0 + E δ_c (and v0 + (cC/wk) E δ_c: v is affine in u with that slope).
/// `u` and `v` are the step's full state, changed in place on c only (the values at the
/// predictor are kept for c alone: a step copies no vector of model size).
class CondensedIncrement final : public NonlinearProblem {
 public:
  CondensedIncrement(const Assembler& assembler, LinearPartCondensation& condensation,
                     StatusLoop& status_loop, const StepLabel& label,
                     const IntegrationCoefficients& coeff, double wk, VectorXd& u, VectorXd& v,
                     VectorXd y, double reference)
      : assembler_(assembler),
        condensation_(condensation),
        status_loop_(status_loop),
        label_(label),
        coeff_(coeff),
        wk_(wk),
        u_(u),
        v_(v),
        u0_c_(condensation.size()),
        v0_c_(condensation.size()),
        y_(std::move(y)),
        reference_(reference),
        phi0_(VectorXd::Zero(condensation.size())) {
    const auto& c = condensation_.dofs();
    for (std::size_t k = 0; k < c.size(); ++k) {
      u0_c_(static_cast<Eigen::Index>(k)) = u_(c[k]);
      v0_c_(static_cast<Eigen::Index>(k)) = v_(c[k]);
    }
    assembler_.assemble_nonlinear_part(coeff_, wk_, u_, v_, condensation_.position(), phi0_,
                                       nullptr);
  }
  /// u on c at the predictor.
  const VectorXd& u0_c() const { return u0_c_; }

  int n_unknowns() const override { return condensation_.size(); }
  double residual(const VectorXd& delta, VectorXd& r, double& reference) override {
    set_state(delta);
    VectorXd phi = VectorXd::Zero(n_unknowns());
    assembler_.assemble_nonlinear_part(coeff_, wk_, u_, v_, condensation_.position(), phi, nullptr);
    r = condensation_.schur() * (y_ - delta) - (phi - phi0_);
    reference = reference_;
    return r.norm();
  }
  bool tangent_stale() const override { return stale_; }
  void factorize_tangent(const VectorXd& delta) override {
    set_state(delta);
    MatrixXd tangent = condensation_.schur();
    VectorXd phi = VectorXd::Zero(n_unknowns());
    assembler_.assemble_nonlinear_part(coeff_, wk_, u_, v_, condensation_.position(), phi,
                                       &tangent);
    // From the factor of the last tangent (earlier in the step or in an earlier step): a gap
    // that opened or closed changes it on its own DOFs only.
    condensation_.tangent_factor().factorize(tangent);
    stale_ = false;
  }
  VectorXd solve(const VectorXd& r) override { return condensation_.tangent_factor().solve(r); }
  bool update_status(const VectorXd& delta) override {
    set_state(delta);
    n_status_changes_ += status_loop_.update(u_, label_);
    if (n_status_changes_ == reported_) return false;
    reported_ = n_status_changes_;
    stale_ = true;
    return true;
  }
  int n_status_changes() const { return n_status_changes_; }

 private:
  void set_state(const VectorXd& delta) {
    const double slope = wk_ != 0.0 ? coeff_.cC / wk_ : 0.0;  // dv/du of the time scheme
    const auto& c = condensation_.dofs();
    for (std::size_t k = 0; k < c.size(); ++k) {
      const auto j = static_cast<Eigen::Index>(k);
      u_(c[k]) = u0_c_(j) + delta(j);
      v_(c[k]) = v0_c_(j) + slope * delta(j);
    }
  }

  const Assembler& assembler_;
  LinearPartCondensation& condensation_;
  StatusLoop& status_loop_;
  StepLabel label_;
  IntegrationCoefficients coeff_;
  double wk_;
  VectorXd& u_;  // full state at the current δ_c
  VectorXd& v_;
  VectorXd u0_c_, v0_c_;  // on c, at the predictor
  VectorXd y_;
  double reference_;
  VectorXd phi0_;
  bool stale_ = true;
  int n_status_changes_ = 0, reported_ = 0;
};

}  // namespace

bool EquilibriumIncrement::solve_condensed(VectorXd& u, const NewtonOptions& newton,
                                           NewtonResult& result) {
  Increment& inc = inc_;
  LinearPartCondensation& condensation = *disc_->condensation();
  const ConvergenceOptions& conv = structure_.options().convergence;
  try {
    condensation.prepare(inc.coeff);
  } catch (const SingularMatrixError& e) {
    // A DOF held only by nonlinear elements (no mass, no linear stiffness): full Newton.
    condensation_note_ = fmt::format(
        "condensed transient not used: the linear part alone is singular at {} (held only by "
        "nonlinear elements)",
        disc_->describe_dof(e.column()));
    disc_->drop_condensation();
    return false;
  }
  const int nf = disc_->dofs().n_free();
  VectorXd& r = step_residual_;  // kept: a step allocates no vector of model size
  double reference = 0.0;
  residual(u, r, reference);  // also v(u0) into inc.v
  const VectorXd y = condensation.condense(r.head(nf));
  const auto& c = condensation.dofs();
  // The problem moves u and inc.v on c; the residual below forms inc.v again from u.
  CondensedIncrement problem(disc_->assembler(), condensation, disc_->status_loop(), inc.label,
                             inc.coeff, inc.weights.stiffness, u, inc.v, y, reference);
  // δ_c = y, the linear part's own answer, is the exact solution when the nonlinear elements
  // add no force there (ρ(y) = 0: gaps that stay open) and keep their statuses: then the step is
  // the linear part's solve alone (free flight).
  VectorXd delta = y;
  VectorXd rho;
  double unused = 0.0;
  const bool inactive =
      problem.residual(delta, rho, unused) == 0.0 && !problem.update_status(delta);
  if (inactive) {
    result = NewtonResult{};
    result.converged = true;
    result.iterations = 1;
  } else {
    delta.setZero();
    result = NewtonRaphson(newton, ConvergenceTest(conv)).solve(problem, delta);
  }
  // The whole field, once: δ_c on c, the linear part's rows in balance elsewhere (u holds the
  // last iterate on c; the predictor's values there are put back before the update).
  const VectorXd& u0_c = problem.u0_c();
  for (std::size_t k = 0; k < c.size(); ++k) u(c[k]) = u0_c(static_cast<Eigen::Index>(k));
  condensation.recover(delta, step_correction_);
  u.head(nf) += step_correction_;
  inc.n_status_changes += problem.n_status_changes();
  for (std::size_t k = 0; k < c.size(); ++k)
    u(c[k]) = u0_c(static_cast<Eigen::Index>(k)) + delta(static_cast<Eigen::Index>(k));
  // The full criterion on the recovered state (this evaluation also gives the forces the step
  // is accepted with).
  const double residual_norm = this->residual(u, r, reference);
  const ConvergenceTest test(conv);
  if (!result.converged || !test.force_converged(residual_norm, reference)) {
    disc_->invalidate_factor();  // statuses may have changed since the full tangent was factorized
    ++full_fallback_steps_;
    return false;
  }
  ++condensed_steps_;
  result.residual_norm = residual_norm;
  result.reference = test.reference(reference);
  return true;
}

}  // namespace impactfe
