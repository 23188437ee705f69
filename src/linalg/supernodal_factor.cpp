#include "linalg/supernodal_factor.h"

#include <Eigen/Dense>

#include <algorithm>
#include <climits>
#include <cmath>

#include "linalg/solver_support.h"
#include "linalg/supernodal_substitution.h"

namespace impactfe {

namespace {

using Block = Eigen::Map<MatrixXd, 0, Eigen::OuterStride<>>;
using ConstBlock = Eigen::Map<const MatrixXd, 0, Eigen::OuterStride<>>;

/// Resolves (row, column) positions of the factor to offsets in its value array, grouped by the
/// supernode that stores them: `local[r]` is the position of row r in the supernode last
/// loaded, so each supernode's row list is read once per group of lookups.
class SlotFinder {
 public:
  SlotFinder(int n, const std::vector<int>& super, const std::vector<int>& row_start,
             const std::vector<int>& value_start, const std::vector<int>& rows)
      : super_(super),
        row_start_(row_start),
        value_start_(value_start),
        rows_(rows),
        local_(static_cast<std::size_t>(n), -1),
        column_super_(static_cast<std::size_t>(n)) {
    for (std::size_t s = 0; s + 1 < super.size(); ++s)
      for (int j = super[s]; j < super[s + 1]; ++j) column_super_[static_cast<std::size_t>(j)] = s;
  }
  std::size_t super_of(int column) const { return column_super_[static_cast<std::size_t>(column)]; }
  /// Offset of L(row, column), row >= column, both permuted; -1 when not in the pattern.
  int slot(int row, int column) {
    const std::size_t s = super_of(column);
    if (s != loaded_) load(s);
    const int i = local_[static_cast<std::size_t>(row)];
    if (i < 0) return -1;
    const int n_rows = row_start_[s + 1] - row_start_[s];
    return value_start_[s] + (column - super_[s]) * n_rows + i;
  }

 private:
  void load(std::size_t s) {
    if (loaded_ != kNone)
      for (int k = row_start_[loaded_]; k < row_start_[loaded_ + 1]; ++k)
        local_[static_cast<std::size_t>(rows_[static_cast<std::size_t>(k)])] = -1;
    for (int k = row_start_[s]; k < row_start_[s + 1]; ++k)
      local_[static_cast<std::size_t>(rows_[static_cast<std::size_t>(k)])] = k - row_start_[s];
    loaded_ = s;
  }
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  const std::vector<int>& super_;
  const std::vector<int>& row_start_;
  const std::vector<int>& value_start_;
  const std::vector<int>& rows_;
  std::vector<int> local_;
  std::vector<std::size_t> column_super_;
  std::size_t loaded_ = kNone;
};

}  // namespace

bool SupernodalFactor::analyze(const SparseMatrix& lower, cholmod_common& common) {
  valid_ = false;
  cholmod_sparse A = solver_support::cholmod_lower_view(lower);
  A.xtype = CHOLMOD_PATTERN;
  const int saved = common.supernodal;
  common.supernodal = CHOLMOD_SUPERNODAL;
  cholmod_factor* F = cholmod_analyze(&A, &common);
  common.supernodal = saved;
  if (!F) return false;
  const bool fits = F->is_super && F->xsize < static_cast<std::size_t>(INT_MAX / 2) &&
                    F->ssize < static_cast<std::size_t>(INT_MAX / 2);
  if (fits) {
    n_ = static_cast<int>(F->n);
    n_super_ = static_cast<int>(F->nsuper);
    const auto* perm = static_cast<const int*>(F->Perm);
    const auto* super = static_cast<const int*>(F->super);
    const auto* pi = static_cast<const int*>(F->pi);
    const auto* px = static_cast<const int*>(F->px);
    const auto* s = static_cast<const int*>(F->s);
    perm_.assign(perm, perm + n_);
    super_.assign(super, super + n_super_ + 1);
    row_start_.assign(pi, pi + n_super_ + 1);
    value_start_.assign(px, px + n_super_ + 1);
    rows_.assign(s, s + row_start_.back());
  }
  cholmod_free_factor(&F, &common);
  if (!fits) return false;
  x_.assign(static_cast<std::size_t>(value_start_.back()), 0.0);

  std::vector<int> inverse(static_cast<std::size_t>(n_));
  for (int k = 0; k < n_; ++k)
    inverse[static_cast<std::size_t>(perm_[static_cast<std::size_t>(k)])] = k;
  SlotFinder finder(n_, super_, row_start_, value_start_, rows_);
  // Where each value of A goes: grouped by target supernode (columns of the permuted matrix
  // in order), so that each supernode's rows are loaded once.
  const int nnz = static_cast<int>(lower.nonZeros());
  std::vector<int> entry_row(static_cast<std::size_t>(nnz)), entry_column(entry_row.size());
  for (int j = 0; j < lower.outerSize(); ++j)
    for (int k = lower.outerIndexPtr()[j]; k < lower.outerIndexPtr()[j + 1]; ++k) {
      int p = inverse[static_cast<std::size_t>(lower.innerIndexPtr()[k])];
      int q = inverse[static_cast<std::size_t>(j)];
      if (p < q) std::swap(p, q);
      entry_row[static_cast<std::size_t>(k)] = p;
      entry_column[static_cast<std::size_t>(k)] = q;
    }
  std::vector<int> order(static_cast<std::size_t>(nnz));
  for (int k = 0; k < nnz; ++k) order[static_cast<std::size_t>(k)] = k;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return entry_column[static_cast<std::size_t>(a)] < entry_column[static_cast<std::size_t>(b)];
  });
  a_slot_.assign(static_cast<std::size_t>(nnz), -1);
  for (int k : order) {
    const int slot = finder.slot(entry_row[static_cast<std::size_t>(k)],
                                 entry_column[static_cast<std::size_t>(k)]);
    if (slot < 0) return false;  // not in CHOLMOD's pattern: cannot happen for its own analysis
    a_slot_[static_cast<std::size_t>(k)] = slot;
  }
  // The rank update of supernode s touches L(r, c) for every pair r >= c of its rows below its
  // columns; c's supernode stores it. Column by column of the update, so a target is loaded
  // once per run of columns it holds.
  update_start_.assign(static_cast<std::size_t>(n_super_ + 1), 0);
  update_slot_.clear();
  std::size_t largest = 0;
  for (int s = 0; s < n_super_; ++s) {
    update_start_[static_cast<std::size_t>(s)] = static_cast<int>(update_slot_.size());
    const int n_cols =
        super_[static_cast<std::size_t>(s) + 1] - super_[static_cast<std::size_t>(s)];
    const int first = row_start_[static_cast<std::size_t>(s)] + n_cols;
    const int last = row_start_[static_cast<std::size_t>(s) + 1];
    largest = std::max(largest, static_cast<std::size_t>(last - first));
    for (int jj = first; jj < last; ++jj)
      for (int ii = jj; ii < last; ++ii) {
        const int slot =
            finder.slot(rows_[static_cast<std::size_t>(ii)], rows_[static_cast<std::size_t>(jj)]);
        if (slot < 0) return false;
        update_slot_.push_back(slot);
      }
    if (update_slot_.size() > static_cast<std::size_t>(INT_MAX / 2)) return false;
  }
  update_start_[static_cast<std::size_t>(n_super_)] = static_cast<int>(update_slot_.size());
  work_.assign(std::max(largest * largest, static_cast<std::size_t>(1)), 0.0);
  return true;
}

bool SupernodalFactor::factorize(const SparseMatrix& lower) {
  valid_ = false;
  std::fill(x_.begin(), x_.end(), 0.0);
  const double* a = lower.valuePtr();
  for (std::size_t k = 0; k < a_slot_.size(); ++k) x_[static_cast<std::size_t>(a_slot_[k])] += a[k];
  for (int s = 0; s < n_super_; ++s) {
    const std::size_t si = static_cast<std::size_t>(s);
    const int n_cols = super_[si + 1] - super_[si];
    const int n_rows = row_start_[si + 1] - row_start_[si];
    const int n_below = n_rows - n_cols;
    Block block(x_.data() + value_start_[si], n_rows, n_cols, Eigen::OuterStride<>(n_rows));
    // The diagonal block (its descendants' updates already in): dense Cholesky in place.
    auto diagonal = block.topRows(n_cols);
    Eigen::LLT<Eigen::Ref<MatrixXd, 0, Eigen::OuterStride<>>> llt(diagonal);
    if (llt.info() != Eigen::Success) return false;  // not positive definite
    // A NaN anywhere reaches a pivot (through L(i, j)² in the update of A(i, i)); Eigen's LLT
    // lets NaN pivots pass, CHOLMOD does not.
    for (int j = 0; j < n_cols; ++j)
      if (!(diagonal(j, j) > 0.0) || !std::isfinite(diagonal(j, j))) return false;
    if (n_below == 0) continue;
    // The rows below, L_21 = A_21 L_11⁻ᵀ; the ancestors get −L_21 L_21ᵀ (its lower triangle,
    // column by column into the slots of the supernodes that store it).
    auto below = block.bottomRows(n_below);
    diagonal.triangularView<Eigen::Lower>().transpose().solveInPlace<Eigen::OnTheRight>(below);
    Block update(work_.data(), n_below, n_below, Eigen::OuterStride<>(n_below));
    update.setZero();
    update.selfadjointView<Eigen::Lower>().rankUpdate(below);
    const int* slot = update_slot_.data() + update_start_[si];
    for (int j = 0; j < n_below; ++j)
      for (int i = j; i < n_below; ++i) x_[static_cast<std::size_t>(*slot++)] -= update(i, j);
  }
  valid_ = true;
  return true;
}

VectorXd SupernodalFactor::solve(const VectorXd& b) const {
  VectorXd y(n_);
  for (int k = 0; k < n_; ++k) y(k) = b(perm_[static_cast<std::size_t>(k)]);
  SupernodalLayout layout;
  layout.n_super = n_super_;
  layout.super = super_.data();
  layout.row_start = row_start_.data();
  layout.value_start = value_start_.data();
  layout.rows = rows_.data();
  layout.values = x_.data();
  forward_substitution(layout, y.data(), work_);  // L y = P b
  back_substitution(layout, y.data(), work_);     // Lᵀ (P x) = y
  VectorXd x(n_);
  for (int k = 0; k < n_; ++k) x(perm_[static_cast<std::size_t>(k)]) = y(k);
  return x;
}

MatrixXd SupernodalFactor::solve(const MatrixXd& B) const {
  MatrixXd X(B.rows(), B.cols());
  for (Eigen::Index j = 0; j < B.cols(); ++j) X.col(j) = solve(VectorXd(B.col(j)));
  return X;
}

double SupernodalFactor::rcond() const {
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
  for (int s = 0; s < n_super_; ++s) {
    const std::size_t si = static_cast<std::size_t>(s);
    const int n_cols = super_[si + 1] - super_[si];
    const int n_rows = row_start_[si + 1] - row_start_[si];
    for (int j = 0; j < n_cols; ++j) {
      const double d = std::abs(x_[static_cast<std::size_t>(value_start_[si] + j * n_rows + j)]);
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
  }
  return hi > 0.0 ? (lo / hi) * (lo / hi) : 0.0;
}

long SupernodalFactor::stored_bytes() const {
  return static_cast<long>(x_.size() * sizeof(double) + rows_.size() * sizeof(int));
}

}  // namespace impactfe
