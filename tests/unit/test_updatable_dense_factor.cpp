// UpdatableDenseFactor: a matrix that changes in a few rows and columns is solved through
// rank-one updates of the previous factor, as accurately as by a new factorization; larger
// changes, lost definiteness and too many updates factor anew.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <random>

#include "linalg/updatable_dense_factor.h"

namespace impactfe::test_updatable_dense_factor {
namespace {

/// A symmetric positive definite m × m matrix (a dense Schur complement's kind).
MatrixXd spd(int m, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  MatrixXd b(m, m);
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) b(i, j) = value(rng);
  return b * b.transpose() + m * MatrixXd::Identity(m, m);
}

double solve_error(const UpdatableDenseFactor& f, const MatrixXd& a) {
  const VectorXd x = VectorXd::LinSpaced(a.rows(), -1.0, 2.0);
  const VectorXd b = a * x;
  return (f.solve(b) - x).norm() / x.norm();
}

TEST(UpdatableDenseFactor, GapsOpeningAndClosingUpdateTheFactor) {
  const int m = 80;
  MatrixXd a = spd(m, 1);
  UpdatableDenseFactor f;
  f.factorize(a);
  EXPECT_EQ(f.full_factorizations(), 1);
  // Gaps close (stiffness added on their DOFs), then some open again (removed).
  for (const int dof : {3, 17, 42}) {
    a(dof, dof) += 1e3;
    f.factorize(a);
    EXPECT_LE(solve_error(f, a), 1e-12);
  }
  for (const int dof : {17, 3}) {
    a(dof, dof) -= 1e3;
    f.factorize(a);
    EXPECT_LE(solve_error(f, a), 1e-11);
  }
  EXPECT_EQ(f.full_factorizations(), 1);
  EXPECT_EQ(f.rank_one_updates(), 5);
  // A two-DOF element (coupling block) changes two rows at once: two rank-one terms.
  a(10, 10) += 50.0;
  a(20, 20) += 50.0;
  a(10, 20) -= 50.0;
  a(20, 10) -= 50.0;
  f.factorize(a);
  EXPECT_LE(solve_error(f, a), 1e-12);
  EXPECT_EQ(f.full_factorizations(), 1);
  EXPECT_EQ(f.rank_one_updates(), 6);  // the block [1 -1; -1 1] has rank one
  // The same matrix again: nothing to do.
  f.factorize(a);
  EXPECT_EQ(f.rank_one_updates(), 6);
}

TEST(UpdatableDenseFactor, LargeChangesAndLostDefinitenessFactorAnew) {
  const int m = 40;
  MatrixXd a = spd(m, 2);
  UpdatableDenseFactor f;
  f.factorize(a);
  // More than m/8 rows change: a new factorization.
  for (int i = 0; i < m / 4; ++i) a(i, i) += 1.0;
  f.factorize(a);
  EXPECT_EQ(f.full_factorizations(), 2);
  EXPECT_LE(solve_error(f, a), 1e-12);
  // A downdate that makes the matrix indefinite: LDLᵀ of the new matrix, still solved.
  a(5, 5) = -3.0 * a.cwiseAbs().maxCoeff();
  f.factorize(a);
  EXPECT_EQ(f.full_factorizations(), 3);
  EXPECT_LE(solve_error(f, a), 1e-10);
  // After reset the next matrix is factored afresh.
  f.reset();
  f.factorize(spd(m, 3));
  EXPECT_EQ(f.full_factorizations(), 4);
}

TEST(UpdatableDenseFactor, RoundOffIsBoundedByRefactoringAfterManyUpdates) {
  const int m = 60;
  MatrixXd a = spd(m, 4);
  UpdatableDenseFactor f;
  f.factorize(a);
  // Gaps close and open again, one after the other.
  for (int k = 0; k < 3 * UpdatableDenseFactor::kMaxUpdates; ++k) {
    const int dof = (k / 2) % m;
    a(dof, dof) += (k % 2 == 0 ? 1e4 : -1e4);
    f.factorize(a);
    ASSERT_LE(solve_error(f, a), 1e-9) << k;
  }
  EXPECT_GE(f.full_factorizations(), 3);  // every kMaxUpdates updates
  EXPECT_GT(f.rank_one_updates(), 2 * UpdatableDenseFactor::kMaxUpdates);
}

}  // namespace
}  // namespace impactfe::test_updatable_dense_factor
