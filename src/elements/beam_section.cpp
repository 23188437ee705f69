#include "elements/beam_section.h"

#include <fmt/format.h>
#include <numbers>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace impactfe {

namespace {

[[noreturn]] void bad(const std::string& msg) {
  throw std::invalid_argument(msg);
}

double field(const std::vector<double>& d, std::size_t i, double fallback = 0.0) {
  return i < d.size() && d[i] != 0.0 ? d[i] : fallback;
}

/// Most cells of a section along one direction: the fibres of a rectangle are (2 Nb + 1)(2 Nh + 1)
/// and every integration point of every element visits each one, so 100 × 100 cells (40 401
/// fibres) is already far finer than a section needs.
constexpr double kMaxCells = 100.0;

int count_field(const std::vector<double>& d, std::size_t i, int fallback,
                const std::string& what) {
  const double v = field(d, i, fallback);
  if (v != std::floor(v) || v < 1.0) bad(fmt::format("{} must be a positive integer", what));
  if (v > kMaxCells) bad(fmt::format("{} = {:g} cells: at most {:g}", what, v, kMaxCells));
  return static_cast<int>(v);
}

/// Points and weights of the composite Simpson rule on [a, b] with n cells (2n + 1 points; the
/// cell ends are shared). Exact for cubics on every cell, and its end points lie on the boundary,
/// so a section's outermost fibres sit on its surface (first yield of a plastic section is exact).
std::vector<std::pair<double, double>> simpson(double a, double b, int n) {
  const double h = (b - a) / n;
  std::vector<std::pair<double, double>> p;
  for (int k = 0; k <= 2 * n; ++k) {
    const double w = (k == 0 || k == 2 * n) ? 1.0 : (k % 2 == 1 ? 4.0 : 2.0);
    p.emplace_back(a + 0.5 * h * k, w * h / 6.0);
  }
  return p;
}

/// Rectangle [y0, y1] × [z0, z1] as ny × nz cells, 3 × 3 Simpson points per cell (exact for the
/// area and the first and second moments; fully plastic moments exact when no cell straddles the
/// neutral axis, since |z| is then linear on every cell).
void add_rectangle(std::vector<BeamFibre>& f, double y0, double y1, double z0, double z1, int ny,
                   int nz) {
  for (const auto& [y, wy] : simpson(y0, y1, ny))
    for (const auto& [z, wz] : simpson(z0, z1, nz)) f.push_back({y, z, wy * wz});
}

/// Annulus ri ≤ r ≤ ro as n sectors (midpoint rule in θ, points at θ = 2πk/n, so that for n a
/// multiple of 4 the points at ±y and ±z lie on the outer surface) × nr rings (Simpson in r on
/// the integrand r, r³: exact for the area and the second moments when n ≥ 3). The centre point of
/// a solid circle has zero weight and is skipped.
void add_annulus(std::vector<BeamFibre>& f, double ri, double ro, int n, int nr) {
  const double dth = 2.0 * std::numbers::pi / n;
  for (int k = 0; k < n; ++k) {
    const double th = k * dth;
    for (const auto& [r, w] : simpson(ri, ro, nr))
      if (r > 0.0) f.push_back({r * std::cos(th), r * std::sin(th), w * r * dth});
  }
}

/// Torsion constant of a solid a × b rectangle (a ≥ b), the series of Saint-Venant's solution:
/// J = a b³/3 [1 − (192/π⁵)(b/a) Σ_{n odd} tanh(nπa/2b)/n⁵] (Timoshenko & Goodier, Theory of
/// Elasticity, §109).
double rectangle_torsion(double w, double h) {
  const double a = std::max(w, h), b = std::min(w, h);
  double sum = 0.0;
  for (int n = 1; n < 200; n += 2)
    sum += std::tanh(n * std::numbers::pi * a / (2.0 * b)) / std::pow(n, 5);
  return a * b * b * b / 3.0 * (1.0 - 192.0 / std::pow(std::numbers::pi, 5) * (b / a) * sum);
}

/// Area, centroid, second moments and extreme fibres from the fibres; moves the fibres so that
/// the centroid is the origin (SECOFFSET,CENT).
void moments_from_fibres(BeamSectionProperties& p, double y_lo, double y_hi, double z_lo,
                         double z_hi) {
  double a = 0.0, sy = 0.0, sz = 0.0;
  for (const BeamFibre& f : p.fibres) {
    a += f.area;
    sy += f.area * f.y;
    sz += f.area * f.z;
  }
  p.area = a;
  p.centroid_y = sy / a;
  p.centroid_z = sz / a;
  p.iyy = p.izz = p.iyz = 0.0;
  for (BeamFibre& f : p.fibres) {
    f.y -= p.centroid_y;
    f.z -= p.centroid_z;
    p.iyy += f.area * f.z * f.z;
    p.izz += f.area * f.y * f.y;
    p.iyz += f.area * f.y * f.z;
  }
  if (std::abs(p.iyz) < 1e-12 * std::max(p.iyy, p.izz)) p.iyz = 0.0;
  p.y_min = y_lo - p.centroid_y;
  p.y_max = y_hi - p.centroid_y;
  p.z_min = z_lo - p.centroid_z;
  p.z_max = z_hi - p.centroid_z;
}

/// Four fibres of area A/4 on the principal axes of the given second moments (ASEC: the section
/// has no geometry, only properties).
void property_fibres(BeamSectionProperties& p) {
  Eigen::Matrix2d S;
  S << p.izz, p.iyz, p.iyz, p.iyy;  // Σ a [y² yz; yz z²]
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(S);
  for (int k = 0; k < 2; ++k) {
    const double lam = std::max(0.0, eig.eigenvalues()(k));
    const Eigen::Vector2d q = std::sqrt(2.0 * lam / p.area) * eig.eigenvectors().col(k);
    for (double s : {-1.0, 1.0}) p.fibres.push_back({s * q(0), s * q(1), 0.25 * p.area});
  }
}

}  // namespace

const std::vector<std::string>& beam_section_subtypes() {
  static const std::vector<std::string> subtypes = {"RECT", "CSOLID", "CTUBE", "I", "HREC", "ASEC"};
  return subtypes;
}

BeamSectionProperties beam_section_properties(const std::string& subtype,
                                              const std::vector<double>& d, double nu) {
  BeamSectionProperties p;
  p.subtype = subtype;
  auto positive = [&](std::size_t i, const char* name) {
    const double v = field(d, i);
    if (!(v > 0.0)) bad(fmt::format("{}: {} must be positive", subtype, name));
    return v;
  };
  if (subtype == "RECT") {
    // B along y, H along z; Nb × Nh cells (default 2 × 2).
    const double b = positive(0, "B"), h = positive(1, "H");
    add_rectangle(p.fibres, -b / 2, b / 2, -h / 2, h / 2, count_field(d, 2, 2, "RECT: Nb"),
                  count_field(d, 3, 2, "RECT: Nh"));
    moments_from_fibres(p, -b / 2, b / 2, -h / 2, h / 2);
    p.torsion = rectangle_torsion(b, h);
    p.shear_area_y = p.shear_area_z = 5.0 / 6.0 * p.area;
    p.shear_note = "5/6 A";
  } else if (subtype == "CSOLID") {
    const double r = positive(0, "R");
    const int n = count_field(d, 1, 8, "CSOLID: N"), t = count_field(d, 2, 2, "CSOLID: T");
    if (n < 3) bad("CSOLID: N (divisions around) must be at least 3");
    add_annulus(p.fibres, 0.0, r, n, t);
    moments_from_fibres(p, -r, r, -r, r);
    p.torsion = std::numbers::pi * std::pow(r, 4) / 2.0;
    p.shear_area_y = p.shear_area_z = 0.9 * p.area;
    p.shear_note = "0.9 A (APDL_MODELING §7.2)";
  } else if (subtype == "CTUBE") {
    const double ri = field(d, 0), ro = positive(1, "Ro");
    if (ri < 0.0 || ri >= ro) bad("CTUBE: Ri must satisfy 0 <= Ri < Ro");
    const int n = count_field(d, 2, 8, "CTUBE: N");
    if (n < 3) bad("CTUBE: N (cells around) must be at least 3");
    if (d.size() > 3) bad("CTUBE: only Ri, Ro, N are supported (more than 3 SECDATA fields)");
    add_annulus(p.fibres, ri, ro, n, 1);
    moments_from_fibres(p, -ro, ro, -ro, ro);
    p.torsion = std::numbers::pi * (std::pow(ro, 4) - std::pow(ri, 4)) / 2.0;
    // Cowper (1966), J. Appl. Mech. 33, Table 1, hollow circle, m = Ri/Ro.
    const double m2 = (ri / ro) * (ri / ro), q = (1.0 + m2) * (1.0 + m2);
    const double k = 6.0 * (1.0 + nu) * q / ((7.0 + 6.0 * nu) * q + (20.0 + 12.0 * nu) * m2);
    p.shear_area_y = p.shear_area_z = k * p.area;
    p.shear_note = fmt::format("Cowper k = {:.4g} (nu = {:.3g})", k, nu);
  } else if (subtype == "I") {
    // W1 bottom flange, W2 top flange, W3 depth, t1/t2 flange thicknesses, t3 web.
    const double w1 = positive(0, "W1"), w2 = positive(1, "W2"), w3 = positive(2, "W3");
    const double t1 = positive(3, "t1"), t2 = positive(4, "t2"), t3 = positive(5, "t3");
    if (t1 + t2 >= w3) bad("I: the flanges (t1 + t2) must be thinner than the depth W3");
    if (t3 > std::min(w1, w2)) bad("I: the web t3 must not be wider than the flanges");
    add_rectangle(p.fibres, -w1 / 2, w1 / 2, 0.0, t1, 4, 2);
    add_rectangle(p.fibres, -w2 / 2, w2 / 2, w3 - t2, w3, 4, 2);
    add_rectangle(p.fibres, -t3 / 2, t3 / 2, t1, w3 - t2, 2, 4);
    const double wmax = std::max(w1, w2) / 2;
    moments_from_fibres(p, -wmax, wmax, 0.0, w3);
    // Open thin-walled section: J = Σ b t³/3 (flanges and web between them).
    p.torsion = (w1 * t1 * t1 * t1 + w2 * t2 * t2 * t2 + (w3 - t1 - t2) * t3 * t3 * t3) / 3.0;
    p.shear_area_z = w3 * t3;
    p.shear_area_y = 5.0 / 6.0 * (w1 * t1 + w2 * t2);
    p.shear_note = "web W3·t3 along z, 5/6 of the flanges along y";
  } else if (subtype == "HREC") {
    // W1 outer width (y), W2 outer height (z); walls t1 left, t2 right, t3 bottom, t4 top.
    const double w1 = positive(0, "W1"), w2 = positive(1, "W2");
    const double t1 = positive(2, "t1"), t2 = positive(3, "t2"), t3 = positive(4, "t3"),
                 t4 = positive(5, "t4");
    if (t1 + t2 >= w1 || t3 + t4 >= w2) bad("HREC: the walls must leave a hollow inside");
    add_rectangle(p.fibres, 0.0, t1, 0.0, w2, 2, 4);
    add_rectangle(p.fibres, w1 - t2, w1, 0.0, w2, 2, 4);
    add_rectangle(p.fibres, t1, w1 - t2, 0.0, t3, 4, 2);
    add_rectangle(p.fibres, t1, w1 - t2, w2 - t4, w2, 4, 2);
    moments_from_fibres(p, 0.0, w1, 0.0, w2);
    // Closed thin-walled section (Bredt): J = 4 Am² / ∮ds/t on the wall centre line.
    const double bm = w1 - (t1 + t2) / 2, hm = w2 - (t3 + t4) / 2;
    p.torsion = 4.0 * bm * bm * hm * hm / (hm / t1 + hm / t2 + bm / t3 + bm / t4);
    p.shear_area_z = w2 * (t1 + t2);
    p.shear_area_y = w1 * (t3 + t4);
    p.shear_note = "vertical walls along z, horizontal walls along y";
  } else if (subtype == "ASEC") {
    // A, Iyy, Iyz, Izz, Iw, J, CGy, CGz, SHy, SHz, TKz, TKy.
    p.area = positive(0, "A");
    p.iyy = positive(1, "Iyy");
    p.iyz = field(d, 2);
    p.izz = positive(3, "Izz");
    p.warping = field(d, 4);
    p.torsion = positive(5, "J");
    if (p.iyz * p.iyz >= p.iyy * p.izz) bad("ASEC: Iyz² must be less than Iyy·Izz");
    if (field(d, 8) != 0.0 || field(d, 9) != 0.0)
      bad("ASEC: a shear centre away from the centroid (SHy, SHz) is not supported");
    // CGy, CGz only place the centroid: the node lies on it (SECOFFSET,CENT).
    const double tkz = field(d, 10), tky = field(d, 11);
    if (tkz < 0.0 || tky < 0.0) bad("ASEC: TKz and TKy must not be negative");
    p.y_max = tky / 2;
    p.y_min = -tky / 2;
    p.z_max = tkz / 2;
    p.z_min = -tkz / 2;
    property_fibres(p);
    p.shear_note = "none given: shear-rigid (Euler-Bernoulli)";
  } else {
    bad(fmt::format("beam subtype {} not supported (RECT, CSOLID, CTUBE, I, HREC, ASEC)", subtype));
  }
  return p;
}

std::string describe_beam_section(const BeamSectionProperties& p) {
  return fmt::format(
      "A = {:.6g}, Iyy = {:.6g}, Iyz = {:.6g}, Izz = {:.6g}, Iw = {:.6g}, J = {:.6g}, "
      "centroid (y, z) = ({:.6g}, {:.6g}), shear areas (y, z) = ({:.6g}, {:.6g}) [{}], "
      "{} fibres",
      p.area, p.iyy, p.iyz, p.izz, p.warping, p.torsion, p.centroid_y, p.centroid_z, p.shear_area_y,
      p.shear_area_z, p.shear_note, p.fibres.size());
}

void integrate_fibres(const std::vector<BeamFibre>& fibres, const Eigen::Vector3d& e,
                      const FibreLaw& law, Eigen::Vector3d& s, Eigen::Matrix3d& D) {
  s.setZero();
  D.setZero();
  for (std::size_t k = 0; k < fibres.size(); ++k) {
    const BeamFibre& f = fibres[k];
    const Eigen::Vector3d g(1.0, f.z, -f.y);
    double stress = 0.0, tangent = 0.0;
    law(static_cast<int>(k), g.dot(e), stress, tangent);
    s += stress * f.area * g;
    D += tangent * f.area * g * g.transpose();
  }
}

}  // namespace impactfe
