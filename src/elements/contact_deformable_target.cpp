/// A contact node against a deformable TARGE170 target (elements/target_surface.h
/// DeformableTargetPoint): candidate facets (fixed at setup with small sliding, re-found between
/// steps with large sliding), the search among them, and the node-to-segment kinematics with
/// their exact first and second variations.
#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "elements/hyper_dual.h"
#include "elements/so3.h"
#include "elements/target_surface.h"

namespace impactfe {

namespace {

/// The projection of x_s on the plane of the triangle x₁ x₂ x₃: barycentric N and the signed
/// distance along the unit normal.
struct Projection {
  Vec3 e1, e2, normal;
  double area2 = 0.0;  // |e₁ × e₂|
  double gap = 0.0;    // n·(x_s − x₁)
  Eigen::Matrix2d Minv;
  Eigen::Vector2d xi;
  std::array<double, 3> N{};
};

Projection project(const Vec3& xs, const Vec3& x1, const Vec3& x2, const Vec3& x3) {
  Projection p;
  p.e1 = x2 - x1;
  p.e2 = x3 - x1;
  const Vec3 a = p.e1.cross(p.e2);
  p.area2 = a.norm();
  p.normal = a / p.area2;
  const Vec3 d = xs - x1;
  p.gap = p.normal.dot(d);
  Eigen::Matrix2d M;
  M << p.e1.dot(p.e1), p.e1.dot(p.e2), p.e1.dot(p.e2), p.e2.dot(p.e2);
  p.Minv = M.inverse();
  p.xi = p.Minv * Eigen::Vector2d(p.e1.dot(d), p.e2.dot(d));
  p.N = {1.0 - p.xi(0) - p.xi(1), p.xi(0), p.xi(1)};
  return p;
}

/// u_t = (I − n nᵀ)(u_s − Σ N_a u_a) on the triangle x₁ x₂ x₃ as a function of the 12
/// displacements (u_s, u₁, u₂, u₃), for its exact second derivatives (the same construction as
/// project() and DeformableTargetPoint::kinematics, in second-order dual numbers).
ad::V3<12> tangential_displacement(const std::array<Vec3, 4>& x0,
                                   const Eigen::Matrix<double, 12, 1>& u) {
  using D = ad::Dual2<12>;
  using V = ad::V3<12>;
  std::array<V, 4> du, x;
  for (int i = 0; i < 4; ++i) {
    du[static_cast<std::size_t>(i)] = ad::variables<12>(Vec3::Zero(), u, 3 * i);
    x[static_cast<std::size_t>(i)] =
        ad::constant<12>(x0[static_cast<std::size_t>(i)]) + du[static_cast<std::size_t>(i)];
  }
  const V e1 = x[2] - x[1], e2 = x[3] - x[1], d = x[0] - x[1];
  const V a = ad::cross(e1, e2);
  const D inv_norm = ad::inverse(ad::sqrt(ad::dot(a, a)));
  const V n = inv_norm * a;
  // ξ = M⁻¹ (e_α·d), M_αβ = e_α·e_β (Cramer's rule).
  const D m11 = ad::dot(e1, e1), m12 = ad::dot(e1, e2), m22 = ad::dot(e2, e2);
  const D r1 = ad::dot(e1, d), r2 = ad::dot(e2, d);
  const D inv_det = ad::inverse(m11 * m22 - m12 * m12);
  const D xi1 = inv_det * (m22 * r1 - m12 * r2), xi2 = inv_det * (m11 * r2 - m12 * r1);
  const D n1 = D(1.0) - xi1 - xi2;
  const V w = du[0] - n1 * du[1] - xi1 * du[2] - xi2 * du[3];
  return w - ad::dot(n, w) * n;
}

}  // namespace

DeformableTargetPoint::DeformableTargetPoint(const char* family, int id, std::vector<int> nodes,
                                             std::vector<Vec3> x,
                                             std::shared_ptr<const TargetSurface> target,
                                             std::vector<int> facets, double reach, double offset,
                                             const ContactLawData& data, bool large_sliding)
    : ContactPoint(id, translation_dofs(nodes), data),
      family_(family),
      nodes_(std::move(nodes)),
      x_(std::move(x)),
      target_(std::move(target)),
      facets_(std::move(facets)),
      reach_(reach),
      offset_(offset),
      large_sliding_(large_sliding) {
  classify();
  initialize();
}

void DeformableTargetPoint::classify() {
  const auto& tris = target_->triangles();
  const auto is_candidate = [&](int f) {
    return std::find(facets_.begin(), facets_.end(), f) != facets_.end();
  };
  candidates_.clear();
  for (int f : facets_) {
    const auto& t = tris[static_cast<std::size_t>(f)];
    Candidate c;
    for (int a = 0; a < 3; ++a)
      c.local[static_cast<std::size_t>(a)] = static_cast<int>(
          std::find(nodes_.begin(), nodes_.end(), t.nodes[static_cast<std::size_t>(a)]) -
          nodes_.begin());
    // The facets sharing an edge with f lie within f's extent of its centroid (initial
    // configuration: the adjacency does not change with the deformation).
    const double extent = std::max({(t.b - t.a).norm(), (t.c - t.a).norm(), (t.c - t.b).norm()});
    const std::vector<int> around = target_->near((t.a + t.b + t.c) / 3.0, extent);
    for (std::size_t a = 0; a < 3; ++a) {
      const int i = t.nodes[(a + 1) % 3], j = t.nodes[(a + 2) % 3];
      for (int g : around) {
        if (g == f) continue;
        const auto& o = tris[static_cast<std::size_t>(g)].nodes;
        if (std::find(o.begin(), o.end(), i) != o.end() &&
            std::find(o.begin(), o.end(), j) != o.end())
          c.edge[a] = is_candidate(g) ? 1 : std::max(c.edge[a], 2);
      }
    }
    candidates_.push_back(c);
  }
}

bool DeformableTargetPoint::refresh_dofs(const Eigen::VectorXd& u, const NodePositions& positions) {
  if (!large_sliding_) return false;
  const int self = nodes_.front();
  const Vec3 xs = positions.at(self);
  const auto usable = [&](int f) {
    const auto& n = target_->triangles()[static_cast<std::size_t>(f)].nodes;
    return std::find(n.begin(), n.end(), self) == n.end();
  };
  bool covered = true;
  for (int f : target_->near_current(xs, reach_, positions))
    if (usable(f) && std::find(facets_.begin(), facets_.end(), f) == facets_.end()) covered = false;
  if (covered) return false;
  // Re-found over the margin, with the facet in use kept (its contact state continues on it).
  std::vector<int> facets;
  if (!facets_.empty()) facets.push_back(facet());
  for (int f : target_->near_current(xs, kLargeSlidingMargin * reach_, positions))
    if (usable(f) && std::find(facets.begin(), facets.end(), f) == facets.end())
      facets.push_back(f);
  std::vector<int> nodes = {self};
  std::vector<Vec3> x = {x_.front()};
  for (int f : facets) {
    const auto& t = target_->triangles()[static_cast<std::size_t>(f)];
    for (std::size_t k = 0; k < 3; ++k)
      if (std::find(nodes.begin(), nodes.end(), t.nodes[k]) == nodes.end()) {
        nodes.push_back(t.nodes[k]);
        x.push_back(k == 0 ? t.a : k == 1 ? t.b : t.c);
      }
  }
  (void)u;
  nodes_ = std::move(nodes);
  x_ = std::move(x);
  facets_ = std::move(facets);
  current_ = 0;
  classify();
  set_dofs(translation_dofs(nodes_));
  return true;
}

bool DeformableTargetPoint::locate(const Eigen::VectorXd& u) {
  if (facets_.empty()) return false;
  const auto pos = [&](int i) -> Vec3 {
    return x_[static_cast<std::size_t>(i)] + u.segment<3>(3 * i);
  };
  const Vec3 xs = pos(0);
  constexpr double eps = 1e-9;
  {
    // Hysteresis: the facet in use is kept while the node projects into it (with a slack of
    // 1e-6 of its size), so a node on the edge between two facets (a quadrilateral's diagonal)
    // does not switch normals from one iteration to the next.
    const Candidate& c = candidates_[static_cast<std::size_t>(current_)];
    const Projection p = project(xs, pos(c.local[0]), pos(c.local[1]), pos(c.local[2]));
    if (p.area2 > 0.0 && std::min({p.N[0], p.N[1], p.N[2]}) >= -1e-6)
      return std::abs(p.gap) <= reach_;
  }
  int best = -1, least = -1;
  double best_gap = 0.0, least_min = 0.0, least_gap = 0.0;
  for (std::size_t k = 0; k < candidates_.size(); ++k) {
    const Candidate& c = candidates_[k];
    const Projection p = project(xs, pos(c.local[0]), pos(c.local[1]), pos(c.local[2]));
    if (!(p.area2 > 0.0)) continue;
    const double lowest = std::min({p.N[0], p.N[1], p.N[2]});
    if (lowest >= -eps) {
      if (best < 0 || std::abs(p.gap) < std::abs(best_gap)) {
        best = static_cast<int>(k);
        best_gap = p.gap;
      }
    } else if (least < 0 || lowest > least_min) {
      least = static_cast<int>(k);
      least_min = lowest;
      least_gap = p.gap;
    }
  }
  if (best >= 0) {
    current_ = best;
    return std::abs(best_gap) <= reach_;
  }
  if (least >= 0 && std::abs(least_gap) <= reach_) {
    // Outside every candidate: across the edge opposite the most negative coordinate.
    const Candidate& c = candidates_[static_cast<std::size_t>(least)];
    const Projection p = project(xs, pos(c.local[0]), pos(c.local[1]), pos(c.local[2]));
    const auto a = static_cast<std::size_t>(std::min_element(p.N.begin(), p.N.end()) - p.N.begin());
    if (c.edge[a] == 1 || (c.edge[a] == 0 && p.N[a] >= -kTargetEdgeTolerance)) {
      // Between two candidates at a convex edge, or just beyond a free edge of the target (a
      // node on the rim of a target that deforms with it): the nearest facet, extended.
      current_ = least;
      return true;
    }
    if (c.edge[a] == 2 && large_sliding_)
      throw ElementSolutionError(
          id(), fmt::format("element {}: contact node {} slid across all its candidate target "
                            "facets within one substep (large sliding re-finds them between "
                            "substeps, over {} times the pinball): use smaller substeps "
                            "(NSUBST / DELTIM) or a larger pinball (real constant 6 PINB)",
                            id(), nodes_.front(), kLargeSlidingMargin));
    if (c.edge[a] == 2)
      throw ElementSolutionError(
          id(),
          fmt::format("element {}: contact node {} slid out of the target facets found within "
                      "its pinball at setup (small sliding [A]: the candidate facets of a node "
                      "against a deformable target are fixed when the model is built); enlarge "
                      "the pinball (real constant 6 PINB) to cover the sliding distance",
                      id(), nodes_.front()));
  }
  return false;
}

ContactKinematics DeformableTargetPoint::kinematics(const Eigen::VectorXd& u) const {
  const int n = n_dofs();
  ContactKinematics k;
  k.G = Eigen::VectorXd::Zero(n);
  k.T = Eigen::MatrixXd::Zero(3, n);
  if (facets_.empty()) {
    k.gap = reach_;  // never in reach: open for good
    return k;
  }
  const Candidate& c = candidates_[static_cast<std::size_t>(current_)];
  const std::array<int, 4> at = {0, c.local[0], c.local[1], c.local[2]};
  std::array<Vec3, 4> x, du;
  for (std::size_t i = 0; i < 4; ++i) {
    du[i] = u.segment<3>(3 * at[i]);
    x[i] = x_[static_cast<std::size_t>(at[i])] + du[i];
  }
  const Projection p = project(x[0], x[1], x[2], x[3]);
  const Vec3& nn = p.normal;
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d P = I - nn * nn.transpose();
  // Linear operators on the 12 coordinates (x_s, x₁, x₂, x₃): Δr = R Δx, Δe_α = E_α Δx.
  using M3x12 = Eigen::Matrix<double, 3, 12>;
  M3x12 R, E1, E2;
  R << I, -p.N[0] * I, -p.N[1] * I, -p.N[2] * I;
  E1 << Eigen::Matrix3d::Zero(), -I, I, Eigen::Matrix3d::Zero();
  E2 << Eigen::Matrix3d::Zero(), -I, Eigen::Matrix3d::Zero(), I;
  // Δn = (I − nnᵀ)(Δe₁ × e₂ + e₁ × Δe₂)/|e₁ × e₂|.
  const M3x12 DN = P * (-so3::spin(p.e2) * E1 + so3::spin(p.e1) * E2) / p.area2;
  // Δξ = M⁻¹ [e_α·Δr + g n·Δe_α] (differentiated projection condition e_α·(x_s − x_p) = 0).
  Eigen::Matrix<double, 2, 12> B;
  B.row(0) = p.e1.transpose() * R + p.gap * nn.transpose() * E1;
  B.row(1) = p.e2.transpose() * R + p.gap * nn.transpose() * E2;
  const Eigen::Matrix<double, 2, 12> Xi = p.Minv * B;
  const Eigen::Matrix<double, 12, 1> G = R.transpose() * nn;
  // Δδg = Δn·δr − Δξ_α n·δe_α.
  const Eigen::Matrix<double, 12, 12> H =
      R.transpose() * DN - (E1.transpose() * nn) * Xi.row(0) - (E2.transpose() * nn) * Xi.row(1);
  // u_t = P w, w = u_s − Σ N_a u_a: Δw = R Δu − (u₂ − u₁) Δξ₁ − (u₃ − u₁) Δξ₂ and
  // ΔP w = −(n·w) Δn − n (w·Δn).
  const Vec3 w = du[0] - p.N[0] * du[1] - p.N[1] * du[2] - p.N[2] * du[3];
  const M3x12 Tl = P * (R - (du[2] - du[1]) * Xi.row(0) - (du[3] - du[1]) * Xi.row(1)) -
                   nn.dot(w) * DN - nn * (w.transpose() * DN);
  k.normal = nn;
  k.gap = p.gap - offset_;
  k.ut = P * w;
  k.H = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < 4; ++i) {
    const int gi = 3 * at[static_cast<std::size_t>(i)];
    k.G.segment<3>(gi) += G.segment<3>(3 * i);
    k.T.middleCols<3>(gi) += Tl.middleCols<3>(3 * i);
    for (int j = 0; j < 4; ++j)
      k.H.block<3, 3>(gi, 3 * at[static_cast<std::size_t>(j)]) += H.block<3, 3>(3 * i, 3 * j);
  }
  return k;
}

}  // namespace impactfe

namespace impactfe {

void DeformableTargetPoint::add_friction_curvature(const Eigen::VectorXd& u, const Vec3& ft,
                                                   Eigen::MatrixXd& K) const {
  if (facets_.empty()) return;
  const Candidate& c = candidates_[static_cast<std::size_t>(current_)];
  const std::array<int, 4> at = {0, c.local[0], c.local[1], c.local[2]};
  std::array<Vec3, 4> x0;
  Eigen::Matrix<double, 12, 1> ul;
  for (std::size_t i = 0; i < 4; ++i) {
    x0[i] = x_[static_cast<std::size_t>(at[i])];
    ul.segment<3>(3 * static_cast<Eigen::Index>(i)) = u.segment<3>(3 * at[i]);
  }
  const ad::V3<12> ut = tangential_displacement(x0, ul);
  Eigen::Matrix<double, 12, 12> h = Eigen::Matrix<double, 12, 12>::Zero();
  for (int k = 0; k < 3; ++k) h += ft(k) * ut[static_cast<std::size_t>(k)].h;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      K.block<3, 3>(3 * at[static_cast<std::size_t>(i)], 3 * at[static_cast<std::size_t>(j)]) +=
          h.block<3, 3>(3 * i, 3 * j);
}

}  // namespace impactfe
