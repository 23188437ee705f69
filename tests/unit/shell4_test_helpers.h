#pragma once
/// Helpers shared by the SHELL63 unit and benchmark tests: build elements without a deck,
/// solve with prescribed values, assemble at a displacement (large deflection).
#include <Eigen/Dense>

#include <map>
#include <memory>
#include <set>
#include <vector>

#include "../support/dense_assembly.h"
#include "elements/shell4.h"

namespace impactfe::testing {

struct ShellMesh {
  std::map<int, Vec3> nodes;
  std::vector<std::vector<int>> elements;  // 3 or 4 node ids, counter-clockwise
};

inline shell::KernelData plate_data(double E, double nu, double t, double rho = 0.0) {
  shell::KernelData k;
  k.E = E;
  k.nu = nu;
  k.rho = rho;
  k.t = {t, t, t, t};
  return k;
}

inline std::unique_ptr<Element> make_shell(int id, const std::vector<int>& ids,
                                           const std::vector<Vec3>& x, const shell::KernelData& k) {
  Shell4Data d;
  d.node_ids = ids;
  d.positions = x;
  d.kernel = k;
  return std::make_unique<Shell4>(id, d, SourceLocation{"test", 1, "E"});
}

inline std::vector<std::unique_ptr<Element>> build(const ShellMesh& mesh,
                                                   const shell::KernelData& k) {
  std::vector<std::unique_ptr<Element>> out;
  int id = 1;
  for (const auto& e : mesh.elements) {
    std::vector<Vec3> x;
    for (int n : e) x.push_back(mesh.nodes.at(n));
    out.push_back(make_shell(id++, e, x, k));
  }
  return out;
}

/// Solves K u = f with the DOFs in `prescribed` set to the given values.
inline Eigen::VectorXd solve_prescribed(const DenseSystem& s, const Eigen::VectorXd& f,
                                        const std::map<DofKey, double>& prescribed) {
  std::vector<int> free, fixed;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(s.n());
  for (int i = 0; i < s.n(); ++i) {
    const auto it = prescribed.find(s.dofs()[static_cast<std::size_t>(i)]);
    if (it == prescribed.end()) {
      free.push_back(i);
    } else {
      fixed.push_back(i);
      u(i) = it->second;
    }
  }
  const int nf = static_cast<int>(free.size());
  Eigen::MatrixXd Kff(nf, nf);
  Eigen::VectorXd rhs(nf);
  for (int a = 0; a < nf; ++a) {
    rhs(a) = f(free[a]);
    for (int i : fixed) rhs(a) -= s.K(free[a], i) * u(i);
    for (int b = 0; b < nf; ++b) Kff(a, b) = s.K(free[a], free[b]);
  }
  const Eigen::VectorXd uf = Kff.ldlt().solve(rhs);
  for (int a = 0; a < nf; ++a) u(free[a]) = uf(a);
  return u;
}

/// Assembles K_T and f_int at the global displacement u.
inline void assemble_at(const DenseSystem& s, const std::vector<std::unique_ptr<Element>>& els,
                        const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
                        Eigen::VectorXd& f) {
  K.setZero(s.n(), s.n());
  f.setZero(s.n());
  for (const auto& e : els) {
    Eigen::MatrixXd ke;
    Eigen::VectorXd fe;
    e->tangent(ctx, gather(s, *e, u), ke, fe);
    const auto& d = e->dofs();
    for (int a = 0; a < e->n_dofs(); ++a) {
      const int ia =
          s.index(d[static_cast<std::size_t>(a)].node, d[static_cast<std::size_t>(a)].dof);
      f(ia) += fe(a);
      for (int b = 0; b < e->n_dofs(); ++b)
        K(ia, s.index(d[static_cast<std::size_t>(b)].node, d[static_cast<std::size_t>(b)].dof)) +=
            ke(a, b);
    }
  }
}

/// Consistent nodal loads of a uniform pressure q along `dir` (∫ N_a q dA, bilinear/linear N).
inline Eigen::VectorXd pressure_load(const DenseSystem& s, const ShellMesh& mesh, double q,
                                     const Vec3& dir) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(s.n());
  const Dof dofs[3] = {Dof::UX, Dof::UY, Dof::UZ};
  for (const auto& e : mesh.elements) {
    std::vector<double> share(e.size(), 0.0);
    if (e.size() == 3) {
      const Vec3 a = mesh.nodes.at(e[1]) - mesh.nodes.at(e[0]);
      const Vec3 b = mesh.nodes.at(e[2]) - mesh.nodes.at(e[0]);
      for (auto& v : share) v = 0.5 * a.cross(b).norm() / 3.0;
    } else {
      const double g = 1.0 / std::sqrt(3.0);
      const double xs[4] = {-1, 1, 1, -1}, ys[4] = {-1, -1, 1, 1};
      for (int p = 0; p < 4; ++p) {
        const double xi = xs[p] * g, eta = ys[p] * g;
        Vec3 dxi = Vec3::Zero(), deta = Vec3::Zero();
        double N[4];
        for (int i = 0; i < 4; ++i) {
          N[i] = 0.25 * (1 + xi * xs[i]) * (1 + eta * ys[i]);
          dxi += 0.25 * xs[i] * (1 + eta * ys[i]) * mesh.nodes.at(e[static_cast<std::size_t>(i)]);
          deta += 0.25 * ys[i] * (1 + xi * xs[i]) * mesh.nodes.at(e[static_cast<std::size_t>(i)]);
        }
        const double dA = dxi.cross(deta).norm();
        for (int i = 0; i < 4; ++i) share[static_cast<std::size_t>(i)] += N[i] * dA;
      }
    }
    for (std::size_t i = 0; i < e.size(); ++i)
      for (int c = 0; c < 3; ++c)
        if (dir(c) != 0.0) f(s.index(e[i], dofs[c])) += q * dir(c) * share[i];
  }
  return f;
}

}  // namespace impactfe::testing
