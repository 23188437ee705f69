/// A contact node against a rigid TARGE170 target moving with its pilot node
/// (elements/target_surface.h RigidTargetPoint): translating only (the point pair of
/// elements/contact_point.h), or turning with the pilot's rotation vector ψ, with the kinematics
/// differentiated exactly (elements/hyper_dual.h) for the force, the pilot's moment and the
/// consistent tangent including the rotation terms.
#include <Eigen/Dense>

#include "elements/hyper_dual.h"
#include "elements/so3.h"
#include "elements/target_surface.h"

namespace impactfe {

namespace {

std::vector<DofKey> rotating_dofs(int pilot, int node) {
  std::vector<DofKey> out;
  for (int n : {pilot, node})
    for (Dof d : {Dof::UX, Dof::UY, Dof::UZ}) out.push_back({n, d});
  for (Dof d : {Dof::ROTX, Dof::ROTY, Dof::ROTZ}) out.push_back({pilot, d});
  return out;
}

constexpr int kN = 9;  // pilot UX UY UZ, node UX UY UZ, pilot ROTX ROTY ROTZ
using D = ad::Dual2<kN>;
using V = ad::V3<kN>;

struct RotatingGeometry {
  D gap;
  V normal, ut;
};

/// g = n₀·y − c₀ − CNOF with y = X_P + R(ψ)ᵀ(x_s − x_P), n = R(ψ) n₀ and
/// u_t = (I − n nᵀ)(x_s − x_P − R(ψ)(X_s − X_P)) (target_surface.h).
RotatingGeometry rotating_geometry(const Eigen::VectorXd& u, const Vec3& xs0, const Vec3& xp0,
                                   const Vec3& n0, double c0) {
  const Eigen::Matrix<double, kN, 1> v = u.head<kN>();
  const V xp = ad::variables<kN>(xp0, v, 0), xs = ad::variables<kN>(xs0, v, 3);
  const V psi = ad::variables<kN>(Vec3::Zero(), v, 6);
  const V minus_psi = {-psi[0], -psi[1], -psi[2]};
  const V d = xs - xp;
  RotatingGeometry r;
  r.gap = ad::dot(n0, ad::rotate(minus_psi, d)) + D(n0.dot(xp0) - c0);
  r.normal = ad::rotate(psi, ad::constant<kN>(n0));
  const V q = d - ad::rotate(psi, ad::constant<kN>(xs0 - xp0));
  r.ut = q - ad::dot(r.normal, q) * r.normal;
  return r;
}

}  // namespace

RigidTargetPoint::RigidTargetPoint(const char* family, int id, int node, const Vec3& x,
                                   const Vec3& pilot_x, std::shared_ptr<const TargetSurface> target,
                                   double reach, double offset, const ContactLawData& data)
    : ContactPoint(id,
                   target->rotates() ? rotating_dofs(target->pilot(), node)
                                     : std::vector<DofKey>{{target->pilot(), Dof::UX},
                                                           {target->pilot(), Dof::UY},
                                                           {target->pilot(), Dof::UZ},
                                                           {node, Dof::UX},
                                                           {node, Dof::UY},
                                                           {node, Dof::UZ}},
                   data),
      family_(family),
      x_(x),
      pilot_x_(pilot_x),
      target_(std::move(target)),
      reach_(reach),
      offset_(offset),
      rotating_(target_->rotates()) {
  initialize();
}

bool RigidTargetPoint::locate(const Eigen::VectorXd& u) {
  const Vec3 d(u(3) - u(0), u(4) - u(1), u(5) - u(2));
  if (!rotating_) {
    const auto hit = target_->closest(x_ + d, reach_);
    if (!hit) return false;
    data_.normal = hit->normal;
    data_.gap0 = hit->gap - offset_ - hit->normal.dot(d);
    return true;
  }
  // The node in the target's initial frame: y = X_P + Rᵀ(x_s − x_P).
  const Eigen::Matrix3d R = so3::exp_map(u.segment<3>(6));
  const Vec3 y = pilot_x_ + R.transpose() * (x_ - pilot_x_ + d);
  const auto hit = target_->closest(y, reach_);
  if (!hit) return false;
  n0_ = hit->normal;
  c0_ = n0_.dot(y) - hit->gap;
  data_.normal = R * n0_;
  return true;
}

ContactKinematics RigidTargetPoint::kinematics(const Eigen::VectorXd& u) const {
  if (!rotating_) return ContactPoint::kinematics(u);
  const RotatingGeometry r = rotating_geometry(u, x_, pilot_x_, n0_, c0_ + offset_);
  ContactKinematics k;
  k.gap = r.gap.v;
  k.G = r.gap.g;
  k.H = r.gap.h;
  k.T.resize(3, kN);
  for (int c = 0; c < 3; ++c) {
    k.normal(c) = r.normal[c].v;
    k.ut(c) = r.ut[c].v;
    k.T.row(c) = r.ut[c].g.transpose();
  }
  return k;
}

void RigidTargetPoint::add_friction_curvature(const Eigen::VectorXd& u, const Vec3& ft,
                                              Eigen::MatrixXd& K) const {
  if (!rotating_) return;  // T = [−P, P] is constant
  const RotatingGeometry r = rotating_geometry(u, x_, pilot_x_, n0_, c0_ + offset_);
  for (int c = 0; c < 3; ++c) K += ft(c) * r.ut[c].h;
}

}  // namespace impactfe
