// Houbolt amplification matrix (thesis eq. 3-9, re-derived) and its spectral radius (thesis
// eq. 3-11, Fig. 3-4).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "core/errors.h"
#include "time/houbolt_spectrum.h"
#include "time/time_integrator.h"

namespace impactfe::test_houbolt_spectrum {
namespace {

constexpr double kPi = std::numbers::pi;

/// Thesis Fig. 3-4: rho(A) <= 1 for every dt/T (unconditional stability), on a log grid
/// 1e-3..1e3 (121 points) for xi = 0 and 0.05. Tolerance 1e-12 above 1 (round-off of the
/// eigen-solver near the double root at dt/T -> 0).
TEST(HouboltSpectrum, UnconditionallyStable) {
  for (double xi : {0.0, 0.05}) {
    for (double r : log_grid(1e-3, 1e3, 121)) {
      EXPECT_LE(spectral_radius(houbolt_amplification_matrix(r, xi)), 1.0 + 1e-12)
          << "dt/T=" << r << " xi=" << xi;
    }
  }
}

/// Fig. 3-4 shape: rho -> 1 as dt/T -> 0 (consistency: rho > 0.999 at dt/T = 1e-3), and
/// rho -> 0 as dt/T -> infinity, monotonically over 10..1e3. Asymptotics of the characteristic
/// polynomial (see EigenvaluesAreRootsOfTheRecursion) for large w h, small l:
///   xi = 0:  (w h)^2 l^3 ~ -1            -> rho ~ (w h)^(-2/3)         = 0.00294 at dt/T = 1e3
///   xi > 0:  (w h)^2 l^3 ~ -2 xi w h / 3 -> rho ~ (2 xi / (3 w h))^(1/3) = 0.0174 (xi = 0.05)
/// (physical damping slows the decay to zero). Tolerance 20 % relative on those estimates
/// (next-order terms are O(rho)).
TEST(HouboltSpectrum, LimitsOfFigure3_4) {
  for (double xi : {0.0, 0.05}) {
    const auto rho = [xi](double r) {
      return spectral_radius(houbolt_amplification_matrix(r, xi));
    };
    EXPECT_GT(rho(1e-3), 0.999) << xi;
    EXPECT_LT(rho(1e3), rho(1e2)) << xi;
    EXPECT_LT(rho(1e2), rho(10.0)) << xi;
    const double wh = 2.0 * kPi * 1e3;
    const double estimate = xi == 0.0 ? std::pow(wh, -2.0 / 3.0) : std::cbrt(2.0 * xi / (3.0 * wh));
    EXPECT_NEAR(rho(1e3), estimate, 0.2 * estimate) << xi;
  }
}

/// Fig. 3-4 shows rho decreasing monotonically with dt/T; checked on 601 log-spaced points
/// 1e-3..1e3 (allowing 1e-12 of round-off between neighbours).
TEST(HouboltSpectrum, DecreasesMonotonically) {
  for (double xi : {0.0, 0.05}) {
    double previous = 1.0 + 1e-12;
    for (double r : log_grid(1e-3, 1e3, 601)) {
      const double rho = spectral_radius(houbolt_amplification_matrix(r, xi));
      EXPECT_LE(rho, previous + 1e-12) << "dt/T=" << r << " xi=" << xi;
      previous = rho;
    }
  }
}

/// Undamped Houbolt damps numerically: rho < 1 strictly at dt/T = 0.01, 0.1, 1 (Bathe: the
/// amplitude decay is noticeable already at dt/T = 0.1).
TEST(HouboltSpectrum, NumericalDampingWhenUndamped) {
  for (double r : {0.01, 0.1, 1.0}) {
    EXPECT_LT(spectral_radius(houbolt_amplification_matrix(r, 0.0)), 1.0 - 1e-8) << r;
  }
}

/// Every eigenvalue l of A is a root of the characteristic polynomial of the Houbolt recursion,
/// written directly from thesis eqs. 3-2, 3-3 and 3-8 with x_n = l^n (times h^2):
///   (2 l^3 - 5 l^2 + 4 l - 1) + xi w h (11 l^3 - 18 l^2 + 9 l - 2)/3 + (w h)^2 l^3 = 0.
/// Tolerance: |p(l)| <= 1e-10 times the sum of the magnitudes of the terms.
TEST(HouboltSpectrum, EigenvaluesAreRootsOfTheRecursion) {
  for (double xi : {0.0, 0.05, 0.3}) {
    for (double r : {0.001, 0.03, 0.2, 1.0, 17.0}) {
      const double wh = 2.0 * kPi * r;
      Eigen::EigenSolver<Eigen::Matrix3d> es(houbolt_amplification_matrix(r, xi), false);
      for (int i = 0; i < 3; ++i) {
        const std::complex<double> l = es.eigenvalues()(i);
        const std::complex<double> l2 = l * l, l3 = l2 * l;
        const std::complex<double> p = (2.0 * l3 - 5.0 * l2 + 4.0 * l - 1.0) +
                                       xi * wh * (11.0 * l3 - 18.0 * l2 + 9.0 * l - 2.0) / 3.0 +
                                       wh * wh * l3;
        const double scale =
            2.0 * std::abs(l3) + 5.0 * std::abs(l2) + 4.0 * std::abs(l) + 1.0 +
            xi * wh * (11.0 * std::abs(l3) + 18.0 * std::abs(l2) + 9.0 * std::abs(l) + 2.0) / 3.0 +
            wh * wh * std::abs(l3);
        EXPECT_LE(std::abs(p), 1e-10 * scale) << "dt/T=" << r << " xi=" << xi << " l=" << l;
      }
    }
  }
}

/// Iterating A (eq. 3-10) reproduces the Houbolt integrator itself on x'' + 2 xi w x' + w^2 x = 0
/// (one linear solve per step through the residual contract: weights 1, K_eff = k + cC c + cM m),
/// starting from the uniformly accelerated history u_{-1} = u0 - h v0 + h^2 a0/2,
/// u_{-2} = u0 - 2h v0 + 2h^2 a0 (spec §10.2). 60 steps, relative 1e-10.
TEST(HouboltSpectrum, MatrixReproducesIntegrator) {
  const double r = 0.07, xi = 0.05, T = 0.5;
  const double h = r * T, w = 2.0 * kPi / T;
  const double m = 3.0, k = m * w * w, c = 2.0 * xi * w * m;
  const double u0 = 0.2, v0 = -1.3, a0 = (-c * v0 - k * u0) / m;
  auto ti = make_houbolt();
  ti->start(Eigen::VectorXd::Constant(1, u0), Eigen::VectorXd::Constant(1, v0),
            Eigen::VectorXd::Constant(1, a0), h);
  Eigen::Vector3d x(u0, u0 - h * v0 + 0.5 * h * h * a0, u0 - 2 * h * v0 + 2 * h * h * a0);
  const Eigen::Matrix3d A = houbolt_amplification_matrix(r, xi);
  const auto coef = ti->coefficients();
  for (int n = 0; n < 60; ++n) {
    Eigen::VectorXd u = ti->predict(), v, a;
    ti->kinematics(u, v, a);
    const double res = -m * a(0) - (k * u(0) + c * v(0));
    u(0) += res / (coef.cK * k + coef.cC * c + coef.cM * m);
    ti->advance(u);
    x = A * x;
    EXPECT_NEAR(ti->u()(0), x(0), 1e-10 * (std::abs(u0) + std::abs(v0) * T)) << "step " << n + 1;
  }
}

/// CSV for `impactfe houbolt-spectrum`: header, one row per (xi, dt/T), values parse back and
/// equal spectral_radius() to the printed precision (1e-9).
TEST(HouboltSpectrum, CsvTable) {
  const std::vector<double> r = {0.01, 1.0, 100.0};
  const std::vector<double> xi = {0.0, 0.05};
  const std::string csv = houbolt_spectrum_csv(r, xi);
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "dt_over_T,xi,spectral_radius");
  int rows = 0;
  for (double z : xi) {
    for (double q : r) {
      ASSERT_TRUE(std::getline(in, line));
      double a = 0, b = 0, rho = 0;
      ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf", &a, &b, &rho), 3) << line;
      EXPECT_DOUBLE_EQ(a, q);
      EXPECT_DOUBLE_EQ(b, z);
      EXPECT_NEAR(rho, spectral_radius(houbolt_amplification_matrix(q, z)), 1e-9);
      ++rows;
    }
  }
  EXPECT_EQ(rows, 6);
  EXPECT_FALSE(std::getline(in, line));
}

TEST(HouboltSpectrum, LogGridAndBadInput) {
  const auto g = log_grid(1e-3, 1e3, 7);
  ASSERT_EQ(g.size(), 7u);
  for (int i = 0; i < 7; ++i) EXPECT_NEAR(g[i], std::pow(10.0, i - 3), 1e-12 * g[i]);
  EXPECT_THROW(houbolt_amplification_matrix(0.0, 0.0), InternalError);
  EXPECT_THROW(log_grid(1.0, 0.5, 3), InternalError);
  EXPECT_THROW(spectral_radius(Eigen::MatrixXd(2, 3)), InternalError);
  // spectral_radius of a known matrix: eigenvalues 2 and -3.
  Eigen::MatrixXd M(2, 2);
  M << 0, 6, 1, -1;
  EXPECT_NEAR(spectral_radius(M), 3.0, 1e-12);
}

}  // namespace
}  // namespace impactfe::test_houbolt_spectrum
