// Uniform reduced integration of the 4-node PLANE182 (KEYOPT(1) = 1, elements/plane_solid.h):
// the stabilisation ("hourglass") stiffness that the one-point quadrature at the centre leaves
// out. MAPDL documents the technique (Flanagan & Belytschko 1981) and the one stiffness point,
// not its hourglass coefficient; the choice here is the physical stabilisation of Belytschko &
// Bindeman (1991): the energy of the strain that varies over the element, with the
// incompatible bending modes relaxing its parasitic shear (docs/elements/plane182.md).
#include <Eigen/Dense>

#include "elements/plane_solid.h"

namespace impactfe {

void PlaneSolid::form_hourglass() {
  // The one point: the element's mean strain B̄ = ∫ B dV / V over the whole volume V (2x2 Gauss,
  // exact for the bilinear element, also with the radius), Flanagan & Belytschko's "uniform
  // strain"; in plane stress and plane strain B̄ is B at the centre (their eq. (17)), in
  // axisymmetry it differs, and with it the constant-stress patch test stays exact there.
  // Stabilisation: K_hg = Σ_q dV_q (B_q − B̄ + G_q α)ᵀ D (B_q − B̄ + G_q α), α condensed
  // (minimising the energy), over the 2x2 points, G_q the incompatible modes of mode_matrix()
  // with their mean removed. Properties:
  //  * positive semi-definite (an energy of the elastic D, minimised over α);
  //  * zero on every linear displacement field, whose strain is the same at every point of the
  //    bilinear element (also u_r = a r, u_z = b z in axisymmetry): the patch test is that of
  //    the one point. In plane stress and plane strain B_q − B̄ acts on u only through the
  //    hourglass amplitudes q_i = γ·u_i with Flanagan & Belytschko's vectors
  //    γ = h − (h·x) b_x − (h·y) b_y, h = (1, −1, 1, −1), orthogonal to the linear fields, so
  //    K_hg = Σ_ij c_ij γγᵀ has rank 2 (the two hourglass modes);
  //  * Σ_q dV_q (B_q − B̄ + G_q α) = 0, so the elastic K = V B̄ᵀ D B̄ + K_hg equals the
  //    incompatible-mode element's (KEYOPT(1) = 3): a rectangle bends exactly under a couple,
  //    without the shear locking of full 2x2 and without the softness of a small arbitrary
  //    hourglass coefficient (coefficient 1 on the elastic D: [A], MAPDL's is undocumented);
  //    the one-point character shows where the material is inelastic (one state);
  //  * in axisymmetry the varying hoop strain u_r / r is included, so that the rotation about
  //    the centre (zero mean hoop strain) is resisted too: only the axial translation is free.
  // The stiffness stays elastic when the point yields or creeps (the stiffness form of
  // Flanagan & Belytschko, scaled by the elastic moduli).
  const int n = 2 * static_cast<int>(nodes_.size());
  std::vector<Eigen::MatrixXd> bq;
  std::vector<Eigen::Matrix4d> g;
  std::vector<double> dv;
  Eigen::Matrix4d mean = Eigen::Matrix4d::Zero();
  mean_strain_ = Eigen::MatrixXd::Zero(4, n);
  double total = 0.0;
  for (const QuadraturePoint& q : gauss_square(2)) {
    const Eigen::Vector2d xi = q.xi.head<2>();
    const Point p = point_at(xi);
    dv.push_back(measure(p, q.weight));
    bq.push_back(strain_matrix(p));
    g.push_back(mode_matrix(p, xi));
    mean += dv.back() * g.back();
    mean_strain_ += dv.back() * bq.back();
    total += dv.back();
  }
  mean /= total;
  mean_strain_ /= total;
  Eigen::MatrixXd kuu = Eigen::MatrixXd::Zero(n, n), kau = Eigen::MatrixXd::Zero(4, n);
  Eigen::Matrix4d kaa = Eigen::Matrix4d::Zero();
  for (std::size_t q = 0; q < dv.size(); ++q) {
    const Eigen::MatrixXd db = bq[q] - mean_strain_;
    const Eigen::Matrix4d gq = g[q] - mean;
    kuu.noalias() += dv[q] * db.transpose() * d_ * db;
    kau.noalias() += dv[q] * gq.transpose() * d_ * db;
    kaa.noalias() += dv[q] * gq.transpose() * d_ * gq;
  }
  hourglass_ = kuu - kau.transpose() * kaa.ldlt().solve(kau);
  hourglass_ = 0.5 * (hourglass_ + hourglass_.transpose()).eval();
}

}  // namespace impactfe
