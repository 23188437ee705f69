#include "elements/shell_kernel.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace impactfe::shell {

namespace {

constexpr double kXiQ[4] = {-1.0, 1.0, 1.0, -1.0};
constexpr double kEtaQ[4] = {-1.0, -1.0, 1.0, 1.0};

/// Corner (quadratic) and midside shape functions of the DK rotation fields, value and natural
/// derivatives: out[0..n) corners, out[n..2n) midside of side k (corner k → corner k+1).
/// Triangle: 6-node quadratic (Batoz et al. 1980 eq. 14); quad: 8-node serendipity (Batoz &
/// Ben Tahar 1982).
void dk_shape(int n, double xi, double eta, double* val, double* dxi, double* deta) {
  if (n == 3) {
    const double L = 1.0 - xi - eta;
    val[0] = L * (2 * L - 1), dxi[0] = -(4 * L - 1), deta[0] = -(4 * L - 1);
    val[1] = xi * (2 * xi - 1), dxi[1] = 4 * xi - 1, deta[1] = 0.0;
    val[2] = eta * (2 * eta - 1), dxi[2] = 0.0, deta[2] = 4 * eta - 1;
    val[3] = 4 * xi * L, dxi[3] = 4 * L - 4 * xi, deta[3] = -4 * xi;     // side 1-2
    val[4] = 4 * xi * eta, dxi[4] = 4 * eta, deta[4] = 4 * xi;           // side 2-3
    val[5] = 4 * eta * L, dxi[5] = -4 * eta, deta[5] = 4 * L - 4 * eta;  // side 3-1
    return;
  }
  for (int i = 0; i < 4; ++i) {
    const double a = kXiQ[i], b = kEtaQ[i];
    val[i] = 0.25 * (1 + xi * a) * (1 + eta * b) * (xi * a + eta * b - 1);
    dxi[i] = 0.25 * a * (1 + eta * b) * (2 * xi * a + eta * b);
    deta[i] = 0.25 * b * (1 + xi * a) * (xi * a + 2 * eta * b);
  }
  val[4] = 0.5 * (1 - xi * xi) * (1 - eta), dxi[4] = -xi * (1 - eta),
  deta[4] = -0.5 * (1 - xi * xi);
  val[5] = 0.5 * (1 + xi) * (1 - eta * eta), dxi[5] = 0.5 * (1 - eta * eta),
  deta[5] = -eta * (1 + xi);
  val[6] = 0.5 * (1 - xi * xi) * (1 + eta), dxi[6] = -xi * (1 + eta), deta[6] = 0.5 * (1 - xi * xi);
  val[7] = 0.5 * (1 - xi) * (1 - eta * eta), dxi[7] = -0.5 * (1 - eta * eta),
  deta[7] = -eta * (1 - xi);
}

}  // namespace

double plane_stress_von_mises(double sx, double sy, double sxy) {
  return std::sqrt(std::max(0.0, sx * sx - sx * sy + sy * sy + 3.0 * sxy * sxy));
}

Eigen::Matrix3d plane_stress(double nu, double scale) {
  Eigen::Matrix3d D;
  D << 1.0, nu, 0.0, nu, 1.0, 0.0, 0.0, 0.0, 0.5 * (1.0 - nu);
  return D * scale;
}

FlatShellKernel::FlatShellKernel(const std::vector<Eigen::Vector2d>& xy, const KernelData& data)
    : n_(static_cast<int>(xy.size())), data_(data), xy_(xy) {
  if (n_ != 3 && n_ != 4) throw std::invalid_argument("a shell facet has 3 or 4 corners");
  // Jacobian check and area.
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  double detJ = 0.0;
  for (const auto& p : points()) {
    shape(p.xi, p.eta, N, dN, detJ);
    if (!(detJ > 0.0))
      throw std::invalid_argument("non-positive Jacobian (zero area or bad shape)");
    area_ += detJ * p.w;
    volume_ += thickness_at(N) * detJ * p.w;
    total_mass_ += (data_.rho * thickness_at(N) + data_.added_mass) * detJ * p.w;
  }
  // DK side coefficients (Batoz et al. 1980 eq. 19 with x_ij = x_i − x_j).
  side_.resize(static_cast<std::size_t>(n_));
  for (int k = 0; k < n_; ++k) {
    const Eigen::Vector2d d =
        xy_[static_cast<std::size_t>(k)] - xy_[static_cast<std::size_t>((k + 1) % n_)];
    const double l2 = d.squaredNorm();
    side_[static_cast<std::size_t>(k)] = {
        -d.x() / l2, 0.75 * d.x() * d.y() / l2, (0.25 * d.x() * d.x() - 0.5 * d.y() * d.y()) / l2,
        -d.y() / l2, (0.25 * d.y() * d.y() - 0.5 * d.x() * d.x()) / l2};
  }
  set_centroid_data();
}

void FlatShellKernel::set_centroid_data() {
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  double detJ = 0.0;
  const double c = n_ == 3 ? 1.0 / 3.0 : 0.0;
  shape(c, c, N, dN, detJ);
  Bm0_.setZero(3, 2 * n_);
  for (int a = 0; a < n_; ++a) {
    Bm0_(0, 2 * a) = dN(0, a);
    Bm0_(1, 2 * a + 1) = dN(1, a);
    Bm0_(2, 2 * a) = dN(1, a);
    Bm0_(2, 2 * a + 1) = dN(0, a);
  }
  bending_b(c, c, Bb0_);
  if (data_.mindlin) shear_b(c, c, Bs0_);
  n_modes_ = n_ == 4 && data_.extra_shapes ? 4 : 0;
  if (n_modes_ == 0) return;
  shape(0.0, 0.0, N, dN, detJ0_);
  // J0⁻¹ from the bilinear map at the centre (Taylor, Beresford & Wilson 1976).
  Eigen::Matrix2d J0 = Eigen::Matrix2d::Zero();
  for (int i = 0; i < 4; ++i) {
    J0(0, 0) += 0.25 * kXiQ[i] * xy_[static_cast<std::size_t>(i)].x();
    J0(0, 1) += 0.25 * kXiQ[i] * xy_[static_cast<std::size_t>(i)].y();
    J0(1, 0) += 0.25 * kEtaQ[i] * xy_[static_cast<std::size_t>(i)].x();
    J0(1, 1) += 0.25 * kEtaQ[i] * xy_[static_cast<std::size_t>(i)].y();
  }
  J0i_ = J0.inverse();
}

Eigen::MatrixXd FlatShellKernel::stiffness() const {
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(6 * n_, 6 * n_);
  if (data_.membrane) add_membrane(K);
  // The drilling term also stiffens θz when the membrane is switched off, so the element stays
  // regular; it still vanishes for rigid in-plane rotations.
  add_drilling(K);
  if (data_.bending) add_bending(K);
  if (data_.bending && data_.mindlin) add_shear(K);
  add_foundation(K);
  return K;
}

Eigen::MatrixXd FlatShellKernel::elastic_extra() const {
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(6 * n_, 6 * n_);
  add_drilling(K);
  // Transverse shear stays elastic under plasticity (the J2 layers are plane stress).
  if (data_.bending && data_.mindlin) add_shear(K);
  add_foundation(K);
  return K;
}

void FlatShellKernel::add_foundation(Eigen::MatrixXd& K) const {
  if (data_.efs > 0.0)
    for (int a = 0; a < n_; ++a) K(6 * a + 2, 6 * a + 2) += data_.efs * area_ / n_;
}

std::vector<FlatShellKernel::Point> FlatShellKernel::points() const {
  if (n_ == 3) {
    const double w = 1.0 / 6.0;  // reference triangle area 1/2, three interior points (degree 2)
    return {{1.0 / 6.0, 1.0 / 6.0, w}, {2.0 / 3.0, 1.0 / 6.0, w}, {1.0 / 6.0, 2.0 / 3.0, w}};
  }
  const double g = 1.0 / std::sqrt(3.0);
  return {{-g, -g, 1.0}, {g, -g, 1.0}, {g, g, 1.0}, {-g, g, 1.0}};
}

void FlatShellKernel::shape(double xi, double eta, Eigen::VectorXd& N, Eigen::MatrixXd& dN_dx,
                            double& detJ) const {
  Eigen::MatrixXd dnat(2, n_);
  N.resize(n_);
  if (n_ == 3) {
    N << 1.0 - xi - eta, xi, eta;
    dnat << -1.0, 1.0, 0.0, -1.0, 0.0, 1.0;
  } else {
    for (int i = 0; i < 4; ++i) {
      N(i) = 0.25 * (1 + xi * kXiQ[i]) * (1 + eta * kEtaQ[i]);
      dnat(0, i) = 0.25 * kXiQ[i] * (1 + eta * kEtaQ[i]);
      dnat(1, i) = 0.25 * kEtaQ[i] * (1 + xi * kXiQ[i]);
    }
  }
  Eigen::Matrix2d J = Eigen::Matrix2d::Zero();
  for (int i = 0; i < n_; ++i) {
    J(0, 0) += dnat(0, i) * xy_[static_cast<std::size_t>(i)].x();
    J(0, 1) += dnat(0, i) * xy_[static_cast<std::size_t>(i)].y();
    J(1, 0) += dnat(1, i) * xy_[static_cast<std::size_t>(i)].x();
    J(1, 1) += dnat(1, i) * xy_[static_cast<std::size_t>(i)].y();
  }
  detJ = J.determinant();
  dN_dx = J.inverse() * dnat;
}

double FlatShellKernel::thickness_at(const Eigen::VectorXd& N) const {
  double t = 0.0;
  for (int i = 0; i < n_; ++i) t += N(i) * data_.t[static_cast<std::size_t>(i)];
  return t;
}

void FlatShellKernel::dk_fields(const double* f, Eigen::VectorXd& Hx, Eigen::VectorXd& Hy) const {
  // βx = Hx·U, βy = Hy·U, U = (w, θx, θy) per corner. At a corner β = (θy, −θx); at a midside
  // the tangential rotation comes from the cubic w along the side and the normal one is the
  // mean of the corners (Batoz et al. 1980 eqs. 17–20, same construction for DKQ).
  Hx.setZero(3 * n_);
  Hy.setZero(3 * n_);
  for (int i = 0; i < n_; ++i) {
    Hx(3 * i + 2) += f[i];
    Hy(3 * i + 1) -= f[i];
  }
  for (int k = 0; k < n_; ++k) {
    const auto& s = side_[static_cast<std::size_t>(k)];
    const double M = f[n_ + k];
    const int i = k, j = (k + 1) % n_;
    Hx(3 * i) += 1.5 * s[0] * M;
    Hx(3 * j) -= 1.5 * s[0] * M;
    Hy(3 * i) += 1.5 * s[3] * M;
    Hy(3 * j) -= 1.5 * s[3] * M;
    for (int node : {i, j}) {
      Hx(3 * node + 1) += s[1] * M;
      Hx(3 * node + 2) -= s[2] * M;
      Hy(3 * node + 1) += s[4] * M;
      Hy(3 * node + 2) -= s[1] * M;
    }
  }
}

void FlatShellKernel::dk_rotations(double xi, double eta, Eigen::VectorXd& Hx,
                                   Eigen::VectorXd& Hy) const {
  double v[8], dx[8], de[8];
  dk_shape(n_, xi, eta, v, dx, de);
  dk_fields(v, Hx, Hy);
}

void FlatShellKernel::dk_curvature(double xi, double eta, Eigen::MatrixXd& B, double& detJ) const {
  double v[8], dxi[8], deta[8];
  dk_shape(n_, xi, eta, v, dxi, deta);
  Eigen::VectorXd Hx_xi, Hy_xi, Hx_eta, Hy_eta;
  dk_fields(dxi, Hx_xi, Hy_xi);
  dk_fields(deta, Hx_eta, Hy_eta);
  // Jacobian of the (bi)linear geometry map.
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  shape(xi, eta, N, dN, detJ);
  Eigen::Matrix2d J = Eigen::Matrix2d::Zero();
  // Rebuild J⁻¹ from dN/dx: for the linear map, [∂/∂x; ∂/∂y] = J⁻¹ [∂/∂ξ; ∂/∂η].
  Eigen::MatrixXd dnat(2, n_);
  if (n_ == 3) {
    dnat << -1.0, 1.0, 0.0, -1.0, 0.0, 1.0;
  } else {
    for (int i = 0; i < 4; ++i) {
      dnat(0, i) = 0.25 * kXiQ[i] * (1 + eta * kEtaQ[i]);
      dnat(1, i) = 0.25 * kEtaQ[i] * (1 + xi * kXiQ[i]);
    }
  }
  for (int i = 0; i < n_; ++i) {
    J(0, 0) += dnat(0, i) * xy_[static_cast<std::size_t>(i)].x();
    J(0, 1) += dnat(0, i) * xy_[static_cast<std::size_t>(i)].y();
    J(1, 0) += dnat(1, i) * xy_[static_cast<std::size_t>(i)].x();
    J(1, 1) += dnat(1, i) * xy_[static_cast<std::size_t>(i)].y();
  }
  const Eigen::Matrix2d Ji = J.inverse();
  B.resize(3, 3 * n_);
  const Eigen::RowVectorXd Hx_x = Ji(0, 0) * Hx_xi.transpose() + Ji(0, 1) * Hx_eta.transpose();
  const Eigen::RowVectorXd Hx_y = Ji(1, 0) * Hx_xi.transpose() + Ji(1, 1) * Hx_eta.transpose();
  const Eigen::RowVectorXd Hy_x = Ji(0, 0) * Hy_xi.transpose() + Ji(0, 1) * Hy_eta.transpose();
  const Eigen::RowVectorXd Hy_y = Ji(1, 0) * Hy_xi.transpose() + Ji(1, 1) * Hy_eta.transpose();
  B.row(0) = Hx_x;
  B.row(1) = Hy_y;
  B.row(2) = Hx_y + Hy_x;
}

void FlatShellKernel::add_membrane(Eigen::MatrixXd& K) const {
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  double detJ = 0.0;
  auto compatible_B = [&](const Eigen::MatrixXd& d) {
    Eigen::MatrixXd B = Eigen::MatrixXd::Zero(3, 2 * n_);
    for (int a = 0; a < n_; ++a) {
      B(0, 2 * a) = d(0, a);
      B(1, 2 * a + 1) = d(1, a);
      B(2, 2 * a) = d(1, a);
      B(2, 2 * a + 1) = d(0, a);
    }
    return B;
  };
  Eigen::MatrixXd Kuu = Eigen::MatrixXd::Zero(2 * n_, 2 * n_);
  const bool incompatible = n_modes_ > 0;
  Eigen::MatrixXd Kua = Eigen::MatrixXd::Zero(2 * n_, 4), Kaa = Eigen::MatrixXd::Zero(4, 4);
  for (const auto& p : points()) {
    shape(p.xi, p.eta, N, dN, detJ);
    const double t = thickness_at(N);
    const double wgt = detJ * p.w;
    const Eigen::Matrix3d D =
        data_.laminate ? data_.laminate->A
                       : plane_stress(data_.nu, data_.E * t / (1.0 - data_.nu * data_.nu));
    const Eigen::MatrixXd B = compatible_B(dN);
    Kuu += B.transpose() * D * B * wgt;
    if (incompatible) {
      // Modified incompatible modes: derivatives with J0 and the factor detJ0/detJ so that
      // ∫ B_inc dA = 0 on any quad, i.e. the patch test is passed.
      Eigen::Vector2d d1 = (detJ0_ / detJ) * J0i_ * Eigen::Vector2d(-2.0 * p.xi, 0.0);
      Eigen::Vector2d d2 = (detJ0_ / detJ) * J0i_ * Eigen::Vector2d(0.0, -2.0 * p.eta);
      Eigen::Matrix<double, 3, 4> Bi;
      Bi << d1.x(), d2.x(), 0.0, 0.0, 0.0, 0.0, d1.y(), d2.y(), d1.y(), d2.y(), d1.x(), d2.x();
      Kua += B.transpose() * D * Bi * wgt;
      Kaa += Bi.transpose() * D * Bi * wgt;
    }
  }
  if (incompatible) Kuu -= Kua * Kaa.ldlt().solve(Kua.transpose());
  for (int a = 0; a < n_; ++a)
    for (int b = 0; b < n_; ++b)
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) K(6 * a + i, 6 * b + j) += Kuu(2 * a + i, 2 * b + j);
}

void FlatShellKernel::add_drilling(Eigen::MatrixXd& K) const {
  // Hughes–Brezzi drilling penalty on r = θz − ½(∂v/∂x − ∂u/∂y), on (u, v, θz) per node; a
  // laminate's G the thickness average A66 / t.
  const double G = data_.laminate ? data_.laminate->A(2, 2) / data_.laminate->thickness
                                  : data_.E / (2.0 * (1.0 + data_.nu));
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  double detJ = 0.0;
  Eigen::MatrixXd Kd = Eigen::MatrixXd::Zero(3 * n_, 3 * n_);
  for (const auto& p : points()) {
    shape(p.xi, p.eta, N, dN, detJ);
    const double t = thickness_at(N);
    const double wgt = detJ * p.w;
    Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(3 * n_);
    for (int a = 0; a < n_; ++a) {
      r(3 * a) = 0.5 * dN(1, a);
      r(3 * a + 1) = -0.5 * dN(0, a);
      r(3 * a + 2) = N(a);
    }
    Kd += data_.drill_factor * G * t * r.transpose() * r * wgt;
  }
  const int map[3] = {0, 1, 5};
  for (int a = 0; a < n_; ++a)
    for (int b = 0; b < n_; ++b)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) K(6 * a + map[i], 6 * b + map[j]) += Kd(3 * a + i, 3 * b + j);
  // Membrane only (KEYOPT(1) = 1): nothing resists the in-plane rotations θx, θy, which MAPDL's
  // membrane has no DOFs for; a diagonal stiffness of the drilling term's size holds them at
  // zero so that a curved membrane's nodes (whose nodal axes the element plane does not share)
  // are not singular. They couple with no translation, so the membrane's answer is unchanged.
  if (!data_.bending) {
    double t = 0.0;
    for (int a = 0; a < n_; ++a) t += data_.t[static_cast<std::size_t>(a)] / n_;
    const double k = data_.drill_factor * G * t * area_ / n_;
    for (int a = 0; a < n_; ++a) K(6 * a + 3, 6 * a + 3) += k, K(6 * a + 4, 6 * a + 4) += k;
  }
}

void FlatShellKernel::add_bending(Eigen::MatrixXd& K) const {
  Eigen::MatrixXd B;
  double detJ = 0.0;
  Eigen::MatrixXd Kb = Eigen::MatrixXd::Zero(3 * n_, 3 * n_);
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  for (const auto& p : points()) {
    shape(p.xi, p.eta, N, dN, detJ);
    const double t = thickness_at(N);
    const Eigen::Matrix3d D =
        data_.laminate ? data_.laminate->D
                       : plane_stress(data_.nu, data_.E * t * t * t * data_.rmi /
                                                    (12.0 * (1.0 - data_.nu * data_.nu)));
    bending_b(p.xi, p.eta, B);
    Kb += B.transpose() * D * B * detJ * p.w;
  }
  for (int a = 0; a < n_; ++a)
    for (int b = 0; b < n_; ++b)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) K(6 * a + 2 + i, 6 * b + 2 + j) += Kb(3 * a + i, 3 * b + j);
}

Eigen::MatrixXd FlatShellKernel::consistent_mass() const {
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(6 * n_, 6 * n_);
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  double detJ = 0.0;
  for (const auto& p : points()) {
    shape(p.xi, p.eta, N, dN, detJ);
    const double t = thickness_at(N);
    const double m = (data_.rho * t + data_.added_mass) * detJ * p.w;
    const double r = data_.rotary_inertia ? data_.rho * t * t * t / 12.0 * detJ * p.w : 0.0;
    for (int a = 0; a < n_; ++a)
      for (int b = 0; b < n_; ++b) {
        const double nn = N(a) * N(b);
        for (int i = 0; i < 3; ++i) {
          M(6 * a + i, 6 * b + i) += m * nn;
          M(6 * a + 3 + i, 6 * b + 3 + i) += r * nn;
        }
      }
  }
  return M;
}

Eigen::MatrixXd FlatShellKernel::lumped_mass() const {
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(6 * n_, 6 * n_);
  for (int a = 0; a < n_; ++a)
    for (int i = 0; i < 3; ++i) M(6 * a + i, 6 * a + i) = total_mass_ / n_;
  // Mindlin: the normal's rotations θx, θy are independent fields with the inertia ρt³/12 per
  // area (Mindlin 1951), lumped like the translations (a corner's share A/n at its thickness).
  // θz, the drilling rotation, has no inertia of its own.
  if (data_.mindlin && data_.rotary_inertia)
    for (int a = 0; a < n_; ++a) {
      const double t = data_.t[static_cast<std::size_t>(a)];
      M(6 * a + 3, 6 * a + 3) = M(6 * a + 4, 6 * a + 4) = data_.rho * t * t * t / 12.0 * area_ / n_;
    }
  return M;
}

Resultants FlatShellKernel::resultants(const Eigen::VectorXd& d) const {
  // Every shell's resultants at every stored point: vectors of fixed capacity and products into
  // fixed sizes, so nothing here allocates (five allocations per call were a third of the
  // thesis helmet's, issue 11).
  Resultants r;
  const double centroid_shape = n_ == 3 ? 1.0 / 3.0 : 0.25;  // each N_a at the centroid
  for (int a = 0; a < n_; ++a) r.t += centroid_shape * data_.t[static_cast<std::size_t>(a)];
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 8, 1> dm(2 * n_);
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 12, 1> db(3 * n_);
  for (int a = 0; a < n_; ++a) {
    dm(2 * a) = d(6 * a), dm(2 * a + 1) = d(6 * a + 1);
    for (int i = 0; i < 3; ++i) db(3 * a + i) = d(6 * a + 2 + i);
  }
  const double nu2 = 1.0 - data_.nu * data_.nu;
  Eigen::Vector3d strain;
  if (data_.membrane) {
    strain.noalias() = Bm0_ * dm;
    r.N = data_.laminate ? (data_.laminate->A * strain).eval()
                         : (plane_stress(data_.nu, data_.E * r.t / nu2) * strain).eval();
  }
  if (data_.bending) {
    strain.noalias() = Bb0_ * db;
    r.M = data_.laminate
              ? (data_.laminate->D * strain).eval()
              : (plane_stress(data_.nu, data_.E * r.t * r.t * r.t * data_.rmi / (12.0 * nu2)) *
                 strain)
                    .eval();
    if (data_.mindlin) {
      Eigen::Vector2d gamma;
      gamma.noalias() = Bs0_ * db;
      r.Q = data_.laminate
                ? (data_.laminate->shear * gamma).eval()
                : (data_.shear_factor * data_.E / (2.0 * (1.0 + data_.nu)) * r.t * gamma).eval();
    }
  }
  return r;
}

Eigen::MatrixXd FlatShellKernel::geometric_stiffness(const Eigen::VectorXd& d) const {
  const Eigen::Vector3d Nr = resultants(d).N;
  Eigen::Matrix2d S;
  S << Nr(0), Nr(2), Nr(2), Nr(1);
  Eigen::MatrixXd Kg = Eigen::MatrixXd::Zero(6 * n_, 6 * n_);
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  double detJ = 0.0;
  for (const auto& p : points()) {
    shape(p.xi, p.eta, N, dN, detJ);
    const Eigen::MatrixXd g = dN.transpose() * S * dN * (detJ * p.w);
    for (int a = 0; a < n_; ++a)
      for (int b = 0; b < n_; ++b)
        for (int i = 0; i < 3; ++i) Kg(6 * a + i, 6 * b + i) += g(a, b);
  }
  return Kg;
}

}  // namespace impactfe::shell
