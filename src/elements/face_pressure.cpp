#include "elements/face_pressure.h"

#include <Eigen/Geometry>  // cross product

namespace impactfe {

std::array<Vec3, 4> bilinear_face_pressure_forces(const std::array<Vec3, 4>& x,
                                                  const std::array<double, 4>& p) {
  static const double g[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
  static const double w[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  static const double xi_a[4] = {-1, 1, 1, -1}, eta_a[4] = {-1, -1, 1, 1};
  std::array<Vec3, 4> f;
  f.fill(Vec3::Zero());
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double n[4];
      Vec3 dxi = Vec3::Zero(), deta = Vec3::Zero();
      double pressure = 0.0;
      for (std::size_t a = 0; a < 4; ++a) {
        n[a] = 0.25 * (1 + xi_a[a] * g[i]) * (1 + eta_a[a] * g[j]);
        dxi += 0.25 * xi_a[a] * (1 + eta_a[a] * g[j]) * x[a];
        deta += 0.25 * eta_a[a] * (1 + xi_a[a] * g[i]) * x[a];
        pressure += n[a] * p[a];
      }
      const Vec3 normal = dxi.cross(deta);
      for (std::size_t a = 0; a < 4; ++a) f[a] += w[i] * w[j] * n[a] * pressure * normal;
    }
  return f;
}

}  // namespace impactfe
