/// A contact node against a TARGE169 target (elements/target_line.h LineTargetPoint): the
/// segment search, the candidates of a deformable target (large sliding re-finds them between
/// steps) and the 2-D node-to-segment kinematics with their exact first and second variations.
#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "elements/hyper_dual.h"
#include "elements/target_line.h"
#include "elements/target_surface.h"

namespace impactfe {

namespace {

// Local variables of one evaluation: u_s (2), then u₁ (2) and u₂ (2) of a deformable segment,
// or the pilot's UX, UY and ROTZ.
constexpr int kLineVars = 6;
using LD = ad::Dual2<kLineVars>;  // a number with its gradient and Hessian over those variables
using LV = ad::V3<kLineVars>;     // a vector of them (z constant in 2-D)

struct SegmentGeometry {
  LD gap;
  LV normal, ut;
};

/// The in-plane vector c + (variables first, first + 1), z = c_z constant.
LV plane_vector(const Vec3& c, const Eigen::Matrix<double, kLineVars, 1>& q, int first) {
  return {LD::variable(c.x() + q(first), first), LD::variable(c.y() + q(first + 1), first + 1),
          LD(c.z())};
}

/// g = n·(x_s − x₁) − CNOF, u_t = t t·(u_s − (1 − ξ) u₁ − ξ u₂) on the segment x₁ x₂
/// (target_line.h), n = (t_y, −t_x).
SegmentGeometry on_segment(const LV& xs, const LV& us, const LV& x1, const LV& u1, const LV& x2,
                           const LV& u2, double offset) {
  const LV e = x2 - x1;
  const LD inv_length = ad::inverse(ad::sqrt(ad::dot(e, e)));
  const LV t = inv_length * e;
  SegmentGeometry g;
  g.normal = {t[1], -t[0], LD(0.0)};
  const LV d = xs - x1;
  g.gap = ad::dot(g.normal, d) - LD(offset);
  const LD xi = inv_length * ad::dot(t, d);
  const LV w = us - (LD(1.0) - xi) * u1 - xi * u2;
  g.ut = ad::dot(t, w) * t;
  return g;
}

/// The in-plane rotation R(θ) a (θ about +Z).
LV rotate_z(const LD& theta, const Vec3& a) {
  const LD c = ad::chain(theta, std::cos(theta.v), -std::sin(theta.v), -std::cos(theta.v));
  const LD s = ad::chain(theta, std::sin(theta.v), std::cos(theta.v), -std::sin(theta.v));
  return {a.x() * c - a.y() * s, a.x() * s + a.y() * c, LD(a.z())};
}

/// The geometry of the contact node (initially at `xs0`) on segment `seg` of `target` for the
/// local variables q (see kLineVars), with the segment's ends moved as the target moves.
SegmentGeometry evaluate(const LineTarget& target, const LineTarget::Segment& seg, const Vec3& xs0,
                         const Eigen::Matrix<double, kLineVars, 1>& q, double offset) {
  const LV us = plane_vector(Vec3::Zero(), q, 0);
  const LV xs = plane_vector(xs0, q, 0);
  switch (target.motion()) {
    case LineTarget::Motion::Fixed: {
      const LV zero = ad::constant<kLineVars>(Vec3::Zero());
      return on_segment(xs, us, ad::constant<kLineVars>(seg.a), zero,
                        ad::constant<kLineVars>(seg.b), zero, offset);
    }
    case LineTarget::Motion::Pilot: {
      // x_a = X_P + u_P + R(θ)(X_a − X_P), u_a = x_a − X_a.
      const Vec3& xp = target.pilot_position();
      const LV up = plane_vector(Vec3::Zero(), q, 2);
      const LD theta = target.rotates() ? LD::variable(q(4), 4) : LD(0.0);
      const LV x1 = ad::constant<kLineVars>(xp) + up + rotate_z(theta, seg.a - xp);
      const LV x2 = ad::constant<kLineVars>(xp) + up + rotate_z(theta, seg.b - xp);
      return on_segment(xs, us, x1, x1 - ad::constant<kLineVars>(seg.a), x2,
                        x2 - ad::constant<kLineVars>(seg.b), offset);
    }
    case LineTarget::Motion::Deformable:
      break;
  }
  return on_segment(xs, us, plane_vector(seg.a, q, 2), plane_vector(Vec3::Zero(), q, 2),
                    plane_vector(seg.b, q, 4), plane_vector(Vec3::Zero(), q, 4), offset);
}

}  // namespace

LineTargetPoint::LineTargetPoint(const char* family, int id, int node, const Vec3& x,
                                 std::shared_ptr<const LineTarget> target,
                                 std::vector<int> candidates, double reach, double offset,
                                 const ContactLawData& data, bool large_sliding)
    : ContactPoint(id, std::vector<DofKey>{}, data),
      family_(family),
      target_(std::move(target)),
      candidates_(std::move(candidates)),
      reach_(reach),
      offset_(offset),
      large_sliding_(large_sliding) {
  nodes_ = {node};
  x_ = {x};
  switch (target_->motion()) {
    case LineTarget::Motion::Fixed:
      break;
    case LineTarget::Motion::Pilot:
      nodes_.push_back(target_->pilot());
      x_.push_back(target_->pilot_position());
      break;
    case LineTarget::Motion::Deformable:
      for (int s : candidates_)
        for (std::size_t e = 0; e < 2; ++e) {
          const auto& seg = target_->segments()[static_cast<std::size_t>(s)];
          if (local(seg.nodes[e]) < 0) {
            nodes_.push_back(seg.nodes[e]);
            x_.push_back(e == 0 ? seg.a : seg.b);
          }
        }
      break;
  }
  if (target_->motion() != LineTarget::Motion::Deformable)
    for (std::size_t s = 0; s < target_->segments().size(); ++s)
      all_.push_back(static_cast<int>(s));
  set_dofs(dof_list());
  initialize();
}

int LineTargetPoint::local(int node) const {
  const auto it = std::find(nodes_.begin(), nodes_.end(), node);
  return it == nodes_.end() ? -1 : static_cast<int>(it - nodes_.begin());
}

std::vector<DofKey> LineTargetPoint::dof_list() const {
  std::vector<DofKey> out;
  for (int n : nodes_)
    for (Dof d : {Dof::UX, Dof::UY}) out.push_back({n, d});
  if (target_->motion() == LineTarget::Motion::Pilot && target_->rotates())
    out.push_back({target_->pilot(), Dof::ROTZ});
  return out;
}

const std::vector<int>& LineTargetPoint::searched() const {
  return target_->motion() == LineTarget::Motion::Deformable ? candidates_ : all_;
}

std::array<int, 6> LineTargetPoint::slots(int s) const {
  std::array<int, 6> out = {0, 1, -1, -1, -1, -1};
  switch (target_->motion()) {
    case LineTarget::Motion::Fixed:
      break;
    case LineTarget::Motion::Pilot:
      out[2] = 2;
      out[3] = 3;
      if (target_->rotates()) out[4] = 4;
      break;
    case LineTarget::Motion::Deformable: {
      const auto& seg = target_->segments()[static_cast<std::size_t>(s)];
      for (std::size_t e = 0; e < 2; ++e) {
        const int l = local(seg.nodes[e]);
        out[2 + 2 * e] = 2 * l;
        out[3 + 2 * e] = 2 * l + 1;
      }
      break;
    }
  }
  return out;
}

std::array<Vec3, 2> LineTargetPoint::ends(int s, const Eigen::VectorXd& u) const {
  const auto& seg = target_->segments()[static_cast<std::size_t>(s)];
  switch (target_->motion()) {
    case LineTarget::Motion::Fixed:
      return {seg.a, seg.b};
    case LineTarget::Motion::Pilot: {
      const Vec3 up(u(2), u(3), 0.0);
      const Vec3& xp = target_->pilot_position();
      if (!target_->rotates()) return {seg.a + up, seg.b + up};
      const double c = std::cos(u(4)), sn = std::sin(u(4));
      const auto turn = [&](const Vec3& a) {
        const Vec3 r = a - xp;
        return Vec3(xp.x() + up.x() + c * r.x() - sn * r.y(),
                    xp.y() + up.y() + sn * r.x() + c * r.y(), a.z());
      };
      return {turn(seg.a), turn(seg.b)};
    }
    case LineTarget::Motion::Deformable:
      break;
  }
  const int i = local(seg.nodes[0]), j = local(seg.nodes[1]);
  return {seg.a + Vec3(u(2 * i), u(2 * i + 1), 0.0), seg.b + Vec3(u(2 * j), u(2 * j + 1), 0.0)};
}

bool LineTargetPoint::locate(const Eigen::VectorXd& u) {
  const Vec3 xs = x_.front() + Vec3(u(0), u(1), 0.0);
  const auto project = [&](int s, double& xi, double& gap) {
    const auto [a, b] = ends(s, u);
    const Vec3 e = b - a;
    xi = (xs - a).dot(e) / e.squaredNorm();
    gap = LineTarget::normal(a, b).dot(xs - a);
  };
  double xi = 0.0, gap = 0.0;
  // Hysteresis: the segment in use is kept while the node projects onto it (a slack of 1e-6 of
  // its length), so a node at the joint of two segments does not switch between iterations.
  if (current_ >= 0) {
    project(current_, xi, gap);
    if (xi >= -1e-6 && xi <= 1.0 + 1e-6) return std::abs(gap) <= reach_;
  }
  constexpr double eps = 1e-9;
  int best = -1, least = -1;
  double best_gap = 0.0, least_excess = 0.0, least_xi = 0.0;
  for (int s : searched()) {
    project(s, xi, gap);
    if (std::abs(gap) > reach_) continue;
    if (xi >= -eps && xi <= 1.0 + eps) {
      if (best < 0 || std::abs(gap) < std::abs(best_gap)) {
        best = s;
        best_gap = gap;
      }
      continue;
    }
    const double excess = xi < 0.0 ? -xi : xi - 1.0;
    if (least < 0 || excess < least_excess) {
      least = s;
      least_excess = excess;
      least_xi = xi;
    }
  }
  if (best >= 0) {
    current_ = best;
    return true;
  }
  if (least < 0) return false;
  // Beyond the end of every segment: across the end the node is past.
  const auto& seg = target_->segments()[static_cast<std::size_t>(least)];
  const std::size_t end = least_xi < 0.0 ? 0 : 1;
  const int neighbour = seg.neighbour[end];
  const auto& pool = searched();
  const bool shared_with_searched =
      neighbour >= 0 && std::find(pool.begin(), pool.end(), neighbour) != pool.end();
  if (shared_with_searched || (neighbour < 0 && least_excess <= kTargetEdgeTolerance)) {
    // At a convex corner between two segments, or just past a free end: the nearest, extended.
    current_ = least;
    return true;
  }
  if (neighbour >= 0 && large_sliding_)  // a deformable target's segment, not a candidate
    throw ElementSolutionError(
        id(), fmt::format("element {}: contact node {} slid past all its candidate target "
                          "segments within one substep (large sliding re-finds them between "
                          "substeps): use smaller substeps (NSUBST / DELTIM) or a larger pinball "
                          "(real constant 6 PINB)",
                          id(), nodes_.front()));
  if (neighbour >= 0)
    throw ElementSolutionError(
        id(), fmt::format("element {}: contact node {} slid out of the target segments found "
                          "within its pinball at setup (small sliding, KEYOPT(18) = 1): enlarge "
                          "the pinball (real constant 6 PINB)",
                          id(), nodes_.front()));
  return false;
}

ContactKinematics LineTargetPoint::kinematics(const Eigen::VectorXd& u) const {
  const int n = n_dofs();
  ContactKinematics k;
  k.G = Eigen::VectorXd::Zero(n);
  k.T = Eigen::MatrixXd::Zero(3, n);
  k.H = Eigen::MatrixXd::Zero(n, n);
  if (current_ < 0) {
    // No segment found yet: out of reach, open.
    k.gap = reach_ + std::abs(offset_) + 1.0;
    return k;
  }
  const std::array<int, 6> slot = slots(current_);
  Eigen::Matrix<double, kLineVars, 1> q = Eigen::Matrix<double, kLineVars, 1>::Zero();
  for (int i = 0; i < kLineVars; ++i)
    if (slot[static_cast<std::size_t>(i)] >= 0) q(i) = u(slot[static_cast<std::size_t>(i)]);
  const SegmentGeometry g = evaluate(
      *target_, target_->segments()[static_cast<std::size_t>(current_)], x_.front(), q, offset_);
  k.gap = g.gap.v;
  for (int c = 0; c < 3; ++c) {
    k.normal(c) = g.normal[static_cast<std::size_t>(c)].v;
    k.ut(c) = g.ut[static_cast<std::size_t>(c)].v;
  }
  for (int i = 0; i < kLineVars; ++i) {
    const int a = slot[static_cast<std::size_t>(i)];
    if (a < 0) continue;
    k.G(a) += g.gap.g(i);
    for (int c = 0; c < 3; ++c) k.T(c, a) += g.ut[static_cast<std::size_t>(c)].g(i);
    for (int j = 0; j < kLineVars; ++j) {
      const int b = slot[static_cast<std::size_t>(j)];
      if (b >= 0) k.H(a, b) += g.gap.h(i, j);
    }
  }
  return k;
}

void LineTargetPoint::add_friction_curvature(const Eigen::VectorXd& u, const Vec3& ft,
                                             Eigen::MatrixXd& K) const {
  if (current_ < 0 || target_->motion() == LineTarget::Motion::Fixed) return;
  // The same evaluation as kinematics(), for the Hessians of u_t (cheap: 6 variables).
  const std::array<int, 6> slot = slots(current_);
  Eigen::Matrix<double, kLineVars, 1> q = Eigen::Matrix<double, kLineVars, 1>::Zero();
  for (int i = 0; i < kLineVars; ++i)
    if (slot[static_cast<std::size_t>(i)] >= 0) q(i) = u(slot[static_cast<std::size_t>(i)]);
  const SegmentGeometry g = evaluate(
      *target_, target_->segments()[static_cast<std::size_t>(current_)], x_.front(), q, offset_);
  Eigen::Matrix<double, kLineVars, kLineVars> h =
      Eigen::Matrix<double, kLineVars, kLineVars>::Zero();
  for (int c = 0; c < 3; ++c) h += ft(c) * g.ut[static_cast<std::size_t>(c)].h;
  for (int i = 0; i < kLineVars; ++i)
    for (int j = 0; j < kLineVars; ++j) {
      const int a = slot[static_cast<std::size_t>(i)], b = slot[static_cast<std::size_t>(j)];
      if (a >= 0 && b >= 0) K(a, b) += h(i, j);
    }
}

bool LineTargetPoint::refresh_dofs(const Eigen::VectorXd& u, const NodePositions& positions) {
  if (!updates_connectivity()) return false;
  (void)u;
  const int self = nodes_.front();
  const Vec3 xs = positions.at(self);
  const auto at = [&](int node, const Vec3&) { return Vec3(positions.at(node)); };
  const auto usable = [&](int s) {
    const auto& n = target_->segments()[static_cast<std::size_t>(s)].nodes;
    return n[0] != self && n[1] != self;
  };
  bool covered = true;
  for (int s : target_->near(xs, reach_, at))
    if (usable(s) && std::find(candidates_.begin(), candidates_.end(), s) == candidates_.end())
      covered = false;
  if (covered) return false;
  // Re-found over the margin, with the segment in use kept (its contact state continues on it).
  std::vector<int> segments;
  if (current_ >= 0) segments.push_back(current_);
  for (int s : target_->near(xs, kLargeSlidingMargin * reach_, at))
    if (usable(s) && std::find(segments.begin(), segments.end(), s) == segments.end())
      segments.push_back(s);
  nodes_.resize(1);
  x_.resize(1);
  for (int s : segments)
    for (std::size_t e = 0; e < 2; ++e) {
      const auto& seg = target_->segments()[static_cast<std::size_t>(s)];
      if (local(seg.nodes[e]) < 0) {
        nodes_.push_back(seg.nodes[e]);
        x_.push_back(e == 0 ? seg.a : seg.b);
      }
    }
  candidates_ = std::move(segments);
  set_dofs(dof_list());
  return true;
}

}  // namespace impactfe
