#pragma once
/// Newton-Raphson equilibrium iterations (Bathe §8.4.1; spec §10.3), full or modified, with a
/// line-search hook and the element status loop inside each iteration. The problem (a static
/// load increment, a time step of a dynamic analysis) supplies the residual and the tangent; the
/// solver knows neither elements nor time schemes.
#include <functional>
#include <vector>

#include "linalg/sparse.h"
#include "nonlinear/convergence.h"

namespace impactfe {

/// One increment's nonlinear system R(u) = 0 over the leading `n_unknowns()` entries of u (the
/// free DOFs; the trailing entries, prescribed displacements, stay fixed).
class NonlinearProblem {
 public:
  virtual ~NonlinearProblem() = default;
  virtual int n_unknowns() const = 0;
  /// Residual (out-of-balance force) at u, the norm of its unknown part, and the reference
  /// force magnitude of the force criterion.
  virtual double residual(const VectorXd& u, VectorXd& r, double& reference) = 0;
  /// True when no valid factorization of the tangent exists (first iteration, changed
  /// coefficients, a status change since the last factorization).
  virtual bool tangent_stale() const = 0;
  /// Forms and factorizes the tangent at u.
  virtual void factorize_tangent(const VectorXd& u) = 0;
  /// Δu = K_T⁻¹ r over the unknowns.
  virtual VectorXd solve(const VectorXd& r_unknowns) = 0;
  /// Said before each residual evaluation: true when a factorization of the tangent at the same
  /// iterate follows unless that residual converges (the first iteration of full Newton, whose
  /// predictor is accepted only in exact balance). The problem may then form the tangent's
  /// element parts with the forces in one evaluation.
  virtual void expect_tangent(bool likely) {}
  /// Re-evaluates element statuses (gaps, sliders) at the new iterate; true when one changed,
  /// which makes the iteration unconverged and the tangent stale.
  virtual bool update_status(const VectorXd& u) { return false; }
};

struct NewtonOptions {
  int max_iterations = 25;
  /// Full Newton re-forms the tangent every `reform_every` iterations when the tangent depends
  /// on u (KRF / NROPT,FULL); modified Newton only when it is stale (NROPT,MODI / INIT).
  bool full_newton = true;
  int reform_every = 1;
  /// False for a problem whose tangent does not depend on u (then only a status change or new
  /// coefficients re-form it, whatever the Newton variant).
  bool tangent_varies = true;
  /// LNSRCH: each correction scaled by the step length s that makes the residual nearly
  /// orthogonal to it (line_search_step).
  bool line_search = false;
  /// LNSRCH,AUTO: the search only for a correction after one that raised the residual norm
  /// (the first, the predictor's, aside): full Newton while it converges.
  bool line_search_auto = false;
};

struct NewtonResult {
  bool converged = false;
  int iterations = 0;           // equilibrium iterations (corrections applied)
  double residual_norm = 0.0;   // at the last evaluation
  double reference = 0.0;       // with MINREF applied
  bool finite = true;           // false: the residual became NaN or infinite (iteration stopped)
  std::vector<double> history;  // residual norm at each evaluation
  int line_searches = 0;        // corrections the line search shortened (s < 1)
};

/// Scales the correction Δu (line search). Arguments: iterate u, correction du over the
/// unknowns, residual norm before the correction; returns the step length s (u += s Δu).
using LineSearch = std::function<double(const VectorXd& u, const VectorXd& du, double r_norm)>;

/// The line search of LNSRCH (Crisfield 1991, §9.3; Bathe §8.4.2): g(s) = Δuᵀ R(u + s Δu), the
/// residual's component along the correction, is zero at the energy minimum along it. The full
/// step is kept when |g(1)| <= ½ g(0); otherwise s is found by regula falsi (Illinois) on
/// [0, 1] when g changes sign there, in at most five more residual evaluations, and kept in
/// [0.05, 1]. `r0`: the residual at u over the unknowns. The problem's residual is evaluated at
/// the trial points; its statuses are not updated.
double line_search_step(NonlinearProblem& problem, const VectorXd& u, const VectorXd& du,
                        const VectorXd& r0);

class NewtonRaphson {
 public:
  NewtonRaphson(const NewtonOptions& options, const ConvergenceTest& test)
      : options_(options), test_(test) {}
  void set_line_search(LineSearch line_search) { line_search_ = std::move(line_search); }

  /// Iterates from u (updated in place) until the force and displacement criteria hold with no
  /// status change in the last iteration, or max_iterations corrections were applied.
  NewtonResult solve(NonlinearProblem& problem, VectorXd& u) const;

 private:
  NewtonOptions options_;
  ConvergenceTest test_;
  LineSearch line_search_;
};

}  // namespace impactfe
