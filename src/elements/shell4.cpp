#include "elements/shell4.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "core/errors.h"
#include "core/log.h"
#include "elements/element_registry.h"
#include "elements/face_pressure.h"
#include "elements/shell_frame.h"
#include "elements/so3.h"
#include "materials/inelastic_strain.h"
#include "materials/isotropic_elasticity.h"

namespace impactfe {

namespace {

using Mat3 = Eigen::Matrix3d;
using so3::spin;
// Fixed capacity (at most 4 corners, 24 DOFs): no heap in the co-rotational hot path.
using Mat24 = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, 24, 24>;

/// The co-rotational state of an element at a displacement u (Nour-Omid & Rankin 1991;
/// Felippa & Haugen 2005): the frame of the current corners, and per corner its position r
/// relative to the centroid, its nodal rotation vector ψ, its deformational rotation
/// θ = log(Rcᵀ exp(ψ) R0), and the Jacobians T(ψ) and T(θ)⁻¹.
struct CorotationalState {
  ShellFrame frame;
  std::array<Vec3, 4> r, psi, theta;
  std::array<Mat3, 4> T, Ji;
};

}  // namespace

Shell4::Shell4(int id, const Shell4Data& data, const SourceLocation& where)
    : Element(id),
      n_(static_cast<int>(data.node_ids.size())),
      X_(data.positions),
      plasticity_(data.plasticity),
      laminate_(data.kernel.laminate) {
  for (int node : data.node_ids)
    for (Dof d : kAllDofs) dofs_.push_back(DofKey{node, d});
  ShellCorners corners(3, n_);
  for (int a = 0; a < n_; ++a) corners.col(a) = X_[static_cast<std::size_t>(a)];
  const ShellFrame frame0 = shell_frame(corners, false);
  R0_ = frame0.R;
  c0_ = frame0.c;
  if (!R0_.allFinite())
    throw InputError(where,
                     fmt::format("element {}: zero area (coincident or collinear nodes)", id));
  std::vector<Eigen::Vector2d> xy;
  double hmax = 0.0;
  for (const auto& x : X_) {
    const Vec3 l = R0_.transpose() * (x - c0_);
    xy.emplace_back(l.x(), l.y());
    h_.push_back(l.z());
    hmax = std::max(hmax, std::abs(l.z()));
  }
  try {
    kernel_ = std::make_unique<shell::FlatShellKernel>(xy, data.kernel);
  } catch (const std::invalid_argument& e) {
    throw InputError(where, fmt::format("element {}: {}", id, e.what()));
  }
  const double warp = hmax / std::sqrt(kernel_->area());
  if (warp > 0.02)
    Log::warn(
        "element {}: warped quadrilateral (corner offset / sqrt(area) = {:.3g}), projected "
        "on its mean plane",
        id, warp);
  theta_ = data.theta_deg * M_PI / 180.0;

  if (plasticity_) committed_.resize(static_cast<std::size_t>(kernel_->n_material_points()));
  // A triangle is flat (no warping links): its co-rotational kinematics have closed forms in
  // its own frame (corotational_triangle.h), valid while the kernel keeps membrane and bending
  // apart, as the elastic one does.
  if (n_ == 3 && !plasticity_) {
    const Eigen::MatrixXd K_l = kernel_->stiffness();
    if (CorotationalTriangle::uncoupled(K_l))
      triangle_ = std::make_unique<CorotationalTriangle>(std::array<Vec3, 3>{X_[0], X_[1], X_[2]},
                                                         R0_, c0_, K_l);
  }
  if (data.keep_corotational_stiffness && !triangle_ && !plasticity_)
    K_bar_ = form_corotational_stiffness();
}

Eigen::MatrixXd Shell4::rigid_links() const {
  Eigen::MatrixXd W = Eigen::MatrixXd::Identity(6 * n_, 6 * n_);
  for (int a = 0; a < n_; ++a) {
    // Flat corner = actual corner − h e3, rigidly linked: u_f = u − h θy, v_f = v + h θx.
    W(6 * a, 6 * a + 4) = -h_[static_cast<std::size_t>(a)];
    W(6 * a + 1, 6 * a + 3) = h_[static_cast<std::size_t>(a)];
  }
  return W;
}

Eigen::MatrixXd Shell4::to_local() const {
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(6 * n_, 6 * n_);
  for (int a = 0; a < n_; ++a) {
    T.block<3, 3>(6 * a, 6 * a) = R0_.transpose();
    T.block<3, 3>(6 * a + 3, 6 * a + 3) = R0_.transpose();
  }
  return rigid_links() * T;
}

Eigen::VectorXd Shell4::apply_rigid_links(Eigen::VectorXd d) const {
  // The rows of W that differ from the identity (rigid_links): u_f = u − h θy, v_f = v + h θx.
  for (int a = 0; a < n_; ++a) {
    const double h = h_[static_cast<std::size_t>(a)];
    const double theta_x = d(6 * a + 3), theta_y = d(6 * a + 4);
    d(6 * a) -= h * theta_y;
    d(6 * a + 1) += h * theta_x;
  }
  return d;
}

Eigen::VectorXd Shell4::apply_to_local(const Eigen::VectorXd& u) const {
  // T u: each corner's translation and rotation in element axes (R0ᵀ), then W.
  Eigen::VectorXd d(6 * n_);
  for (int a = 0; a < 2 * n_; ++a) d.segment<3>(3 * a) = R0_.transpose() * u.segment<3>(3 * a);
  return apply_rigid_links(std::move(d));
}

Eigen::MatrixXd Shell4::form_corotational_stiffness() const {
  const bool warped = std::any_of(h_.begin(), h_.end(), [](double h) { return h != 0.0; });
  if (!warped) return kernel_->stiffness();
  const Eigen::MatrixXd W = rigid_links();
  return W.transpose() * kernel_->stiffness() * W;
}

const Eigen::MatrixXd& Shell4::corotational_stiffness(Eigen::MatrixXd& scratch) const {
  if (K_bar_.size() > 0) return K_bar_;
  scratch = form_corotational_stiffness();
  return scratch;
}

namespace {

/// Co-rotational state at u, and the deformational displacement d (6n): per corner the
/// corotated position change Rcᵀ r_a − R0ᵀ(X_a − c0) and the deformational rotation θ_a.
template <class VecD>
CorotationalState corotate(const std::vector<Vec3>& X, const Mat3& R0, const Vec3& c0,
                           const Eigen::VectorXd& u, bool with_derivatives, VecD& d) {
  const int n = static_cast<int>(X.size());
  ShellCorners x(3, n);
  for (int a = 0; a < n; ++a) x.col(a) = X[static_cast<std::size_t>(a)] + u.segment<3>(6 * a);
  CorotationalState s;
  s.frame = shell_frame(x, with_derivatives);
  const Mat3& Rc = s.frame.R;
  d.resize(6 * n);
  for (int a = 0; a < n; ++a) {
    const std::size_t i = static_cast<std::size_t>(a);
    s.r[i] = x.col(a) - s.frame.c;
    d.template segment<3>(6 * a) = Rc.transpose() * s.r[i] - R0.transpose() * (X[i] - c0);
    s.psi[i] = u.segment<3>(6 * a + 3);
    s.theta[i] = so3::log_map(Rc.transpose() * so3::exp_map(s.psi[i]) * R0);
    d.template segment<3>(6 * a + 3) = s.theta[i];
    if (!with_derivatives) continue;
    s.T[i] = so3::left_jacobian(s.psi[i]);
    s.Ji[i] = so3::left_jacobian_inverse(s.theta[i]);
  }
  return s;
}

/// B = ∂d/∂u: δd_a = Rcᵀ(δx_a − δc + spin(r_a) δω) and δθ_a = T(θ_a)⁻¹ Rcᵀ(T(ψ_a) δψ_a − δω),
/// δω = G δx (Nour-Omid & Rankin 1991, eqs. 43–49; Crisfield vol. 2, §17.5).
template <class MatB>
void kinematic_matrix(const CorotationalState& s, MatB& B) {
  const int n = s.frame.n;
  const Mat3& Rc = s.frame.R;
  const ShellMat3N& G = s.frame.G;
  B.setZero(6 * n, 6 * n);
  const ShellMat3N RtG = Rc.transpose() * G;  // 3 × 3n over corner translations
  for (int a = 0; a < n; ++a) {
    const std::size_t i = static_cast<std::size_t>(a);
    const ShellMat3N RsG = Rc.transpose() * spin(s.r[i]) * G;
    const ShellMat3N JRtG = s.Ji[i] * RtG;
    for (int b = 0; b < n; ++b) {
      Mat3 blk = RsG.block<3, 3>(0, 3 * b) - Rc.transpose() / n;
      if (a == b) blk += Rc.transpose();
      B.template block<3, 3>(6 * a, 6 * b) = blk;
      B.template block<3, 3>(6 * a + 3, 6 * b) = -JRtG.block<3, 3>(0, 3 * b);
    }
    B.template block<3, 3>(6 * a + 3, 6 * a + 3) = s.Ji[i] * Rc.transpose() * s.T[i];
  }
}

/// Adds the geometric stiffness K_G δu = δ(Bᵀ) f_l at fixed local forces f_l = [n_a; m_a].
///
/// Bᵀ f_l in global terms (N_a = Rc n_a, M_a = Rc T(θ_a)⁻ᵀ m_a, P the centroid projection):
///   f_x = P N + Gᵀ w,  w = −Σ_a (r_a × N_a + M_a),   f_ψa = T(ψ_a)ᵀ M_a.
/// Its variation, with δN_a = δω × N_a, δr_a = δx_a − δc, δθ_a from B and
/// Z_a = Rc ∂(T(θ_a)⁻ᵀ m_a)/∂θ T(θ_a)⁻¹ Rcᵀ:
///   δM_a = −spin(M_a) δω + Z_a (T(ψ_a) δψ_a − δω),
///   δw   = Σ_a spin(N_a − N̄) δx_a + Q δω − Σ_a Z_a T(ψ_a) δψ_a,
///          Q = Σ_a (spin(r_a) spin(N_a) + spin(M_a) + Z_a),
///   δf_x = −[spin(N_b − N̄) δω]_b + ∂(Gᵀw)/∂x δx + Gᵀ δw,
///   δf_ψa = ∂(T(ψ_a)ᵀ M_a)/∂ψ δψ_a + T(ψ_a)ᵀ δM_a.
/// This is the exact derivative of this formulation's Bᵀ (Nour-Omid & Rankin 1991, §5, and
/// Felippa & Haugen 2005, §7, derive the same terms as K_GR, K_GP and K_GM; here the frame is
/// the facet's own, so ∂G/∂x comes from frame_spin_derivative).
template <int n, class VecF, class MatK>
void add_geometric_stiffness_n(const CorotationalState& s, const VecF& f_l, MatK& K) {
  // Fixed corner count: the 3 × 3n operands are maps of the frame's fixed-capacity matrices.
  using Mat3N = Eigen::Matrix<double, 3, 3 * n>;
  const Mat3& Rc = s.frame.R;
  const Eigen::Map<const Mat3N> G(s.frame.G.data());
  std::array<Vec3, 4> N, M;
  std::array<Mat3, 4> Z;
  Vec3 N_mean = Vec3::Zero(), w = Vec3::Zero();
  Mat3 Q = Mat3::Zero();
  for (int a = 0; a < n; ++a) {
    const std::size_t i = static_cast<std::size_t>(a);
    N[i] = Rc * f_l.template segment<3>(6 * a);
    const Vec3 m = f_l.template segment<3>(6 * a + 3);
    M[i] = Rc * (s.Ji[i].transpose() * m);
    Z[i] = Rc * so3::d_left_jacobian_inverse_transpose(s.theta[i], m) * s.Ji[i] * Rc.transpose();
    N_mean += N[i] / n;
    w -= s.r[i].cross(N[i]) + M[i];
    Q += spin(s.r[i]) * spin(N[i]) + spin(M[i]) + Z[i];
  }
  // Translations × translations: frame curvature, centroid projection, and Gᵀ δw.
  const Mat3N QG = Q * G;
  Eigen::Matrix<double, 3 * n, 3 * n> Kxx = frame_spin_derivative(s.frame, w);
  Kxx.noalias() += G.transpose().lazyProduct(QG);
  for (int a = 0; a < n; ++a) {
    const Mat3 SN = spin(N[static_cast<std::size_t>(a)] - N_mean);
    const Mat3N SNG = SN * G;
    Kxx.template middleRows<3>(3 * a) -= SNG;              // δ(P N)
    Kxx.template middleCols<3>(3 * a) -= SNG.transpose();  // Gᵀ spin(N_a − N̄) δx_a (= −(SN G)ᵀ)
  }
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      K.template block<3, 3>(6 * a, 6 * b) += Kxx.template block<3, 3>(3 * a, 3 * b);
  // Rotation columns and rows.
  for (int a = 0; a < n; ++a) {
    const std::size_t i = static_cast<std::size_t>(a);
    const Mat3& T = s.T[i];
    const Mat3N Kxpsi_t = -((Z[i] * T).transpose() * G);             // (3n × 3)ᵀ
    const Mat3N Kpsix = -(T.transpose() * (spin(M[i]) + Z[i])) * G;  // 3 × 3n
    for (int b = 0; b < n; ++b) {
      K.template block<3, 3>(6 * b, 6 * a + 3) +=
          Kxpsi_t.template block<3, 3>(0, 3 * b).transpose();
      K.template block<3, 3>(6 * a + 3, 6 * b) += Kpsix.template block<3, 3>(0, 3 * b);
    }
    K.template block<3, 3>(6 * a + 3, 6 * a + 3) +=
        so3::d_left_jacobian_transpose(s.psi[i], M[i]) + T.transpose() * Z[i] * T;
  }
}

template <class VecF, class MatK>
void add_geometric_stiffness(const CorotationalState& s, const VecF& f_l, MatK& K) {
  if (s.frame.n == 4)
    add_geometric_stiffness_n<4>(s, f_l, K);
  else
    add_geometric_stiffness_n<3>(s, f_l, K);
}

/// Material part Bᵀ K̄ B, using the sparsity of B: the column of a nodal rotation ψ_b has only
/// the 3 × 3 block T(θ_b)⁻¹ Rcᵀ T(ψ_b) in the rows of θ_b (about half the work of dense products).
template <class MatB>
void material_stiffness(const MatB& B, const Eigen::MatrixXd& K_bar, Eigen::MatrixXd& K) {
  const int nd = static_cast<int>(B.rows());
  Mat24 KB(nd, nd);
  for (int b = 0; b < nd; b += 6) {
    KB.middleCols<3>(b).noalias() = K_bar.lazyProduct(B.template middleCols<3>(b));
    KB.middleCols<3>(b + 3).noalias() =
        K_bar.middleCols<3>(b + 3) * B.template block<3, 3>(b + 3, b + 3);
  }
  K.resize(nd, nd);
  for (int b = 0; b < nd; b += 6) {
    K.middleRows<3>(b).noalias() = B.template middleCols<3>(b).transpose().lazyProduct(KB);
    K.middleRows<3>(b + 3).noalias() =
        B.template block<3, 3>(b + 3, b + 3).transpose() * KB.middleRows<3>(b + 3);
  }
}

/// material_stiffness with fixed-size operands for ND = 6n DOFs (B and K̄ are ND × ND, stored
/// contiguously), written as column operations that vectorize: K̄ B as sums of columns of K̄
/// (dense translation columns of B, the 3 × 3 rotation block otherwise), then Bᵀ (K̄ B) as dot
/// products of contiguous columns. Same terms per entry as material_stiffness; the rounding of
/// the vectorized partial sums may differ in the last bits.
template <int ND>
void material_stiffness_fixed(const double* B_data, const double* K_bar_data, Eigen::MatrixXd& K) {
  using MatD = Eigen::Matrix<double, ND, ND>;
  using VecD = Eigen::Matrix<double, ND, 1>;
  const Eigen::Map<const MatD> B(B_data), K_bar(K_bar_data);
  MatD KB;
  for (int b = 0; b < ND; b += 6) {
    for (int j = b; j < b + 3; ++j) {
      VecD acc = K_bar.col(0) * B(0, j);
      for (int k = 1; k < ND; ++k) acc += K_bar.col(k) * B(k, j);
      KB.col(j) = acc;
    }
    for (int j = b + 3; j < b + 6; ++j)
      KB.col(j) = K_bar.col(b + 3) * B(b + 3, j) + K_bar.col(b + 4) * B(b + 4, j) +
                  K_bar.col(b + 5) * B(b + 5, j);
  }
  K.resize(ND, ND);
  for (int c = 0; c < ND; ++c)
    for (int b = 0; b < ND; b += 6) {
      for (int r = b; r < b + 3; ++r) K(r, c) = B.col(r).dot(KB.col(c));
      K.template block<3, 1>(b + 3, c).noalias() =
          B.template block<3, 3>(b + 3, b + 3).transpose() * KB.col(c).template segment<3>(b + 3);
    }
}

template <class MatB>
void material_stiffness_any(const MatB& B, const Eigen::MatrixXd& K_bar, Eigen::MatrixXd& K) {
  const auto nd = B.rows();
  if (B.cols() != nd || K_bar.rows() != nd || K_bar.cols() != nd)
    material_stiffness(B, K_bar, K);
  else if (nd == 24)  // quadrilateral
    material_stiffness_fixed<24>(B.data(), K_bar.data(), K);
  else if (nd == 18)  // triangle
    material_stiffness_fixed<18>(B.data(), K_bar.data(), K);
  else
    material_stiffness(B, K_bar, K);
}

}  // namespace

void Shell4::corotational_kinematics(const Eigen::VectorXd& u, Eigen::VectorXd& d,
                                     Eigen::MatrixXd* B) const {
  const CorotationalState s = corotate(X_, R0_, c0_, u, B != nullptr, d);
  if (B != nullptr) kinematic_matrix(s, *B);
}

void Shell4::corotational_geometric_stiffness(const Eigen::VectorXd& u, const Eigen::VectorXd& f_l,
                                              Eigen::MatrixXd& K_G) const {
  Eigen::VectorXd d;
  const CorotationalState s = corotate(X_, R0_, c0_, u, true, d);
  K_G.setZero(6 * n_, 6 * n_);
  add_geometric_stiffness(s, f_l, K_G);
}

void Shell4::plastic_tangent(
    const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K, Eigen::VectorXd& f_int,
    std::vector<PlasticState>* updated, shell::Resultants* mean,
    std::array<Eigen::Vector3d, shell::FlatShellKernel::kLayers>* layers) const {
  Eigen::MatrixXd k_l;
  Eigen::VectorXd f_l;
  if (!ctx.large_deflection) {
    if (ctx.stress_stiffening)
      throw ElementSolutionError(
          id(), fmt::format("element {}: stress stiffening without large deflection is not "
                            "implemented for SHELL181 with plasticity (use NLGEOM,ON)",
                            id()));
    const Eigen::MatrixXd A = to_local();
    kernel_->plastic_response(*plasticity_, committed_, A * u, k_l, f_l, updated, mean, layers);
    K = A.transpose() * k_l * A;
    K = 0.5 * (K + K.transpose()).eval();
    f_int = A.transpose() * f_l;
    return;
  }
  // Co-rotational (see tangent()) with the elastic-plastic local response in place of K̄ d.
  using Vec24 = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, 24, 1>;
  Vec24 d;
  const CorotationalState s = corotate(X_, R0_, c0_, u, true, d);
  Mat24 B;
  kinematic_matrix(s, B);
  const Eigen::MatrixXd W = rigid_links();
  kernel_->plastic_response(*plasticity_, committed_, W * d, k_l, f_l, updated, mean, layers);
  const Eigen::VectorXd f_bar = W.transpose() * f_l;
  f_int = B.transpose() * f_bar;
  material_stiffness_any(B, Eigen::MatrixXd(W.transpose() * k_l * W), K);
  add_geometric_stiffness(s, f_bar, K);
}

void Shell4::commit_history(const ElementContext& ctx, const Eigen::VectorXd& u) {
  if (!plasticity_) return;
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  std::vector<PlasticState> next = committed_;
  plastic_tangent(ctx, u, K, f, &next);
  committed_ = std::move(next);
}

std::vector<double> Shell4::history_state() const {
  std::vector<double> out;
  if (plasticity_)
    for (const PlasticState& s : committed_) append_state(out, s);  // point × layer
  return out;
}

void Shell4::restore_history_state(const std::vector<double>& state) {
  std::size_t pos = 0;
  if (plasticity_)
    for (PlasticState& s : committed_) read_state(state, pos, s);
  IMPACTFE_CHECK(pos == state.size(), "SHELL: saved state of the wrong length");
}

double Shell4::plastic_work() const {
  return plasticity_ ? kernel_->plastic_work(committed_) : 0.0;
}

void Shell4::tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
                     Eigen::VectorXd& f_int) const {
  if (plasticity_) {
    plastic_tangent(ctx, u, K, f_int, nullptr);
    return;
  }
  if (!ctx.large_deflection) {
    const Eigen::MatrixXd A = to_local();
    K = A.transpose() * kernel_->stiffness() * A;
    K = 0.5 * (K + K.transpose()).eval();
    if (ctx.stress_stiffening) {
      const Eigen::VectorXd d = A * u;
      K += A.transpose() * kernel_->geometric_stiffness(d) * A;
    }
    f_int = K * u;
    return;
  }
  if (triangle_) {
    triangle_->tangent(u, K, f_int);
    return;
  }
  corotational_tangent_general(u, K, f_int);
}

void Shell4::corotational_tangent_general(const Eigen::VectorXd& u, Eigen::MatrixXd& K,
                                          Eigen::VectorXd& f_int) const {
  // Co-rotational: f_int = Bᵀ K̄ d, K = Bᵀ K̄ B (material) + δ(Bᵀ) K̄ d (geometric, exact).
  using Vec24 = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, 24, 1>;
  Vec24 d;
  const CorotationalState s = corotate(X_, R0_, c0_, u, true, d);
  Mat24 B;
  kinematic_matrix(s, B);
  Eigen::MatrixXd scratch;
  const Eigen::MatrixXd& K_bar = corotational_stiffness(scratch);
  const Vec24 f_l = K_bar * d;
  f_int = B.transpose() * f_l;
  material_stiffness_any(B, K_bar, K);
  add_geometric_stiffness(s, f_l, K);
}

void Shell4::internal_force(const ElementContext& ctx, const Eigen::VectorXd& u,
                            Eigen::VectorXd& f_int) const {
  if (!separate_internal_force(ctx)) {
    Element::internal_force(ctx, u, f_int);
    return;
  }
  if (triangle_) {
    triangle_->internal_force(u, f_int);
    return;
  }
  // tangent()'s f_int = Bᵀ K̄ d (the same operations) without Bᵀ K̄ B and the geometric part.
  using Vec24 = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, 24, 1>;
  Vec24 d;
  const CorotationalState s = corotate(X_, R0_, c0_, u, true, d);
  Mat24 B;
  kinematic_matrix(s, B);
  Eigen::MatrixXd scratch;
  const Vec24 f_l = corotational_stiffness(scratch) * d;
  f_int = B.transpose() * f_l;
}

void Shell4::mass(const ElementContext& ctx, Eigen::MatrixXd& M) const {
  if (!ctx.lumped_mass) {
    const Eigen::MatrixXd A = to_local();
    M = A.transpose() * kernel_->consistent_mass() * A;
    M = 0.5 * (M + M.transpose()).eval();
    return;
  }
  // Lumped: ρtA/n on each translation, no rotary inertia; isotropic, so no transformation.
  M = kernel_->lumped_mass();
}

void Shell4::pressure_load(const ElementContext& ctx, int face, const std::array<double, 4>& p,
                           const Eigen::VectorXd& u, Eigen::VectorXd& f) const {
  if (face < 1 || face > 6)
    throw ModelError(
        fmt::format("element {}: shell face {} does not exist (faces 1 and 2: bottom "
                    "and top; 3..6: the edges J-I, K-J, L-K, I-L)",
                    id(), face));
  std::vector<Vec3> x = X_;
  if (ctx.large_deflection)
    for (int a = 0; a < n_; ++a) x[static_cast<std::size_t>(a)] += u.segment<3>(6 * a);
  f.setZero(n_dofs());
  if (face >= 3) {
    // Edge pressure (MAPDL SHELL63/SHELL181 faces 3..6), a force per unit length in the shell's
    // plane, normal to the edge, positive into the element: f_a = −∫ N_a p m ds with m the
    // in-plane outward normal of the edge; linear p: ∫ N_a p ds = ℓ (2 p_a + p_b) / 6. A
    // triangle's L is its K, so its edge L-K has no length and I-L is I-K.
    constexpr int kEdge[4][2] = {{1, 0}, {2, 1}, {3, 2}, {0, 3}};  // face-node order
    const int ia = std::min(kEdge[face - 3][0], n_ - 1);
    const int ib = std::min(kEdge[face - 3][1], n_ - 1);
    const Vec3 edge = x[static_cast<std::size_t>(ib)] - x[static_cast<std::size_t>(ia)];
    const double length = edge.norm();
    if (length == 0.0) return;
    Vec3 centroid = Vec3::Zero();
    for (const Vec3& xa : x) centroid += xa / static_cast<double>(n_);
    const Vec3 mid = 0.5 * (x[static_cast<std::size_t>(ia)] + x[static_cast<std::size_t>(ib)]);
    Vec3 m = (mid - centroid) - (mid - centroid).dot(edge) / (length * length) * edge;
    m.normalize();
    const double pa = p[0], pb = p[1];
    f.segment<3>(6 * ia) -= length * (2.0 * pa + pb) / 6.0 * m;
    f.segment<3>(6 * ib) -= length * (pa + 2.0 * pb) / 6.0 * m;
    return;
  }
  const double sign = face == 1 ? 1.0 : -1.0;
  if (n_ == 3) {
    // Flat triangle, linear pressure: ∫ N_a p dA = A (2 p_a + p_b + p_c) / 12.
    const Vec3 area = 0.5 * (x[1] - x[0]).cross(x[2] - x[0]);
    for (int a = 0; a < 3; ++a) {
      const double pa = 2.0 * p[static_cast<std::size_t>(a)] +
                        p[static_cast<std::size_t>((a + 1) % 3)] +
                        p[static_cast<std::size_t>((a + 2) % 3)];
      f.segment<3>(6 * a) = sign * pa / 12.0 * area;
    }
    return;
  }
  // Bilinear surface; n = ∂x/∂ξ × ∂x/∂η follows I-J-K-L by the right-hand rule.
  const std::array<Vec3, 4> fa = bilinear_face_pressure_forces({x[0], x[1], x[2], x[3]}, p);
  for (int a = 0; a < 4; ++a) f.segment<3>(6 * a) += sign * fa[static_cast<std::size_t>(a)];
}

namespace {
const std::vector<std::string> kShell4Results = {
    "TX",       "TY",     "TXY",    "MX",      "MY",      "MXY",    "SX_TOP",  "SY_TOP",
    "SXY_TOP",  "SX_MID", "SY_MID", "SXY_MID", "SX_BOT",  "SY_BOT", "SXY_BOT", "SEQV_TOP",
    "SEQV_BOT", "EPEQ",   "SRAT",   "PLWK",    "QXZ",     "QYZ",    "EPCRX",   "EPCRY",
    "EPCRZ",    "EPCRXY", "EPCRYZ", "EPCRXZ",  "EPCREQV", "CREQ"};
}  // namespace

const std::vector<std::string>& Shell4::names() {
  return kShell4Results;
}

const std::vector<std::string>& Shell4::layered_names() {
  static const std::vector<std::string> names =
      shell::with_layer_result_names(kShell4Results, kMaxResultLayers);
  return names;
}

const std::vector<std::string>& Shell4::result_names() const {
  return laminate_ ? layered_names() : kShell4Results;
}

Eigen::VectorXd Shell4::local_displacement(const ElementContext& ctx,
                                           const Eigen::VectorXd& u) const {
  if (!ctx.large_deflection) return apply_to_local(u);
  if (triangle_) return triangle_->deformation(u);
  Eigen::VectorXd d;
  corotational_kinematics(u, d, nullptr);
  return apply_rigid_links(std::move(d));
}

void Shell4::results(const ElementContext& ctx, const Eigen::VectorXd& u, const Eigen::VectorXd&,
                     ElementResultValues& out) const {
  shell::Resultants r;
  std::array<Eigen::Vector3d, shell::FlatShellKernel::kLayers> layers;
  double epeq = 0.0, srat = 0.0, plwk = 0.0, creq = 0.0;
  Vector6d creep = Vector6d::Zero();
  if (plasticity_) {
    // The states at u (the committed ones after a converged step).
    Eigen::MatrixXd K;
    Eigen::VectorXd f;
    std::vector<PlasticState> at = committed_;
    plastic_tangent(ctx, u, K, f, &at, &r, &layers);
    for (const PlasticState& s : at) {
      epeq = std::max(epeq, s.alpha);
      srat = std::max(
          srat, impactfe::von_mises(s.stress - s.back_stress) / plasticity_->flow_stress(s.alpha));
    }
    plwk = kernel_->plastic_work(at) / kernel_->volume();
    if (plasticity_->has_creep()) {
      // Implicit creep: the inelastic strain is the creep strain (EPCR at the top surface, as
      // S; NL CREQ the largest accumulated equivalent creep strain); no plastic items.
      creep = kernel_->layer_inelastic_strain(at, shell::FlatShellKernel::kLayers - 1);
      creq = epeq;
      epeq = srat = plwk = 0.0;
    }
  } else {
    r = kernel_->resultants(local_displacement(ctx, u));
  }
  // Rotate the in-plane tensors to the THETA axes.
  const double cs = std::cos(theta_), sn = std::sin(theta_);
  auto rot = [&](const Eigen::Vector3d& s) {
    return Eigen::Vector3d(s(0) * cs * cs + s(1) * sn * sn + 2.0 * s(2) * sn * cs,
                           s(0) * sn * sn + s(1) * cs * cs - 2.0 * s(2) * sn * cs,
                           (s(1) - s(0)) * sn * cs + s(2) * (cs * cs - sn * sn));
  };
  const Eigen::Vector3d N = rot(r.N), Mm = rot(r.M);
  // Transverse shear forces per length (SHELL181's Mindlin kernel; zero for SHELL63's DK).
  const Eigen::Vector2d Q(cs * r.Q(0) + sn * r.Q(1), -sn * r.Q(0) + cs * r.Q(1));
  // The creep strain in the THETA axes: in-plane as a tensor (engineering shear halved, then
  // doubled back), the transverse shears as a vector.
  const Eigen::Vector3d creep_in_plane = rot(Eigen::Vector3d(creep(0), creep(1), 0.5 * creep(3)));
  const double creep_xz = cs * creep(5) + sn * creep(4), creep_yz = -sn * creep(5) + cs * creep(4);
  // Elastic: linear through the thickness; plastic: the layer stresses (surfaces and middle).
  Eigen::Vector3d mid = plasticity_ ? rot(layers[2]) : Eigen::Vector3d(N / r.t);
  Eigen::Vector3d top =
      plasticity_ ? rot(layers[4]) : Eigen::Vector3d(mid + 6.0 * Mm / (r.t * r.t));
  Eigen::Vector3d bot =
      plasticity_ ? rot(layers[0]) : Eigen::Vector3d(mid - 6.0 * Mm / (r.t * r.t));
  // A laminate: the mid-surface strain ε0 = A⁻¹N and curvature κ = D⁻¹M (B = 0), each layer's
  // stress Q̄ (ε0 + z κ) (classical lamination, Jones §4.2), piecewise linear through the
  // thickness: TOP and BOT the top of the top layer and the bottom of the bottom one, MID z = 0
  // in the layer holding it.
  std::vector<double> layer_values;
  if (laminate_) {
    const Eigen::Vector3d e0 = laminate_->A.ldlt().solve(r.N);
    const Eigen::Vector3d kappa = laminate_->D.ldlt().solve(r.M);
    const auto& plies = laminate_->plies;
    const auto stress = [&](std::size_t k, double z) { return rot(plies[k].Q * (e0 + z * kappa)); };
    std::size_t mid_layer = 0;
    while (mid_layer + 1 < plies.size() && plies[mid_layer].z_top <= 0.0) ++mid_layer;
    top = stress(plies.size() - 1, plies.back().z_top);
    mid = stress(mid_layer, 0.0);
    bot = stress(0, plies.front().z_bot);
    for (std::size_t k = 0; k < plies.size(); ++k)
      for (const double z :
           {plies[k].z_top, 0.5 * (plies[k].z_top + plies[k].z_bot), plies[k].z_bot}) {
        const Eigen::Vector3d s = stress(k, z);
        layer_values.insert(layer_values.end(),
                            {s(0), s(1), s(2), shell::plane_stress_von_mises(s(0), s(1), s(2))});
      }
  }
  out = {N(0),
         N(1),
         N(2),
         Mm(0),
         Mm(1),
         Mm(2),
         top(0),
         top(1),
         top(2),
         mid(0),
         mid(1),
         mid(2),
         bot(0),
         bot(1),
         bot(2),
         shell::plane_stress_von_mises(top(0), top(1), top(2)),
         shell::plane_stress_von_mises(bot(0), bot(1), bot(2)),
         epeq,
         srat,
         plwk,
         Q(0),
         Q(1),
         creep_in_plane(0),
         creep_in_plane(1),
         creep(2),
         2.0 * creep_in_plane(2),
         creep_yz,
         creep_xz,
         equivalent_inelastic_strain(creep),
         creq};
  if (laminate_) {
    out.insert(out.end(), layer_values.begin(), layer_values.end());
    out.resize(layered_names().size(), 0.0);
  }
}

Eigen::Matrix3d Shell4::result_axes(const ElementContext& ctx, const Eigen::VectorXd& u) const {
  Mat3 R = R0_;
  if (ctx.large_deflection && u.size() == 6 * n_) {
    // The co-rotated frame that results() measures the deformation in (corotate above).
    ShellCorners x(3, n_);
    for (int a = 0; a < n_; ++a) x.col(a) = X_[static_cast<std::size_t>(a)] + u.segment<3>(6 * a);
    R = shell_frame(x, false).R;
  }
  // results() rotates the in-plane tensors to x' = cos θ e1 + sin θ e2 (THETA).
  const double cs = std::cos(theta_), sn = std::sin(theta_);
  Mat3 A;
  A.col(0) = cs * R.col(0) + sn * R.col(1);
  A.col(1) = -sn * R.col(0) + cs * R.col(1);
  A.col(2) = R.col(2);
  return A;
}

}  // namespace impactfe
