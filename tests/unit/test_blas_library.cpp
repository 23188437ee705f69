// The system BLAS and LAPACK are mapped only when a supernodal factorization needs them, and
// CHOLMOD's calls reach them through the entry points of linalg/blas_library.cpp.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "core/thread_pool.h"
#include "linalg/blas_library.h"
#include "linalg/linear_solver.h"

extern "C" void dgemm_(void*, void*, void*, void*, void*, void*, void*, void*, void*, void*, void*,
                       void*, void*);

namespace impactfe::test_blas_library {
namespace {

bool mapped(const std::string& library) {
  std::ifstream maps("/proc/self/maps");
  std::stringstream s;
  s << maps.rdbuf();
  return s.str().find(library) != std::string::npos;
}

/// Lower triangle of the 3-D Laplacian on an m³ grid (m = 24: beyond the inline kernels).
SparseMatrix laplacian(int m) {
  const auto at = [m](int i, int j, int k) { return (i * m + j) * m + k; };
  std::vector<Eigen::Triplet<double, int>> t;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < m; ++k) {
        const int p = at(i, j, k);
        t.emplace_back(p, p, 6.5);
        if (i > 0) t.emplace_back(p, at(i - 1, j, k), -1.0);
        if (j > 0) t.emplace_back(p, at(i, j - 1, k), -1.0);
        if (k > 0) t.emplace_back(p, at(i, j, k - 1), -1.0);
      }
  SparseMatrix a(m * m * m, m * m * m);
  a.setFromTriplets(t.begin(), t.end());
  return a;
}

TEST(BlasLibrary, NotMappedUntilAFactorizationNeedsIt) {
  // The first test of this binary: nothing has asked for BLAS yet.
  EXPECT_FALSE(blas::loaded());
  EXPECT_FALSE(mapped("libblas.so")) << "BLAS mapped at start-up";
  EXPECT_EQ(blas::describe(), "not loaded");
  // A small model factors with the inline kernels: still not loaded.
  const SparseMatrix small = laplacian(6);
  auto solver = make_linear_solver(static_cast<int>(small.rows()));
  solver->analyze_pattern(small);
  solver->factorize(small);
  EXPECT_FALSE(blas::loaded());
  // A large one takes CHOLMOD's supernodal kernels: loaded, and the answer right.
  const SparseMatrix large = laplacian(24);
  auto big = make_linear_solver(static_cast<int>(large.rows()));
  big->analyze_pattern(large);
  big->factorize(large);
  EXPECT_TRUE(blas::loaded());
  EXPECT_TRUE(mapped("libblas.so"));
  const VectorXd b = VectorXd::LinSpaced(large.rows(), 0.0, 1.0);
  const VectorXd x = big->solve(b);
  const VectorXd r = SparseMatrix(large.selfadjointView<Eigen::Lower>()) * x - b;
  EXPECT_LE(r.norm(), 1e-10 * b.norm());
  EXPECT_NE(blas::describe().find("libblas.so.3"), std::string::npos) << blas::describe();
}

TEST(BlasLibrary, EntryPointsForwardToTheLibrary) {
  blas::require();
  // C = A B with A = [1 2; 3 4], B = I (column-major).
  double A[4] = {1, 3, 2, 4}, B[4] = {1, 0, 0, 1}, C[4] = {0, 0, 0, 0};
  char no = 'N';
  int two = 2;
  double one = 1.0, zero = 0.0;
  dgemm_(&no, &no, &two, &two, &two, &one, A, &two, B, &two, &zero, C, &two);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(C[i], A[i]);
}

TEST(BlasLibrary, RunsOnOneThreadWhateverTheThreadSetting) {
  const int saved = threads::max_threads();
  threads::set_max_threads(2);
  blas::require();
  const int n = blas::threads();
  threads::set_max_threads(saved);
  if (n == 0) GTEST_SKIP() << "not OpenBLAS: " << blas::describe();
  EXPECT_EQ(n, 1);
}

}  // namespace
}  // namespace impactfe::test_blas_library
