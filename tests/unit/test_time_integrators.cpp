// Time integrators on a single-DOF oscillator m x'' + c x' + k x = f(t), driven by a tiny Newton
// loop that follows the residual/weights contract of src/time/time_integrator.h literally, so
// these tests also check the contract (cK, cC, cM are the exact derivative of the residual).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <vector>

#include "core/log.h"
#include "core/model.h"
#include "time/time_integrator.h"

namespace impactfe::test_time_integrators {
namespace {

/// Chung & Hulbert (1993) generalized-alpha parameters from the spectral radius at infinity
/// rho_inf in [0, 1]: alpha_m = (2 rho - 1)/(rho + 1), alpha_f = rho/(rho + 1), then the HHT
/// relations gamma = 1/2 - am + af, beta = (1 - am + af)^2 / 4.
GeneralizedAlphaParameters chung_hulbert(double rho_inf) {
  return GeneralizedAlphaParameters::hht(rho_inf / (rho_inf + 1.0),
                                         (2.0 * rho_inf - 1.0) / (rho_inf + 1.0));
}

constexpr double kPi = std::numbers::pi;

struct Sdof {
  double m = 1.0;
  double c = 0.0;
  double k = 1.0;
  std::function<double(double)> f = [](double) { return 0.0; };
};

Eigen::VectorXd vec(double x) {
  return Eigen::VectorXd::Constant(1, x);
}

/// Contract residual r(u) at trial u = u_{n+1} (header comment of time_integrator.h).
double residual(const TimeIntegrator& ti, const Sdof& s, double t, double u) {
  const ResidualWeights w = ti.weights();
  Eigen::VectorXd v1, a1;
  ti.kinematics(vec(u), v1, a1);
  const double h = ti.step();
  const double un = ti.u()(0), vn = ti.v()(0), an = ti.a()(0);
  return w.external * s.f(t + h) + (1.0 - w.external) * s.f(t) - w.inertia * s.m * a1(0) -
         (1.0 - w.inertia) * s.m * an - w.stiffness * (s.k * u + s.c * v1(0)) -
         (1.0 - w.stiffness) * (s.k * un + s.c * vn);
}

double effective_stiffness(const TimeIntegrator& ti, const Sdof& s) {
  const IntegrationCoefficients c = ti.coefficients();
  return c.cK * s.k + c.cC * s.c + c.cM * s.m;
}

/// One Newton step from the predictor. The problem is linear, so one correction must give
/// equilibrium; the test asserts that (a wrong cK/cC/cM would leave a residual).
void take_step(TimeIntegrator& ti, const Sdof& s, double t) {
  double u = ti.predict()(0);
  const double r0 = residual(ti, s, t, u);
  u += r0 / effective_stiffness(ti, s);
  const double r1 = residual(ti, s, t, u);
  // Round-off scale: every term of r is a coefficient times a displacement of size |u|, |u_n|.
  const double scale = effective_stiffness(ti, s) * (std::abs(u) + std::abs(ti.u()(0))) +
                       std::abs(s.f(t + ti.step())) + 1e-300;
  ASSERT_LE(std::abs(r1), 1e-10 * scale) << ti.name() << " residual after one Newton step";
  ti.advance(vec(u));
}

void start(TimeIntegrator& ti, const Sdof& s, double x0, double v0, double h) {
  const double a0 = (s.f(0.0) - s.c * v0 - s.k * x0) / s.m;  // equilibrium at t = 0
  ti.start(vec(x0), vec(v0), vec(a0), h);
}

/// Integrates to t_end with n steps; returns max |x_i - exact(t_i)| over the steps.
double max_error(TimeIntegrator& ti, const Sdof& s, double x0, double v0, double t_end, int n,
                 const std::function<double(double)>& exact) {
  const double h = t_end / n;
  start(ti, s, x0, v0, h);
  double err = 0.0;
  for (int i = 0; i < n; ++i) {
    take_step(ti, s, i * h);
    err = std::max(err, std::abs(ti.u()(0) - exact((i + 1) * h)));
  }
  return err;
}

/// Closed form of x'' + 2 xi w x' + w^2 x = f/m (constant f), xi < 1.
double exact_sdof(const Sdof& s, double f, double x0, double v0, double t) {
  const double w = std::sqrt(s.k / s.m);
  const double xi = s.c / (2.0 * std::sqrt(s.k * s.m));
  const double wd = w * std::sqrt(1.0 - xi * xi);
  const double xs = f / s.k;
  const double A = x0 - xs;
  const double B = (v0 + xi * w * A) / wd;
  return xs + std::exp(-xi * w * t) * (A * std::cos(wd * t) + B * std::sin(wd * t));
}

using Factory = std::function<std::unique_ptr<TimeIntegrator>()>;

struct Scheme {
  const char* label;
  Factory make;
};

std::vector<Scheme> second_order_schemes() {
  return {
      {"Newmark average acceleration",
       [] {
         return make_generalized_alpha(GeneralizedAlphaParameters::newmark_beta_gamma(0.25, 0.5));
       }},
      {"HHT alpha_f=0.1",
       [] { return make_generalized_alpha(GeneralizedAlphaParameters::hht(0.1)); }},
      {"generalized-alpha rho_inf=0.8", [] { return make_generalized_alpha(chung_hulbert(0.8)); }},
      {"Houbolt", [] { return make_houbolt(); }},
  };
}

/// Period T = 1 (w = 2 pi), x0 = 1, v0 = 0.5, integrated over two periods with h = T/50 .. T/400;
/// error = max |x_i - x(t_i)| over the steps against the closed form. The observed order
/// log2(e(h)/e(h/2)) of every pair must lie in 2 +- 0.05 (observed: 1.97..2.00 for Houbolt,
/// 1.997..2.000 for the others). Error bound at h = T/400: 5e-3 (the period error of these
/// schemes is O((w h)^2) per radian, (w h)^2 = 2.5e-4, times w t_end = 12.6 gives ~3e-3).
void check_order(double xi, double force) {
  Sdof s;
  s.m = 2.0;
  s.k = s.m * 4.0 * kPi * kPi;
  s.c = 2.0 * xi * std::sqrt(s.k * s.m);
  s.f = [force](double) { return force; };
  const double x0 = 1.0, v0 = 0.5, t_end = 2.0;
  auto exact = [&](double t) { return exact_sdof(s, force, x0, v0, t); };
  for (const Scheme& scheme : second_order_schemes()) {
    std::vector<double> err;
    for (int n : {100, 200, 400, 800}) {
      auto ti = scheme.make();
      err.push_back(max_error(*ti, s, x0, v0, t_end, n, exact));
    }
    for (size_t i = 1; i < err.size(); ++i) {
      const double order = std::log2(err[i - 1] / err[i]);
      std::printf("%s xi=%g h=T/%d err=%.3e order=%.3f\n", scheme.label, xi, 50 << i, err[i],
                  order);
      EXPECT_NEAR(order, 2.0, 0.05)
          << scheme.label << " xi=" << xi << " errors " << err[i - 1] << " -> " << err[i];
    }
    EXPECT_LT(err.back(), 5e-3) << scheme.label << " xi=" << xi;
  }
}

TEST(TimeIntegrators, SecondOrderUndamped) {
  check_order(0.0, 0.0);
}
TEST(TimeIntegrators, SecondOrderDampedWithLoad) {
  check_order(0.05, 30.0);
}

/// K_eff = cK K + cC C + cM M must be minus the derivative of the contract residual.
TEST(TimeIntegrators, CoefficientsAreResidualDerivative) {
  Sdof s{3.0, 0.7, 50.0, [](double t) { return 4.0 + t; }};
  std::vector<Scheme> schemes = second_order_schemes();
  schemes.push_back({"Newmark g=0.1", [] {
                       return make_generalized_alpha(GeneralizedAlphaParameters::newmark(0.1));
                     }});
  for (const Scheme& scheme : schemes) {
    auto ti = scheme.make();
    start(*ti, s, 0.3, -0.2, 0.01);
    take_step(*ti, s, 0.0);  // non-trivial history
    const double u = 0.31, du = 1e-3;
    const double slope =
        (residual(*ti, s, 0.01, u + du) - residual(*ti, s, 0.01, u - du)) / (2 * du);
    EXPECT_NEAR(-slope, effective_stiffness(*ti, s), 1e-7 * effective_stiffness(*ti, s))
        << scheme.label;
  }
}

/// Trapezoidal rule (beta = 1/4, gamma = 1/2) conserves 1/2 m v^2 + 1/2 k x^2 exactly for a
/// linear undamped system (it is the implicit midpoint rule in (x, v)). Tolerance 1e-12 relative
/// over 1000 steps (round-off only).
TEST(TimeIntegrators, TrapezoidalConservesEnergy) {
  Sdof s{2.0, 0.0, 2.0 * 4.0 * kPi * kPi, [](double) { return 0.0; }};
  auto ti = make_generalized_alpha(GeneralizedAlphaParameters::newmark_beta_gamma(0.25, 0.5));
  const double h = 1.0 / 20.0;
  start(*ti, s, 1.0, 0.3, h);
  auto energy = [&] {
    return 0.5 * s.m * ti->v()(0) * ti->v()(0) + 0.5 * s.k * ti->u()(0) * ti->u()(0);
  };
  const double e0 = energy();
  double worst = 0.0;
  for (int i = 0; i < 1000; ++i) {
    take_step(*ti, s, i * h);
    worst = std::max(worst, std::abs(energy() - e0) / e0);
  }
  EXPECT_LT(worst, 1e-12);
}

/// Newmark with gamma > 1/2 (TINTP GAMMA = 0.1: beta = 0.3025, gamma = 0.6) dissipates: the
/// energy after 10 periods at h = T/10 is below 0.9 of the initial energy and never grows by
/// more than round-off. (Trapezoidal would keep it to 1e-12, see above.)
TEST(TimeIntegrators, NewmarkWithGammaAboveHalfDissipates) {
  Sdof s{1.0, 0.0, 4.0 * kPi * kPi, [](double) { return 0.0; }};
  auto ti = make_generalized_alpha(GeneralizedAlphaParameters::newmark(0.1));
  const double h = 0.1;
  start(*ti, s, 1.0, 0.0, h);
  auto energy = [&] {
    return 0.5 * s.m * ti->v()(0) * ti->v()(0) + 0.5 * s.k * ti->u()(0) * ti->u()(0);
  };
  const double e0 = energy();
  for (int i = 0; i < 100; ++i) take_step(*ti, s, i * h);
  EXPECT_LT(energy(), 0.9 * e0);
  EXPECT_GT(energy(), 0.0);
}

/// Numerical amplification matrix of a one-step scheme in the state (u, v, h a): one step from
/// each unit state, undamped, unloaded, w h given.
Eigen::Matrix3d one_step_amplification(const Factory& make, double omega_h) {
  Sdof s{1.0, 0.0, omega_h * omega_h, [](double) { return 0.0; }};
  Eigen::Matrix3d A;
  for (int j = 0; j < 3; ++j) {
    auto ti = make();
    Eigen::Vector3d e = Eigen::Vector3d::Unit(j);
    ti->start(vec(e(0)), vec(e(1)), vec(e(2)), 1.0);  // h = 1, a scaled by h^2 = 1
    double u = ti->predict()(0);
    u += residual(*ti, s, 0.0, u) / effective_stiffness(*ti, s);
    ti->advance(vec(u));
    A.col(j) << ti->u()(0), ti->v()(0), ti->a()(0);
  }
  return A;
}

double rho(const Eigen::Matrix3d& A) {
  return Eigen::EigenSolver<Eigen::Matrix3d>(A, false).eigenvalues().cwiseAbs().maxCoeff();
}

/// Spectral radius at w h -> infinity (evaluated at w h = 1e5):
///  HHT-alpha (Hilber, Hughes & Taylor 1977, ANSYS sign alpha >= 0): rho_inf = (1-a)/(1+a);
///    alpha = 0.1 -> 0.818182.
///  Newmark with amplitude decay g (beta = (1+g)^2/4, gamma = 1/2+g): rho_inf = (1-g)/(1+g)
///    (the limit map has the double eigenvalue (s-2)/s with s = 1 + g).
///  Chung-Hulbert generalized-alpha: rho_inf is the parameter itself.
/// Tolerance 2e-3 (the finite w h and the nearly defective eigenvalue at the limit).
TEST(TimeIntegrators, SpectralRadiusAtInfinity) {
  const double wh = 1e5;
  for (double a : {0.05, 0.1, 0.3}) {
    const double r = rho(one_step_amplification(
        [a] { return make_generalized_alpha(GeneralizedAlphaParameters::hht(a)); }, wh));
    EXPECT_NEAR(r, (1.0 - a) / (1.0 + a), 2e-3) << "HHT alpha=" << a;
  }
  EXPECT_NEAR(rho(one_step_amplification(
                  [] { return make_generalized_alpha(GeneralizedAlphaParameters::hht(0.1)); }, wh)),
              0.9 / 1.1, 2e-3);
  for (double g : {0.005, 0.1}) {
    const double r = rho(one_step_amplification(
        [g] { return make_generalized_alpha(GeneralizedAlphaParameters::newmark(g)); }, wh));
    EXPECT_NEAR(r, (1.0 - g) / (1.0 + g), 2e-3) << "Newmark g=" << g;
  }
  for (double r_inf : {0.5, 0.8, 1.0}) {
    const double r = rho(one_step_amplification(
        [r_inf] { return make_generalized_alpha(chung_hulbert(r_inf)); }, wh));
    EXPECT_NEAR(r, r_inf, 2e-3) << "generalized-alpha rho_inf=" << r_inf;
  }
  // Trapezoidal: no dissipation at any w h.
  for (double w : {0.1, 1.0, 10.0, 1e3}) {
    const double r = rho(one_step_amplification(
        [] {
          return make_generalized_alpha(GeneralizedAlphaParameters::newmark_beta_gamma(0.25, 0.5));
        },
        w));
    EXPECT_NEAR(r, 1.0, 1e-9) << "trapezoidal w h=" << w;
  }
}

/// Chung-Hulbert relations (1993, eqs. 25 and 17): am = (2r-1)/(r+1), af = r/(r+1),
/// gamma = 1/2 - am + af, beta = (1 - am + af)^2/4. For r = 0.5: am = 0, af = 1/3,
/// gamma = 5/6, beta = 4/9.
TEST(TimeIntegrators, ChungHulbertParameters) {
  // (chung_hulbert above is the test's parametrisation of the generalized-alpha class.)
  const auto p = chung_hulbert(0.5);
  EXPECT_NEAR(p.alpha_m, 0.0, 1e-15);
  EXPECT_NEAR(p.alpha_f, 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(p.gamma, 5.0 / 6.0, 1e-15);
  EXPECT_NEAR(p.beta, 4.0 / 9.0, 1e-15);
}

/// Free fall from x0 with v0 under constant force m g: Houbolt with the uniformly accelerated
/// start-up integrates the parabola x0 + v0 t + g t^2/2 exactly (relative 1e-12), also across
/// the helmet's step changes 0.004 -> 0.0004 -> 6.667e-5 (spec §10.2).
TEST(Houbolt, FreeFallIsExactAcrossStepChanges) {
  const double g = 386.4, x0 = 1.5, v0 = -3.0;
  Sdof s{0.05, 0.0, 0.0, [&](double) { return 0.05 * g; }};
  auto ti = make_houbolt();
  start(*ti, s, x0, v0, 0.004);
  double t = 0.0;
  auto check = [&] {
    const double scale = std::abs(x0) + std::abs(v0 * t) + 0.5 * g * t * t;
    EXPECT_NEAR(ti->u()(0), x0 + v0 * t + 0.5 * g * t * t, 1e-12 * scale) << "t=" << t;
    EXPECT_NEAR(ti->v()(0), v0 + g * t, 1e-9 * (std::abs(v0) + g * t)) << "t=" << t;
    EXPECT_NEAR(ti->a()(0), g, 1e-6 * g) << "t=" << t;
  };
  for (auto [h, n] :
       std::vector<std::pair<double, int>>{{0.004, 20}, {0.0004, 30}, {6.667e-5, 40}}) {
    ti->set_step(h);
    EXPECT_EQ(ti->step(), h);
    for (int i = 0; i < n; ++i) {
      take_step(*ti, s, t);
      t += h;
      check();
    }
  }
}

/// Start at rest and unloaded, force F switched on after t = 0: the history is u0 three times,
/// so (2m/h^2) u1 = F, u1 = F h^2/(2m) (spec §10.2, the car-crash impulse step).
TEST(Houbolt, StepLoadFromRestFirstStep) {
  const double m = 0.0073, F = 12.0, h = 1e-4;
  Sdof s{m, 0.0, 0.0, [&](double t) { return t > 0.0 ? F : 0.0; }};
  auto ti = make_houbolt();
  start(*ti, s, 0.0, 0.0, h);
  take_step(*ti, s, 0.0);
  EXPECT_NEAR(ti->u()(0), F * h * h / (2.0 * m), 1e-14 * F * h * h / m);
}

/// The backward differences (thesis eqs. 3-2, 3-3) are exact for a cubic once the history holds
/// cubic samples: after three advances with u(t) = 1 + 2t - 3t^2 + 5t^3, kinematics() of the
/// next sample gives u'(t), u''(t) to 1e-9 relative.
TEST(Houbolt, BackwardDifferencesExactForCubic) {
  auto c = [](double t) { return 1.0 + 2.0 * t - 3.0 * t * t + 5.0 * t * t * t; };
  auto dc = [](double t) { return 2.0 - 6.0 * t + 15.0 * t * t; };
  auto ddc = [](double t) { return -6.0 + 30.0 * t; };
  const double h = 0.1;
  auto ti = make_houbolt();
  ti->start(vec(c(0)), vec(dc(0)), vec(ddc(0)), h);
  for (int i = 1; i <= 3; ++i) ti->advance(vec(c(i * h)));
  Eigen::VectorXd v, a;
  ti->kinematics(vec(c(4 * h)), v, a);
  EXPECT_NEAR(v(0), dc(4 * h), 1e-9 * std::abs(dc(4 * h)));
  EXPECT_NEAR(a(0), ddc(4 * h), 1e-9 * std::abs(ddc(4 * h)));
  // The state reported after advance is the same pair of formulas.
  ti->advance(vec(c(4 * h)));
  EXPECT_NEAR(ti->v()(0), dc(4 * h), 1e-9 * std::abs(dc(4 * h)));
  EXPECT_NEAR(ti->a()(0), ddc(4 * h), 1e-9 * std::abs(ddc(4 * h)));
  // Coefficients: cK = 1, cC = 11/(6h), cM = 2/h^2 (thesis eq. 3-4).
  const auto k = ti->coefficients();
  EXPECT_DOUBLE_EQ(k.cK, 1.0);
  EXPECT_DOUBLE_EQ(k.cC, 11.0 / (6.0 * h));
  EXPECT_DOUBLE_EQ(k.cM, 2.0 / (h * h));
}

/// After set_step the history is the parabola through the current state at the new spacing:
/// the state (u, v, a) is unchanged and kinematics() of u + h v + h^2 a/2 returns v + h a and a.
TEST(Houbolt, StepChangeKeepsStateAndResamplesHistory) {
  auto ti = make_houbolt();
  ti->start(vec(0.0), vec(1.0), vec(0.0), 0.01);
  for (int i = 1; i <= 5; ++i) ti->advance(vec(std::sin(0.01 * i)));
  const double u = ti->u()(0), v = ti->v()(0), a = ti->a()(0);
  const double h = 0.001;
  ti->set_step(h);
  EXPECT_EQ(ti->u()(0), u);
  EXPECT_EQ(ti->v()(0), v);
  EXPECT_EQ(ti->a()(0), a);
  Eigen::VectorXd vn, an;
  ti->kinematics(vec(u + h * v + 0.5 * h * h * a), vn, an);
  EXPECT_NEAR(vn(0), v + h * a, 1e-9);
  EXPECT_NEAR(an(0), a, 1e-6);
  EXPECT_NEAR(ti->predict()(0), u + h * v + 0.5 * h * h * a, 1e-15);
}

/// A step that differs from the current one only by round-off (1e-12 relative) keeps the true
/// history: kinematics() is unchanged (1e-9) for a non-parabolic history u = sin(10 t), whereas a
/// real change re-samples (the acceleration then differs by O(h |u'''|) = O(100)).
TEST(Houbolt, RoundOffStepChangeKeepsHistory) {
  const double h = 0.1;
  auto ti = make_houbolt();
  ti->start(vec(0.0), vec(10.0), vec(0.0), h);
  for (int i = 1; i <= 4; ++i) ti->advance(vec(std::sin(10.0 * i * h)));
  Eigen::VectorXd v0, a0, v1, a1;
  const Eigen::VectorXd trial = vec(std::sin(10.0 * 5 * h));
  ti->kinematics(trial, v0, a0);
  ti->set_step(h * (1.0 + 1e-12));
  ti->kinematics(trial, v1, a1);
  EXPECT_NEAR(a1(0), a0(0), 1e-9 * std::abs(a0(0)));
  EXPECT_NEAR(v1(0), v0(0), 1e-9 * std::abs(v0(0)));
  ti->set_step(h * 1.001);
  ti->kinematics(trial, v1, a1);
  EXPECT_GT(std::abs(a1(0) - a0(0)), 1.0);
}

TEST(TimeIntegrators, RequireStart) {
  Eigen::VectorXd v, a;
  EXPECT_THROW(make_houbolt()->kinematics(vec(0.0), v, a), std::logic_error);
  EXPECT_THROW(make_generalized_alpha({})->kinematics(vec(0.0), v, a), std::logic_error);
}

/// make_time_integrator follows TINTP (spec §10.3): Newmark default g = 0.005 -> beta =
/// 0.25250625, gamma = 0.505; explicit ALPHA/DELTA are textbook beta/gamma; HHT default
/// alpha_f = 0.005, alpha_m = 0; HHT with GAMMA g -> alpha_f = g. Parameters are read back
/// from the coefficients: beta = 1/(cM h^2) (when am = 0), gamma = cC beta h / cK.
TEST(TimeIntegrators, FactoryFollowsTintp) {
  const double h = 0.01;
  auto params = [h](const TimeIntegrator& ti, double& beta, double& gamma) {
    const auto c = ti.coefficients();
    const auto w = ti.weights();
    beta = w.inertia / (c.cM * h * h);
    gamma = c.cC * beta * h / c.cK;
  };
  double beta = 0, gamma = 0;
  AnalysisOptions o;
  o.integrator = IntegratorKind::Houbolt;
  EXPECT_EQ(make_time_integrator(o)->name(), "Houbolt");

  o.integrator = IntegratorKind::Newmark;
  auto ti = make_time_integrator(o);
  ti->set_step(h);
  params(*ti, beta, gamma);
  EXPECT_NEAR(beta, 0.25250625, 1e-12);
  EXPECT_NEAR(gamma, 0.505, 1e-12);
  EXPECT_DOUBLE_EQ(ti->weights().external, 1.0);

  o.tintp.alpha = 0.25;
  o.tintp.delta = 0.5;
  ti = make_time_integrator(o);
  ti->set_step(h);
  params(*ti, beta, gamma);
  EXPECT_NEAR(beta, 0.25, 1e-12);
  EXPECT_NEAR(gamma, 0.5, 1e-12);

  o.tintp.gamma = 0.1;  // GAMMA given wins
  ti = make_time_integrator(o);
  ti->set_step(h);
  params(*ti, beta, gamma);
  EXPECT_NEAR(beta, 0.3025, 1e-12);
  EXPECT_NEAR(gamma, 0.6, 1e-12);

  o.tintp = {};
  o.integrator = IntegratorKind::HHT;
  ti = make_time_integrator(o);
  ti->set_step(h);
  EXPECT_NEAR(ti->weights().external, 1.0 - 0.005, 1e-15);
  EXPECT_NEAR(ti->weights().stiffness, 1.0 - 0.005, 1e-15);
  EXPECT_NEAR(ti->weights().inertia, 1.0, 1e-15);
  params(*ti, beta, gamma);
  EXPECT_NEAR(beta, 1.005 * 1.005 / 4.0, 1e-12);
  EXPECT_NEAR(gamma, 0.505, 1e-12);

  o.tintp.gamma = 0.1;
  ti = make_time_integrator(o);
  ti->set_step(h);
  EXPECT_NEAR(ti->weights().external, 0.9, 1e-15);
  EXPECT_NEAR(ti->weights().inertia, 1.0, 1e-15);

  o.tintp = {};
  o.tintp.alpha_f = 0.2;
  o.tintp.alpha_m = 0.1;
  ti = make_time_integrator(o);
  ti->set_step(h);
  EXPECT_NEAR(ti->weights().external, 0.8, 1e-15);
  EXPECT_NEAR(ti->weights().inertia, 0.9, 1e-15);
  // beta = (1 + af - am)^2/4 = 0.3025, read back with the inertia weight.
  params(*ti, beta, gamma);
  EXPECT_NEAR(beta, 0.3025, 1e-12);
  EXPECT_NEAR(gamma, 0.6, 1e-12);
}

/// Conditionally stable TINTP values are accepted but logged: Newmark beta = 0.1 < gamma/2 = 0.25
/// (Hughes 2000, §9.1.2) warns once; the default Newmark and HHT presets do not warn.
TEST(TimeIntegrators, FactoryWarnsOnConditionalStability) {
  Log::set_sink([](LogLevel, const std::string&) {});
  Log::clear();
  AnalysisOptions o;
  o.integrator = IntegratorKind::Newmark;
  make_time_integrator(o);
  o.integrator = IntegratorKind::HHT;
  make_time_integrator(o);
  EXPECT_EQ(Log::warnings().size(), 0u);
  o.integrator = IntegratorKind::Newmark;
  o.tintp.alpha = 0.1;
  o.tintp.delta = 0.5;
  make_time_integrator(o);
  EXPECT_EQ(Log::warnings().size(), 1u);
  Log::clear();
}

TEST(TimeIntegrators, RejectsNonPositiveStep) {
  auto h = make_houbolt();
  EXPECT_THROW(h->set_step(0.0), InputError);
  auto n = make_generalized_alpha(GeneralizedAlphaParameters::newmark(0.0));
  EXPECT_THROW(n->set_step(-1.0), InputError);
}

}  // namespace
}  // namespace impactfe::test_time_integrators
