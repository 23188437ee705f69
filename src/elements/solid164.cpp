// SOLID164: the 8-node explicit brick (MAPDL Element Reference release 18.2; LS-DYNA solid
// formulation 1), docs/explicit_dynamics.md. One-point (uniform strain) integration with the
// volume derivatives of Flanagan & Belytschko (1981), hexahedron_volume.h; Flanagan–Belytschko
// hourglass control, viscous or (EDMP,HGLS types 4, 5) stiffness form, with the hourglass shape
// vectors γ orthogonal to every linear velocity field (so a uniform strain rate is never
// resisted: the patch test is exact); the Jaumann-rate hypoelastic stress update with radial
// return for TB plasticity (materials/rate_plasticity.h); linear and quadratic bulk viscosity
// (EDBVIS, EDMP,HGLS). Runs only in an explicit analysis: its implicit factory refuses.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "elements/element_fields.h"
#include "elements/element_registry.h"
#include "elements/hexahedron_volume.h"
#include "materials/isotropic_elasticity.h"
#include "materials/rate_plasticity.h"

namespace impactfe {

namespace {

const std::string kSolid164Family = "Solid164";
const std::vector<std::string> kResults = {"SX", "SY", "SZ", "SXY", "SYZ", "SXZ", "SEQV", "EPEQ"};

/// The hourglass base vectors ηζ, ξζ, ξη, ξηζ at the corners I..P (FB eq. (50)).
constexpr double kHourglassBase[4][8] = {{1, 1, -1, -1, -1, -1, 1, 1},
                                         {1, -1, -1, 1, -1, 1, 1, -1},
                                         {1, -1, 1, -1, 1, -1, 1, -1},
                                         {-1, 1, -1, 1, 1, -1, 1, -1}};

/// The kinematics of one element at x_{n+1} from v_{n+1/2}.
struct BrickKinematics {
  double x[8], y[8], z[8], vx[8], vy[8], vz[8];
  double bx[8], by[8], bz[8];  // ∂V/∂x
  double volume = 0.0;
  double d[6];           // strain rate D (tensor components)
  double w01, w12, w02;  // spin W_xy, W_yz, W_xz
};

void gather(const ExplicitNodalView& s, const int* n, BrickKinematics& k) {
  for (int a = 0; a < 8; ++a) {
    k.x[a] = s.x[n[a]];
    k.y[a] = s.y[n[a]];
    k.z[a] = s.z[n[a]];
    k.vx[a] = s.vx[n[a]];
    k.vy[a] = s.vy[n[a]];
    k.vz[a] = s.vz[n[a]];
  }
}

/// Velocity gradient L_ij = Σ_I v_iI b_jI / V, split into D and W.
void rates(BrickKinematics& k) {
  double l[3][3] = {};
  for (int a = 0; a < 8; ++a) {
    const double v[3] = {k.vx[a], k.vy[a], k.vz[a]};
    for (int i = 0; i < 3; ++i) {
      l[i][0] += v[i] * k.bx[a];
      l[i][1] += v[i] * k.by[a];
      l[i][2] += v[i] * k.bz[a];
    }
  }
  const double inv = 1.0 / k.volume;
  k.d[0] = l[0][0] * inv;
  k.d[1] = l[1][1] * inv;
  k.d[2] = l[2][2] * inv;
  k.d[3] = 0.5 * (l[0][1] + l[1][0]) * inv;
  k.d[4] = 0.5 * (l[1][2] + l[2][1]) * inv;
  k.d[5] = 0.5 * (l[0][2] + l[2][0]) * inv;
  k.w01 = 0.5 * (l[0][1] - l[1][0]) * inv;
  k.w12 = 0.5 * (l[1][2] - l[2][1]) * inv;
  k.w02 = 0.5 * (l[0][2] - l[2][0]) * inv;
}

/// The characteristic length of the stable step: LS-DYNA's V / A_max, bounded for distorted
/// bricks by √1.5 V / |b| (|b|² = Σ_I b_I·b_I, the uniform-strain operator's norm, which grows
/// as a corner flattens; √1.5 makes it h for a cube of side h, so regular bricks are not
/// penalised). V / A_max alone let a mapped mesh with 175° corners go unstable at TSSFAC 0.9.
double characteristic_length(const BrickKinematics& k) {
  double norm2 = 0.0;
  for (int a = 0; a < 8; ++a) norm2 += k.bx[a] * k.bx[a] + k.by[a] * k.by[a] + k.bz[a] * k.bz[a];
  const double by_faces = k.volume / hexahedron::largest_face_area(k.x, k.y, k.z);
  return std::min(by_faces, std::sqrt(1.5 / norm2) * k.volume);
}

inline double contract(const double* s, const double* d) {
  return s[0] * d[0] + s[1] * d[1] + s[2] * d[2] + 2.0 * (s[3] * d[3] + s[4] * d[4] + s[5] * d[5]);
}

/// The hourglass shape vectors γ_α = Γ_α − (Γ_α·x_i) b_i / V of the four modes (FB eq. (50)
/// ff.: orthogonal to every linear velocity field) and the hourglass velocities q_α = Σ_I v_I γ_αI.
struct HourglassModes {
  double gamma[4][8];
  double q[4][3];
};

void hourglass_modes(const BrickKinematics& k, HourglassModes& m) {
  const double inv = 1.0 / k.volume;
  for (int mode = 0; mode < 4; ++mode) {
    const double* base = kHourglassBase[mode];
    double hx = 0.0, hy = 0.0, hz = 0.0;  // Γ·x per direction
    for (int a = 0; a < 8; ++a) {
      hx += base[a] * k.x[a];
      hy += base[a] * k.y[a];
      hz += base[a] * k.z[a];
    }
    double* gamma = m.gamma[mode];
    double* q = m.q[mode];
    q[0] = q[1] = q[2] = 0.0;
    for (int a = 0; a < 8; ++a) {
      gamma[a] = base[a] - inv * (hx * k.bx[a] + hy * k.by[a] + hz * k.bz[a]);
      q[0] += k.vx[a] * gamma[a];
      q[1] += k.vy[a] * gamma[a];
      q[2] += k.vz[a] * gamma[a];
    }
  }
}

/// Adds the hourglass forces Σ_α Q_α γ_αI (Q_α a vector per mode) to f.
void add_hourglass_forces(const HourglassModes& m, const double (*force)[3], double* f) {
  for (int mode = 0; mode < 4; ++mode)
    for (int a = 0; a < 8; ++a)
      for (int i = 0; i < 3; ++i) f[3 * a + i] += force[mode][i] * m.gamma[mode][a];
}

/// Viscous form: Q_α = c q_α; returns the power c Σ|q_α|² (≥ 0: dissipated).
double viscous_hourglass(const HourglassModes& m, double coefficient, double* f) {
  double force[4][3], power = 0.0;
  for (int mode = 0; mode < 4; ++mode)
    for (int i = 0; i < 3; ++i) {
      force[mode][i] = coefficient * m.q[mode][i];
      power += force[mode][i] * m.q[mode][i];
    }
  add_hourglass_forces(m, force, f);
  return power;
}

/// Stiffness form: the stored hourglass forces Q_α (global axes, 12 values) turn with the spin
/// W over dt and grow by κ q_α dt; returns the power ½(Q_α,n + Q_α,n+1)·q_α, whose integral is
/// the energy ½|Q|²/κ the hourglass springs hold (recoverable, not dissipated).
double stiffness_hourglass(const HourglassModes& m, const BrickKinematics& k, double stiffness,
                           double dt, double* stored, double* f) {
  double force[4][3], power = 0.0;
  for (int mode = 0; mode < 4; ++mode) {
    double* qs = stored + 3 * mode;
    const double turned[3] = {qs[0] + dt * (k.w01 * qs[1] + k.w02 * qs[2]),
                              qs[1] + dt * (-k.w01 * qs[0] + k.w12 * qs[2]),
                              qs[2] + dt * (-k.w02 * qs[0] - k.w12 * qs[1])};
    for (int i = 0; i < 3; ++i) {
      qs[i] = turned[i] + stiffness * dt * m.q[mode][i];
      force[mode][i] = qs[i];
      power += 0.5 * (turned[i] + qs[i]) * m.q[mode][i];
    }
  }
  add_hourglass_forces(m, force, f);
  return power;
}

class Solid164Set final : public ExplicitElementSet {
 public:
  Solid164Set(const ExplicitBuildContext& ctx, const std::vector<const ElementRecord*>& records);

  const std::string& family() const override { return kSolid164Family; }
  std::size_t size() const override { return ids_.size(); }
  int element_id(std::size_t k) const override { return ids_[k]; }
  int nodes_per_element() const override { return 8; }
  const int* nodes(std::size_t k) const override { return &nodes_[8 * k]; }
  void add_element_mass(std::size_t k, std::vector<double>& mass) const override {
    for (int a = 0; a < 8; ++a) mass[nodes_[8 * k + a]] += density_[k] * share_[8 * k + a];
  }
  Eigen::Matrix3d second_mass_moment(const ExplicitNodalView& state, std::size_t k) const override {
    double x[8], y[8], z[8], m[9];
    for (int a = 0; a < 8; ++a) {
      const int n = nodes_[8 * k + a];
      x[a] = state.x[n];
      y[a] = state.y[n];
      z[a] = state.z[n];
    }
    hexahedron::second_moment(x, y, z, m);
    return density_[k] * Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(m);
  }
  double element_step(const ExplicitNodalView& state, std::size_t k) const override;
  double scale_mass(std::size_t k, double factor, std::vector<double>& mass) override {
    const double added = (factor - 1.0) * density_[k];
    double total = 0.0;
    for (int a = 0; a < 8; ++a) {
      mass[nodes_[8 * k + a]] += added * share_[8 * k + a];
      total += added * share_[8 * k + a];
    }
    density_[k] *= factor;
    return total;
  }
  void results(Eigen::MatrixXd& out) const override;
  void segments(std::vector<ExplicitSegment>& out) const override;

 private:
  ExplicitStepLimit chunk_forces(const ExplicitNodalView& state, double dt, double* element_forces,
                                 double* element_moments, std::size_t begin, std::size_t end,
                                 ExplicitSetEnergies& energies) override;
  /// σ_{n+1} of element k from D, W over dt (its plastic work added to `energies`); returns the
  /// stress power's mean σ:D.
  double update_stress(std::size_t k, const BrickKinematics& kin, double dt,
                       ExplicitSetEnergies& energies);

  std::vector<int> ids_;
  std::vector<int> nodes_;       // 8 per element
  std::vector<double> share_;    // ∫N_I dV at the initial configuration, 8 per element
  std::vector<double> density_;  // ρ, mass-scaled
  /// √(smallest corner share / mean share) of the row-sum mass: the step estimate L/c assumes
  /// ρV/8 at every corner; a distorted brick's lighter corner vibrates faster by 1/√ of it.
  std::vector<double> mass_factor_;
  std::vector<int> material_;  // index into materials_
  std::vector<RateMaterial> materials_;
  std::vector<double> stress_;  // 6 per element
  std::vector<double> back_;    // 6 per element (kinematic hardening)
  std::vector<double> alpha_;   // equivalent plastic strain
  /// EDMP,HGLS (or EDHGLS, EDBVIS) of each material, as materials_.
  std::vector<ExplicitHourglass> hourglass_;
  /// The stiffness form's stored hourglass forces, 12 per element (empty when no material
  /// uses it).
  std::vector<double> hourglass_force_;
};

Solid164Set::Solid164Set(const ExplicitBuildContext& ctx,
                         const std::vector<const ElementRecord*>& records) {
  std::map<int, int> material_index;
  for (const ElementRecord* r : records) {
    if (r->nodes.size() != 8)
      throw InputError(r->where, fmt::format("element {}: SOLID164 needs 8 nodes I..P, got {}",
                                             r->id, r->nodes.size()));
    const ElementType& type = ctx.model.element_type(r->type);
    if (const std::string why = keyopt_refusal(type); !why.empty())
      throw InputError(type.where.known() ? type.where : r->where,
                       fmt::format("element type {}: {}", type.id, why));
    auto [it, added] = material_index.emplace(r->mat, static_cast<int>(materials_.size()));
    if (added) {
      const IsotropicElasticity e = read_isotropic_elasticity(ctx.model, r->mat, r->id, r->where);
      if (!(e.density > 0.0))
        throw InputError(r->where, fmt::format("element {}: material {} has no density (DENS): "
                                               "explicit dynamics needs the mass of every element",
                                               r->id, r->mat));
      RateMaterial m;
      m.shear = e.young / (2.0 * (1.0 + e.poisson));
      m.bulk = e.young / (3.0 * (1.0 - 2.0 * e.poisson));
      m.density = e.density;
      m.plasticity = plasticity_of(ctx.model, *r, e.young, e.poisson, false);
      materials_.push_back(std::move(m));
      hourglass_.push_back(ctx.hourglass_of(r->mat));
    }
    double x[8], y[8], z[8], share[8];
    for (int a = 0; a < 8; ++a) {
      const int index = ctx.node_index(r->nodes[static_cast<std::size_t>(a)], *r);
      nodes_.push_back(index);
      const Vec3& p = ctx.model.node(r->nodes[static_cast<std::size_t>(a)]).x;
      x[a] = p.x();
      y[a] = p.y();
      z[a] = p.z();
    }
    hexahedron::row_sum_volumes(x, y, z, share);
    double volume = 0.0;
    for (double s : share) volume += s;
    if (!(volume > 0.0))
      throw InputError(r->where, fmt::format("element {}: zero or negative volume {:g} (nodes "
                                             "I..P: IJKL the bottom face, counter-clockwise "
                                             "seen from MNOP)",
                                             r->id, volume));
    share_.insert(share_.end(), share, share + 8);
    mass_factor_.push_back(std::sqrt(*std::min_element(share, share + 8) / (volume / 8.0)));
    ids_.push_back(r->id);
    material_.push_back(it->second);
    density_.push_back(materials_[static_cast<std::size_t>(it->second)].density);
  }
  stress_.assign(6 * ids_.size(), 0.0);
  back_.assign(6 * ids_.size(), 0.0);
  alpha_.assign(ids_.size(), 0.0);
  if (std::any_of(hourglass_.begin(), hourglass_.end(),
                  [](const ExplicitHourglass& h) { return h.stiffness(); }))
    hourglass_force_.assign(12 * ids_.size(), 0.0);
}

double Solid164Set::element_step(const ExplicitNodalView& state, std::size_t k) const {
  BrickKinematics kin;
  gather(state, &nodes_[8 * k], kin);
  hexahedron::volume_derivatives(kin.x, kin.y, kin.z, kin.bx, kin.by, kin.bz);
  kin.volume = hexahedron::volume(kin.x, kin.bx);
  const RateMaterial& m = materials_[static_cast<std::size_t>(material_[k])];
  const double c = std::sqrt((m.bulk + 4.0 * m.shear / 3.0) / density_[k]);
  return mass_factor_[k] * characteristic_length(kin) / c;
}

double Solid164Set::update_stress(std::size_t k, const BrickKinematics& kin, double dt,
                                  ExplicitSetEnergies& energies) {
  double* s = &stress_[6 * k];
  const RateMaterial& m = materials_[static_cast<std::size_t>(material_[k])];
  jaumann_rotate(s, kin.w01, kin.w12, kin.w02, dt);
  const double power_old = contract(s, kin.d);
  elastic_increment(s, kin.d, dt, m);
  if (m.plasticity)
    energies.plastic_work += kin.volume * radial_return(s, &back_[6 * k], alpha_[k], m);
  return 0.5 * (power_old + contract(s, kin.d));
}

ExplicitStepLimit Solid164Set::chunk_forces(const ExplicitNodalView& state, double dt,
                                            double* element_forces, double*, std::size_t begin,
                                            std::size_t end, ExplicitSetEnergies& energies) {
  ExplicitStepLimit limit;
  BrickKinematics kin;
  for (std::size_t k = begin; k < end; ++k) {
    gather(state, &nodes_[8 * k], kin);
    hexahedron::volume_derivatives(kin.x, kin.y, kin.z, kin.bx, kin.by, kin.bz);
    kin.volume = hexahedron::volume(kin.x, kin.bx);
    if (!(kin.volume > 0.0))
      throw ElementSolutionError(ids_[k], fmt::format("element {} (SOLID164) turned inside out "
                                                      "(volume {:.4g}): a time step too large or "
                                                      "an hourglass mode out of control",
                                                      ids_[k], kin.volume));
    rates(kin);
    const double stress_power = update_stress(k, kin, dt, energies);
    const auto mat = static_cast<std::size_t>(material_[k]);
    const RateMaterial& m = materials_[mat];
    const ExplicitHourglass& control = hourglass_[mat];
    const double modulus = m.bulk + 4.0 * m.shear / 3.0;  // λ + 2μ = ρc²
    const double rho = density_[k];
    const double c = std::sqrt(modulus / rho);
    const double length = characteristic_length(kin);
    // Bulk viscosity (LS-DYNA theory manual, "Bulk viscosity"): in compression only.
    const double volumetric = kin.d[0] + kin.d[1] + kin.d[2];
    double q = 0.0, speed_term = 0.0;
    if (volumetric < 0.0) {
      speed_term = control.bulk_quadratic * length * -volumetric + control.bulk_linear * c;
      q = rho * length * speed_term * -volumetric;
    }
    limit.take(mass_factor_[k] * length / (speed_term + std::sqrt(speed_term * speed_term + c * c)),
               ids_[k]);
    energies.internal += internal_work(k, dt * kin.volume * (stress_power - q * volumetric));
    const double* s = &stress_[6 * k];
    double* f = element_forces + 24 * k;
    for (int a = 0; a < 8; ++a) {
      f[3 * a] = (s[0] - q) * kin.bx[a] + s[3] * kin.by[a] + s[5] * kin.bz[a];
      f[3 * a + 1] = s[3] * kin.bx[a] + (s[1] - q) * kin.by[a] + s[4] * kin.bz[a];
      f[3 * a + 2] = s[5] * kin.bx[a] + s[4] * kin.by[a] + (s[2] - q) * kin.bz[a];
    }
    if (!(control.membrane > 0.0)) continue;  // QM 0: no hourglass control
    HourglassModes modes;
    hourglass_modes(kin, modes);
    if (control.stiffness()) {
      // FB stiffness form: κ = QM (λ + 2μ) Σ_I b_I·b_I / (3V), 0.5 QM (λ + 2μ) h on a cube of
      // side h, of the order of the stiffness a fully integrated brick has for these modes.
      double norm2 = 0.0;
      for (int a = 0; a < 8; ++a)
        norm2 += kin.bx[a] * kin.bx[a] + kin.by[a] * kin.by[a] + kin.bz[a] * kin.bz[a];
      const double stiffness = control.membrane * modulus * norm2 / (3.0 * kin.volume);
      energies.hourglass += hourglass_work(
          k, dt * stiffness_hourglass(modes, kin, stiffness, dt, &hourglass_force_[12 * k], f));
    } else {
      // FB viscous form: QM ρ c V^{2/3} / 4 (LS-DYNA theory manual, hourglass types 2, 3).
      const double coefficient =
          0.25 * control.membrane * rho * c * std::cbrt(kin.volume * kin.volume);
      energies.hourglass += hourglass_work(k, dt * viscous_hourglass(modes, coefficient, f));
    }
  }
  return limit;
}

void Solid164Set::results(Eigen::MatrixXd& out) const {
  out.resize(static_cast<Eigen::Index>(size()), static_cast<Eigen::Index>(kResults.size()));
  for (std::size_t k = 0; k < size(); ++k) {
    const double* s = &stress_[6 * k];
    Vector6d v;
    v << s[0], s[1], s[2], s[3], s[4], s[5];
    const auto row = static_cast<Eigen::Index>(k);
    for (int i = 0; i < 6; ++i) out(row, i) = s[i];
    out(row, 6) = von_mises(v);
    out(row, 7) = alpha_[k];
  }
}

const ElementRegistration kSolid164{
    {.name = "SOLID164",
     .number = 164,
     .family = kSolid164Family,
     .n_nodes = 8,
     .needs_material = true,
     .vtk_cell = VtkCell::Hexahedron,
     .role = ShapeRole::Solid,
     .result_names = kResults,
     .result_sequences = {{"S", "X", "SX"},
                          {"S", "Y", "SY"},
                          {"S", "Z", "SZ"},
                          {"S", "XY", "SXY"},
                          {"S", "YZ", "SYZ"},
                          {"S", "XZ", "SXZ"},
                          {"S", "EQV", "SEQV"},
                          {"NL", "EPEQ", "EPEQ"}},
     .plasticity = true,
     .create = [](const ElementBuildContext&, const ElementRecord& r) -> std::unique_ptr<Element> {
       refuse_in_implicit_analysis(r, "SOLID164", "; use SOLID185 in an implicit one");
     },
     .explicit_set = [](const ExplicitBuildContext& ctx,
                        const std::vector<const ElementRecord*>& records)
         -> std::unique_ptr<ExplicitElementSet> {
       return std::make_unique<Solid164Set>(ctx, records);
     }}};

/// The six faces of the brick I..P, counterclockwise seen from outside (outward normal).
constexpr int kFaces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                              {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

void Solid164Set::segments(std::vector<ExplicitSegment>& out) const {
  for (std::size_t k = 0; k < size(); ++k) {
    double volume = 0.0;
    for (int a = 0; a < 8; ++a) volume += share_[8 * k + a];
    for (const auto& face : kFaces) {
      ExplicitSegment s;
      for (int a = 0; a < 4; ++a) s.nodes[a] = nodes_[8 * k + face[a]];
      s.element = ids_[k];
      s.bulk_modulus = materials_[material_[k]].bulk;
      s.volume = volume;
      out.push_back(s);
    }
  }
}

}  // namespace

}  // namespace impactfe
