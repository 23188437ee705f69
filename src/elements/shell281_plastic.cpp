// SHELL281 with plasticity or implicit creep (a TB table of a homogeneous isotropic section):
// the plane-stress J2 return at the in-plane points of the membrane and bending rule and 5
// Gauss–Lobatto points through the thickness, the committed states, and the results of the
// states (docs/elements/shell281.md, "Plasticity and creep").
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "elements/shell281.h"
#include "elements/shell_kernel.h"
#include "materials/inelastic_strain.h"

namespace impactfe {

namespace {

using Mat3 = Eigen::Matrix3d;

/// 5-point Gauss–Lobatto on ζ ∈ [−1, 1] (exact to degree 7; the surfaces are points), as
/// SHELL181's (shell_kernel_plastic.cpp).
const double kLobattoZeta[Shell281::kPlasticPoints] = {-1.0, -0.65465367070797714, 0.0,
                                                       0.65465367070797714, 1.0};
const double kLobattoWeight[Shell281::kPlasticPoints] = {0.1, 49.0 / 90.0, 32.0 / 45.0, 49.0 / 90.0,
                                                         0.1};

}  // namespace

void Shell281::plastic_sum(const Eigen::VectorXd& ue, Eigen::MatrixXd& K, Eigen::VectorXd& f,
                           std::vector<PlasticState>* updated) const {
  // Membrane and bending: the plane-stress J2 return of the in-plane strains (ε11, ε22, γ12) at
  // every point, its consistent tangent condensed on σ33 = 0 (J2Plasticity::plane_stress), the
  // transverse shear strains given as zero (they stay elastic, below), as SHELL181's.
  const J2Plasticity& law = *data_.plasticity;
  const int nd = 6 * n_;
  K = Eigen::MatrixXd::Zero(nd, nd);
  f = Eigen::VectorXd::Zero(nd);
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  const std::vector<Rule> rule = bending_rule();
  for (std::size_t ip = 0; ip < rule.size(); ++ip) {
    const Rule& q = rule[ip];
    shape(q.xi, q.eta, N, dN);
    const Mat3 R = frame(N, dN, nullptr);
    for (int k = 0; k < kPlasticPoints; ++k) {
      double detJ = 0.0;
      const Eigen::MatrixXd B =
          strains(gradient(q.xi, q.eta, kLobattoZeta[k], R, &detJ)).topRows(3);
      Vector5d strain = Vector5d::Zero();
      strain.head<3>() = B * ue;
      const std::size_t index = ip * kPlasticPoints + static_cast<std::size_t>(k);
      const PlaneStressResponse r =
          law.plane_stress(committed_[index], strain, updated ? &(*updated)[index] : nullptr);
      const double dV = detJ * q.w * kLobattoWeight[k];
      f.noalias() += B.transpose() * r.stress.head<3>() * dV;
      K.noalias() += B.transpose() * r.tangent.topLeftCorner<3, 3>() * B * dV;
    }
  }
  const Eigen::MatrixXd Ksd = shear_drilling_stiffness();
  f += Ksd * ue;
  K += Ksd;
  K = 0.5 * (K + K.transpose()).eval();
}

void Shell281::commit_history(const ElementContext&, const Eigen::VectorXd& u) {
  if (!data_.plasticity) return;
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  std::vector<PlasticState> next = committed_;
  plastic_sum(expand(u), K, f, &next);
  committed_ = std::move(next);
}

double Shell281::plastic_work() const {
  if (!data_.plasticity) return 0.0;
  double w = 0.0;
  const std::vector<Rule> rule = bending_rule();
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  for (std::size_t ip = 0; ip < rule.size(); ++ip) {
    shape(rule[ip].xi, rule[ip].eta, N, dN);
    const Mat3 R = frame(N, dN, nullptr);
    for (int k = 0; k < kPlasticPoints; ++k) {
      double detJ = 0.0;
      gradient(rule[ip].xi, rule[ip].eta, kLobattoZeta[k], R, &detJ);
      w += detJ * rule[ip].w * kLobattoWeight[k] *
           committed_[ip * kPlasticPoints + static_cast<std::size_t>(k)].plastic_work;
    }
  }
  return w;
}

std::vector<double> Shell281::history_state() const {
  std::vector<double> out;
  for (const PlasticState& s : committed_) append_state(out, s);
  return out;
}

void Shell281::restore_history_state(const std::vector<double>& state) {
  std::size_t pos = 0;
  for (PlasticState& s : committed_) read_state(state, pos, s);
  IMPACTFE_CHECK(pos == state.size(), "SHELL281: saved state of the wrong length");
}

std::vector<double> Shell281::point_weights(double xi, double eta) const {
  const std::vector<Rule> rule = bending_rule();
  std::vector<double> w(rule.size(), 0.0);
  if (n_ == 8) {
    // The 3 x 3 Gauss points: Lagrange in ξ and η through −√0.6, 0, √0.6.
    const double g = std::sqrt(0.6);
    const auto lagrange = [g](double node, double x) {
      double v = 1.0;
      for (double m : {-g, 0.0, g})
        if (std::abs(m - node) > 1e-12) v *= (x - m) / (node - m);
      return v;
    };
    for (std::size_t p = 0; p < rule.size(); ++p)
      w[p] = lagrange(rule[p].xi, xi) * lagrange(rule[p].eta, eta);
    return w;
  }
  // The triangle's three midside points: linear through them.
  Eigen::Matrix3d V;
  for (int p = 0; p < 3; ++p)
    V.row(p) << 1.0, rule[static_cast<std::size_t>(p)].xi, rule[static_cast<std::size_t>(p)].eta;
  const Eigen::Vector3d c = V.transpose().partialPivLu().solve(Eigen::Vector3d(1.0, xi, eta));
  for (std::size_t p = 0; p < 3; ++p) w[p] = c(static_cast<Eigen::Index>(p));
  return w;
}

std::vector<ElementResultValues> Shell281::plastic_point_values(const Eigen::VectorXd& ue) const {
  std::vector<PlasticState> at = committed_;  // the states at ue (committed after convergence)
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  plastic_sum(ue, K, f, &at);
  const bool creep = data_.plasticity->has_creep();
  const std::vector<Rule> rule = bending_rule();
  std::vector<ElementResultValues> out;
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  for (std::size_t ip = 0; ip < rule.size(); ++ip) {
    const Rule& q = rule[ip];
    shape(q.xi, q.eta, N, dN);
    const Mat3 R = frame(N, dN, nullptr);
    const double h = 0.5 * thickness_at(N);
    const PlasticState* s = &at[ip * kPlasticPoints];  // bottom .. top
    const auto in_plane = [](const Vector6d& v) { return Eigen::Vector3d(v(0), v(1), v(3)); };
    // Resultants of the Lobatto points: N = ∫σ dz, M = ∫zσ dz about the mid-surface.
    Eigen::Vector3d Nr = Eigen::Vector3d::Zero(), Mr = Eigen::Vector3d::Zero();
    double alpha = 0.0, work = 0.0;
    for (int k = 0; k < kPlasticPoints; ++k) {
      const Eigen::Vector3d sk = in_plane(s[k].stress);
      Nr += sk * h * kLobattoWeight[k];
      Mr += sk * kLobattoZeta[k] * h * h * kLobattoWeight[k];
      alpha = std::max(alpha, s[k].alpha);
      work += 0.5 * kLobattoWeight[k] * s[k].plastic_work;
    }
    Eigen::Vector2d Q = Eigen::Vector2d::Zero();
    for (const ThicknessPoint& z : thickness_rule())
      Q += layers_[z.layer].Gs * (shear_b(q.xi, q.eta, z.zeta, R) * ue) * h * z.w;
    ElementResultValues v = {Nr(0), Nr(1), Nr(2), Mr(0), Mr(1), Mr(2)};
    for (int k : {4, 2, 0}) {  // TOP, MID, BOT
      const Eigen::Vector3d sk = in_plane(s[k].stress);
      v.insert(v.end(), {sk(0), sk(1), sk(2)});
    }
    for (int k : {4, 2, 0}) {
      const Eigen::Vector3d sk = in_plane(s[k].stress);
      v.push_back(shell::plane_stress_von_mises(sk(0), sk(1), sk(2)));
    }
    v.insert(v.end(), {Q(0), Q(1)});
    for (int k : {4, 2, 0}) {  // the elastic strains: total less inelastic
      const Eigen::Vector3d e =
          strains(gradient(q.xi, q.eta, kLobattoZeta[k], R, nullptr)).topRows(3) * ue -
          in_plane(s[k].plastic_strain);
      v.insert(v.end(), {e(0), e(1), e(2)});
    }
    // Plastic: EPEQ (the largest at the point) and the plastic work per volume; creep (the
    // inelastic strain is the creep strain): EPCR at the top surface, as S, and CREQ.
    const Vector6d& top = s[kPlasticPoints - 1].plastic_strain;
    if (creep)
      v.insert(v.end(), {0.0, 0.0, top(0), top(1), top(2), top(3), top(4), top(5),
                         equivalent_inelastic_strain(top), alpha});
    else
      v.insert(v.end(), {alpha, work, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0});
    out.push_back(std::move(v));
  }
  return out;
}

}  // namespace impactfe
