#include "elements/corotational_triangle.h"

#include <Eigen/Dense>

#include <cmath>
#include <cstring>

#include "core/errors.h"
#include "elements/so3.h"

namespace impactfe {

namespace {

using Mat3 = Eigen::Matrix3d;
using Vec3 = Eigen::Vector3d;
using Row18 = Eigen::Matrix<double, 1, 18>;
using Mat3x18 = Eigen::Matrix<double, 3, 18>;
using Mat24x16 = Eigen::Matrix<double, 24, 16>;

using so3::spin;

// Local DOFs per corner a: u v w θx θy θz at 6a..6a+5. The membrane set (u, v, θz) is
// numbered 3a + {0, 1, 2}, the bending rotations (θx, θy) 2a + {0, 1}.
constexpr int membrane_dof(int a, int k) {
  return 6 * a + (k < 2 ? k : 5);
}
constexpr int bending_dof(int a, int k) {
  return 6 * a + 3 + k;
}

/// Rows 0..17 of `to` = the 18 columns of `from` (their first To::Cols entries) transposed, and
/// zero padding below. An element-wise copy: Eigen's transposed assignment of these fixed sizes
/// took several times as long.
template <class From, class To>
void transpose_into(const From& from, To& to) {
  for (int j = 0; j < 18; ++j)
    for (int i = 0; i < To::ColsAtCompileTime; ++i) to(j, i) = from(i, j);
  to.template bottomRows<To::RowsAtCompileTime - 18>().setZero();
}

}  // namespace

/// The co-rotated state at u: the frame (Rc, corners (0, 0), (L, 0), (b1, b2)), the corners
/// from the centroid in it (ξ, η), the spin coefficients c1..c3, per corner the rotation
/// vector ψ, the deformational rotation θ = log(Rcᵀ exp(ψ) R0) and T(θ)⁻¹, T(ψ); then the
/// local forces.
struct CorotationalTriangle::State {
  Mat3 Rc;
  double L = 0.0, b1 = 0.0, b2 = 0.0;
  std::array<double, 3> xi{}, eta{}, c1{}, c2{}, c3{};
  std::array<Vec3, 3> psi, theta;
  std::array<Mat3, 3> Ji, T;
  // Forces in the frame: n̂ (translations), m̂ (rotations), M̂ = T(θ)⁻ᵀ m̂, ŵ (the frame's
  // moment), f̂_x (frame components of the corner forces).
  std::array<Vec3, 3> n, m, M, fx;
  Vec3 w = Vec3::Zero();
};

CorotationalTriangle::CorotationalTriangle(const std::array<Vec3, 3>& X, const Mat3& R0,
                                           const Vec3& c0, const Eigen::MatrixXd& K_local)
    : X_(X), q0_(R0), K16_(Eigen::Matrix<double, 16, 16>::Zero()) {
  for (int a = 0; a < 3; ++a) {
    const Vec3 l = R0.transpose() * (X[static_cast<std::size_t>(a)] - c0);
    xi0_[static_cast<std::size_t>(a)] = l.x();
    eta0_[static_cast<std::size_t>(a)] = l.y();
  }
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          K_membrane_(3 * a + i, 3 * b + j) = K_local(membrane_dof(a, i), membrane_dof(b, j));
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
          K_bending_(2 * a + i, 2 * b + j) = K_local(bending_dof(a, i), bending_dof(b, j));
      // The tangent's order: u, v, θx, θy, θz at 5a + k (local DOF 6a + {0, 1, 3, 4, 5}).
      constexpr int kLocal[] = {0, 1, 3, 4, 5};
      for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j)
          K16_(5 * a + i, 5 * b + j) = K_local(6 * a + kLocal[i], 6 * b + kLocal[j]);
    }
}

CorotationalTriangle::~CorotationalTriangle() = default;

bool CorotationalTriangle::uncoupled(const Eigen::MatrixXd& K_local) {
  if (K_local.rows() != 18 || K_local.cols() != 18) return false;
  auto membrane = [](int i) {
    const int k = i % 6;
    return k == 0 || k == 1 || k == 5;
  };
  for (int i = 0; i < 18; ++i)
    for (int j = 0; j < 18; ++j)
      if (membrane(i) != membrane(j) && K_local(i, j) != 0.0) return false;
  return true;
}

void CorotationalTriangle::corotate(const Eigen::VectorXd& u, State& s) const {
  std::array<Vec3, 3> x;
  for (int a = 0; a < 3; ++a)
    x[static_cast<std::size_t>(a)] = X_[static_cast<std::size_t>(a)] + u.segment<3>(6 * a);
  // The frame: e1 along side 0→1 (in the facet's plane exactly), e3 the normal.
  const Vec3 v = x[1] - x[0];
  const Vec3 b = x[2] - x[0];
  const Vec3 e3 = v.cross(b).normalized();
  s.L = v.norm();
  const Vec3 e1 = v / s.L;
  const Vec3 e2 = e3.cross(e1);
  s.Rc.col(0) = e1;
  s.Rc.col(1) = e2;
  s.Rc.col(2) = e3;
  s.b1 = e1.dot(b);
  s.b2 = e2.dot(b);
  const double xi_c = (s.L + s.b1) / 3.0, eta_c = s.b2 / 3.0;
  s.xi = {-xi_c, s.L - xi_c, s.b1 - xi_c};
  s.eta = {-eta_c, -eta_c, s.b2 - eta_c};
  const double Lb2 = s.L * s.b2;
  s.c1 = {(s.b1 - s.L) / Lb2, -s.b1 / Lb2, s.L / Lb2};
  s.c2 = {1.0 / s.L, -1.0 / s.L, 0.0};
  s.c3 = {-1.0 / s.L, 1.0 / s.L, 0.0};
  // θ = log(Rcᵀ exp(ψ) R0), composed as quaternions (so3.h).
  const Eigen::Quaterniond qc_inverse = Eigen::Quaterniond(s.Rc).conjugate();
  for (std::size_t a = 0; a < 3; ++a) {
    s.psi[a] = u.segment<3>(6 * static_cast<int>(a) + 3);
    Eigen::Quaterniond q;
    so3::exp_quaternion_and_left_jacobian(s.psi[a], q, s.T[a]);
    s.theta[a] = so3::log_quaternion_and_left_jacobian_inverse(qc_inverse * q * q0_, s.Ji[a]);
  }
}

const CorotationalTriangle::State& CorotationalTriangle::state_at(const Eigen::VectorXd& u,
                                                                  bool with_forces) const {
  IMPACTFE_CHECK(u.size() == 18, "CorotationalTriangle: 18 displacements per evaluation");
  // Bitwise equality (not ==): a memo that answers for a different u, even by a signed zero,
  // would break the results' independence of the order of evaluations.
  if (!last_ || std::memcmp(u.data(), last_u_.data(), sizeof(double) * 18) != 0) {
    if (!last_) last_ = std::make_unique<State>();
    corotate(u, *last_);
    last_u_ = u;
    last_has_forces_ = false;
  }
  if (with_forces && !last_has_forces_) {
    local_forces(*last_);
    last_has_forces_ = true;
  }
  return *last_;
}

Eigen::VectorXd CorotationalTriangle::deformation(const Eigen::VectorXd& u) const {
  const State& s = state_at(u, false);
  Eigen::VectorXd d = Eigen::VectorXd::Zero(18);
  for (std::size_t a = 0; a < 3; ++a) {
    const int i = 6 * static_cast<int>(a);
    d(i) = s.xi[a] - xi0_[a];
    d(i + 1) = s.eta[a] - eta0_[a];
    d.segment<3>(i + 3) = s.theta[a];
  }
  return d;
}

void CorotationalTriangle::local_forces(State& s) const {
  // Deformational displacements: in-plane corner moves and the rotations. The out-of-plane
  // translations are zero for every u, so the w rows of K̄ (bending, foundation) do no work
  // and n̂_z is left out (the general path carries it at round-off level).
  Eigen::Matrix<double, 9, 1> d_m;
  Eigen::Matrix<double, 6, 1> d_b;
  for (std::size_t a = 0; a < 3; ++a) {
    const int i = static_cast<int>(a);
    d_m.segment<3>(3 * i) << s.xi[a] - xi0_[a], s.eta[a] - eta0_[a], s.theta[a].z();
    d_b.segment<2>(2 * i) << s.theta[a].x(), s.theta[a].y();
  }
  const Eigen::Matrix<double, 9, 1> f_m = K_membrane_ * d_m;
  const Eigen::Matrix<double, 6, 1> f_b = K_bending_ * d_b;
  Vec3 n_mean = Vec3::Zero();
  s.w.setZero();
  for (std::size_t a = 0; a < 3; ++a) {
    const int i = static_cast<int>(a);
    s.n[a] << f_m(3 * i), f_m(3 * i + 1), 0.0;
    s.m[a] << f_b(2 * i), f_b(2 * i + 1), f_m(3 * i + 2);
    s.M[a] = s.Ji[a].transpose() * s.m[a];
    n_mean += s.n[a] / 3.0;
    const Vec3 r(s.xi[a], s.eta[a], 0.0);
    s.w -= r.cross(s.n[a]) + s.M[a];
  }
  // f̂_x_b = n̂_b − n̄ + Ĝ_bᵀ ŵ: the centroid projection and the frame's spin.
  for (std::size_t b = 0; b < 3; ++b) {
    s.fx[b] = s.n[b] - n_mean;
    s.fx[b].y() += s.w.z() * s.c3[b];
    s.fx[b].z() += s.w.x() * s.c1[b] + s.w.y() * s.c2[b];
  }
}

void CorotationalTriangle::internal_force(const Eigen::VectorXd& u, Eigen::VectorXd& f) const {
  const State& s = state_at(u, true);
  f.resize(18);
  for (std::size_t a = 0; a < 3; ++a) {
    const int i = 6 * static_cast<int>(a);
    f.segment<3>(i) = s.Rc * s.fx[a];
    f.segment<3>(i + 3) = s.T[a].transpose() * (s.Rc * s.M[a]);
  }
}

void CorotationalTriangle::tangent(const Eigen::VectorXd& u, Eigen::MatrixXd& K,
                                   Eigen::VectorXd& f) const {
  const State& s = state_at(u, true);
  const Mat16x18 B = frame_variation(s);
  Mat24x18 Kl = material_part(B);
  add_geometric_part(s, B, Kl);
  to_global(s, Kl, K, f);
}

CorotationalTriangle::Mat16x18 CorotationalTriangle::frame_variation(const State& s) {
  // Variations in the frame, per corner b: δξ̂ = (δx̂_b, δφ̂_b) with δx̂ = Rcᵀ δx and
  // δφ̂ = Rcᵀ T(ψ) δψ (column 6b + k). The deformation δd = B̂ δξ̂ over the 15 rows
  // (u, v, θx, θy, θz of corner a at 5a + k):
  //   in-plane:  δd_a = δx̂_a − δx̂_c + r̂_a × δω̂, δω̂ = Ĝ δξ̂ (the frame's spin, header),
  //   rotations: δθ_a = T(θ_a)⁻¹ (δφ̂_a − δω̂).
  // B̂ has a zero 16th row (the padding of K16_).
  Mat16x18 B = Mat16x18::Zero();
  for (int a = 0; a < 3; ++a) {
    const std::size_t k = static_cast<std::size_t>(a);
    const Mat3& Ji = s.Ji[k];
    for (int b = 0; b < 3; ++b) {
      const std::size_t l = static_cast<std::size_t>(b);
      const double centre = (a == b ? 1.0 : 0.0) - 1.0 / 3.0;
      B(5 * a, 6 * b) = centre;
      B(5 * a, 6 * b + 1) = s.eta[k] * s.c3[l];
      B(5 * a + 1, 6 * b + 1) = centre - s.xi[k] * s.c3[l];
      B.block<3, 1>(5 * a + 2, 6 * b + 1) = -Ji.col(2) * s.c3[l];
      B.block<3, 1>(5 * a + 2, 6 * b + 2) = -(Ji.col(0) * s.c1[l] + Ji.col(1) * s.c2[l]);
    }
    B.block<3, 3>(5 * a + 2, 6 * a + 3) = Ji;
  }
  return B;
}

CorotationalTriangle::Mat24x18 CorotationalTriangle::material_part(const Mat16x18& B) const {
  // Material part B̂ᵀ K̄ B̂ over the nonzero rows of each column of B̂ (a fixed pattern: a
  // column of δû has its 3 u rows, one of δŵ the 9 rotation rows, one of δφ̂ its corner's 3).
  // The products are sums of whole columns, 16 or 24 long (padded with zeros): whole SIMD
  // packets.
  const auto rows_of = [](int j) -> std::pair<const int*, int> {
    static constexpr int kU[] = {0, 5, 10};
    static constexpr int kAll[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14};
    static constexpr int kRot[] = {2, 3, 4, 7, 8, 9, 12, 13, 14};
    switch (j % 6) {
      case 0:
        return {kU, 3};
      case 1:
        return {kAll, 15};
      case 2:
        return {kRot, 9};
      default:
        return {kRot + 3 * (j / 6), 3};
    }
  };
  Eigen::Matrix<double, 16, 18> KB;  // K̄ B̂, column by column
  for (int j = 0; j < 18; ++j) {
    const auto [rows, n] = rows_of(j);
    Eigen::Matrix<double, 16, 1> col = K16_.col(rows[0]) * B(rows[0], j);
    for (int r = 1; r < n; ++r) col += K16_.col(rows[r]) * B(rows[r], j);
    KB.col(j) = col;
  }
  Mat24x16 KBt;  // (K̄ B̂)ᵀ
  transpose_into(KB, KBt);
  Mat24x18 Kl;  // B̂ᵀ K̄ B̂ in rows 0..17, symmetric: column i is (K̄ B̂)ᵀ B̂(:, i)
  for (int i = 0; i < 18; ++i) {
    const auto [rows, n] = rows_of(i);
    Eigen::Matrix<double, 24, 1> col = KBt.col(rows[0]) * B(rows[0], i);
    for (int r = 1; r < n; ++r) col += KBt.col(rows[r]) * B(rows[r], i);
    Kl.col(i) = col;
  }
  return Kl;
}

void CorotationalTriangle::add_geometric_part(const State& s, const Mat16x18& B, Mat24x18& Kl) {
  // Geometric part: the variation of f̂ at fixed local forces K̄ d.
  // The frame's spin δω̂ = Ĝ δξ̂: ω̂1 = Σ c1_b δẑ_b, ω̂2 = Σ c2_b δẑ_b, ω̂3 = Σ c3_b δŷ_b, so a
  // product with Ĝ only fills the columns of δŷ_b and δẑ_b.
  // Ẑ_a δθ_a, Ẑ_a = ∂(T(θ)⁻ᵀ m̂_a)/∂θ at θ_a (δθ_a: the rotation rows of B̂, nonzero in the
  // δŷ, δẑ columns of every corner and the δφ̂ columns of its own).
  std::array<Mat3x18, 3> ZTheta;
  Mat3x18 W = Mat3x18::Zero();  // δŵ = Σ_a n̂_a × δr̂_a − Σ_a Ẑ_a δθ_a
  for (int a = 0; a < 3; ++a) {
    const std::size_t k = static_cast<std::size_t>(a);
    const Mat3 Z = so3::d_left_jacobian_inverse_transpose(s.theta[k], s.m[k]);
    Mat3x18& ZT = ZTheta[k];
    ZT.setZero();
    for (int b = 0; b < 3; ++b)
      for (int j = 6 * b + 1; j <= 6 * b + 2; ++j)
        ZT.col(j).noalias() = Z * B.block<3, 1>(5 * a + 2, j);
    ZT.middleCols<3>(6 * a + 3).noalias() = Z * B.block<3, 3>(5 * a + 2, 6 * a + 3);
    // n̂_z = δr̂_z = 0: n̂ × δr̂ = (0, 0, n_x δr_y − n_y δr_x).
    const Vec3& n = s.n[k];
    W.row(2) += n.x() * B.row(5 * a + 1) - n.y() * B.row(5 * a);
    W -= ZT;
  }
  // −spin(v) Ĝ into the rows `row` of Kl, for each corner b: the columns of δŷ_b and δẑ_b.
  const auto subtract_spin_g = [&](const Vec3& v, int row) {
    const Mat3 S = spin(v);
    for (int b = 0; b < 3; ++b) {
      const std::size_t l = static_cast<std::size_t>(b);
      Kl.block<3, 1>(row, 6 * b + 1) -= S.col(2) * s.c3[l];
      Kl.block<3, 1>(row, 6 * b + 2) -= S.col(0) * s.c1[l] + S.col(1) * s.c2[l];
    }
  };
  // The shape of the frame: δL, δb1, δb2 and the spin coefficients' variations.
  Row18 dL = Row18::Zero();
  dL(6) = 1.0;
  dL(0) = -1.0;
  Row18 db1 = Row18::Zero(), db2 = Row18::Zero();
  for (int b = 0; b < 2; ++b) {  // c3_2 = 0
    db1(6 * b + 1) = s.b2 * s.c3[static_cast<std::size_t>(b)];
    db2(6 * b + 1) = -s.b1 * s.c3[static_cast<std::size_t>(b)];
  }
  db1(12) += 1.0;
  db1(0) -= 1.0;
  db2(13) += 1.0;
  db2(1) -= 1.0;
  const double Lb2 = s.L * s.b2;
  const Row18 d_ratio = dL / s.L + db2 / s.b2;  // δ(L b2) / (L b2)
  const std::array<Row18, 3> dk1 = {db1 - dL, -db1, dL};
  for (int b = 0; b < 3; ++b) {
    const std::size_t k = static_cast<std::size_t>(b);
    const Row18 dc1 = dk1[k] / Lb2 - s.c1[k] * d_ratio;
    const double dc2 = -s.c2[k] / s.L, dc3 = -s.c3[k] / s.L;  // times δL
    Kl.row(6 * b + 1) += s.c3[k] * W.row(2) + (s.w.z() * dc3) * dL;
    Kl.row(6 * b + 2) +=
        s.c1[k] * W.row(0) + s.c2[k] * W.row(1) + s.w.x() * dc1 + (s.w.y() * dc2) * dL;
    // The frame turns the corner forces: δ(Rc f̂) = Rc (δf̂ + δω̂ × f̂).
    subtract_spin_g(s.fx[k], 6 * b);
    Kl.middleRows<3>(6 * b + 3) += ZTheta[k];
    subtract_spin_g(s.M[k], 6 * b + 3);
  }
}

void CorotationalTriangle::to_global(const State& s, const Mat24x18& Kl, Eigen::MatrixXd& K,
                                     Eigen::VectorXd& f) {
  // Back to global axes: K = T̂ᵀ K̂ T̂ with the blocks Rcᵀ (translations) and Rcᵀ T(ψ)
  // (rotations), plus ∂(T(ψ)ᵀ M)/∂ψ at the global M = Rc M̂. Column blocks first (K̂ T̂, as
  // sums of columns), then each 3-row block of every column.
  std::array<Mat3, 6> P;
  for (std::size_t a = 0; a < 3; ++a) {
    P[2 * a] = s.Rc.transpose();
    P[2 * a + 1] = s.Rc.transpose() * s.T[a];
  }
  Mat24x18 KP;
  for (int j = 0; j < 6; ++j) {
    const Mat3& Pj = P[static_cast<std::size_t>(j)];
    for (int c = 0; c < 3; ++c)
      KP.col(3 * j + c) =
          Kl.col(3 * j) * Pj(0, c) + Kl.col(3 * j + 1) * Pj(1, c) + Kl.col(3 * j + 2) * Pj(2, c);
  }
  // K = T̂ᵀ (K̂ T̂) as the transpose of (K̂ T̂)ᵀ T̂: sums of columns again.
  Mat24x18 KPt;
  transpose_into(KP, KPt);
  Mat24x18 Kt;
  for (int i = 0; i < 6; ++i) {
    const Mat3& Pi = P[static_cast<std::size_t>(i)];
    for (int c = 0; c < 3; ++c)
      Kt.col(3 * i + c) =
          KPt.col(3 * i) * Pi(0, c) + KPt.col(3 * i + 1) * Pi(1, c) + KPt.col(3 * i + 2) * Pi(2, c);
  }
  K = Kt.topRows<18>().transpose();
  f.resize(18);
  for (std::size_t a = 0; a < 3; ++a) {
    const int i = 6 * static_cast<int>(a);
    const Vec3 M = s.Rc * s.M[a];
    K.block<3, 3>(i + 3, i + 3) += so3::d_left_jacobian_transpose(s.psi[a], M);
    f.segment<3>(i) = s.Rc * s.fx[a];
    f.segment<3>(i + 3) = s.T[a].transpose() * M;
  }
}

}  // namespace impactfe
