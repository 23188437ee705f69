#pragma once
/// Sparse and dense matrix types used across impactfe.
#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace impactfe {

/// Compressed sparse column matrix. Symmetric system matrices store the LOWER triangle only.
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
using Eigen::MatrixXd;
using Eigen::VectorXd;

}  // namespace impactfe
