/// The integration points of CONTA174's segment-to-segment contact (elements/contact_segment.h):
/// the closest-point projection on a bilinear target facet with its exact first and second
/// variations, the search among the candidate facets, and the Gauss point against a rigid target.
#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "elements/contact_segment.h"
#include "elements/so3.h"
#include "elements/target_surface.h"

namespace impactfe {

namespace {

/// The closest point of x_s on the facet through x (m nodes): Newton on the projection condition
/// F_α = (x_s − x(ξ))·a_α = 0 with the Jacobian A_αβ = a_α·a_β − r·a_α,β (Wriggers §4.1,
/// eq. 4.7; a bilinear facet has a_1,1 = a_2,2 = 0). `ok` false when Newton does not converge.
struct FacetProjection {
  bool ok = false;
  double xi = 0.0, eta = 0.0;
  FacetShape s;
  Vec3 xm, a1, a2, a12, r, n;
  double len = 0.0;  // |a₁ × a₂|
  Eigen::Matrix2d A;
};

/// The facet's point, tangents and projection Jacobian at (ξ, η).
void evaluate(FacetProjection& p, const Vec3& xs, const Vec3* x, int m, double xi, double eta) {
  p.xi = xi;
  p.eta = eta;
  p.s = facet_shape(m, xi, eta);
  p.xm.setZero();
  p.a1.setZero();
  p.a2.setZero();
  p.a12.setZero();
  for (int a = 0; a < m; ++a) {
    p.xm += p.s.N[a] * x[a];
    p.a1 += p.s.dN[a][0] * x[a];
    p.a2 += p.s.dN[a][1] * x[a];
    p.a12 += p.s.dN12[a] * x[a];
  }
  p.r = xs - p.xm;
  const double a12 = p.a1.dot(p.a2) - p.r.dot(p.a12);
  p.A << p.a1.dot(p.a1), a12, a12, p.a2.dot(p.a2);
}

FacetProjection project(const Vec3& xs, const Vec3* x, int m) {
  FacetProjection p;
  double xi = m == 4 ? 0.0 : 1.0 / 3.0, eta = xi;
  for (int it = 0; it < 50; ++it) {
    evaluate(p, xs, x, m, xi, eta);
    const double scale = std::max(p.A(0, 0), p.A(1, 1));
    if (!(std::abs(p.A.determinant()) > 1e-14 * scale * scale)) return p;
    const Eigen::Vector2d d = p.A.inverse() * Eigen::Vector2d(p.r.dot(p.a1), p.r.dot(p.a2));
    xi += d(0);
    eta += d(1);
    if (std::abs(xi) > 1e3 || std::abs(eta) > 1e3) return p;
    if (d.norm() > 1e-13 && !(it >= 8 && d.norm() < 1e-10)) continue;  // round-off floor
    evaluate(p, xs, x, m, xi, eta);
    const Vec3 c = p.a1.cross(p.a2);
    p.len = c.norm();
    if (!(p.len > 0.0)) return p;
    p.n = c / p.len;
    p.ok = true;
    return p;
  }
  return p;
}

/// The pilot's node then the face corners.
std::vector<int> with_pilot(int pilot, const std::vector<int>& corners) {
  std::vector<int> out = {pilot};
  out.insert(out.end(), corners.begin(), corners.end());
  return out;
}

}  // namespace

FacetShape facet_shape(int m, double xi, double eta) {
  FacetShape s;
  s.m = m;
  if (m == 3) {
    s.N[0] = 1.0 - xi - eta;
    s.N[1] = xi;
    s.N[2] = eta;
    s.dN[0][0] = -1.0, s.dN[0][1] = -1.0;
    s.dN[1][0] = 1.0, s.dN[1][1] = 0.0;
    s.dN[2][0] = 0.0, s.dN[2][1] = 1.0;
    return s;
  }
  static constexpr double sx[4] = {-1.0, 1.0, 1.0, -1.0}, sy[4] = {-1.0, -1.0, 1.0, 1.0};
  for (int a = 0; a < 4; ++a) {
    s.N[a] = 0.25 * (1.0 + sx[a] * xi) * (1.0 + sy[a] * eta);
    s.dN[a][0] = 0.25 * sx[a] * (1.0 + sy[a] * eta);
    s.dN[a][1] = 0.25 * sy[a] * (1.0 + sx[a] * xi);
    s.dN12[a] = 0.25 * sx[a] * sy[a];
  }
  return s;
}

double facet_outside(int m, double xi, double eta) {
  if (m == 3) return std::max({0.0, -xi, -eta, xi + eta - 1.0});
  return 0.5 * std::max({0.0, std::abs(xi) - 1.0, std::abs(eta) - 1.0});
}

int facet_exit_edge(int m, double xi, double eta) {
  // Quadrilateral edges 0 (η = −1), 1 (ξ = 1), 2 (η = 1), 3 (ξ = −1); triangle edges 0 (η = 0),
  // 1 (ξ + η = 1), 2 (ξ = 0).
  const std::array<double, 4> out =
      m == 3 ? std::array<double, 4>{-eta, xi + eta - 1.0, -xi, -1e300}
             : std::array<double, 4>{-1.0 - eta, xi - 1.0, eta - 1.0, -1.0 - xi};
  return static_cast<int>(std::max_element(out.begin(), out.end()) - out.begin());
}

SegmentPoint::SegmentPoint(const char* family, int id, std::vector<int> nodes, std::vector<Vec3> x,
                           int n_face, std::vector<double> phi,
                           std::vector<SegmentCandidate> candidates, int current, double reach,
                           double offset, const ContactLawData& data)
    : ContactPoint(id, translation_dofs(nodes), data),
      family_(family),
      nodes_(std::move(nodes)),
      x_(std::move(x)),
      n_face_(n_face),
      phi_(std::move(phi)),
      candidates_(std::move(candidates)),
      current_(current),
      reach_(reach),
      offset_(offset) {
  initialize();
}

bool SegmentPoint::locate(const Eigen::VectorXd& u) {
  if (candidates_.empty()) return false;
  const auto pos = [&](int i) -> Vec3 {
    return x_[static_cast<std::size_t>(i)] + u.segment<3>(3 * i);
  };
  Vec3 xs = Vec3::Zero();
  for (int i = 0; i < n_face_; ++i) xs += phi_[static_cast<std::size_t>(i)] * pos(i);
  const auto try_facet = [&](int c) {
    const std::vector<int>& local = candidates_[static_cast<std::size_t>(c)].local;
    Vec3 x[4];
    const int m = static_cast<int>(local.size());
    for (int a = 0; a < m; ++a) x[a] = pos(local[static_cast<std::size_t>(a)]);
    return project(xs, x, m);
  };
  {
    // Hysteresis: the facet in use is kept while the point projects into it (slack 1e-6).
    const FacetProjection p = try_facet(current_);
    const int m = static_cast<int>(candidates_[static_cast<std::size_t>(current_)].local.size());
    if (p.ok && facet_outside(m, p.xi, p.eta) <= 1e-6) return std::abs(p.n.dot(p.r)) <= reach_;
  }
  int best = -1, least = -1;
  double best_gap = 0.0, least_out = 0.0, least_gap = 0.0;
  for (std::size_t c = 0; c < candidates_.size(); ++c) {
    const FacetProjection p = try_facet(static_cast<int>(c));
    if (!p.ok) continue;
    const double out = facet_outside(static_cast<int>(candidates_[c].local.size()), p.xi, p.eta);
    const double gap = p.n.dot(p.r);
    if (out <= 1e-9) {
      if (best < 0 || std::abs(gap) < std::abs(best_gap))
        best = static_cast<int>(c), best_gap = gap;
    } else if (least < 0 || out < least_out) {
      least = static_cast<int>(c), least_out = out, least_gap = gap;
    }
  }
  if (best >= 0) {
    current_ = best;
    return std::abs(best_gap) <= reach_;
  }
  if (least < 0 || std::abs(least_gap) > reach_) return false;
  const SegmentCandidate& c = candidates_[static_cast<std::size_t>(least)];
  const int m = static_cast<int>(c.local.size());
  const FacetProjection p = try_facet(least);
  const int edge = c.edge[static_cast<std::size_t>(facet_exit_edge(m, p.xi, p.eta))];
  if (edge == 1 || (edge == 0 && least_out <= kTargetEdgeTolerance)) {
    // Between two candidates at a convex edge, or just beyond a free edge of the target: the
    // nearest facet, extended.
    current_ = least;
    return true;
  }
  if (edge == 2)
    throw ElementSolutionError(
        id(), fmt::format("element {}: an integration point of the contact face slid out of the "
                          "target facets found within its pinball at setup (small sliding [A]: "
                          "the candidate facets of a segment-to-segment contact point are fixed "
                          "when the model is built); enlarge the pinball (real constant 6 PINB) "
                          "to cover the sliding distance",
                          id()));
  return false;
}

ContactKinematics SegmentPoint::kinematics(const Eigen::VectorXd& u) const {
  const int n = n_dofs();
  ContactKinematics k;
  k.G = Eigen::VectorXd::Zero(n);
  k.T = Eigen::MatrixXd::Zero(3, n);
  if (candidates_.empty()) {
    k.gap = reach_;  // never in reach: open for good
    return k;
  }
  const std::vector<int>& local = candidates_[static_cast<std::size_t>(current_)].local;
  const int m = static_cast<int>(local.size());
  Vec3 xs = Vec3::Zero(), us = Vec3::Zero(), x[4], um[4];
  for (int i = 0; i < n_face_; ++i) {
    const double f = phi_[static_cast<std::size_t>(i)];
    us += f * u.segment<3>(3 * i);
    xs += f * (x_[static_cast<std::size_t>(i)] + u.segment<3>(3 * i));
  }
  for (int a = 0; a < m; ++a) {
    const int j = local[static_cast<std::size_t>(a)];
    um[a] = u.segment<3>(3 * j);
    x[a] = x_[static_cast<std::size_t>(j)] + um[a];
  }
  const FacetProjection p = project(xs, x, m);
  if (!p.ok) {
    k.gap = reach_;  // a degenerate facet: no contact
    return k;
  }
  const Vec3& nn = p.n;
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d P = I - nn * nn.transpose();
  // Linear operators on the element's coordinates: Δr̃ = R Δx (r̃ = Σ φ_i x_i − Σ N_a x_a at
  // fixed ξ), Δa_α = E_α Δx at fixed ξ.
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(3, n), E1 = R, E2 = R;
  for (int i = 0; i < n_face_; ++i) R.middleCols<3>(3 * i) += phi_[static_cast<std::size_t>(i)] * I;
  for (int a = 0; a < m; ++a) {
    const int c = 3 * local[static_cast<std::size_t>(a)];
    R.middleCols<3>(c) -= p.s.N[a] * I;
    E1.middleCols<3>(c) += p.s.dN[a][0] * I;
    E2.middleCols<3>(c) += p.s.dN[a][1] * I;
  }
  // Δξ = A⁻¹ [a_α·Δr̃ + r·Δa_α] (the differentiated projection condition, r = x_s − x_m = g n).
  Eigen::MatrixXd B(2, n);
  B.row(0) = p.a1.transpose() * R + p.r.transpose() * E1;
  B.row(1) = p.a2.transpose() * R + p.r.transpose() * E2;
  const Eigen::MatrixXd Xi = p.A.inverse() * B;
  // Δn = P (Δa₁ × a₂ + a₁ × Δa₂)/|a₁ × a₂| with the total Δa₁ = E₁ Δx + a_12 Δη and
  // Δa₂ = E₂ Δx + a_12 Δξ (a_1,1 = a_2,2 = 0 on a bilinear facet).
  const Eigen::MatrixXd DA1 = E1 + p.a12 * Xi.row(1), DA2 = E2 + p.a12 * Xi.row(0);
  const Eigen::MatrixXd DN = P * (-so3::spin(p.a2) * DA1 + so3::spin(p.a1) * DA2) / p.len;
  // δg = n·δr̃ and Δδg = Δn·δr̃ − (n·δa_β) Δξ^β (Wriggers §4.3 / §9.3 for the node-to-segment
  // case; here x_s = Σ φ_i x_i at fixed φ).
  k.G = R.transpose() * nn;
  k.H = R.transpose() * DN - (E1.transpose() * nn) * Xi.row(0) - (E2.transpose() * nn) * Xi.row(1);
  // Tangential relative displacement u_t = P w, w = Σ φ_i u_i − Σ N_a u_a (the slip over the
  // target's material, small sliding): Δw = R Δu − (Σ N_a,β u_a) Δξ^β, ΔP w = −(n·w) Δn − n (w·Δn).
  Vec3 w = us, b1 = Vec3::Zero(), b2 = Vec3::Zero();
  for (int a = 0; a < m; ++a) {
    w -= p.s.N[a] * um[a];
    b1 += p.s.dN[a][0] * um[a];
    b2 += p.s.dN[a][1] * um[a];
  }
  k.T = P * (R - b1 * Xi.row(0) - b2 * Xi.row(1)) - nn.dot(w) * DN - nn * (w.transpose() * DN);
  k.normal = nn;
  k.gap = nn.dot(p.r) - offset_;
  k.ut = P * w;
  return k;
}

RigidGaussPoint::RigidGaussPoint(const char* family, int id, int pilot,
                                 const std::vector<int>& corners, const Vec3& xs,
                                 std::vector<double> phi,
                                 std::shared_ptr<const TargetSurface> target, double reach,
                                 double offset, const ContactLawData& data)
    : ContactPoint(id, translation_dofs(with_pilot(pilot, corners)), data),
      family_(family),
      xs_(xs),
      phi_(std::move(phi)),
      target_(std::move(target)),
      reach_(reach),
      offset_(offset) {
  initialize();
}

Vec3 RigidGaussPoint::relative(const Eigen::VectorXd& u) const {
  Vec3 d = -u.segment<3>(0);
  for (std::size_t i = 0; i < phi_.size(); ++i)
    d += phi_[i] * u.segment<3>(3 * static_cast<Eigen::Index>(i + 1));
  return d;
}

bool RigidGaussPoint::locate(const Eigen::VectorXd& u) {
  const Vec3 d = relative(u);
  const auto hit = target_->closest(xs_ + d, reach_);
  if (!hit) return false;
  data_.normal = hit->normal;
  data_.gap0 = hit->gap - offset_ - hit->normal.dot(d);
  return true;
}

ContactKinematics RigidGaussPoint::kinematics(const Eigen::VectorXd& u) const {
  // g = g₀ + n·(Σ φ_i u_i − u_pilot): the point law of a contact node (ContactPoint) at x_s.
  ContactKinematics k;
  const Vec3 d = relative(u);
  const Vec3& n = data_.normal;
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - n * n.transpose();
  k.normal = n;
  k.gap = data_.gap0 + n.dot(d);
  k.ut = P * d;
  const Eigen::Index nd = n_dofs();
  k.G.resize(nd);
  k.T.resize(3, nd);
  k.G.head<3>() = -n;
  k.T.leftCols<3>() = -P;
  for (std::size_t i = 0; i < phi_.size(); ++i) {
    const auto c = 3 * static_cast<Eigen::Index>(i + 1);
    k.G.segment<3>(c) = phi_[i] * n;
    k.T.middleCols<3>(c) = phi_[i] * P;
  }
  return k;
}

}  // namespace impactfe
