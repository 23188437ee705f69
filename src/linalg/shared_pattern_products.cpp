#include "linalg/shared_pattern_products.h"

#include <algorithm>

#include "core/errors.h"

namespace impactfe {

SharedPatternProducts::SharedPatternProducts(const std::vector<const SparseMatrix*>& matrices)
    : n_matrices_(static_cast<int>(matrices.size())) {
  IMPACTFE_CHECK(n_matrices_ >= 1 && n_matrices_ <= kMaxMatrices,
                 "SharedPatternProducts: 1 to 3 matrices expected");
  int n = 0;
  for (const SparseMatrix* a : matrices) n = std::max(n, static_cast<int>(a->rows()));
  // The union pattern, row by row (a row-major matrix of ones: no cancellation).
  std::vector<Eigen::Triplet<double, int>> ones;
  for (int m = 0; m < n_matrices_; ++m) {
    const SparseMatrix& a = *matrices[static_cast<std::size_t>(m)];
    IMPACTFE_CHECK(a.nonZeros() == 0 || (a.rows() == n && a.cols() == n),
                   "SharedPatternProducts: matrices of different sizes");
    nonzero_[static_cast<std::size_t>(m)] = a.nonZeros() > 0;
    for (int j = 0; j < a.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(a, j); it; ++it)
        ones.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), 1.0);
  }
  Eigen::SparseMatrix<double, Eigen::RowMajor, int> pattern(n, n);
  pattern.setFromTriplets(ones.begin(), ones.end());
  pattern.makeCompressed();
  row_start_.assign(pattern.outerIndexPtr(), pattern.outerIndexPtr() + n + 1);
  column_.assign(pattern.innerIndexPtr(), pattern.innerIndexPtr() + pattern.nonZeros());
  for (int m = 0; m < n_matrices_; ++m) {
    const SparseMatrix& a = *matrices[static_cast<std::size_t>(m)];
    std::vector<double>& value = value_[static_cast<std::size_t>(m)];
    if (a.nonZeros() > 0) value.assign(column_.size(), 0.0);
    for (int j = 0; j < a.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(a, j); it; ++it) {
        const int row = static_cast<int>(it.row());
        const int* begin = column_.data() + row_start_[static_cast<std::size_t>(row)];
        const int* end = column_.data() + row_start_[static_cast<std::size_t>(row) + 1];
        const auto k =
            static_cast<std::size_t>(std::lower_bound(begin, end, it.col()) - column_.data());
        value[k] += it.value();
      }
  }
}

SharedPatternProducts::SharedPatternProducts(const std::vector<int>& row_start,
                                             const std::vector<int>& column,
                                             const std::vector<unsigned char>& kept,
                                             const std::vector<const std::vector<double>*>& values)
    : n_matrices_(static_cast<int>(values.size())) {
  IMPACTFE_CHECK(n_matrices_ >= 1 && n_matrices_ <= kMaxMatrices,
                 "SharedPatternProducts: 1 to 3 matrices expected");
  IMPACTFE_CHECK(!row_start.empty() && kept.size() == column.size(),
                 "SharedPatternProducts: inconsistent pattern");
  const std::size_t n = row_start.size() - 1;
  row_start_.assign(n + 1, 0);
  column_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    for (auto k = static_cast<std::size_t>(row_start[i]);
         k < static_cast<std::size_t>(row_start[i + 1]); ++k)
      if (kept[k]) column_.push_back(column[k]);
    row_start_[i + 1] = static_cast<int>(column_.size());
  }
  for (int m = 0; m < n_matrices_; ++m) {
    const auto sm = static_cast<std::size_t>(m);
    const std::vector<double>* from = values[sm];
    nonzero_[sm] = from != nullptr;
    if (from == nullptr) continue;
    IMPACTFE_CHECK(from->size() == column.size(), "SharedPatternProducts: values of another size");
    std::vector<double>& to = value_[sm];
    to.reserve(column_.size());
    for (std::size_t k = 0; k < column.size(); ++k)
      if (kept[k]) to.push_back((*from)[k]);
  }
}

namespace {

/// y_m(i) = Σ_k A_m(i, col k) x_m(col k) for N matrices with values a[m].
template <int N>
void multiply_rows(int rows, const int* row_start, const int* column, const double* const* a,
                   const double* const* x, double* const* y) {
  for (int i = 0; i < rows; ++i) {
    double sum[N] = {};
    for (int k = row_start[i]; k < row_start[i + 1]; ++k) {
      const int j = column[k];
      for (int m = 0; m < N; ++m) sum[m] += a[m][k] * x[m][j];
    }
    for (int m = 0; m < N; ++m) y[m][i] = sum[m];
  }
}

}  // namespace

void SharedPatternProducts::multiply(const std::array<const VectorXd*, kMaxMatrices>& x,
                                     const std::array<VectorXd*, kMaxMatrices>& y) const {
  const int n = rows();
  const double* as[kMaxMatrices];
  const double* xs[kMaxMatrices];
  double* ys[kMaxMatrices];
  int count = 0;
  for (int m = 0; m < n_matrices_; ++m) {
    const auto s = static_cast<std::size_t>(m);
    if (x[s] == nullptr || y[s] == nullptr) continue;
    IMPACTFE_CHECK(x[s]->size() == n, "SharedPatternProducts: vector of the wrong size");
    if (!nonzero_[s]) {
      y[s]->setZero(n);
      continue;
    }
    y[s]->resize(n);
    as[count] = value_[s].data();
    xs[count] = x[s]->data();
    ys[count] = y[s]->data();
    ++count;
  }
  const int* rs = row_start_.data();
  const int* col = column_.data();
  switch (count) {
    case 1:
      multiply_rows<1>(n, rs, col, as, xs, ys);
      break;
    case 2:
      multiply_rows<2>(n, rs, col, as, xs, ys);
      break;
    case 3:
      multiply_rows<3>(n, rs, col, as, xs, ys);
      break;
    default:
      break;
  }
}

}  // namespace impactfe
