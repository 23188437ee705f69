// Finite strain of the 3-D solids (elements/solid_finite_strain.h), the formulation MAPDL
// documents for its 18x solids (Theory Reference §3.2 "Large Strain": updated Lagrangian,
// hypoelastic, so small elastic but arbitrarily large plastic strain; the logarithmic strain
// accumulated from increments; Cauchy stress). The 3-D form of plane_solid_finite.cpp:
//
//  * Midpoint configuration (Hughes & Winget 1980): with the committed displacement u_n and the
//    current u, Δu = u − u_n, the increment gradient L = ∂Δu/∂x_½ = ΔH F_½⁻¹ (ΔH = ∂Δu/∂X,
//    F_½ = I + ∂(u_n + ½Δu)/∂X). Strain increment Δε = sym L (second-order accurate for the
//    logarithmic strain increment), spin ΔW = skew L.
//  * Incremental rotation ΔR = (I − ½ΔW)⁻¹ (I + ½ΔW) (Hughes & Winget 1980): orthogonal, exact
//    for a rigid rotation below 180° in one increment (the midpoint L then has Δε = 0).
//  * Stress update σ_{n+1} = ΔR σ̂ ΔRᵀ, σ̂ the return of the J2 law (or D ε, elastic) from the
//    committed state at the strain ε_n + ΔRᵀ Δε ΔR. For the isotropic laws this is the
//    objective update σ_{n+1} = ΔR σ_n ΔRᵀ + C : Δε when elastic; the committed strain,
//    plastic strain and back stress are rotated by ΔR when a step is accepted, so every state
//    is in global axes of the current configuration.
//  * Internal force on the current configuration: f_a = ∫ σ ∇_x N_a dv, dv = det F dV₀.
//  * Tangent: the exact derivative of f (δ∇_x N = −δlᵀ ∇_x N, δdv = tr δl dv), per DOF pair
//    j, k with δl_j = ∂(δu_j)/∂x:
//        K_jk = ∫ [ δσ_k : δl_j − σ : (δl_j δl_k) + (σ : δl_j) tr δl_k ] dv,
//    δσ_k through the midpoint kinematics δL = (I − ½L) δH F_½⁻¹, the derivative of ΔR,
//    ∂ΔR/∂ω_m = ½ (I − ½ΔW)⁻¹ G_m (I + ΔR) (G_m the generator of the axial component m), and the
//    algorithmic tangent of the law; the σ-terms are the initial-stress stiffness. It is not
//    symmetric (rotation and volume terms of the order of σ, midpoint terms of the order of the
//    increment). Its symmetric part is a poor Newton matrix once σ is comparable with the
//    plastic tangent modulus (the 20-node brick's iterations stall in uniaxial plastic flow
//    with E_t = 2000, σ ≈ 300): the symmetric solvers get FiniteStrainTangent::Symmetric
//    instead, the material term ∫ δε̄ᵀ C δε̄ dv (the law's algorithmic tangent rotated by ΔR)
//    plus the initial-stress term ∫ ∇N_a·σ∇N_b I dv, the stress stiffness of MAPDL's
//    large-strain solids (Theory Reference §3.2); Newton then converges linearly, in a few
//    more iterations.
//  * Mean dilatation (SOLID185 B-bar): the volumetric part of each point's Δε replaced by its
//    element mean (reference volume weights), the rate form of Hughes (1980).
#include "elements/solid_finite_strain.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <array>

#include "core/errors.h"

namespace impactfe {

namespace {

using Mat3f = Eigen::Matrix3d;

/// Symmetric tensor of a Voigt vector (xx yy zz xy yz xz), `shear` times the shear entries (½
/// for an engineering strain, 1 for a stress).
Mat3f sym_tensor3(const Vector6d& v, double shear) {
  Mat3f t;
  t << v(0), shear * v(3), shear * v(5), shear * v(3), v(1), shear * v(4), shear * v(5),
      shear * v(4), v(2);
  return t;
}

Vector6d voigt3(const Mat3f& t, double shear) {
  Vector6d v;
  v << t(0, 0), t(1, 1), t(2, 2), shear * 0.5 * (t(0, 1) + t(1, 0)),
      shear * 0.5 * (t(1, 2) + t(2, 1)), shear * 0.5 * (t(0, 2) + t(2, 0));
  return v;
}

Vector6d rotate_strain3(const Mat3f& r, const Vector6d& e) {
  return voigt3(r * sym_tensor3(e, 0.5) * r.transpose(), 2.0);
}

Vector6d rotate_stress3(const Mat3f& r, const Vector6d& s) {
  return voigt3(r * sym_tensor3(s, 1.0) * r.transpose(), 1.0);
}

/// G_m: ΔW = Σ ω_m G_m for the axial vector ω = (W_zy, W_xz, W_yx).
const std::array<Mat3f, 3>& spin_generators3() {
  static const std::array<Mat3f, 3> g = [] {
    std::array<Mat3f, 3> out;
    for (Mat3f& m : out) m.setZero();
    out[0](2, 1) = 1.0, out[0](1, 2) = -1.0;
    out[1](0, 2) = 1.0, out[1](2, 0) = -1.0;
    out[2](1, 0) = 1.0, out[2](0, 1) = -1.0;
    return out;
  }();
  return g;
}

/// Symmetric basis of the strain increment q(0..5) = (xx yy zz xy yz xz), tensor shear.
const std::array<Mat3f, 6>& strain_basis3() {
  static const std::array<Mat3f, 6> e = [] {
    std::array<Mat3f, 6> out;
    for (Mat3f& m : out) m.setZero();
    out[0](0, 0) = out[1](1, 1) = out[2](2, 2) = 1.0;
    out[3](0, 1) = out[3](1, 0) = 1.0;
    out[4](1, 2) = out[4](2, 1) = 1.0;
    out[5](0, 2) = out[5](2, 0) = 1.0;
    return out;
  }();
  return e;
}

/// Kinematics of one point.
struct PointKinematics3 {
  Eigen::Matrix3Xd h;                           // ∇_x N of the current configuration
  double det = 0.0;                             // det F
  double dv0 = 0.0;                             // reference measure
  Eigen::Matrix<double, 9, 1> q;                // Δε xx yy zz xy yz xz (tensor shear), ω
  Eigen::Matrix<double, 9, Eigen::Dynamic> dq;  // ∂q/∂u (9 x 3n)
};

/// Pass 1 of finite_strain_sum at one point: F_½, L, ∇_x N, the increment q and ∂q/∂u.
void point_kinematics3(const FiniteStrainElement& element, const FiniteStrainPoint& point,
                       const Eigen::Matrix3Xd& u_n, const Eigen::Matrix3Xd& du,
                       PointKinematics3& k) {
  const auto nn = du.cols();
  const auto nd = 3 * nn;
  const Eigen::Matrix3Xd& g0 = point.grad;  // ∂N/∂X
  k.dv0 = point.dv0;
  const Mat3f fn = Mat3f::Identity() + u_n * g0.transpose();
  const Mat3f dh = du * g0.transpose();
  const Mat3f fh = fn + 0.5 * dh;
  const Mat3f f_cur = fn + dh;
  const Mat3f fh_inv = fh.inverse();
  const Mat3f l = dh * fh_inv;
  k.det = f_cur.determinant();
  if (!(k.det > 0.0))
    throw ElementSolutionError(
        element.id,
        fmt::format("element {}: the deformation turned an integration point inside out "
                    "(det F = {:.3g}); a smaller load increment may help",
                    element.id, k.det));
  const Eigen::Matrix3Xd gh = fh_inv.transpose() * g0;  // ∇_{x½} N
  k.h = f_cur.inverse().transpose() * g0;
  const Mat3f m = Mat3f::Identity() - 0.5 * l;  // δL = (I − ½L) δH F_½⁻¹
  k.q << l(0, 0), l(1, 1), l(2, 2), 0.5 * (l(0, 1) + l(1, 0)), 0.5 * (l(1, 2) + l(2, 1)),
      0.5 * (l(0, 2) + l(2, 0)), 0.5 * (l(2, 1) - l(1, 2)), 0.5 * (l(0, 2) - l(2, 0)),
      0.5 * (l(1, 0) - l(0, 1));
  k.dq.setZero(9, nd);
  for (Eigen::Index b = 0; b < nn; ++b)
    for (int i = 0; i < 3; ++i) {
      const Mat3f dl = m.col(i) * gh.col(b).transpose();
      const Eigen::Index j = 3 * b + i;
      k.dq(0, j) = dl(0, 0);
      k.dq(1, j) = dl(1, 1);
      k.dq(2, j) = dl(2, 2);
      k.dq(3, j) = 0.5 * (dl(0, 1) + dl(1, 0));
      k.dq(4, j) = 0.5 * (dl(1, 2) + dl(2, 1));
      k.dq(5, j) = 0.5 * (dl(0, 2) + dl(2, 0));
      k.dq(6, j) = 0.5 * (dl(2, 1) - dl(1, 2));
      k.dq(7, j) = 0.5 * (dl(0, 2) - dl(2, 0));
      k.dq(8, j) = 0.5 * (dl(1, 0) - dl(0, 1));
    }
}

/// Mean dilatation of the increment over the reference volume (Hughes 1980, rate form): the
/// volumetric part of each point's q replaced by the element mean.
void mean_dilatation3(std::vector<PointKinematics3>& kin, double v0, Eigen::Index nd) {
  double theta = 0.0;
  Eigen::RowVectorXd dtheta = Eigen::RowVectorXd::Zero(nd);
  for (const PointKinematics3& k : kin) {
    theta += k.dv0 / v0 * k.q.head<3>().sum();
    dtheta += k.dv0 / v0 * k.dq.topRows<3>().colwise().sum();
  }
  for (PointKinematics3& k : kin) {
    const double shift = (theta - k.q.head<3>().sum()) / 3.0;
    const Eigen::RowVectorXd dshift = (dtheta - k.dq.topRows<3>().colwise().sum()) / 3.0;
    for (int r = 0; r < 3; ++r) {
      k.q(r) += shift;
      k.dq.row(r) += dshift;
    }
  }
}

/// ∂σ/∂q (6 x 9): the law's tangent through ΔRᵀ Δε ΔR (columns Δε), and the rotation of σ̂
/// through ∂ΔR/∂ω_m = ½ (I − ½ΔW)⁻¹ G_m (I + ΔR) (columns ω).
Eigen::Matrix<double, 6, 9> stress_derivative3(const Mat3f& rot, const Mat3f& a_inv,
                                               const Mat3f& d2, const Mat3f& sh3,
                                               const Matrix6d& c_alg) {
  const auto& gen = spin_generators3();
  const auto& basis = strain_basis3();
  Eigen::Matrix<double, 6, 9> ds;
  for (int m = 0; m < 6; ++m) {
    const Mat3f& e = basis[static_cast<std::size_t>(m)];
    const Vector6d dsh = c_alg * voigt3(rot.transpose() * e * rot, 2.0);
    ds.col(m) = voigt3(rot * sym_tensor3(dsh, 1.0) * rot.transpose(), 1.0);
  }
  for (int m = 0; m < 3; ++m) {
    const Mat3f drot = 0.5 * a_inv * gen[static_cast<std::size_t>(m)] * (Mat3f::Identity() + rot);
    const Mat3f de = drot.transpose() * d2 * rot + rot.transpose() * d2 * drot;
    const Vector6d dsh = c_alg * voigt3(de, 2.0);
    const Mat3f dsig = drot * sh3 * rot.transpose() +
                       rot * sym_tensor3(dsh, 1.0) * rot.transpose() + rot * sh3 * drot.transpose();
    ds.col(6 + m) = voigt3(dsig, 1.0);
  }
  return ds;
}

/// FiniteStrainTangent::Symmetric: ∫ δε̄_jᵀ C̃ δε̄_k dv (tensor shears: the shear rows count
/// twice in the contraction) and the initial-stress stiffness δ_ij ∫ ∇N_bj · σ ∇N_bk dv.
void add_symmetric_tangent3(const PointKinematics3& k, const Eigen::Matrix<double, 6, 9>& ds,
                            const Mat3f& s3, double dv, Eigen::MatrixXd& kk) {
  const auto nn = k.h.cols();
  Eigen::Matrix<double, 6, Eigen::Dynamic> weighted = k.dq.topRows<6>();
  weighted.bottomRows<3>() *= 2.0;
  kk.noalias() += dv * (weighted.transpose() * (ds.leftCols<6>() * k.dq.topRows<6>()));
  const Eigen::MatrixXd g = dv * (k.h.transpose() * (s3 * k.h));
  for (Eigen::Index bj = 0; bj < nn; ++bj)
    for (Eigen::Index bk = 0; bk < nn; ++bk)
      for (int i = 0; i < 3; ++i) kk(3 * bj + i, 3 * bk + i) += g(bj, bk);
}

/// The exact tangent K_jk = ∫ [ δσ_k : δl_j − σ : (δl_j δl_k) + (σ : δl_j) tr δl_k ] dv.
void add_exact_tangent3(const PointKinematics3& k, const Eigen::Matrix<double, 6, 9>& ds,
                        const Eigen::Matrix3Xd& sh_all, const Eigen::Map<const Eigen::VectorXd>& a,
                        double dv, Eigen::MatrixXd& kk) {
  const auto nn = k.h.cols();
  const Eigen::MatrixXd dsigma = ds * k.dq;  // 6 x nd
  for (Eigen::Index bk = 0; bk < nn; ++bk)
    for (int ik = 0; ik < 3; ++ik) {
      const Eigen::Index col = 3 * bk + ik;
      // δσ_k : δl_j = (δσ_k ∇N_bj)_ij for every j at once.
      const Eigen::Matrix3Xd dsh = sym_tensor3(dsigma.col(col), 1.0) * k.h;
      const double tr = k.h(ik, bk);  // tr δl_k
      for (Eigen::Index bj = 0; bj < nn; ++bj) {
        const double hj = k.h(ik, bj);
        for (int ij = 0; ij < 3; ++ij) {
          const Eigen::Index row = 3 * bj + ij;
          // − σ : (δl_j δl_k) = −(∇N_bj · e_ik) (σ ∇N_bk)_ij; + (σ : δl_j) tr δl_k.
          kk(row, col) += dv * (dsh(ij, bj) - hj * sh_all(ij, bk) + a(row) * tr);
        }
      }
    }
}

}  // namespace

void finite_strain_sum(const FiniteStrainElement& element, const Eigen::Matrix3Xd& u_n,
                       const Eigen::Matrix3Xd& u, const std::vector<FiniteStrainState>& committed,
                       Eigen::MatrixXd* K, Eigen::VectorXd& f, FiniteStrainUpdate* update,
                       FiniteStrainTangent form) {
  const std::vector<FiniteStrainPoint>& points = *element.points;
  const auto nn = u.cols();
  const auto nd = 3 * nn;
  const std::size_t np = points.size();
  const Eigen::Matrix3Xd du = u - u_n;

  // Pass 1: kinematics of every point (the mean dilatation couples the points).
  std::vector<PointKinematics3> kin(np);
  double v0 = 0.0;
  for (std::size_t p = 0; p < np; ++p) {
    point_kinematics3(element, points[p], u_n, du, kin[p]);
    v0 += kin[p].dv0;
  }
  if (element.mean_dilatation) mean_dilatation3(kin, v0, nd);

  // Pass 2: the law at every point, internal force and tangent.
  f.setZero(nd);
  if (K) K->setZero(nd, nd);
  if (update) {
    update->states.resize(np);
    update->stress.resize(np);
    update->dv.resize(np);
  }
  const auto& gen = spin_generators3();
  for (std::size_t p = 0; p < np; ++p) {
    const PointKinematics3& k = kin[p];
    Mat3f w = Mat3f::Zero();
    for (int m = 0; m < 3; ++m) w += k.q(6 + m) * gen[static_cast<std::size_t>(m)];
    const Mat3f a_inv = (Mat3f::Identity() - 0.5 * w).inverse();
    const Mat3f rot = a_inv * (Mat3f::Identity() + 0.5 * w);
    Mat3f d2;
    d2 << k.q(0), k.q(3), k.q(5), k.q(3), k.q(1), k.q(4), k.q(5), k.q(4), k.q(2);
    // The increment rotated back to the axes of the committed state: ΔRᵀ Δε ΔR.
    const Vector6d strain = committed[p].strain + voigt3(rot.transpose() * d2 * rot, 2.0);
    Vector6d s_hat;
    Matrix6d c_alg;
    PlasticState next;
    if (element.plasticity) {
      const PlasticResponse r = element.plasticity->solid(committed[p].plastic, strain, &next);
      s_hat = r.stress;
      c_alg = r.tangent;
    } else {
      s_hat = element.d * strain;
      c_alg = element.d;
    }
    const Mat3f sh3 = sym_tensor3(s_hat, 1.0);
    const Mat3f s3 = rot * sh3 * rot.transpose();
    const double dv = k.det * k.dv0;
    // σ : δl_j per DOF (the integrand of f): (σ ∇_x N_b)_i.
    const Eigen::Matrix3Xd sh_all = s3 * k.h;
    const Eigen::Map<const Eigen::VectorXd> a(sh_all.data(), nd);
    f.noalias() += dv * a;
    if (update) {
      FiniteStrainState st;
      st.strain = rotate_strain3(rot, strain);
      if (element.plasticity) {
        next.plastic_strain = rotate_strain3(rot, next.plastic_strain);
        next.back_stress = rotate_stress3(rot, next.back_stress);
        next.stress = rotate_stress3(rot, next.stress);
        st.plastic = next;
      }
      update->states[p] = st;
      update->stress[p] = voigt3(s3, 1.0);
      update->dv[p] = dv;
    }
    if (!K) continue;
    const Eigen::Matrix<double, 6, 9> ds = stress_derivative3(rot, a_inv, d2, sh3, c_alg);
    if (form == FiniteStrainTangent::Symmetric)
      add_symmetric_tangent3(k, ds, s3, dv, *K);
    else
      add_exact_tangent3(k, ds, sh_all, a, dv, *K);
  }
}

}  // namespace impactfe
