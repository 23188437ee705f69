#include "elements/brick8.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "core/log.h"
#include "elements/element_registry.h"
#include "materials/inelastic_strain.h"

namespace impactfe {

namespace {

// Natural coordinates of the corners I..P (IJKL at ζ = -1, MNOP at ζ = +1).
constexpr double kCornerXi[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                    {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};

/// Trilinear shape functions and their natural derivatives (row i = d/dξ_i) at (ξ, η, ζ).
void shape(const double* xi, Eigen::Matrix<double, 8, 1>& n, Eigen::Matrix<double, 3, 8>& dn) {
  for (int a = 0; a < 8; ++a) {
    const double f0 = 1.0 + xi[0] * kCornerXi[a][0];
    const double f1 = 1.0 + xi[1] * kCornerXi[a][1];
    const double f2 = 1.0 + xi[2] * kCornerXi[a][2];
    n(a) = 0.125 * f0 * f1 * f2;
    dn(0, a) = 0.125 * kCornerXi[a][0] * f1 * f2;
    dn(1, a) = 0.125 * f0 * kCornerXi[a][1] * f2;
    dn(2, a) = 0.125 * f0 * f1 * kCornerXi[a][2];
  }
}

/// The trilinear functions at the 2x2x2 Gauss points ξ_p = ξ_corner p / √3: the same for every
/// brick, so not kept per element.
const std::array<Eigen::Matrix<double, 8, 1>, 8>& gauss_shape() {
  static const auto table = [] {
    std::array<Eigen::Matrix<double, 8, 1>, 8> n;
    Eigen::Matrix<double, 3, 8> dn;
    const double g = 1.0 / std::sqrt(3.0);
    for (int p = 0; p < 8; ++p) {
      const double xi[3] = {g * kCornerXi[p][0], g * kCornerXi[p][1], g * kCornerXi[p][2]};
      shape(xi, n[static_cast<std::size_t>(p)], dn);
    }
    return n;
  }();
  return table;
}

/// Jacobian J(i, j) = ∂x_j/∂ξ_i (Bathe's convention: ∂/∂x = J⁻¹ ∂/∂ξ).
Eigen::Matrix3d jacobian(const Eigen::Matrix<double, 3, 8>& dn, const std::array<Vec3, 8>& x) {
  Eigen::Matrix3d j = Eigen::Matrix3d::Zero();
  for (int a = 0; a < 8; ++a) j += dn.col(a) * x[a].transpose();
  return j;
}

Eigen::Matrix3d voigt_to_tensor(const Vector6d& s) {
  Eigen::Matrix3d t;
  t << s(0), s(3), s(5), s(3), s(1), s(4), s(5), s(4), s(2);
  return t;
}

}  // namespace

Brick8::Brick8(int id, const std::array<int, 8>& nodes, const std::array<Vec3, 8>& x,
               const IsotropicElasticity& material, bool extra_shapes, const SourceLocation& where,
               std::optional<J2Plasticity> plasticity, bool large_deflection, BrickStrain strain)
    : Element(id), nodes_(nodes), x_(x), plasticity_(std::move(plasticity)) {
  // Distinct nodes in order of first appearance; coincident corners share DOFs.
  std::vector<int> unique;
  for (int c = 0; c < 8; ++c) {
    const auto it = std::find(unique.begin(), unique.end(), nodes[c]);
    if (it == unique.end()) {
      corner_to_unique_[c] = static_cast<int>(unique.size());
      unique.push_back(nodes[c]);
    } else {
      corner_to_unique_[c] = static_cast<int>(it - unique.begin());
    }
  }
  n_unique_ = static_cast<int>(unique.size());
  if (n_unique_ < 4)
    throw InputError(where, fmt::format("element {}: a brick needs at least 4 distinct nodes, "
                                        "got {}",
                                        id, n_unique_));
  for (int node : unique)
    for (Dof dof : {Dof::UX, Dof::UY, Dof::UZ}) dofs_.push_back(DofKey{node, dof});

  d_ = isotropic_elasticity_matrix(material.young, material.poisson);
  density_ = material.density;
  // Wilson's bubbles need a genuine hexahedron: dropped for collapsed shapes (ANSYS does too).
  // Enhanced strain needs them too; a collapsed enhanced brick keeps B-bar against volumetric
  // locking. B-bar has no internal parameters.
  strain_ = strain;
  if (strain_ == BrickStrain::Enhanced && n_unique_ < 8) strain_ = BrickStrain::BBar;
  extra_shapes_ = strain_ == BrickStrain::Enhanced ||
                  (strain_ == BrickStrain::Standard && extra_shapes && n_unique_ == 8);
  n_internal_ = strain_ == BrickStrain::Enhanced ? 13 : (extra_shapes_ ? 9 : 0);

  // Length scale for the Jacobian test: a determinant below 1e-10 of (size/2)³ is "zero".
  double size = 0.0;
  for (int a = 0; a < 8; ++a)
    for (int b = a + 1; b < 8; ++b) size = std::max(size, (x[a] - x[b]).norm());
  const double det_floor = 1e-10 * std::pow(0.5 * size, 3);

  Eigen::Matrix<double, 8, 1> n;
  Eigen::Matrix<double, 3, 8> dn;
  const double centre[3] = {0.0, 0.0, 0.0};
  shape(centre, n, dn);
  const Eigen::Matrix3d j0 = jacobian(dn, x);
  const double det0 = j0.determinant();
  det0_ = det0;
  if (!(det0 > det_floor))
    throw InputError(where, fmt::format("element {}: zero or negative Jacobian determinant {:.6g} "
                                        "at the element centre (check the node order I..P and "
                                        "coincident nodes)",
                                        id, det0));
  const Eigen::Matrix3d j0_inv = j0.inverse();
  grad_centre_ = j0_inv * dn;

  const double g = 1.0 / std::sqrt(3.0);
  volume_ = 0.0;
  for (int p = 0; p < kGauss; ++p) {
    const double xi[3] = {g * kCornerXi[p][0], g * kCornerXi[p][1], g * kCornerXi[p][2]};
    shape(xi, n, dn);
    const Eigen::Matrix3d j = jacobian(dn, x);
    const double det = j.determinant();
    if (!(det > det_floor))
      throw InputError(where, fmt::format("element {}: zero or negative Jacobian determinant "
                                          "{:.6g} at Gauss point {} (check the node order I..P "
                                          "and coincident nodes)",
                                          id, det, p + 1));
    GaussPoint& gp = gauss_[p];
    gp.dv = det;  // Gauss weights are 1 for the 2-point rule
    gp.grad.setZero();
    gp.grad.leftCols<8>() = j.inverse() * dn;
    // Taylor's modification: bubble gradients with the centre Jacobian, scaled by det J0/det J,
    // so that ∫ ∂P/∂x dV = det J0 J0⁻¹ ∫ ∂P/∂ξ dξ = 0 and constant strain is reproduced.
    for (int k = 0; k < kModes; ++k) {
      Eigen::Vector3d dp = Eigen::Vector3d::Zero();
      dp(k) = -2.0 * xi[k];
      gp.grad.col(8 + k) = (det0 / det) * (j0_inv * dp);
    }
    volume_ += det;
  }
  mean_dilatation_.setZero();
  for (const GaussPoint& gp : gauss_)
    for (int a = 0; a < 8; ++a)
      mean_dilatation_.segment<3>(3 * a) +=
          (gp.dv / volume_) * gp.grad.col(a).head<3>().transpose();

  if (plasticity_) committed_.resize(kGauss);
  // The finite-strain form (solid_finite_strain.h) has the mean dilatation but no internal
  // strain parameters, and no creep clock: a plastic brick with modes or creep is not built for
  // it (the registration refuses such a deck; tangent() refuses to solve it under NLGEOM).
  if (plasticity_ && large_deflection && n_internal_ == 0 && !plasticity_->has_creep()) {
    finite_points_.resize(kGauss);
    for (int p = 0; p < kGauss; ++p) {
      finite_points_[static_cast<std::size_t>(p)].grad = gauss_[p].grad.leftCols<8>();
      finite_points_[static_cast<std::size_t>(p)].dv0 = gauss_[p].dv;
    }
    finite_.resize(kGauss);
    committed_u_.setZero(3, 8);
  }
  if (extra_shapes_ && (plasticity_ || large_deflection)) mode_recovery_ = mode_recovery();
}

Eigen::MatrixXd Brick8::mode_recovery() const {
  if (mode_recovery_.size() != 0) return mode_recovery_;
  Eigen::MatrixXd r;
  small_strain_stiffness(&r);
  return r;
}

Eigen::Matrix<double, 6, Eigen::Dynamic> Brick8::strain_operator(int p, bool internal) const {
  const GaussPoint& gp = gauss_[static_cast<std::size_t>(p)];
  const int nf = internal && extra_shapes_ ? kFunctions : 8;
  const int n_vol = internal && strain_ == BrickStrain::Enhanced ? 4 : 0;
  Eigen::Matrix<double, 6, Eigen::Dynamic> b =
      Eigen::Matrix<double, 6, Eigen::Dynamic>::Zero(6, 3 * nf + n_vol);
  for (int a = 0; a < nf; ++a) {  // small-strain B (Bathe 5.3), engineering shear
    const double g0 = gp.grad(0, a), g1 = gp.grad(1, a), g2 = gp.grad(2, a);
    b(0, 3 * a) = g0;
    b(1, 3 * a + 1) = g1;
    b(2, 3 * a + 2) = g2;
    b(3, 3 * a) = g1;
    b(3, 3 * a + 1) = g0;
    b(4, 3 * a + 1) = g2;
    b(4, 3 * a + 2) = g1;
    b(5, 3 * a) = g2;
    b(5, 3 * a + 2) = g0;
  }
  if (n_vol > 0) {
    // Enhanced volumetric strains (Simo & Rifai 1990, eq. 3.13 form): ε = (det J0 / det J)
    // E(ξ) α with E = m (ξη, ηζ, ξζ, ξηζ), m = (1 1 1 0 0 0)ᵀ. ∫E dξ = 0, so they are
    // orthogonal to constant stress (patch test). With the bubbles' ξ, η, ζ dilatations they
    // make the 8 Gauss points' volumetric strains independent: no volumetric locking.
    const double g = 1.0 / std::sqrt(3.0);
    const double xi = g * kCornerXi[p][0], eta = g * kCornerXi[p][1], zeta = g * kCornerXi[p][2];
    const double scale = det0_ / gp.dv;  // the 2-point Gauss weights are 1: dv = det J
    const double e[4] = {xi * eta, eta * zeta, xi * zeta, xi * eta * zeta};
    for (int m = 0; m < 4; ++m) b.col(3 * nf + m).head<3>().setConstant(scale * e[m]);
  }
  if (bbar_active()) {
    // B-bar (selective dilatational, Hughes 1980; SOLID185 KEYOPT(2) = 0): the volumetric
    // strain of every point is replaced by the element mean (1/V)∫ div u dV, so an isochoric
    // field (plastic flow, ν → 0.5) is not constrained at each point.
    Eigen::Matrix<double, 1, 24> vol;
    for (int a = 0; a < 8; ++a) vol.segment<3>(3 * a) = gp.grad.col(a).head<3>().transpose();
    const Eigen::Matrix<double, 1, 24> shift = (mean_dilatation_ - vol) / 3.0;
    for (int i = 0; i < 3; ++i) b.row(i) += shift;
  }
  return b;
}

Eigen::Matrix<double, 24, 24> Brick8::small_strain_stiffness(Eigen::MatrixXd* recovery) const {
  if (strain_ != BrickStrain::Standard) {
    // K = Σ Bᵀ D B dV over the corners and internal parameters, then the internal ones
    // condensed: K = K_cc − K_ca K_aa⁻¹ K_ac (Simo & Rifai 1990 eq. 4.9, linear case).
    const int nq = 24 + n_internal_;
    Eigen::MatrixXd kfull = Eigen::MatrixXd::Zero(nq, nq);
    for (int p = 0; p < kGauss; ++p) {
      const Eigen::Matrix<double, 6, Eigen::Dynamic> b = strain_operator(p, true);
      kfull.noalias() += gauss_[static_cast<std::size_t>(p)].dv * (b.transpose() * d_ * b);
    }
    Eigen::Matrix<double, 24, 24> k = kfull.topLeftCorner<24, 24>();
    if (n_internal_ == 0) {
      if (recovery) recovery->setZero(9, 24);
      return 0.5 * (k + k.transpose());
    }
    const Eigen::MatrixXd modes = -kfull.bottomRightCorner(n_internal_, n_internal_)
                                       .ldlt()
                                       .solve(kfull.bottomLeftCorner(n_internal_, 24));
    if (recovery) *recovery = modes;
    k += kfull.topRightCorner(24, n_internal_) * modes;
    return 0.5 * (k + k.transpose());
  }
  // q = 0 in the total-Lagrangian sum; with extra shapes the bubble amplitudes condensed out
  // (static condensation, Wilson et al. 1973): K = K_cc − K_ca K_aa⁻¹ K_ac.
  Eigen::Matrix<double, 24, 24> k;
  if (!extra_shapes_) {
    Eigen::Matrix<double, 24, 1> ffull;
    tl_sum<8>(Eigen::Matrix<double, 24, 1>::Zero(), &k, ffull);
    if (recovery) recovery->setZero(9, 24);
    return k;
  }
  Eigen::Matrix<double, 3 * kFunctions, 3 * kFunctions> kfull;
  Eigen::Matrix<double, 3 * kFunctions, 1> ffull;
  tl_sum<kFunctions>(Eigen::Matrix<double, 3 * kFunctions, 1>::Zero(), &kfull, ffull);
  const Eigen::Matrix<double, 9, 9> kaa = kfull.bottomRightCorner<9, 9>();
  const Eigen::Matrix<double, 9, 24> modes = -kaa.ldlt().solve(kfull.bottomLeftCorner<9, 24>());
  if (recovery) *recovery = modes;
  k = kfull.topLeftCorner<24, 24>() + kfull.topRightCorner<24, 9>() * modes;
  return 0.5 * (k + k.transpose());
}

Eigen::Matrix<double, 24, 1> Brick8::to_corners(const Eigen::VectorXd& u) const {
  Eigen::Matrix<double, 24, 1> uc;
  for (int c = 0; c < 8; ++c) uc.segment<3>(3 * c) = u.segment<3>(3 * corner_to_unique_[c]);
  return uc;
}

void Brick8::from_corners(const Eigen::MatrixXd& kc, const Eigen::VectorXd& fc, Eigen::MatrixXd& k,
                          Eigen::VectorXd& f) const {
  const int n = 3 * n_unique_;
  k.setZero(n, n);
  f.setZero(n);
  for (int a = 0; a < 8; ++a) {
    const int p = 3 * corner_to_unique_[a];
    f.segment<3>(p) += fc.segment<3>(3 * a);
    for (int b = 0; b < 8; ++b)
      k.block<3, 3>(p, 3 * corner_to_unique_[b]) += kc.block<3, 3>(3 * a, 3 * b);
  }
}

template <int NF, int K0>
void Brick8::tl_sum(const Eigen::Matrix<double, 3 * NF, 1>& q,
                    Eigen::Matrix<double, 3 * NF, 3 * NF>* k_out,
                    Eigen::Matrix<double, 3 * NF, 1>& f) const {
  // St. Venant-Kirchhoff with this element's isotropic D (S = λ tr(E) I + 2μ E). With
  // h_a = F ∇N_a, the variation of the Green strain by function a in direction i is
  // δE = sym(Fᵀ e_i ⊗ ∇N_a); with C = λ I ⊗ I + 2μ 𝕀 the Voigt sum B_Lᵀ D B_L + Gᵀ S G of
  // Bathe §6.2.3 has the 3 × 3 blocks
  //   K_ab = λ h_a h_bᵀ + μ (h_b h_aᵀ + (∇N_a · ∇N_b) F Fᵀ) + (∇N_aᵀ S ∇N_b) I,
  // and f_a = F S ∇N_a (first Piola-Kirchhoff stress on the gradient), all times dV0: the same
  // sums as the Voigt products with a general D, without the 6 × 3NF matrices.
  static_assert(0 <= K0 && K0 < NF);
  constexpr int NK = NF - K0;  // functions of the K block formed
  const double lambda = d_(0, 1), mu = d_(3, 3);
  f.setZero();
  // q and f as 3 × NF (column a = function a).
  const Eigen::Map<const Eigen::Matrix<double, 3, NF>> q_mat(q.data());
  Eigen::Map<Eigen::Matrix<double, 3, NF>> f_mat(f.data());
  // For K, the Gauss-point terms are gathered as columns and summed by products after the loop
  // (vectorised, instead of 3 × 3 blocks per point): h of point p as column p of h_all and
  // dV0 h in hw_all (Σ dV0 vec(h) vec(h)ᵀ holds the λ and μ h h terms); ∇N_a · ∇N_b for a ≤ b
  // as column p of gram_all and the 6 distinct entries of μ dV0 F Fᵀ as row p of c_all (their
  // product holds the μ (∇N_a · ∇N_b) F Fᵀ term); and Σ ∇Nᵀ S dV0 ∇N. Functions K0.. only.
  constexpr int kPairs = NK * (NK + 1) / 2;  // (a, b), a ≤ b, at b (b + 1) / 2 + a
  Eigen::Matrix<double, 3 * NK, kGauss> h_all, hw_all;
  Eigen::Matrix<double, kPairs, kGauss> gram_all;
  Eigen::Matrix<double, kGauss, 6> c_all;
  Eigen::Matrix<double, NK, NK> gsg = Eigen::Matrix<double, NK, NK>::Zero();
  for (int p = 0; p < kGauss; ++p) {
    const GaussPoint& gp = gauss_[static_cast<std::size_t>(p)];
    const auto grad = gp.grad.template leftCols<NF>();
    // Deformation gradient F = I + Σ q_a ⊗ ∇N_a (Bathe 6.2.3).
    const Eigen::Matrix3d f_grad =
        Eigen::Matrix3d::Identity() + q_mat.lazyProduct(grad.transpose());
    const Eigen::Matrix3d e = 0.5 * (f_grad.transpose() * f_grad - Eigen::Matrix3d::Identity());
    // 2nd Piola-Kirchhoff stress times dV0.
    Eigen::Matrix3d s_dv = (2.0 * mu * gp.dv) * e;
    s_dv.diagonal().array() += lambda * gp.dv * e.trace();
    f_mat.noalias() += (f_grad * s_dv).lazyProduct(grad);
    if (!k_out) continue;
    const auto grad_k = gp.grad.template middleCols<NK>(K0);
    Eigen::Map<Eigen::Matrix<double, 3, NK>>(h_all.col(p).data()) = f_grad.lazyProduct(grad_k);
    hw_all.col(p) = gp.dv * h_all.col(p);
    for (int b = 0, ab = 0; b < NK; ++b)
      for (int a = 0; a <= b; ++a, ++ab) gram_all(ab, p) = grad_k.col(a).dot(grad_k.col(b));
    const Eigen::Matrix3d c_mu = (mu * gp.dv) * (f_grad * f_grad.transpose());
    c_all.row(p) << c_mu(0, 0), c_mu(1, 1), c_mu(2, 2), c_mu(0, 1), c_mu(1, 2), c_mu(0, 2);
    gsg.noalias() += grad_k.transpose().lazyProduct(s_dv * grad_k);
  }
  if (!k_out) return;
  const Eigen::Matrix<double, 3 * NK, 3 * NK> hh = hw_all.lazyProduct(h_all.transpose());
  const Eigen::Matrix<double, kPairs, 6> gram_c = gram_all.lazyProduct(c_all);
  // Blocks a ≤ b, then the lower triangle mirrored. hh is symmetric: hh(3b+i, 3a+j) =
  // hh(3a+j, 3b+i), the μ h_b h_aᵀ term.
  static constexpr int kVoigt[3][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}};
  auto k = k_out->template bottomRightCorner<3 * NK, 3 * NK>();
  for (int b = 0, ab = 0; b < NK; ++b)
    for (int a = 0; a <= b; ++a, ++ab)
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i)
          k(3 * a + i, 3 * b + j) = lambda * hh(3 * a + i, 3 * b + j) +
                                    mu * hh(3 * a + j, 3 * b + i) + gram_c(ab, kVoigt[i][j]) +
                                    (i == j ? gsg(a, b) : 0.0);
  for (int c = 0; c < 3 * NK; ++c)
    for (int r = c + 1; r < 3 * NK; ++r) k(r, c) = k(c, r);
}

void Brick8::tangent_linear(const ElementContext& ctx, const Eigen::Matrix<double, 24, 1>& uc,
                            Eigen::MatrixXd& kc, Eigen::VectorXd& fc) const {
  Eigen::MatrixXd recovery;
  const Eigen::Matrix<double, 24, 24> k =
      small_strain_stiffness(ctx.stress_stiffening ? &recovery : nullptr);
  kc = k;
  fc = k * uc;
  if (!ctx.stress_stiffening) return;
  // Stress stiffness with the small-strain stress of u (standard functions only).
  Eigen::VectorXd q(24 + n_internal_);
  q.head<24>() = uc;
  if (n_internal_ > 0) q.tail(n_internal_) = recovery * uc;
  Eigen::Matrix<double, 24, 24> kg = Eigen::Matrix<double, 24, 24>::Zero();
  for (int p = 0; p < kGauss; ++p) {
    const GaussPoint& gp = gauss_[static_cast<std::size_t>(p)];
    const Vector6d sigma = d_ * (strain_operator(p, true) * q);
    const auto grad = gp.grad.leftCols<8>();
    const Eigen::Matrix<double, 8, 8> gs =
        gp.dv * (grad.transpose() * voigt_to_tensor(sigma) * grad);
    for (int a = 0; a < 8; ++a)
      for (int c = 0; c < 8; ++c)
        for (int i = 0; i < 3; ++i) kg(3 * a + i, 3 * c + i) += gs(a, c);
  }
  kc += kg;
  fc += kg * uc;
}

void Brick8::tangent_large(const Eigen::Matrix<double, 24, 1>& uc, Eigen::MatrixXd& kc,
                           Eigen::VectorXd& fc) const {
  if (!extra_shapes_) {
    Eigen::Matrix<double, 24, 24> k8;
    Eigen::Matrix<double, 24, 1> f8;
    tl_sum<8>(uc, &k8, f8);
    kc = k8;
    fc = f8;
    return;
  }
  // Incompatible modes in the deformation gradient: the bubble amplitudes α are internal, so
  // solve ∂Π/∂α = f_α(u, α) = 0 by Newton for this u, then condense the consistent tangent:
  // K = K_uu - K_uα K_αα⁻¹ K_αu (exact at f_α = 0).
  constexpr int kNq = 3 * kFunctions;
  Eigen::Matrix<double, kNq, 1> q;
  q.head<24>() = uc;
  q.tail<9>() = mode_recovery().topRows<9>() * uc;  // small-strain prediction (bubbles)
  Eigen::Matrix<double, kNq, kNq> kq;
  Eigen::Matrix<double, kNq, 1> fq;
  const double scale = std::max(uc.lpNorm<Eigen::Infinity>(), 1e-300);
  bool converged = false;
  for (int iter = 0; iter < 30; ++iter) {
    tl_sum<kFunctions, 8>(q, &kq, fq);  // f and the bubbles' block K_αα only
    const Eigen::Matrix<double, 9, 1> step =
        -kq.bottomRightCorner<9, 9>().ldlt().solve(fq.tail<9>());
    q.tail<9>() += step;
    if (step.lpNorm<Eigen::Infinity>() <=
        1e-13 * std::max(scale, q.tail<9>().lpNorm<Eigen::Infinity>())) {
      converged = true;
      break;
    }
  }
  if (!converged)
    Log::warn("element {}: incompatible-mode amplitudes did not converge (large deflection)", id());
  tl_sum<kFunctions>(q, &kq, fq);
  const Eigen::Matrix<double, 9, 9> kaa = kq.bottomRightCorner<9, 9>();
  const Eigen::Matrix<double, 9, 24> kau = kq.bottomLeftCorner<9, 24>();
  const auto kaa_ldlt = kaa.ldlt();
  kc = kq.topLeftCorner<24, 24>() - kau.transpose() * kaa_ldlt.solve(kau);
  kc = 0.5 * (kc + kc.transpose()).eval();
  fc = fq.head<24>() - kau.transpose() * kaa_ldlt.solve(fq.tail<9>());
}

void Brick8::plastic_sum(const Eigen::VectorXd& q, Eigen::MatrixXd& k, Eigen::VectorXd& f,
                         PointStates* updated) const {
  const auto nq = q.size();
  k.setZero(nq, nq);
  f.setZero(nq);
  for (int p = 0; p < kGauss; ++p) {
    const GaussPoint& gp = gauss_[static_cast<std::size_t>(p)];
    // B-bar without internal parameters (isochoric plastic flow does not lock), else the
    // incompatible / enhanced modes in the strain (strain_operator()).
    const Eigen::Matrix<double, 6, Eigen::Dynamic> b = strain_operator(p, nq > 24);
    const Vector6d eps = b * q;
    const PlasticResponse r =
        plasticity_->solid(committed_[static_cast<std::size_t>(p)], eps,
                           updated ? &(*updated)[static_cast<std::size_t>(p)] : nullptr);
    f.noalias() += gp.dv * (b.transpose() * r.stress);
    k.noalias() += gp.dv * (b.transpose() * r.tangent * b);
  }
}

void Brick8::tangent_plastic(const Eigen::Matrix<double, 24, 1>& uc, Eigen::MatrixXd& kc,
                             Eigen::VectorXd& fc, PointStates* updated) const {
  if (!extra_shapes_) {
    plastic_sum(uc, kc, fc, updated);
    return;
  }
  // The mode amplitudes α are internal: f_α(u, α) = ∫B_αᵀσ dV = 0 is solved by Newton from the
  // elastic prediction (each evaluation returns every point from its committed state, so this
  // stays a function of (committed state, u)); then K = K_uu − K_uα K_αα⁻¹ K_αu, exact at f_α = 0
  // (Simo & Rifai 1990 for the enhanced-strain analogue).
  const int ni = n_internal_;
  Eigen::VectorXd q(24 + ni);
  q.head<24>() = uc;
  q.tail(ni) = mode_recovery() * uc;
  Eigen::MatrixXd kq;
  Eigen::VectorXd fq;
  const double scale = std::max(uc.lpNorm<Eigen::Infinity>(), 1e-300);
  for (int iter = 0; iter < 25; ++iter) {
    plastic_sum(q, kq, fq, nullptr);
    const Eigen::VectorXd step = -kq.bottomRightCorner(ni, ni).ldlt().solve(fq.tail(ni));
    q.tail(ni) += step;
    if (step.lpNorm<Eigen::Infinity>() <=
        1e-12 * std::max(scale, q.tail(ni).lpNorm<Eigen::Infinity>()))
      break;
  }
  // A residual f_α left by an unconverged local iteration is condensed consistently below.
  plastic_sum(q, kq, fq, updated);
  const Eigen::MatrixXd kau = kq.bottomLeftCorner(ni, 24);
  const auto kaa_ldlt = kq.bottomRightCorner(ni, ni).ldlt();
  kc = kq.topLeftCorner<24, 24>() - kau.transpose() * kaa_ldlt.solve(kau);
  kc = 0.5 * (kc + kc.transpose()).eval();
  fc = fq.head<24>() - kau.transpose() * kaa_ldlt.solve(fq.tail(ni));
}

void Brick8::commit_history(const ElementContext& ctx, const Eigen::VectorXd& u) {
  if (!plasticity_) return;
  if (finite_strain() && ctx.large_deflection) {
    finite_commit(to_corners(u));
    return;
  }
  Eigen::MatrixXd kc;
  Eigen::VectorXd fc;
  PointStates next = committed_;
  tangent_plastic(to_corners(u), kc, fc, &next);
  committed_ = next;
}

std::vector<double> Brick8::history_state() const {
  std::vector<double> out;
  if (plasticity_)
    for (const PlasticState& s : committed_) append_state(out, s);  // per Gauss point
  // Finite strain: the accumulated strains, then the committed corner displacements.
  for (const FiniteStrainState& s : finite_)
    out.insert(out.end(), s.strain.data(), s.strain.data() + 6);
  out.insert(out.end(), committed_u_.data(), committed_u_.data() + committed_u_.size());
  return out;
}

void Brick8::restore_history_state(const std::vector<double>& state) {
  std::size_t pos = 0;
  if (plasticity_)
    for (PlasticState& s : committed_) read_state(state, pos, s);
  const std::size_t finite = 6 * finite_.size() + static_cast<std::size_t>(committed_u_.size());
  IMPACTFE_CHECK(pos + finite == state.size(), "SOLID: saved state of the wrong length");
  for (std::size_t p = 0; p < finite_.size(); ++p) {
    for (int i = 0; i < 6; ++i) finite_[p].strain(i) = state[pos++];
    finite_[p].plastic = committed_[p];
  }
  for (Eigen::Index i = 0; i < committed_u_.size(); ++i) committed_u_.data()[i] = state[pos++];
}

double Brick8::plastic_work() const {
  double w = 0.0;
  for (std::size_t p = 0; p < committed_.size(); ++p)
    w += committed_[p].plastic_work * gauss_[p].dv;
  return w;
}

void Brick8::tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
                     Eigen::VectorXd& f_int) const {
  const Eigen::Matrix<double, 24, 1> uc = to_corners(u);
  // Corner order is the DOF order when no node repeats: the corner matrices are then formed in
  // K and f_int, which keep their storage from one evaluation to the next (two allocations per
  // evaluation otherwise, issue 11).
  const bool corners_are_dofs = n_unique_ == 8;
  Eigen::MatrixXd kc_collapsed;
  Eigen::VectorXd fc_collapsed;
  Eigen::MatrixXd& kc = corners_are_dofs ? K : kc_collapsed;
  Eigen::VectorXd& fc = corners_are_dofs ? f_int : fc_collapsed;
  if (plasticity_) {
    if (ctx.large_deflection && !finite_strain())
      throw ElementSolutionError(
          id(), fmt::format("element {}: large deflection (NLGEOM,ON) with a TB plasticity "
                            "material is implemented for a brick built with NLGEOM,ON, without "
                            "incompatible or enhanced modes and without creep",
                            id()));
    if (!ctx.large_deflection && finite_strain())
      throw ElementSolutionError(
          id(), fmt::format("element {}: a plastic brick built with NLGEOM,ON cannot be solved "
                            "small-strain: large deflection may not change within an analysis "
                            "of a plastic brick",
                            id()));
    if (ctx.large_deflection) {
      // Updated Lagrangian: the symmetric tangent includes the initial-stress stiffness.
      finite_sum(uc, &kc, fc, nullptr, FiniteStrainTangent::Symmetric);
      kc = 0.5 * (kc + kc.transpose()).eval();
    } else if (ctx.stress_stiffening) {
      throw ElementSolutionError(
          id(), fmt::format("element {}: stress stiffening (SSTIF) without large deflection "
                            "with a TB plasticity material is not implemented for bricks",
                            id()));
    } else {
      tangent_plastic(uc, kc, fc, nullptr);
    }
  } else if (ctx.large_deflection)
    tangent_large(uc, kc, fc);
  else
    tangent_linear(ctx, uc, kc, fc);
  if (!corners_are_dofs) from_corners(kc, fc, K, f_int);
}

void Brick8::internal_force(const ElementContext& ctx, const Eigen::VectorXd& u,
                            Eigen::VectorXd& f_int) const {
  // The bubble amplitudes of extra shapes are solved with the stiffness; plasticity and the
  // small-strain forms cost little beside their tangent: those take the full evaluation.
  if (!separate_internal_force(ctx)) {
    Element::internal_force(ctx, u, f_int);
    return;
  }
  Eigen::Matrix<double, 24, 1> fc;
  tl_sum<8>(to_corners(u), nullptr, fc);
  if (n_unique_ == 8) {  // as from_corners
    f_int = fc;
    return;
  }
  const int n = 3 * n_unique_;
  f_int.setZero(n);
  for (int a = 0; a < 8; ++a) f_int.segment<3>(3 * corner_to_unique_[a]) += fc.segment<3>(3 * a);
}

Eigen::MatrixXd Brick8::scalar_mass() const {
  Eigen::Matrix<double, 8, 8> mc = Eigen::Matrix<double, 8, 8>::Zero();
  const auto& n = gauss_shape();
  for (int p = 0; p < kGauss; ++p)
    mc.noalias() += (density_ * gauss_[static_cast<std::size_t>(p)].dv) *
                    (n[static_cast<std::size_t>(p)] * n[static_cast<std::size_t>(p)].transpose());
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n_unique_, n_unique_);
  for (int a = 0; a < 8; ++a)
    for (int b = 0; b < 8; ++b) m(corner_to_unique_[a], corner_to_unique_[b]) += mc(a, b);
  return m;
}

void Brick8::mass(const ElementContext& ctx, Eigen::MatrixXd& M) const {
  Eigen::MatrixXd ms = scalar_mass();
  if (ctx.lumped_mass) {
    // HRZ (Hinton-Rock-Zienkiewicz): diagonal of the consistent matrix scaled to ρV.
    const Eigen::VectorXd diag = ms.diagonal();
    const double sum = diag.sum();
    ms.setZero();
    if (sum > 0.0) ms.diagonal() = diag * (density_ * volume_ / sum);
  }
  const int n = 3 * n_unique_;
  M.setZero(n, n);
  for (int p = 0; p < n_unique_; ++p)
    for (int q = 0; q < n_unique_; ++q)
      for (int i = 0; i < 3; ++i) M(3 * p + i, 3 * q + i) = ms(p, q);
}

Vector6d Brick8::centroid_stress(const ElementContext& ctx, const Eigen::VectorXd& u) const {
  const Eigen::Matrix<double, 24, 1> uc = to_corners(u);
  // The bubble gradients vanish at ξ = 0, so only the trilinear part contributes here.
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for (int a = 0; a < 8; ++a) h += uc.segment<3>(3 * a) * grad_centre_.col(a).transpose();
  if (!ctx.large_deflection) {
    Vector6d eps;
    eps << h(0, 0), h(1, 1), h(2, 2), h(0, 1) + h(1, 0), h(1, 2) + h(2, 1), h(0, 2) + h(2, 0);
    // The enhanced volumetric modes vanish at ξ = 0 too; B-bar: the element's mean dilatation.
    if (bbar_active()) eps.head<3>().array() += (mean_dilatation_ * uc - h.trace()) / 3.0;
    // σ = D (ε − ε_th), the temperature at the centroid the mean of the corners'.
    return d_ * (eps - thermal_strain(Eigen::Matrix<double, 8, 1>::Constant(0.125)));
  }
  const Eigen::Matrix3d f_grad = Eigen::Matrix3d::Identity() + h;
  const Eigen::Matrix3d e = 0.5 * (f_grad.transpose() * f_grad - Eigen::Matrix3d::Identity());
  Vector6d e_voigt;
  e_voigt << e(0, 0), e(1, 1), e(2, 2), 2.0 * e(0, 1), 2.0 * e(1, 2), 2.0 * e(0, 2);
  // Cauchy stress σ = F S Fᵀ / det F (Bathe 6.2.2).
  const Eigen::Matrix3d sigma =
      f_grad * voigt_to_tensor(d_ * e_voigt) * f_grad.transpose() / f_grad.determinant();
  Vector6d out;
  out << sigma(0, 0), sigma(1, 1), sigma(2, 2), sigma(0, 1), sigma(1, 2), sigma(0, 2);
  return out;
}

Vector6d Brick8::thermal_strain(const Eigen::Matrix<double, 8, 1>& n) const {
  Vector6d eps = Vector6d::Zero();
  const std::vector<double>& dT = temperature_change();
  if (dT.size() != 8) return eps;
  double t = 0.0;
  for (int a = 0; a < 8; ++a) t += n(a) * dT[static_cast<std::size_t>(a)];
  eps.head<3>() = thermal_expansion().alpha * t;
  return eps;
}

void Brick8::thermal_load(const ElementContext&, Eigen::VectorXd& f) const {
  // f = Σ_p Bᵀ σ_th dV_p with σ_th = D ε_th(ξ_p), B over the corners and the internal
  // parameters (B-bar when in effect: the work conjugate of the stiffness's strain).
  const int nq = 24 + n_internal_;
  Eigen::VectorXd ffull = Eigen::VectorXd::Zero(nq);
  const auto& n = gauss_shape();
  for (int p = 0; p < kGauss; ++p) {
    const GaussPoint& gp = gauss_[static_cast<std::size_t>(p)];
    const Vector6d s = d_ * thermal_strain(n[static_cast<std::size_t>(p)]);
    ffull.noalias() += gp.dv * (strain_operator(p, true).transpose() * s);
  }
  Eigen::Matrix<double, 24, 1> fc = ffull.head<24>();
  // Static condensation of the internal amplitudes: K_aa a + K_ac u = f_a gives the corner load
  // f_c − K_ca K_aa⁻¹ f_a = f_c + Rᵀ f_a with the recovery R = −K_aa⁻¹ K_ac.
  if (n_internal_ > 0) fc += mode_recovery().transpose() * ffull.tail(n_internal_);
  const int nu = 3 * n_unique_;
  f.setZero(nu);
  for (int c = 0; c < 8; ++c) f.segment<3>(3 * corner_to_unique_[c]) += fc.segment<3>(3 * c);
}

const std::vector<std::string>& Brick8::result_names() const {
  return brick8_result_names();
}

const std::vector<std::string>& brick8_result_names() {
  // A function-local static: the registrations (brick8_types.cpp) read it during static
  // initialisation, before a namespace-scope table of this file may be constructed.
  static const std::vector<std::string> names = {
      "SX",   "SY",    "SZ",    "SXY",   "SYZ",    "SXZ",    "S1",     "S2",      "S3",   "SINT",
      "SEQV", "EPPLX", "EPPLY", "EPPLZ", "EPPLXY", "EPPLYZ", "EPPLXZ", "EPEQ",    "SEPL", "SRAT",
      "PLWK", "EPCRX", "EPCRY", "EPCRZ", "EPCRXY", "EPCRYZ", "EPCRXZ", "EPCREQV", "CREQ"};
  return names;
}

ElementResultValues solid_stress_row(const Vector6d& s) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(voigt_to_tensor(s),
                                                          Eigen::EigenvaluesOnly);
  const Eigen::Vector3d pr = es.eigenvalues();  // ascending
  const double s1 = pr(2), s2 = pr(1), s3 = pr(0);
  const double seqv =
      std::sqrt(0.5 * ((s1 - s2) * (s1 - s2) + (s2 - s3) * (s2 - s3) + (s3 - s1) * (s3 - s1)));
  ElementResultValues out = {s(0), s(1), s(2), s(3), s(4), s(5), s1, s2, s3, s1 - s3, seqv};
  out.resize(brick8_result_names().size(), 0.0);
  return out;
}

bool Brick8::nodal_results(const ElementContext& ctx, const Eigen::VectorXd& u,
                           std::map<int, ElementResultValues>& at_node) const {
  if (plasticity_ || ctx.large_deflection || degenerate() || thermal_expansion().expands())
    return false;
  const Eigen::Matrix<double, 24, 1> uc = to_corners(u);
  Eigen::VectorXd q(24 + n_internal_);
  q.head<24>() = uc;
  if (n_internal_ > 0) q.tail(n_internal_) = mode_recovery() * uc;
  std::array<Vector6d, kGauss> sigma;
  for (int p = 0; p < kGauss; ++p)
    sigma[static_cast<std::size_t>(p)] = d_ * (strain_operator(p, n_internal_ > 0) * q);
  // Gauss point p sits at ξ = corner p / √3: the trilinear functions of the points, at the
  // corner c, are those of the element at ξ = √3 · corner c.
  const double r3 = std::sqrt(3.0);
  at_node.clear();
  Eigen::Matrix<double, 8, 1> n;
  Eigen::Matrix<double, 3, 8> dn;
  for (int c = 0; c < 8; ++c) {
    const double xi[3] = {r3 * kCornerXi[c][0], r3 * kCornerXi[c][1], r3 * kCornerXi[c][2]};
    shape(xi, n, dn);
    Vector6d s = Vector6d::Zero();
    for (int p = 0; p < kGauss; ++p) s += n(p) * sigma[static_cast<std::size_t>(p)];
    at_node[nodes_[static_cast<std::size_t>(c)]] = solid_stress_row(s);
  }
  return true;
}

void Brick8::results(const ElementContext& ctx, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                     ElementResultValues& out) const {
  Vector6d s;
  Vector6d plastic_strain = Vector6d::Zero();
  double epeq = 0.0, sepl = 0.0, srat = 0.0, plwk = 0.0;
  const bool finite = plasticity_ && finite_strain() && ctx.large_deflection;
  if (finite || (plasticity_ && !ctx.large_deflection && !ctx.stress_stiffening)) {
    // The states at u (the committed ones after a converged step), averaged over the (reference)
    // volume; under large deflection the Cauchy stresses and the states rotated to the current
    // configuration.
    PointStates at = committed_;
    if (finite) {
      FiniteStrainUpdate up;
      Eigen::VectorXd fc;
      finite_sum(to_corners(u), nullptr, fc, &up);
      for (std::size_t p = 0; p < at.size(); ++p) at[p] = up.states[p].plastic;
    } else {
      Eigen::MatrixXd kc;
      Eigen::VectorXd fc;
      tangent_plastic(to_corners(u), kc, fc, &at);
    }
    s.setZero();
    for (int p = 0; p < kGauss; ++p) {
      const PlasticState& st = at[static_cast<std::size_t>(p)];
      const double w = gauss_[static_cast<std::size_t>(p)].dv / volume_;
      s += w * st.stress;
      plastic_strain += w * st.plastic_strain;
      epeq += w * st.alpha;
      plwk += w * st.plastic_work;
      srat = std::max(srat,
                      von_mises(st.stress - st.back_stress) / plasticity_->flow_stress(st.alpha));
    }
    sepl = plasticity_->flow_stress(epeq);
  } else {
    s = centroid_stress(ctx, u);
  }
  // A creep material's inelastic strain is its creep strain (EPCR, NL CREQ); it has no
  // plastic strain, yield surface or plastic work.
  Vector6d creep_strain = Vector6d::Zero();
  double creq = 0.0;
  if (plasticity_ && plasticity_->has_creep()) {
    creep_strain = plastic_strain;
    creq = epeq;
    plastic_strain.setZero();
    epeq = sepl = srat = plwk = 0.0;
  }
  out = solid_stress_row(s);
  const double inelastic[18] = {plastic_strain(0),
                                plastic_strain(1),
                                plastic_strain(2),
                                plastic_strain(3),
                                plastic_strain(4),
                                plastic_strain(5),
                                epeq,
                                sepl,
                                srat,
                                plwk,
                                creep_strain(0),
                                creep_strain(1),
                                creep_strain(2),
                                creep_strain(3),
                                creep_strain(4),
                                creep_strain(5),
                                equivalent_inelastic_strain(creep_strain),
                                creq};
  std::copy(inelastic, inelastic + 18, out.begin() + 11);
}

}  // namespace impactfe
