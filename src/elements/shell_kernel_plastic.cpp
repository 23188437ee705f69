// Elastic-plastic response of the flat shell kernel (SHELL181 with TB plasticity): layered
// integration through the thickness with the plane-stress J2 return at every layer point.
#include <Eigen/Dense>

#include <cmath>

#include "elements/shell_kernel.h"

namespace impactfe::shell {

namespace {

/// 5-point Gauss–Lobatto rule on [−1, 1] (exact to degree 7; the surfaces are points).
const double kLobattoZeta[FlatShellKernel::kLayers] = {-1.0, -std::sqrt(3.0 / 7.0), 0.0,
                                                       std::sqrt(3.0 / 7.0), 1.0};
const double kLobattoWeight[FlatShellKernel::kLayers] = {0.1, 49.0 / 90.0, 32.0 / 45.0, 49.0 / 90.0,
                                                         0.1};

}  // namespace

int FlatShellKernel::n_material_points() const {
  return static_cast<int>(points().size()) * kLayers;
}

Eigen::MatrixXd FlatShellKernel::membrane_b(const Point& p) const {
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  double detJ = 0.0;
  shape(p.xi, p.eta, N, dN, detJ);
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(3, 2 * n_ + n_modes_);
  for (int a = 0; a < n_; ++a) {
    B(0, 2 * a) = dN(0, a);
    B(1, 2 * a + 1) = dN(1, a);
    B(2, 2 * a) = dN(1, a);
    B(2, 2 * a + 1) = dN(0, a);
  }
  if (n_modes_ > 0) {
    // The modified incompatible modes of add_membrane (Taylor, Beresford & Wilson 1976).
    const Eigen::Vector2d d1 = (detJ0_ / detJ) * J0i_ * Eigen::Vector2d(-2.0 * p.xi, 0.0);
    const Eigen::Vector2d d2 = (detJ0_ / detJ) * J0i_ * Eigen::Vector2d(0.0, -2.0 * p.eta);
    const int c = 2 * n_;
    B(0, c) = d1.x();
    B(0, c + 1) = d2.x();
    B(1, c + 2) = d1.y();
    B(1, c + 3) = d2.y();
    B(2, c) = d1.y();
    B(2, c + 1) = d2.y();
    B(2, c + 2) = d1.x();
    B(2, c + 3) = d2.x();
  }
  return B;
}

void FlatShellKernel::plastic_sum(const J2Plasticity& law,
                                  const std::vector<PlasticState>& committed,
                                  const Eigen::VectorXd& qm, const Eigen::VectorXd& qb,
                                  Eigen::MatrixXd& K, Eigen::VectorXd& f,
                                  std::vector<PlasticState>* updated, Resultants* mean,
                                  std::array<Eigen::Vector3d, kLayers>* layers) const {
  const int nm = static_cast<int>(qm.size()), nb = static_cast<int>(qb.size());
  K.setZero(nm + nb, nm + nb);
  f.setZero(nm + nb);
  if (mean) *mean = Resultants{};
  if (layers) layers->fill(Eigen::Vector3d::Zero());
  const auto pts = points();
  Eigen::VectorXd N;
  Eigen::MatrixXd dN, Bb;
  for (std::size_t ip = 0; ip < pts.size(); ++ip) {
    const Point& p = pts[ip];
    double detJ = 0.0;
    shape(p.xi, p.eta, N, dN, detJ);
    const double t = thickness_at(N);
    const double wgt = detJ * p.w;
    const Eigen::MatrixXd Bm = membrane_b(p);
    bending_b(p.xi, p.eta, Bb);
    const Eigen::Vector3d e = data_.membrane ? Eigen::Vector3d(Bm * qm) : Eigen::Vector3d::Zero();
    const Eigen::Vector3d kappa =
        data_.bending ? Eigen::Vector3d(Bb * qb) : Eigen::Vector3d::Zero();
    // Resultants N = ∫σ dz, M = ∫zσ dz and the section tangent [A B; B D] (ε(z) = e + zκ).
    Eigen::Vector3d n_res = Eigen::Vector3d::Zero(), m_res = Eigen::Vector3d::Zero();
    Eigen::Matrix3d a = Eigen::Matrix3d::Zero(), b = a, d = a;
    for (int k = 0; k < kLayers; ++k) {
      const double z = 0.5 * t * kLobattoZeta[k];
      const double hw = 0.5 * t * kLobattoWeight[k];
      Vector5d strain = Vector5d::Zero();
      strain.head<3>() = e + z * kappa;
      const std::size_t index = ip * kLayers + static_cast<std::size_t>(k);
      const PlaneStressResponse r =
          law.plane_stress(committed[index], strain, updated ? &(*updated)[index] : nullptr);
      const Eigen::Vector3d s = r.stress.head<3>();
      const Eigen::Matrix3d c = r.tangent.topLeftCorner<3, 3>();
      n_res += hw * s;
      m_res += hw * z * s;
      a += hw * c;
      b += hw * z * c;
      d += hw * z * z * c;
      if (layers) (*layers)[static_cast<std::size_t>(k)] += (wgt / area_) * s;
    }
    if (mean) {
      mean->N += (wgt / area_) * n_res;
      mean->M += (wgt / area_) * m_res;
      mean->t += (wgt / area_) * t;
    }
    if (data_.membrane) {
      f.head(nm) += wgt * Bm.transpose() * n_res;
      K.topLeftCorner(nm, nm) += wgt * Bm.transpose() * a * Bm;
    }
    if (data_.bending) {
      f.tail(nb) += wgt * Bb.transpose() * m_res;
      K.bottomRightCorner(nb, nb) += wgt * Bb.transpose() * d * Bb;
    }
    if (data_.membrane && data_.bending) {
      const Eigen::MatrixXd kmb = wgt * Bm.transpose() * b * Bb;
      K.topRightCorner(nm, nb) += kmb;
      K.bottomLeftCorner(nb, nm) += kmb.transpose();
    }
  }
}

void FlatShellKernel::plastic_response(const J2Plasticity& law,
                                       const std::vector<PlasticState>& committed,
                                       const Eigen::VectorXd& d, Eigen::MatrixXd& K,
                                       Eigen::VectorXd& f, std::vector<PlasticState>* updated,
                                       Resultants* mean,
                                       std::array<Eigen::Vector3d, kLayers>* layers) const {
  const int nc = 2 * n_, nm = nc + n_modes_, nb = 3 * n_;
  Eigen::VectorXd qm = Eigen::VectorXd::Zero(nm), qb(nb);
  for (int a = 0; a < n_; ++a) {
    qm(2 * a) = d(6 * a);
    qm(2 * a + 1) = d(6 * a + 1);
    for (int i = 0; i < 3; ++i) qb(3 * a + i) = d(6 * a + 2 + i);
  }
  Eigen::MatrixXd kq;
  Eigen::VectorXd fq;
  const int modes = data_.membrane ? n_modes_ : 0;
  if (modes > 0) {
    // Incompatible modes: internal, so f_α(d, α) = 0 is solved by Newton (each pass returns
    // every point from its committed state), then condensed; exact for an elastic step at once.
    const double scale = std::max(qm.head(nc).lpNorm<Eigen::Infinity>(), 1e-300);
    for (int iter = 0; iter < 25; ++iter) {
      plastic_sum(law, committed, qm, qb, kq, fq, nullptr, nullptr, nullptr);
      const Eigen::VectorXd step =
          -kq.block(nc, nc, modes, modes).ldlt().solve(fq.segment(nc, modes));
      qm.segment(nc, modes) += step;
      if (step.lpNorm<Eigen::Infinity>() <=
          1e-12 * std::max(scale, qm.segment(nc, modes).lpNorm<Eigen::Infinity>()))
        break;
    }
  }
  plastic_sum(law, committed, qm, qb, kq, fq, updated, mean, layers);
  // Condense the modes: coordinates r = (membrane corners, bending), α = modes.
  std::vector<int> r;
  for (int i = 0; i < nc; ++i) r.push_back(i);
  for (int i = 0; i < nb; ++i) r.push_back(nm + i);
  const int nr = static_cast<int>(r.size());
  Eigen::MatrixXd krr(nr, nr);
  Eigen::VectorXd fr(nr);
  for (int i = 0; i < nr; ++i) {
    fr(i) = fq(r[static_cast<std::size_t>(i)]);
    for (int j = 0; j < nr; ++j)
      krr(i, j) = kq(r[static_cast<std::size_t>(i)], r[static_cast<std::size_t>(j)]);
  }
  if (modes > 0) {
    Eigen::MatrixXd kra(nr, modes);
    for (int i = 0; i < nr; ++i)
      kra.row(i) = kq.block(r[static_cast<std::size_t>(i)], nc, 1, modes);
    const auto kaa = kq.block(nc, nc, modes, modes).ldlt();
    krr -= kra * kaa.solve(kra.transpose());
    fr -= kra * kaa.solve(fq.segment(nc, modes));
  }
  // Scatter to the 6n local DOFs (u, v | w, θx, θy per node), plus the elastic extras.
  std::vector<int> dof(static_cast<std::size_t>(nr));
  for (int a = 0; a < n_; ++a) {
    dof[static_cast<std::size_t>(2 * a)] = 6 * a;
    dof[static_cast<std::size_t>(2 * a + 1)] = 6 * a + 1;
    for (int i = 0; i < 3; ++i) dof[static_cast<std::size_t>(nc + 3 * a + i)] = 6 * a + 2 + i;
  }
  K = elastic_extra();
  f = K * d;
  for (int i = 0; i < nr; ++i) {
    f(dof[static_cast<std::size_t>(i)]) += fr(i);
    for (int j = 0; j < nr; ++j)
      K(dof[static_cast<std::size_t>(i)], dof[static_cast<std::size_t>(j)]) += krr(i, j);
  }
  K = 0.5 * (K + K.transpose()).eval();
  if (mean && data_.mindlin && data_.bending) {
    // Elastic transverse shear forces at the centroid (shell_kernel_mindlin.cpp).
    mean->Q = data_.shear_factor * data_.E / (2.0 * (1.0 + data_.nu)) * mean->t * (Bs0_ * qb);
  }
}

double FlatShellKernel::plastic_work(const std::vector<PlasticState>& states) const {
  const auto pts = points();
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  double w = 0.0;
  for (std::size_t ip = 0; ip < pts.size(); ++ip) {
    double detJ = 0.0;
    shape(pts[ip].xi, pts[ip].eta, N, dN, detJ);
    const double t = thickness_at(N);
    for (int k = 0; k < kLayers; ++k)
      w += detJ * pts[ip].w * 0.5 * t * kLobattoWeight[k] *
           states[ip * kLayers + static_cast<std::size_t>(k)].plastic_work;
  }
  return w;
}

Vector6d FlatShellKernel::layer_inelastic_strain(const std::vector<PlasticState>& states,
                                                 int layer) const {
  const auto pts = points();
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  Vector6d mean = Vector6d::Zero();
  for (std::size_t ip = 0; ip < pts.size(); ++ip) {
    double detJ = 0.0;
    shape(pts[ip].xi, pts[ip].eta, N, dN, detJ);
    mean += (detJ * pts[ip].w / area_) *
            states[ip * kLayers + static_cast<std::size_t>(layer)].plastic_strain;
  }
  return mean;
}

}  // namespace impactfe::shell
