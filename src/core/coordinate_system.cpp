#include "core/coordinate_system.h"

#include <algorithm>
#include <cmath>

namespace impactfe {

namespace {

constexpr double kDeg = M_PI / 180.0;

Mat3 rot_x(double a) {
  const double c = std::cos(a), s = std::sin(a);
  Mat3 r;
  r << 1, 0, 0, 0, c, -s, 0, s, c;
  return r;
}
Mat3 rot_y(double a) {
  const double c = std::cos(a), s = std::sin(a);
  Mat3 r;
  r << c, 0, s, 0, 1, 0, -s, 0, c;
  return r;
}
Mat3 rot_z(double a) {
  const double c = std::cos(a), s = std::sin(a);
  Mat3 r;
  r << c, -s, 0, s, c, 0, 0, 0, 1;
  return r;
}

}  // namespace

Mat3 rotation_from_angles(const Vec3& angles_deg) {
  return rot_z(angles_deg(0) * kDeg) * rot_x(angles_deg(1) * kDeg) * rot_y(angles_deg(2) * kDeg);
}

Vec3 angles_from_rotation(const Mat3& r) {
  // R = Rz(a) Rx(b) Ry(c): R(2,1) = sin b, R(0,1) = −sin a cos b, R(1,1) = cos a cos b,
  // R(2,0) = −cos b sin c, R(2,2) = cos b cos c.
  const double sb = std::clamp(r(2, 1), -1.0, 1.0);
  const double b = std::asin(sb);
  double a = 0.0, c = 0.0;
  if (std::abs(sb) < 1.0 - 1e-12) {
    a = std::atan2(-r(0, 1), r(1, 1));
    c = std::atan2(-r(2, 0), r(2, 2));
  } else {
    // cos b = 0: only a ± c is defined; take c = 0, then R(0,0) = cos a, R(1,0) = sin a.
    a = std::atan2(r(1, 0), r(0, 0));
  }
  return Vec3(a, b, c) / kDeg;
}

Vec3 CoordinateSystem::to_global(const Vec3& c) const {
  Vec3 local;
  switch (kind) {
    case CsysKind::Cartesian:
      local = c;
      break;
    case CsysKind::Cylindrical:
      local = Vec3(c(0) * std::cos(c(1) * kDeg), c(0) * std::sin(c(1) * kDeg), c(2));
      break;
    case CsysKind::Spherical: {
      const double t = c(1) * kDeg, p = c(2) * kDeg;
      local = c(0) * Vec3(std::cos(p) * std::cos(t), std::cos(p) * std::sin(t), std::sin(p));
      break;
    }
  }
  return origin + axes * local;
}

Vec3 CoordinateSystem::from_global(const Vec3& x) const {
  const Vec3 l = axes.transpose() * (x - origin);
  switch (kind) {
    case CsysKind::Cartesian:
      return l;
    case CsysKind::Cylindrical:
      return Vec3(std::hypot(l(0), l(1)), std::atan2(l(1), l(0)) / kDeg, l(2));
    case CsysKind::Spherical: {
      const double rxy = std::hypot(l(0), l(1));
      return Vec3(l.norm(), std::atan2(l(1), l(0)) / kDeg, std::atan2(l(2), rxy) / kDeg);
    }
  }
  return l;
}

bool CoordinateSystem::axes_at(const Vec3& x, Mat3& out) const {
  out = axes;
  if (kind == CsysKind::Cartesian) return true;
  const Vec3 l = axes.transpose() * (x - origin);
  const double rxy = std::hypot(l(0), l(1));
  const double scale = std::max({1.0, l.norm(), origin.norm()});
  if (rxy <= 1e-12 * scale) return false;
  const double ct = l(0) / rxy, st = l(1) / rxy;
  Mat3 local;
  if (kind == CsysKind::Cylindrical) {
    local << ct, -st, 0, st, ct, 0, 0, 0, 1;
  } else {
    const double r = l.norm();
    const double cp = rxy / r, sp = l(2) / r;
    // Columns: e_R, e_θ, e_φ (right-handed: e_R × e_θ = e_φ).
    local << cp * ct, -st, -sp * ct, cp * st, ct, -sp * st, sp, 0, cp;
  }
  out = axes * local;
  return true;
}

CoordinateSystem WorkingPlane::as_system() const {
  return CoordinateSystem{polar ? CsysKind::Cylindrical : CsysKind::Cartesian, origin, axes};
}

CoordinateSystems::CoordinateSystems() {
  systems_[0] = CoordinateSystem{};
  systems_[1] = CoordinateSystem{CsysKind::Cylindrical, Vec3::Zero(), Mat3::Identity()};
  systems_[2] = CoordinateSystem{CsysKind::Spherical, Vec3::Zero(), Mat3::Identity()};
  // CSYS 5: axis +Y, θ = 0 along +X, local y = −Z. CSYS 6: axis +X, θ = 0 along +Y.
  Mat3 y_axis, x_axis;
  y_axis << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  x_axis << 0, 0, 1, 1, 0, 0, 0, 1, 0;
  systems_[5] = CoordinateSystem{CsysKind::Cylindrical, Vec3::Zero(), y_axis};
  systems_[6] = CoordinateSystem{CsysKind::Cylindrical, Vec3::Zero(), x_axis};
}

CoordinateSystem CoordinateSystems::get(int id) const {
  if (id == 4) return working_plane.as_system();
  return systems_.at(id);
}

bool CoordinateSystems::remove(int id) {
  if (id <= 10) return false;
  return systems_.erase(id) != 0;
}

}  // namespace impactfe
