// Guyan reduction (thesis eq. 4-21 with the corrected damping term, spec §10.4) and master
// selection, checked against independently formed dense formulas and closed forms.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "core/errors.h"
#include "reduction/guyan.h"

namespace test_guyan {

using namespace impactfe;

namespace {

SparseMatrix sparse(const MatrixXd& a) {
  return a.sparseView();
}

/// Random SPD matrix of size n (diagonally dominant).
MatrixXd spd(int n, unsigned seed) {
  std::srand(seed);
  MatrixXd r = MatrixXd::Random(n, n);
  return r * r.transpose() + n * MatrixXd::Identity(n, n);
}

}  // namespace

TEST(Guyan, SeriesSpringsCondenseToTheSeriesStiffness) {
  // Chain ground -k1- u0 -k2- u1, master u1, slave u0: K_r = k1 k2 / (k1 + k2).
  const double k1 = 300.0, k2 = 600.0;
  MatrixXd k(2, 2);
  k << k1 + k2, -k2, -k2, k2;
  const MatrixXd m = MatrixXd::Identity(2, 2);
  GuyanReduction g(sparse(k), sparse(m), nullptr, 2, {1});
  EXPECT_NEAR(g.k()(0, 0), k1 * k2 / (k1 + k2), 1e-10);
  // T = k2/(k1+k2); M_r = 1 + T².
  const double t = k2 / (k1 + k2);
  EXPECT_NEAR(g.transformation()(0, 0), t, 1e-14);
  EXPECT_NEAR(g.m()(0, 0), 1.0 + t * t, 1e-12);
}

TEST(Guyan, MatchesEquation421WithCorrectedDampingTerm) {
  const int n = 7;
  const MatrixXd k = spd(n, 1), m = spd(n, 2), c = spd(n, 3);
  const std::vector<int> masters = {1, 4, 6};
  const std::vector<int> slaves = {0, 2, 3, 5};
  GuyanReduction g(sparse(k), sparse(m), nullptr, n, masters);
  const SparseMatrix cs = sparse(c);
  GuyanReduction gd(sparse(k), sparse(m), &cs, n, masters);
  auto block = [&](const MatrixXd& a, const std::vector<int>& r, const std::vector<int>& cidx) {
    MatrixXd out(r.size(), cidx.size());
    for (std::size_t i = 0; i < r.size(); ++i)
      for (std::size_t j = 0; j < cidx.size(); ++j) out(i, j) = a(r[i], cidx[j]);
    return out;
  };
  const MatrixXd kss_inv = block(k, slaves, slaves).inverse();  // fine in a test, 4x4
  const MatrixXd kms = block(k, masters, slaves), ksm = kms.transpose();
  // Eq. 4-21 (corrected): every term written out.
  const MatrixXd kr = block(k, masters, masters) - kms * kss_inv * ksm;
  auto reduced = [&](const MatrixXd& a) {
    return MatrixXd(block(a, masters, masters) - kms * kss_inv * block(a, slaves, masters) -
                    block(a, masters, slaves) * kss_inv * ksm +
                    kms * kss_inv * block(a, slaves, slaves) * kss_inv * ksm);
  };
  EXPECT_LT((g.k() - kr).norm(), 1e-10 * kr.norm());
  EXPECT_LT((g.m() - reduced(m)).norm(), 1e-10 * m.norm());
  EXPECT_LT((gd.c() - reduced(c)).norm(), 1e-10 * c.norm());
  // The thesis misprint (C_ms instead of K_ms in the second term) gives a different matrix.
  const MatrixXd misprint = block(c, masters, masters) -
                            block(c, masters, slaves) * kss_inv * block(c, slaves, masters) -
                            block(c, masters, slaves) * kss_inv * ksm +
                            kms * kss_inv * block(c, slaves, slaves) * kss_inv * ksm;
  EXPECT_GT((gd.c() - misprint).norm(), 1e-3 * c.norm());
  // Reduced load f_r = f_m − K_ms K_ss⁻¹ f_s.
  const VectorXd f = VectorXd::LinSpaced(n, 1.0, 7.0);
  VectorXd fs(4), fm(3);
  for (int i = 0; i < 4; ++i) fs(i) = f(slaves[i]);
  for (int i = 0; i < 3; ++i) fm(i) = f(masters[i]);
  EXPECT_LT((g.reduce_force(f) - (fm - kms * kss_inv * fs)).norm(), 1e-10 * f.norm());
  EXPECT_EQ(g.n_slaves(), 4);
}

TEST(Guyan, ExpansionWithStaticCorrectionSatisfiesTheSlaveEquations) {
  const int n = 6;
  const MatrixXd k = spd(n, 5);
  GuyanReduction g(sparse(k), sparse(MatrixXd::Identity(n, n)), nullptr, n, {0, 3});
  const VectorXd um = (VectorXd(2) << 0.3, -1.2).finished();
  const VectorXd f = (VectorXd(6) << 0, 2, -1, 0, 4, 0.5).finished();
  const VectorXd u = g.expand(um, &f);
  EXPECT_DOUBLE_EQ(u(0), 0.3);
  EXPECT_DOUBLE_EQ(u(3), -1.2);
  const VectorXd r = k * u - f;  // slave rows must balance: K_sm u_m + K_ss u_s = f_s
  for (int s : {1, 2, 4, 5}) EXPECT_NEAR(r(s), 0.0, 1e-10 * f.norm());
  // Without the correction, the slave rows balance a zero slave load.
  const VectorXd u0 = g.expand(um);
  const VectorXd r0 = k * u0;
  for (int s : {1, 2, 4, 5}) EXPECT_NEAR(r0(s), 0.0, 1e-10 * k.norm());
}

TEST(Guyan, AllDofsMastersIsExact) {
  const int n = 5;
  const MatrixXd k = spd(n, 7), m = spd(n, 8);
  GuyanReduction g(sparse(k), sparse(m), nullptr, n, {0, 1, 2, 3, 4});
  EXPECT_EQ(g.n_slaves(), 0);
  EXPECT_LT((g.k() - k).norm(), 1e-12 * k.norm());
  EXPECT_LT((g.m() - m).norm(), 1e-12 * m.norm());
}

TEST(Guyan, UnrestrainedSlaveIsReportedByName) {
  // DOF 2 is coupled to nothing: the masters cannot restrain it.
  MatrixXd k = MatrixXd::Zero(3, 3);
  k << 2, -1, 0, -1, 2, 0, 0, 0, 0;
  try {
    GuyanReduction g(sparse(k), sparse(MatrixXd::Identity(3, 3)), nullptr, 3, {0});
    FAIL() << "expected ModelError";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("not restrained"), std::string::npos) << e.what();
  }
}

}  // namespace test_guyan
