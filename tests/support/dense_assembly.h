#pragma once
/// Test support: dense assembly of a handful of elements, for element-level benchmark tests
/// that must not depend on the analysis drivers. Not for production use.
#include <Eigen/Dense>

#include <map>
#include <memory>
#include <set>
#include <vector>

#include "elements/element.h"

namespace impactfe::testing {

/// Numbers every (node, dof) that appears in the elements, in sorted order.
class DenseSystem {
 public:
  explicit DenseSystem(const std::vector<std::unique_ptr<Element>>& elements) {
    std::set<DofKey> keys;
    for (const auto& e : elements)
      for (const auto& k : e->dofs()) keys.insert(k);
    for (const auto& k : keys) {
      index_[k] = static_cast<int>(dofs_.size());
      dofs_.push_back(k);
    }
    const int n = static_cast<int>(dofs_.size());
    K.setZero(n, n);
    M.setZero(n, n);
    Eigen::VectorXd u_zero;
    for (const auto& e : elements) {
      Eigen::MatrixXd ke, me;
      Eigen::VectorXd fe;
      u_zero.setZero(e->n_dofs());
      e->tangent(ctx, u_zero, ke, fe);
      e->mass(ctx, me);
      const auto& d = e->dofs();
      for (int a = 0; a < e->n_dofs(); ++a)
        for (int b = 0; b < e->n_dofs(); ++b) {
          K(index_.at(d[a]), index_.at(d[b])) += ke(a, b);
          M(index_.at(d[a]), index_.at(d[b])) += me(a, b);
        }
    }
  }

  int n() const { return static_cast<int>(dofs_.size()); }
  int index(int node, Dof dof) const { return index_.at(DofKey{node, dof}); }
  bool has(int node, Dof dof) const { return index_.count(DofKey{node, dof}) != 0; }
  const std::vector<DofKey>& dofs() const { return dofs_; }

  /// Solves K u = f with the listed DOFs fixed to zero; returns u over all DOFs.
  Eigen::VectorXd solve_static(const Eigen::VectorXd& f, const std::set<DofKey>& fixed) const {
    std::vector<int> free;
    for (int i = 0; i < n(); ++i)
      if (!fixed.count(dofs_[i])) free.push_back(i);
    const int nf = static_cast<int>(free.size());
    Eigen::MatrixXd Kff(nf, nf);
    Eigen::VectorXd ff(nf);
    for (int a = 0; a < nf; ++a) {
      ff(a) = f(free[a]);
      for (int b = 0; b < nf; ++b) Kff(a, b) = K(free[a], free[b]);
    }
    const Eigen::VectorXd uf = Kff.ldlt().solve(ff);
    Eigen::VectorXd u = Eigen::VectorXd::Zero(n());
    for (int a = 0; a < nf; ++a) u(free[a]) = uf(a);
    return u;
  }

  /// Lowest generalized eigenvalues omega^2 of K x = w^2 M x with the listed DOFs fixed.
  Eigen::VectorXd eigenvalues(const std::set<DofKey>& fixed) const {
    std::vector<int> free;
    for (int i = 0; i < n(); ++i)
      if (!fixed.count(dofs_[i])) free.push_back(i);
    const int nf = static_cast<int>(free.size());
    Eigen::MatrixXd Kff(nf, nf), Mff(nf, nf);
    for (int a = 0; a < nf; ++a)
      for (int b = 0; b < nf; ++b) {
        Kff(a, b) = K(free[a], free[b]);
        Mff(a, b) = M(free[a], free[b]);
      }
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Kff, Mff);
    return es.eigenvalues();
  }

  ElementContext ctx;
  Eigen::MatrixXd K;
  Eigen::MatrixXd M;

 private:
  std::map<DofKey, int> index_;
  std::vector<DofKey> dofs_;
};

/// Element part of a global vector.
inline Eigen::VectorXd gather(const DenseSystem& s, const Element& e, const Eigen::VectorXd& u) {
  Eigen::VectorXd ue(e.n_dofs());
  for (int a = 0; a < e.n_dofs(); ++a) {
    const DofKey& k = e.dofs()[static_cast<std::size_t>(a)];
    ue(a) = u(s.index(k.node, k.dof));
  }
  return ue;
}

}  // namespace impactfe::testing
