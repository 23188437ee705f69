#include "elements/beam.h"

#include <fmt/format.h>

#include <Eigen/Geometry>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "elements/beam_setup.h"
#include "elements/so3.h"

namespace impactfe {

namespace {

using Mat3 = Eigen::Matrix3d;

/// Hermite (cubic) consistent mass of one bending plane on (w1, φ1, w2, φ2) with φ = w'
/// (translational ρA and rotary ρI parts; Przemieniecki §11.3, eqs. 11.34 and 11.40).
Eigen::Matrix4d hermite_mass(double rho_a, double rho_i, double L) {
  Eigen::Matrix4d t, r;
  t << 156, 22 * L, 54, -13 * L, 22 * L, 4 * L * L, 13 * L, -3 * L * L, 54, 13 * L, 156, -22 * L,
      -13 * L, -3 * L * L, -22 * L, 4 * L * L;
  r << 36, 3 * L, -36, 3 * L, 3 * L, 4 * L * L, -3 * L, -L * L, -36, -3 * L, 36, -3 * L, 3 * L,
      -L * L, -3 * L, 4 * L * L;
  return rho_a * L / 420.0 * t + rho_i / (30.0 * L) * r;
}

}  // namespace

Beam::Beam(int id, BeamData data) : Element(id), data_(std::move(data)) {
  length_ = (data_.xj - data_.xi).norm();
  for (int k : data_.active)
    dofs_.push_back(DofKey{k < 6 ? data_.node_i : data_.node_j, static_cast<Dof>(k % 6)});
  const BeamSectionProperties& p = data_.section;
  const double E = data_.youngs_modulus, G = data_.shear_modulus, L = length_;
  torsion_stiffness_ = G * p.torsion;
  // Residual bending flexibility (MacNeal): 1/S = 1/(G kA) + L²/(12 EI); kA = 0 → rigid shear.
  auto shear = [&](double shear_area, double ei) {
    const double bending = L * L / (12.0 * ei);
    return 1.0 / (bending + (shear_area > 0.0 ? 1.0 / (G * shear_area) : 0.0));
  };
  // Virgin fibres: the response at zero strain is elastic.
  if (data_.plasticity) committed_.assign(p.fibres.size(), UniaxialPlasticState{});
  Eigen::Vector3d s;
  Eigen::Matrix3d& D = D_elastic_;
  section_response(Eigen::Vector3d::Zero(), s, D);
  shear_y_ = shear(p.shear_area_y, D(2, 2));  // bending in the x-y plane: E Izz
  shear_z_ = shear(p.shear_area_z, D(1, 1));  // x-z plane: E Iyy
  (void)E;
  Vec12 f;
  local_response(Vec12::Zero(), false, f, &K_linear_);
}

void Beam::section_response(const Eigen::Vector3d& e, Eigen::Vector3d& s, Eigen::Matrix3d& D,
                            std::vector<UniaxialPlasticState>* updated) const {
  if (!data_.plasticity) {
    const double E = data_.youngs_modulus;
    integrate_fibres(
        data_.section.fibres, e,
        [E](int, double strain, double& stress, double& tangent) {
          stress = E * strain;
          tangent = E;
        },
        s, D);
    return;
  }
  // Plastic fibres: the 1-D return of each fibre from its committed state (pure function of the
  // committed state and the strain), its consistent tangent into D.
  const J2Plasticity& law = *data_.plasticity;
  if (updated) updated->resize(committed_.size());
  integrate_fibres(
      data_.section.fibres, e,
      [&](int k, double strain, double& stress, double& tangent) {
        const auto f = static_cast<std::size_t>(k);
        const UniaxialResponse r =
            law.uniaxial(committed_[f], strain, updated ? &(*updated)[f] : nullptr);
        stress = r.stress;
        tangent = r.tangent;
      },
      s, D);
}

void Beam::local_response(const Vec12& d, bool stiffening, Vec12& f, Mat12* K,
                          std::vector<UniaxialPlasticState>* updated) const {
  const double L = length_;
  // Generalised strains at mid-length: rows ε0, κy, κz, twist, γy, γz.
  Eigen::Matrix<double, 6, 12> B = Eigen::Matrix<double, 6, 12>::Zero();
  B(0, 0) = -1 / L, B(0, 6) = 1 / L;
  B(1, 4) = -1 / L, B(1, 10) = 1 / L;
  B(2, 5) = -1 / L, B(2, 11) = 1 / L;
  B(3, 3) = -1 / L, B(3, 9) = 1 / L;
  B(4, 1) = -1 / L, B(4, 7) = 1 / L, B(4, 5) = -0.5, B(4, 11) = -0.5;
  B(5, 2) = -1 / L, B(5, 8) = 1 / L, B(5, 4) = 0.5, B(5, 10) = 0.5;
  Eigen::Matrix<double, 6, 1> e = B * d;
  const double dv = d(7) - d(1), dw = d(8) - d(2);
  if (stiffening) {
    e(0) += (dv * dv + dw * dw) / (2 * L * L);
    B(0, 1) = -dv / (L * L), B(0, 7) = dv / (L * L);
    B(0, 2) = -dw / (L * L), B(0, 8) = dw / (L * L);
  }
  Eigen::Vector3d s_ab;
  Eigen::Matrix3d D_ab;
  section_response(e.head<3>(), s_ab, D_ab, updated);
  const double N0 = data_.youngs_modulus * data_.section.area * data_.initial_strain;
  Eigen::Matrix<double, 6, 1> s;
  s << s_ab(0) + N0, s_ab(1), s_ab(2), torsion_stiffness_ * e(3), shear_y_ * e(4), shear_z_ * e(5);
  f = L * B.transpose() * s;
  if (K == nullptr) return;
  Eigen::Matrix<double, 6, 6> D = Eigen::Matrix<double, 6, 6>::Zero();
  D.topLeftCorner<3, 3>() = D_ab;
  D(3, 3) = torsion_stiffness_;
  D(4, 4) = shear_y_;
  D(5, 5) = shear_z_;
  *K = L * B.transpose() * D * B;
  if (stiffening) {
    const double g = s(0) / L;  // L · N · ∂²ε0/∂d² = (N/L) blk(1)
    for (int c : {1, 2}) {
      (*K)(c, c) += g, (*K)(c + 6, c + 6) += g;
      (*K)(c, c + 6) -= g, (*K)(c + 6, c) -= g;
    }
  }
}

Beam::Mat12 Beam::rotation() const {
  Mat12 T = Mat12::Zero();
  for (int b = 0; b < 4; ++b) T.block<3, 3>(3 * b, 3 * b) = data_.frame.transpose();
  return T;
}

Beam::Vec12 Beam::expand(const Eigen::VectorXd& u) const {
  Vec12 U = Vec12::Zero();
  for (std::size_t k = 0; k < data_.active.size(); ++k)
    U(data_.active[k]) = u(static_cast<Eigen::Index>(k));
  return U;
}

void Beam::restrict(const Vec12& f, const Mat12& K, Eigen::VectorXd& f_out,
                    Eigen::MatrixXd& K_out) const {
  const auto n = static_cast<Eigen::Index>(data_.active.size());
  f_out.resize(n);
  K_out.resize(n, n);
  for (Eigen::Index a = 0; a < n; ++a) {
    f_out(a) = f(data_.active[static_cast<std::size_t>(a)]);
    for (Eigen::Index b = 0; b < n; ++b)
      K_out(a, b) =
          K(data_.active[static_cast<std::size_t>(a)], data_.active[static_cast<std::size_t>(b)]);
  }
}

Beam::Corotated Beam::corotate(const Vec12& u, Mat12* B) const {
  const Mat3& R0 = data_.frame;
  const Vec3 chord = data_.xj + u.segment<3>(6) - data_.xi - u.segment<3>(0);
  const double ln = chord.norm();
  if (!(ln > 1e-12 * length_))
    throw ElementSolutionError(
        id(), fmt::format("element {} (beam) collapsed to zero length under large deflection; "
                          "use a smaller time step or more substeps, or check the loads",
                          id()));
  const Vec3 psi1 = u.segment<3>(3), psi2 = u.segment<3>(9);
  const Mat3 R1 = so3::exp_map(psi1), R2 = so3::exp_map(psi2);
  const Vec3 r1 = chord / ln;
  const Vec3 q1 = R1 * R0.col(1), q2 = R2 * R0.col(1), q = 0.5 * (q1 + q2);
  Vec3 r3 = r1.cross(q);
  if (!(r3.norm() > 1e-8))
    throw ElementSolutionError(
        id(), fmt::format("element {} (beam): the nodal triads twisted by 90 degrees or more "
                          "relative to the chord within one increment; use smaller increments",
                          id()));
  r3.normalize();
  Corotated c;
  c.Rr.col(0) = r1;
  c.Rr.col(1) = r3.cross(r1);
  c.Rr.col(2) = r3;
  const Vec3 th1 = so3::log_map(c.Rr.transpose() * R1 * R0);
  const Vec3 th2 = so3::log_map(c.Rr.transpose() * R2 * R0);
  c.d.setZero();
  c.d(6) = ln - length_;
  c.d.segment<3>(3) = th1;
  c.d.segment<3>(9) = th2;
  if (B == nullptr) return c;

  // Spin of the frame, δω (local components) = Gl Eᵀ δp, δp = [δx1, δw1, δx2, δw2] (spatial
  // spins δw = T(ψ) δψ); Gl from r3·q = 0 and the chord (Battini & Pacoste 2002, eq. 33).
  const Mat3 Rt = c.Rr.transpose();
  const Vec3 ql = Rt * q, q1l = Rt * q1, q2l = Rt * q2;
  const double eta = ql(0) / ql(1);
  Eigen::Matrix<double, 3, 12> Gl = Eigen::Matrix<double, 3, 12>::Zero();
  Gl(0, 2) = eta / ln, Gl(0, 3) = 0.5 * q1l(1) / ql(1), Gl(0, 4) = -0.5 * q1l(0) / ql(1);
  Gl(0, 8) = -eta / ln, Gl(0, 9) = 0.5 * q2l(1) / ql(1), Gl(0, 10) = -0.5 * q2l(0) / ql(1);
  Gl(1, 2) = 1 / ln, Gl(1, 8) = -1 / ln;
  Gl(2, 1) = -1 / ln, Gl(2, 7) = 1 / ln;
  Eigen::Matrix<double, 3, 12> W;
  for (int b = 0; b < 4; ++b) W.middleCols<3>(3 * b) = Gl.middleCols<3>(3 * b) * Rt;
  // δū = r1·(δx2 − δx1); δθ̄_a = T(θ̄_a)⁻¹ (Rrᵀ δw_a − δω).
  Mat12 Bp = Mat12::Zero();
  Bp.block<1, 3>(6, 0) = -r1.transpose();
  Bp.block<1, 3>(6, 6) = r1.transpose();
  for (int a = 0; a < 2; ++a) {
    Eigen::Matrix<double, 3, 12> A = -W;
    A.middleCols<3>(6 * a + 3) += Rt;
    Bp.middleRows<3>(6 * a + 3) = so3::left_jacobian_inverse(a == 0 ? th1 : th2) * A;
  }
  c.Bp = Bp;
  c.W = W;
  c.q1l = q1l;
  c.q2l = q2l;
  c.ln = ln;
  *B = Bp;
  B->middleCols<3>(3) = Bp.middleCols<3>(3) * so3::left_jacobian(psi1);
  B->middleCols<3>(9) = Bp.middleCols<3>(9) * so3::left_jacobian(psi2);
  return c;
}

Beam::Mat12 Beam::corotational_geometric(const Vec12& u, const Corotated& c,
                                         const Vec12& fl) const {
  // f = Sᵀ Bpᵀ f_l with S = diag(I, T(ψ1), I, T(ψ2)); g = Bpᵀ f_l (δp space) is
  //   g = N (−r1, 0, r1, 0) + Σ_a E_aᵀ h_a − Wᵀ H,  h_a = T(θ̄_a)⁻ᵀ m_a,  H = h_1 + h_2,
  // E_a = Rrᵀ on the spin of node a. Its derivative at fixed f_l (Battini & Pacoste 2002,
  // §3.3, with the frame of eq. 33): δRr = Rr spin(W δp), δr1 = (I − r1 r1ᵀ)(δx2 − δx1)/ln,
  // δq_al = spin(q_al)(W − E_a) δp, and δh_a = ∂(T⁻ᵀm)/∂θ̄ · Bp_a δp (so3 derivatives).
  using so3::spin;
  const Mat3& Rr = c.Rr;
  const Mat3 Rt = Rr.transpose();
  const Vec3 r1 = Rr.col(0);
  const double ln = c.ln, N = fl(6);
  const Eigen::Matrix<double, 3, 12>& W = c.W;
  auto E = [&](int a) {
    Eigen::Matrix<double, 3, 12> e = Eigen::Matrix<double, 3, 12>::Zero();
    e.middleCols<3>(6 * a + 3) = Rt;
    return e;
  };
  Mat12 K = Mat12::Zero();
  // Axial: N δ(−r1, r1).
  const Mat3 A = (Mat3::Identity() - r1 * r1.transpose()) * (N / ln);
  K.block<3, 3>(0, 0) += A, K.block<3, 3>(0, 6) -= A;
  K.block<3, 3>(6, 0) -= A, K.block<3, 3>(6, 6) += A;
  // Moments: h_a, their variations Dh_a = ∂h_a/∂p.
  Vec3 h[2], H = Vec3::Zero();
  Eigen::Matrix<double, 3, 12> Dh[2], DH = Eigen::Matrix<double, 3, 12>::Zero();
  for (int a = 0; a < 2; ++a) {
    const Vec3 th = c.d.segment<3>(6 * a + 3), m = fl.segment<3>(6 * a + 3);
    h[a] = so3::left_jacobian_inverse(th).transpose() * m;
    Dh[a] = so3::d_left_jacobian_inverse_transpose(th, m) * c.Bp.middleRows<3>(6 * a + 3);
    H += h[a];
    DH += Dh[a];
    // δ(Rr h_a) on the spin rows of node a.
    K.middleRows<3>(6 * a + 3) += -Rr * spin(h[a]) * W + Rr * Dh[a];
  }
  // −δ(Wᵀ H): block b of Wᵀ H is Rr γ_b with γ = Glᵀ H (local), Gl of corotate().
  const Vec3 ql = 0.5 * (c.q1l + c.q2l);
  const double eta = ql(0) / ql(1);
  using Row = Eigen::Matrix<double, 1, 12>;
  Row d_ln = Row::Zero();
  d_ln.segment<3>(0) = -r1.transpose(), d_ln.segment<3>(6) = r1.transpose();
  const Row d_inv = -d_ln / (ln * ln);
  const Eigen::Matrix<double, 3, 12> dq1 = spin(c.q1l) * (W - E(0)), dq2 = spin(c.q2l) * (W - E(1));
  const Eigen::Matrix<double, 3, 12> dq = 0.5 * (dq1 + dq2);
  const Row d_eta = (dq.row(0) - eta * dq.row(1)) / ql(1);
  Vec12 gamma = Vec12::Zero();
  Eigen::Matrix<double, 12, 12> dgamma = Eigen::Matrix<double, 12, 12>::Zero();
  gamma(1) = -H(2) / ln, dgamma.row(1) = -H(2) * d_inv;
  gamma(2) = (eta * H(0) + H(1)) / ln;
  dgamma.row(2) = H(0) * (d_eta / ln + eta * d_inv) + H(1) * d_inv;
  gamma(7) = -gamma(1), dgamma.row(7) = -dgamma.row(1);
  gamma(8) = -gamma(2), dgamma.row(8) = -dgamma.row(2);
  const Vec3* qa[2] = {&c.q1l, &c.q2l};
  const Eigen::Matrix<double, 3, 12>* dqa[2] = {&dq1, &dq2};
  for (int a = 0; a < 2; ++a) {
    const Vec3& q = *qa[a];
    const Eigen::Matrix<double, 3, 12>& dqq = *dqa[a];
    const int j = 6 * a + 3;
    gamma(j) = 0.5 * q(1) / ql(1) * H(0);
    gamma(j + 1) = -0.5 * q(0) / ql(1) * H(0);
    dgamma.row(j) = 0.5 * H(0) * (dqq.row(1) / ql(1) - q(1) * dq.row(1) / (ql(1) * ql(1)));
    dgamma.row(j + 1) = -0.5 * H(0) * (dqq.row(0) / ql(1) - q(0) * dq.row(1) / (ql(1) * ql(1)));
  }
  // The H-variation part of δ(Wᵀ H) is Wᵀ δH = Wᵀ DH; γ's part through Gl (at fixed H).
  const Eigen::Matrix<double, 3, 12> Gl = [&] {
    Eigen::Matrix<double, 3, 12> g;
    for (int b = 0; b < 4; ++b) g.middleCols<3>(3 * b) = W.middleCols<3>(3 * b) * Rr;
    return g;
  }();
  for (int b = 0; b < 4; ++b) {
    const Vec3 gb = gamma.segment<3>(3 * b);
    K.middleRows<3>(3 * b) -= -Rr * spin(gb) * W + Rr * dgamma.middleRows<3>(3 * b) +
                              Rr * Gl.middleCols<3>(3 * b).transpose() * DH;
  }
  // S-factors: f_ψa = T(ψ_a)ᵀ g_wa, so K_u = Sᵀ K S + diag(∂(Tᵀ g_wa)/∂ψ_a).
  const Vec12 g = c.Bp.transpose() * fl;
  Mat12 S = Mat12::Identity();
  for (int a = 0; a < 2; ++a)
    S.block<3, 3>(6 * a + 3, 6 * a + 3) = so3::left_jacobian(u.segment<3>(6 * a + 3));
  Mat12 Ku = S.transpose() * K * S;
  for (int a = 0; a < 2; ++a)
    Ku.block<3, 3>(6 * a + 3, 6 * a + 3) +=
        so3::d_left_jacobian_transpose(u.segment<3>(6 * a + 3), g.segment<3>(6 * a + 3));
  return Ku;
}

bool Beam::is_nonlinear(const ElementContext& ctx) const {
  return ctx.large_deflection || ctx.stress_stiffening || data_.plasticity.has_value();
}

void Beam::tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
                   Eigen::VectorXd& f_int) const {
  const Vec12 U = expand(u);
  Vec12 f;
  Mat12 Kg;
  if (!ctx.large_deflection) {
    const Mat12 T = rotation();
    Mat12 Kl;
    local_response(T * U, ctx.stress_stiffening, f, &Kl);
    f = T.transpose() * f;
    Kg = T.transpose() * Kl * T;
  } else {
    Mat12 B;
    const Corotated c = corotate(U, &B);
    Vec12 fl;
    Mat12 Kl;
    local_response(c.d, false, fl, data_.plasticity ? &Kl : nullptr);
    if (!data_.plasticity) Kl = K_linear_;  // elastic: the local stiffness is constant
    f = B.transpose() * fl;
    const Mat12 KG = corotational_geometric(U, c, fl);
    Kg = B.transpose() * Kl * B + KG;
    // The assembler stores one triangle: use the symmetric part (the co-rotational tangent with
    // additive rotation vectors is symmetric only at equilibrium).
    Kg = (0.5 * (Kg + Kg.transpose())).eval();
  }
  restrict(f, Kg, f_int, K);
}

void Beam::mass(const ElementContext& ctx, Eigen::MatrixXd& M) const {
  const BeamSectionProperties& p = data_.section;
  const double rho = data_.density, L = length_;
  const double rho_a = rho * p.area + data_.added_mass;
  Mat12 Ml = Mat12::Zero();
  if (ctx.lumped_mass || data_.lumped_mass) {
    for (int n = 0; n < 2; ++n) {
      for (int c = 0; c < 3; ++c) Ml(6 * n + c, 6 * n + c) = 0.5 * rho_a * L;
      Ml(6 * n + 3, 6 * n + 3) = 0.5 * rho * (p.iyy + p.izz) * L;
      Ml(6 * n + 4, 6 * n + 4) = 0.5 * rho * p.iyy * L;
      Ml(6 * n + 5, 6 * n + 5) = 0.5 * rho * p.izz * L;
    }
  } else {
    auto linear = [&](int a, double m) {
      Ml(a, a) += m / 3, Ml(a + 6, a + 6) += m / 3;
      Ml(a, a + 6) += m / 6, Ml(a + 6, a) += m / 6;
    };
    linear(0, rho_a * L);
    linear(3, rho * (p.iyy + p.izz) * L);
    // x-y plane (v, θz = v'), x-z plane (w, θy = −w').
    const std::array<int, 4> xy{1, 5, 7, 11}, xz{2, 4, 8, 10};
    // Rotary inertia: ρI ∫ φ² dx of the section rotation φ. Without shear flexibility φ = w'
    // and the Hermite rotary part (Przemieniecki eq. 11.40) is that integral. With it (BEAM188,
    // Timoshenko), φ = w' − γ: the Hermite part would put ρI on the slope w', shear included,
    // which in a deep beam adds rotary inertia that is not there and converges to the wrong
    // frequencies (vmp09-t5-188, 3rd bending pair 9 % low with 40 and 80 elements); there φ is
    // interpolated linearly between the nodal rotations instead, ρI L/6 [2 1; 1 2].
    auto plane_mass = [&](double rho_i, double shear_area) {
      if (shear_area <= 0.0) return hermite_mass(rho_a, rho_i, L);
      Eigen::Matrix4d m = hermite_mass(rho_a, 0.0, L);
      m(1, 1) += rho_i * L / 3, m(3, 3) += rho_i * L / 3;
      m(1, 3) += rho_i * L / 6, m(3, 1) += rho_i * L / 6;
      return m;
    };
    const Eigen::Matrix4d mxy = plane_mass(rho * p.izz, p.shear_area_y);
    Eigen::Matrix4d mxz = plane_mass(rho * p.iyy, p.shear_area_z);
    const Eigen::Vector4d sgn(1, -1, 1, -1);
    mxz = sgn.asDiagonal() * mxz * sgn.asDiagonal();
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) {
        Ml(xy[a], xy[b]) += mxy(a, b);
        Ml(xz[a], xz[b]) += mxz(a, b);
      }
  }
  const Mat12 T = rotation();
  const Mat12 Mg = T.transpose() * Ml * T;
  Eigen::VectorXd unused;
  restrict(Vec12::Zero(), Mg, unused, M);
}

Beam::Vec12 Beam::local_displacement(const ElementContext& ctx, const Vec12& U) const {
  return ctx.large_deflection ? corotate(U, nullptr).d : Vec12(rotation() * U);
}

Beam::Vec12 Beam::local_forces(const ElementContext& ctx, const Eigen::VectorXd& u,
                               std::vector<UniaxialPlasticState>* states) const {
  Vec12 fl;
  local_response(local_displacement(ctx, expand(u)), ctx.stress_stiffening && !ctx.large_deflection,
                 fl, nullptr, states);
  return fl;
}

void Beam::commit_history(const ElementContext& ctx, const Eigen::VectorXd& u) {
  if (!data_.plasticity) return;
  std::vector<UniaxialPlasticState> next;
  local_forces(ctx, u, &next);
  committed_ = std::move(next);
}

std::vector<double> Beam::history_state() const {
  std::vector<double> out;
  for (const UniaxialPlasticState& s : committed_) append_state(out, s);  // per fibre
  return out;
}

void Beam::restore_history_state(const std::vector<double>& state) {
  std::size_t pos = 0;
  for (UniaxialPlasticState& s : committed_) read_state(state, pos, s);
  IMPACTFE_CHECK(pos == state.size(), "BEAM: saved state of the wrong length");
}

double Beam::plastic_work() const {
  // ∫σ dε_p dV = Σ_f w_f a_f L (one section point for the whole length).
  double w = 0.0;
  for (std::size_t k = 0; k < committed_.size(); ++k)
    w += committed_[k].plastic_work * data_.section.fibres[k].area;
  return w * length_;
}

const std::vector<std::string>& beam_result_names() {
  static const std::vector<std::string> names = {
      "FX_I",   "MY_I",   "MZ_I",   "TQ_I",   "SFZ_I",  "SFY_I",  "FX_J",   "MY_J",
      "MZ_J",   "TQ_J",   "SFZ_J",  "SFY_J",  "SDIR_I", "SBYT_I", "SBYB_I", "SBZT_I",
      "SBZB_I", "SDIR_J", "SBYT_J", "SBYB_J", "SBZT_J", "SBZB_J", "SMAX_I", "SMIN_I",
      "SMAX_J", "SMIN_J", "EPEQ",   "SRAT",   "PLWK"};
  return names;
}

const std::vector<std::string>& Beam::result_names() const {
  return beam_result_names();
}

Eigen::Vector3d Beam::thermal_resultants() const {
  const std::vector<double>& dT = temperature_change();
  if (dT.size() < 2) return Eigen::Vector3d::Zero();
  const double eps = thermal_expansion().alpha.x() * 0.5 * (dT[0] + dT[1]);
  return D_elastic_.col(0) * eps;  // D (ε_th, 0, 0): N, and My, Mz of an offset section
}

void Beam::pressure_load(const ElementContext& ctx, int face, const std::array<double, 4>& p,
                         const Eigen::VectorXd& u, Eigen::VectorXd& f) const {
  // The faces of MAPDL's beams (SFBEAM, SFE): BEAM188 and BEAM4 1 −z, 2 −y (normal, I-J),
  // 3 +x (tangential), 4 +x at I, 5 −x at J (axial); BEAM3 1 −y, 2 +x, 3 I, 4 J. Force per
  // length, p[0] at I and p[1] at J, linear between.
  const bool planar = data_.active.size() == 6;
  const int kind = planar ? (face == 1 ? 2 : face + 1) : face;  // as BEAM188's numbering
  if (kind < 1 || kind > 5 || (planar && face > 4))
    throw ModelError(fmt::format("element {} (beam) has no face {}", id(), face));
  // The element's axes: under large deflection the co-rotated frame and chord (a follower
  // load, MAPDL's beam pressures act in the element axes), else the initial ones.
  Mat3 axes = data_.frame;
  double L = length_;
  if (ctx.large_deflection) {
    const Vec12 U = expand(u);
    axes = corotate(U, nullptr).Rr;
    L = (data_.xj + U.segment<3>(6) - data_.xi - U.segment<3>(0)).norm();
  }
  const double pi = p[0], pj = p[1];
  Vec12 fl = Vec12::Zero();  // local: node I (u v w θx θy θz), then node J
  if (kind == 1 || kind == 2) {
    // Hermite (cubic) work-equivalent loads of q(s) = pi + (pj − pi) s/L (Przemieniecki §5.5):
    // the fixed-end forces L(7pi + 3pj)/20, L(3pi + 7pj)/20 and moments L²(3pi + 2pj)/60,
    // −L²(2pi + 3pj)/60; with the element's exact stiffness they give exact nodal
    // displacements. A load along −y turns about z (θz = v'), one along −z about y (θy = −w').
    const double fi = L * (7.0 * pi + 3.0 * pj) / 20.0, fj = L * (3.0 * pi + 7.0 * pj) / 20.0;
    const double mi = L * L * (3.0 * pi + 2.0 * pj) / 60.0;
    const double mj = -L * L * (2.0 * pi + 3.0 * pj) / 60.0;
    if (kind == 2) {  // along −y
      fl(1) = -fi, fl(7) = -fj, fl(5) = -mi, fl(11) = -mj;
    } else {  // along −z
      fl(2) = -fi, fl(8) = -fj, fl(4) = mi, fl(10) = mj;
    }
  } else if (kind == 3) {
    fl(0) = L * (2.0 * pi + pj) / 6.0;  // linear interpolation of the axial displacement
    fl(6) = L * (pi + 2.0 * pj) / 6.0;
  } else if (kind == 4) {
    fl(0) = pi;  // +x at I
  } else {
    fl(6) = -p[0];  // −x at J (the face's one node)
  }
  Vec12 fg;
  for (int b = 0; b < 4; ++b) fg.segment<3>(3 * b) = axes * fl.segment<3>(3 * b);
  f.resize(static_cast<Eigen::Index>(data_.active.size()));
  for (std::size_t k = 0; k < data_.active.size(); ++k)
    f(static_cast<Eigen::Index>(k)) = fg(data_.active[k]);
}

void Beam::thermal_load(const ElementContext&, Eigen::VectorXd& f) const {
  const Eigen::Vector3d r = thermal_resultants();
  // Local end loads in the DOF order u v w θx θy θz: −r at I, +r at J (as f_int = Bᵀ r).
  Vec12 fl = Vec12::Zero();
  for (int end = 0; end < 2; ++end) {
    const double sg = end == 0 ? -1.0 : 1.0;
    fl(6 * end + 0) = sg * r(0);
    fl(6 * end + 4) = sg * r(1);
    fl(6 * end + 5) = sg * r(2);
  }
  const Vec12 fg = rotation().transpose() * fl;
  f.resize(static_cast<Eigen::Index>(data_.active.size()));
  for (std::size_t k = 0; k < data_.active.size(); ++k)
    f(static_cast<Eigen::Index>(k)) = fg(data_.active[k]);
}

void Beam::results(const ElementContext& ctx, const Eigen::VectorXd& u, const Eigen::VectorXd&,
                   ElementResultValues& out) const {
  std::vector<UniaxialPlasticState> states;  // at u (the committed ones after a converged step)
  const Vec12 fl = local_forces(ctx, u, data_.plasticity ? &states : nullptr);
  const BeamSectionProperties& p = data_.section;
  const double E = data_.youngs_modulus;
  const Eigen::Matrix3d& D = D_elastic_;
  out.assign(beam_result_names().size(), 0.0);
  const Eigen::Vector3d r_th = thermal_resultants();
  for (int end = 0; end < 2; ++end) {
    // Section forces: −f at I, +f at J (N tension positive; My, Mz, T about the element axes).
    const double sg = end == 0 ? -1.0 : 1.0;
    const Eigen::Matrix<double, 6, 1> r = sg * fl.segment<6>(6 * end);
    // The thermal strain's resultants are taken off: f_int − f_th = Bᵀ (r − r_th).
    const double N = r(0) - r_th(0), Vy = r(1), Vz = r(2), Tq = r(3), My = r(4) - r_th(1),
                 Mz = r(5) - r_th(2);
    const std::size_t o = 6 * static_cast<std::size_t>(end);
    out[o + 0] = N, out[o + 1] = My, out[o + 2] = Mz, out[o + 3] = Tq, out[o + 4] = Vz,
            out[o + 5] = Vy;
    // The elastic (nominal) extreme-fibre stresses of the end resultants, also for a plastic
    // beam, whose fibre stresses stay on the yield surface (EPEQ and SRAT below say where it
    // yields).
    const BeamFibreStresses st = beam_fibre_stresses(p, E, D, N, My, Mz);
    const std::size_t so = 12 + 5 * static_cast<std::size_t>(end);
    out[so + 0] = st.sdir, out[so + 1] = st.sbyt, out[so + 2] = st.sbyb, out[so + 3] = st.sbzt,
             out[so + 4] = st.sbzb;
    out[22 + 2 * static_cast<std::size_t>(end)] = st.smax;
    out[23 + 2 * static_cast<std::size_t>(end)] = st.smin;
  }
  if (!data_.plasticity) return;
  double epeq = 0.0, srat = 0.0, work = 0.0;
  for (std::size_t k = 0; k < states.size(); ++k) {
    const UniaxialPlasticState& st = states[k];
    epeq = std::max(epeq, st.alpha);
    srat = std::max(srat,
                    std::abs(st.stress - st.back_stress) / data_.plasticity->flow_stress(st.alpha));
    work += st.plastic_work * p.fibres[k].area;
  }
  out[26] = epeq, out[27] = srat, out[28] = work / p.area;
}

}  // namespace impactfe
