#include "nonlinear/newton_raphson.h"

#include <algorithm>
#include <cmath>

namespace impactfe {

NewtonResult NewtonRaphson::solve(NonlinearProblem& problem, VectorXd& u) const {
  const int n = problem.n_unknowns();
  const int reform_every = std::max(1, options_.reform_every);
  NewtonResult result;
  VectorXd r;
  // True when the last correction left the iteration unconverged whatever the residual says:
  // a status changed, or the displacement criterion was not met.
  bool unsettled = false;
  int iteration = 0;
  for (; iteration <= options_.max_iterations; ++iteration) {
    double reference = 0.0;
    problem.expect_tangent(
        iteration == 0 && n > 0 &&
        (problem.tangent_stale() || (options_.tangent_varies && options_.full_newton)));
    const double residual_norm = problem.residual(u, r, reference);
    result.history.push_back(residual_norm);
    result.residual_norm = residual_norm;
    result.reference = test_.reference(reference);
    if (!std::isfinite(residual_norm)) {  // more iterations cannot repair a NaN or an overflow
      result.finite = false;
      break;
    }
    // The first evaluation converges only when nothing is out of balance: a predictor is never
    // accepted on a relative criterion alone.
    if (!unsettled && test_.force_converged(residual_norm, reference) &&
        (iteration > 0 || residual_norm == 0.0 || n == 0)) {
      // A predictor in exact balance (free flight) is accepted only with the statuses it has:
      // otherwise a gap it penetrates would stay open (no correction, so no status update,
      // would follow). A change re-evaluates the residual at the same iterate.
      if (iteration == 0 && n > 0 && problem.update_status(u)) {
        unsettled = true;
        result.history.clear();
        --iteration;
        continue;
      }
      result.converged = true;
      break;
    }
    if (iteration == options_.max_iterations) break;
    if (n == 0) {
      result.converged = true;
      break;
    }
    const bool reform =
        problem.tangent_stale() ||
        (options_.tangent_varies && options_.full_newton && iteration % reform_every == 0);
    if (reform) problem.factorize_tangent(u);
    VectorXd du = problem.solve(VectorXd(r.head(n)));
    if (line_search_) {
      const double step = line_search_(u, du, residual_norm);
      if (step != 1.0) du *= step;
    }
    u.head(n) += du;
    unsettled = !test_.displacement_converged(du.norm(), u.head(n).norm());
    if (problem.update_status(u)) unsettled = true;
  }
  result.iterations = iteration;
  return result;
}

}  // namespace impactfe
