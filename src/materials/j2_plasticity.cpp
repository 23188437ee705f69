#include "materials/j2_plasticity.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

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
  const double f = kSqrt32 * xi_norm - flow_stress(committed.alpha);
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
  const double d_alpha = solve_increment(kSqrt32 * xi_norm, 3.0 * mu, committed.alpha);
  const double d_gamma = kSqrt32 * d_alpha;
  const Vector6d n = xi / xi_norm;
  out.stress = trial - 2.0 * mu * d_gamma * n;
  out.yielding = true;
  // Consistent tangent, Simo & Hughes (3.3.14) with combined hardening:
  // C = κ 1⊗1 + 2μθ I_dev − 2μθ̄ n⊗n, θ = 1 − 2μΔγ/|ξ_trial|,
  // θ̄ = 1/(1 + (k' + H)/(3μ)) − (1 − θ). In Voigt form with engineering shear strains I_dev has
  // 1/2 on the shear diagonal and n⊗n acts on the strain through n:ε = n_v·ε_v.
  const double theta = 1.0 - 2.0 * mu * d_gamma / xi_norm;
  const double h = flow_slope(committed.alpha + d_alpha) + kinematic_;
  const double theta_bar = 1.0 / (1.0 + h / (3.0 * mu)) - (1.0 - theta);
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
  const double scale = std::max(flow_stress(committed.alpha), r.stress.cwiseAbs().maxCoeff());
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

}  // namespace

std::optional<J2Plasticity> plasticity_of(const Model& model, const ElementRecord& record,
                                          double young, double poisson) {
  const MaterialTable* table = nullptr;
  for (const auto& [key, t] : model.material_tables)
    if (key.first == record.mat && is_plasticity_table(t.label)) table = &t;
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
    const double et = data.constants.size() > 1 ? data.constants[1] : 0.0;
    if (!(sy > 0.0)) fail(fmt::format("yield stress (TBDATA 1) is {} (must be positive)", sy));
    if (!(et >= 0.0 && et < young))
      fail(fmt::format("tangent modulus Et (TBDATA 2) = {} must satisfy 0 ≤ Et < EX = {}", et,
                       young));
    return J2Plasticity::bilinear(young, poisson, sy, et, law == "BKIN");
  }
  // MISO: TB,PLAS,,,,MISO points are (plastic strain, stress); legacy TB,MISO points are (total
  // strain, stress) with the first on the elastic line, converted by ε_p = ε − σ/E (spec §6.3).
  std::vector<std::pair<double, double>> curve = data.points;
  if (curve.empty()) fail("no stress-strain points (TBPT)");
  if (table->label == "MISO") {
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
  return J2Plasticity::multilinear(young, poisson, std::move(curve));
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
