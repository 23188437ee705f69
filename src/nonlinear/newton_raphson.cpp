#include "nonlinear/newton_raphson.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace impactfe {

double line_search_step(NonlinearProblem& problem, const VectorXd& u, const VectorXd& du,
                        const VectorXd& r0) {
  const int n = static_cast<int>(du.size());
  const double g0 = du.dot(r0);
  if (!(g0 > 0.0)) return 1.0;  // not a descent direction of the energy: nothing to search
  VectorXd trial = u, r;
  const auto g = [&](double s) {
    trial.head(n) = u.head(n) + s * du;
    double reference = 0.0;
    problem.expect_tangent(false);
    problem.residual(trial, r, reference);
    const double value = du.dot(r.head(n));
    return std::isfinite(value) ? value : -std::numeric_limits<double>::infinity();
  };
  constexpr double kTolerance = 0.5, kSmallest = 0.05;
  double s_hi = 1.0, g_hi = g(1.0);
  if (std::abs(g_hi) <= kTolerance * g0 || g_hi > 0.0) return 1.0;  // energy still falling at 1
  double s_lo = 0.0, g_lo = g0;
  double s = 1.0;
  int side = 0;  // Illinois: the end kept twice in a row has its g halved
  for (int k = 0; k < 5; ++k) {
    s = std::isfinite(g_hi) ? s_hi - g_hi * (s_hi - s_lo) / (g_hi - g_lo) : 0.5 * (s_lo + s_hi);
    s = std::clamp(s, kSmallest, 1.0);
    const double gs = g(s);
    if (std::abs(gs) <= kTolerance * g0) break;
    if (gs > 0.0) {
      s_lo = s;
      g_lo = gs;
      if (side == -1) g_hi *= 0.5;
      side = -1;
    } else {
      s_hi = s;
      g_hi = gs;
      if (side == 1) g_lo *= 0.5;
      side = 1;
    }
    if (s <= kSmallest && gs < 0.0) break;
  }
  return s;
}

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
    } else if (options_.line_search ||
               (options_.line_search_auto && result.history.size() >= 3 &&
                result.history.back() > result.history[result.history.size() - 2])) {
      const double step = line_search_step(problem, u, du, r.head(n));
      if (step != 1.0) {
        du *= step;
        ++result.line_searches;
      }
    }
    u.head(n) += du;
    unsettled = !test_.displacement_converged(du.norm(), u.head(n).norm());
    if (problem.update_status(u)) unsettled = true;
  }
  result.iterations = iteration;
  return result;
}

}  // namespace impactfe
