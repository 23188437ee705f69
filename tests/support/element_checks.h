#pragma once
/// Test support: checks shared by the element unit tests.
#include <Eigen/Core>

#include "elements/element.h"

namespace impactfe::testing {

/// Central finite-difference derivative of the internal force, d f_int / d u, at u (step h).
inline Eigen::MatrixXd fd_tangent(const Element& e, const ElementContext& ctx,
                                  const Eigen::VectorXd& u, double h) {
  const int n = e.n_dofs();
  Eigen::MatrixXd K(n, n), Kd;
  Eigen::VectorXd fp, fm;
  for (int j = 0; j < n; ++j) {
    Eigen::VectorXd up = u, um = u;
    up(j) += h;
    um(j) -= h;
    e.tangent(ctx, up, Kd, fp);
    e.tangent(ctx, um, Kd, fm);
    K.col(j) = (fp - fm) / (2.0 * h);
  }
  return K;
}

}  // namespace impactfe::testing
