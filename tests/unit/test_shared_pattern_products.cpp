// SharedPatternProducts: one pass over the union pattern gives each matrix's own product, equal to
// Eigen's sparse product to round-off, with zero matrices and omitted products handled.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/thread_pool.h"
#include "linalg/shared_pattern_products.h"

namespace impactfe::test_shared_pattern_products {
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

/// A matrix with node blocks: `dofs` rows per node share their columns (a mesh's pattern).
SparseMatrix node_blocked(int nodes, int dofs, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<Eigen::Triplet<double, int>> t;
  for (int a = 0; a < nodes; ++a)
    for (int b : {a - 2, a - 1, a, a + 1, a + 5})
      if (b >= 0 && b < nodes)
        for (int i = 0; i < dofs; ++i)
          for (int j = 0; j < dofs; ++j) t.emplace_back(dofs * a + i, dofs * b + j, value(rng));
  SparseMatrix m(nodes * dofs, nodes * dofs);
  m.setFromTriplets(t.begin(), t.end());
  return m;
}

TEST(SharedPatternProducts, NodeBlocksShareTheirColumnsAndSumInRowOrder) {
  for (int dofs : {1, 2, 3, 5, 6, 7, 9}) {
    const int nodes = 40, n = nodes * dofs;
    const SparseMatrix k = node_blocked(nodes, dofs, 11), m = node_blocked(nodes, dofs, 12);
    const SharedPatternProducts products({&k, &m});
    // One group per node (9 rows are two groups: at most 8 rows share a list).
    EXPECT_EQ(products.row_groups(), dofs <= 8 ? nodes : 2 * nodes) << dofs;
    const VectorXd u = VectorXd::Random(n), a = VectorXd::Random(n);
    VectorXd ku, ma;
    products.multiply({&u, &a, nullptr}, {&ku, &ma, nullptr});
    // The row-by-row sums in column order, exactly.
    const Eigen::SparseMatrix<double, Eigen::RowMajor, int> kr = k, mr = m;
    for (int i = 0; i < n; ++i) {
      double sk = 0.0, sm = 0.0;
      for (Eigen::SparseMatrix<double, Eigen::RowMajor, int>::InnerIterator it(kr, i); it; ++it)
        sk += it.value() * u(it.col());
      for (Eigen::SparseMatrix<double, Eigen::RowMajor, int>::InnerIterator it(mr, i); it; ++it)
        sm += it.value() * a(it.col());
      ASSERT_EQ(ku(i), sk) << "dofs " << dofs << " row " << i;
      ASSERT_EQ(ma(i), sm) << "dofs " << dofs << " row " << i;
    }
  }
}

TEST(SharedPatternProducts, SymmetricMatricesStoreHalfAndGiveTheSameProducts) {
  for (int dofs : {1, 2, 3, 6, 9}) {
    const int nodes = 50, n = nodes * dofs;
    const SparseMatrix kb = node_blocked(nodes, dofs, 21), mb = node_blocked(nodes, dofs, 22);
    const SparseMatrix k = SparseMatrix(kb.transpose()) + kb;  // exactly symmetric
    const SparseMatrix m = SparseMatrix(mb.transpose()) + mb;
    const SharedPatternProducts half({&k, &m});
    EXPECT_TRUE(half.symmetric());
    const VectorXd u = VectorXd::Random(n), a = VectorXd::Random(n);
    VectorXd ku, ma;
    half.multiply({&u, &a, nullptr}, {&ku, &ma, nullptr});
    EXPECT_LT(relative_difference(ku, k * u), 1e-14) << dofs;
    EXPECT_LT(relative_difference(ma, m * a), 1e-14) << dofs;
    // One entry off its mirror by an ulp counts as symmetric (round-off of element products),
    // by 1e-9 it does not: the full pass.
    SparseMatrix k_ulp = k;
    k_ulp.coeffRef(dofs, 0) = std::nextafter(k_ulp.coeff(dofs, 0), 1e300);
    EXPECT_TRUE(SharedPatternProducts({&k_ulp}).symmetric());
    SparseMatrix k_off = k;
    k_off.coeffRef(dofs, 0) *= 1.0 + 1e-9;
    const SharedPatternProducts full({&k_off});
    EXPECT_FALSE(full.symmetric());
    VectorXd ku_off;
    full.multiply({&u, nullptr, nullptr}, {&ku_off, nullptr, nullptr});
    EXPECT_LT(relative_difference(ku_off, k_off * u), 1e-14) << dofs;
  }
}

/// A symmetric node-blocked matrix of a chain of nodes, each coupled to the next `reach` ones
/// (a mesh numbered with locality).
SparseMatrix symmetric_chain(int nodes, int dofs, int reach, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<Eigen::Triplet<double, int>> t;
  for (int a = 0; a < nodes; ++a)
    for (int b = a; b <= std::min(nodes - 1, a + reach); ++b)
      for (int i = 0; i < dofs; ++i)
        for (int j = 0; j < dofs; ++j) {
          const int r = dofs * a + i, c = dofs * b + j;
          if (a == b && j < i) continue;
          const double v = value(rng);
          t.emplace_back(r, c, v);
          if (r != c) t.emplace_back(c, r, v);
        }
  SparseMatrix m(nodes * dofs, nodes * dofs);
  m.setFromTriplets(t.begin(), t.end());
  return m;
}

TEST(SharedPatternProducts, LargeSymmetricProductsInChunksGiveTheSameBitsOnAnyThreadCount) {
  // 5 000 shell nodes, each coupled to the next 5: about 1.1e6 stored values per matrix.
  const int nodes = 5000, dofs = 6, n = nodes * dofs;
  const SparseMatrix k = symmetric_chain(nodes, dofs, 5, 31),
                     m = symmetric_chain(nodes, dofs, 5, 32);
  const SharedPatternProducts products({&k, &m});
  ASSERT_TRUE(products.symmetric());
  EXPECT_EQ(products.chunks(), SharedPatternProducts::kChunks);
  const VectorXd u = VectorXd::Random(n), a = VectorXd::Random(n);
  const int saved = threads::max_threads();
  std::vector<VectorXd> results;
  for (int n_threads : {1, 2, 3, 1}) {
    threads::set_max_threads(n_threads);
    VectorXd ku, ma, ma_alone;
    products.multiply({&u, &a, nullptr}, {&ku, &ma, nullptr});
    EXPECT_LT(relative_difference(ku, k * u), 1e-14) << n_threads;
    EXPECT_LT(relative_difference(ma, m * a), 1e-14) << n_threads;
    products.multiply({nullptr, &a, nullptr}, {nullptr, &ma_alone, nullptr});
    EXPECT_EQ(ma_alone, ma);
    results.push_back(ku);
    results.push_back(ma);
  }
  threads::set_max_threads(saved);
  for (std::size_t i = 2; i < results.size(); ++i)
    EXPECT_EQ(results[i], results[i % 2]) << i;  // bitwise: operator== compares exactly

  // Couplings that reach across the whole matrix (no locality): one pass on one thread.
  std::vector<Eigen::Triplet<double, int>> anti;
  for (int i = 0; i < n; ++i) anti.emplace_back(i, n - 1 - i, 1.0);
  SparseMatrix reach(n, n);
  reach.setFromTriplets(anti.begin(), anti.end());
  const SparseMatrix far = k + reach;
  const SharedPatternProducts unchunked({&far});
  EXPECT_EQ(unchunked.chunks(), 0);
  VectorXd kf;
  unchunked.multiply({&u, nullptr, nullptr}, {&kf, nullptr, nullptr});
  EXPECT_LT(relative_difference(kf, far * u), 1e-14);
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
}  // namespace impactfe::test_shared_pattern_products
