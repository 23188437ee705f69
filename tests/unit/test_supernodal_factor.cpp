// SupernodalFactor: the inline supernodal LLᵀ on CHOLMOD's symbolic analysis solves like a dense
// factorization, refactors a pattern with new values, reports a matrix that is not positive
// definite instead of factoring it, and gives CHOLMOD's reciprocal condition estimate.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <random>

#include "linalg/supernodal_factor.h"

namespace impactfe::test_supernodal_factor {
namespace {

/// Lower triangle of an SPD matrix with the pattern of a brick mesh of m³ cells and 3 DOFs per
/// node (element blocks of random values made diagonally dominant).
SparseMatrix brick_mesh_matrix(int m, unsigned seed, double shift = 0.0) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  const auto node = [m](int i, int j, int k) { return (i * (m + 1) + j) * (m + 1) + k; };
  const int n = 3 * (m + 1) * (m + 1) * (m + 1);
  std::vector<Eigen::Triplet<double, int>> t;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < m; ++k) {
        std::vector<int> dofs;
        for (int a = 0; a < 8; ++a)
          for (int d = 0; d < 3; ++d)
            dofs.push_back(3 * node(i + (a & 1), j + ((a >> 1) & 1), k + ((a >> 2) & 1)) + d);
        for (std::size_t p = 0; p < dofs.size(); ++p) {
          t.emplace_back(dofs[p], dofs[p], 30.0 + shift);
          for (std::size_t q = 0; q < p; ++q) {
            const int r = std::max(dofs[p], dofs[q]), c = std::min(dofs[p], dofs[q]);
            t.emplace_back(r, c, value(rng));
          }
        }
      }
  SparseMatrix a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  a.makeCompressed();
  return a;
}

struct Common {
  Common() { cholmod_start(&c); }
  ~Common() { cholmod_finish(&c); }
  cholmod_common c;
};

TEST(SupernodalFactor, SolvesLikeADenseFactorization) {
  Common common;
  for (int m : {1, 2, 4}) {
    const SparseMatrix a = brick_mesh_matrix(m, 7u + static_cast<unsigned>(m));
    SupernodalFactor f;
    ASSERT_TRUE(f.analyze(a, common.c));
    ASSERT_TRUE(f.factorize(a));
    EXPECT_TRUE(f.valid());
    const MatrixXd full = MatrixXd(a).selfadjointView<Eigen::Lower>();
    const Eigen::LDLT<MatrixXd> dense(full);
    MatrixXd B(a.rows(), 3);
    B.col(0) = VectorXd::LinSpaced(a.rows(), -1.0, 2.0);
    B.col(1) = VectorXd::Ones(a.rows());
    B.col(2) = B.col(0).array().sin();
    const MatrixXd X = f.solve(B);
    EXPECT_LE((X - dense.solve(B)).norm(), 1e-12 * X.norm()) << "m = " << m;
    EXPECT_LE((full * X - B).norm(), 1e-12 * B.norm()) << "m = " << m;
    EXPECT_EQ(f.solve(VectorXd(B.col(2))), X.col(2));
    // Relaxed supernodes store at least the factor's entries.
    EXPECT_GE(f.stored_values(), static_cast<long>(common.c.lnz));
  }
}

TEST(SupernodalFactor, RefactorsThePatternWithNewValues) {
  Common common;
  const SparseMatrix a = brick_mesh_matrix(3, 1u);
  const SparseMatrix b = brick_mesh_matrix(3, 2u, 5.0);  // same pattern, other values
  SupernodalFactor f;
  ASSERT_TRUE(f.analyze(a, common.c));
  ASSERT_TRUE(f.factorize(a));
  ASSERT_TRUE(f.factorize(b));
  const VectorXd rhs = VectorXd::LinSpaced(b.rows(), 1.0, 3.0);
  const MatrixXd full = MatrixXd(b).selfadjointView<Eigen::Lower>();
  EXPECT_LE((full * f.solve(rhs) - rhs).norm(), 1e-12 * rhs.norm());
}

TEST(SupernodalFactor, AMatrixThatIsNotPositiveDefiniteIsNotFactored) {
  Common common;
  const SparseMatrix a = brick_mesh_matrix(2, 3u, -29.0);  // diagonal 1: indefinite
  SupernodalFactor f;
  ASSERT_TRUE(f.analyze(a, common.c));
  EXPECT_FALSE(f.factorize(a));
  EXPECT_FALSE(f.valid());
  SparseMatrix nan = brick_mesh_matrix(2, 3u);
  nan.valuePtr()[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(f.factorize(nan));
}

TEST(SupernodalFactor, ReciprocalConditionIsTheSquaredPivotRatio) {
  // diag(4, 1, 9, 16, 25) and a coupling: L has diagonal 2, 1, 3, 4, 5 up to the coupling.
  Common common;
  std::vector<Eigen::Triplet<double, int>> t = {
      {0, 0, 4.0}, {1, 1, 1.0}, {2, 2, 9.0}, {3, 3, 16.0}, {4, 4, 25.0}};
  SparseMatrix a(5, 5);
  a.setFromTriplets(t.begin(), t.end());
  SupernodalFactor f;
  ASSERT_TRUE(f.analyze(a, common.c));
  ASSERT_TRUE(f.factorize(a));
  EXPECT_NEAR(f.rcond(), (1.0 / 5.0) * (1.0 / 5.0), 1e-15);
}

}  // namespace
}  // namespace impactfe::test_supernodal_factor
