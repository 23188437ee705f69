// solve_mass_system (the initial acceleration M a0 = r): the conjugate gradient path agrees
// with a direct solve, needs a mesh-independent number of iterations, and hands a system it
// cannot solve to a factorization.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <vector>

#include "linalg/mass_solve.h"

namespace impactfe::test_mass_solve {
namespace {

/// Lower triangle of the consistent mass of a grid of nx × ny bilinear quadrilaterals (unit
/// squares, density × thickness 2.5, one DOF per node): the element mass is
/// ρt A/36 [4 2 1 2; 2 4 2 1; 1 2 4 2; 2 1 2 4] (Zienkiewicz & Taylor, vol. 1, §16.2).
SparseMatrix quad_grid_mass(int nx, int ny) {
  const auto node = [&](int i, int j) { return j * (nx + 1) + i; };
  const double c = 2.5 / 36.0;
  const double me[4][4] = {{4, 2, 1, 2}, {2, 4, 2, 1}, {1, 2, 4, 2}, {2, 1, 2, 4}};
  std::vector<Eigen::Triplet<double, int>> t;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int n[4] = {node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)};
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b)
          if (n[a] >= n[b]) t.emplace_back(n[a], n[b], c * me[a][b]);
    }
  const int n = (nx + 1) * (ny + 1);
  SparseMatrix m(n, n);
  m.setFromTriplets(t.begin(), t.end());
  return m;
}

VectorXd direct_solve(const SparseMatrix& lower, const VectorXd& r) {
  Eigen::SimplicialLDLT<SparseMatrix> ldlt(lower);
  return ldlt.solve(r);
}

VectorXd varied_load(int n) {
  VectorXd r(n);
  for (int i = 0; i < n; ++i) r(i) = 1.0 + 0.5 * std::sin(0.37 * i) - 0.01 * (i % 7);
  return r;
}

TEST(MassSolve, SmallSystemsAreSolvedDirectly) {
  const SparseMatrix m = quad_grid_mass(10, 10);  // 121 rows
  const VectorXd r = varied_load(121);
  const MassSolveResult s = solve_mass_system(m, r);
  EXPECT_EQ(s.method, MassSolveMethod::SimplicialLdlt);
  EXPECT_LT((s.a - direct_solve(m, r)).norm(), 1e-14 * s.a.norm());
}

TEST(MassSolve, LargeSystemsTakeConjugateGradientsAndAgreeWithADirectSolve) {
  // The iteration count stays the same when the mesh is refined (Wathen's bound): 4 times the
  // rows, at most a few more iterations.
  int iterations_coarse = 0;
  for (const int nx : {80, 160}) {
    const SparseMatrix m = quad_grid_mass(nx, nx);
    const auto n = static_cast<int>(m.rows());
    const VectorXd r = varied_load(n);
    const MassSolveResult s = solve_mass_system(m, r);
    ASSERT_EQ(s.method, MassSolveMethod::ConjugateGradient) << n << " rows";
    const VectorXd exact = direct_solve(m, r);
    EXPECT_LT((s.a - exact).norm(), 1e-12 * exact.norm()) << n << " rows";
    // cond ≤ 9 after scaling: CG needs at most about √9 / 2 · ln(2 / 1e-16) ≈ 56 iterations.
    EXPECT_LE(s.iterations, 60) << n << " rows";
    if (nx == 80)
      iterations_coarse = s.iterations;
    else
      EXPECT_LE(s.iterations, iterations_coarse + 5);
  }
}

TEST(MassSolve, ARigidBodyLoadGivesTheRigidAcceleration) {
  // r = M g 1 (a uniform body load) must give a = g at every node.
  const SparseMatrix m = quad_grid_mass(100, 60);
  const VectorXd ones = VectorXd::Ones(m.rows());
  const VectorXd mass_times_ones = m.selfadjointView<Eigen::Lower>() * ones;
  const VectorXd r = 386.4 * mass_times_ones;
  const MassSolveResult s = solve_mass_system(m, r);
  EXPECT_EQ(s.method, MassSolveMethod::ConjugateGradient);
  EXPECT_LT((s.a - 386.4 * ones).cwiseAbs().maxCoeff(), 1e-10 * 386.4);
}

TEST(MassSolve, AZeroLoadNeedsNoSolve) {
  const SparseMatrix m = quad_grid_mass(100, 60);
  const MassSolveResult s = solve_mass_system(m, VectorXd::Zero(m.rows()));
  EXPECT_EQ(s.a.size(), m.rows());
  EXPECT_TRUE(s.a.isZero(0.0));
  EXPECT_EQ(s.iterations, 0);
}

TEST(MassSolve, ABadlyScaledSystemFallsBackToAFactorization) {
  // Not a mass matrix the bounds hold for: a 1-D stiffness-like chain (condition number grows
  // with n²), which conjugate gradients do not finish in the allowed iterations.
  const int n = 6000;
  std::vector<Eigen::Triplet<double, int>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, i == 0 ? 3.0 : 2.0);
    if (i + 1 < n) t.emplace_back(i + 1, i, -1.0);
  }
  SparseMatrix k(n, n);
  k.setFromTriplets(t.begin(), t.end());
  const VectorXd r = varied_load(n);
  const MassSolveResult s = solve_mass_system(k, r);
  EXPECT_EQ(s.method, MassSolveMethod::SparseFactorization);
  const VectorXd exact = direct_solve(k, r);
  EXPECT_LT((s.a - exact).norm(), 1e-9 * exact.norm());
}

}  // namespace
}  // namespace impactfe::test_mass_solve
