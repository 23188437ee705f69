// The harmonic response on matrices (harmonic_response.h): frequencies of the load steps and
// the complex solves of the full and the mode-superposition methods.
#include "analysis/harmonic_response.h"

#include <Eigen/Dense>
#include <Eigen/SparseLU>
#include <cmath>

#include <fmt/format.h>

#include "core/errors.h"

namespace impactfe {

std::vector<HarmonicPoint> harmonic_points(const std::vector<LoadStep>& steps) {
  std::vector<HarmonicPoint> out;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const LoadStep& s = steps[i];
    if (!s.frequency_range)
      throw InputError(s.where,
                       fmt::format("load step {}: no harmonic frequency (HARFRQ) given", s.number));
    const auto [fb, fe] = *s.frequency_range;
    const int n = fb == fe ? 1 : std::max(1, s.n_substeps.value_or(1));
    for (int k = 1; k <= n; ++k) {
      HarmonicPoint p;
      p.step_index = i;
      p.substep = k;
      // Evenly spaced, the last at FREQE (MAPDL: FREQB + (FREQE − FREQB) k / NSUBST).
      p.frequency = fb + (fe - fb) * static_cast<double>(k) / n;
      p.load_factor = s.stepped ? 1.0 : static_cast<double>(k) / n;
      out.push_back(p);
    }
  }
  return out;
}

VectorXcd solve_full_harmonic(const SparseMatrix& k, const SparseMatrix& c, const SparseMatrix& m,
                              double omega, double structural_g, double damping_ratio,
                              const VectorXcd& f) {
  using Complex = std::complex<double>;
  using ComplexSparse = Eigen::SparseMatrix<Complex, Eigen::ColMajor, int>;
  // A = K (1 + i (g + 2ζ)) + i Ω C − Ω² M.
  const Complex stiffness_factor(1.0, structural_g + 2.0 * damping_ratio);
  ComplexSparse a = k.cast<Complex>() * stiffness_factor;
  if (m.nonZeros()) a += m.cast<Complex>() * Complex(-omega * omega, 0.0);
  if (c.nonZeros()) a += c.cast<Complex>() * Complex(0.0, omega);
  a.makeCompressed();
  Eigen::SparseLU<ComplexSparse> lu;
  lu.analyzePattern(a);
  lu.factorize(a);
  if (lu.info() != Eigen::Success)
    throw SolutionError(fmt::format(
        "harmonic response at {:g} Hz: K + iΩC − Ω²M is singular (an undamped resonance, or "
        "a DOF without stiffness and mass)",
        omega / (2.0 * M_PI)));
  VectorXcd u = lu.solve(f);
  if (lu.info() != Eigen::Success || !u.allFinite())
    throw SolutionError(
        fmt::format("harmonic response at {:g} Hz: the solve failed", omega / (2.0 * M_PI)));
  return u;
}

VectorXcd solve_modal_harmonic(const Eigen::VectorXd& omega_modes, const Eigen::MatrixXd& modal_c,
                               double omega, double structural_g, const VectorXcd& f_modal) {
  using Complex = std::complex<double>;
  const auto n = omega_modes.size();
  Eigen::MatrixXcd a = modal_c.cast<Complex>() * Complex(0.0, omega);
  for (Eigen::Index j = 0; j < n; ++j)
    a(j, j) +=
        Complex(omega_modes(j) * omega_modes(j), structural_g * omega_modes(j) * omega_modes(j)) -
        Complex(omega * omega, 0.0);
  Eigen::FullPivLU<Eigen::MatrixXcd> lu(a);
  if (!lu.isInvertible())
    throw SolutionError(fmt::format(
        "mode-superposition harmonic response at {:g} Hz: an undamped mode resonates there",
        omega / (2.0 * M_PI)));
  return lu.solve(f_modal);
}

}  // namespace impactfe
