// Response spectrum numerics (analysis/mode_combination.h): the spectrum value read from the
// FREQ/SV curves (log-log and linear, between damping curves), the CQC correlation against the
// equal-damping textbook form, and a two-DOF base-excited chain whose SRSS and CQC responses are
// worked out by hand from its modes.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "analysis/mode_combination.h"

namespace test_mode_combination {

using namespace impactfe;

TEST(SpectrumValue, LogLogInterpolationReproducesAPowerLaw) {
  // S = f² sampled at 1 and 4 Hz: log-log interpolation is exact at 2 Hz (4), linear gives 6.
  SpectrumTable t;
  t.frequencies = {1.0, 4.0};
  t.curves = {{0.0, {1.0, 16.0}}};
  EXPECT_NEAR(spectrum_value(t, 2.0, 0.0), 4.0, 1e-12);
  t.linear = true;
  EXPECT_NEAR(spectrum_value(t, 2.0, 0.0), 6.0, 1e-12);
  // Outside the table the extreme values are used.
  EXPECT_DOUBLE_EQ(spectrum_value(t, 0.5, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(spectrum_value(t, 9.0, 0.0), 16.0);
}

TEST(SpectrumValue, InterpolatesBetweenTheCurvesThatBracketTheDamping) {
  SpectrumTable t;
  t.frequencies = {1.0, 10.0};
  t.curves = {{0.02, {2.0, 2.0}}, {0.08, {0.5, 0.5}}};
  // log S linear in log ζ: at ζ = 0.04 (halfway in log between 0.02 and 0.08), S = √(2 · 0.5).
  EXPECT_NEAR(spectrum_value(t, 3.0, 0.04), 1.0, 1e-12);
  t.linear = true;
  EXPECT_NEAR(spectrum_value(t, 3.0, 0.04), 2.0 - 1.5 / 3.0, 1e-12);
  EXPECT_DOUBLE_EQ(spectrum_value(t, 3.0, 0.01), 2.0);  // below the lowest curve: that curve
  EXPECT_DOUBLE_EQ(spectrum_value(t, 3.0, 0.20), 0.5);
}

TEST(ModeCombination, CqcCorrelationMatchesTheEqualDampingForm) {
  // ε = 8 ξ² (1 + r) r^{3/2} / ((1 − r²)² + 4 ξ² r (1 + r)²) for ξi = ξj = ξ.
  const double xi = 0.05;
  for (double r : {1.05, 1.1, 1.5, 3.0}) {
    Eigen::VectorXd omega(2), zeta(2);
    omega << 10.0, 10.0 * r;
    zeta << xi, xi;
    const Eigen::MatrixXd eps = mode_correlation(CombinationMethod::CQC, omega, zeta, 10.0);
    const double expected = 8 * xi * xi * (1 + r) * std::pow(r, 1.5) /
                            (std::pow(1 - r * r, 2) + 4 * xi * xi * r * std::pow(1 + r, 2));
    EXPECT_NEAR(eps(0, 1), expected, 1e-12) << "r " << r;
    EXPECT_NEAR(eps(1, 0), expected, 1e-12) << "r " << r;  // symmetric for equal damping
    EXPECT_DOUBLE_EQ(eps(0, 0), 1.0);
  }
  // ξ = 5 %, r = 1.1: ε = 0.5233 (the closely spaced modes are strongly correlated).
  Eigen::VectorXd omega(2), zeta(2);
  omega << 1.0, 1.1;
  zeta << 0.05, 0.05;
  EXPECT_NEAR(mode_correlation(CombinationMethod::CQC, omega, zeta, 10.0)(0, 1), 0.5233, 1e-4);
}

TEST(ModeCombination, TwoDofBaseExcitedChainSrssAndCqcByHand) {
  // Ground − k1 − m1 − k2 − m2, excited along the chain by a flat acceleration spectrum Sa.
  // Modes of [[k1 + k2, −k2], [−k2, k2]] φ = ω² diag(m1, m2) φ, mass-normalised; γi = φiᵀ M 1,
  // Ai = Sa γi / ωi², modal displacement of m2: Ai φi(2).
  const double k1 = 2000.0, k2 = 1000.0, m1 = 2.0, m2 = 1.0, sa = 3.0, xi = 0.02;
  Eigen::Matrix2d k, m;
  k << k1 + k2, -k2, -k2, k2;
  m << m1, 0.0, 0.0, m2;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> eig(k, m);
  const Eigen::Matrix2d phi = eig.eigenvectors();  // φᵀ M φ = I
  const Eigen::Vector2d omega = eig.eigenvalues().cwiseSqrt();
  const Eigen::Vector2d gamma = phi.transpose() * m * Eigen::Vector2d::Ones();
  // Σ γi² is the total mass (both modes together carry all of it).
  EXPECT_NEAR(gamma.squaredNorm(), m1 + m2, 1e-10);
  Eigen::MatrixXd responses(2, 2);
  for (int i = 0; i < 2; ++i)
    responses.row(i) = sa * gamma(i) / (omega(i) * omega(i)) * phi.col(i).transpose();
  const Eigen::Vector2d zeta(xi, xi);
  const Eigen::VectorXd srss = combine_modes(CombinationMethod::SRSS, responses, omega, zeta, 10.0);
  for (int dof = 0; dof < 2; ++dof)
    EXPECT_NEAR(srss(dof), std::hypot(responses(0, dof), responses(1, dof)), 1e-14);
  // CQC: R² = R1² + R2² + 2 ε12 R1 R2 with ε12 of the equal-damping form.
  const double r = omega(1) / omega(0);
  const double eps = 8 * xi * xi * (1 + r) * std::pow(r, 1.5) /
                     (std::pow(1 - r * r, 2) + 4 * xi * xi * r * std::pow(1 + r, 2));
  const Eigen::VectorXd cqc = combine_modes(CombinationMethod::CQC, responses, omega, zeta, 10.0);
  for (int dof = 0; dof < 2; ++dof) {
    const double a = responses(0, dof), b = responses(1, dof);
    EXPECT_NEAR(cqc(dof), std::sqrt(a * a + b * b + 2 * eps * a * b), 1e-12);
  }
  // Well separated modes (r ≈ 2.7): CQC stays within a few per mille of SRSS.
  EXPECT_NEAR(cqc(1) / srss(1), 1.0, 5e-3);
}

TEST(ModeCombination, GroupingNrlAndDoubleSum) {
  // Three modes, the first two within 10 %: GRP adds |R1 R2| twice, NRLSUM the largest plus the
  // SRSS of the rest, DSUM with ε → 1 for equal frequencies.
  Eigen::VectorXd omega(3), zeta(3);
  omega << 10.0, 10.5, 30.0;
  zeta << 0.05, 0.05, 0.05;
  Eigen::MatrixXd r(3, 1);
  r << 1.0, -2.0, 0.5;
  EXPECT_NEAR(combine_modes(CombinationMethod::GRP, r, omega, zeta, 10.0)(0),
              std::sqrt(1.0 + 4.0 + 0.25 + 2 * 2.0), 1e-12);
  EXPECT_NEAR(combine_modes(CombinationMethod::NRLSUM, r, omega, zeta, 10.0)(0),
              2.0 + std::sqrt(1.0 + 0.25), 1e-12);
  Eigen::VectorXd same(2), z2(2);
  same << 20.0, 20.0;
  z2 << 0.05, 0.05;
  Eigen::MatrixXd r2(2, 1);
  r2 << 1.0, 1.0;
  EXPECT_NEAR(combine_modes(CombinationMethod::DSUM, r2, same, z2, 10.0)(0), 2.0, 1e-12);
  EXPECT_NEAR(combine_modes(CombinationMethod::SRSS, r2, same, z2, 10.0)(0), std::sqrt(2.0), 1e-12);
}

}  // namespace test_mode_combination
