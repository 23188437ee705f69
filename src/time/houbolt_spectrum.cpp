/// Houbolt amplification matrix (thesis eq. 3-9, re-derived) and spectral radius (eq. 3-11).
#include "time/houbolt_spectrum.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "core/errors.h"
#include "time/time_integrator.h"

namespace impactfe {

/// Substituting the backward differences (eqs. 3-2, 3-3) into x'' + 2 xi w x' + w^2 x = r
/// (eq. 3-8) at t+dt and dividing by w^2 gives
///   x_{t+dt} = A11 x_t + A12 x_{t-dt} + A13 x_{t-2dt} + beta/w^2 r_{t+dt},
///   beta = (2/(w dt)^2 + 11 xi/(3 w dt) + 1)^-1,  gamma = xi beta/(w dt),
///   A11 = 5 beta/(w dt)^2 + 6 gamma, A12 = -(4 beta/(w dt)^2 + 3 gamma),
///   A13 = beta/(w dt)^2 + 2 gamma/3   (Bathe 1996, §9.4 stability analysis of Houbolt).
/// The printed eq. 3-9 drops xi from beta and the minus sign on the 3 gamma of A12.
Eigen::Matrix3d houbolt_amplification_matrix(double dt_over_period, double damping_ratio) {
  IMPACTFE_CHECK(!(!(dt_over_period > 0.0)), "houbolt_amplification_matrix: dt/T must be positive");
  const double wdt = 2.0 * std::numbers::pi * dt_over_period;  // omega * dt
  const double xi = damping_ratio;
  const double q = 1.0 / (wdt * wdt);
  const double beta = 1.0 / (2.0 * q + 11.0 * xi / (3.0 * wdt) + 1.0);
  const double gamma = xi * beta / wdt;
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  A(0, 0) = 5.0 * beta * q + 6.0 * gamma;
  A(0, 1) = -(4.0 * beta * q + 3.0 * gamma);
  A(0, 2) = beta * q + 2.0 * gamma / 3.0;
  A(1, 0) = 1.0;
  A(2, 1) = 1.0;
  return A;
}

double spectral_radius(const Eigen::MatrixXd& A) {
  IMPACTFE_CHECK(!(A.rows() != A.cols() || A.rows() == 0),
                 "spectral_radius: matrix must be square and non-empty");
  Eigen::EigenSolver<Eigen::MatrixXd> solver(A, /*computeEigenvectors=*/false);
  return solver.eigenvalues().cwiseAbs().maxCoeff();
}

std::string houbolt_spectrum_csv(const std::vector<double>& dt_over_T,
                                 const std::vector<double>& xi) {
  std::string out = "dt_over_T,xi,spectral_radius\n";
  for (double z : xi) {
    for (double r : dt_over_T) {
      const double rho = spectral_radius(houbolt_amplification_matrix(r, z));
      out += fmt::format("{:.6g},{:.6g},{:.10g}\n", r, z, rho);
    }
  }
  return out;
}

std::vector<double> log_grid(double lo, double hi, int n) {
  IMPACTFE_CHECK(!(!(lo > 0.0 && hi > lo) || n < 2), "log_grid: need 0 < lo < hi and n >= 2");
  std::vector<double> g(n);
  const double a = std::log10(lo);
  const double b = std::log10(hi);
  for (int i = 0; i < n; ++i) g[i] = std::pow(10.0, a + (b - a) * i / (n - 1));
  g.back() = hi;
  return g;
}

}  // namespace impactfe
