#include "explicit/rigid_body.h"

#include <Eigen/Eigenvalues>

namespace impactfe {

std::array<bool, 3> rigid_constraint_axes(int code) {
  switch (code) {
    case 1:
      return {true, false, false};
    case 2:
      return {false, true, false};
    case 3:
      return {false, false, true};
    case 4:
      return {true, true, false};
    case 5:
      return {false, true, true};
    case 6:
      return {true, false, true};
    case 7:
      return {true, true, true};
    default:
      return {false, false, false};
  }
}

void set_rigid_body_inertia(RigidBody& body, const std::vector<double>& mass,
                            const std::vector<double>& x0, const std::vector<double>& y0,
                            const std::vector<double>& z0, const Eigen::Matrix3d& second_moment) {
  body.mass = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  for (std::size_t n : body.nodes) {
    body.mass += mass[n];
    first += mass[n] * Eigen::Vector3d(x0[n], y0[n], z0[n]);
  }
  body.centre0 = body.mass > 0.0 ? Eigen::Vector3d(first / body.mass) : Eigen::Vector3d::Zero();
  body.offsets.clear();
  for (std::size_t n : body.nodes)
    body.offsets.push_back(Eigen::Vector3d(x0[n], y0[n], z0[n]) - body.centre0);
  const Eigen::Matrix3d s = second_moment - body.mass * body.centre0 * body.centre0.transpose();
  body.inertia0 = s.trace() * Eigen::Matrix3d::Identity() - s;
}

Eigen::Vector3d rigid_angular_acceleration(const Eigen::Matrix3d& inertia,
                                           const Eigen::Vector3d& moment,
                                           const std::array<bool, 3>& fixed) {
  // The free axes' block of J: fixed rows and columns become identity rows with zero moment.
  Eigen::Matrix3d J = inertia;
  Eigen::Vector3d m = moment;
  for (int i = 0; i < 3; ++i)
    if (fixed[static_cast<std::size_t>(i)]) {
      J.row(i).setZero();
      J.col(i).setZero();
      J(i, i) = 1.0;
      m(i) = 0.0;
    }
  // J is symmetric positive semi-definite: invert it on the directions that carry inertia.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(J);
  const double largest = eig.eigenvalues().cwiseAbs().maxCoeff();
  Eigen::Vector3d alpha = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    const double lambda = eig.eigenvalues()(k);
    if (lambda > 1e-12 * largest) {
      const Eigen::Vector3d q = eig.eigenvectors().col(k);
      alpha += q * (q.dot(m) / lambda);
    }
  }
  for (int i = 0; i < 3; ++i)
    if (fixed[static_cast<std::size_t>(i)]) alpha(i) = 0.0;
  return alpha;
}

}  // namespace impactfe
