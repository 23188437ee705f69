// Layered shell sections: layer stiffness, A B D and the equivalent-energy transverse shear
// (shell_laminate.h).
#include "elements/shell_laminate.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace impactfe::shell {

LayerElasticity layer_elasticity(const Material& m, int id) {
  LayerElasticity e;
  e.E1 = m.get("EX", 0.0);
  if (!(e.E1 > 0.0))
    throw std::invalid_argument(fmt::format("material {}: EX must be positive", id));
  e.E2 = m.has("EY") ? m.get("EY", 0.0) : e.E1;
  if (!(e.E2 > 0.0))
    throw std::invalid_argument(fmt::format("material {}: EY must be positive", id));
  // PRXY is the major Poisson's ratio, NUXY the minor one (MAPDL MP): ν_xy / E_x = ν_yx / E_y.
  if (m.has("PRXY"))
    e.nu12 = m.get("PRXY", 0.0);
  else if (m.has("NUXY"))
    e.nu12 = m.get("NUXY", 0.0) * e.E1 / e.E2;
  else
    e.nu12 = 0.3;
  if (!(e.nu12 * e.nu12 * e.E2 / e.E1 < 1.0))
    throw std::invalid_argument(
        fmt::format("material {}: ν_xy ν_yx = {:g} must be below 1 (plane-stress stiffness)", id,
                    e.nu12 * e.nu12 * e.E2 / e.E1));
  const double g_iso = e.E1 / (2.0 * (1.0 + e.nu12));
  e.G12 = m.has("GXY") ? m.get("GXY", 0.0) : g_iso;
  e.G13 = m.has("GXZ") ? m.get("GXZ", 0.0) : e.G12;
  e.G23 = m.has("GYZ") ? m.get("GYZ", 0.0) : e.G12;
  for (const double g : {e.G12, e.G13, e.G23})
    if (!(g > 0.0))
      throw std::invalid_argument(fmt::format("material {}: shear moduli must be positive", id));
  e.rho = m.get("DENS", 0.0);
  e.isotropic =
      e.E2 == e.E1 && std::abs(e.G12 - g_iso) <= 1e-4 * g_iso && e.G13 == e.G12 && e.G23 == e.G12;
  return e;
}

Eigen::Matrix3d rotated_plane_stiffness(const LayerElasticity& e, double theta_deg) {
  // Reduced stiffness in the layer axes (Jones eq. 2.61).
  const double nu21 = e.nu12 * e.E2 / e.E1;
  const double den = 1.0 - e.nu12 * nu21;
  Eigen::Matrix3d Q;
  Q << e.E1 / den, e.nu12 * e.E2 / den, 0.0, e.nu12 * e.E2 / den, e.E2 / den, 0.0, 0.0, 0.0, e.G12;
  if (theta_deg == 0.0) return Q;
  // Layer strains of the element strains (engineering shear): ε' = T ε, 1 at θ from x.
  const double th = theta_deg * std::numbers::pi / 180.0, c = std::cos(th), s = std::sin(th);
  Eigen::Matrix3d T;
  T << c * c, s * s, c * s, s * s, c * c, -c * s, -2.0 * c * s, 2.0 * c * s, c * c - s * s;
  return T.transpose() * Q * T;
}

Eigen::Matrix2d rotated_shear_stiffness(const LayerElasticity& e, double theta_deg) {
  Eigen::Matrix2d G = Eigen::Vector2d(e.G13, e.G23).asDiagonal();
  if (theta_deg == 0.0) return G;
  // (γ13, γ23) = T (γxz, γyz).
  const double th = theta_deg * std::numbers::pi / 180.0, c = std::cos(th), s = std::sin(th);
  Eigen::Matrix2d T;
  T << c, s, -s, c;
  return T.transpose() * G * T;
}

namespace {

/// The equivalent-energy shear correction factor of one bending direction: cylindrical bending
/// about the neutral axis z0 (∫E (z − z0) dz = 0) gives the shear stress τ(z) = Q g(z) with
/// g(z) = −∫_{−h/2}^{z} E (ζ − z0) dζ / ∫E (z − z0)² dz (equilibrium, ∫g dz = 1); equating the
/// shear strain energy ∫τ²/G dz to that of a constant strain over the stiffness k ∫G dz gives
/// k = 1 / (∫G dz · ∫g²/G dz). 5/6 for a homogeneous layer.
double shear_factor(const std::vector<Ply>& plies, int dir) {
  double EA = 0.0, ES = 0.0, GA = 0.0;
  for (const Ply& p : plies) {
    const double E = p.Q(dir, dir);
    EA += E * (p.z_top - p.z_bot);
    ES += E * 0.5 * (p.z_top * p.z_top - p.z_bot * p.z_bot);
    GA += p.G(dir, dir) * (p.z_top - p.z_bot);
  }
  if (!(EA > 0.0) || !(GA > 0.0)) return 5.0 / 6.0;
  const double z0 = ES / EA;
  double EI = 0.0;
  for (const Ply& p : plies) {
    const double a = p.z_bot - z0, b = p.z_top - z0;
    EI += p.Q(dir, dir) * (b * b * b - a * a * a) / 3.0;
  }
  // ∫g²/G dz with 3-point Gauss per layer: g is quadratic in each layer, g² quartic (exact).
  const double gz[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
  const double gw[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  double below = 0.0, energy = 0.0;  // ∫_{−h/2}^{z_bot} E (ζ − z0) dζ
  for (const Ply& p : plies) {
    const double E = p.Q(dir, dir), a = p.z_bot - z0, h = p.z_top - p.z_bot;
    for (int k = 0; k < 3; ++k) {
      const double z = p.z_bot + 0.5 * h * (1.0 + gz[k]) - z0;
      const double g = (below + 0.5 * E * (z * z - a * a)) / EI;
      energy += g * g / p.G(dir, dir) * 0.5 * h * gw[k];
    }
    const double b = p.z_top - z0;
    below += 0.5 * E * (b * b - a * a);
  }
  return 1.0 / (GA * energy);
}

}  // namespace

Laminate make_laminate(const std::vector<LayerInput>& layers, double homogeneous_factor) {
  Laminate lam;
  if (layers.empty()) throw std::invalid_argument("the section has no layers");
  for (const LayerInput& l : layers) {
    if (!(l.thickness > 0.0)) throw std::invalid_argument("layer thickness must be positive");
    lam.thickness += l.thickness;
  }
  double z = -0.5 * lam.thickness;
  for (const LayerInput& l : layers) {
    Ply p;
    p.z_bot = z;
    p.z_top = z + l.thickness;
    z = p.z_top;
    p.theta_deg = l.theta_deg;
    p.material = l.material;
    p.points = l.points;
    p.Q = rotated_plane_stiffness(l.elasticity, l.theta_deg);
    p.G = rotated_shear_stiffness(l.elasticity, l.theta_deg);
    p.rho = l.elasticity.rho;
    // Classical lamination (Jones eq. 4.22): A = Σ Q̄ (z_t − z_b), B = ½ Σ Q̄ (z_t² − z_b²),
    // D = ⅓ Σ Q̄ (z_t³ − z_b³).
    lam.A += p.Q * (p.z_top - p.z_bot);
    lam.B += p.Q * 0.5 * (p.z_top * p.z_top - p.z_bot * p.z_bot);
    lam.D += p.Q * (std::pow(p.z_top, 3) - std::pow(p.z_bot, 3)) / 3.0;
    lam.mass_per_area += p.rho * l.thickness;
    lam.plies.push_back(p);
  }
  const Ply& first = lam.plies.front();
  for (const Ply& p : lam.plies)
    if (p.Q != first.Q || p.G != first.G || p.rho != first.rho) lam.homogeneous = false;
  if (lam.homogeneous)
    lam.shear_factor.setConstant(homogeneous_factor);
  else
    lam.shear_factor = Eigen::Vector2d(shear_factor(lam.plies, 0), shear_factor(lam.plies, 1));
  const Eigen::Vector2d k = lam.shear_factor.cwiseSqrt();
  for (const Ply& p : lam.plies)
    lam.shear += k.asDiagonal() * p.G * k.asDiagonal() * (p.z_top - p.z_bot);
  return lam;
}

std::vector<LayerInput> section_layers(const Model& model, const Section& section,
                                       int element_material) {
  const std::vector<std::vector<double>> lines =
      section.layers.empty() ? std::vector<std::vector<double>>{section.data} : section.layers;
  std::vector<LayerInput> out;
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const std::vector<double>& v = lines[k];
    const auto at = [&](std::size_t i) { return i < v.size() ? v[i] : 0.0; };
    LayerInput l;
    l.thickness = at(0);
    if (!(l.thickness > 0.0))
      throw std::invalid_argument(
          fmt::format("section {} layer {}: thickness must be positive", section.id, k + 1));
    l.material = at(1) != 0.0 ? static_cast<int>(at(1)) : element_material;
    l.theta_deg = at(2);
    l.points = at(3) != 0.0 ? static_cast<int>(at(3)) : 3;
    const auto m = model.materials.find(l.material);
    if (m == model.materials.end() || !m->second.has("EX"))
      throw std::invalid_argument(
          fmt::format("section {} layer {}: material {} has no EX", section.id, k + 1, l.material));
    l.elasticity = layer_elasticity(m->second, l.material);
    out.push_back(l);
  }
  return out;
}

std::vector<std::string> with_layer_result_names(const std::vector<std::string>& homogeneous,
                                                 int layers) {
  std::vector<std::string> out = homogeneous;
  for (int l = 1; l <= layers; ++l)
    for (const char* where : {"TOP", "MID", "BOT"})
      for (const char* item : {"SX", "SY", "SXY", "SEQV"})
        out.push_back(fmt::format("{}_L{}_{}", item, l, where));
  return out;
}

}  // namespace impactfe::shell
