#pragma once
/// The DOF adjacency of an element mesh: DOFs i and j are adjacent when one element carries
/// both, so every matrix assembled from element matrices has its entries there. Built once,
/// directly from the element index lists (symbolic assembly: George & Liu, Computer Solution of
/// Large Sparse Positive Definite Systems, §5), instead of sorting one triplet per element
/// entry: at 6·10⁵ DOFs the triplets alone were 10⁸ entries (1.6 GB) and their sort most of a
/// run's set-up (issue 11).
#include <cstddef>
#include <vector>

#include "assembly/dof_map.h"
#include "linalg/sparse.h"

namespace impactfe {

class DofGraph {
 public:
  /// Over all active DOFs of `dofs`, for its first `n_elements` elements; every diagonal is
  /// present. Rows are compressed with their columns ascending; the graph is symmetric, so a
  /// row is also the column of the same index.
  DofGraph(const DofMap& dofs, std::size_t n_elements);

  int size() const { return static_cast<int>(row_start_.size()) - 1; }
  long long n_entries() const { return static_cast<long long>(column_.size()); }
  const std::vector<int>& row_start() const { return row_start_; }
  const std::vector<int>& column() const { return column_; }

  /// slots[a * n + b] = the entry of (idx[a], idx[b]) for an element with DOF indices idx.
  void element_slots(const std::vector<int>& idx, std::vector<int>& slots) const;

  /// The lower triangle of the first `n` DOFs (the free ones), column-compressed.
  SparsePattern lower_pattern(int n) const;

 private:
  std::vector<int> row_start_;
  std::vector<int> column_;
};

/// One matrix assembled on a DofGraph: the entry values and which entries received a nonzero
/// element contribution. Those, and only those, are the entries a triplet assembly that skips
/// exact zeros creates (an entry whose contributions cancel stays, as it does there), so the
/// sparse matrices built from it have the same structure — and, summed in element order, the
/// same values bit for bit — as before the graph existed.
///
/// The storage (9 bytes per graph entry) is allocated at the first nonzero contribution: a
/// matrix nothing contributes to (the damping of an undamped model) costs nothing — 78 MB on
/// the 155 522-DOF shell dome (issue 11).
struct GraphMatrix {
  explicit GraphMatrix(const DofGraph& graph)
      : n_entries(static_cast<std::size_t>(graph.n_entries())) {}
  std::size_t n_entries;
  std::vector<double> value;           // n_entries values; none while nothing was added
  std::vector<unsigned char> touched;  // likewise

  /// Adds element matrix m at `slots` (DofGraph::element_slots); transposed when the graph's
  /// rows are to be read as columns (a column-compressed result).
  void add(const std::vector<int>& slots, const MatrixXd& m, bool transposed);
  /// The touched entries as a column-compressed matrix (the graph's rows read as columns: add
  /// with transposed = true).
  SparseMatrix to_sparse(const DofGraph& graph) const;
};

}  // namespace impactfe
