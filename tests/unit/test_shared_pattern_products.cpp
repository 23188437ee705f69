// SharedPatternProducts: one pass over the union pattern gives each matrix's own product, equal to
// Eigen's sparse product to round-off, with zero matrices and omitted products handled.
#include <gtest/gtest.h>

#include <random>

#include "linalg/shared_pattern_products.h"

namespace impactfe {
namespace {

/// A random n × n sparse matrix with about `per_row` entries per row (different patterns for
/// different seeds, so the union is larger than each).
SparseMatrix random_sparse(int n, int per_row, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> column(0, n - 1);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<Eigen::Triplet<double, int>> t;
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < per_row; ++k) t.emplace_back(i, column(rng), value(rng));
  SparseMatrix a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  return a;
}

double relative_difference(const VectorXd& a, const VectorXd& b) {
  return (a - b).norm() / std::max(b.norm(), 1e-300);
}

TEST(SharedPatternProducts, EachProductEqualsItsOwnMatrixProduct) {
  const int n = 300;
  const SparseMatrix k = random_sparse(n, 7, 1), c = random_sparse(n, 3, 2),
                     m = random_sparse(n, 5, 3);
  const SharedPatternProducts products({&k, &c, &m});
  EXPECT_EQ(products.rows(), n);
  EXPECT_GE(products.nonzeros(), k.nonZeros());
  const VectorXd u = VectorXd::Random(n), v = VectorXd::Random(n), a = VectorXd::Random(n);
  VectorXd ku, cv, ma;
  products.multiply({&u, &v, &a}, {&ku, &cv, &ma});
  EXPECT_LT(relative_difference(ku, k * u), 1e-14);
  EXPECT_LT(relative_difference(cv, c * v), 1e-14);
  EXPECT_LT(relative_difference(ma, m * a), 1e-14);
  // One product alone gives the same values (the pass does not depend on the others).
  VectorXd ma_alone;
  products.multiply({nullptr, nullptr, &a}, {nullptr, nullptr, &ma_alone});
  EXPECT_EQ(ma_alone, ma);
  VectorXd ku_cv[2];
  products.multiply({&u, &v, nullptr}, {&ku_cv[0], &ku_cv[1], nullptr});
  EXPECT_EQ(ku_cv[0], ku);
  EXPECT_EQ(ku_cv[1], cv);
}

TEST(SharedPatternProducts, ZeroMatrixGivesZeroVector) {
  const int n = 50;
  const SparseMatrix k = random_sparse(n, 4, 7);
  const SparseMatrix empty(n, n);
  const SharedPatternProducts products({&k, &empty});
  const VectorXd u = VectorXd::Random(n), v = VectorXd::Random(n);
  VectorXd ku, cv = VectorXd::Ones(3);
  products.multiply({&u, &v, nullptr}, {&ku, &cv, nullptr});
  EXPECT_LT(relative_difference(ku, k * u), 1e-14);
  ASSERT_EQ(cv.size(), n);
  EXPECT_EQ(cv.norm(), 0.0);
}

TEST(SharedPatternProducts, DuplicateEntriesAreSummed) {
  // Element assembly gives several triplets per position: they must add up.
  std::vector<Eigen::Triplet<double, int>> t = {
      {0, 0, 1.0}, {0, 0, 2.0}, {1, 0, -1.0}, {0, 1, -1.0}, {1, 1, 4.0}};
  SparseMatrix k(2, 2);
  k.setFromTriplets(t.begin(), t.end());
  const SharedPatternProducts products({&k});
  const VectorXd u = VectorXd::Ones(2);
  VectorXd ku;
  products.multiply({&u, nullptr, nullptr}, {&ku, nullptr, nullptr});
  EXPECT_DOUBLE_EQ(ku(0), 2.0);
  EXPECT_DOUBLE_EQ(ku(1), 3.0);
}

}  // namespace
}  // namespace impactfe
