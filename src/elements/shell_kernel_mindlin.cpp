// Mindlin–Reissner bending and assumed transverse shear of the flat shell kernel (SHELL181):
// rotations interpolated independently of w with the corner shape functions, transverse shear
// strains from the MITC assumed covariant fields so that thin plates do not lock.
#include <Eigen/Dense>

#include <algorithm>

#include "elements/shell_kernel.h"

namespace impactfe::shell {

namespace {

constexpr double kXi[4] = {-1.0, 1.0, 1.0, -1.0};
constexpr double kEta[4] = {-1.0, -1.0, 1.0, 1.0};

/// Corner shape functions and their natural derivatives (row 0: ∂/∂ξ, row 1: ∂/∂η).
void natural_shape(int n, double xi, double eta, Eigen::VectorXd& N, Eigen::MatrixXd& dnat) {
  N.resize(n);
  dnat.resize(2, n);
  if (n == 3) {
    N << 1.0 - xi - eta, xi, eta;
    dnat << -1.0, 1.0, 0.0, -1.0, 0.0, 1.0;
    return;
  }
  for (int i = 0; i < 4; ++i) {
    N(i) = 0.25 * (1 + xi * kXi[i]) * (1 + eta * kEta[i]);
    dnat(0, i) = 0.25 * kXi[i] * (1 + eta * kEta[i]);
    dnat(1, i) = 0.25 * kEta[i] * (1 + xi * kXi[i]);
  }
}

}  // namespace

Eigen::Matrix2d FlatShellKernel::jacobian(double xi, double eta) const {
  Eigen::VectorXd N;
  Eigen::MatrixXd dnat;
  natural_shape(n_, xi, eta, N, dnat);
  Eigen::Matrix2d J = Eigen::Matrix2d::Zero();
  for (int i = 0; i < n_; ++i) {
    J.col(0) += dnat.col(i) * xy_[static_cast<std::size_t>(i)].x();
    J.col(1) += dnat.col(i) * xy_[static_cast<std::size_t>(i)].y();
  }
  return J;
}

void FlatShellKernel::bending_b(double xi, double eta, Eigen::MatrixXd& B) const {
  double detJ = 0.0;
  if (!data_.mindlin) {
    dk_curvature(xi, eta, B, detJ);
    return;
  }
  // β = (βx, βy) = Σ N_a (θy_a, −θx_a): u(z) = z βx, v(z) = z βy; κ = (βx,x, βy,y, βx,y + βy,x).
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  shape(xi, eta, N, dN, detJ);
  B.setZero(3, 3 * n_);
  for (int a = 0; a < n_; ++a) {
    B(0, 3 * a + 2) = dN(0, a);
    B(1, 3 * a + 1) = -dN(1, a);
    B(2, 3 * a + 2) = dN(1, a);
    B(2, 3 * a + 1) = -dN(0, a);
  }
}

Eigen::Matrix<double, 2, Eigen::Dynamic> FlatShellKernel::covariant_shear(double xi,
                                                                          double eta) const {
  // γξ = ∂w/∂ξ + βx ∂x/∂ξ + βy ∂y/∂ξ (and η), the covariant components of (γxz, γyz): with
  // J = [∂(x, y)/∂ξ; ∂(x, y)/∂η], (γξ, γη) = J (γxz, γyz).
  Eigen::VectorXd N;
  Eigen::MatrixXd dnat;
  natural_shape(n_, xi, eta, N, dnat);
  const Eigen::Matrix2d J = jacobian(xi, eta);
  Eigen::Matrix<double, 2, Eigen::Dynamic> G = Eigen::MatrixXd::Zero(2, 3 * n_);
  for (int a = 0; a < n_; ++a)
    for (int r = 0; r < 2; ++r) {
      G(r, 3 * a) = dnat(r, a);
      G(r, 3 * a + 1) = -N(a) * J(r, 1);  // βy = −θx
      G(r, 3 * a + 2) = N(a) * J(r, 0);   // βx = θy
    }
  return G;
}

void FlatShellKernel::shear_b(double xi, double eta, Eigen::MatrixXd& B) const {
  Eigen::Matrix<double, 2, Eigen::Dynamic> g(2, 3 * n_);
  if (n_ == 4) {
    // MITC4 (Bathe & Dvorkin 1985, eq. 8): γξ tied at the midpoints A (0, −1), C (0, 1) of the
    // sides η = ∓1 and linear in η; γη tied at D (−1, 0), B (1, 0) and linear in ξ.
    const auto A = covariant_shear(0.0, -1.0), C = covariant_shear(0.0, 1.0);
    const auto D = covariant_shear(-1.0, 0.0), Bm = covariant_shear(1.0, 0.0);
    g.row(0) = 0.5 * (1.0 - eta) * A.row(0) + 0.5 * (1.0 + eta) * C.row(0);
    g.row(1) = 0.5 * (1.0 - xi) * D.row(1) + 0.5 * (1.0 + xi) * Bm.row(1);
  } else {
    // MITC3 (Lee & Bathe 2004): a constant field plus the rotation c (s, −r), tied to the
    // tangential strain at the midpoint of each side: γr at (½, 0), γs at (0, ½), and
    // γs − γr (the tangent of the side r + s = 1) at (½, ½):
    // γr = γr⁽¹⁾ + c s, γs = γs⁽²⁾ − c r, c = γs⁽²⁾ − γr⁽¹⁾ − γs⁽³⁾ + γr⁽³⁾.
    const auto e1 = covariant_shear(0.5, 0.0), e2 = covariant_shear(0.0, 0.5);
    const auto e3 = covariant_shear(0.5, 0.5);
    const Eigen::RowVectorXd c = e2.row(1) - e1.row(0) - e3.row(1) + e3.row(0);
    g.row(0) = e1.row(0) + eta * c;
    g.row(1) = e2.row(1) - xi * c;
  }
  B = jacobian(xi, eta).inverse() * g;
}

void FlatShellKernel::add_shear(Eigen::MatrixXd& K) const {
  const double G = data_.E / (2.0 * (1.0 + data_.nu));
  Eigen::VectorXd N;
  Eigen::MatrixXd dN, Bs;
  double detJ = 0.0;
  // MITC3's linear rotations cannot follow every Kirchhoff mode of a thin mesh (Lee & Bathe
  // 2004 call it 'still somewhat stiff'; MITC3+ adds a cubic bubble for this). The triangle
  // takes the stabilisation of Lyly, Stenberg & Vihinen (1993): the shear stiffness times
  // t² / (t² + α h²), h the longest side, α = 0.1, which unlocks thin meshes and tends to 1 as
  // the mesh is refined (h → 0) or the plate thickens.
  double stabilise_h2 = 0.0;
  if (n_ == 3)
    for (int k = 0; k < 3; ++k)
      stabilise_h2 = std::max(stabilise_h2, (xy_[static_cast<std::size_t>(k)] -
                                             xy_[static_cast<std::size_t>((k + 1) % 3)])
                                                .squaredNorm());
  constexpr double kAlpha = 0.1;
  Eigen::MatrixXd Ks = Eigen::MatrixXd::Zero(3 * n_, 3 * n_);
  for (const auto& p : points()) {
    shape(p.xi, p.eta, N, dN, detJ);
    shear_b(p.xi, p.eta, Bs);
    // D_s = k G t (Mindlin 1951; k = 5/6, Reissner 1945).
    const double t = thickness_at(N);
    const double stab = t * t / (t * t + kAlpha * stabilise_h2);
    if (data_.laminate)
      Ks += stab * Bs.transpose() * data_.laminate->shear * Bs * detJ * p.w;
    else
      Ks += stab * data_.shear_factor * G * t * Bs.transpose() * Bs * detJ * p.w;
  }
  for (int a = 0; a < n_; ++a)
    for (int b = 0; b < n_; ++b)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) K(6 * a + 2 + i, 6 * b + 2 + j) += Ks(3 * a + i, 3 * b + j);
}

}  // namespace impactfe::shell
