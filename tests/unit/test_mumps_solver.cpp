// The MUMPS backend (docs/scaling.md) in one process (singleton MPI): agrees with a dense solve
// for SPD and indefinite matrices and many right-hand sides, counts the negative pivots as
// Sylvester's inertia says, reuses its analysis across factorizations, and names the row of a
// zero pivot. Skipped when the module was not built. The multi-rank runs are the mpi.* tests.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cstdlib>
#include <filesystem>

#include "linalg/linear_solver.h"
#include "linalg/parallel_backend.h"

namespace impactfe::test_mumps_solver {
namespace {

/// MPI_Finalize once, after every test of this binary.
class MpiEnvironment : public ::testing::Environment {
 public:
  void TearDown() override { stop_parallel_backend(); }
};
[[maybe_unused]] const auto* const kEnvironment =
    ::testing::AddGlobalTestEnvironment(new MpiEnvironment);

std::unique_ptr<LinearSolver> mumps_or_skip() {
  const auto module = std::filesystem::path(IMPACTFE_BINARY).parent_path() / "libimpactfe_mumps.so";
  if (!std::filesystem::exists(module)) return nullptr;
  setenv("IMPACTFE_MUMPS_MODULE", module.c_str(), 0);
  start_parallel_backend({});
  return make_linear_solver(200);
}

/// Lower triangle of a 1-D Laplacian (2, −1) minus sigma on the diagonal: eigenvalues
/// 2 − 2 cos(kπ/(n+1)) − sigma, k = 1..n (indefinite for 0 < sigma < 4).
SparseMatrix laplacian(int n, double sigma) {
  std::vector<Eigen::Triplet<double, int>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 2.0 - sigma);
    if (i + 1 < n) t.emplace_back(i + 1, i, -1.0);
  }
  SparseMatrix a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  return a;
}

MatrixXd full(const SparseMatrix& lower) {
  return MatrixXd(lower).selfadjointView<Eigen::Lower>();
}

TEST(MumpsSolver, SpdAndIndefiniteMatchDenseSolves) {
  auto solver = mumps_or_skip();
  if (!solver) GTEST_SKIP() << "libimpactfe_mumps.so not built (no MUMPS/MPI)";
  EXPECT_EQ(solver->name(), "MUMPS");
  const int n = 200;
  MatrixXd b(n, 3);
  for (int i = 0; i < n; ++i) {
    b(i, 0) = 1.0;
    b(i, 1) = std::sin(0.1 * i);
    b(i, 2) = i % 7 == 0 ? 1.0 : 0.0;
  }
  // SPD: shifted Laplacian, well conditioned.
  const SparseMatrix spd = laplacian(n, -0.5);
  solver->analyze_pattern(spd);
  solver->factorize(spd);
  const MatrixXd x = solver->solve(b);
  const MatrixXd x_ref = full(spd).ldlt().solve(b);
  EXPECT_LT((x - x_ref).norm() / x_ref.norm(), 1e-13);
  EXPECT_EQ(solver->negative_pivots(), 0);
  EXPECT_LT((solver->solve(VectorXd(b.col(1))) - x_ref.col(1)).norm(), 1e-13 * x_ref.norm());
  // Indefinite, same pattern: the LDLᵀ retry; inertia = eigenvalues below sigma.
  const double sigma = 1.3;
  const SparseMatrix indefinite = laplacian(n, sigma);
  solver->factorize(indefinite);
  const MatrixXd y_ref = full(indefinite).lu().solve(b);
  EXPECT_LT((solver->solve(b) - y_ref).norm() / y_ref.norm(), 1e-12);
  int below = 0;
  for (int k = 1; k <= n; ++k) below += 2.0 - 2.0 * std::cos(k * M_PI / (n + 1)) < sigma ? 1 : 0;
  EXPECT_EQ(solver->negative_pivots(), below);
  // The factor of the last matrix is reused; the SPD analysis is not repeated for the
  // same-pattern SPD factorizations, only for the switch to LDLᵀ.
  EXPECT_EQ(solver->counters().analyses, 1);
  EXPECT_EQ(solver->counters().factorizations, 2);
  EXPECT_EQ(solver->counters().solves, 3 + 1 + 3);
}

TEST(MumpsSolver, ZeroPivotNamesItsRow) {
  auto solver = mumps_or_skip();
  if (!solver) GTEST_SKIP() << "libimpactfe_mumps.so not built (no MUMPS/MPI)";
  // Row 37 has no stiffness at all (an unrestrained DOF): its diagonal is an explicit zero.
  const int n = 120;
  std::vector<Eigen::Triplet<double, int>> t;
  for (int i = 0; i < n; ++i) {
    if (i == 37) {
      t.emplace_back(i, i, 0.0);
      continue;
    }
    t.emplace_back(i, i, 3.0);
    if (i + 1 < n && i + 1 != 37) t.emplace_back(i + 1, i, -1.0);
  }
  SparseMatrix a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  solver->analyze_pattern(a);
  try {
    solver->factorize(a);
    FAIL() << "a zero pivot must be reported";
  } catch (const SingularMatrixError& e) {
    EXPECT_EQ(e.column(), 37);
  }
}

}  // namespace
}  // namespace impactfe::test_mumps_solver
