#pragma once
/// Several sparse matrices on one row-compressed pattern (the union of theirs), each multiplied
/// with its own vector in a single pass over the pattern: y_m = A_m x_m.
///
/// The linear part of a transient residual needs K u, C v and M a at every evaluation, over the
/// same element connectivity. Three separate column-compressed products read the indices three
/// times and scatter into y; one row-wise pass reads them once and accumulates in registers
/// (issue 11: a step costs a solve plus O(nnz) vector work, and this is that work).
#include <array>
#include <vector>

#include "linalg/sparse.h"

namespace impactfe {

class SharedPatternProducts {
 public:
  static constexpr int kMaxMatrices = 3;

  SharedPatternProducts() = default;
  /// Square matrices of one size (an empty matrix, 0 × 0 or without nonzeros, is a zero).
  explicit SharedPatternProducts(const std::vector<const SparseMatrix*>& matrices);
  /// From entry values on one row-compressed pattern (`row_start`, `column`, columns ascending):
  /// keeps the entries whose `kept` flag is set; `values[m]` null for a zero matrix.
  SharedPatternProducts(const std::vector<int>& row_start, const std::vector<int>& column,
                        const std::vector<unsigned char>& kept,
                        const std::vector<const std::vector<double>*>& values);

  int rows() const { return static_cast<int>(row_start_.size()) - 1; }
  long long nonzeros() const { return static_cast<long long>(column_.size()); }

  /// y[m] = A_m x[m] for each m with both pointers non-null; y[m] is resized. A zero matrix
  /// gives a zero vector without a pass.
  void multiply(const std::array<const VectorXd*, kMaxMatrices>& x,
                const std::array<VectorXd*, kMaxMatrices>& y) const;

 private:
  int n_matrices_ = 0;
  std::array<bool, kMaxMatrices> nonzero_{};
  std::vector<int> row_start_{0};
  std::vector<int> column_;
  std::array<std::vector<double>, kMaxMatrices> value_;  // value_[m][k]: entry k of matrix m
};

}  // namespace impactfe
