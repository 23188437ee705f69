#include "linalg/eigen_solver.h"

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>
#include <fmt/format.h>
#include <Eigen/Dense>
#include <algorithm>
#include <memory>
#include <numeric>
#include <stdexcept>

#include "linalg/linear_solver.h"

namespace impactfe {

namespace {

/// (K − σM)⁻¹ x through the project's sparse LinearSolver (CHOLMOD, or MUMPS under
/// `--solver mumps`: every rank runs the same Lanczos iteration in lockstep).
class ShiftInvertOperator {
 public:
  using Scalar = double;
  ShiftInvertOperator(const SparseMatrix& k, const SparseMatrix& m) : k_(k), m_(m) {}
  Eigen::Index rows() const { return k_.rows(); }
  Eigen::Index cols() const { return k_.cols(); }
  void set_shift(double sigma) {
    const SparseMatrix a = (k_ - sigma * m_).pruned();
    solver_ = make_linear_solver(static_cast<int>(a.rows()));
    solver_->analyze_pattern(a);
    solver_->factorize(a);
  }
  void perform_op(const double* x_in, double* y_out) const {
    const Eigen::Map<const VectorXd> x(x_in, rows());
    Eigen::Map<VectorXd>(y_out, rows()) = solver_->solve(VectorXd(x));
  }

 private:
  const SparseMatrix& k_;
  const SparseMatrix& m_;
  std::unique_ptr<LinearSolver> solver_;
};

EigenResult dense_eigenpairs(const SparseMatrix& k_lower, const SparseMatrix& m_lower, int n_modes,
                             double shift) {
  const MatrixXd k = MatrixXd(k_lower).selfadjointView<Eigen::Lower>();
  const MatrixXd m = MatrixXd(m_lower).selfadjointView<Eigen::Lower>();
  const Eigen::LLT<MatrixXd> llt(k - shift * m);
  if (llt.info() != Eigen::Success)
    throw SingularMatrixError(-1, "K - sigma M is not positive definite");
  // S = L⁻¹ M L⁻ᵀ, S y = ν y, λ = σ + 1/ν, x = L⁻ᵀ y.
  MatrixXd s = llt.matrixL().solve(m);
  s = llt.matrixL().solve(s.transpose()).transpose();
  Eigen::SelfAdjointEigenSolver<MatrixXd> es(0.5 * (s + s.transpose()));
  const VectorXd nu = es.eigenvalues();
  const double nu_max = nu.cwiseAbs().maxCoeff();
  std::vector<int> order;
  for (int i = static_cast<int>(nu.size()) - 1; i >= 0; --i)
    if (nu(i) > 1e-12 * nu_max) order.push_back(i);  // ν ≈ 0: massless, λ = ∞
  const int n = std::min<int>(n_modes, static_cast<int>(order.size()));
  EigenResult out;
  out.eigenvalues.resize(n);
  out.eigenvectors.resize(k.rows(), n);
  for (int j = 0; j < n; ++j) {
    const int i = order[static_cast<std::size_t>(j)];
    out.eigenvalues(j) = shift + 1.0 / nu(i);
    VectorXd x = llt.matrixU().solve(es.eigenvectors().col(i));
    x /= std::sqrt(x.dot(m * x));
    out.eigenvectors.col(j) = x;
  }
  return out;
}

}  // namespace

EigenResult lowest_eigenpairs(const SparseMatrix& k_lower, const SparseMatrix& m_lower, int n_modes,
                              double shift) {
  const int n = static_cast<int>(k_lower.rows());
  if (n <= 400) return dense_eigenpairs(k_lower, m_lower, n_modes, shift);
  // Full symmetric copies for K − σM (the shift operator) and B = M products.
  const SparseMatrix k_full = k_lower.selfadjointView<Eigen::Lower>();
  const SparseMatrix m_full = m_lower.selfadjointView<Eigen::Lower>();
  SparseMatrix k_low = k_full.triangularView<Eigen::Lower>();
  SparseMatrix m_low = m_full.triangularView<Eigen::Lower>();
  ShiftInvertOperator op(k_low, m_low);
  Spectra::SparseSymMatProd<double> bop(m_full);
  const int nev = std::min(n_modes, n - 1);
  const int ncv = std::min(n, std::max(2 * nev + 1, 20));
  Spectra::SymGEigsShiftSolver<ShiftInvertOperator, Spectra::SparseSymMatProd<double>,
                               Spectra::GEigsMode::ShiftInvert>
      solver(op, bop, nev, ncv, shift);
  // Spectra reports problems in its own words (e.g. "initial residual vector cannot be zero"
  // for a zero mass matrix): say what they mean for the model instead.
  try {
    solver.init();
    solver.compute(Spectra::SortRule::LargestMagn, 1000, 1e-10);
  } catch (const SingularMatrixError&) {
    throw;
  } catch (const std::exception& e) {
    throw std::runtime_error(fmt::format(
        "the Lanczos eigensolver could not run ({}): the mass matrix is zero or nearly so for the "
        "{} modes requested; check the densities (DENS) and point masses",
        e.what(), nev));
  }
  if (solver.info() != Spectra::CompInfo::Successful)
    throw std::runtime_error(fmt::format(
        "the Lanczos eigensolver did not converge to {} modes in 1000 restarts; request fewer "
        "modes (MODOPT) or check the mass distribution",
        nev));
  const VectorXd values = solver.eigenvalues();
  const MatrixXd vectors = solver.eigenvectors();
  std::vector<int> order(static_cast<std::size_t>(values.size()));
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return values(a) < values(b); });
  EigenResult out;
  out.eigenvalues.resize(values.size());
  out.eigenvectors.resize(n, values.size());
  for (std::size_t j = 0; j < order.size(); ++j) {
    out.eigenvalues(static_cast<int>(j)) = values(order[j]);
    VectorXd x = vectors.col(order[j]);
    x /= std::sqrt(x.dot(m_full * x));
    out.eigenvectors.col(static_cast<int>(j)) = x;
  }
  return out;
}

}  // namespace impactfe
