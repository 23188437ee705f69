// QR damped modes (MODOPT,QRDAMP): the first-order eigenproblem of the system projected on the
// undamped modes against single-DOF closed forms, and against the state-space eigenvalues of a
// non-proportionally damped two-DOF system in physical coordinates (all modes kept: the
// projection is exact); the modal analysis of a deck stores them for *GET MODE DFRQ, STAB.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

#include "../support/run_deck.h"
#include "analysis/damped_modes.h"

namespace impactfe::test_damped_modes {
namespace {

TEST(DampedModes, SingleDofUnderdampedIsSigmaPlusIOmegaD) {
  const double w = 10.0, zeta = 0.05;
  VectorXd omega(1);
  omega << w;
  const MatrixXd c = MatrixXd::Constant(1, 1, 2.0 * zeta * w);
  const auto modes = damped_modes(omega, c);
  ASSERT_EQ(modes.size(), 1u);
  EXPECT_NEAR(modes[0].stability, -zeta * w, 1e-12);
  EXPECT_NEAR(modes[0].damped_frequency, w * std::sqrt(1.0 - zeta * zeta), 1e-12);
  EXPECT_NEAR(modes[0].natural_frequency, w, 1e-12);
}

TEST(DampedModes, SingleDofOverdampedHasNoFrequencyAndTheSlowDecay) {
  const double w = 4.0, zeta = 2.0;  // λ = −ω (ζ ± √(ζ² − 1))
  VectorXd omega(1);
  omega << w;
  const auto modes = damped_modes(omega, MatrixXd::Constant(1, 1, 2.0 * zeta * w));
  ASSERT_EQ(modes.size(), 1u);
  EXPECT_EQ(modes[0].damped_frequency, 0.0);
  EXPECT_NEAR(modes[0].stability, -w * (zeta - std::sqrt(zeta * zeta - 1.0)), 1e-10);
  EXPECT_NEAR(modes[0].natural_frequency, w, 1e-10);
}

TEST(DampedModes, NonProportionalTwoDofEqualsPhysicalStateSpace) {
  // Two masses in a chain, a damper on the second only (not a combination of M and K).
  Eigen::Matrix2d m, k, c;
  m << 2.0, 0.0, 0.0, 1.0;
  k << 600.0, -200.0, -200.0, 200.0;
  c << 0.0, 0.0, 0.0, 3.0;
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> eig(k, m);
  const MatrixXd phi = eig.eigenvectors();  // mass-normalised
  const VectorXd omega = eig.eigenvalues().cwiseSqrt();
  const MatrixXd cm = phi.transpose() * c * phi;
  const auto modes = damped_modes(omega, cm);
  ASSERT_EQ(modes.size(), 2u);

  Eigen::Matrix4d a = Eigen::Matrix4d::Zero();
  a.topRightCorner<2, 2>().setIdentity();
  a.bottomLeftCorner<2, 2>() = -m.inverse() * k;
  a.bottomRightCorner<2, 2>() = -m.inverse() * c;
  const Eigen::EigenSolver<Eigen::Matrix4d> full(a, false);
  std::vector<std::complex<double>> upper;
  for (int i = 0; i < 4; ++i)
    if (full.eigenvalues()(i).imag() > 0.0) upper.push_back(full.eigenvalues()(i));
  ASSERT_EQ(upper.size(), 2u);
  std::sort(upper.begin(), upper.end(), [](auto x, auto y) { return std::abs(x) < std::abs(y); });
  for (int j = 0; j < 2; ++j) {
    EXPECT_NEAR(modes[j].stability, upper[j].real(), 1e-10);
    EXPECT_NEAR(modes[j].damped_frequency, upper[j].imag(), 1e-10);
  }
  // Not the proportional answer: the damper couples the modes (off-diagonal C_m).
  EXPECT_GT(std::abs(cm(0, 1)), 0.1);
}

// The deck path: a mass on a spring-damper (COMBIN14 k = 400, c = 4, m = 1: ω = 20 rad/s,
// ζ = c / (2 m ω) = 0.1) with DMPRAT 0.05 added: ζ = 0.15 in the modal damping.
TEST(DampedModes, QrdampModalAnalysisAnswersGetDfrqAndStab) {
  const std::string deck =
      "/PREP7\nET,1,COMBIN14,,2\nET,2,MASS21,,,4\nR,1,400,4\nR,2,1\nN,1\nN,2,1\n"
      "TYPE,1\nREAL,1\nE,1,2\nTYPE,2\nREAL,2\nE,2\nD,1,ALL\nD,2,UX\nFINISH\n"
      "/SOLU\nANTYPE,MODAL\nMODOPT,QRDAMP,1\nDMPRAT,0.05\nSOLVE\n"
      "*GET,DF,MODE,1,DFRQ\n*GET,ST,MODE,1,STAB\n*GET,F,MODE,1,FREQ\n"
      "*CFOPEN,damped,txt\n*VWRITE,F,DF,ST\n(3E24.15)\n*CFCLOS\nFINISH\n";
  const auto run = testing::run_deck_text("qrdamp_sdof", deck);
  std::ifstream in(run.directory / "damped.txt");
  double f = 0.0, df = 0.0, st = 0.0;
  ASSERT_TRUE(static_cast<bool>(in >> f >> df >> st));
  const double w = 20.0, zeta = 0.15;
  EXPECT_NEAR(f, w / (2.0 * M_PI), 1e-9);
  EXPECT_NEAR(df, w * std::sqrt(1.0 - zeta * zeta) / (2.0 * M_PI), 1e-9);
  EXPECT_NEAR(st, -zeta * w / (2.0 * M_PI), 1e-9);
  ASSERT_EQ(run.reader->damped_frequencies().size(), 1u);
  EXPECT_NEAR(run.reader->stabilities()[0], st, 1e-12);
}

TEST(DampedModes, UndampedModalAnalysisRefusesDfrq) {
  const std::string deck =
      "/PREP7\nET,1,COMBIN14,,2\nET,2,MASS21,,,4\nR,1,400\nR,2,1\nN,1\nN,2,1\n"
      "TYPE,1\nREAL,1\nE,1,2\nTYPE,2\nREAL,2\nE,2\nD,1,ALL\nD,2,UX\nFINISH\n"
      "/SOLU\nANTYPE,MODAL\nMODOPT,LANB,1\nSOLVE\n*GET,DF,MODE,1,DFRQ\n";
  try {
    testing::run_deck_text("qrdamp_refused", deck);
    FAIL() << "DFRQ of an undamped modal analysis was accepted";
  } catch (const LocatedError& e) {
    EXPECT_NE(std::string(e.what()).find("needs MODOPT,QRDAMP"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace impactfe::test_damped_modes
