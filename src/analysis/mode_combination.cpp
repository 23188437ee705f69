#include "analysis/mode_combination.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace impactfe {

namespace {

/// Interpolates y(x) between (x0, y0) and (x1, y1): in log x and log y unless `linear` or a
/// value is not positive (a logarithm needs both ends positive; then linear).
double interpolate(double x, double x0, double x1, double y0, double y1, bool linear) {
  if (x1 == x0) return y0;
  const bool log_x = !linear && x0 > 0.0 && x1 > 0.0 && x > 0.0;
  const bool log_y = !linear && y0 > 0.0 && y1 > 0.0;
  const double w = log_x ? std::log(x / x0) / std::log(x1 / x0) : (x - x0) / (x1 - x0);
  return log_y ? std::exp(std::log(y0) + w * std::log(y1 / y0)) : y0 + w * (y1 - y0);
}

/// The value of one curve at f: the extreme values outside the table (SV notes).
double curve_value(const std::vector<double>& freqs, const std::vector<double>& values, double f,
                   bool linear) {
  const auto n = std::min(freqs.size(), values.size());
  if (n == 0) return 0.0;
  if (f <= freqs.front() || n == 1) return values.front();
  if (f >= freqs[n - 1]) return values[n - 1];
  std::size_t k = 1;
  while (k < n - 1 && freqs[k] < f) ++k;
  return interpolate(f, freqs[k - 1], freqs[k], values[k - 1], values[k], linear);
}

}  // namespace

double spectrum_value(const SpectrumTable& table, double f, double zeta) {
  const auto& curves = table.curves;
  if (curves.empty()) return 0.0;
  auto at = [&](const SpectrumCurve& c) {
    return curve_value(table.frequencies, c.values, f, table.linear);
  };
  if (curves.size() == 1 || zeta <= curves.front().damping) return at(curves.front());
  if (zeta >= curves.back().damping) return at(curves.back());
  std::size_t k = 1;
  while (k < curves.size() - 1 && curves[k].damping < zeta) ++k;
  return interpolate(zeta, curves[k - 1].damping, curves[k].damping, at(curves[k - 1]),
                     at(curves[k]), table.linear);
}

Eigen::MatrixXd mode_correlation(CombinationMethod method, const Eigen::VectorXd& omega,
                                 const Eigen::VectorXd& zeta, double duration) {
  const auto n = omega.size();
  Eigen::MatrixXd eps = Eigen::MatrixXd::Identity(n, n);
  switch (method) {
    case CombinationMethod::SRSS:
    case CombinationMethod::NRLSUM:
      break;
    case CombinationMethod::CQC:
      // ε_ij = 8 √(ξi ξj) (ξi + r ξj) r^{3/2} / ((1 − r²)² + 4 ξi ξj r (1 + r²) + 4 (ξi² + ξj²)
      // r²), r = ωj / ωi (Theory Reference, CQC method). Undamped modes are uncorrelated.
      for (Eigen::Index i = 0; i < n; ++i)
        for (Eigen::Index j = 0; j < n; ++j) {
          if (i == j) continue;
          const double r = omega(j) / omega(i), xi = zeta(i), xj = zeta(j);
          const double num = 8.0 * std::sqrt(xi * xj) * (xi + r * xj) * std::pow(r, 1.5);
          const double den = std::pow(1.0 - r * r, 2) + 4.0 * xi * xj * r * (1.0 + r * r) +
                             4.0 * (xi * xi + xj * xj) * r * r;
          eps(i, j) = den > 0.0 ? num / den : 0.0;
        }
      break;
    case CombinationMethod::GRP: {
      // Closely spaced modes: a group runs while the frequencies stay within 10 % of its lowest
      // one; every pair within a group is fully correlated.
      Eigen::Index start = 0;
      while (start < n) {
        Eigen::Index end = start + 1;
        while (end < n && omega(end) <= 1.1 * omega(start)) ++end;
        eps.block(start, start, end - start, end - start).setOnes();
        start = end;
      }
      break;
    }
    case CombinationMethod::DSUM:
      // ε_ij = 1 / (1 + ((ω'i − ω'j) / (ξ'i ωi + ξ'j ωj))²), ω' = ω √(1 − ξ²), ξ' = ξ + 2/(td ω)
      // (Rosenblueth's double sum, Theory Reference).
      for (Eigen::Index i = 0; i < n; ++i)
        for (Eigen::Index j = 0; j < n; ++j) {
          if (i == j) continue;
          auto damped = [&](Eigen::Index k) {
            return omega(k) * std::sqrt(std::max(0.0, 1.0 - zeta(k) * zeta(k)));
          };
          auto zeta_td = [&](Eigen::Index k) { return zeta(k) + 2.0 / (duration * omega(k)); };
          const double q =
              (damped(i) - damped(j)) / (zeta_td(i) * omega(i) + zeta_td(j) * omega(j));
          eps(i, j) = 1.0 / (1.0 + q * q);
        }
      break;
  }
  return eps;
}

Eigen::VectorXd combine_modes(CombinationMethod method, const Eigen::MatrixXd& responses,
                              const Eigen::VectorXd& omega, const Eigen::VectorXd& zeta,
                              double duration) {
  const auto n_values = responses.cols();
  Eigen::VectorXd combined = Eigen::VectorXd::Zero(n_values);
  if (responses.rows() == 0) return combined;
  if (method == CombinationMethod::NRLSUM) {
    // NRL sum: the largest modal response in absolute value plus the SRSS of the others.
    for (Eigen::Index c = 0; c < n_values; ++c) {
      const Eigen::VectorXd a = responses.col(c).cwiseAbs();
      Eigen::Index k = 0;
      const double largest = a.maxCoeff(&k);
      combined(c) = largest + std::sqrt(std::max(0.0, a.squaredNorm() - largest * largest));
      if (!std::isfinite(a.sum())) combined(c) = std::numeric_limits<double>::quiet_NaN();
    }
    return combined;
  }
  const Eigen::MatrixXd eps = mode_correlation(method, omega, zeta, duration);
  // GRP and DSUM sum absolute products; CQC keeps the signs (Theory Reference).
  const bool absolute = method == CombinationMethod::GRP || method == CombinationMethod::DSUM;
  const Eigen::MatrixXd r = absolute ? Eigen::MatrixXd(responses.cwiseAbs()) : responses;
  // Σ_i Σ_j ε_ij R_i R_j for every column at once: the column sums of R ∘ (ε R).
  const Eigen::MatrixXd products = r.cwiseProduct(eps * r);
  for (Eigen::Index c = 0; c < n_values; ++c)
    combined(c) = std::sqrt(std::abs(products.col(c).sum()));
  return combined;
}

}  // namespace impactfe
