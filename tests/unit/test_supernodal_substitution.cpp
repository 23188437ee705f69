// Forward and back substitution on CHOLMOD's supernodal factor (supernodal_substitution.h): the
// same L⁻¹ b and L⁻ᵀ b as CHOLMOD's own solve, to round-off, on factors whose supernodes have
// from one to hundreds of columns (all remainders of the eight-column blocks), column by column
// and eight columns per pass, and x = A⁻¹ b; the same on several threads (SubtreeSubstitution).
#include <gtest/gtest.h>

#include <cholmod.h>

#include <algorithm>
#include <cstring>
#include <random>

#include "core/thread_pool.h"
#include "linalg/solver_support.h"
#include "linalg/supernodal_substitution.h"

namespace impactfe::test_supernodal_substitution {
namespace {

/// Lower triangle of an SPD matrix: a 3-D grid of nx × ny × nz nodes with `dofs` unknowns per
/// node, coupled to the 26 neighbours by random blocks (diagonally dominant).
SparseMatrix grid_matrix(int nx, int ny, int nz, int dofs, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  const auto node = [&](int i, int j, int k) { return (i * ny + j) * nz + k; };
  const int n = dofs * nx * ny * nz;
  std::vector<Eigen::Triplet<double, int>> t;
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int k = 0; k < nz; ++k)
        for (int di = 0; di <= 1; ++di)
          for (int dj = -1; dj <= 1; ++dj)
            for (int dk = -1; dk <= 1; ++dk) {
              const int i2 = i + di, j2 = j + dj, k2 = k + dk;
              if (i2 >= nx || j2 < 0 || j2 >= ny || k2 < 0 || k2 >= nz) continue;
              const int a = node(i, j, k), b = node(i2, j2, k2);
              if (b < a) continue;
              for (int p = 0; p < dofs; ++p)
                for (int q = 0; q < dofs; ++q) {
                  const int r = dofs * b + q, c = dofs * a + p;
                  if (r < c) continue;
                  t.emplace_back(r, c, r == c ? 60.0 * dofs : value(rng));
                }
            }
  SparseMatrix a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  a.makeCompressed();
  return a;
}

struct Factor {
  cholmod_common c{};
  cholmod_factor* f = nullptr;
  explicit Factor(const SparseMatrix& lower) {
    cholmod_start(&c);
    c.supernodal = CHOLMOD_SUPERNODAL;
    c.final_ll = 1;
    cholmod_sparse a = solver_support::cholmod_lower_view(lower);
    f = cholmod_analyze(&a, &c);
    cholmod_factorize(&a, f, &c);
  }
  ~Factor() {
    cholmod_free_factor(&f, &c);
    cholmod_finish(&c);
  }
  /// CHOLMOD's own solve of `system` (CHOLMOD_L, CHOLMOD_Lt or CHOLMOD_A).
  VectorXd cholmod(int system, const VectorXd& b) {
    cholmod_dense rhs{};
    rhs.nrow = rhs.nzmax = rhs.d = static_cast<size_t>(b.size());
    rhs.ncol = 1;
    rhs.x = const_cast<double*>(b.data());
    rhs.xtype = CHOLMOD_REAL;
    rhs.dtype = CHOLMOD_DOUBLE;
    cholmod_dense* x = cholmod_solve(system, f, &rhs, &c);
    VectorXd out = Eigen::Map<const VectorXd>(static_cast<const double*>(x->x), b.size());
    cholmod_free_dense(&x, &c);
    return out;
  }
};

double relative(const VectorXd& a, const VectorXd& b) {
  return (a - b).norm() / b.norm();
}

TEST(SupernodalSubstitution, MatchesCholmodOnEverySupernodeWidth) {
  std::vector<int> widths;  // of every supernode of the factors below
  for (const auto& [nx, dofs] :
       {std::pair{3, 1}, std::pair{5, 3}, std::pair{9, 3}, std::pair{7, 6}}) {
    const SparseMatrix a = grid_matrix(nx, nx, nx, dofs, 11u + static_cast<unsigned>(nx));
    Factor factor(a);
    ASSERT_TRUE(factor.f->is_super) << nx;
    SupernodalLayout layout = solver_support::supernodal_layout(factor.f);
    for (int s = 0; s < layout.n_super; ++s)
      widths.push_back(layout.super[s + 1] - layout.super[s]);
    const VectorXd b = VectorXd::Random(a.rows());
    const auto* perm = static_cast<const int*>(factor.f->Perm);
    const SparseMatrix full = SparseMatrix(a.selfadjointView<Eigen::Lower>());
    // Column by column (the factor's own supernodes are below 1024 rows), then eight columns
    // per pass on every supernode with more than 8 rows.
    for (int long_column : {1024, 8}) {
      layout.long_column = long_column;
      std::vector<double> work;
      VectorXd forward = b;
      forward_substitution(layout, forward.data(), work);
      EXPECT_LT(relative(forward, factor.cholmod(CHOLMOD_L, b)), 1e-13) << nx << " " << long_column;
      VectorXd backward = b;
      back_substitution(layout, backward.data(), work);
      EXPECT_LT(relative(backward, factor.cholmod(CHOLMOD_Lt, b)), 1e-13)
          << nx << " " << long_column;

      // x = A⁻¹ b through the permutation, and its residual.
      VectorXd y(a.rows());
      for (Eigen::Index k = 0; k < a.rows(); ++k) y(k) = b(perm[k]);
      forward_substitution(layout, y.data(), work);
      back_substitution(layout, y.data(), work);
      VectorXd x(a.rows());
      for (Eigen::Index k = 0; k < a.rows(); ++k) x(perm[k]) = y(k);
      EXPECT_LT(relative(x, factor.cholmod(CHOLMOD_A, b)), 1e-12) << nx << " " << long_column;
      EXPECT_LT((full * x - b).norm() / b.norm(), 1e-12) << nx << " " << long_column;
    }
  }
  // The factors had wide supernodes, and widths of every remainder of the eight-column blocks.
  EXPECT_GE(*std::max_element(widths.begin(), widths.end()), 16);
  for (int r = 0; r < 8; ++r)
    EXPECT_TRUE(std::any_of(widths.begin(), widths.end(), [r](int w) { return w % 8 == r; }))
        << "no supernode of width " << r << " mod 8";
}

/// Bitwise equality of two vectors.
bool same_bits(const VectorXd& a, const VectorXd& b) {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

TEST(SubtreeSubstitution, SolvesAsTheSerialSubstitutionsOnAnyThreadCount) {
  const SparseMatrix a = grid_matrix(14, 14, 14, 3, 5u);  // 8232 unknowns
  Factor factor(a);
  ASSERT_TRUE(factor.f->is_super);
  const SupernodalLayout layout = solver_support::supernodal_layout(factor.f);
  SubtreeSubstitution subtrees;
  const long long values = layout.value_start[layout.n_super];
  subtrees.plan(layout, values + 1);  // below the threshold: one thread
  EXPECT_EQ(subtrees.groups(), 0);
  subtrees.plan(layout, values);
  ASSERT_GE(subtrees.groups(), 2);
  // The top separators of a small 3-D grid are a large part of its factor.
  EXPECT_GT(subtrees.serial_fraction(), 0.0);
  EXPECT_LT(subtrees.serial_fraction(), 0.5);

  const VectorXd b = VectorXd::Random(a.rows());
  std::vector<double> work;
  VectorXd serial_forward = b, serial_back = b;
  forward_substitution(layout, serial_forward.data(), work);
  back_substitution(layout, serial_back.data(), work);
  const int saved = threads::max_threads();
  std::vector<VectorXd> results;
  for (int n_threads : {1, 2, 3, 1}) {
    threads::set_max_threads(n_threads);
    // Twice each: the group buffers must be back to zero after a forward substitution.
    for (int repeat = 0; repeat < 2; ++repeat) {
      VectorXd forward = b;
      subtrees.forward(layout, forward.data());
      // The separators' rows sum the groups' updates in another order: round-off apart.
      EXPECT_LT(relative(forward, serial_forward), 1e-14) << n_threads;
      results.push_back(forward);
      VectorXd back = b;
      subtrees.back(layout, back.data());
      EXPECT_TRUE(same_bits(back, serial_back)) << n_threads;  // only reads across subtrees
      // x = A⁻¹ b.
      const auto* perm = static_cast<const int*>(factor.f->Perm);
      VectorXd y(a.rows());
      for (Eigen::Index k = 0; k < a.rows(); ++k) y(k) = b(perm[k]);
      subtrees.forward(layout, y.data());
      subtrees.back(layout, y.data());
      VectorXd x(a.rows());
      for (Eigen::Index k = 0; k < a.rows(); ++k) x(perm[k]) = y(k);
      EXPECT_LT(relative(x, factor.cholmod(CHOLMOD_A, b)), 1e-12) << n_threads;
    }
  }
  threads::set_max_threads(saved);
  for (const VectorXd& r : results) EXPECT_TRUE(same_bits(r, results.front()));
}

}  // namespace
}  // namespace impactfe::test_supernodal_substitution
