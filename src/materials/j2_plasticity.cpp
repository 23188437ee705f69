#include "materials/j2_plasticity.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/errors.h"

namespace impactfe {

namespace {

const double kSqrt32 = std::sqrt(1.5);

/// Tensor norm of a Voigt stress-like vector (tensor shear components).
double tensor_norm(const Vector6d& s) {
  return std::sqrt(s.head<3>().squaredNorm() + 2.0 * s.tail<3>().squaredNorm());
}

Vector6d deviator(const Vector6d& s) {
  Vector6d d = s;
  const double p = (s(0) + s(1) + s(2)) / 3.0;
  d.head<3>().array() -= p;
  return d;
}

/// A strain-like Voigt vector (engineering shear) of the tensor n: shear components doubled.
Vector6d engineering(const Vector6d& n) {
  Vector6d e = n;
  e.tail<3>() *= 2.0;
  return e;
}

}  // namespace

double von_mises(const Vector6d& s) {
  return kSqrt32 * tensor_norm(deviator(s));
}

J2Plasticity J2Plasticity::bilinear(double young, double poisson, double yield_stress,
                                    double tangent_modulus, bool kinematic) {
  IMPACTFE_CHECK(
      young > 0.0 && yield_stress > 0.0 && tangent_modulus >= 0.0 && tangent_modulus < young,
      "bilinear plasticity needs E > 0, σy > 0 and 0 ≤ Et < E");
  J2Plasticity law;
  law.kind_ = kinematic ? HardeningKind::BilinearKinematic : HardeningKind::BilinearIsotropic;
  law.young_ = young;
  law.poisson_ = poisson;
  // Plastic modulus from the tangent modulus (uniaxial): 1/Et = 1/E + 1/H.
  const double h = young * tangent_modulus / (young - tangent_modulus);
  if (kinematic) {
    law.isotropic_ = {{0.0, yield_stress}};
    law.extend_last_slope_ = false;
    law.kinematic_ = h;
  } else {
    law.isotropic_ = {{0.0, yield_stress}, {1.0, yield_stress + h}};
    law.extend_last_slope_ = true;
  }
  return law;
}

J2Plasticity J2Plasticity::multilinear(double young, double poisson,
                                       std::vector<std::pair<double, double>> curve) {
  IMPACTFE_CHECK(
      young > 0.0 && !curve.empty() && curve.front().first == 0.0 && curve.front().second > 0.0,
      "multilinear plasticity needs E > 0 and a curve starting at (0, σy > 0)");
  J2Plasticity law;
  law.kind_ = HardeningKind::MultilinearIsotropic;
  law.young_ = young;
  law.poisson_ = poisson;
  law.isotropic_ = std::move(curve);
  law.extend_last_slope_ = false;  // perfectly plastic beyond the last point (MAPDL MISO)
  return law;
}

J2Plasticity J2Plasticity::creep(double young, double poisson, CreepLaw law,
                                 std::shared_ptr<const CreepClock> clock) {
  IMPACTFE_CHECK(young > 0.0 && clock != nullptr, "creep needs E > 0 and the solution's clock");
  J2Plasticity out;
  out.kind_ = HardeningKind::Creep;
  out.young_ = young;
  out.poisson_ = poisson;
  // No yield surface: the inelastic strain is the creep strain alone.
  out.isotropic_ = {{0.0, std::numeric_limits<double>::infinity()}};
  out.extend_last_slope_ = false;
  out.creep_ = std::move(law);
  out.clock_ = std::move(clock);
  return out;
}

double CreepLaw::increment(double q, double e, double t_end, double dt, double temperature) const {
  if (!(q > 0.0) || !(dt > 0.0)) return 0.0;
  // Arrhenius factor e^(−C/T); a zero constant means no temperature dependence.
  const auto arrhenius = [&](double k) { return k == 0.0 ? 1.0 : std::exp(-k / temperature); };
  const double t0 = std::max(t_end - dt, 0.0), t1 = t_end;
  // ∫ t^C3 dt over the substep, exact: (t1^(C3+1) − t0^(C3+1)) / (C3+1).
  const auto time_integral = [&](double c3) {
    if (std::abs(c3 + 1.0) < 1e-12) return t0 > 0.0 ? std::log(t1 / t0) : 0.0;
    return (std::pow(t1, c3 + 1.0) - std::pow(t0, c3 + 1.0)) / (c3 + 1.0);
  };
  const double c1 = constant(1), c2 = constant(2), c3 = constant(3), c4 = constant(4);
  // MAPDL integrates every implicit creep law by backward Euler (Theory Reference, implicit
  // creep): the laws it gives as rates (1, 2, 3, 7, 10) contribute ε̇(σ, ε, t_n+1) Δt, the rate at
  // the end of the substep; the laws it gives as strains (6, 11) contribute the difference of
  // their strain between t_n and t_n+1 at the end-of-substep stress. So time hardening (2) and
  // modified time hardening (6), equal at constant stress in the continuum, differ per substep:
  // NAFEMS R0049 CR1b (vmr049-cr1b) integrates TBOPT 2 at Δt = 100 to ε(1000) = 0.251 where
  // t^0.5/0.5 gives 0.316.
  switch (option) {
    case 1:  // strain hardening, backward Euler at the end-of-substep creep strain
      return dt * c1 * std::pow(q, c2) * std::pow(e, c3) * arrhenius(c4);
    case 2:  // time hardening ε̇ = C1 σ^C2 t^C3 e^(−C4/T) at t_n+1
      return dt * c1 * std::pow(q, c2) * std::pow(t1, c3) * arrhenius(c4);
    case 6:  // modified time hardening: ε(t_n+1) − ε(t_n) of ε = C1 σ^C2 t^(C3+1) e^(−C4/T)/(C3+1)
      return c1 * std::pow(q, c2) * arrhenius(c4) * time_integral(c3);
    case 3: {  // generalized exponential ε̇ = C1 σ^C2 r e^(−rt) at t_n+1
      const double r = constant(5) * std::pow(q, c3) * arrhenius(c4);
      return dt * c1 * std::pow(q, c2) * r * std::exp(-r * t1);
    }
    case 7:  // modified strain hardening
      return dt * std::pow(c1 * std::pow(q, c2) * std::pow((c3 + 1.0) * e, c3), 1.0 / (c3 + 1.0)) *
             arrhenius(c4);
    case 10:  // Norton
      return dt * c1 * std::pow(q, c2) * arrhenius(c3);
    case 11:  // combined time hardening: primary (modified time hardening) plus secondary
      return c1 * std::pow(q, c2) * arrhenius(c4) * time_integral(c3) +
             constant(5) * std::pow(q, constant(6)) * arrhenius(constant(7)) * dt;
    default:
      IMPACTFE_CHECK(false, "creep equation not implemented");
      return 0.0;
  }
}

bool J2Plasticity::creeping() const {
  return clock_ && clock_->active && clock_->dt > 0.0;
}

double J2Plasticity::creep_increment(double q_trial, double c, double alpha_n,
                                     double& slope) const {
  // g(Δ) = Δ − F(q_tr − cΔ, α_n + Δ) rises from g(0) = −F(q_tr, α_n) ≤ 0 to g(q_tr/c) = q_tr/c
  // (F = 0 at zero stress): the root is bracketed; Newton with bisection where it leaves the
  // bracket. F's partial derivatives by central differences (relative step 1e-6).
  const CreepClock& k = *clock_;
  const auto F = [&](double q, double e) {
    return creep_.increment(q, e, k.time, k.dt, k.temperature);
  };
  // Only the strain-hardening laws (1, 7) read the creep strain: the others skip its partial,
  // two of the five evaluations of the law per iteration.
  const bool strain_hardening = creep_.option == 1 || creep_.option == 7;
  const auto partials = [&](double q, double e, double& fq, double& fe) {
    const double hq = 1e-6 * q;
    fq = hq > 0.0 ? (F(q + hq, e) - F(q - hq, e)) / (2.0 * hq) : 0.0;
    fe = 0.0;
    if (!strain_hardening) return;
    const double he = 1e-6 * std::max(e, 1e-300);
    fe = e > he ? (F(q, e + he) - F(q, e - he)) / (2.0 * he) : (F(q, e + he) - F(q, e)) / he;
    if (!std::isfinite(fe)) fe = 0.0;
  };
  slope = 0.0;
  if (!(q_trial > 0.0) || F(q_trial, alpha_n) <= 0.0) return 0.0;
  double lo = 0.0, hi = q_trial / c;
  double d = std::min(F(q_trial, alpha_n), 0.5 * hi);
  if (!std::isfinite(d)) d = 0.5 * hi;
  for (int it = 0; it < 200; ++it) {
    const double q = q_trial - c * d, e = alpha_n + d;
    const double g = d - F(q, e);
    if (g < 0.0)
      lo = d;
    else
      hi = d;
    if (std::abs(g) <= 1e-13 * d || hi - lo <= 1e-15 * hi) break;
    double fq = 0.0, fe = 0.0;
    partials(q, e, fq, fe);
    const double dg = 1.0 + c * fq - fe;
    double next = d - g / dg;
    if (!std::isfinite(next) || next <= lo || next >= hi || !(dg > 0.0)) next = 0.5 * (lo + hi);
    d = next;
  }
  double fq = 0.0, fe = 0.0;
  partials(q_trial - c * d, alpha_n + d, fq, fe);
  const double denominator = 1.0 + c * fq - fe;
  slope = denominator > 0.0 ? fq / denominator : 0.0;  // dΔ/dq_tr from dg = 0
  return d;
}

double J2Plasticity::flow_slope(double alpha) const {
  const auto& p = isotropic_;
  // The segment that a forward increment from α enters (right-sided at a breakpoint).
  for (std::size_t j = 0; j + 1 < p.size(); ++j)
    if (alpha < p[j + 1].first)
      return (p[j + 1].second - p[j].second) / (p[j + 1].first - p[j].first);
  if (extend_last_slope_ && p.size() >= 2) {
    const auto& a = p[p.size() - 2];
    const auto& b = p.back();
    return (b.second - a.second) / (b.first - a.first);
  }
  return 0.0;
}

double J2Plasticity::flow_stress(double alpha) const {
  const auto& p = isotropic_;
  for (std::size_t j = 0; j + 1 < p.size(); ++j)
    if (alpha < p[j + 1].first)
      return p[j].second +
             (p[j + 1].second - p[j].second) / (p[j + 1].first - p[j].first) * (alpha - p[j].first);
  return p.back().second + (alpha - p.back().first) * flow_slope(alpha);
}

double J2Plasticity::solve_increment(double s, double c, double alpha_n) const {
  // r(Δα) = s − (c + H)Δα − k(α_n + Δα) falls monotonically (k non-decreasing); k is linear on
  // each segment, so the root is exact once the segment holding it is found.
  const double a = c + kinematic_;
  double alpha = alpha_n;
  for (;;) {
    const double slope = flow_slope(alpha);
    // End of the segment that starts at α (none for the last one).
    double end = -1.0;
    for (const auto& [x, k] : isotropic_)
      if (x > alpha) {
        end = x;
        break;
      }
    if (end > alpha && s - a * (end - alpha_n) - flow_stress(end) > 0.0) {
      alpha = end;  // the root lies beyond this segment
      continue;
    }
    const double k = flow_stress(alpha);
    // s − a(α − α_n) − a x − k − slope x = 0 with x = α_{n+1} − α.
    const double x = (s - a * (alpha - alpha_n) - k) / (a + slope);
    return alpha + x - alpha_n;
  }
}

UniaxialResponse J2Plasticity::uniaxial(const UniaxialPlasticState& committed, double strain,
                                        UniaxialPlasticState* updated) const {
  UniaxialResponse out;
  const double trial = young_ * (strain - committed.plastic_strain);
  if (kind_ == HardeningKind::Creep) {
    // Backward Euler on the creep strain: σ = E(ε − ε_cr,n − sign Δ), Δ = F(|σ|, α_n + Δ);
    // dσ/dε = E(1 − E dΔ/dq_tr).
    double h = 0.0;
    const double d =
        creeping() ? creep_increment(std::abs(trial), young_, committed.alpha, h) : 0.0;
    const double sign = trial >= 0.0 ? 1.0 : -1.0;
    const double creep_strain = committed.plastic_strain + sign * d;
    out.stress = young_ * (strain - creep_strain);
    out.tangent = young_ * (1.0 - young_ * h);
    out.yielding = d > 0.0;
    if (updated) {
      *updated = committed;
      updated->plastic_strain = creep_strain;
      updated->alpha = committed.alpha + d;
      updated->plastic_work =
          committed.plastic_work + 0.5 * (committed.stress + out.stress) * sign * d;
      updated->stress = out.stress;
    }
    return out;
  }
  const double xi = trial - committed.back_stress;
  const double f = std::abs(xi) - flow_stress(committed.alpha);
  if (f <= 0.0) {
    out.stress = trial;
    out.tangent = young_;
    if (updated) {
      *updated = committed;
      updated->stress = trial;
    }
    return out;
  }
  // Box 3.1: Δα from the consistency condition, return along sign(ξ).
  const double d_alpha = solve_increment(std::abs(xi), young_, committed.alpha);
  const double sign = xi > 0.0 ? 1.0 : -1.0;
  const double plastic_strain = committed.plastic_strain + sign * d_alpha;
  out.stress = young_ * (strain - plastic_strain);
  const double h = flow_slope(committed.alpha + d_alpha) + kinematic_;
  out.tangent = young_ * h / (young_ + h);  // Box 3.1: E(K' + H)/(E + K' + H)
  out.yielding = true;
  if (updated) {
    updated->plastic_strain = plastic_strain;
    updated->back_stress = committed.back_stress + sign * kinematic_ * d_alpha;
    updated->alpha = committed.alpha + d_alpha;
    // Trapezoidal rule, like the internal work of the energy balance.
    updated->plastic_work =
        committed.plastic_work + 0.5 * (committed.stress + out.stress) * sign * d_alpha;
    updated->stress = out.stress;
  }
  return out;
}

PlasticResponse J2Plasticity::solid(const PlasticState& committed, const Vector6d& strain,
                                    PlasticState* updated) const {
  PlasticResponse out;
  const double bulk = young_ / (3.0 * (1.0 - 2.0 * poisson_));
  const double mu = young_ / (2.0 * (1.0 + poisson_));
  const Matrix6d elastic = isotropic_elasticity_matrix(young_, poisson_);
  const Vector6d trial = elastic * (strain - committed.plastic_strain);
  const Vector6d xi = deviator(trial) - committed.back_stress;
  const double xi_norm = tensor_norm(xi);
  // Creep: Δ = F(q_tr − 3μΔ, α_n + Δ) replaces the consistency condition (no yield surface).
  double creep_slope = 0.0;
  const double creep =
      kind_ == HardeningKind::Creep && creeping() && xi_norm > 0.0
          ? creep_increment(kSqrt32 * xi_norm, 3.0 * mu, committed.alpha, creep_slope)
          : 0.0;
  const double f = kind_ == HardeningKind::Creep ? (creep > 0.0 ? 1.0 : -1.0)
                                                 : kSqrt32 * xi_norm - flow_stress(committed.alpha);
  if (f <= 0.0) {
    out.stress = trial;
    out.tangent = elastic;
    if (updated) {
      *updated = committed;
      updated->stress = trial;
    }
    return out;
  }
  // Box 3.2: σ_eq,trial − (3μ + H)Δα − k(α_n + Δα) = 0, Δγ = √(3/2) Δα.
  const double d_alpha = kind_ == HardeningKind::Creep
                             ? creep
                             : solve_increment(kSqrt32 * xi_norm, 3.0 * mu, committed.alpha);
  const double d_gamma = kSqrt32 * d_alpha;
  const Vector6d n = xi / xi_norm;
  out.stress = trial - 2.0 * mu * d_gamma * n;
  out.yielding = true;
  // Consistent tangent, Simo & Hughes (3.3.14) with combined hardening:
  // C = κ 1⊗1 + 2μθ I_dev − 2μθ̄ n⊗n, θ = 1 − 2μΔγ/|ξ_trial|,
  // θ̄ = 1/(1 + (k' + H)/(3μ)) − (1 − θ). In Voigt form with engineering shear strains I_dev has
  // 1/2 on the shear diagonal and n⊗n acts on the strain through n:ε = n_v·ε_v.
  const double theta = 1.0 - 2.0 * mu * d_gamma / xi_norm;
  // Creep: dΔ/dq_tr = F_q / (1 + 3μ F_q − F_ε) takes the place of 1/(3μ + k' + H).
  const double h =
      kind_ == HardeningKind::Creep ? 0.0 : flow_slope(committed.alpha + d_alpha) + kinematic_;
  const double theta_bar = kind_ == HardeningKind::Creep
                               ? 3.0 * mu * creep_slope - (1.0 - theta)
                               : 1.0 / (1.0 + h / (3.0 * mu)) - (1.0 - theta);
  Matrix6d dev = Matrix6d::Zero();
  dev.topLeftCorner<3, 3>().setConstant(-1.0 / 3.0);
  dev.topLeftCorner<3, 3>().diagonal().array() += 1.0;
  dev.bottomRightCorner<3, 3>().diagonal().setConstant(0.5);
  Matrix6d one = Matrix6d::Zero();
  one.topLeftCorner<3, 3>().setOnes();
  out.tangent = bulk * one + 2.0 * mu * theta * dev - 2.0 * mu * theta_bar * n * n.transpose();
  if (updated) {
    const Vector6d d_plastic = d_gamma * engineering(n);
    updated->plastic_strain = committed.plastic_strain + d_plastic;
    updated->back_stress = committed.back_stress + (2.0 / 3.0) * kinematic_ * d_gamma * n;
    updated->alpha = committed.alpha + d_alpha;
    updated->plastic_work =
        committed.plastic_work + 0.5 * (committed.stress + out.stress).dot(d_plastic);
    updated->stress = out.stress;
    updated->thickness_strain = committed.thickness_strain;
  }
  return out;
}

PlaneStressResponse J2Plasticity::plane_stress(const PlasticState& committed,
                                               const Vector5d& strain,
                                               PlasticState* updated) const {
  // Positions of (xx, yy, xy, yz, xz) in the 6-vector; zz is position 2.
  static constexpr int kIn[5] = {0, 1, 3, 4, 5};
  Vector6d e;
  for (int i = 0; i < 5; ++i) e(kIn[i]) = strain(i);
  // Start: the thickness strain of an elastic step from the committed plastic strain (exact when
  // the step stays elastic).
  const Vector6d& ep = committed.plastic_strain;
  e(2) = ep(2) - poisson_ / (1.0 - poisson_) * (strain(0) - ep(0) + strain(1) - ep(1));
  PlasticResponse r = solid(committed, e, nullptr);
  const double scale = kind_ == HardeningKind::Creep
                           ? std::max(r.stress.cwiseAbs().maxCoeff(), 1e-300)
                           : std::max(flow_stress(committed.alpha), r.stress.cwiseAbs().maxCoeff());
  for (int it = 0; it < 50 && std::abs(r.stress(2)) > 1e-12 * scale; ++it) {
    e(2) -= r.stress(2) / r.tangent(2, 2);  // Newton on σzz(εzz) = 0
    r = solid(committed, e, nullptr);
  }
  if (std::abs(r.stress(2)) > 1e-8 * scale)
    throw SolutionError(fmt::format(
        "plane-stress return did not converge (σzz = {:g} after 50 iterations)", r.stress(2)));
  PlaneStressResponse out;
  out.yielding = r.yielding;
  // Condensation of σzz = 0: C_ps = C_rr − C_rz C_zr / C_zz (implicit function theorem).
  for (int i = 0; i < 5; ++i) {
    out.stress(i) = r.stress(kIn[i]);
    for (int j = 0; j < 5; ++j)
      out.tangent(i, j) =
          r.tangent(kIn[i], kIn[j]) - r.tangent(kIn[i], 2) * r.tangent(2, kIn[j]) / r.tangent(2, 2);
  }
  if (updated) {
    solid(committed, e, updated);
    updated->thickness_strain = e(2);
  }
  return out;
}

namespace {

bool is_plasticity_table(const std::string& label) {
  return label == "PLAS" || label == "BISO" || label == "BKIN" || label == "MISO" ||
         label == "MKIN" || label == "KINH";
}

std::string table_name(const MaterialTable& t) {
  return t.label == "PLAS" ? "TB,PLAS,,,," + t.option : "TB," + t.label;
}

/// The plasticity table (TB,PLAS, BISO, BKIN, MISO, MKIN, KINH) and the creep table of the
/// element's material; TB,HILL is checked to be von Mises's potential.
void plasticity_tables_of(const Model& model, const ElementRecord& record,
                          const MaterialTable*& table, const MaterialTable*& creep) {
  for (const auto& [key, t] : model.material_tables) {
    if (key.first == record.mat && is_plasticity_table(t.label)) table = &t;
    if (key.first == record.mat && t.label == "CREEP") creep = &t;
    // TB,HILL: Hill's potential with the ratios R11 R22 R33 R12 R23 R13 all 1 is von Mises's,
    // which the laws here are; any other ratio (an anisotropic potential) is refused.
    if (key.first == record.mat && t.label == "HILL") {
      const std::vector<double>& r = t.temperatures.front().constants;
      bool isotropic = r.size() == 6;
      for (double v : r) isotropic = isotropic && v == 1.0;
      if (!isotropic)
        throw InputError(t.where, fmt::format("material {} (TB,HILL, used by element {}): only "
                                              "the isotropic potential (TBDATA,1,1,1,1,1,1,1: von "
                                              "Mises) is implemented",
                                              record.mat, record.id));
    }
  }
}

/// Implicit creep (TB,CREEP): the law's option and constants, checked.
J2Plasticity creep_of(const Model& model, const ElementRecord& record, const MaterialTable* creep,
                      const MaterialTable* table, double young, double poisson, bool implicit) {
  const auto fail = [&](const std::string& what) {
    throw InputError(creep->where, fmt::format("material {} (TB,CREEP,,,,{}, used by element "
                                               "{}): {}",
                                               record.mat, creep->option, record.id, what));
  };
  if (table)
    fail(fmt::format("creep combined with {} plasticity (TB at {}:{}) is not implemented",
                     table_name(*table), table->where.file, table->where.line));
  if (!implicit) fail("implicit creep is not available in explicit dynamics");
  CreepLaw law;
  law.option = std::stoi(creep->option);
  law.c = creep->temperatures.front().constants;
  if (!(law.constant(1) > 0.0))
    fail(fmt::format("C1 (TBDATA 1) is {} (must be positive)", law.constant(1)));
  if ((law.option == 2 || law.option == 6 || law.option == 11) && law.constant(3) <= -1.0)
    fail(fmt::format("C3 = {} must be greater than −1 (time exponent)", law.constant(3)));
  if (law.option == 7 && law.constant(3) <= -1.0)
    fail(fmt::format("C3 = {} must be greater than −1", law.constant(3)));
  return J2Plasticity::creep(young, poisson, std::move(law), model.creep_clock);
}

/// The hardening curve of MISO as (plastic strain, stress) points, checked: TB,PLAS,,,,MISO
/// points are (plastic strain, stress); legacy TB,MISO points are (total strain, stress) with the
/// first on the elastic line, converted by ε_p = ε − σ/E (spec §6.3).
template <class Fail>
std::vector<std::pair<double, double>> multilinear_curve(const MaterialTable& table, double young,
                                                         const Fail& fail) {
  std::vector<std::pair<double, double>> curve = table.temperatures.front().points;
  if (curve.empty()) fail("no stress-strain points (TBPT)");
  if (table.label == "MISO") {
    const auto [e1, s1] = curve.front();
    if (!(e1 > 0.0) || std::abs(s1 / e1 - young) > 1e-3 * young)
      fail(
          fmt::format("the first point ({}, {}) must lie on the elastic line (slope {} ≠ EX = "
                      "{})",
                      e1, s1, e1 > 0.0 ? s1 / e1 : 0.0, young));
    for (auto& [eps, sig] : curve) eps -= sig / young;
    curve.front().first = 0.0;
  }
  if (std::abs(curve.front().first) > 1e-12)
    fail(fmt::format("the first point must be at plastic strain 0 (it is at {})",
                     curve.front().first));
  curve.front().first = 0.0;
  if (!(curve.front().second > 0.0))
    fail(fmt::format("the yield stress (first point) is {} (must be positive)",
                     curve.front().second));
  for (std::size_t j = 1; j < curve.size(); ++j)
    if (!(curve[j].first > curve[j - 1].first) || curve[j].second < curve[j - 1].second)
      fail(
          fmt::format("point {} ({}, {}): plastic strain must increase and stress must not "
                      "fall (softening is not supported)",
                      j + 1, curve[j].first, curve[j].second));
  return curve;
}

}  // namespace

std::optional<J2Plasticity> plasticity_of(const Model& model, const ElementRecord& record,
                                          double young, double poisson, bool implicit) {
  const MaterialTable* table = nullptr;
  const MaterialTable* creep = nullptr;
  plasticity_tables_of(model, record, table, creep);
  if (creep) return creep_of(model, record, creep, table, young, poisson, implicit);
  if (!table) return std::nullopt;
  const std::string name = table_name(*table);
  const auto fail = [&](const std::string& what) {
    throw InputError(table->where, fmt::format("material {} ({}, used by element {}): {}",
                                               record.mat, name, record.id, what));
  };
  const std::string law = table->label == "PLAS" ? table->option : table->label;
  if (law == "KINH" || law == "MKIN")
    fail(
        "multilinear kinematic hardening (Besseling sublayers) is not implemented; use "
        "BKIN, BISO or MISO");
  if (table->temperatures.size() != 1)
    fail(fmt::format("{} temperatures given; only one temperature is supported",
                     table->temperatures.size()));
  const auto& data = table->temperatures.front();
  if (law == "BISO" || law == "BKIN") {
    const double sy = data.constants.size() > 0 ? data.constants[0] : 0.0;
    double et = data.constants.size() > 1 ? data.constants[1] : 0.0;
    if (!(sy > 0.0)) fail(fmt::format("yield stress (TBDATA 1) is {} (must be positive)", sy));
    if (table->label == "PLAS") {
      // TB,PLAS,,,,BISO|BKIN gives the plastic tangent modulus Ep = dσ/dε_pl (vm198's deck says
      // so, and the NAFEMS decks vmr049-pl1b..pl3b pass E Et/(E − Et) there), not TB,BISO's
      // tangent modulus Et = dσ/dε: Et = E Ep/(E + Ep).
      if (!(et >= 0.0))
        fail(fmt::format("plastic tangent modulus (TBDATA 2) = {} must be ≥ 0", et));
      et = young * et / (young + et);
    }
    if (!(et >= 0.0 && et < young))
      fail(fmt::format("tangent modulus Et (TBDATA 2) = {} must satisfy 0 ≤ Et < EX = {}", et,
                       young));
    return J2Plasticity::bilinear(young, poisson, sy, et, law == "BKIN");
  }
  return J2Plasticity::multilinear(young, poisson, multilinear_curve(*table, young, fail));
}

// ---- flat forms of the committed states (restart files) ----------------------------------------

void append_state(std::vector<double>& out, const UniaxialPlasticState& s) {
  out.insert(out.end(), {s.plastic_strain, s.back_stress, s.alpha, s.plastic_work, s.stress});
}

void append_state(std::vector<double>& out, const PlasticState& s) {
  out.insert(out.end(), s.plastic_strain.data(), s.plastic_strain.data() + 6);
  out.insert(out.end(), s.back_stress.data(), s.back_stress.data() + 6);
  out.insert(out.end(), {s.alpha, s.plastic_work, s.thickness_strain});
  out.insert(out.end(), s.stress.data(), s.stress.data() + 6);
}

void read_state(const std::vector<double>& in, std::size_t& pos, UniaxialPlasticState& s) {
  IMPACTFE_CHECK(pos + 5 <= in.size(), "saved uniaxial plastic state too short");
  s.plastic_strain = in[pos];
  s.back_stress = in[pos + 1];
  s.alpha = in[pos + 2];
  s.plastic_work = in[pos + 3];
  s.stress = in[pos + 4];
  pos += 5;
}

void read_state(const std::vector<double>& in, std::size_t& pos, PlasticState& s) {
  IMPACTFE_CHECK(pos + 21 <= in.size(), "saved plastic state too short");
  for (int i = 0; i < 6; ++i) s.plastic_strain(i) = in[pos + static_cast<std::size_t>(i)];
  for (int i = 0; i < 6; ++i) s.back_stress(i) = in[pos + 6 + static_cast<std::size_t>(i)];
  s.alpha = in[pos + 12];
  s.plastic_work = in[pos + 13];
  s.thickness_strain = in[pos + 14];
  for (int i = 0; i < 6; ++i) s.stress(i) = in[pos + 15 + static_cast<std::size_t>(i)];
  pos += 21;
}

}  // namespace impactfe
