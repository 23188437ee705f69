// LinearSolver: CHOLMOD and dense back ends agree with a direct solve, count their work, and
// report the row of a zero pivot (so a singular model can name its node and DOF).
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "linalg/linear_solver.h"

namespace impactfe::test_linear_solver {
namespace {

/// Lower triangle of the stiffness of a chain of n springs k = 1..n, grounded at one end:
/// tridiagonal, symmetric positive definite.
SparseMatrix spring_chain(int n, bool grounded = true) {
  std::vector<Eigen::Triplet<double, int>> t;
  for (int i = 0; i < n; ++i) {
    const double k_left = (i == 0 && !grounded) ? 0.0 : 1.0 + i;
    const double k_right = i + 1 < n ? 2.0 + i : 0.0;
    t.emplace_back(i, i, k_left + k_right);
    if (i + 1 < n) t.emplace_back(i + 1, i, -(2.0 + i));
  }
  SparseMatrix a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  return a;
}

class LinearSolverBackends : public ::testing::TestWithParam<LinearSolverKind> {};

TEST_P(LinearSolverBackends, SolvesAndCounts) {
  const int n = 200;
  const SparseMatrix a = spring_chain(n);
  auto solver = make_linear_solver(n, GetParam());
  solver->analyze_pattern(a);
  solver->factorize(a);
  const VectorXd b = VectorXd::LinSpaced(n, 1.0, 2.0);
  const VectorXd x = solver->solve(b);
  const MatrixXd full = MatrixXd(a).selfadjointView<Eigen::Lower>();
  EXPECT_LT((full * x - b).norm(), 1e-10 * b.norm());
  MatrixXd B(n, 3);
  B << b, 2.0 * b, -b;
  const MatrixXd X = solver->solve(B);
  EXPECT_LT((X.col(1) - 2.0 * x).norm(), 1e-10 * x.norm());
  EXPECT_EQ(solver->counters().analyses, 1);
  EXPECT_EQ(solver->counters().factorizations, 1);
  EXPECT_EQ(solver->counters().solves, 4);
}

TEST_P(LinearSolverBackends, ReportsFactorSizesAndTimes) {
  // A dense SPD matrix cannot fill in: nnz(L) = nnz(lower A) = n(n+1)/2 for any ordering.
  const int n = 80;
  MatrixXd dense = MatrixXd::Constant(n, n, 1.0);
  dense.diagonal().array() += n;
  const SparseMatrix a = MatrixXd(dense.triangularView<Eigen::Lower>()).sparseView();
  auto solver = make_linear_solver(n, GetParam());
  solver->analyze_pattern(a);
  solver->factorize(a);
  const VectorXd x = solver->solve(VectorXd(VectorXd::Ones(n)));
  EXPECT_NEAR(x(0), 1.0 / (2.0 * n), 1e-12);
  const SolverCounters& c = solver->counters();
  EXPECT_EQ(c.matrix_nonzeros, n * (n + 1) / 2);
  EXPECT_EQ(c.factor_nonzeros, n * (n + 1) / 2);
  // A solve reads at least the values of L, and (dense or supernodal) at most a full square
  // block of values plus one row index per value.
  EXPECT_GE(c.factor_bytes, static_cast<long>(sizeof(double)) * c.factor_nonzeros);
  EXPECT_LE(c.factor_bytes, static_cast<long>(sizeof(double) + sizeof(int)) * n * n);
  EXPECT_GT(c.factorize_seconds, 0.0);
  EXPECT_GT(c.solve_seconds, 0.0);
  EXPECT_GE(c.analyze_seconds, 0.0);
}

TEST(SolverCounters, SumCountsAndTimesKeepLargestSizes) {
  SolverCounters a, b;
  a.analyses = 1;
  a.factorizations = 2;
  a.solves = 10;
  a.factorize_seconds = 0.5;
  a.factor_nonzeros = 100;
  a.factor_bytes = 1200;
  a.matrix_nonzeros = 40;
  b.factorizations = 3;
  b.solves = 5;
  b.factorize_seconds = 0.25;
  b.solve_seconds = 0.125;
  b.factor_nonzeros = 300;
  b.factor_bytes = 1000;
  b.matrix_nonzeros = 20;
  a += b;
  EXPECT_EQ(a.analyses, 1);
  EXPECT_EQ(a.factorizations, 5);
  EXPECT_EQ(a.solves, 15);
  EXPECT_DOUBLE_EQ(a.factorize_seconds, 0.75);
  EXPECT_DOUBLE_EQ(a.solve_seconds, 0.125);
  EXPECT_EQ(a.factor_nonzeros, 300);
  EXPECT_EQ(a.factor_bytes, 1200);
  EXPECT_EQ(a.matrix_nonzeros, 40);
}

TEST_P(LinearSolverBackends, NamesTheZeroPivot) {
  // An ungrounded chain is a mechanism (rigid translation): the factorization must fail.
  const int n = 100;
  auto solver = make_linear_solver(n, GetParam());
  const SparseMatrix a = spring_chain(n, /*grounded=*/false);
  solver->analyze_pattern(a);
  try {
    solver->factorize(a);
    FAIL() << "a singular matrix was factorized";
  } catch (const SingularMatrixError& e) {
    EXPECT_GE(e.column(), 0);
    EXPECT_LT(e.column(), n);
  }
}

TEST_P(LinearSolverBackends, IndefiniteButRegularMatrixIsSolved) {
  // diag(2, -1, 3) with a coupling: regular, not positive definite (compressive stress
  // stiffening can do this); the LDLᵀ path must solve it.
  std::vector<Eigen::Triplet<double, int>> t = {
      {0, 0, 2.0}, {1, 1, -1.0}, {2, 2, 3.0}, {1, 0, 0.5}};
  SparseMatrix a(3, 3);
  a.setFromTriplets(t.begin(), t.end());
  auto solver = make_linear_solver(3, GetParam());
  solver->analyze_pattern(a);
  solver->factorize(a);
  const VectorXd b = VectorXd::Ones(3);
  const MatrixXd full = MatrixXd(a).selfadjointView<Eigen::Lower>();
  EXPECT_LT((full * solver->solve(b) - b).norm(), 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Backends, LinearSolverBackends,
                         ::testing::Values(LinearSolverKind::Cholmod, LinearSolverKind::Dense),
                         [](const ::testing::TestParamInfo<LinearSolverKind>& info) {
                           return info.param == LinearSolverKind::Cholmod ? "Cholmod" : "Dense";
                         });

TEST(WeakestPivot, FindsTheMechanismRow) {
  // Chain grounded, but spring 50-51 missing: the part beyond 50 floats.
  const int n = 100;
  std::vector<Eigen::Triplet<double, int>> t;
  for (int i = 0; i < n; ++i) {
    double d = 0.0;
    if (i == 0) d += 1.0;
    if (i > 0 && i != 51) d += 1.0;
    if (i + 1 < n && i != 50) {
      d += 1.0;
      t.emplace_back(i + 1, i, -1.0);
    }
    t.emplace_back(i, i, d);
  }
  SparseMatrix a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  const int row = weakest_pivot_row(a);
  EXPECT_GE(row, 51);  // a row of the floating part
}

}  // namespace
}  // namespace impactfe::test_linear_solver
