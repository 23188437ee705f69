// SHELL281: the 8-node quadratic degenerated-continuum shell (shell281.h), its factory and
// registration.
#include "elements/shell281.h"

#include <fmt/format.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <set>

#include "core/errors.h"
#include "elements/element_registry.h"
#include "elements/quadratic_shapes.h"
#include "elements/shell_frame.h"
#include "elements/shell_kernel.h"
#include "materials/isotropic_elasticity.h"

namespace impactfe {

namespace {

using Mat3 = Eigen::Matrix3d;

/// Natural coordinates of the nodes: the quadrilateral's corners, then its midsides; the
/// triangle's corners (0,0) (1,0) (0,1), then the midsides of 0-1 1-2 2-0 (quadratic_shapes.h).
constexpr double kQuadXi[8][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1},
                                  {0, -1},  {1, 0},  {0, 1}, {-1, 0}};
constexpr double kTriXi[6][2] = {{0, 0}, {1, 0}, {0, 1}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}};

/// Two-point Gauss through the thickness: exact for the strain energy of a homogeneous shell
/// whose strains are linear in ζ (the flat element; O(t/R) close to it on a curved one).
constexpr double kZeta = 0.57735026918962576;
constexpr bool kAssumedShear = true;

Mat3 skew(const Vec3& v) {
  Mat3 s;
  s << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return s;
}

const std::vector<std::string> kShell281Results = {
    "TX",       "TY",       "TXY",     "MX",      "MY",       "MXY",     "SX_TOP",   "SY_TOP",
    "SXY_TOP",  "SX_MID",   "SY_MID",  "SXY_MID", "SX_BOT",   "SY_BOT",  "SXY_BOT",  "SEQV_TOP",
    "SEQV_MID", "SEQV_BOT", "QXZ",     "QYZ",     "EPX_TOP",  "EPY_TOP", "EPXY_TOP", "EPX_MID",
    "EPY_MID",  "EPXY_MID", "EPX_BOT", "EPY_BOT", "EPXY_BOT", "EPEQ",    "PLWK",     "EPCRX",
    "EPCRY",    "EPCRZ",    "EPCRXY",  "EPCRYZ",  "EPCRXZ",   "EPCREQV", "CREQ"};

}  // namespace

Shell281::Shell281(int id, const Shell281Data& data, const SourceLocation& where)
    : Element(id),
      n_(static_cast<int>(data.node_ids.size())),
      X_(data.positions),
      t_(data.thickness),
      node_ids_(data.node_ids),
      data_(data),
      zeta0_(data.offset) {
  IMPACTFE_CHECK(n_ == 8 || n_ == 6, "SHELL281: 8 or 6 nodes");
  if (data.laminate.plies.empty()) {
    // One homogeneous isotropic layer.
    const double c = data.E / (1.0 - data.nu * data.nu);
    Mat3 Q;
    Q << c, c * data.nu, 0, c * data.nu, c, 0, 0, 0, c * 0.5 * (1.0 - data.nu);
    const double G = data.E / (2.0 * (1.0 + data.nu));
    layers_.push_back(
        {-1.0, 1.0, Q, data.shear_factor * G * Eigen::Matrix2d::Identity(), data.rho});
  } else {
    // The laminate's layers at their share of the thickness, the transverse shear scaled by
    // the section's correction factors (shell_laminate.h).
    const shell::Laminate& lam = data.laminate;
    const Eigen::Vector2d k = lam.shear_factor.cwiseSqrt();
    for (const shell::Ply& p : lam.plies)
      layers_.push_back({2.0 * p.z_bot / lam.thickness, 2.0 * p.z_top / lam.thickness, p.Q,
                         k.asDiagonal() * p.G * k.asDiagonal(), p.rho});
    layers_.back().zeta_top = 1.0;
  }
  for (const Layer& l : layers_) drill_g_ += 0.5 * (l.zeta_top - l.zeta_bot) * l.Q(2, 2);
  if (layers_.size() > static_cast<std::size_t>(kMaxResultLayers))
    throw InputError(where, fmt::format("element {}: {} layers; at most {} are carried out", id,
                                        layers_.size(), kMaxResultLayers));
  // Membrane only (KEYOPT(1) = 1): the translations alone, as MAPDL's membrane shells have
  // (the rotations would carry no stiffness).
  for (int node : data.node_ids)
    for (Dof d : kAllDofs)
      if (!data.membrane_only || d == Dof::UX || d == Dof::UY || d == Dof::UZ)
        dofs_.push_back(DofKey{node, d});
  // Nodal directors: the element's own surface normal at each node.
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  for (int a = 0; a < n_; ++a) {
    const double* xi = n_ == 8 ? kQuadXi[a] : kTriXi[a];
    shape(xi[0], xi[1], N, dN);
    Vec3 a1 = Vec3::Zero(), a2 = Vec3::Zero();
    for (int b = 0; b < n_; ++b) {
      a1 += dN(0, b) * X_[static_cast<std::size_t>(b)];
      a2 += dN(1, b) * X_[static_cast<std::size_t>(b)];
    }
    const Vec3 n = a1.cross(a2);
    if (!(n.norm() > 0.0))
      throw InputError(where, fmt::format("element {}: zero area at node {} (coincident or "
                                          "collinear nodes)",
                                          id, data.node_ids[static_cast<std::size_t>(a)]));
    V_.push_back(n.normalized());
  }
  for (const Rule& q : full_rule())
    for (double zeta : {-kZeta, kZeta}) {
      double detJ = 0.0;
      const Mat3 R = Mat3::Identity();
      gradient(q.xi, q.eta, zeta, R, &detJ);
      if (!(detJ > 0.0))
        throw InputError(where, fmt::format("element {}: non-positive Jacobian (distorted "
                                            "element, or thickness large against the curvature)",
                                            id));
      volume_ += detJ * q.w;
    }
  if (data_.plasticity) committed_.assign(bending_rule().size() * kPlasticPoints, PlasticState{});
}

void Shell281::shape(double xi, double eta, Eigen::VectorXd& N, Eigen::MatrixXd& dN) const {
  Eigen::Matrix<double, 2, Eigen::Dynamic> d;
  Eigen::VectorXd corner;
  quadratic_face_shape(n_, Eigen::Vector3d(xi, eta, 0.0), N, d, corner);
  dN = d;
}

double Shell281::thickness_at(const Eigen::VectorXd& N) const {
  double t = 0.0;
  for (int a = 0; a < n_; ++a) t += N(a) * t_[static_cast<std::size_t>(a)];
  return t;
}

std::vector<Shell281::ThicknessPoint> Shell281::thickness_rule() const {
  if (data_.membrane_only) return {{0.0, 2.0, 0}};
  return layer_points();
}

std::vector<Shell281::ThicknessPoint> Shell281::layer_points() const {
  std::vector<ThicknessPoint> out;
  for (std::size_t k = 0; k < layers_.size(); ++k) {
    const double mid = 0.5 * (layers_[k].zeta_top + layers_[k].zeta_bot);
    const double half = 0.5 * (layers_[k].zeta_top - layers_[k].zeta_bot);
    out.push_back({mid - half * kZeta, half, k});
    out.push_back({mid + half * kZeta, half, k});
  }
  return out;
}

Mat3 Shell281::mean_q() const {
  Mat3 Q = Mat3::Zero();
  for (const Layer& l : layers_) Q += 0.5 * (l.zeta_top - l.zeta_bot) * l.Q;
  return Q;
}

std::vector<Shell281::Rule> Shell281::full_rule() const {
  std::vector<Rule> out;
  for (const QuadraturePoint& q : n_ == 8 ? gauss_square(3) : collapsed_triangle(3))
    out.push_back({q.xi(0), q.xi(1), q.weight});
  return out;
}

std::vector<Shell281::Rule> Shell281::bending_rule() const {
  if (n_ == 8) return full_rule();
  // The triangle's midside rule: exact to degree 2 (Zienkiewicz & Taylor vol. 1, Table 6.3).
  return {{0.5, 0.0, 1.0 / 6.0}, {0.5, 0.5, 1.0 / 6.0}, {0.0, 0.5, 1.0 / 6.0}};
}

std::vector<Shell281::Rule> Shell281::shear_rule() const {
  if (n_ == 6) return bending_rule();
  if (kAssumedShear) return full_rule();
  std::vector<Rule> out;
  for (const QuadraturePoint& q : gauss_square(2)) out.push_back({q.xi(0), q.xi(1), q.weight});
  return out;
}

Mat3 Shell281::frame(const Eigen::VectorXd& N, const Eigen::MatrixXd& dN, double* dA) const {
  Vec3 a1 = Vec3::Zero(), a2 = Vec3::Zero();
  for (int a = 0; a < n_; ++a) {
    a1 += dN(0, a) * X_[static_cast<std::size_t>(a)];
    a2 += dN(1, a) * X_[static_cast<std::size_t>(a)];
  }
  const Vec3 n = a1.cross(a2);
  if (dA != nullptr) *dA = n.norm();
  Mat3 R;
  R.col(2) = n.normalized();
  R.col(0) = data_.esys_axes ? shell_esys_x_axis(*data_.esys_axes, R.col(2)) : a1.normalized();
  R.col(1) = R.col(2).cross(R.col(0));
  return R;
}

Eigen::MatrixXd Shell281::global_gradient(double xi, double eta, double zeta, double* detJ) const {
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  shape(xi, eta, N, dN);
  // J: rows ∂X/∂ξ, ∂X/∂η, ∂X/∂ζ, so that (f,ξ f,η f,ζ)ᵀ = J ∇f.
  Mat3 J = Mat3::Zero();
  for (int a = 0; a < n_; ++a) {
    const double h = 0.5 * t_[static_cast<std::size_t>(a)];
    const Vec3 x =
        X_[static_cast<std::size_t>(a)] + (zeta + zeta0_) * h * V_[static_cast<std::size_t>(a)];
    J.row(0) += dN(0, a) * x.transpose();
    J.row(1) += dN(1, a) * x.transpose();
    J.row(2) += N(a) * h * V_[static_cast<std::size_t>(a)].transpose();
  }
  if (detJ != nullptr) *detJ = J.determinant();
  const Mat3 Ji = J.inverse();
  // ∂U_i/∂X_j (row 3i + j): U = Σ N_a u_a + Σ ζ h_a N_a θ_a × V_a, and
  // (θ × V)_i = θ · (V × E_i).
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(9, 6 * n_);
  for (int a = 0; a < n_; ++a) {
    const double h = 0.5 * t_[static_cast<std::size_t>(a)];
    const Vec3 g = Ji * Vec3(dN(0, a), dN(1, a), 0.0);
    const double z = zeta + zeta0_;
    const Vec3 r = h * (Ji * Vec3(z * dN(0, a), z * dN(1, a), N(a)));
    const Vec3& V = V_[static_cast<std::size_t>(a)];
    for (int i = 0; i < 3; ++i) {
      const Vec3 c = V.cross(Vec3::Unit(i));
      for (int j = 0; j < 3; ++j) {
        G(3 * i + j, 6 * a + i) = g(j);
        G.block<1, 3>(3 * i + j, 6 * a + 3) = r(j) * c.transpose();
      }
    }
  }
  return G;
}

Eigen::MatrixXd Shell281::gradient(double xi, double eta, double zeta, const Mat3& R,
                                   double* detJ) const {
  const Eigen::MatrixXd G = global_gradient(xi, eta, zeta, detJ);
  // L_pq = Σ_ij R_ip R_jq ∂U_i/∂X_j.
  Eigen::MatrixXd L = Eigen::MatrixXd::Zero(9, 6 * n_);
  for (int p = 0; p < 3; ++p)
    for (int q = 0; q < 3; ++q)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          const double w = R(i, p) * R(j, q);
          if (w != 0.0) L.row(3 * p + q) += w * G.row(3 * i + j);
        }
  return L;
}

Eigen::MatrixXd Shell281::strains(const Eigen::MatrixXd& G) {
  Eigen::MatrixXd B(5, G.cols());
  B.row(0) = G.row(0);
  B.row(1) = G.row(4);
  B.row(2) = G.row(1) + G.row(3);
  B.row(3) = G.row(2) + G.row(6);
  B.row(4) = G.row(5) + G.row(7);
  return B;
}

Eigen::MatrixXd Shell281::covariant_shear(double xi, double eta, double zeta) const {
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  shape(xi, eta, N, dN);
  // Base vectors g_ξ, g_η, g_ζ and the operators of ∂U/∂ξ, ∂U/∂η, ∂U/∂ζ (3 × 6n each), with
  // U = Σ N_a u_a − Σ ζ h_a N_a (V_a ×) θ_a.
  Vec3 g[3] = {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  Eigen::MatrixXd dU[3];
  for (auto& m : dU) m = Eigen::MatrixXd::Zero(3, 6 * n_);
  for (int a = 0; a < n_; ++a) {
    const double h = 0.5 * t_[static_cast<std::size_t>(a)];
    const Vec3& V = V_[static_cast<std::size_t>(a)];
    const Vec3 x = X_[static_cast<std::size_t>(a)] + (zeta + zeta0_) * h * V;
    g[0] += dN(0, a) * x;
    g[1] += dN(1, a) * x;
    g[2] += N(a) * h * V;
    const Mat3 S = -h * skew(V);
    dU[0].block<3, 3>(0, 6 * a) = dN(0, a) * Mat3::Identity();
    dU[1].block<3, 3>(0, 6 * a) = dN(1, a) * Mat3::Identity();
    dU[0].block<3, 3>(0, 6 * a + 3) = (zeta + zeta0_) * dN(0, a) * S;
    dU[1].block<3, 3>(0, 6 * a + 3) = (zeta + zeta0_) * dN(1, a) * S;
    dU[2].block<3, 3>(0, 6 * a + 3) = N(a) * S;
  }
  // γ_ξζ = g_ξ·∂U/∂ζ + g_ζ·∂U/∂ξ, γ_ηζ likewise.
  Eigen::MatrixXd E(2, 6 * n_);
  E.row(0) = g[0].transpose() * dU[2] + g[2].transpose() * dU[0];
  E.row(1) = g[1].transpose() * dU[2] + g[2].transpose() * dU[1];
  return E;
}

Eigen::MatrixXd Shell281::assumed_shear(double xi, double eta, double zeta, const Mat3& R) const {
  // Assumed covariant transverse shear: γ_ξζ = c0 + c1 ξ + c2 η + c3 ξη + c4 η², tied at the
  // four points (±a, ±1) of the sides η = ±1 (a = 1/√3) and at the centre; γ_ηζ the same with
  // ξ and η exchanged. The side values depend on that side's nodes alone and are shared with the
  // neighbour, so an n × n mesh carries ~6 shear constraints per element against ~9 bending
  // DOFs; 2 × 2 Gauss (8 per element) over-constrains the clamped thin plate (w at a/t = 1000
  // on 8 × 8 elements: 0.66 of Kirchhoff's).
  const double a = 0.57735026918962576;
  auto tied = [&](int row, double s, double r, bool swap) {
    // s: the coordinate along the tying sides, r: across them.
    auto at = [&](double along, double across) {
      return swap ? covariant_shear(across, along, zeta).row(row).eval()
                  : covariant_shear(along, across, zeta).row(row).eval();
    };
    const Eigen::RowVectorXd e0 = at(0.0, 0.0);
    const Eigen::RowVectorXd e1 = at(-a, -1.0), e2 = at(a, -1.0);
    const Eigen::RowVectorXd e3 = at(-a, 1.0), e4 = at(a, 1.0);
    return (e0 * (1.0 - r * r) + 0.25 * (r * r + r) * (e3 + e4) + 0.25 * (r * r - r) * (e1 + e2) +
            s / (2.0 * a) * (0.5 * (1.0 + r) * (e4 - e3) + 0.5 * (1.0 - r) * (e2 - e1)))
        .eval();
  };
  const Eigen::RowVectorXd ex = tied(0, xi, eta, false);
  const Eigen::RowVectorXd ey = tied(1, eta, xi, true);
  double detJ = 0.0;
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  shape(xi, eta, N, dN);
  Mat3 J = Mat3::Zero();
  for (int b = 0; b < n_; ++b) {
    const double h = 0.5 * t_[static_cast<std::size_t>(b)];
    const Vec3 x =
        X_[static_cast<std::size_t>(b)] + (zeta + zeta0_) * h * V_[static_cast<std::size_t>(b)];
    J.row(0) += dN(0, b) * x.transpose();
    J.row(1) += dN(1, b) * x.transpose();
    J.row(2) += N(b) * h * V_[static_cast<std::size_t>(b)].transpose();
  }
  detJ = J.determinant();
  (void)detJ;
  const Mat3 Ji = J.inverse();
  const double c3 = Ji.col(2).dot(R.col(2));
  Eigen::MatrixXd B(2, 6 * n_);
  for (int i = 0; i < 2; ++i)
    B.row(i) = c3 * (Ji.col(0).dot(R.col(i)) * ex + Ji.col(1).dot(R.col(i)) * ey);
  return B;
}

Eigen::MatrixXd Shell281::shear_b(double xi, double eta, double zeta, const Mat3& R) const {
  if (n_ == 8 && kAssumedShear) return assumed_shear(xi, eta, zeta, R);
  return strains(gradient(xi, eta, zeta, R, nullptr)).bottomRows(2);
}

Eigen::MatrixXd Shell281::stiffness() const {
  const Eigen::MatrixXd K = membrane_bending_stiffness() + shear_drilling_stiffness();
  return 0.5 * (K + K.transpose());
}

Eigen::MatrixXd Shell281::membrane_bending_stiffness() const {
  const int nd = 6 * n_;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(nd, nd);
  const Mat3 Qm = mean_q();
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  // Membrane and bending, layer by layer (membrane only: the mid-surface, twice the weight of
  // ζ ∈ [−1, 1], with the thickness-averaged stiffness).
  const std::vector<ThicknessPoint> rule = thickness_rule();
  for (const Rule& q : bending_rule()) {
    shape(q.xi, q.eta, N, dN);
    const Mat3 R = frame(N, dN, nullptr);
    for (const ThicknessPoint& z : rule) {
      double detJ = 0.0;
      const Eigen::MatrixXd B = strains(gradient(q.xi, q.eta, z.zeta, R, &detJ)).topRows(3);
      const Mat3& Q = data_.membrane_only ? Qm : layers_[z.layer].Q;
      K.noalias() += B.transpose() * Q * B * (detJ * q.w * z.w);
    }
  }
  return K;
}

Eigen::MatrixXd Shell281::shear_drilling_stiffness() const {
  const int nd = 6 * n_;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(nd, nd);
  const double G = drill_g_;
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  const std::vector<ThicknessPoint> rule = thickness_rule();
  if (!data_.membrane_only)
    for (const Rule& q : shear_rule()) {
      shape(q.xi, q.eta, N, dN);
      const Mat3 R = frame(N, dN, nullptr);
      for (const ThicknessPoint& z : rule) {
        double detJ = 0.0;
        gradient(q.xi, q.eta, z.zeta, R, &detJ);
        const Eigen::MatrixXd B = shear_b(q.xi, q.eta, z.zeta, R);
        K.noalias() += B.transpose() * layers_[z.layer].Gs * B * (detJ * q.w * z.w);
      }
    }
  // Drilling: γ ∫ (θ·e3 − ½(L_yx − L_xy))² dA on the mid-surface (Hughes & Brezzi 1989, eq. 4.1
  // with their γ = G); a rigid rotation ω gives θ·e3 = ω·e3 = ½ curl, so no energy. None for
  // the membrane-only element, which has no rotations (θ = 0 would penalise the curl).
  if (!data_.membrane_only)
    for (const Rule& q : full_rule()) {
      shape(q.xi, q.eta, N, dN);
      double dA = 0.0;
      const Mat3 R = frame(N, dN, &dA);
      const Eigen::MatrixXd L = gradient(q.xi, q.eta, 0.0, R, nullptr);
      Eigen::RowVectorXd b = -0.5 * (L.row(3) - L.row(1));
      for (int a = 0; a < n_; ++a) b.segment<3>(6 * a + 3) += N(a) * R.col(2).transpose();
      const double gamma = data_.drill_factor * G * thickness_at(N);
      K.noalias() += b.transpose() * b * (gamma * dA * q.w);
    }
  return K;
}

Eigen::MatrixXd Shell281::geometric_stiffness(const Eigen::VectorXd& u) const {
  // K_G = ∫ Σ_i (∂U_i/∂X)ᵀ σ (∂U_i/∂X) dV with σ the stress of u in global axes (Cook et al.
  // §18.3); σ33 = 0.
  const int nd = 6 * n_;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(nd, nd);
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  for (const Rule& q : bending_rule()) {
    shape(q.xi, q.eta, N, dN);
    const Mat3 R = frame(N, dN, nullptr);
    for (const ThicknessPoint& z : thickness_rule()) {
      const double zeta = z.zeta;
      double detJ = 0.0;
      const Eigen::MatrixXd Gg = global_gradient(q.xi, q.eta, zeta, &detJ);
      const Eigen::VectorXd e = strains(gradient(q.xi, q.eta, zeta, R, nullptr)) * u;
      const Layer& l = layers_[z.layer];
      const Eigen::Vector3d sm = (data_.membrane_only ? mean_q() : l.Q) * e.head<3>();
      const Eigen::Vector2d sq =
          data_.membrane_only ? Eigen::Vector2d::Zero() : (l.Gs * e.tail<2>()).eval();
      const double s13 = sq(0), s23 = sq(1);
      Mat3 S;
      S << sm(0), sm(2), s13, sm(2), sm(1), s23, s13, s23, 0.0;
      const Mat3 sigma = R * S * R.transpose();
      for (int i = 0; i < 3; ++i) {
        const Eigen::MatrixXd Gi = Gg.middleRows(3 * i, 3);
        K.noalias() += Gi.transpose() * sigma * Gi * (detJ * q.w * z.w);
      }
    }
  }
  return 0.5 * (K + K.transpose());
}

Eigen::VectorXd Shell281::expand(const Eigen::VectorXd& u) const {
  if (!data_.membrane_only) return u;
  Eigen::VectorXd full = Eigen::VectorXd::Zero(6 * n_);
  for (int a = 0; a < n_; ++a) full.segment<3>(6 * a) = u.segment<3>(3 * a);
  return full;
}

Eigen::MatrixXd Shell281::reduce(const Eigen::MatrixXd& A) const {
  if (!data_.membrane_only) return A;
  Eigen::MatrixXd out(3 * n_, 3 * n_);
  for (int a = 0; a < n_; ++a)
    for (int b = 0; b < n_; ++b) out.block<3, 3>(3 * a, 3 * b) = A.block<3, 3>(6 * a, 6 * b);
  return out;
}

void Shell281::tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
                       Eigen::VectorXd& f_int) const {
  if (data_.plasticity) {
    if (ctx.stress_stiffening)
      throw ElementSolutionError(
          id(), fmt::format("element {}: stress stiffening is not implemented for SHELL281 with "
                            "plasticity or creep",
                            id()));
    plastic_sum(u, K, f_int, nullptr);  // never membrane only (refused when built)
    return;
  }
  K = reduce(stiffness());
  f_int = K * u;
  if (ctx.stress_stiffening) K += reduce(geometric_stiffness(expand(u)));
}

void Shell281::mass(const ElementContext& ctx, Eigen::MatrixXd& M) const {
  const int nd = 6 * n_;
  M = Eigen::MatrixXd::Zero(nd, nd);
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  double total = 0.0;
  for (const Rule& q : full_rule()) {
    shape(q.xi, q.eta, N, dN);
    double dA = 0.0;
    const Mat3 R = frame(N, dN, &dA);
    double rho_mean = 0.0;  // the thickness-averaged density
    for (const ThicknessPoint& z : layer_points()) {
      const double zeta = z.zeta, rho = layers_[z.layer].rho * z.w;
      rho_mean += 0.5 * rho;
      double detJ = 0.0;
      global_gradient(q.xi, q.eta, zeta, &detJ);
      // H: U = Σ N_a u_a − Σ ζ h_a N_a (V_a ×) θ_a.
      Eigen::MatrixXd H = Eigen::MatrixXd::Zero(3, nd);
      for (int a = 0; a < n_; ++a) {
        H.block<3, 3>(0, 6 * a) = N(a) * Mat3::Identity();
        H.block<3, 3>(0, 6 * a + 3) = -(zeta + zeta0_) * 0.5 * t_[static_cast<std::size_t>(a)] *
                                      N(a) * skew(V_[static_cast<std::size_t>(a)]);
      }
      M.noalias() += H.transpose() * H * (rho * detJ * q.w);
      total += rho * detJ * q.w;
    }
    // The drilling rotation carries the rotary inertia ρt³/12 of the other two (the directors
    // give it none), as SHELL181's θz does.
    const double t = thickness_at(N);
    Eigen::RowVectorXd b = Eigen::RowVectorXd::Zero(nd);
    for (int a = 0; a < n_; ++a) b.segment<3>(6 * a + 3) = N(a) * R.col(2).transpose();
    M.noalias() += b.transpose() * b * (rho_mean * t * t * t / 12.0 * dA * q.w);
  }
  M = 0.5 * (M + M.transpose()).eval();
  if (!ctx.lumped_mass) {
    M = reduce(M);
    return;
  }
  // HRZ: the diagonal, scaled so that each translation carries the element's mass; the
  // rotations keep their diagonal terms.
  Eigen::MatrixXd L = Eigen::MatrixXd::Zero(nd, nd);
  for (int i = 0; i < 3; ++i) {
    double sum = 0.0;
    for (int a = 0; a < n_; ++a) sum += M(6 * a + i, 6 * a + i);
    for (int a = 0; a < n_; ++a)
      L(6 * a + i, 6 * a + i) = sum > 0.0 ? total * M(6 * a + i, 6 * a + i) / sum : 0.0;
  }
  for (int a = 0; a < n_; ++a)
    for (int i = 3; i < 6; ++i) L(6 * a + i, 6 * a + i) = M(6 * a + i, 6 * a + i);
  M = reduce(L);
}

void Shell281::pressure_load(const ElementContext& ctx, int face, const std::array<double, 4>& p,
                             const Eigen::VectorXd& u, Eigen::VectorXd& f) const {
  full_pressure_load(ctx, face, p, u, f);
  if (!data_.membrane_only) return;
  Eigen::VectorXd translations(3 * n_);
  for (int a = 0; a < n_; ++a) translations.segment<3>(3 * a) = f.segment<3>(6 * a);
  f = translations;
}

void Shell281::full_pressure_load(const ElementContext& ctx, int face,
                                  const std::array<double, 4>& p, const Eigen::VectorXd&,
                                  Eigen::VectorXd& f) const {
  if (face < 1 || face > 6)
    throw ModelError(
        fmt::format("element {}: shell face {} does not exist (faces 1 and 2: bottom "
                    "and top; 3..6: the edges J-I, K-J, L-K, I-L)",
                    id(), face));
  if (ctx.large_deflection)
    throw ElementSolutionError(id(), fmt::format("element {}: SHELL281 under large deflection "
                                                 "is not implemented",
                                                 id()));
  f.setZero(6 * n_);
  if (face >= 3) {
    // In-plane edge pressure: f_a = −∫ N_a p m ds, m the outward in-plane normal of the edge,
    // p linear between the edge's corner values; 3-point Gauss on the quadratic edge.
    constexpr int kQuadEdge[4][3] = {{1, 0, 4}, {2, 1, 5}, {3, 2, 6}, {0, 3, 7}};
    constexpr int kTriEdge[4][3] = {{1, 0, 3}, {2, 1, 4}, {-1, -1, -1}, {0, 2, 5}};
    const int* e = n_ == 8 ? kQuadEdge[face - 3] : kTriEdge[face - 3];
    if (e[0] < 0) return;  // the triangle's collapsed L-K
    Vec3 centroid = Vec3::Zero();
    for (const Vec3& x : X_) centroid += x / static_cast<double>(n_);
    const double gs[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
    const double gw[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
    for (int g = 0; g < 3; ++g) {
      const double s = gs[g];
      const double Ne[3] = {0.5 * s * (s - 1.0), 0.5 * s * (s + 1.0), 1.0 - s * s};
      const double dNe[3] = {s - 0.5, s + 0.5, -2.0 * s};
      Vec3 x = Vec3::Zero(), dx = Vec3::Zero(), n = Vec3::Zero();
      for (int k = 0; k < 3; ++k) {
        x += Ne[k] * X_[static_cast<std::size_t>(e[k])];
        dx += dNe[k] * X_[static_cast<std::size_t>(e[k])];
        n += Ne[k] * V_[static_cast<std::size_t>(e[k])];
      }
      Vec3 m = dx.cross(n);
      if (m.dot(x - centroid) < 0.0) m = -m;
      m.normalize();
      const double pressure = 0.5 * (1.0 - s) * p[0] + 0.5 * (1.0 + s) * p[1];
      for (int k = 0; k < 3; ++k)
        f.segment<3>(6 * e[k]) -= Ne[k] * pressure * dx.norm() * gw[g] * m;
    }
    return;
  }
  const double sign = face == 1 ? 1.0 : -1.0;
  Eigen::VectorXd N, corner;
  Eigen::Matrix<double, 2, Eigen::Dynamic> dN;
  for (const Rule& q : full_rule()) {
    quadratic_face_shape(n_, Eigen::Vector3d(q.xi, q.eta, 0.0), N, dN, corner);
    Vec3 a1 = Vec3::Zero(), a2 = Vec3::Zero();
    for (int a = 0; a < n_; ++a) {
      a1 += dN(0, a) * X_[static_cast<std::size_t>(a)];
      a2 += dN(1, a) * X_[static_cast<std::size_t>(a)];
    }
    double pressure = 0.0;
    for (int c = 0; c < static_cast<int>(corner.size()); ++c)
      pressure += corner(c) * p[static_cast<std::size_t>(c)];
    const Vec3 load = sign * pressure * q.w * a1.cross(a2);
    for (int a = 0; a < n_; ++a) f.segment<3>(6 * a) += N(a) * load;
  }
}

const std::vector<std::string>& Shell281::names() {
  return kShell281Results;
}

const std::vector<std::string>& Shell281::layered_names() {
  static const std::vector<std::string> names =
      shell::with_layer_result_names(kShell281Results, kMaxResultLayers);
  return names;
}

const std::vector<std::string>& Shell281::result_names() const {
  return layered() ? layered_names() : kShell281Results;
}

ElementResultValues Shell281::values_at(double xi, double eta, const Eigen::VectorXd& u) const {
  if (data_.plasticity) {
    // The values of the states at the points, interpolated at (ξ, η).
    const std::vector<ElementResultValues> at = plastic_point_values(u);
    const std::vector<double> w = point_weights(xi, eta);
    ElementResultValues out(at.front().size(), 0.0);
    for (std::size_t p = 0; p < at.size(); ++p)
      for (std::size_t i = 0; i < out.size(); ++i) out[i] += w[p] * at[p][i];
    return out;
  }
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  shape(xi, eta, N, dN);
  const Mat3 R = frame(N, dN, nullptr);
  const double t = thickness_at(N), h = 0.5 * t;
  const Mat3 Qm = mean_q();
  auto strain = [&](double zeta) -> Eigen::VectorXd {
    return strains(gradient(xi, eta, data_.membrane_only ? 0.0 : zeta, R, nullptr)) * u;
  };
  // The stress at ζ in layer k (the membrane element: the mean stiffness).
  auto stress = [&](double zeta, std::size_t k) -> Eigen::Vector3d {
    return (data_.membrane_only ? Qm : layers_[k].Q) * strain(zeta).head<3>();
  };
  // Resultants by the thickness rule: N = ∫σ dz, M = ∫zσ dz (z = ζ t/2 toward the top, about
  // the mid-surface), Q = ∫ k G γ dz.
  Eigen::Vector3d Nr = Eigen::Vector3d::Zero(), Mr = Eigen::Vector3d::Zero();
  Eigen::Vector2d Q = Eigen::Vector2d::Zero();
  for (const ThicknessPoint& z : thickness_rule()) {
    const Eigen::Vector3d s = stress(z.zeta, z.layer);
    Nr += s * h * z.w;
    Mr += s * z.zeta * h * h * z.w;
    if (!data_.membrane_only)
      Q += layers_[z.layer].Gs * (shear_b(xi, eta, z.zeta, R) * u) * h * z.w;
  }
  // TOP and BOT: the top of the top layer, the bottom of the bottom one; MID: ζ = 0 in the layer
  // that holds it (the upper one at an interface).
  std::size_t mid_layer = 0;
  while (mid_layer + 1 < layers_.size() && layers_[mid_layer].zeta_top <= 0.0) ++mid_layer;
  const Eigen::VectorXd et = strain(1.0), em = strain(0.0), eb = strain(-1.0);
  const Eigen::Vector3d st = stress(1.0, layers_.size() - 1), sm = stress(0.0, mid_layer),
                        sb = stress(-1.0, 0);
  ElementResultValues out = {Nr(0),
                             Nr(1),
                             Nr(2),
                             Mr(0),
                             Mr(1),
                             Mr(2),
                             st(0),
                             st(1),
                             st(2),
                             sm(0),
                             sm(1),
                             sm(2),
                             sb(0),
                             sb(1),
                             sb(2),
                             shell::plane_stress_von_mises(st(0), st(1), st(2)),
                             shell::plane_stress_von_mises(sm(0), sm(1), sm(2)),
                             shell::plane_stress_von_mises(sb(0), sb(1), sb(2)),
                             Q(0),
                             Q(1),
                             et(0),
                             et(1),
                             et(2),
                             em(0),
                             em(1),
                             em(2),
                             eb(0),
                             eb(1),
                             eb(2)};
  out.resize(kShell281Results.size(), 0.0);  // elastic: no inelastic strain
  if (!layered()) return out;
  // Each layer's stresses at its top, middle and bottom (layered_names() order); the unused
  // layers' columns stay zero.
  out.resize(layered_names().size(), 0.0);
  for (std::size_t k = 0; k < layers_.size(); ++k) {
    const Layer& l = layers_[k];
    std::size_t i = kShell281Results.size() + 12 * k;
    for (const double zeta : {l.zeta_top, 0.5 * (l.zeta_top + l.zeta_bot), l.zeta_bot}) {
      const Eigen::Vector3d s = stress(zeta, k);
      out[i] = s(0), out[i + 1] = s(1), out[i + 2] = s(2);
      out[i + 3] = shell::plane_stress_von_mises(s(0), s(1), s(2));
      i += 4;
    }
  }
  return out;
}

Eigen::Matrix3d Shell281::result_axes(const ElementContext&, const Eigen::VectorXd&) const {
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  if (n_ == 8)
    shape(0.0, 0.0, N, dN);
  else
    shape(1.0 / 3.0, 1.0 / 3.0, N, dN);
  return frame(N, dN, nullptr);
}

void Shell281::results(const ElementContext&, const Eigen::VectorXd& u, const Eigen::VectorXd&,
                       ElementResultValues& out) const {
  out = n_ == 8 ? values_at(0.0, 0.0, expand(u)) : values_at(1.0 / 3.0, 1.0 / 3.0, expand(u));
}

namespace {

/// values_at()'s values in axes turned by φ (cos φ = c, sin φ = s) about the normal: the
/// in-plane tensors (N, M, the surfaces' S and EPEL, engineering shear strains) and Q.
ElementResultValues in_centre_axes(ElementResultValues v, double c, double s) {
  const auto tensor = [&](std::size_t i, double shear) {
    const double x = v[i], y = v[i + 1], xy = shear * v[i + 2];
    v[i] = c * c * x + s * s * y - 2.0 * c * s * xy;
    v[i + 1] = s * s * x + c * c * y + 2.0 * c * s * xy;
    v[i + 2] = (c * s * (x - y) + (c * c - s * s) * xy) / shear;
  };
  for (std::size_t i : {0, 3, 6, 9, 12}) tensor(i, 1.0);
  for (std::size_t i : {20, 23, 26}) tensor(i, 0.5);
  // A layered element's layer stresses (Shell281::layered_names()), SEQV unchanged.
  for (std::size_t i = Shell281::names().size(); i + 4 <= v.size(); i += 4) tensor(i, 1.0);
  const double qx = v[18], qy = v[19];
  v[18] = c * qx - s * qy;
  v[19] = s * qx + c * qy;
  return v;
}

}  // namespace

bool Shell281::nodal_results(const ElementContext&, const Eigen::VectorXd& u,
                             std::map<int, ElementResultValues>& at_node) const {
  // With plasticity or creep the values depend on the history, which only the solution holds:
  // the stored centroid values stand for the nodes (as for SHELL181 and MAPDL's ERESX for a
  // nonlinear material, which copies the integration points' values).
  if (data_.plasticity) return false;
  // Extrapolated from the 2 x 2 Gauss points of the quadrilateral (the 3 points of the triangle)
  // as MAPDL's SHELL281 reports its nodal results (ERESX default for a linear material): the
  // bilinear (linear) field through the points' values, evaluated at the nodes, so a midside
  // takes the mean of its corners. The 8-node field evaluated at a corner directly carries the
  // spurious membrane stresses of a curved element (Cook's barrel vault, vm42: +190 kPa of hoop
  // membrane stress at the crown node) that the Gauss points do not.
  const Eigen::VectorXd ue = expand(u);
  constexpr double g = 0.57735026918962576;
  const std::vector<std::array<double, 2>> points =
      n_ == 8 ? std::vector<std::array<double, 2>>{{-g, -g}, {g, -g}, {g, g}, {-g, g}}
              : std::vector<std::array<double, 2>>{
                    {1.0 / 6.0, 1.0 / 6.0}, {2.0 / 3.0, 1.0 / 6.0}, {1.0 / 6.0, 2.0 / 3.0}};
  const auto basis = [&](double xi, double eta) {
    Eigen::VectorXd b(points.size());
    b(0) = 1.0, b(1) = xi, b(2) = eta;
    if (points.size() == 4) b(3) = xi * eta;
    return b;
  };
  const auto np = static_cast<Eigen::Index>(points.size());
  Eigen::MatrixXd V(np, np);
  std::vector<ElementResultValues> at_points;
  const Mat3 R0 = result_axes(ElementContext{}, u);
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  for (Eigen::Index k = 0; k < np; ++k) {
    const auto& p = points[static_cast<std::size_t>(k)];
    V.row(k) = basis(p[0], p[1]).transpose();
    // The point's values are in its lamina frame: turned into the centre frame (the axes POST1
    // rotates the nodal values with) by the in-plane angle between the frames' e1.
    shape(p[0], p[1], N, dN);
    const Mat3 R = frame(N, dN, nullptr);
    const double c = R0.col(0).dot(R.col(0)), sn = R0.col(1).dot(R.col(0)),
                 norm = std::hypot(c, sn);
    at_points.push_back(in_centre_axes(values_at(p[0], p[1], ue), c / norm, sn / norm));
  }
  const Eigen::MatrixXd Vinv = V.inverse();
  const std::size_t n_values = at_points.front().size();
  for (int a = 0; a < n_; ++a) {
    const double* xi = n_ == 8 ? kQuadXi[a] : kTriXi[a];
    const Eigen::VectorXd w = Vinv.transpose() * basis(xi[0], xi[1]);
    ElementResultValues v(n_values, 0.0);
    for (Eigen::Index k = 0; k < np; ++k)
      for (std::size_t i = 0; i < n_values; ++i)
        v[i] += w(k) * at_points[static_cast<std::size_t>(k)][i];
    // The equivalent stresses of the extrapolated components (not extrapolated themselves).
    for (int s = 0; s < 3; ++s)
      v[static_cast<std::size_t>(15 + s)] = shell::plane_stress_von_mises(
          v[static_cast<std::size_t>(6 + 3 * s)], v[static_cast<std::size_t>(7 + 3 * s)],
          v[static_cast<std::size_t>(8 + 3 * s)]);
    for (std::size_t i = names().size(); i + 4 <= v.size(); i += 4)
      v[i + 3] = shell::plane_stress_von_mises(v[i], v[i + 1], v[i + 2]);
    at_node[node_ids_[static_cast<std::size_t>(a)]] = std::move(v);
  }
  return true;
}

}  // namespace impactfe
