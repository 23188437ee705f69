// Large deflection (NLGEOM,ON) of PLANE182 / PLANE183 (elements/plane_solid.h): finite strain
// and finite rotation in the formulation MAPDL documents for its 18x solids (Theory Reference,
// §3.2 "Large Strain": updated Lagrangian, hypoelastic, so small elastic but arbitrarily large
// plastic strain; the logarithmic strain accumulated from increments; Cauchy stress):
//
//  * Midpoint configuration (Theory Reference §3.2.2; Hughes & Winget 1980, eqs. for the
//    "midpoint" integration): with the committed displacement u_n and the current u,
//    Δu = u − u_n, x_½ = X + u_n + ½Δu, the increment gradient L = ∂Δu/∂x_½ = ΔH F_½⁻¹
//    (ΔH = ∂Δu/∂X, F_½ = I + ∂(u_n + ½Δu)/∂X). Strain increment Δε = sym L (second-order
//    accurate for the logarithmic strain increment), spin ΔW = skew L; in axisymmetry the hoop
//    increment Δu_r / r_½.
//  * Incremental rotation (Hughes & Winget 1980): ΔR = (I − ½ΔW)⁻¹ (I + ½ΔW), exact for a
//    rigid rotation of any angle below 180° in one increment (with the midpoint L, Δε = 0).
//  * Stress update: σ_{n+1} = ΔR σ̂ ΔRᵀ, σ̂ the return of the J2 law (or D ε, elastic) from the
//    committed state at the strain ε_n + ΔRᵀ Δε ΔR. For the isotropic laws here this is
//    σ_{n+1} = ΔR σ_n ΔRᵀ + C : Δε when elastic (the rotation commutes with the return); the
//    committed strain, plastic strain and back stress are rotated by ΔR when a step is accepted,
//    so that every state is in global axes of the current configuration.
//  * Internal force on the current configuration: f_a = ∫ σ ∇_x N_a dv (+ σ_θ N_a / r dv in
//    axisymmetry); dv = det F dV₀ (× r/R in axisymmetry, × the thickness stretch exp(ε_zz) in
//    plane stress).
//  * Tangent: the exact derivative of f with respect to u (δ∇_x N = −∇_x N δl, δdv = tr δl dv),
//    written per DOF pair j, k with δl_j = ∂(δu_j)/∂x:
//        K_jk = ∫ [ δσ_k : δl_j − σ : (δl_j δl_k) + (σ : δl_j) tr δl_k ] dv,
//    δσ_k through the midpoint kinematics δL = (I − ½L) δH F_½⁻¹, the derivative of ΔR and the
//    algorithmic tangent of the law (the initial-stress stiffness is the σ-terms). It is not
//    symmetric (the rotation terms, of the order of σ/E, and the midpoint kinematics, of the
//    order of the increment); tangent() assembles its symmetric part for the symmetric solvers. In
//    plane stress the change of thickness enters the tangent through the elastic relation δε_zz =
//    −ν/(1−ν) tr δε (exact while elastic).
//  * B-bar (PLANE182 KEYOPT(1) = 0, plane strain and axisymmetry): the volumetric part of each
//    point's Δε replaced by its mean over the element (reference volume weights), the rate form
//    of the mean dilatation of the small-strain element.
#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "elements/plane_solid.h"

namespace impactfe {

namespace {

using Mat2 = Eigen::Matrix2d;
using Vec4 = Eigen::Vector4d;

/// ΔR = (I − ½W)⁻¹ (I + ½W) for W = [[0, −ω], [ω, 0]], c = ω/2 (Hughes & Winget 1980): the
/// rotation by 2 atan(c).
Mat2 incremental_rotation(double c) {
  const double s = 1.0 / (1.0 + c * c);
  Mat2 r;
  r << s * (1.0 - c * c), -2.0 * s * c, 2.0 * s * c, s * (1.0 - c * c);
  return r;
}

/// In-plane tensor of (xx, yy, zz, xy) with `shear` times the xy entry (½ for an engineering
/// strain, 1 for a stress).
Mat2 in_plane(const Vec4& v, double shear) {
  Mat2 t;
  t << v(0), shear * v(3), shear * v(3), v(1);
  return t;
}

Vec4 voigt(const Mat2& t, double zz, double shear) {
  return Vec4(t(0, 0), t(1, 1), zz, shear * t(0, 1));
}

Vec4 rotate_strain(const Mat2& r, const Vec4& e) {
  return voigt(r * in_plane(e, 0.5) * r.transpose(), e(2), 2.0);
}

Vec4 rotate_stress(const Mat2& r, const Vec4& s) {
  return voigt(r * in_plane(s, 1.0) * r.transpose(), s(2), 1.0);
}

/// The in-plane part of a Voigt 6-vector (xx, yy, zz, xy, yz, xz) rotated about z (yz, xz are
/// zero in the plane elements and stay so).
Vector6d rotate6(const Mat2& r, const Vector6d& v, bool strain) {
  Vector6d out = v;
  const Vec4 in = v.head<4>();
  out.head<4>() = strain ? rotate_strain(r, in) : rotate_stress(r, in);
  return out;
}

}  // namespace

struct PlaneSolid::FiniteUpdate {
  std::vector<FiniteState> finite;  // rotated into the current configuration
  PointStates plastic;              // rotated likewise
  std::vector<Vec4> stress;         // Cauchy
};

Eigen::Vector4d PlaneSolid::elastic_strain(const Eigen::Vector4d& s) const {
  const double e = young_, nu = poisson_;
  return Vec4((s(0) - nu * (s(1) + s(2))) / e, (s(1) - nu * (s(0) + s(2))) / e,
              (s(2) - nu * (s(0) + s(1))) / e, 2.0 * (1.0 + nu) * s(3) / e);
}

/// Kinematics of one point (pass 1 of finite_sum; the mean dilatation of B-bar couples them).
struct PlaneSolid::FiniteKinematics {
  Eigen::VectorXd n;
  Eigen::Matrix2Xd h;             // ∇_x N of the current configuration
  Mat2 l;                         // L = ∂Δu/∂x_½ (in-plane)
  double lzz = 0.0;               // hoop increment Δu_r / r_½ (axisymmetry)
  double r = 0.0;                 // current radius
  double r0 = 0.0;                // reference radius
  double det = 0.0;               // det F (in-plane)
  double dv0 = 0.0;               // reference measure
  Eigen::Matrix<double, 5, 1> q;  // Δε xx yy zz xy (tensor shear), ω
  Eigen::MatrixXd dq;             // ∂q/∂u (5 x nd)
};

/// The law's response at one point (pass 2 of finite_sum), in the current configuration.
struct PlaneSolid::FiniteResponse {
  Mat2 rot;               // ΔR
  Mat2 drot;              // ∂ΔR/∂ω
  Mat2 d2;                // Δε (in-plane tensor)
  Vec4 strain;            // ε_n + ΔRᵀ Δε ΔR, the law's strain in the committed axes
  Vec4 s_hat;             // σ̂, the law's stress in the committed axes
  Eigen::Matrix4d c_alg;  // dσ̂/dε
  PlasticState next;      // the law's state at the strain
  double ezz = 0.0;       // thickness (plane stress) or zz strain
  Mat2 sh2;               // σ̂ in-plane
  Mat2 s2;                // σ = ΔR σ̂ ΔRᵀ in-plane
  Vec4 sigma;             // Cauchy stress
  double dv = 0.0;        // current measure
};

namespace {

/// Mean dilatation of the increment over the reference volume (Hughes 1980, rate form): B-bar
/// replaces the volumetric part of each point's q by the element mean.
template <class Kinematics>
void plane_mean_dilatation(std::vector<Kinematics>& kin, double v0, int nd) {
  double theta = 0.0;
  Eigen::RowVectorXd dtheta = Eigen::RowVectorXd::Zero(nd);
  for (const Kinematics& k : kin) {
    theta += k.dv0 / v0 * k.q.template head<3>().sum();
    dtheta += k.dv0 / v0 * k.dq.topRows(3).colwise().sum();
  }
  for (Kinematics& k : kin) {
    const double shift = (theta - k.q.template head<3>().sum()) / 3.0;
    const Eigen::RowVectorXd dshift = (dtheta - k.dq.topRows(3).colwise().sum()) / 3.0;
    for (int r = 0; r < 3; ++r) {
      k.q(r) += shift;
      k.dq.row(r) += dshift;
    }
  }
}

/// ∂σ/∂q (4 x 5): the law's tangent through ΔRᵀ Δε ΔR (columns Δε) and the rotation of σ̂
/// (column ω).
Eigen::Matrix<double, 4, 5> plane_stress_derivative(const Mat2& rot, const Mat2& drot,
                                                    const Mat2& d2, const Mat2& sh2,
                                                    const Eigen::Matrix4d& c_alg) {
  Eigen::Matrix<double, 4, 5> ds;
  for (int m = 0; m < 4; ++m) {
    Mat2 e2 = Mat2::Zero();
    double ezz_m = 0.0;
    if (m == 0) e2(0, 0) = 1.0;
    if (m == 1) e2(1, 1) = 1.0;
    if (m == 2) ezz_m = 1.0;
    if (m == 3) e2(0, 1) = e2(1, 0) = 1.0;
    const Vec4 dsh = c_alg * voigt(rot.transpose() * e2 * rot, ezz_m, 2.0);
    ds.col(m) = voigt(rot * in_plane(dsh, 1.0) * rot.transpose(), dsh(2), 1.0);
  }
  {
    const Mat2 de = drot.transpose() * d2 * rot + rot.transpose() * d2 * drot;
    const Vec4 dsh = c_alg * voigt(de, 0.0, 2.0);
    const Mat2 dsig = drot * sh2 * rot.transpose() + rot * in_plane(dsh, 1.0) * rot.transpose() +
                      rot * sh2 * drot.transpose();
    ds.col(4) = voigt(dsig, dsh(2), 1.0);
  }
  return ds;
}

}  // namespace

void PlaneSolid::finite_kinematics(std::size_t p, const Eigen::Map<const Eigen::Matrix2Xd>& un,
                                   const Eigen::Matrix2Xd& du, FiniteKinematics& k) const {
  const int nn = static_cast<int>(nodes_.size());
  const int nd = 2 * nn;
  const bool axi = options_.behaviour == PlaneBehaviour::Axisymmetric;
  const Point pt = point_at(rule_[p].xi.head<2>());
  k.n = pt.n;
  k.dv0 = measure(pt, rule_[p].weight);
  const Eigen::Matrix2Xd& g0 = pt.grad;  // ∂N/∂X
  const Mat2 fn = Mat2::Identity() + un * g0.transpose();
  const Mat2 dh = du * g0.transpose();
  const Mat2 fh = fn + 0.5 * dh;
  const Mat2 f_cur = fn + dh;
  const Mat2 fh_inv = fh.inverse();
  k.l = dh * fh_inv;
  k.det = f_cur.determinant();
  if (!(k.det > 0.0))
    throw ElementSolutionError(
        id(), fmt::format("element {}: the deformation turned an integration point inside out "
                          "(det F = {:.3g}); a smaller load increment may help",
                          id(), k.det));
  const Eigen::Matrix2Xd gh = fh_inv.transpose() * g0;  // ∇_{x½} N
  k.h = f_cur.inverse().transpose() * g0;
  double rh = 0.0;
  if (axi) {
    const double dur = k.n.dot(du.row(0).transpose());
    const double unr = k.n.dot(un.row(0).transpose());
    rh = pt.radius + unr + 0.5 * dur;
    k.r = pt.radius + unr + dur;
    k.r0 = pt.radius;
    k.lzz = dur / rh;
  }
  const Mat2 m = Mat2::Identity() - 0.5 * k.l;  // δL = (I − ½L) δH F_½⁻¹
  k.q << k.l(0, 0), k.l(1, 1), k.lzz, 0.5 * (k.l(0, 1) + k.l(1, 0)), 0.5 * (k.l(1, 0) - k.l(0, 1));
  k.dq.setZero(5, nd);
  for (int b = 0; b < nn; ++b)
    for (int i = 0; i < 2; ++i) {
      const Mat2 dl = m.col(i) * gh.col(b).transpose();
      const int j = 2 * b + i;
      k.dq(0, j) = dl(0, 0);
      k.dq(1, j) = dl(1, 1);
      if (axi && i == 0) k.dq(2, j) = k.n(b) / rh * (1.0 - 0.5 * k.lzz);
      k.dq(3, j) = 0.5 * (dl(0, 1) + dl(1, 0));
      k.dq(4, j) = 0.5 * (dl(1, 0) - dl(0, 1));
    }
}

void PlaneSolid::finite_response(std::size_t p, const FiniteKinematics& k,
                                 FiniteResponse& r) const {
  const bool axi = options_.behaviour == PlaneBehaviour::Axisymmetric;
  const bool pstress = options_.behaviour == PlaneBehaviour::PlaneStress;
  const double nu_ratio = poisson_ / (1.0 - poisson_);
  Mat2 jrot;
  jrot << 0.0, -1.0, 1.0, 0.0;
  // Built as local values and stored at the end: Eigen evaluates a product assigned to an
  // existing matrix by another path than one it constructs, and with FMA the two can round
  // differently (the results stay bitwise those of the undivided finite_sum).
  const double c = 0.5 * k.q(4);
  const Mat2 rot = incremental_rotation(c);
  const Mat2 drot = (1.0 / (1.0 + c * c)) * jrot * rot;  // ∂ΔR/∂ω
  Mat2 d2;
  d2 << k.q(0), k.q(3), k.q(3), k.q(1);
  // The increment rotated back to the axes of the committed state: ΔRᵀ Δε ΔR.
  const Vec4 strain = finite_[p].strain + voigt(rot.transpose() * d2 * rot, k.q(2), 2.0);
  Vec4 s_hat;
  Eigen::Matrix4d c_alg;
  PlasticState next;
  double ezz = strain(2);
  if (plasticity_) {
    point_response(committed_[p], strain, s_hat, c_alg, &next);
    if (pstress) ezz = next.thickness_strain;
  } else {
    s_hat = d_ * strain;
    c_alg = d_;
    if (pstress) ezz = -nu_ratio * (strain(0) + strain(1));
  }
  const Mat2 sh2 = in_plane(s_hat, 1.0);
  const Mat2 s2 = rot * sh2 * rot.transpose();
  const Vec4 sigma = voigt(s2, s_hat(2), 1.0);
  // Current measure dv = J dV₀.
  double jac = k.det;
  if (axi) jac *= k.r / k.r0;  // F_θθ = r / R
  if (pstress) jac *= std::exp(ezz);
  const double dv = jac * k.dv0;
  r.rot = rot;
  r.drot = drot;
  r.d2 = d2;
  r.strain = strain;
  r.s_hat = s_hat;
  r.c_alg = c_alg;
  r.next = next;
  r.ezz = ezz;
  r.sh2 = sh2;
  r.s2 = s2;
  r.sigma = sigma;
  r.dv = dv;
}

void PlaneSolid::add_finite_tangent(const FiniteKinematics& k, const FiniteResponse& r,
                                    const Eigen::VectorXd& a, const Eigen::VectorXd& lzz,
                                    Eigen::MatrixXd& K) const {
  const int nn = static_cast<int>(nodes_.size());
  const int nd = 2 * nn;
  const bool pstress = options_.behaviour == PlaneBehaviour::PlaneStress;
  const double nu_ratio = poisson_ / (1.0 - poisson_);
  const Eigen::Matrix<double, 4, 5> ds =
      plane_stress_derivative(r.rot, r.drot, r.d2, r.sh2, r.c_alg);
  const Eigen::MatrixXd dsigma = ds * k.dq;  // 4 x nd
  // tr δl_k (+ the change of the thickness in plane stress).
  Eigen::VectorXd tr(nd);
  for (int b = 0; b < nn; ++b)
    for (int i = 0; i < 2; ++i) tr(2 * b + i) = k.h(i, b) + lzz(2 * b + i);
  if (pstress) tr.noalias() -= nu_ratio * (k.dq.row(0) + k.dq.row(1)).transpose();
  const double dv = r.dv;
  for (int bk = 0; bk < nn; ++bk)
    for (int ik = 0; ik < 2; ++ik) {
      const int col = 2 * bk + ik;
      const Mat2 dsk = in_plane(dsigma.col(col), 1.0);
      const Eigen::Vector2d sh_k = r.s2 * k.h.col(bk);
      for (int bj = 0; bj < nn; ++bj) {
        const Eigen::Vector2d dsh = dsk * k.h.col(bj);
        for (int ij = 0; ij < 2; ++ij) {
          const int row = 2 * bj + ij;
          // δσ_k : δl_j, δl_j = e_ij ⊗ ∇N_bj (+ the hoop entry N / r).
          double v = dsh(ij) + dsigma(2, col) * lzz(row);
          // − σ : (δl_j δl_k): (δl_j δl_k) = e_ij (∇N_bj · e_ik) ⊗ ∇N_bk.
          v -= k.h(ik, bj) * sh_k(ij) + r.sigma(2) * lzz(row) * lzz(col);
          v += a(row) * tr(col);
          K(row, col) += dv * v;
        }
      }
    }
}

void PlaneSolid::finite_sum(const Eigen::VectorXd& u, Eigen::MatrixXd* K, Eigen::VectorXd& f,
                            FiniteUpdate* update) const {
  const int nn = static_cast<int>(nodes_.size());
  const int nd = 2 * nn;
  const bool axi = options_.behaviour == PlaneBehaviour::Axisymmetric;
  const bool bbar = options_.technology == PlaneTechnology::BBar;
  const Eigen::Map<const Eigen::Matrix2Xd> un(committed_u_.data(), 2, nn);
  const Eigen::Map<const Eigen::Matrix2Xd> uc(u.data(), 2, nn);
  const Eigen::Matrix2Xd du = uc - un;
  const std::size_t np = rule_.size();

  // Pass 1: kinematics of every point (the mean dilatation of B-bar couples the points).
  std::vector<FiniteKinematics> kin(np);
  double v0 = 0.0;
  for (std::size_t p = 0; p < np; ++p) {
    finite_kinematics(p, un, du, kin[p]);
    v0 += kin[p].dv0;
  }
  if (bbar) plane_mean_dilatation(kin, v0, nd);

  // Pass 2: the law at every point, internal force and tangent.
  f.setZero(nd);
  if (K) K->setZero(nd, nd);
  if (update) {
    update->finite.resize(np);
    update->plastic = committed_;
    update->stress.resize(np);
  }
  for (std::size_t p = 0; p < np; ++p) {
    const FiniteKinematics& k = kin[p];
    FiniteResponse r;
    finite_response(p, k, r);
    // σ : δl_j per DOF (the integrand of f) and the spatial gradient rows.
    Eigen::VectorXd a(nd), lzz = Eigen::VectorXd::Zero(nd);
    for (int b = 0; b < nn; ++b) {
      const Eigen::Vector2d sh = r.s2 * k.h.col(b);
      a(2 * b) = sh(0);
      a(2 * b + 1) = sh(1);
      if (axi) {
        lzz(2 * b) = k.n(b) / k.r;
        a(2 * b) += r.sigma(2) * lzz(2 * b);
      }
    }
    f.noalias() += r.dv * a;
    if (update) {
      FiniteState st;
      st.strain = rotate_strain(r.rot, r.strain);
      st.strain(2) = r.ezz;
      update->finite[p] = st;
      if (plasticity_) {
        PlasticState next = r.next;
        next.plastic_strain = rotate6(r.rot, next.plastic_strain, true);
        next.back_stress = rotate6(r.rot, next.back_stress, false);
        next.stress = rotate6(r.rot, next.stress, false);
        update->plastic[p] = next;
      }
      update->stress[p] = r.sigma;
    }
    if (K) add_finite_tangent(k, r, a, lzz, *K);
  }
}

void PlaneSolid::finite_tangent(const Eigen::VectorXd& u, Eigen::MatrixXd& K,
                                Eigen::VectorXd& f_int, bool symmetric) const {
  IMPACTFE_CHECK(options_.large_deflection, "finite_tangent of an element built small-strain");
  finite_sum(u, &K, f_int, nullptr);
  if (symmetric) K = 0.5 * (K + K.transpose()).eval();
}

Eigen::Vector4d PlaneSolid::finite_point_stress(const Eigen::VectorXd& u, int p) const {
  FiniteUpdate at;
  Eigen::VectorXd f;
  finite_sum(u, nullptr, f, &at);
  return at.stress.at(static_cast<std::size_t>(p));
}

void PlaneSolid::finite_commit(const Eigen::VectorXd& u) {
  FiniteUpdate at;
  Eigen::VectorXd f;
  finite_sum(u, nullptr, f, &at);
  finite_ = at.finite;
  if (plasticity_) committed_ = at.plastic;
  committed_u_ = u;
}

void PlaneSolid::finite_results(const Eigen::VectorXd& u, ElementResultValues& out) const {
  FiniteUpdate at;
  Eigen::VectorXd f;
  finite_sum(u, nullptr, f, &at);
  // Volume averages over the points (reference weights), as the plastic small-strain element.
  double total = 0.0;
  std::vector<double> w;
  for (const QuadraturePoint& q : rule_) {
    w.push_back(measure(point_at(q.xi.head<2>()), q.weight));
    total += w.back();
  }
  Vec4 s = Vec4::Zero();
  Vector6d eppl = Vector6d::Zero();
  double epeq = 0.0, plwk = 0.0, srat = 0.0;
  for (std::size_t p = 0; p < rule_.size(); ++p) {
    const double wp = w[p] / total;
    s += wp * at.stress[p];
    if (!plasticity_) continue;
    const PlasticState& st = at.plastic[p];
    eppl += wp * st.plastic_strain;
    epeq += wp * st.alpha;
    plwk += wp * st.plastic_work;
    srat =
        std::max(srat, von_mises(st.stress - st.back_stress) / plasticity_->flow_stress(st.alpha));
  }
  out = plane_stress_items(s);
  if (plasticity_) {
    const double plastic[8] = {
        eppl(0), eppl(1), eppl(2), eppl(3), epeq, plasticity_->flow_stress(epeq), srat, plwk};
    std::copy(plastic, plastic + 8, out.begin() + 9);
  }
  const Vec4 epel = elastic_strain(s);
  std::copy(epel.data(), epel.data() + 4, out.begin() + 23);
}

void PlaneSolid::finite_point_stresses(const Eigen::VectorXd& u,
                                       std::vector<Eigen::Vector4d>& sigma, bool& inelastic) const {
  FiniteUpdate at;
  Eigen::VectorXd f;
  finite_sum(u, nullptr, f, &at);
  sigma.assign(at.stress.begin(), at.stress.end());
  inelastic = false;
  if (plasticity_)
    for (const PlasticState& st : at.plastic) inelastic = inelastic || st.alpha > 0.0;
}

}  // namespace impactfe
