// BEAM161: the explicit 3-D beam (MAPDL Element Reference release 18.2; LS-DYNA beam formulation
// 1, Hughes–Liu with cross-section integration, one station along the length),
// docs/explicit_dynamics.md. Nodes I, J; node K orients the section at the start (the s axis lies
// in the plane IJK). Six DOFs per node. Large rotations by a co-rotational frame per element and
// cycle: r = e1 along IJ, s = e2 the last cycle's e2 turned by the mean nodal spin over dt (so
// the section twists with the nodes) and made orthogonal to e1, t = e3 = e1 × e2. The rates, in
// the frame of the midpoint configuration x_{n+1/2}, from the nodal velocities v_a and angular
// velocities ω_a (LS-DYNA Theory Manual, "Belytschko Beam" / "Hughes-Liu Beam"; Belytschko, Liu &
// Moran, Nonlinear Finite Elements, §9.5):
//   ε̇ = e1·(v_J − v_I)/L,  κ̇_r,s,t = e_{1,2,3}·(ω_J − ω_I)/L,
//   γ̇_s = e2·(v_J − v_I)/L − e3·ω̄,  γ̇_t = e3·(v_J − v_I)/L + e2·ω̄  (ω̄ the mean of ω_I, ω_J),
// and at a section point (s, t): d_rr = ε̇ + t κ̇_s − s κ̇_t, 2d_rs = SHRF γ̇_s − t κ̇_r,
// 2d_rt = SHRF γ̇_t + s κ̇_r. A rigid motion (v = v0 + ω × x, ω the same at every node) makes none.
// Stresses σ_rr, τ_rs, τ_rt at the section points in the co-rotational frame (objective: they
// turn with it); the nodal forces and moments, in the frame at x_{n+1}, are the derivatives of the
// power L∫σ:d dA by the nodal velocities. Runs only in an explicit analysis: its implicit factory
// refuses.
#include <fmt/format.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "elements/element_fields.h"
#include "elements/element_registry.h"
#include "materials/isotropic_elasticity.h"
#include "materials/rate_plasticity.h"

namespace impactfe {

namespace {
namespace beam161 {

const std::string kFamily = "Beam161";
// Resultants in the element frame (r axial, s and t the section axes): axial force, shear forces
// along s and t, torque, bending moments about s and t; the largest equivalent stress and
// equivalent plastic strain over the section points.
const std::vector<std::string> kResults = {"FORC", "SFS", "SFT", "TQ", "MS", "MT", "SEQV", "EPEQ"};
constexpr int kMaxPoints = 16;

/// A section point: its coordinates in the section (s, t) and its share of the area.
struct SectionPoint {
  double s = 0.0, t = 0.0, w = 0.0;
};

/// The section's points, its area and its second moments about s and t (of the points: exact
/// for the rules used, which integrate the cubic in s and t exactly).
struct Section {
  std::array<SectionPoint, kMaxPoints> points{};
  int n = 0;
  double area = 0.0, iss = 0.0, itt = 0.0;  // iss = ∫t² dA (about s), itt = ∫s² dA (about t)
  void finish() {
    area = iss = itt = 0.0;
    for (int p = 0; p < n; ++p) {
      area += points[p].w;
      iss += points[p].w * points[p].t * points[p].t;
      itt += points[p].w * points[p].s * points[p].s;
    }
  }
};

/// Rectangle TS × TT (along s, t), 2×2 Gauss (LS-DYNA's default quadrature).
Section rectangle(double ts, double tt) {
  Section sec;
  const double g = 1.0 / std::sqrt(3.0);
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      sec.points[sec.n++] = {(i ? g : -g) * 0.5 * ts, (j ? g : -g) * 0.5 * tt, 0.25 * ts * tt};
  sec.finish();
  return sec;
}

/// Tube (or solid circle, inner diameter 0): 2 Gauss points in the radius with the weight r dr
/// (exact for r³, the second moments) times 8 equally spaced angles (exact for cos²).
Section circle(double outer, double inner) {
  Section sec;
  const double ro = 0.5 * outer, ri = 0.5 * inner;
  const double g = 1.0 / std::sqrt(3.0);
  for (int i = 0; i < 2; ++i) {
    const double r = 0.5 * (ro + ri) + (i ? g : -g) * 0.5 * (ro - ri);
    const double w = 0.5 * (ro - ri) * r;  // Gauss weight 1 × half-length × r
    for (int j = 0; j < 8; ++j) {
      const double a = M_PI / 4.0 * j;
      sec.points[sec.n++] = {r * std::cos(a), r * std::sin(a), w * M_PI / 4.0};
    }
  }
  sec.finish();
  return sec;
}

struct BeamMaterial {
  double young = 0.0, shear = 0.0, density = 0.0;
  std::optional<J2Plasticity> plasticity;
};

class Beam161Set final : public ExplicitElementSet {
 public:
  Beam161Set(const ExplicitBuildContext& ctx, const std::vector<const ElementRecord*>& records);

  const std::string& family() const override { return kFamily; }
  std::size_t size() const override { return ids_.size(); }
  int element_id(std::size_t k) const override { return ids_[k]; }
  int nodes_per_element() const override { return 2; }
  const int* nodes(std::size_t k) const override { return &nodes_[2 * k]; }
  bool has_rotations() const override { return true; }
  void add_element_mass(std::size_t k, std::vector<double>& mass) const override {
    for (int a = 0; a < 2; ++a) mass[nodes_[2 * k + a]] += half_mass(k);
  }
  void add_rotary_inertia(std::vector<double>& inertia) const override {
    for (std::size_t k = 0; k < size(); ++k)
      for (int a = 0; a < 2; ++a) inertia[nodes_[2 * k + a]] += rotary_inertia(k);
  }
  /// ∫ρ x xᵀ dV: the axis's m (aaᵀ + bbᵀ)/3 + m (abᵀ + baᵀ)/6 (x linear along it) plus the
  /// section's ρL (∫t² dA e3e3ᵀ + ∫s² dA e2e2ᵀ).
  Eigen::Matrix3d second_mass_moment(const ExplicitNodalView& s, std::size_t k) const override {
    const int i = nodes_[2 * k], j = nodes_[2 * k + 1];
    const Eigen::Vector3d a(s.x[i], s.y[i], s.z[i]), b(s.x[j], s.y[j], s.z[j]);
    const double m = 2.0 * half_mass(k);
    const Vec3 e1 = (b - a).normalized();
    Vec3 e2 = frame_[k] - frame_[k].dot(e1) * e1;
    e2.normalize();
    const Vec3 e3 = e1.cross(e2);
    const Section& sec = sections_[section_[k]];
    const double rl = density_[k] * length0_[k];
    return m / 3.0 * (a * a.transpose() + b * b.transpose()) +
           m / 6.0 * (a * b.transpose() + b * a.transpose()) +
           rl * (sec.iss * e3 * e3.transpose() + sec.itt * e2 * e2.transpose());
  }
  double element_step(const ExplicitNodalView& s, std::size_t k) const override {
    return step(k, length(s, k));
  }
  double scale_mass(std::size_t k, double factor, std::vector<double>& mass) override {
    const double added = (factor - 1.0) * 2.0 * half_mass(k);
    for (int a = 0; a < 2; ++a) mass[nodes_[2 * k + a]] += 0.5 * added;
    density_[k] *= factor;
    return added;
  }
  void results(Eigen::MatrixXd& out) const override;

 private:
  ExplicitStepLimit chunk_forces(const ExplicitNodalView& s, double dt, double* f, double* moments,
                                 std::size_t begin, std::size_t end,
                                 ExplicitSetEnergies& energies) override;
  double half_mass(std::size_t k) const {
    return 0.5 * density_[k] * sections_[section_[k]].area * length0_[k];
  }
  /// The nodal rotary inertia, the same about every axis: the half element's physical one about
  /// its stiffer bending axis, ρ(L/2) max(I_s, I_t), raised where needed to ρ(L/2) κGA L²/(4(E −
  /// κG)) so that no rotational mode of the element is faster than the axial one (see step()):
  /// LS-DYNA too scales the beams' rotary inertia so that rotations do not control the step.
  double rotary_inertia(std::size_t k) const {
    const Section& sec = sections_[section_[k]];
    const BeamMaterial& m = materials_[material_[k]];
    const double l = length0_[k], kg = shear_factor_[k] * m.shear;
    const double raised = kg * sec.area * l * l / (4.0 * std::max(m.young - kg, 0.1 * m.young));
    return 0.5 * density_[k] * l * std::max({sec.iss, sec.itt, raised});
  }
  /// The critical step 2/ω_max of the free element with its lumped masses m = ρAL/2 and rotary
  /// inertias J (its linear modes in closed form): axial ω² = 4E/(ρL²) (the step L/c of LS-DYNA's
  /// beams, LS-DYNA Theory Manual "Time step control"), torsion 2GI_p/(LJ), bending (the two
  /// rotations opposite) 2EI/(LJ), shear (the rotations equal, against the one-point transverse
  /// shear) κGA L (2/(L²m) + 1/(2J)). With the rotary inertia above the axial mode controls; the
  /// bound holds for any other choice.
  double step(std::size_t k, double l) const {
    const Section& sec = sections_[section_[k]];
    const BeamMaterial& m = materials_[material_[k]];
    const double rho = density_[k];
    const double mass = half_mass(k), j = rotary_inertia(k);
    const double kga = shear_factor_[k] * m.shear * sec.area;
    const double w2 =
        std::max({4.0 * m.young / (rho * l * l), 2.0 * m.shear * (sec.iss + sec.itt) / (l * j),
                  2.0 * m.young * std::max(sec.iss, sec.itt) / (l * j),
                  kga * l * (2.0 / (l * l * mass) + 0.5 / j)});
    return 2.0 / std::sqrt(w2);
  }
  double length(const ExplicitNodalView& s, std::size_t k) const {
    const int i = nodes_[2 * k], j = nodes_[2 * k + 1];
    return std::hypot(s.x[j] - s.x[i], s.y[j] - s.y[i], s.z[j] - s.z[i]);
  }
  /// Updates point p of element k over dt from the rates (d_rr, 2d_rs, 2d_rt, engineering
  /// shears); returns the plastic work per unit volume.
  double update_point(std::size_t k, int p, const double* d, double dt);

  std::vector<int> ids_, nodes_;
  std::vector<std::size_t> material_, section_;
  std::vector<double> length0_, density_, shear_factor_;
  std::vector<Vec3> frame_;  // per element: e2 (the s axis) of the last cycle
  std::vector<Section> sections_;
  std::vector<BeamMaterial> materials_;
  // Per element and point (kMaxPoints each): σ_rr, τ_rs, τ_rt; back stress; plastic strain.
  std::vector<double> stress_, back_, alpha_;
};

Beam161Set::Beam161Set(const ExplicitBuildContext& ctx,
                       const std::vector<const ElementRecord*>& records) {
  std::map<int, std::size_t> material_index;
  for (const ElementRecord* r : records) {
    const ElementType& type = ctx.model.element_type(r->type);
    if (const std::string why = keyopt_refusal(type); !why.empty())
      throw InputError(type.where.known() ? type.where : r->where,
                       fmt::format("element type {}: {}", type.id, why));
    if (r->nodes.size() < 3 || r->nodes[2] == 0)
      throw InputError(r->where, fmt::format("element {}: BEAM161 needs the orientation node K "
                                             "(E,I,J,K): it sets the section's s axis",
                                             r->id));
    if (r->nodes[0] == r->nodes[1])
      throw InputError(r->where,
                       fmt::format("element {}: BEAM161 needs two distinct nodes I, J", r->id));
    const auto real = ctx.model.real_sets.find(r->real);
    if (real == ctx.model.real_sets.end())
      throw InputError(r->where, fmt::format("element {}: BEAM161 needs real constant set {} "
                                             "(R,{},SHRF,TS1,TS2,TT1,TT2)",
                                             r->id, r->real, r->real));
    if (const std::string why = real_set_refusal(type, real->second); !why.empty())
      throw InputError(r->where, fmt::format("element {}: {}", r->id, why));
    const RealSet& set = real->second;
    const double shrf = set.get(1) == 0.0 ? 1.0 : set.get(1);
    if (!(shrf > 0.0))
      throw InputError(r->where, fmt::format("element {}: BEAM161 SHRF (R1) must be > 0, got {:g}",
                                             r->id, shrf));
    // TS2 and TT2 default to TS1 and TT1; a tapered beam takes the mean of its ends.
    const double ts1 = set.get(2), tt1 = set.get(4);
    const double ts = 0.5 * (ts1 + (set.get(3) == 0.0 ? ts1 : set.get(3)));
    const double tt = 0.5 * (tt1 + (set.get(5) == 0.0 ? tt1 : set.get(5)));
    const bool round = type.key(5) == 1;
    Section sec;
    if (round) {
      if (!(ts > 0.0) || tt < 0.0 || tt >= ts)
        throw InputError(r->where, fmt::format("element {}: BEAM161 tube (KEYOPT(5) = 1) needs "
                                               "the outer diameters DS1, DS2 (R2, R3) > 0 and "
                                               "inner ones DT1, DT2 (R4, R5) below them, got "
                                               "{:g} and {:g}",
                                               r->id, ts, tt));
      sec = circle(ts, tt);
    } else {
      if (!(ts > 0.0) || !(tt > 0.0))
        throw InputError(r->where,
                         fmt::format("element {}: BEAM161 rectangular section needs TS1 and TT1 "
                                     "(R2, R4) > 0 (TS2, TT2 default to them), got {:g} and {:g}",
                                     r->id, ts, tt));
      sec = rectangle(ts, tt);
    }
    auto [it, added] = material_index.emplace(r->mat, materials_.size());
    if (added) {
      const IsotropicElasticity e = read_isotropic_elasticity(ctx.model, r->mat, r->id, r->where);
      if (!(e.density > 0.0))
        throw InputError(r->where, fmt::format("element {}: material {} has no density (DENS): "
                                               "explicit dynamics needs the mass of every element",
                                               r->id, r->mat));
      materials_.push_back({e.young, e.young / (2.0 * (1.0 + e.poisson)), e.density,
                            plasticity_of(ctx.model, *r, e.young, e.poisson, false)});
    }
    const Vec3 xi = ctx.model.node(r->nodes[0]).x, xj = ctx.model.node(r->nodes[1]).x,
               xk = ctx.model.node(r->nodes[2]).x;
    const Vec3 e1 = (xj - xi).normalized();
    Vec3 e2 = (xk - xi) - (xk - xi).dot(e1) * e1;
    if (!(e2.norm() > 1e-8 * (xk - xi).norm()))
      throw InputError(r->where, fmt::format("element {}: BEAM161 orientation node K lies on the "
                                             "line IJ",
                                             r->id));
    e2.normalize();
    for (int a = 0; a < 2; ++a) nodes_.push_back(ctx.node_index(r->nodes[a], *r));
    ids_.push_back(r->id);
    material_.push_back(it->second);
    sections_.push_back(sec);
    section_.push_back(sections_.size() - 1);
    length0_.push_back((xj - xi).norm());
    density_.push_back(materials_[it->second].density);
    shear_factor_.push_back(shrf);
    frame_.push_back(e2);
  }
  stress_.assign(3 * kMaxPoints * ids_.size(), 0.0);
  back_.assign(3 * kMaxPoints * ids_.size(), 0.0);
  alpha_.assign(kMaxPoints * ids_.size(), 0.0);
}

double Beam161Set::update_point(std::size_t k, int p, const double* d, double dt) {
  const std::size_t at = kMaxPoints * k + static_cast<std::size_t>(p);
  double* s = &stress_[3 * at];
  const BeamMaterial& m = materials_[material_[k]];
  const double trial[3] = {s[0] + dt * m.young * d[0], s[1] + dt * m.shear * d[1],
                           s[2] + dt * m.shear * d[2]};
  std::copy(trial, trial + 3, s);
  if (!m.plasticity) return 0.0;
  // J2 with σ_ss = σ_tt = σ_st = 0 (the beam's stress state): q = √(ξ_r² + 3ξ_s² + 3ξ_t²),
  // ξ = σ − β. Associated flow dε_p = Δ ∂q/∂σ = Δ (ξ_r, 3ξ_s, 3ξ_t)/q (engineering shears), back
  // stress dβ = H_kin Δ (ξ_r, ξ_s, ξ_t)/q (Prager, uniaxially dβ = H_kin dε_p). Then
  // ξ_r = ξ_r,tr/(1 + (E + H)Δ/q), ξ_s,t = ξ_s,t,tr/(1 + (3G + H)Δ/q) and Δ solves
  // q(Δ) = k(α + Δ) (the 1-D return of LINK160 when the shears vanish).
  const J2Plasticity& law = *m.plasticity;
  const double h = law.kinematic_modulus();
  double* beta = &back_[3 * at];
  const double x[3] = {trial[0] - beta[0], trial[1] - beta[1], trial[2] - beta[2]};
  const double q_tr = std::sqrt(x[0] * x[0] + 3.0 * (x[1] * x[1] + x[2] * x[2]));
  const double alpha = alpha_[at];
  if (q_tr <= law.flow_stress(alpha)) return 0.0;
  const auto excess = [&](double delta) {
    const double yield = law.flow_stress(alpha + delta);
    const double a = x[0] / (1.0 + (m.young + h) * delta / yield);
    const double b = 1.0 / (1.0 + (3.0 * m.shear + h) * delta / yield);
    return std::sqrt(a * a + 3.0 * b * b * (x[1] * x[1] + x[2] * x[2])) - yield;
  };
  // Bracket: excess(0) > 0; at Δ_hi = q_tr/(min(E, 3G) + H) the scaled stress is below k.
  double lo = 0.0, hi = q_tr / (std::min(m.young, 3.0 * m.shear) + h), flo = excess(lo),
         fhi = excess(hi);
  while (fhi > 0.0) hi *= 2.0, fhi = excess(hi);
  double delta = hi;
  for (int it = 0; it < 100; ++it) {
    delta = hi - fhi * (hi - lo) / (fhi - flo);
    if (!(delta > lo && delta < hi)) delta = 0.5 * (lo + hi);
    const double f = excess(delta);
    if (std::abs(f) <= 1e-13 * q_tr || hi - lo <= 1e-15 * hi) break;
    if (f > 0.0) {
      lo = delta, flo = f;
      fhi *= 0.5;  // Illinois: keep the far end from stalling
    } else {
      hi = delta, fhi = f;
      flo *= 0.5;
    }
  }
  const double yield = law.flow_stress(alpha + delta);
  const double ca = 1.0 / (1.0 + (m.young + h) * delta / yield),
               cs = 1.0 / (1.0 + (3.0 * m.shear + h) * delta / yield);
  const double xi[3] = {x[0] * ca, x[1] * cs, x[2] * cs};
  const double q = std::sqrt(xi[0] * xi[0] + 3.0 * (xi[1] * xi[1] + xi[2] * xi[2]));
  const double flow[3] = {delta * xi[0] / q, 3.0 * delta * xi[1] / q, 3.0 * delta * xi[2] / q};
  for (int c = 0; c < 3; ++c) {
    beta[c] += h * delta * xi[c] / q;
    s[c] = beta[c] + xi[c];
  }
  alpha_[at] = alpha + delta;
  return s[0] * flow[0] + s[1] * flow[1] + s[2] * flow[2];
}

ExplicitStepLimit Beam161Set::chunk_forces(const ExplicitNodalView& st, double dt, double* f,
                                           double* moments, std::size_t begin, std::size_t end,
                                           ExplicitSetEnergies& energies) {
  ExplicitStepLimit limit;
  for (std::size_t k = begin; k < end; ++k) {
    const int i = nodes_[2 * k], j = nodes_[2 * k + 1];
    const Vec3 axis(st.x[j] - st.x[i], st.y[j] - st.y[i], st.z[j] - st.z[i]);
    const double l = axis.norm();
    if (!(l > 0.0))
      throw ElementSolutionError(ids_[k],
                                 fmt::format("element {} (BEAM161) has zero length", ids_[k]));
    const Vec3 e1 = axis / l;
    const Vec3 vi(st.vx[i], st.vy[i], st.vz[i]), vj(st.vx[j], st.vy[j], st.vz[j]);
    const Vec3 wi = st.wx ? Vec3(st.wx[i], st.wy[i], st.wz[i]) : Vec3::Zero();
    const Vec3 wj = st.wx ? Vec3(st.wx[j], st.wy[j], st.wz[j]) : Vec3::Zero();
    const Vec3 mean = 0.5 * (wi + wj);
    // The s axis follows the mean spin over the step (Rodrigues) and is made orthogonal to the
    // axis: at x_{n+1/2} (turned by half the step) for the rates, at x_{n+1} for the forces.
    const double angle = dt * mean.norm();
    const auto section_axis = [&](double share, const Vec3& axis_unit) {
      Vec3 e = frame_[k];
      if (angle > 0.0) e = Eigen::AngleAxisd(share * angle, mean.normalized()) * e;
      e -= e.dot(axis_unit) * axis_unit;
      const double norm = e.norm();
      if (!(norm > 1e-6))
        throw ElementSolutionError(ids_[k], fmt::format("element {} (BEAM161) turned its axis "
                                                        "onto its s axis in one step: a time "
                                                        "step too large",
                                                        ids_[k]));
      return Vec3(e / norm);
    };
    // The rates in the frame of the midpoint configuration x_{n+1/2} = x_{n+1} − dt/2 v_{n+1/2}
    // (LS-DYNA Theory Manual, "Hughes-Liu Beam": the strain increments at the midpoint): the
    // chord of a rigid rotation over the step, x_{n+1} − x_n, is exactly normal to the
    // midpoint's axis, so a rotation makes no axial strain; with the axis at x_{n+1} each step
    // would stretch the element by (ω dt)²/2.
    const Vec3 axis_mid = axis - 0.5 * dt * (vj - vi);
    const double lm = axis_mid.norm();
    const Vec3 m1 = axis_mid / lm, m2 = section_axis(0.5, m1), m3 = m1.cross(m2);
    const Vec3 e2 = section_axis(1.0, e1), e3 = e1.cross(e2);
    frame_[k] = e2;
    const Vec3 dv = (vj - vi) / lm, dw = (wj - wi) / lm;
    const double axial = m1.dot(dv), kr = m1.dot(dw), ks = m2.dot(dw), kt = m3.dot(dw);
    const double gs = m2.dot(dv) - m3.dot(mean), gt = m3.dot(dv) + m2.dot(mean);
    const double kappa = shear_factor_[k];
    const Section& sec = sections_[section_[k]];
    double n = 0.0, qs = 0.0, qt = 0.0, tq = 0.0, ms = 0.0, mt = 0.0, power = 0.0, plastic = 0.0;
    for (int p = 0; p < sec.n; ++p) {
      const SectionPoint& pt = sec.points[p];
      const double d[3] = {axial + pt.t * ks - pt.s * kt, gs - pt.t * kr, gt + pt.s * kr};
      const double rate[3] = {d[0], kappa * gs - pt.t * kr, kappa * gt + pt.s * kr};
      const double* s = &stress_[3 * (kMaxPoints * k + static_cast<std::size_t>(p))];
      const double before = s[0] * d[0] + s[1] * d[1] + s[2] * d[2];
      plastic += pt.w * update_point(k, p, rate, dt);
      power += pt.w * 0.5 * (before + s[0] * d[0] + s[1] * d[1] + s[2] * d[2]);
      n += pt.w * s[0];
      qs += pt.w * s[1];
      qt += pt.w * s[2];
      tq += pt.w * (pt.s * s[2] - pt.t * s[1]);
      ms += pt.w * pt.t * s[0];
      mt -= pt.w * pt.s * s[0];
    }
    energies.internal += internal_work(k, dt * lm * power);
    energies.plastic_work += lm * plastic;
    // ∂P/∂v and ∂P/∂ω of P = L(Nε̇ + Q_s γ̇_s + Q_t γ̇_t + T κ̇_r + M_s κ̇_s + M_t κ̇_t).
    const Vec3 force = n * e1 + qs * e2 + qt * e3;
    const Vec3 turn = tq * e1 + ms * e2 + mt * e3;
    const Vec3 shear_turn = 0.5 * l * (qt * e2 - qs * e3);
    double* fk = f + 6 * k;
    double* mk = moments ? moments + 6 * k : nullptr;
    for (int c = 0; c < 3; ++c) {
      fk[c] = -force(c);
      fk[3 + c] = force(c);
      if (mk) {
        mk[c] = -turn(c) + shear_turn(c);
        mk[3 + c] = turn(c) + shear_turn(c);
      }
    }
    limit.take(step(k, l), ids_[k]);
  }
  return limit;
}

void Beam161Set::results(Eigen::MatrixXd& out) const {
  out.resize(static_cast<Eigen::Index>(size()), static_cast<Eigen::Index>(kResults.size()));
  for (std::size_t k = 0; k < size(); ++k) {
    const auto row = static_cast<Eigen::Index>(k);
    const Section& sec = sections_[section_[k]];
    double r[6] = {}, seqv = 0.0, epeq = 0.0;
    for (int p = 0; p < sec.n; ++p) {
      const std::size_t at = kMaxPoints * k + static_cast<std::size_t>(p);
      const double* s = &stress_[3 * at];
      const SectionPoint& pt = sec.points[p];
      r[0] += pt.w * s[0];
      r[1] += pt.w * s[1];
      r[2] += pt.w * s[2];
      r[3] += pt.w * (pt.s * s[2] - pt.t * s[1]);
      r[4] += pt.w * pt.t * s[0];
      r[5] -= pt.w * pt.s * s[0];
      seqv = std::max(seqv, std::sqrt(s[0] * s[0] + 3.0 * (s[1] * s[1] + s[2] * s[2])));
      epeq = std::max(epeq, alpha_[at]);
    }
    for (int c = 0; c < 6; ++c) out(row, c) = r[c];
    out(row, 6) = seqv;
    out(row, 7) = epeq;
  }
}

const ElementRegistration kBeam161{
    {.name = "BEAM161",
     .number = 161,
     .family = kFamily,
     .n_nodes = 2,
     .n_optional_nodes = 1,
     .real_constants = RealConstantUse::Required,
     .needs_material = true,
     .vtk_cell = VtkCell::Line,
     .role = ShapeRole::Line,
     .result_names = kResults,
     .result_sequences = {{"SMISC", "1", "FORC"}, {"S", "EQV", "SEQV"}, {"NL", "EPEQ", "EPEQ"}},
     .plasticity = true,
     .create = [](const ElementBuildContext&, const ElementRecord& r) -> std::unique_ptr<Element> {
       refuse_in_implicit_analysis(r, "BEAM161", "; use BEAM188 in an implicit one");
     },
     .explicit_set = [](const ExplicitBuildContext& ctx,
                        const std::vector<const ElementRecord*>& records)
         -> std::unique_ptr<ExplicitElementSet> {
       return std::make_unique<Beam161Set>(ctx, records);
     }}};

}  // namespace beam161
}  // namespace

}  // namespace impactfe
