// Eigensolver: the dense path and the sparse shift-invert Lanczos path give the closed-form
// eigenvalues of a fixed-free spring-mass chain, mass-normalised vectors, and rigid-body modes
// when the chain is free.
#include <gtest/gtest.h>

#include <cmath>

#include "linalg/eigen_solver.h"

namespace impactfe::test_eigen_solver {
namespace {

/// Fixed-free chain of n unit masses and unit springs: λ_j = 4 sin²((2j−1)π/(2(2n+1))).
void chain(int n, bool fixed, SparseMatrix& k, SparseMatrix& m) {
  std::vector<Eigen::Triplet<double, int>> tk, tm;
  for (int i = 0; i < n; ++i) {
    tk.emplace_back(i, i, (i == 0 && !fixed ? 0.0 : 1.0) + (i + 1 < n ? 1.0 : 0.0));
    if (i + 1 < n) tk.emplace_back(i + 1, i, -1.0);
    tm.emplace_back(i, i, 1.0);
  }
  k.resize(n, n);
  m.resize(n, n);
  k.setFromTriplets(tk.begin(), tk.end());
  m.setFromTriplets(tm.begin(), tm.end());
}

void check_chain(int n) {
  SparseMatrix k, m;
  chain(n, true, k, m);
  const EigenResult r = lowest_eigenpairs(k, m, 5, -1e-3);
  ASSERT_EQ(r.eigenvalues.size(), 5);
  for (int j = 1; j <= 5; ++j) {
    const double exact = 4.0 * std::pow(std::sin((2 * j - 1) * M_PI / (2.0 * (2 * n + 1))), 2);
    EXPECT_NEAR(r.eigenvalues(j - 1), exact, 1e-9 * exact) << "mode " << j << ", n = " << n;
    const VectorXd x = r.eigenvectors.col(j - 1);
    EXPECT_NEAR(x.squaredNorm(), 1.0, 1e-9);  // M = I: mass-normalised
  }
}

TEST(EigenSolver, DensePathMatchesClosedForm) {
  check_chain(60);
}
TEST(EigenSolver, LanczosPathMatchesClosedForm) {
  check_chain(800);
}

TEST(EigenSolver, FreeChainHasOneRigidBodyMode) {
  SparseMatrix k, m;
  chain(30, false, k, m);
  const EigenResult r = lowest_eigenpairs(k, m, 3, -1e-3);
  EXPECT_NEAR(r.eigenvalues(0), 0.0, 1e-9);
  EXPECT_GT(r.eigenvalues(1), 1e-3);
}

}  // namespace
}  // namespace impactfe::test_eigen_solver
