#include "reduction/guyan.h"

#include <algorithm>
#include <numeric>

#include "core/log.h"

namespace impactfe {

MasterSelection select_masters(const std::vector<DofKey>& requested, const DofMap& dofs,
                               const VectorXd& k_diag, const VectorXd& m_diag,
                               std::optional<int> total, bool exclude_rotations) {
  MasterSelection out;
  const int nf = dofs.n_free();
  std::vector<bool> is_master(static_cast<std::size_t>(nf), false);
  for (const DofKey& key : requested) {
    const int i = dofs.index(key);
    if (i < 0 || i >= nf) {
      out.ignored.push_back(key);
      continue;
    }
    if (is_master[static_cast<std::size_t>(i)]) continue;
    is_master[static_cast<std::size_t>(i)] = true;
    out.indices.push_back(i);
  }
  if (total && *total > static_cast<int>(out.indices.size())) {
    // Lowest K_ii / M_ii first: the DOFs whose local frequency is lowest carry the dynamics.
    std::vector<std::pair<double, int>> candidates;
    for (int i = 0; i < nf; ++i) {
      if (is_master[static_cast<std::size_t>(i)] || !(m_diag(i) > 0.0)) continue;
      if (exclude_rotations && is_rotation(dofs.key(i).dof)) continue;
      candidates.emplace_back(k_diag(i) / m_diag(i), i);
    }
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    const std::size_t wanted = static_cast<std::size_t>(*total) - out.indices.size();
    for (std::size_t k = 0; k < candidates.size() && k < wanted; ++k) {
      out.indices.push_back(candidates[k].second);
      out.automatic.push_back(dofs.key(candidates[k].second));
    }
  }
  return out;
}

GuyanReduction::GuyanReduction(const SparseMatrix& k, const SparseMatrix& m, const SparseMatrix* c,
                               int n_free, std::vector<int> masters, const DofMap* names)
    : n_free_(n_free), masters_(std::move(masters)) {
  slave_position_.assign(static_cast<std::size_t>(n_free), -1);
  std::vector<int> master_position(static_cast<std::size_t>(n_free), -1);
  for (std::size_t j = 0; j < masters_.size(); ++j)
    master_position[static_cast<std::size_t>(masters_[j])] = static_cast<int>(j);
  for (int i = 0; i < n_free; ++i)
    if (master_position[static_cast<std::size_t>(i)] < 0) {
      slave_position_[static_cast<std::size_t>(i)] = static_cast<int>(slaves_.size());
      slaves_.push_back(i);
    }
  const int ns = n_slaves(), nm = n_masters();

  // K_ss (lower triangle for the solver) and K_sm (dense right-hand sides).
  std::vector<Eigen::Triplet<double, int>> kss;
  MatrixXd ksm = MatrixXd::Zero(ns, nm);
  for (int col = 0; col < n_free; ++col) {
    const int sc = slave_position_[static_cast<std::size_t>(col)];
    const int mc = master_position[static_cast<std::size_t>(col)];
    for (SparseMatrix::InnerIterator it(k, col); it; ++it) {
      if (it.row() >= n_free) continue;
      const int sr = slave_position_[static_cast<std::size_t>(it.row())];
      if (sr < 0) continue;
      if (sc >= 0 && sr >= sc) kss.emplace_back(sr, sc, it.value());
      if (mc >= 0) ksm(sr, mc) += it.value();
    }
  }
  t_.resize(ns, nm);
  if (ns > 0) {
    SparseMatrix kss_lower(ns, ns);
    kss_lower.setFromTriplets(kss.begin(), kss.end());
    kss_ = make_linear_solver(ns);
    try {
      kss_->analyze_pattern(kss_lower);
      kss_->factorize(kss_lower);
    } catch (const SingularMatrixError& e) {
      int row = e.column();
      if (row < 0 || row >= ns) row = weakest_pivot_row(kss_lower);
      const int free_index = slaves_[static_cast<std::size_t>(std::max(row, 0))];
      throw ModelError(fmt::format(
          "Guyan reduction: slave DOF {} is not restrained by the masters or constraints "
          "(K_ss is singular); make it a master (M) or constrain it (D)",
          names ? describe(names->key(free_index)) : "#" + std::to_string(free_index)));
    }
    if (nm > 0) t_ = -kss_->solve(ksm);
  }
  k_r_ = reduce_matrix(k);
  m_r_ = reduce_matrix(m);
  c_r_ = c ? reduce_matrix(*c) : MatrixXd::Zero(nm, nm);
}

MatrixXd GuyanReduction::reduce_matrix(const SparseMatrix& a) const {
  // A_r = A_mm + A_ms T + Tᵀ A_sm + Tᵀ A_ss T, accumulated column by column of the sparse A.
  const int ns = n_slaves(), nm = n_masters();
  std::vector<int> master_position(static_cast<std::size_t>(n_free_), -1);
  for (int j = 0; j < nm; ++j) master_position[static_cast<std::size_t>(masters_[j])] = j;
  MatrixXd amm = MatrixXd::Zero(nm, nm);
  MatrixXd asm_ = MatrixXd::Zero(ns, nm);   // A_sm
  MatrixXd ass_t = MatrixXd::Zero(ns, nm);  // A_ss T
  for (int col = 0; col < n_free_; ++col) {
    const int sc = slave_position_[static_cast<std::size_t>(col)];
    const int mc = master_position[static_cast<std::size_t>(col)];
    for (SparseMatrix::InnerIterator it(a, col); it; ++it) {
      if (it.row() >= n_free_) continue;
      const int sr = slave_position_[static_cast<std::size_t>(it.row())];
      const int mr = master_position[static_cast<std::size_t>(it.row())];
      if (mc >= 0 && mr >= 0) amm(mr, mc) += it.value();
      if (mc >= 0 && sr >= 0) asm_(sr, mc) += it.value();
      if (sc >= 0 && sr >= 0) ass_t.row(sr) += it.value() * t_.row(sc);
    }
  }
  MatrixXd ar = amm;
  if (ns > 0) {
    const MatrixXd cross = t_.transpose() * asm_;
    ar += cross + cross.transpose() + t_.transpose() * ass_t;
  }
  return 0.5 * (ar + ar.transpose());
}

VectorXd GuyanReduction::reduce_force(const VectorXd& f) const {
  VectorXd fr(n_masters());
  for (int j = 0; j < n_masters(); ++j) fr(j) = f(masters_[static_cast<std::size_t>(j)]);
  if (n_slaves() > 0) {
    VectorXd fs(n_slaves());
    for (int s = 0; s < n_slaves(); ++s) fs(s) = f(slaves_[static_cast<std::size_t>(s)]);
    fr += t_.transpose() * fs;
  }
  return fr;
}

VectorXd GuyanReduction::expand(const VectorXd& u_m, const VectorXd* f) const {
  VectorXd u = VectorXd::Zero(n_free_);
  for (int j = 0; j < n_masters(); ++j) u(masters_[static_cast<std::size_t>(j)]) = u_m(j);
  if (n_slaves() == 0) return u;
  VectorXd us = t_ * u_m;
  if (f) {
    VectorXd fs(n_slaves());
    for (int s = 0; s < n_slaves(); ++s) fs(s) = (*f)(slaves_[static_cast<std::size_t>(s)]);
    if (fs.squaredNorm() > 0.0) us += kss_->solve(fs);
  }
  for (int s = 0; s < n_slaves(); ++s) u(slaves_[static_cast<std::size_t>(s)]) = us(s);
  return u;
}

}  // namespace impactfe
