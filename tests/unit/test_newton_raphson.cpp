// Newton-Raphson of the nonlinear layer (src/nonlinear/newton_raphson.h): quadratic convergence
// of full Newton on a smooth problem (Bathe §8.4.1), modified Newton on a linear problem in one
// iteration, the status hook, the line-search hook and an honest non-convergence report.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "nonlinear/newton_raphson.h"

namespace impactfe::test_newton_raphson {
namespace {

/// Two hardening springs in series, f = (f1, f2):
///   r(u) = f − [k1 u1 + c u1³ − k2 (u2 − u1);  k2 (u2 − u1) + c (u2 − u1)³]   (smooth, convex).
/// The trailing entry of u is a prescribed DOF that must stay untouched.
class HardeningChain final : public NonlinearProblem {
 public:
  double k1 = 100.0, k2 = 50.0, c = 50.0;
  Eigen::Vector2d f{30.0, 20.0};
  bool linear = false;  // c = 0: a linear problem
  int factorizations = 0, solves = 0, status_calls = 0;
  int status_changes_left = 0;  // update_status reports a change this many times
  std::vector<bool> expected;   // expect_tangent's word before each residual

  int n_unknowns() const override { return 2; }
  void expect_tangent(bool likely) override { expected.push_back(likely); }
  double residual(const VectorXd& u, VectorXd& r, double& reference) override {
    const double cc = linear ? 0.0 : c;
    const double d = u(1) - u(0);
    Eigen::Vector2d fint(k1 * u(0) + cc * u(0) * u(0) * u(0) - k2 * d - cc * d * d * d,
                         k2 * d + cc * d * d * d);
    r = VectorXd::Zero(3);
    r.head(2) = f - fint;
    reference = std::max(f.norm(), fint.norm());
    return r.head(2).norm();
  }
  bool tangent_stale() const override { return stale_; }
  void factorize_tangent(const VectorXd& u) override {
    const double cc = linear ? 0.0 : c;
    const double d = u(1) - u(0);
    const double kd = k2 + 3.0 * cc * d * d;
    Eigen::Matrix2d k;
    k << k1 + 3.0 * cc * u(0) * u(0) + kd, -kd, -kd, kd;
    ldlt_.compute(k);
    stale_ = false;
    ++factorizations;
  }
  VectorXd solve(const VectorXd& r) override {
    ++solves;
    return ldlt_.solve(r);
  }
  bool update_status(const VectorXd&) override {
    ++status_calls;
    if (status_changes_left == 0) return false;
    --status_changes_left;
    stale_ = true;
    return true;
  }

 private:
  bool stale_ = true;
  Eigen::LDLT<Eigen::Matrix2d> ldlt_;
};

ConvergenceOptions tight() {
  ConvergenceOptions o;
  o.force_tolerance = 1e-12;
  o.force_minref = 1e-30;
  o.max_iterations = 30;
  return o;
}

TEST(NewtonRaphson, FullNewtonConvergesQuadraticallyOnASmoothProblem) {
  HardeningChain p;
  NewtonOptions options;
  options.max_iterations = 30;
  VectorXd u = VectorXd::Zero(3);
  u(2) = 0.123;  // prescribed, not an unknown
  const NewtonResult result = NewtonRaphson(options, ConvergenceTest(tight())).solve(p, u);
  ASSERT_TRUE(result.converged);
  EXPECT_EQ(u(2), 0.123);
  EXPECT_EQ(p.factorizations, result.iterations);  // full Newton: a tangent per iteration
  EXPECT_LE(result.iterations, 12);
  // Quadratic convergence: once in the basin, r_{k+1} <= C r_k^2 with a moderate C; the number
  // of correct digits doubles. Checked on the last iterations before round-off.
  const auto& h = result.history;
  int quadratic_steps = 0;
  for (std::size_t k = 1; k + 1 < h.size(); ++k) {
    if (h[k] > 1e-2 || h[k + 1] < 1e-11) continue;
    const double rate = h[k + 1] / (h[k] * h[k]);
    EXPECT_LT(rate, 1.0) << "iteration " << k;
    ++quadratic_steps;
  }
  EXPECT_GE(quadratic_steps, 1);
  // The solution satisfies equilibrium.
  VectorXd r;
  double ref = 0.0;
  EXPECT_LT(p.residual(u, r, ref), 1e-10);
}

TEST(NewtonRaphson, SaysBeforeTheFirstResidualOnlyThatATangentFollowsIt) {
  // Full Newton factors the tangent at the predictor unless its residual is zero: the problem
  // hears so before that residual (and may form the tangent with it), before no other. Modified
  // Newton with a valid factor forms none, so there it hears it only while the factor is stale.
  HardeningChain p;
  NewtonOptions options;
  options.max_iterations = 30;
  VectorXd u = VectorXd::Zero(3);
  const NewtonResult full = NewtonRaphson(options, ConvergenceTest(tight())).solve(p, u);
  ASSERT_TRUE(full.converged);
  ASSERT_EQ(p.expected.size(), static_cast<std::size_t>(full.iterations) + 1);
  EXPECT_TRUE(p.expected.front());
  for (std::size_t k = 1; k < p.expected.size(); ++k) EXPECT_FALSE(p.expected[k]) << k;
  // The next increment of modified Newton keeps the factor: nothing follows its first residual.
  options.full_newton = false;
  p.f *= 1.01;
  p.expected.clear();
  const NewtonResult modified = NewtonRaphson(options, ConvergenceTest(tight())).solve(p, u);
  ASSERT_TRUE(modified.converged);
  ASSERT_FALSE(p.expected.empty());
  for (std::size_t k = 0; k < p.expected.size(); ++k) EXPECT_FALSE(p.expected[k]) << k;
}

TEST(NewtonRaphson, ModifiedNewtonSolvesALinearProblemInOneIteration) {
  HardeningChain p;
  p.linear = true;
  NewtonOptions options;
  options.full_newton = false;
  VectorXd u = VectorXd::Zero(3);
  const NewtonResult result = NewtonRaphson(options, ConvergenceTest(tight())).solve(p, u);
  ASSERT_TRUE(result.converged);
  EXPECT_EQ(result.iterations, 1);
  EXPECT_EQ(p.factorizations, 1);
  EXPECT_EQ(p.solves, 1);
  // Exact: u1 = (f1 + f2)/k1, u2 = u1 + f2/k2.
  EXPECT_NEAR(u(0), 50.0 / 100.0, 1e-14);
  EXPECT_NEAR(u(1), 0.5 + 20.0 / 50.0, 1e-14);
}

TEST(NewtonRaphson, ModifiedNewtonKeepsOneTangentOnANonlinearProblem) {
  HardeningChain p;
  NewtonOptions options;
  options.full_newton = false;
  options.max_iterations = 200;
  ConvergenceOptions conv = tight();
  conv.force_tolerance = 1e-8;
  conv.max_iterations = 200;
  VectorXd u = VectorXd::Zero(3);
  const NewtonResult result = NewtonRaphson(options, ConvergenceTest(conv)).solve(p, u);
  ASSERT_TRUE(result.converged);
  EXPECT_EQ(p.factorizations, 1);   // the initial tangent only
  EXPECT_GT(result.iterations, 5);  // linear, not quadratic, convergence
}

TEST(NewtonRaphson, AStatusChangeForcesAnotherIterationAndANewTangent) {
  HardeningChain p;
  p.linear = true;
  p.status_changes_left = 2;
  NewtonOptions options;
  options.full_newton = false;
  VectorXd u = VectorXd::Zero(3);
  const NewtonResult result = NewtonRaphson(options, ConvergenceTest(tight())).solve(p, u);
  ASSERT_TRUE(result.converged);
  // Balanced after the first correction, but two status changes keep the step open.
  EXPECT_EQ(result.iterations, 3);
  EXPECT_EQ(p.factorizations, 3);
}

TEST(NewtonRaphson, ReportsNonConvergenceWithTheLastResidual) {
  HardeningChain p;
  p.f *= 50.0;  // far from the start: many iterations needed
  NewtonOptions options;
  options.max_iterations = 2;
  VectorXd u = VectorXd::Zero(3);
  const NewtonResult result = NewtonRaphson(options, ConvergenceTest(tight())).solve(p, u);
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.iterations, 2);
  EXPECT_EQ(result.history.size(), 3u);
  EXPECT_GT(result.residual_norm, 1e-12 * result.reference);
}

TEST(NewtonRaphson, LineSearchScalesTheCorrection) {
  HardeningChain p;
  p.linear = true;
  NewtonOptions options;
  options.full_newton = false;
  options.max_iterations = 100;
  NewtonRaphson newton(options, ConvergenceTest(tight()));
  int calls = 0;
  newton.set_line_search([&](const VectorXd&, const VectorXd&, double) {
    ++calls;
    return 0.5;  // half steps: the error halves each iteration
  });
  VectorXd u = VectorXd::Zero(3);
  const NewtonResult result = newton.solve(p, u);
  ASSERT_TRUE(result.converged);
  EXPECT_EQ(calls, result.iterations);
  EXPECT_GT(result.iterations, 30);
  for (std::size_t k = 1; k + 1 < result.history.size() && k < 10; ++k)
    EXPECT_NEAR(result.history[k + 1] / result.history[k], 0.5, 1e-9);
}

TEST(NewtonRaphson, APredictorInBalanceIsAcceptedWithoutIterating) {
  HardeningChain p;
  p.f.setZero();
  VectorXd u = VectorXd::Zero(3);
  const NewtonResult result = NewtonRaphson(NewtonOptions{}, ConvergenceTest(tight())).solve(p, u);
  EXPECT_TRUE(result.converged);
  EXPECT_EQ(result.iterations, 0);
  EXPECT_EQ(p.factorizations, 0);
}

/// A saturating spring, f_int = F0 (atan(u − a) + atan a), loaded by f = F0 atan a: the root is
/// u = a. Full Newton from u = 0 overshoots further at every iteration when a > 1.39 (the
/// tangent F0 / (1 + (u − a)²) flattens), the textbook divergence that a line search cures.
class SaturatingSpring final : public NonlinearProblem {
 public:
  double f0 = 100.0, a = 2.0;
  int n_unknowns() const override { return 1; }
  double residual(const VectorXd& u, VectorXd& r, double& reference) override {
    r = VectorXd::Constant(1, f0 * std::atan(a) - f0 * (std::atan(u(0) - a) + std::atan(a)));
    reference = f0 * std::atan(a);
    return std::abs(r(0));
  }
  bool tangent_stale() const override { return true; }
  void factorize_tangent(const VectorXd& u) override { k_ = f0 / (1.0 + (u(0) - a) * (u(0) - a)); }
  VectorXd solve(const VectorXd& r) override { return r / k_; }

 private:
  double k_ = 0.0;
};

TEST(NewtonRaphson, LineSearchConvergesWhereFullNewtonDiverges) {
  NewtonOptions options;
  options.max_iterations = 30;
  SaturatingSpring plain, searched;
  VectorXd u = VectorXd::Zero(1);
  const NewtonResult diverged = NewtonRaphson(options, ConvergenceTest(tight())).solve(plain, u);
  EXPECT_FALSE(diverged.converged);
  options.line_search = true;
  u.setZero();
  const NewtonResult result = NewtonRaphson(options, ConvergenceTest(tight())).solve(searched, u);
  EXPECT_TRUE(result.converged);
  EXPECT_NEAR(u(0), 2.0, 1e-9);
  EXPECT_GE(result.line_searches, 1);
  EXPECT_LE(result.iterations, 12);
}

TEST(NewtonRaphson, AutomaticLineSearchStepsInOnlyWhenTheResidualGrows) {
  // AUTO: the saturating spring's residual grows from its second correction on, and the search
  // then brings it home; the hardening chain converges without one.
  NewtonOptions options;
  options.max_iterations = 30;
  options.line_search_auto = true;
  SaturatingSpring spring;
  VectorXd u = VectorXd::Zero(1);
  const NewtonResult a = NewtonRaphson(options, ConvergenceTest(tight())).solve(spring, u);
  EXPECT_TRUE(a.converged);
  EXPECT_NEAR(u(0), 2.0, 1e-9);
  EXPECT_GE(a.line_searches, 1);
  HardeningChain chain;
  VectorXd w = VectorXd::Zero(3);
  const NewtonResult b = NewtonRaphson(options, ConvergenceTest(tight())).solve(chain, w);
  EXPECT_TRUE(b.converged);
  EXPECT_EQ(b.line_searches, 0);
}

TEST(NewtonRaphson, LineSearchKeepsTheFullStepOnAConvexProblem) {
  // The hardening chain's full corrections already halve g: the search never shortens one,
  // and the iterations are full Newton's.
  HardeningChain plain, searched;
  NewtonOptions options;
  options.max_iterations = 30;
  VectorXd u = VectorXd::Zero(3);
  const NewtonResult a = NewtonRaphson(options, ConvergenceTest(tight())).solve(plain, u);
  options.line_search = true;
  VectorXd w = VectorXd::Zero(3);
  const NewtonResult b = NewtonRaphson(options, ConvergenceTest(tight())).solve(searched, w);
  EXPECT_TRUE(b.converged);
  EXPECT_EQ(b.line_searches, 0);
  EXPECT_EQ(b.iterations, a.iterations);
  EXPECT_NEAR((u - w).norm(), 0.0, 1e-12);
}

}  // namespace
}  // namespace impactfe::test_newton_raphson
