#pragma once
/// Sparse and dense matrix types used across impactfe.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <algorithm>
#include <vector>

namespace impactfe {

/// Compressed sparse column matrix. Symmetric system matrices store the LOWER triangle only.
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
using Eigen::MatrixXd;
using Eigen::VectorXd;

/// The structure of a square column-compressed matrix without its values (rows ascending
/// within a column): what a matrix whose values are formed later needs, at a third of the
/// storage of a SparseMatrix of zeros (issue 11: memory).
struct SparsePattern {
  int size = 0;                   // rows = columns
  std::vector<int> column_start;  // size + 1 offsets into `row`
  std::vector<int> row;
  long long nonzeros() const { return static_cast<long long>(row.size()); }
  /// A compressed matrix with this structure and every value zero.
  SparseMatrix zero_matrix() const {
    SparseMatrix m(size, size);
    m.resizeNonZeros(static_cast<Eigen::Index>(row.size()));
    std::copy(column_start.begin(), column_start.end(), m.outerIndexPtr());
    std::copy(row.begin(), row.end(), m.innerIndexPtr());
    std::fill(m.valuePtr(), m.valuePtr() + row.size(), 0.0);
    return m;
  }
};

}  // namespace impactfe
