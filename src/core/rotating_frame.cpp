#include "core/rotating_frame.h"

#include <Eigen/Geometry>

namespace impactfe {

namespace {
/// [v]×: the matrix of the cross product v × x.
Mat3 cross_matrix(const Vec3& v) {
  Mat3 m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}
}  // namespace

LinearAccelerationField rotational_acceleration(const RotationalLoads& loads) {
  const Mat3 w = cross_matrix(loads.omega);
  const Mat3 dw = cross_matrix(loads.domega);
  const Mat3 cw = cross_matrix(loads.cg_omega);
  const Mat3 dcw = cross_matrix(loads.cg_domega);
  // Transport acceleration of the frame about c (the part in c is the constant term), Coriolis
  // acceleration of the relative velocity ω×x, and the relative acceleration ω̇×x + ω×(ω×x).
  const Mat3 transport = dcw + cw * cw;
  LinearAccelerationField field;
  field.gradient = transport + 2.0 * cw * w + dw + w * w;
  field.at_origin = -(transport * loads.cg_location);
  field.angular = loads.domega + loads.cg_domega + loads.cg_omega.cross(loads.omega);
  return field;
}

}  // namespace impactfe
