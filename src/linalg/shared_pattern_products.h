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
  /// keeps the entries whose `kept` flag is set; `values[m]` empty for a zero matrix. The
  /// values are taken over and each freed once its kept entries are copied, so that the full
  /// arrays of all the matrices are never in memory beside the products (issue 11).
  SharedPatternProducts(const std::vector<int>& row_start, const std::vector<int>& column,
                        const std::vector<unsigned char>& kept,
                        std::vector<std::vector<double>> values);

  int rows() const { return n_rows_; }
  long long nonzeros() const { return nonzeros_; }
  /// Groups of consecutive rows with one column list (a node's DOFs): the pass reads each
  /// column index once per group.
  int row_groups() const { return static_cast<int>(groups_.size()); }
  /// True when every matrix is symmetric (to 1e-13 relative per entry): only the entries of
  /// each group's rows at its own and later columns are stored, the later ones applied to both
  /// rows and columns (half the memory traffic of a pass, which bounds it on large models).
  bool symmetric() const { return symmetric_; }

  /// y[m] = A_m x[m] for each m with both pointers non-null; y[m] is resized. A zero matrix
  /// gives a zero vector without a pass.
  void multiply(const std::array<const VectorXd*, kMaxMatrices>& x,
                const std::array<VectorXd*, kMaxMatrices>& y) const;

  /// Calls visit(row, column, values) once for each stored entry, row by row and, within a
  /// row, by ascending column; values[m] is matrix m's entry (0 for a zero matrix). Symmetric
  /// storage holds each row's entries from its group's first row on: all of the upper triangle
  /// and, inside a group's own block, the entries left of the diagonal too (the assembler forms
  /// the lower triangle of an effective matrix from the products with this).
  template <class Visit>
  void for_each_stored_entry(Visit&& visit) const {
    double values[kMaxMatrices] = {};
    for (const RowGroup& g : groups_)
      for (int r = 0; r < g.rows; ++r)
        for (int k = 0; k < g.columns; ++k) {
          const long long at = g.value_start + static_cast<long long>(k) * g.rows + r;
          for (int m = 0; m < n_matrices_; ++m)
            values[m] = nonzero_[static_cast<std::size_t>(m)]
                            ? value_[static_cast<std::size_t>(m)][static_cast<std::size_t>(at)]
                            : 0.0;
          visit(g.first_row + r, column_[static_cast<std::size_t>(g.column_start + k)],
                static_cast<const double*>(values));
        }
  }

  /// Symmetric products of at least this many values per matrix run in chunks on several
  /// threads (issue 11: a large transient's step is bandwidth-bound, and two cores stream
  /// twice the bytes of one).
  static constexpr long long kMinChunkedValues = 1LL << 20;
  static constexpr int kChunks = 8;
  /// Consecutive groups [first_group, end_group): their rows are summed on one thread; the
  /// transposed terms they add to later chunks' rows go to slots of their own,
  /// added to y in chunk order after the pass, so that the sums do not depend on the thread
  /// count. A plan of the structure alone (empty for small or unsymmetric products, or when
  /// the couplings reach so far that most rows would need a slot).
  struct Chunk {
    int first_group = 0, end_group = 0;
  };
  int chunks() const { return static_cast<int>(chunks_.size()); }

  /// Rows with one column list, stored together: the `rows` values of each column side by side,
  /// so that one index load serves them all and their sums vectorize (a brick mesh's node has
  /// 3 such rows, a shell's 6). Each row's sum runs over its columns in order: the products are
  /// those of a row-by-row pass, bitwise.
  struct RowGroup {
    int first_row = 0;
    int rows = 0;
    int column_start = 0;  // into column_
    int columns = 0;
    int own_columns = 0;        // symmetric storage: the leading columns inside the group's rows
    long long value_start = 0;  // into value_[m]: columns × rows, column-major by group
    // Chunked symmetric products: the columns from first_boundary on are rows of later chunks,
    // whose transposed terms go to the slots slot_[slot_start ...] (columns ascend).
    int first_boundary = 0;
    int slot_start = 0;
  };

 private:
  /// Groups the rows of a row-compressed pattern and lays the values out by group.
  void build(const std::vector<int>& row_start, const std::vector<int>& column,
             const std::vector<std::vector<double>>& values);
  void plan_chunks();
  void plan_unchunked();
  void multiply_symmetric(int count, const double* const* a, const double* const* x,
                          double* const* y) const;

  int n_matrices_ = 0;
  int n_rows_ = 0;
  bool symmetric_ = false;
  long long nonzeros_ = 0;
  std::array<bool, kMaxMatrices> nonzero_{};
  std::vector<RowGroup> groups_;
  std::vector<int> column_;
  std::array<std::vector<double>, kMaxMatrices> value_;
  std::vector<Chunk> chunks_;
  std::vector<int> slot_;      // per boundary column (RowGroup::first_boundary): its slot
  std::vector<int> slot_row_;  // per slot: its row (the slots of chunk 0, then 1, ...)
};

}  // namespace impactfe
