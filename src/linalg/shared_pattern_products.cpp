#include "linalg/shared_pattern_products.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <type_traits>

#include "core/errors.h"
#include "core/thread_pool.h"
#include "linalg/simd_pair.h"

namespace impactfe {

namespace {

/// Rows per group at most (a shell node's 6 DOFs, with room for a little more).
constexpr int kMaxGroupRows = 8;

}  // namespace

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
  const std::vector<int> row_start(pattern.outerIndexPtr(), pattern.outerIndexPtr() + n + 1);
  const std::vector<int> column(pattern.innerIndexPtr(),
                                pattern.innerIndexPtr() + pattern.nonZeros());
  std::vector<std::vector<double>> values(static_cast<std::size_t>(n_matrices_));
  for (int m = 0; m < n_matrices_; ++m) {
    const SparseMatrix& a = *matrices[static_cast<std::size_t>(m)];
    std::vector<double>& value = values[static_cast<std::size_t>(m)];
    if (a.nonZeros() > 0) value.assign(column.size(), 0.0);
    for (int j = 0; j < a.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(a, j); it; ++it) {
        const int row = static_cast<int>(it.row());
        const int* begin = column.data() + row_start[static_cast<std::size_t>(row)];
        const int* end = column.data() + row_start[static_cast<std::size_t>(row) + 1];
        const auto k =
            static_cast<std::size_t>(std::lower_bound(begin, end, it.col()) - column.data());
        value[k] += it.value();
      }
  }
  build(row_start, column, values);
}

SharedPatternProducts::SharedPatternProducts(const std::vector<int>& row_start,
                                             const std::vector<int>& column,
                                             const std::vector<unsigned char>& kept,
                                             std::vector<std::vector<double>> values)
    : n_matrices_(static_cast<int>(values.size())) {
  IMPACTFE_CHECK(n_matrices_ >= 1 && n_matrices_ <= kMaxMatrices,
                 "SharedPatternProducts: 1 to 3 matrices expected");
  IMPACTFE_CHECK(!row_start.empty() && kept.size() == column.size(),
                 "SharedPatternProducts: inconsistent pattern");
  const std::size_t n = row_start.size() - 1;
  std::vector<int> kept_start(n + 1, 0), kept_column;
  for (std::size_t i = 0; i < n; ++i) {
    for (auto k = static_cast<std::size_t>(row_start[i]);
         k < static_cast<std::size_t>(row_start[i + 1]); ++k)
      if (kept[k]) kept_column.push_back(column[k]);
    kept_start[i + 1] = static_cast<int>(kept_column.size());
  }
  std::vector<std::vector<double>> kept_values(static_cast<std::size_t>(n_matrices_));
  for (int m = 0; m < n_matrices_; ++m) {
    const auto sm = static_cast<std::size_t>(m);
    std::vector<double>& from = values[sm];
    nonzero_[sm] = !from.empty();
    if (from.empty()) continue;
    IMPACTFE_CHECK(from.size() == column.size(), "SharedPatternProducts: values of another size");
    std::vector<double>& to = kept_values[sm];
    to.reserve(kept_column.size());
    for (std::size_t k = 0; k < column.size(); ++k)
      if (kept[k]) to.push_back(from[k]);
    std::vector<double>().swap(from);
  }
  build(kept_start, kept_column, kept_values);
}

void SharedPatternProducts::build(const std::vector<int>& row_start, const std::vector<int>& column,
                                  const std::vector<std::vector<double>>& values) {
  n_rows_ = static_cast<int>(row_start.size()) - 1;
  nonzeros_ = static_cast<long long>(column.size());
  // Symmetry of every matrix to round-off: the pattern of a DOF graph is symmetric, and the
  // element matrices are up to the order of their products ((s n_i) n_j against (s n_j) n_i
  // of a consistent mass). The upper triangle's values then stand for both.
  symmetric_ = true;
  for (int i = 0; i < n_rows_ && symmetric_; ++i)
    for (int k = row_start[static_cast<std::size_t>(i)];
         k < row_start[static_cast<std::size_t>(i) + 1] && symmetric_; ++k) {
      const int j = column[static_cast<std::size_t>(k)];
      if (j <= i) continue;
      const int* begin = column.data() + row_start[static_cast<std::size_t>(j)];
      const int* end = column.data() + row_start[static_cast<std::size_t>(j) + 1];
      const int* at = std::lower_bound(begin, end, i);
      if (at == end || *at != i) {
        symmetric_ = false;
        break;
      }
      const auto kt = static_cast<std::size_t>(at - column.data());
      for (const auto& v : values)
        if (!v.empty() && std::abs(v[static_cast<std::size_t>(k)] - v[kt]) >
                              1e-13 * (std::abs(v[static_cast<std::size_t>(k)]) + std::abs(v[kt])))
          symmetric_ = false;
    }
  const auto columns_of = [&](int i) {
    return std::make_pair(column.begin() + row_start[static_cast<std::size_t>(i)],
                          column.begin() + row_start[static_cast<std::size_t>(i) + 1]);
  };
  groups_.clear();
  column_.clear();
  for (int m = 0; m < kMaxMatrices; ++m) value_[static_cast<std::size_t>(m)].clear();
  long long value_start = 0;
  for (int i = 0; i < n_rows_;) {
    const auto [begin, end] = columns_of(i);
    int rows = 1;
    while (rows < kMaxGroupRows && i + rows < n_rows_) {
      const auto [b, e] = columns_of(i + rows);
      if (!std::equal(begin, end, b, e)) break;
      ++rows;
    }
    // Symmetric storage: from the group's first row on (its own block in full).
    const auto first = symmetric_ ? std::lower_bound(begin, end, i) : begin;
    RowGroup g;
    g.first_row = i;
    g.rows = rows;
    g.column_start = static_cast<int>(column_.size());
    g.columns = static_cast<int>(end - first);
    g.own_columns =
        symmetric_ ? static_cast<int>(std::lower_bound(first, end, i + rows) - first) : g.columns;
    g.value_start = value_start;
    column_.insert(column_.end(), first, end);
    value_start += static_cast<long long>(g.columns) * rows;
    groups_.push_back(g);
    i += rows;
  }
  // The values in a second pass, into arrays of their exact size: grown entry by entry they
  // would hold up to twice their size (issue 11: 139 MB at the height of their growth for the
  // 78 MB of K and M on the shell dome).
  column_.shrink_to_fit();
  groups_.shrink_to_fit();
  for (int m = 0; m < n_matrices_; ++m) {
    const std::vector<double>& from = values[static_cast<std::size_t>(m)];
    if (from.empty()) continue;
    std::vector<double>& to = value_[static_cast<std::size_t>(m)];
    to.reserve(static_cast<std::size_t>(value_start));
    for (const RowGroup& g : groups_) {
      // The group's stored columns start `skipped` entries into each of its rows.
      const int first_row_start = row_start[static_cast<std::size_t>(g.first_row)];
      const int skipped =
          row_start[static_cast<std::size_t>(g.first_row) + 1] - first_row_start - g.columns;
      for (int k = 0; k < g.columns; ++k)
        for (int r = 0; r < g.rows; ++r)
          to.push_back(from[static_cast<std::size_t>(
              row_start[static_cast<std::size_t>(g.first_row + r)] + skipped + k)]);
    }
  }
  plan_chunks();
}

namespace {

using RowGroup = SharedPatternProducts::RowGroup;

/// y_m(i) = Σ_k A_m(i, col k) x_m(col k) for the G rows of a group and N matrices; each row's
/// terms are summed in column order.
template <int N, int G>
void multiply_group(const RowGroup& g, const int* column, const double* const* a,
                    const double* const* x, double* const* y) {
  double sum[N][G] = {};
  const int* col = column + g.column_start;
  for (int k = 0; k < g.columns; ++k) {
    const int j = col[k];
    for (int m = 0; m < N; ++m) {
      const double xj = x[m][j];
      const double* v = a[m] + g.value_start + static_cast<long long>(k) * G;
      for (int r = 0; r < G; ++r) sum[m][r] += v[r] * xj;
    }
  }
  for (int m = 0; m < N; ++m)
    for (int r = 0; r < G; ++r) y[m][g.first_row + r] = sum[m][r];
}

template <int N>
void multiply_any(const RowGroup& g, const int* column, const double* const* a,
                  const double* const* x, double* const* y) {
  double sum[N][kMaxGroupRows] = {};
  const int* col = column + g.column_start;
  for (int k = 0; k < g.columns; ++k) {
    const int j = col[k];
    for (int m = 0; m < N; ++m) {
      const double xj = x[m][j];
      const double* v = a[m] + g.value_start + static_cast<long long>(k) * g.rows;
      for (int r = 0; r < g.rows; ++r) sum[m][r] += v[r] * xj;
    }
  }
  for (int m = 0; m < N; ++m)
    for (int r = 0; r < g.rows; ++r) y[m][g.first_row + r] = sum[m][r];
}

/// Where the transposed term of a group's column k goes: y[column] for a row of the caller's
/// chunk, or a slot of `boundary` (a row of a later chunk, SharedPatternProducts::Chunk).
struct Scatter {
  const int* slot;
  double* const* boundary;
  double& at(double* const* y, int m, const RowGroup& g, int k, int j) const {
    return k < g.first_boundary ? y[m][j] : boundary[m][slot[g.slot_start + k - g.first_boundary]];
  }
};

/// Symmetric storage: the group's own columns as above, then each later column j applied to
/// the group's rows (y_i += a_ij x_j) and to row j (y_j += Σ_i a_ij x_i). y starts at zero;
/// the scattered terms of earlier groups are in y_i when the group adds its own sums.
template <int N>
void multiply_any_symmetric(const RowGroup& g, const int* column, const double* const* a,
                            const double* const* x, double* const* y, const Scatter& scatter) {
  const int n = g.rows;
  double sum[N][kMaxGroupRows] = {};
  double xi[N][kMaxGroupRows];
  for (int m = 0; m < N; ++m)
    for (int r = 0; r < n; ++r) xi[m][r] = x[m][g.first_row + r];
  const int* col = column + g.column_start;
  for (int k = 0; k < g.columns; ++k) {
    const int j = col[k];
    for (int m = 0; m < N; ++m) {
      const double xj = x[m][j];
      const double* v = a[m] + g.value_start + static_cast<long long>(k) * n;
      for (int r = 0; r < n; ++r) sum[m][r] += v[r] * xj;
      if (k < g.own_columns) continue;
      double t = 0.0;
      for (int r = 0; r < n; ++r) t += v[r] * xi[m][r];
      scatter.at(y, m, g, k, j) += t;
    }
  }
  for (int m = 0; m < N; ++m)
    for (int r = 0; r < n; ++r) y[m][g.first_row + r] += sum[m][r];
}

/// GCC leaves the transposed product's reduction over a group's rows scalar; with the rows as
/// pairs it is three multiplies and a horizontal add for a node's six DOFs (the 155 522-DOF
/// shell dome: ~12 ms of scalar code per step).
using simd::load_pair;
using simd::Pair;

/// multiply_any_symmetric for a fixed group of G rows: G / 2 row pairs and a remainder row.
template <int N, int G>
void multiply_group_symmetric(const RowGroup& g, const int* column, const double* const* a,
                              const double* const* x, double* const* y, const Scatter& scatter) {
  constexpr int P = G / 2;
  constexpr bool odd = G % 2 != 0;
  constexpr int kPairs = P > 0 ? P : 1;  // no zero-length arrays for a group of one row
  Pair sum[N][kPairs] = {}, xi[N][kPairs];
  double sum_last[N] = {}, xi_last[N] = {};
  for (int m = 0; m < N; ++m) {
    for (int p = 0; p < P; ++p) xi[m][p] = load_pair(x[m] + g.first_row + 2 * p);
    if constexpr (odd) xi_last[m] = x[m][g.first_row + G - 1];
  }
  const int* col = column + g.column_start;
  const auto add_column = [&](int k, auto transposed) {
    const int j = col[k];
    for (int m = 0; m < N; ++m) {
      const double xj = x[m][j];
      const double* v = a[m] + g.value_start + static_cast<long long>(k) * G;
      Pair t = {};
      for (int p = 0; p < P; ++p) {
        const Pair vp = load_pair(v + 2 * p);
        sum[m][p] += vp * xj;
        if constexpr (decltype(transposed)::value) t += vp * xi[m][p];
      }
      if constexpr (odd) sum_last[m] += v[G - 1] * xj;
      if constexpr (decltype(transposed)::value) {
        double tj = t[0] + t[1];
        if constexpr (odd) tj += v[G - 1] * xi_last[m];
        scatter.at(y, m, g, k, j) += tj;
      }
    }
  };
  for (int k = 0; k < g.own_columns; ++k) add_column(k, std::false_type{});
  for (int k = g.own_columns; k < g.columns; ++k) add_column(k, std::true_type{});
  for (int m = 0; m < N; ++m) {
    for (int p = 0; p < P; ++p) {
      y[m][g.first_row + 2 * p] += sum[m][p][0];
      y[m][g.first_row + 2 * p + 1] += sum[m][p][1];
    }
    if constexpr (odd) y[m][g.first_row + G - 1] += sum_last[m];
  }
}

/// The groups [first, end) with symmetric storage; y starts at zero on their rows.
template <int N>
void multiply_groups_symmetric(const RowGroup* groups, int first, int end, const int* column,
                               const double* const* a, const double* const* x, double* const* y,
                               const Scatter& scatter) {
  for (int i = first; i < end; ++i) {
    const RowGroup& g = groups[i];
    switch (g.rows) {
      case 1:
        multiply_group_symmetric<N, 1>(g, column, a, x, y, scatter);
        break;
      case 2:
        multiply_group_symmetric<N, 2>(g, column, a, x, y, scatter);
        break;
      case 3:
        multiply_group_symmetric<N, 3>(g, column, a, x, y, scatter);
        break;
      case 6:
        multiply_group_symmetric<N, 6>(g, column, a, x, y, scatter);
        break;
      default:
        multiply_any_symmetric<N>(g, column, a, x, y, scatter);
        break;
    }
  }
}

template <int N>
void multiply_groups(const std::vector<RowGroup>& groups, const int* column, const double* const* a,
                     const double* const* x, double* const* y) {
  for (const RowGroup& g : groups) {
    switch (g.rows) {
      case 1:
        multiply_group<N, 1>(g, column, a, x, y);
        break;
      case 2:
        multiply_group<N, 2>(g, column, a, x, y);
        break;
      case 3:
        multiply_group<N, 3>(g, column, a, x, y);
        break;
      case 6:
        multiply_group<N, 6>(g, column, a, x, y);
        break;
      default:
        multiply_any<N>(g, column, a, x, y);
        break;
    }
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
  const int* col = column_.data();
  if (symmetric_) {
    multiply_symmetric(count, as, xs, ys);
    return;
  }
  switch (count) {
    case 1:
      multiply_groups<1>(groups_, col, as, xs, ys);
      break;
    case 2:
      multiply_groups<2>(groups_, col, as, xs, ys);
      break;
    case 3:
      multiply_groups<3>(groups_, col, as, xs, ys);
      break;
    default:
      break;
  }
}

void SharedPatternProducts::multiply_symmetric(int count, const double* const* as,
                                               const double* const* xs, double* const* ys) const {
  const auto run = [&](int first, int end, const Scatter& scatter) {
    switch (count) {
      case 1:
        multiply_groups_symmetric<1>(groups_.data(), first, end, column_.data(), as, xs, ys,
                                     scatter);
        break;
      case 2:
        multiply_groups_symmetric<2>(groups_.data(), first, end, column_.data(), as, xs, ys,
                                     scatter);
        break;
      case 3:
        multiply_groups_symmetric<3>(groups_.data(), first, end, column_.data(), as, xs, ys,
                                     scatter);
        break;
      default:
        break;
    }
  };
  const int n = rows();
  if (chunks_.empty()) {
    for (int m = 0; m < count; ++m) std::fill(ys[m], ys[m] + n, 0.0);
    run(0, static_cast<int>(groups_.size()), Scatter{nullptr, nullptr});
    return;
  }
  // Each chunk's rows on one thread; its transposed terms for later chunks' rows into slots of
  // its own, added in chunk order after all chunks (the same sums on any thread count).
  const std::size_t n_slots = slot_row_.size();
  std::vector<double> boundary(static_cast<std::size_t>(count) * n_slots);
  double* slots[kMaxMatrices];
  for (int m = 0; m < count; ++m)
    slots[m] = boundary.data() + static_cast<std::size_t>(m) * n_slots;
  const Scatter scatter{slot_.data(), slots};
  threads::parallel_for(static_cast<int>(chunks_.size()), 1, [&](int c) {
    const Chunk& chunk = chunks_[static_cast<std::size_t>(c)];
    const RowGroup& first = groups_[static_cast<std::size_t>(chunk.first_group)];
    const int end_row = chunk.end_group < static_cast<int>(groups_.size())
                            ? groups_[static_cast<std::size_t>(chunk.end_group)].first_row
                            : n;
    for (int m = 0; m < count; ++m) std::fill(ys[m] + first.first_row, ys[m] + end_row, 0.0);
    run(chunk.first_group, chunk.end_group, scatter);
  });
  for (int m = 0; m < count; ++m)
    for (std::size_t k = 0; k < n_slots; ++k) ys[m][slot_row_[k]] += slots[m][k];
}

void SharedPatternProducts::plan_chunks() {
  plan_unchunked();
  const long long values =
      groups_.empty() ? 0
                      : groups_.back().value_start +
                            static_cast<long long>(groups_.back().columns) * groups_.back().rows;
  if (!symmetric_ || values < kMinChunkedValues) return;
  // Chunks of consecutive groups with about the same number of values.
  const long long per_chunk = (values + kChunks - 1) / kChunks;
  const int n_groups = static_cast<int>(groups_.size());
  for (int first = 0; first < n_groups;) {
    const long long start = groups_[static_cast<std::size_t>(first)].value_start;
    int end = first + 1;
    while (end < n_groups && groups_[static_cast<std::size_t>(end)].value_start - start < per_chunk)
      ++end;
    chunks_.push_back(Chunk{first, end});
    first = end;
  }
  // A slot per distinct later row of each chunk, for the transposed terms of its groups'
  // trailing columns (a group's columns ascend, so those are a suffix of them).
  std::vector<int> slot_of(static_cast<std::size_t>(n_rows_), -1);
  for (const Chunk& chunk : chunks_) {
    const int end_row = chunk.end_group < n_groups
                            ? groups_[static_cast<std::size_t>(chunk.end_group)].first_row
                            : n_rows_;
    const std::size_t chunk_slots = slot_row_.size();
    for (int i = chunk.first_group; i < chunk.end_group; ++i) {
      RowGroup& g = groups_[static_cast<std::size_t>(i)];
      const int* col = column_.data() + g.column_start;
      g.first_boundary = static_cast<int>(
          std::max(std::lower_bound(col, col + g.columns, end_row), col + g.own_columns) - col);
      g.slot_start = static_cast<int>(slot_.size());
      for (int k = g.first_boundary; k < g.columns; ++k) {
        int& slot = slot_of[static_cast<std::size_t>(col[k])];
        if (slot < 0) {
          slot = static_cast<int>(slot_row_.size());
          slot_row_.push_back(col[k]);
        }
        slot_.push_back(slot);
      }
    }
    for (std::size_t k = chunk_slots; k < slot_row_.size(); ++k)
      slot_of[static_cast<std::size_t>(slot_row_[k])] = -1;
    // A numbering whose couplings reach far (no locality) would need slots for most rows of
    // every chunk: one pass on one thread then.
    if (slot_row_.size() > static_cast<std::size_t>(n_rows_) / 2) {
      plan_unchunked();
      return;
    }
  }
  slot_.shrink_to_fit();
  slot_row_.shrink_to_fit();
}

void SharedPatternProducts::plan_unchunked() {
  chunks_.clear();
  std::vector<int>().swap(slot_);
  std::vector<int>().swap(slot_row_);
  for (RowGroup& g : groups_) {
    g.first_boundary = g.columns;
    g.slot_start = 0;
  }
}

}  // namespace impactfe
