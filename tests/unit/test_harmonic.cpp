// Harmonic response on matrices (analysis/harmonic_response.h): the full method against the
// closed forms of a spring-mass-damper and of a two-mass chain, the equivalent damping of
// DMPSTR and DMPRAT, the frequencies of HARFRQ + NSUBST + KBC, and mode superposition against
// the full method on a cantilever beam.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <complex>

#include "analysis/harmonic_response.h"
#include "core/errors.h"

namespace test_harmonic {

using namespace impactfe;
using Complex = std::complex<double>;

namespace {

SparseMatrix sparse(const Eigen::MatrixXd& d) {
  return d.sparseView();
}

/// One DOF: k, c, m as 1x1 matrices; the full solve at Ω for force F.
Complex sdof(double k, double c, double m, double omega, double g = 0.0, double zeta = 0.0) {
  const VectorXcd f = VectorXcd::Constant(1, Complex(10.0, 0.0));
  return solve_full_harmonic(sparse(Eigen::MatrixXd::Constant(1, 1, k)),
                             sparse(Eigen::MatrixXd::Constant(1, 1, c)),
                             sparse(Eigen::MatrixXd::Constant(1, 1, m)), omega, g, zeta, f)(0);
}

}  // namespace

TEST(Harmonic, SpringMassDamperAmplitudeAndPhaseBelowAtAboveResonance) {
  // |u| = F / sqrt((k − mΩ²)² + (cΩ)²), phase = −atan2(cΩ, k − mΩ²) (u lags F).
  const double k = 200.0, c = 6.0, m = 0.5, f = 10.0;  // ω_n = 20 rad/s
  for (double omega : {10.0, 20.0, 40.0}) {
    const Complex u = sdof(k, c, m, omega);
    const double amplitude = f / std::hypot(k - m * omega * omega, c * omega);
    const double phase = -std::atan2(c * omega, k - m * omega * omega);
    EXPECT_NEAR(std::abs(u), amplitude, 1e-10 * amplitude) << "omega " << omega;
    EXPECT_NEAR(std::arg(u), phase, 1e-10) << "omega " << omega;
  }
  // At resonance the response is F / (cΩ) = 0.0833, 90° behind the force (VM86).
  EXPECT_NEAR(std::abs(sdof(k, c, m, 20.0)), 10.0 / 120.0, 1e-12);
}

TEST(Harmonic, StructuralDampingAndConstantRatioAreStiffnessImaginaryParts) {
  // DMPSTR g: u = F / (k (1 + i g) − mΩ²); DMPRAT ζ in the full method: g = 2ζ.
  const double k = 200.0, m = 0.5, omega = 15.0;
  const Complex with_g = sdof(k, 0.0, m, omega, 0.06, 0.0);
  const Complex expected = 10.0 / (k * Complex(1.0, 0.06) - m * omega * omega);
  EXPECT_NEAR(std::abs(with_g - expected), 0.0, 1e-12 * std::abs(expected));
  const Complex with_zeta = sdof(k, 0.0, m, omega, 0.0, 0.03);
  EXPECT_NEAR(std::abs(with_zeta - expected), 0.0, 1e-12 * std::abs(expected));
  // BETAD β gives c = β k, as VM87 (β = 0.03: at resonance |u| = F / (β k Ω) = 0.0833).
  EXPECT_NEAR(std::abs(sdof(k, 0.03 * k, m, 20.0)), 10.0 / (0.03 * k * 20.0), 1e-12);
}

TEST(Harmonic, TwoMassChainAgreesWithTheClosedForm) {
  // Wall − k − m1 − k − m2 − k − wall, F on m1, undamped (VM90): Cramer's rule on
  // [[2k − mΩ², −k], [−k, 2k − mΩ²]] u = [F, 0].
  const double k = 200.0, m = 0.5, f = 200.0;
  Eigen::MatrixXd kd(2, 2), md = m * Eigen::MatrixXd::Identity(2, 2);
  kd << 2 * k, -k, -k, 2 * k;
  for (double hz : {1.5, 4.0, 6.5}) {
    const double omega = 2 * M_PI * hz;
    VectorXcd load(2);
    load << f, 0.0;
    const VectorXcd u =
        solve_full_harmonic(sparse(kd), SparseMatrix(2, 2), sparse(md), omega, 0.0, 0.0, load);
    const double a = 2 * k - m * omega * omega, det = a * a - k * k;
    EXPECT_NEAR(u(0).real(), f * a / det, 1e-10 * std::abs(f * a / det)) << hz << " Hz";
    EXPECT_NEAR(u(1).real(), f * k / det, 1e-10 * std::abs(f * k / det)) << hz << " Hz";
    EXPECT_NEAR(u(0).imag(), 0.0, 1e-14);
  }
  // The VM90 targets at 1.5 Hz: 0.82272 and 0.46274.
  VectorXcd load(2);
  load << f, 0.0;
  const VectorXcd u = solve_full_harmonic(sparse(kd), SparseMatrix(2, 2), sparse(md),
                                          2 * M_PI * 1.5, 0.0, 0.0, load);
  EXPECT_NEAR(u(0).real(), 0.82272, 5e-5);
  EXPECT_NEAR(u(1).real(), 0.46274, 5e-5);
}

TEST(Harmonic, ImaginaryForceShiftsThePhase) {
  // F = i F0: the response is i times that of F0.
  const double k = 200.0, c = 6.0, m = 0.5, omega = 12.0;
  const VectorXcd f = VectorXcd::Constant(1, Complex(0.0, 10.0));
  const Complex u = solve_full_harmonic(
      sparse(Eigen::MatrixXd::Constant(1, 1, k)), sparse(Eigen::MatrixXd::Constant(1, 1, c)),
      sparse(Eigen::MatrixXd::Constant(1, 1, m)), omega, 0.0, 0.0, f)(0);
  const Complex expected = Complex(0.0, 10.0) / Complex(k - m * omega * omega, c * omega);
  EXPECT_NEAR(std::abs(u - expected), 0.0, 1e-12 * std::abs(expected));
}

TEST(Harmonic, FrequenciesOfHarfrqNsubstAndKbc) {
  LoadStep s;
  s.frequency_range = std::make_pair(0.0, 7.5);
  s.n_substeps = 30;
  s.stepped = true;
  LoadStep ramped;
  ramped.frequency_range = std::make_pair(0.1, 1.0);
  ramped.n_substeps = 4;
  const auto points = harmonic_points({s, ramped});
  ASSERT_EQ(points.size(), 34u);
  EXPECT_NEAR(points[0].frequency, 0.25, 1e-14);
  EXPECT_NEAR(points[5].frequency, 1.5, 1e-14);
  EXPECT_NEAR(points[29].frequency, 7.5, 1e-14);
  for (int i = 0; i < 30; ++i) EXPECT_EQ(points[i].load_factor, 1.0);
  // KBC,0: the amplitude ramps with the substeps, full at FREQE.
  EXPECT_NEAR(points[30].frequency, 0.325, 1e-14);
  EXPECT_NEAR(points[30].load_factor, 0.25, 1e-14);
  EXPECT_NEAR(points[33].frequency, 1.0, 1e-14);
  EXPECT_EQ(points[33].load_factor, 1.0);
  EXPECT_EQ(points[33].step_index, 1u);
  EXPECT_EQ(points[33].substep, 4);
  // HARFRQ,,f (FREQB blank = 0) with one substep: the single frequency f at full load.
  LoadStep single;
  single.frequency_range = std::make_pair(0.0, 3.1831);
  const auto one = harmonic_points({single});
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].frequency, 3.1831);
  EXPECT_EQ(one[0].load_factor, 1.0);
  EXPECT_THROW(harmonic_points({LoadStep{}}), InputError);
}

TEST(Harmonic, ModeSuperpositionAgreesWithFullOnACantileverBeam) {
  // Euler-Bernoulli cantilever of 20 elements (w, θ per node; consistent mass), tip force,
  // Rayleigh damping α M + β K. With all modes MSUP is the full solution (1e-9); with the
  // lowest 4 modes at 0.7 f1 the tip response is within 0.5 % (truncation of the stiff modes).
  const int ne = 20, nn = ne + 1, n = 2 * ne;  // node 0 clamped
  const double ei = 2.1e11 * 8.333e-6, rho_a = 7850 * 0.01, length = 2.0, h = length / ne;
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(2 * nn, 2 * nn), m = k;
  Eigen::Matrix4d ke, me;
  ke << 12, 6 * h, -12, 6 * h, 6 * h, 4 * h * h, -6 * h, 2 * h * h, -12, -6 * h, 12, -6 * h, 6 * h,
      2 * h * h, -6 * h, 4 * h * h;
  ke *= ei / (h * h * h);
  me << 156, 22 * h, 54, -13 * h, 22 * h, 4 * h * h, 13 * h, -3 * h * h, 54, 13 * h, 156, -22 * h,
      -13 * h, -3 * h * h, -22 * h, 4 * h * h;
  me *= rho_a * h / 420.0;
  for (int e = 0; e < ne; ++e) {
    k.block(2 * e, 2 * e, 4, 4) += ke;
    m.block(2 * e, 2 * e, 4, 4) += me;
  }
  const Eigen::MatrixXd kf = k.bottomRightCorner(n, n), mf = m.bottomRightCorner(n, n);
  const double alpha = 2.0, beta = 1e-5;
  const Eigen::MatrixXd cf = alpha * mf + beta * kf;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(kf, mf);
  const Eigen::VectorXd omega_n = eig.eigenvalues().cwiseSqrt();
  const Eigen::MatrixXd phi = eig.eigenvectors();  // mass-normalised
  VectorXcd f = VectorXcd::Zero(n);
  f(n - 2) = 1000.0;  // tip w
  const double omega = 0.7 * omega_n(0);
  const VectorXcd full = solve_full_harmonic(sparse(kf), sparse(cf), sparse(mf), omega, 0, 0, f);
  auto msup = [&](int nm) {
    const Eigen::MatrixXd p = phi.leftCols(nm);
    Eigen::MatrixXd cm = alpha * Eigen::MatrixXd::Identity(nm, nm);
    cm.diagonal() += beta * omega_n.head(nm).cwiseProduct(omega_n.head(nm));
    const VectorXcd q =
        solve_modal_harmonic(omega_n.head(nm), cm, omega, 0.0, p.transpose().cast<Complex>() * f);
    return VectorXcd(p.cast<Complex>() * q);
  };
  const VectorXcd all = msup(n);
  EXPECT_LT((all - full).norm(), 1e-9 * full.norm());
  const VectorXcd four = msup(4);
  EXPECT_LT(std::abs(four(n - 2) - full(n - 2)), 5e-3 * std::abs(full(n - 2)));
  // The closed-form first natural frequency of a cantilever: 1.8751² sqrt(EI / (ρA)) / L².
  EXPECT_NEAR(omega_n(0), 1.8751040687 * 1.8751040687 * std::sqrt(ei / rho_a) / (length * length),
              1e-4 * omega_n(0));
}

}  // namespace test_harmonic
