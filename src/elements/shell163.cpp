// SHELL163: the explicit 4-node shell (MAPDL Element Reference release 18.2; LS-DYNA shell
// formulation 2, Belytschko–Tsay), docs/explicit_dynamics.md. Six DOFs per node (translations and
// rotations); a 3-node triangle is the degenerate quadrilateral K = L. One in-plane point in a
// co-rotational frame (Belytschko, Lin & Tsay, CMAME 42 (1984); LS-DYNA Theory Manual, "Belytschko
// -Tsay"): e3 normal to the diagonals r31 × r42, e1 along the side IJ projected on the plane,
// e2 = e3 × e1. Mindlin kinematics of the fibre at z (local axes):
//   d_xx = ∂v_x/∂x + z ∂ω_y/∂x,  d_yy = ∂v_y/∂y − z ∂ω_x/∂y,
//   2d_xy = ∂v_x/∂y + ∂v_y/∂x + z (∂ω_y/∂y − ∂ω_x/∂x),
//   2d_xz = ∂v_z/∂x + ω_y,  2d_yz = ∂v_z/∂y − ω_x,
// with the one-point gradients B1, B2 of the bilinear quadrilateral at its centre and ω the mean
// of the nodal angular velocities. Stresses at NIP Gauss points through the thickness, plane
// stress (σ_zz = 0) in the local frame, transverse shear scaled by SHRF; the nodal forces and
// moments are the derivatives of the internal power A ∫ σ:d dz (so the energy balance holds).
// Hourglass control of the five BT hourglass modes with the shape vector γ orthogonal to linear
// fields, viscous or (EDMP,HGLS types 4, 5) stiffness form; the transverse one through the
// variation of the transverse shear across the element, so that a plate's twist is not resisted.
// Runs only in an explicit analysis: its implicit factory refuses.
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

const std::string kShell163Family = "Shell163";
// Local-frame stresses at the top and bottom integration points, the mean transverse shears,
// the resultants per unit length (N membrane, M bending), the largest SEQV and EPEQ over the
// points.
const std::vector<std::string> kResults = {"SXTOP", "SYTOP", "SXYTOP", "SXBOT", "SYBOT", "SXYBOT",
                                           "SYZ",   "SXZ",   "NX",     "NY",    "NXY",   "MX",
                                           "MY",    "MXY",   "SEQV",   "EPEQ"};
constexpr int kMaxPoints = 10;  // LS-DYNA's Gauss rule through the thickness: 1 to 10 points

/// Gauss–Legendre points and weights on [−1, 1] (Newton on P_n from the Chebyshev guesses).
void gauss_legendre(int n, double* points, double* weights) {
  for (int i = 0; i < n; ++i) {
    double x = std::cos(M_PI * (i + 0.75) / (n + 0.5));
    double derivative = 1.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      derivative = n * (x * p1 - p0) / (x * x - 1.0);
      const double step = p1 / derivative;
      x -= step;
      if (std::abs(step) < 1e-15) break;
    }
    points[n - 1 - i] = x;
    weights[n - 1 - i] = 2.0 / ((1.0 - x * x) * derivative * derivative);
  }
}

/// The kinematics of one element at x_{n+1} from v_{n+1/2}, ω_{n+1/2}, in the local frame.
struct ShellKinematics {
  Vec3 e1, e2, e3;
  double xl[4], yl[4];  // local in-plane coordinates (about the centre)
  double b1[4], b2[4];  // ∂N/∂x, ∂N/∂y at the centre
  double area = 0.0;
  double v[4][3], w[4][3];  // local velocities and angular velocities
};

/// Frame, local coordinates and one-point gradients; false when the element has no area.
bool frame(const ExplicitNodalView& s, const int* n, ShellKinematics& k) {
  Vec3 x[4];
  for (int a = 0; a < 4; ++a) x[a] = Vec3(s.x[n[a]], s.y[n[a]], s.z[n[a]]);
  k.e3 = (x[2] - x[0]).cross(x[3] - x[1]);
  const double norm = k.e3.norm();
  if (!(norm > 0.0)) return false;
  k.e3 /= norm;
  const Vec3 side = x[1] - x[0];
  k.e1 = side - side.dot(k.e3) * k.e3;
  const double n1 = k.e1.norm();
  if (!(n1 > 0.0)) return false;
  k.e1 /= n1;
  k.e2 = k.e3.cross(k.e1);
  const Vec3 centre = 0.25 * (x[0] + x[1] + x[2] + x[3]);
  for (int a = 0; a < 4; ++a) {
    k.xl[a] = k.e1.dot(x[a] - centre);
    k.yl[a] = k.e2.dot(x[a] - centre);
  }
  // 2A = x31 y42 + x24 y31 (the diagonals' cross product).
  const double twice =
      (k.xl[2] - k.xl[0]) * (k.yl[3] - k.yl[1]) + (k.xl[1] - k.xl[3]) * (k.yl[2] - k.yl[0]);
  k.area = 0.5 * twice;
  if (!(k.area > 0.0)) return false;
  const double inv = 1.0 / twice;
  k.b1[0] = (k.yl[1] - k.yl[3]) * inv;
  k.b1[1] = (k.yl[2] - k.yl[0]) * inv;
  k.b1[2] = (k.yl[3] - k.yl[1]) * inv;
  k.b1[3] = (k.yl[0] - k.yl[2]) * inv;
  k.b2[0] = (k.xl[3] - k.xl[1]) * inv;
  k.b2[1] = (k.xl[0] - k.xl[2]) * inv;
  k.b2[2] = (k.xl[1] - k.xl[3]) * inv;
  k.b2[3] = (k.xl[2] - k.xl[0]) * inv;
  return true;
}

void local_velocities(const ExplicitNodalView& s, const int* n, ShellKinematics& k) {
  for (int a = 0; a < 4; ++a) {
    const Vec3 v(s.vx[n[a]], s.vy[n[a]], s.vz[n[a]]);
    const Vec3 w = s.wx ? Vec3(s.wx[n[a]], s.wy[n[a]], s.wz[n[a]]) : Vec3::Zero();
    k.v[a][0] = k.e1.dot(v);
    k.v[a][1] = k.e2.dot(v);
    k.v[a][2] = k.e3.dot(v);
    k.w[a][0] = k.e1.dot(w);
    k.w[a][1] = k.e2.dot(w);
    k.w[a][2] = k.e3.dot(w);
  }
}

/// LS-DYNA's characteristic length of a shell: A / the longest side for a quadrilateral, 2A / the
/// longest side for a triangle (LS-DYNA Theory Manual, "Time step control", shells with
/// ISDO = 0: L = (1 + β) A / max(L1, L2, L3, (1 − β) L4), β = 1 for triangles).
double characteristic_length(const ShellKinematics& k, bool triangle) {
  double longest = 0.0;
  for (int a = 0; a < (triangle ? 3 : 4); ++a) {
    const int b = (a + 1) % 4 == 3 && triangle ? 0 : (a + 1) % 4;
    longest = std::max(longest, std::hypot(k.xl[b] - k.xl[a], k.yl[b] - k.yl[a]));
  }
  return (triangle ? 2.0 : 1.0) * k.area / longest;
}

struct ShellMaterial {
  RateMaterial rate;
  double young = 0.0, poisson = 0.0;
  /// Plane-stress wave speed √(E/(ρ(1 − ν²))) of the unscaled density, for the step.
  double plate_modulus() const { return young / (1.0 - poisson * poisson); }
};

class Shell163Set final : public ExplicitElementSet {
 public:
  Shell163Set(const ExplicitBuildContext& ctx, const std::vector<const ElementRecord*>& records);

  const std::string& family() const override { return kShell163Family; }
  std::size_t size() const override { return ids_.size(); }
  int element_id(std::size_t k) const override { return ids_[k]; }
  int nodes_per_element() const override { return 4; }
  const int* nodes(std::size_t k) const override { return &nodes_[4 * k]; }
  bool has_rotations() const override { return true; }
  void add_element_mass(std::size_t k, std::vector<double>& mass) const override {
    for (int a = 0; a < 4; ++a) mass[nodes_[4 * k + a]] += density_[k] * share_[4 * k + a];
  }
  /// LS-DYNA scales the shells' rotary inertia so that the rotations do not control the step.
  /// Here I = m (A + t²)/6 per node with m its translational share: the stiffest rotational
  /// mode of the one-point element, all nodes turning together against the transverse shear,
  /// then has ω² = 6κG/(ρA) · A/(A + t²) < 6κG/(ρA), below the translational bound 4c²/L² of
  /// the step (c² = 2G/(ρ(1 − ν))).
  void add_rotary_inertia(std::vector<double>& inertia) const override {
    for (std::size_t k = 0; k < size(); ++k) {
      const double factor = (area0_[k] + thickness_[k] * thickness_[k]) / 6.0;
      for (int a = 0; a < 4; ++a)
        inertia[nodes_[4 * k + a]] += density_[k] * share_[4 * k + a] * factor;
    }
  }
  /// ∫ρ x xᵀ over the mid-surface (bilinear map, 3×3 Gauss) times the thickness, plus the
  /// thickness's own ρ t³/12 n nᵀ per area.
  Eigen::Matrix3d second_mass_moment(const ExplicitNodalView& state, std::size_t k) const override {
    const double g[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
    const double w[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
    constexpr double kXi[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    Eigen::Vector3d p[4];
    for (int a = 0; a < 4; ++a) {
      const int n = nodes_[4 * k + a];
      p[a] = {state.x[n], state.y[n], state.z[n]};
    }
    const double t = thickness_[k];
    Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        Eigen::Vector3d x = Eigen::Vector3d::Zero(), dxi = x, deta = x;
        for (int a = 0; a < 4; ++a) {
          const double fx = 1.0 + g[i] * kXi[a][0], fy = 1.0 + g[j] * kXi[a][1];
          x += 0.25 * fx * fy * p[a];
          dxi += 0.25 * kXi[a][0] * fy * p[a];
          deta += 0.25 * fx * kXi[a][1] * p[a];
        }
        const Eigen::Vector3d normal = dxi.cross(deta);
        const double da = w[i] * w[j] * normal.norm();
        if (!(da > 0.0)) continue;
        const Eigen::Vector3d unit = normal.normalized();
        m += da * (t * x * x.transpose() + t * t * t / 12.0 * unit * unit.transpose());
      }
    return density_[k] * m;
  }
  double element_step(const ExplicitNodalView& state, std::size_t k) const override {
    ShellKinematics kin;
    if (!frame(state, &nodes_[4 * k], kin)) return 0.0;
    return characteristic_length(kin, triangle_[k]) / wave_speed(k);
  }
  double scale_mass(std::size_t k, double factor, std::vector<double>& mass) override {
    const double added = (factor - 1.0) * density_[k];
    double total = 0.0;
    for (int a = 0; a < 4; ++a) {
      mass[nodes_[4 * k + a]] += added * share_[4 * k + a];
      total += added * share_[4 * k + a];
    }
    density_[k] *= factor;
    return total;
  }
  void results(Eigen::MatrixXd& out) const override;
  /// Each shell as a two-sided segment of its thickness (explicit_contact.h: the surfaces lie
  /// ±t/2 off the mid-surface, k = f·K·A/(largest diagonal)).
  void segments(std::vector<ExplicitSegment>& out) const override {
    for (std::size_t k = 0; k < size(); ++k) {
      ExplicitSegment s;
      for (int a = 0; a < 4; ++a) s.nodes[a] = nodes_[4 * k + a];
      s.element = ids_[k];
      s.bulk_modulus = materials_[static_cast<std::size_t>(material_[k])].rate.bulk;
      s.thickness = thickness_[k];
      out.push_back(s);
    }
  }

 private:
  ExplicitStepLimit chunk_forces(const ExplicitNodalView& state, double dt, double* element_forces,
                                 double* element_moments, std::size_t begin, std::size_t end,
                                 ExplicitSetEnergies& energies) override;
  double wave_speed(std::size_t k) const {
    return std::sqrt(materials_[static_cast<std::size_t>(material_[k])].plate_modulus() /
                     density_[k]);
  }
  /// Updates the stress of point `p` of element k over dt from the local strain rate d (xx, yy,
  /// xy, yz, xz; tensor components); returns the plastic work per unit volume.
  double update_point(std::size_t k, int p, const double* d, double dt);

  std::vector<int> ids_, nodes_, material_, points_;
  std::vector<std::uint8_t> triangle_;
  std::vector<double> share_;  // t A0 / (corners) per slot: the volume lumped to each slot
  std::vector<double> area0_, thickness_, shear_factor_, density_;
  std::vector<ShellMaterial> materials_;
  // Per element and point (kMaxPoints each): σ (xx, yy, zz = 0, xy, yz, xz, local axes), back
  // stress, equivalent plastic strain.
  std::vector<double> stress_, back_, alpha_;
  /// EDMP,HGLS (or EDHGLS) of each material, as materials_.
  std::vector<ExplicitHourglass> hourglass_;
  /// The stiffness form's stored generalized hourglass forces, 6 per element in the local frame
  /// (membrane x, y; transverse shear variations xz, yz; rotations x, y); empty when no
  /// material uses it.
  std::vector<double> hourglass_force_;
  double gauss_z_[kMaxPoints + 1][kMaxPoints] = {}, gauss_w_[kMaxPoints + 1][kMaxPoints] = {};
};

Shell163Set::Shell163Set(const ExplicitBuildContext& ctx,
                         const std::vector<const ElementRecord*>& records) {
  for (int n = 1; n <= kMaxPoints; ++n) gauss_legendre(n, gauss_z_[n], gauss_w_[n]);
  std::map<int, int> material_index;
  for (const ElementRecord* r : records) {
    if (r->nodes.size() != 4)
      throw InputError(r->where, fmt::format("element {}: SHELL163 needs the nodes I, J, K, L (K "
                                             "repeated as L for a triangle), got {}",
                                             r->id, r->nodes.size()));
    const ElementType& type = ctx.model.element_type(r->type);
    if (const std::string why = keyopt_refusal(type); !why.empty())
      throw InputError(type.where.known() ? type.where : r->where,
                       fmt::format("element type {}: {}", type.id, why));
    const auto real = ctx.model.real_sets.find(r->real);
    if (real == ctx.model.real_sets.end())
      throw InputError(r->where,
                       fmt::format("element {}: SHELL163 needs real constant set {} (R,{},SHRF,"
                                   "NIP,T1,T2,T3,T4)",
                                   r->id, r->real, r->real));
    if (const std::string why = real_set_refusal(type, real->second); !why.empty())
      throw InputError(r->where, fmt::format("element {}: {}", r->id, why));
    const RealSet& set = real->second;
    // SHRF: 0 or blank is 1 (MAPDL / LS-DYNA default; 5/6 is the usual choice for isotropic
    // material). NIP: 0 or blank is 2.
    const double shrf = set.get(1) == 0.0 ? 1.0 : set.get(1);
    const double nip_value = set.get(2) == 0.0 ? 2.0 : set.get(2);
    const int nip = static_cast<int>(nip_value);
    if (!(shrf > 0.0))
      throw InputError(r->where, fmt::format("element {}: SHELL163 SHRF (R1) must be > 0, got {:g}",
                                             r->id, shrf));
    if (nip != nip_value || nip < 2 || nip > kMaxPoints)
      throw InputError(r->where,
                       fmt::format("element {}: SHELL163 NIP (R2) = {:g}: 2 to {} Gauss points "
                                   "through the thickness are implemented (1, the membrane "
                                   "shell, is not)",
                                   r->id, nip_value, kMaxPoints));
    const bool triangle = r->nodes[2] == r->nodes[3];
    const int corners = triangle ? 3 : 4;
    double t[4];
    for (int a = 0; a < 4; ++a) t[a] = set.get(3 + a) == 0.0 ? set.get(3) : set.get(3 + a);
    double thickness = 0.0;
    for (int a = 0; a < corners; ++a) thickness += t[a] / corners;
    if (!(set.get(3) > 0.0) || std::any_of(t, t + corners, [](double v) { return v <= 0.0; }))
      throw InputError(r->where, fmt::format("element {}: SHELL163 thicknesses T1..T4 (R3..R6) "
                                             "must be > 0 (T1 given, the others default to it)",
                                             r->id));
    auto [it, added] = material_index.emplace(r->mat, static_cast<int>(materials_.size()));
    if (added) {
      const IsotropicElasticity e = read_isotropic_elasticity(ctx.model, r->mat, r->id, r->where);
      if (!(e.density > 0.0))
        throw InputError(r->where, fmt::format("element {}: material {} has no density (DENS): "
                                               "explicit dynamics needs the mass of every element",
                                               r->id, r->mat));
      ShellMaterial m;
      m.young = e.young;
      m.poisson = e.poisson;
      m.rate.shear = e.young / (2.0 * (1.0 + e.poisson));
      m.rate.bulk = e.young / (3.0 * (1.0 - 2.0 * e.poisson));
      m.rate.density = e.density;
      m.rate.plasticity = plasticity_of(ctx.model, *r, e.young, e.poisson, false);
      materials_.push_back(std::move(m));
      hourglass_.push_back(ctx.hourglass_of(r->mat));
    }
    std::array<double, 4> x{}, y{}, z{};
    for (int a = 0; a < 4; ++a) {
      nodes_.push_back(ctx.node_index(r->nodes[static_cast<std::size_t>(a)], *r));
      const Vec3& p = ctx.model.node(r->nodes[static_cast<std::size_t>(a)]).x;
      x[a] = p.x(), y[a] = p.y(), z[a] = p.z();
    }
    const ExplicitNodalView view{x.data(), y.data(), z.data()};
    const int local[4] = {0, 1, 2, 3};
    ShellKinematics kin;
    if (!frame(view, local, kin))
      throw InputError(r->where, fmt::format("element {}: SHELL163 has no area (nodes I, J, K, "
                                             "L in order around the element; K = L for a "
                                             "triangle)",
                                             r->id));
    ids_.push_back(r->id);
    material_.push_back(it->second);
    points_.push_back(nip);
    triangle_.push_back(triangle ? 1 : 0);
    area0_.push_back(kin.area);
    thickness_.push_back(thickness);
    shear_factor_.push_back(shrf);
    density_.push_back(materials_[static_cast<std::size_t>(it->second)].rate.density);
    // Row-sum lumping of ρ t A: a quarter per corner, a third per corner of a triangle (its
    // repeated node L gets nothing more).
    for (int a = 0; a < 4; ++a) share_.push_back(a < corners ? thickness * kin.area / corners : 0);
  }
  stress_.assign(6 * kMaxPoints * ids_.size(), 0.0);
  back_.assign(6 * kMaxPoints * ids_.size(), 0.0);
  alpha_.assign(kMaxPoints * ids_.size(), 0.0);
  if (std::any_of(hourglass_.begin(), hourglass_.end(),
                  [](const ExplicitHourglass& h) { return h.stiffness(); }))
    hourglass_force_.assign(6 * ids_.size(), 0.0);
}

double Shell163Set::update_point(std::size_t k, int p, const double* d, double dt) {
  const std::size_t at = kMaxPoints * k + static_cast<std::size_t>(p);
  double* s = &stress_[6 * at];
  const ShellMaterial& m = materials_[static_cast<std::size_t>(material_[k])];
  const double kappa = shear_factor_[k];
  const double plate = m.plate_modulus() * dt, g2 = 2.0 * m.rate.shear * dt;
  if (!m.rate.plasticity) {
    // Plane-stress elastic increment (σ_zz = 0), transverse shear scaled by SHRF.
    s[0] += plate * (d[0] + m.poisson * d[1]);
    s[1] += plate * (d[1] + m.poisson * d[0]);
    s[3] += g2 * d[2];
    s[4] += kappa * g2 * d[3];
    s[5] += kappa * g2 * d[4];
    return 0.0;
  }
  // Plasticity: the 3-D radial return (rate_plasticity.h) with the thickness strain rate d_zz
  // found so that σ_zz = 0 (LS-DYNA's iterative plane-stress return, by secant / regula falsi
  // on d_zz from the elastic value −ν/(1 − ν)(d_xx + d_yy)).
  double* beta = &back_[6 * at];
  const double s0[6] = {s[0], s[1], 0.0, s[3], s[4], s[5]};
  const double b0[6] = {beta[0], beta[1], beta[2], beta[3], beta[4], beta[5]};
  const double alpha0 = alpha_[at];
  double trial[6], b[6], alpha = alpha0, work = 0.0;
  const auto szz = [&](double dzz) {
    std::copy(s0, s0 + 6, trial);
    std::copy(b0, b0 + 6, b);
    alpha = alpha0;
    const double rate[6] = {d[0], d[1], dzz, d[2], kappa * d[3], kappa * d[4]};
    elastic_increment(trial, rate, dt, m.rate);
    work = radial_return(trial, b, alpha, m.rate);
    return trial[2];
  };
  const double nu = m.poisson;
  double z0 = -nu / (1.0 - nu) * (d[0] + d[1]);
  double f0 = szz(z0);
  if (work != 0.0) {
    const double scale = std::abs(s0[0]) + std::abs(s0[1]) + std::abs(trial[0]) +
                         std::abs(trial[1]) + std::abs(trial[3]) + 1e-300;
    double z1 = -(d[0] + d[1]);  // the incompressible (fully plastic) guess
    if (z1 == z0) z1 = z0 + 1e-6 * (std::abs(d[0]) + std::abs(d[1]) + std::abs(d[2]) + 1e-30);
    double f1 = szz(z1);
    for (int it = 0; it < 60 && std::abs(f1) > 1e-12 * scale; ++it) {
      if (f1 == f0) break;
      const double z2 = z1 - f1 * (z1 - z0) / (f1 - f0);
      const double f2 = szz(z2);
      // Keep a bracket once there is one (regula falsi, Illinois), otherwise secant.
      if ((f2 > 0) != (f1 > 0)) {
        z0 = z1, f0 = f1;
      } else if ((f0 > 0) != (f1 > 0)) {
        f0 *= 0.5;
      } else {
        z0 = z1, f0 = f1;
      }
      z1 = z2, f1 = f2;
    }
    szz(z1);
  }
  s[0] = trial[0], s[1] = trial[1], s[2] = 0.0, s[3] = trial[3], s[4] = trial[4];
  s[5] = trial[5];
  std::copy(b, b + 6, beta);
  alpha_[at] = alpha;
  return work;
}

ExplicitStepLimit Shell163Set::chunk_forces(const ExplicitNodalView& state, double dt,
                                            double* element_forces, double* element_moments,
                                            std::size_t begin, std::size_t end,
                                            ExplicitSetEnergies& energies) {
  ExplicitStepLimit limit;
  ShellKinematics kin;
  constexpr double kH[4] = {1.0, -1.0, 1.0, -1.0};  // the hourglass base vector
  for (std::size_t k = begin; k < end; ++k) {
    const int* n = &nodes_[4 * k];
    if (!frame(state, n, kin))
      throw ElementSolutionError(ids_[k], fmt::format("element {} (SHELL163) lost its area: a "
                                                      "time step too large or an hourglass mode "
                                                      "out of control",
                                                      ids_[k]));
    local_velocities(state, n, kin);
    // The mean nodal angular velocity: of the four corners, or of the three distinct ones of a
    // triangle (its repeated node L would otherwise count twice).
    static constexpr double kQuad[4] = {0.25, 0.25, 0.25, 0.25},
                            kTriangle[4] = {1.0 / 3, 1.0 / 3, 1.0 / 3, 0.0};
    const double* mean = triangle_[k] ? kTriangle : kQuad;
    // Membrane, curvature and transverse shear rates at the centre (tensor shear components).
    double g[2][3] = {}, gw[2][2] = {}, centre[2] = {};  // ∂v_i/∂x_α, ∂ω_i/∂x_α, mean ω
    for (int a = 0; a < 4; ++a) {
      for (int i = 0; i < 3; ++i) {
        g[0][i] += kin.b1[a] * kin.v[a][i];
        g[1][i] += kin.b2[a] * kin.v[a][i];
      }
      for (int i = 0; i < 2; ++i) {
        gw[0][i] += kin.b1[a] * kin.w[a][i];
        gw[1][i] += kin.b2[a] * kin.w[a][i];
        centre[i] += mean[a] * kin.w[a][i];
      }
    }
    const double membrane[3] = {g[0][0], g[1][1], 0.5 * (g[1][0] + g[0][1])};
    const double curvature[3] = {gw[0][1], -gw[1][0], 0.5 * (gw[1][1] - gw[0][0])};
    const double shear[2] = {0.5 * (g[1][2] - centre[0]), 0.5 * (g[0][2] + centre[1])};  // yz, xz
    const double t = thickness_[k], half = 0.5 * t;
    // Resultants: N = ∫σ dz (xx, yy, xy, yz, xz), M = ∫zσ dz (xx, yy, xy).
    double resultant[5] = {}, moment[3] = {};
    double power = 0.0, plastic = 0.0;
    const int nip = points_[k];
    for (int p = 0; p < nip; ++p) {
      const double z = gauss_z_[nip][p] * half, weight = gauss_w_[nip][p] * half;
      const double d[5] = {membrane[0] + z * curvature[0], membrane[1] + z * curvature[1],
                           membrane[2] + z * curvature[2], shear[0], shear[1]};
      const double* s = &stress_[6 * (kMaxPoints * k + static_cast<std::size_t>(p))];
      const auto stress_power = [&] {
        return s[0] * d[0] + s[1] * d[1] + 2.0 * (s[3] * d[2] + s[4] * d[3] + s[5] * d[4]);
      };
      const double before = stress_power();
      plastic += weight * update_point(k, p, d, dt);
      power += weight * 0.5 * (before + stress_power());
      resultant[0] += weight * s[0];
      resultant[1] += weight * s[1];
      resultant[2] += weight * s[3];
      resultant[3] += weight * s[4];
      resultant[4] += weight * s[5];
      moment[0] += weight * z * s[0];
      moment[1] += weight * z * s[1];
      moment[2] += weight * z * s[3];
    }
    const double area = kin.area;
    energies.internal += internal_work(k, dt * area * power);
    energies.plastic_work += area * plastic;
    // Hourglass control of the BT modes: γ = h − (h·x) B1 − (h·y) B2 is orthogonal to every
    // linear field, so it never resists a uniform strain rate or a rigid motion.
    double gamma[4], hx = 0.0, hy = 0.0;
    for (int a = 0; a < 4; ++a) hx += kH[a] * kin.xl[a], hy += kH[a] * kin.yl[a];
    for (int a = 0; a < 4; ++a) gamma[a] = kH[a] - hx * kin.b1[a] - hy * kin.b2[a];
    double q[5] = {};  // hourglass rates of v_x, v_y, v_z, ω_x, ω_y
    for (int a = 0; a < 4; ++a) {
      for (int i = 0; i < 3; ++i) q[i] += gamma[a] * kin.v[a][i];
      for (int i = 0; i < 2; ++i) q[3 + i] += gamma[a] * kin.w[a][i];
    }
    // The transverse mode is not γ·v_z alone: on a rectangle v_z = xy is γ's own pattern, and
    // with ω_x = x, ω_y = −y it is a plate's uniform twist, carried by the rotations' gradient
    // at the centre and free of transverse shear. Damping γ·v_z damped every twisting motion of
    // a plate (on a 10 x 10 plate slapping a floor the hourglass took 63 % of the energy).
    // What the one point misses is the variation of the transverse shear across the element:
    // ∂γ_xz/∂y = w,xy + ∂ω_y/∂y and ∂γ_yz/∂x = w,xy − ∂ω_x/∂x, with w,xy = γ·v_z / A (exact
    // on a rectangle), zero for the twist and γ·v_z / A for the hourglass with ω = 0. The
    // control acts on them with c_w A²/2, which is c_w (γ·v_z)² on that hourglass.
    double rot_y = 0.0, rot_x = 0.0;  // ∂ω_y/∂y, ∂ω_x/∂x at the centre
    for (int a = 0; a < 4; ++a) rot_y += kin.b2[a] * kin.w[a][1], rot_x += kin.b1[a] * kin.w[a][0];
    // The generalized hourglass rates: membrane x, y; shear variations xz, yz; rotations x, y.
    const double rate[6] = {q[0], q[1], q[2] / area + rot_y, q[2] / area - rot_x, q[3], q[4]};
    const ExplicitHourglass& control = hourglass_[static_cast<std::size_t>(material_[k])];
    double coefficient[3];  // membrane, shear variation, rotation
    if (control.stiffness()) {
      // Stiffness form (Belytschko, Lin & Tsay 1984; LS-DYNA Theory Manual, "Hourglass
      // control" of the Belytschko–Tsay shell): rates of the hourglass forces r_m E t A/8 B·B,
      // r_w κ G t³ A/12 B·B (times A²/2 on the shear variations, as above), r_θ E t³ A/192 B·B.
      double bb = 0.0;
      for (int a = 0; a < 4; ++a) bb += kin.b1[a] * kin.b1[a] + kin.b2[a] * kin.b2[a];
      const ShellMaterial& sm = materials_[static_cast<std::size_t>(material_[k])];
      const double shear_modulus = sm.young / (2.0 * (1.0 + sm.poisson));
      coefficient[0] = control.membrane * sm.young * t * area / 8.0 * bb;
      coefficient[1] = 0.5 * area * area * control.warping * shear_factor_[k] * shear_modulus * t *
                       t * t * area / 12.0 * bb;
      coefficient[2] = control.bending * sm.young * t * t * t * area / 192.0 * bb;
    } else {
      // Viscous form: the membrane coefficient scales as the solid's QM ρ c V^{2/3}/4 with
      // V^{2/3} → t √A; the transverse and rotational ones by t/√A less (a plate's bending
      // wave of wavelength √A is that much slower than the membrane wave: the same fraction of
      // critical damping), the rotational one by A/12 more (the rotary inertia's A/6 per node).
      const double scale = 0.25 * density_[k] * wave_speed(k) * t;
      const double cw = scale * control.warping * t;
      coefficient[0] = scale * control.membrane * std::sqrt(area);
      coefficient[1] = 0.5 * cw * area * area;
      coefficient[2] = scale * control.bending * t * area / 12.0;
    }
    double h[6];  // the generalized hourglass forces
    double hourglass_power = 0.0;
    for (int i = 0; i < 6; ++i) {
      const double ci = coefficient[i / 2];
      if (control.stiffness()) {
        double& stored = hourglass_force_[6 * k + static_cast<std::size_t>(i)];
        const double before = stored;
        stored += ci * dt * rate[i];
        h[i] = stored;
        hourglass_power += 0.5 * (before + stored) * rate[i];
      } else {
        h[i] = ci * rate[i];
        hourglass_power += h[i] * rate[i];
      }
    }
    energies.hourglass += hourglass_work(k, dt * hourglass_power);
    // Nodal forces and moments: the derivatives of the power A(N:d + M:κ + Q·γ) by the nodal
    // velocities (local axes), then to global axes.
    double* f = element_forces + 12 * k;
    double* mo = element_moments ? element_moments + 12 * k : nullptr;
    for (int a = 0; a < 4; ++a) {
      const double b1 = kin.b1[a], b2 = kin.b2[a];
      const double fx = area * (b1 * resultant[0] + b2 * resultant[2]) + h[0] * gamma[a];
      const double fy = area * (b2 * resultant[1] + b1 * resultant[2]) + h[1] * gamma[a];
      const double fz =
          area * (b1 * resultant[4] + b2 * resultant[3]) + (h[2] + h[3]) * gamma[a] / area;
      const double mx = area * (-b2 * moment[1] - b1 * moment[2] - mean[a] * resultant[3]) +
                        h[4] * gamma[a] - h[3] * b1;
      const double my = area * (b1 * moment[0] + b2 * moment[2] + mean[a] * resultant[4]) +
                        h[5] * gamma[a] + h[2] * b2;
      const Vec3 force = fx * kin.e1 + fy * kin.e2 + fz * kin.e3;
      const Vec3 turn = mx * kin.e1 + my * kin.e2;
      for (int i = 0; i < 3; ++i) {
        f[3 * a + i] = force(i);
        if (mo) mo[3 * a + i] = turn(i);
      }
    }
    limit.take(characteristic_length(kin, triangle_[k]) / wave_speed(k), ids_[k]);
  }
  return limit;
}

void Shell163Set::results(Eigen::MatrixXd& out) const {
  out.resize(static_cast<Eigen::Index>(size()), static_cast<Eigen::Index>(kResults.size()));
  for (std::size_t k = 0; k < size(); ++k) {
    const auto row = static_cast<Eigen::Index>(k);
    const int nip = points_[k];
    const double half = 0.5 * thickness_[k];
    const double* top = &stress_[6 * (kMaxPoints * k + static_cast<std::size_t>(nip - 1))];
    const double* bottom = &stress_[6 * kMaxPoints * k];
    out(row, 0) = top[0], out(row, 1) = top[1], out(row, 2) = top[3];
    out(row, 3) = bottom[0], out(row, 4) = bottom[1], out(row, 5) = bottom[3];
    double n[5] = {}, m[3] = {}, seqv = 0.0, epeq = 0.0;
    for (int p = 0; p < nip; ++p) {
      const std::size_t at = kMaxPoints * k + static_cast<std::size_t>(p);
      const double* s = &stress_[6 * at];
      const double z = gauss_z_[nip][p] * half, w = gauss_w_[nip][p] * half;
      n[0] += w * s[0], n[1] += w * s[1], n[2] += w * s[3], n[3] += w * s[4], n[4] += w * s[5];
      m[0] += w * z * s[0], m[1] += w * z * s[1], m[2] += w * z * s[3];
      Vector6d v;
      v << s[0], s[1], s[2], s[3], s[4], s[5];
      seqv = std::max(seqv, von_mises(v));
      epeq = std::max(epeq, alpha_[at]);
    }
    out(row, 6) = n[3] / thickness_[k];
    out(row, 7) = n[4] / thickness_[k];
    for (int i = 0; i < 3; ++i) out(row, 8 + i) = n[i], out(row, 11 + i) = m[i];
    out(row, 14) = seqv;
    out(row, 15) = epeq;
  }
}

const ElementRegistration kShell163{
    {.name = "SHELL163",
     .number = 163,
     .family = kShell163Family,
     .n_nodes = 4,
     .min_nodes = 3,
     .real_constants = RealConstantUse::Required,
     .needs_material = true,
     .vtk_cell = VtkCell::Quad,
     .role = ShapeRole::Shell,
     .result_names = kResults,
     .result_sequences = {{"S", "EQV", "SEQV"}, {"NL", "EPEQ", "EPEQ"}},
     .plasticity = true,
     .create = [](const ElementBuildContext&, const ElementRecord& r) -> std::unique_ptr<Element> {
       refuse_in_implicit_analysis(r, "SHELL163", "; use SHELL181 in an implicit one");
     },
     .explicit_set = [](const ExplicitBuildContext& ctx,
                        const std::vector<const ElementRecord*>& records)
         -> std::unique_ptr<ExplicitElementSet> {
       return std::make_unique<Shell163Set>(ctx, records);
     }}};

}  // namespace

}  // namespace impactfe
