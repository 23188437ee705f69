#include "analysis/damped_modes.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <complex>

#include "core/errors.h"

namespace impactfe {

std::vector<DampedMode> damped_modes(const VectorXd& omega, const MatrixXd& modal_damping) {
  const auto n = omega.size();
  IMPACTFE_CHECK(modal_damping.rows() == n && modal_damping.cols() == n,
                 "damped_modes: the modal damping matrix does not match the modes");
  // First-order form of q̈ + C_m q̇ + Λ q = 0 with the state (q, q̇): ẋ = A x.
  MatrixXd a = MatrixXd::Zero(2 * n, 2 * n);
  a.topRightCorner(n, n).setIdentity();
  a.bottomLeftCorner(n, n).diagonal() = -omega.cwiseAbs2();
  a.bottomRightCorner(n, n) = -modal_damping;
  const Eigen::EigenSolver<MatrixXd> solver(a, /*computeEigenvectors=*/false);
  if (solver.info() != Eigen::Success)
    throw ModelError("QRDAMP: the damped eigenproblem of the projected modes did not converge");
  const Eigen::VectorXcd lambda = solver.eigenvalues();

  // A real matrix: complex eigenvalues come in conjugate pairs; an eigenvalue whose imaginary
  // part is round-off against its modulus is real (an overdamped or rigid-body mode).
  double scale = 0.0;
  for (Eigen::Index i = 0; i < lambda.size(); ++i) scale = std::max(scale, std::abs(lambda(i)));
  const double tol = 1e-10 * std::max(scale, 1.0);
  std::vector<DampedMode> modes;
  std::vector<double> real_roots;
  for (Eigen::Index i = 0; i < lambda.size(); ++i) {
    const std::complex<double> l = lambda(i);
    if (std::abs(l.imag()) <= tol)
      real_roots.push_back(l.real());
    else if (l.imag() > 0.0)
      modes.push_back({l.real(), l.imag(), std::abs(l)});
  }
  // Overdamped modes: two real roots each (λ₁ λ₂ = ω² for a single degree of freedom).
  std::sort(real_roots.begin(), real_roots.end(),
            [](double x, double y) { return std::abs(x) < std::abs(y); });
  for (std::size_t i = 0; i + 1 < real_roots.size(); i += 2)
    modes.push_back({real_roots[i], 0.0, std::sqrt(std::abs(real_roots[i] * real_roots[i + 1]))});
  std::sort(modes.begin(), modes.end(), [](const DampedMode& x, const DampedMode& y) {
    return x.natural_frequency < y.natural_frequency;
  });
  return modes;
}

MatrixXd project_modal_damping(const MatrixXd& phi, const SparseMatrix& c_free,
                               const AnalysisOptions& options, const VectorXd& omega) {
  const auto n = phi.cols();
  MatrixXd cm = MatrixXd::Zero(n, n);
  if (c_free.nonZeros()) {
    cm = phi.transpose() * (c_free * phi);
    cm = 0.5 * (cm + cm.transpose());
  }
  for (Eigen::Index j = 0; j < n; ++j) {
    double zeta = options.damping_ratio;
    auto it = options.modal_damping.find(static_cast<int>(j) + 1);
    if (it != options.modal_damping.end()) zeta += it->second;
    cm(j, j) += 2.0 * zeta * omega(j);
  }
  return cm;
}

}  // namespace impactfe
