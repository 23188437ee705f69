// Static condensation onto a set c (src/linalg/schur_solver.h), both implementations against
// dense algebra: S = A_cc − A_ci A_ii⁻¹ A_ic, condense(r) = (A⁻¹ r)_c, recover(x_c) satisfies
// the i rows of A x = r with x_c given, recover(condense(r)) = A⁻¹ r.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <string>

#include "linalg/schur_solver.h"

namespace impactfe::test_schur_solver {
namespace {

/// A 3-D grid Laplacian plus a diagonal shift (a stiffness-plus-mass-like SPD matrix), lower
/// triangle, with a few random long-range couplings so that the ordering has work to do.
SparseMatrix grid_matrix(int nx, int ny, int nz, unsigned seed) {
  const int n = nx * ny * nz;
  auto id = [&](int i, int j, int k) { return (k * ny + j) * nx + i; };
  std::vector<Eigen::Triplet<double>> t;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> stiffness(0.5, 2.0);
  VectorXd diagonal = VectorXd::Constant(n, 0.01);
  auto couple = [&](int a, int b, double k) {
    t.emplace_back(std::max(a, b), std::min(a, b), -k);
    diagonal(a) += k;
    diagonal(b) += k;
  };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        if (i + 1 < nx) couple(id(i, j, k), id(i + 1, j, k), stiffness(rng));
        if (j + 1 < ny) couple(id(i, j, k), id(i, j + 1, k), stiffness(rng));
        if (k + 1 < nz) couple(id(i, j, k), id(i, j, k + 1), stiffness(rng));
      }
  std::uniform_int_distribution<int> any(0, n - 1);
  for (int e = 0; e < n / 10; ++e)
    if (const int a = any(rng), b = any(rng); a != b) couple(a, b, 0.1 * stiffness(rng));
  for (int i = 0; i < n; ++i) t.emplace_back(i, i, diagonal(i));
  SparseMatrix lower(n, n);
  lower.setFromTriplets(t.begin(), t.end());
  return lower;
}

MatrixXd block(const MatrixXd& a, const std::vector<int>& rows, const std::vector<int>& cols) {
  MatrixXd b(rows.size(), cols.size());
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t j = 0; j < cols.size(); ++j) b(i, j) = a(rows[i], cols[j]);
  return b;
}

void check_against_dense(SchurSolverKind kind, const SparseMatrix& lower,
                         const std::vector<int>& c) {
  const int n = static_cast<int>(lower.rows());
  const MatrixXd a = MatrixXd(lower).selfadjointView<Eigen::Lower>();
  std::vector<int> rest;
  for (int i = 0, k = 0; i < n; ++i) {
    if (k < static_cast<int>(c.size()) && c[static_cast<std::size_t>(k)] == i)
      ++k;
    else
      rest.push_back(i);
  }
  const auto solver = make_schur_solver(n, c, kind);
  solver->analyze_pattern(lower);
  solver->factorize(lower);
  const MatrixXd schur =
      block(a, c, c) - block(a, c, rest) * block(a, rest, rest).ldlt().solve(block(a, rest, c));
  EXPECT_LT((solver->schur() - schur).norm(), 1e-12 * schur.norm()) << solver->name();
  EXPECT_EQ((solver->schur() - solver->schur().transpose()).norm(), 0.0);

  std::mt19937 rng(7);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  VectorXd r(n), x_c(static_cast<Eigen::Index>(c.size()));
  for (int i = 0; i < n; ++i) r(i) = value(rng);
  for (Eigen::Index k = 0; k < x_c.size(); ++k) x_c(k) = value(rng);
  const VectorXd exact = a.ldlt().solve(r);
  const VectorXd y = solver->condense(r);
  for (std::size_t k = 0; k < c.size(); ++k)
    EXPECT_NEAR(y(static_cast<Eigen::Index>(k)), exact(c[k]), 1e-12 * exact.norm());
  // recover(y) is the whole solution, and recover(x_c) balances the rows of i.
  EXPECT_LT((solver->recover(y) - exact).norm(), 1e-12 * exact.norm()) << solver->name();
  const VectorXd x = solver->recover(x_c);
  for (std::size_t k = 0; k < c.size(); ++k) EXPECT_EQ(x(c[k]), x_c(static_cast<Eigen::Index>(k)));
  const VectorXd residual = a * x - r;
  double worst = 0.0;
  for (int i : rest) worst = std::max(worst, std::abs(residual(i)));
  EXPECT_LT(worst, 1e-12 * a.norm() * x.norm()) << solver->name();
  // The c rows carry exactly the force S (x_c − y) that holds x_c away from y.
  const VectorXd force_c = solver->schur() * (x_c - y);
  for (std::size_t k = 0; k < c.size(); ++k)
    EXPECT_NEAR(residual(c[k]), force_c(static_cast<Eigen::Index>(k)), 1e-10 * force_c.norm());
}

TEST(SchurSolver, SurfaceOfAGridMatchesDenseAlgebra) {
  const SparseMatrix lower = grid_matrix(8, 7, 6, 1);
  std::vector<int> bottom;  // the face k = 0, as contact DOFs
  for (int i = 0; i < 8 * 7; ++i) bottom.push_back(i);
  check_against_dense(SchurSolverKind::Factorization, lower, bottom);
  check_against_dense(SchurSolverKind::Transfer, lower, bottom);
}

TEST(SchurSolver, ScatteredAndDisconnectedSetsMatchDenseAlgebra) {
  // c spread over the grid (not connected through its own block: the elimination tree of the
  // c-last ordering is not a chain, and the ordering must still keep c last).
  const SparseMatrix lower = grid_matrix(6, 6, 6, 2);
  std::vector<int> scattered;
  for (int i = 3; i < 216; i += 17) scattered.push_back(i);
  check_against_dense(SchurSolverKind::Factorization, lower, scattered);
  check_against_dense(SchurSolverKind::Transfer, lower, scattered);
  // A single row, and all rows but one.
  check_against_dense(SchurSolverKind::Factorization, lower, {100});
  std::vector<int> all_but_one;
  for (int i = 0; i < 216; ++i)
    if (i != 50) all_but_one.push_back(i);
  check_against_dense(SchurSolverKind::Factorization, lower, all_but_one);
}

TEST(SchurSolver, NotPositiveDefiniteNamesTheRow) {
  // A chain 0-1-2-3-4 whose row 3 has lost its diagonal: not positive definite.
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < 5; ++i) t.emplace_back(i, i, i == 3 ? -1.0 : 2.0);
  for (int i = 0; i + 1 < 5; ++i) t.emplace_back(i + 1, i, -0.5);
  SparseMatrix lower(5, 5);
  lower.setFromTriplets(t.begin(), t.end());
  const auto solver = make_schur_solver(5, {0, 4}, SchurSolverKind::Factorization);
  solver->analyze_pattern(lower);
  try {
    solver->factorize(lower);
    FAIL() << "no error";
  } catch (const SingularMatrixError& e) {
    EXPECT_GE(e.column(), 1);
    EXPECT_LE(e.column(), 3);  // the failing pivot is in the rest, up to row 3
  }
}

TEST(SchurSolver, ReleasingTheMatrixGivesTheSameFactorization) {
  // factorize_and_release frees the caller's matrix before the factor's values are allocated
  // (issue 11): the same Schur complement and solutions bit for bit, and the matrix is empty.
  const SparseMatrix lower = grid_matrix(6, 5, 4, 3);
  std::vector<int> c;
  for (int i = 0; i < 30; ++i) c.push_back(i);
  for (SchurSolverKind kind : {SchurSolverKind::Factorization, SchurSolverKind::Transfer}) {
    const auto kept = make_schur_solver(120, c, kind);
    const auto released = make_schur_solver(120, c, kind);
    kept->analyze_pattern(lower);
    released->analyze_pattern(lower);
    kept->factorize(lower);
    SparseMatrix copy = lower;
    released->factorize_and_release(copy);
    EXPECT_EQ(copy.nonZeros(), 0);
    EXPECT_EQ(kept->schur(), released->schur()) << kept->name();
    const VectorXd r = VectorXd::LinSpaced(120, -1.0, 2.0);
    const VectorXd y = kept->condense(r);
    EXPECT_EQ(y, released->condense(r)) << kept->name();
    EXPECT_EQ(kept->recover(y), released->recover(y)) << kept->name();
    // Factored again (another time step size) from a fresh copy.
    copy = 2.0 * lower;
    released->factorize_and_release(copy);
    EXPECT_LT((released->schur() - 2.0 * kept->schur()).norm(), 1e-12 * kept->schur().norm());
  }
}

TEST(SchurSolver, NearZeroPivotOfAReleasedMatrixNamesTheRow) {
  // Rows 2 and 3 of a chain are all but dependent (a near-mechanism): every pivot is positive
  // but one is ~1e-15 of its diagonal. The diagnosis reads the solver's permuted copy, since
  // the caller's matrix is gone, and names a row of the original numbering.
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < 6; ++i) t.emplace_back(i, i, i == 2 || i == 3 ? 1.0 : 4.0);
  t.emplace_back(3, 2, 1.0 - 1e-15);
  t.emplace_back(1, 0, -1.0);
  t.emplace_back(5, 4, -1.0);
  SparseMatrix lower(6, 6);
  lower.setFromTriplets(t.begin(), t.end());
  const auto solver = make_schur_solver(6, {0, 5}, SchurSolverKind::Factorization);
  solver->analyze_pattern(lower);
  try {
    solver->factorize_and_release(lower);
    FAIL() << "no error";
  } catch (const SingularMatrixError& e) {
    EXPECT_TRUE(e.column() == 2 || e.column() == 3) << e.column();
    EXPECT_NE(std::string(e.what()).find("near-zero pivot"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace impactfe::test_schur_solver
