#include "substructure/condensation.h"

#include <fmt/format.h>

#include "core/errors.h"

namespace impactfe {

namespace {

/// Position of each full index in a list (−1 when absent).
std::vector<int> positions(int n, const std::vector<int>& list) {
  std::vector<int> pos(static_cast<std::size_t>(n), -1);
  for (std::size_t k = 0; k < list.size(); ++k) pos[static_cast<std::size_t>(list[k])] = int(k);
  return pos;
}

/// Sparse sub-block A(rows, cols); `lower_only` keeps r >= c (for the symmetric solver).
SparseMatrix sparse_block(const SparseMatrix& A, const std::vector<int>& rows,
                          const std::vector<int>& cols, bool lower_only) {
  const std::vector<int> pr = positions(static_cast<int>(A.rows()), rows);
  const std::vector<int> pc = positions(static_cast<int>(A.cols()), cols);
  std::vector<Eigen::Triplet<double, int>> t;
  for (int col = 0; col < A.outerSize(); ++col) {
    const int c = pc[static_cast<std::size_t>(col)];
    if (c < 0) continue;
    for (SparseMatrix::InnerIterator it(A, col); it; ++it) {
      const int r = pr[static_cast<std::size_t>(it.row())];
      if (r < 0 || (lower_only && r < c)) continue;
      t.emplace_back(r, c, it.value());
    }
  }
  SparseMatrix out(static_cast<int>(rows.size()), static_cast<int>(cols.size()));
  out.setFromTriplets(t.begin(), t.end());
  return out;
}

}  // namespace

StaticCondensation::StaticCondensation(const SparseMatrix& K, std::vector<int> masters,
                                       std::vector<int> slaves,
                                       const std::function<std::string(int)>& describe)
    : masters_(std::move(masters)), slaves_(std::move(slaves)) {
  const int ns = n_slaves();
  solver_ = make_linear_solver(ns);
  t_sm_.setZero(ns, n_masters());
  if (ns == 0) return;
  const SparseMatrix kss = sparse_block(K, slaves_, slaves_, /*lower_only=*/true);
  try {
    solver_->analyze_pattern(kss);
    solver_->factorize(kss);
  } catch (const SingularMatrixError& e) {
    throw ModelError(fmt::format(
        "superelement generation: the slave stiffness K_ss is singular at {}: the slave DOFs "
        "must be restrained by the masters and constraints (add masters or D)",
        describe(slaves_[static_cast<std::size_t>(e.column())])));
  }
  const MatrixXd ksm = block(K, slaves_, masters_);
  t_sm_ = -solver_->solve(ksm);
}

MatrixXd StaticCondensation::block(const SparseMatrix& A, const std::vector<int>& rows,
                                   const std::vector<int>& cols) const {
  return MatrixXd(sparse_block(A, rows, cols, false));
}

MatrixXd StaticCondensation::reduce_matrix(const SparseMatrix& A) const {
  const MatrixXd amm = block(A, masters_, masters_);
  if (n_slaves() == 0) return 0.5 * (amm + amm.transpose());
  const MatrixXd asm_ = block(A, slaves_, masters_);
  const SparseMatrix ass = sparse_block(A, slaves_, slaves_, false);
  const MatrixXd ass_t = ass * t_sm_;
  MatrixXd r =
      amm + asm_.transpose() * t_sm_ + t_sm_.transpose() * asm_ + t_sm_.transpose() * ass_t;
  return 0.5 * (r + r.transpose());
}

VectorXd StaticCondensation::reduce_vector(const VectorXd& f) const {
  VectorXd fm(n_masters()), fs(n_slaves());
  for (int k = 0; k < n_masters(); ++k) fm(k) = f(masters_[static_cast<std::size_t>(k)]);
  for (int k = 0; k < n_slaves(); ++k) fs(k) = f(slaves_[static_cast<std::size_t>(k)]);
  return fm + t_sm_.transpose() * fs;
}

VectorXd StaticCondensation::slave_response(const VectorXd& f) const {
  VectorXd fs(n_slaves());
  for (int k = 0; k < n_slaves(); ++k) fs(k) = f(slaves_[static_cast<std::size_t>(k)]);
  if (n_slaves() == 0) return fs;
  return solver_->solve(fs);
}

}  // namespace impactfe
