// Linearized stresses through a section (PRSECT, PLSECT; docs/post_processing.md, "Paths"):
// the stress components along the straight line between the first two points (nodes) of the
// current path, split into a membrane part (the mean over the thickness t), a bending part
// (linear, equal and opposite at the two ends) and the peak (the rest), as the pressure-vessel
// codes classify them (ASME BPVC VIII-2, Annex 5-A, Eqs. 5.A.1-5.A.2, which also define them
// for every component in global axes):
//   σ_m = (1/t) ∫ σ ds,   σ_b(outside) = −σ_b(inside) = (6/t²) ∫ σ (s − t/2) ds,
// with s the distance from the inside (first) point, integrated by Simpson's rule over the
// path's nDiv + 1 points (exact for a linear stress). Plane and 3-D sections (RHO = 0); the
// axisymmetric forms (RHO ≠ 0), which weight the integrals by the radius, are refused.
#include <fmt/format.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>

#include "deck/post1_path.h"
#include "results/svg_plot.h"

namespace impactfe::deck {

// Helpers in a named namespace: the unity build compiles this file with others.
namespace section_ops {

constexpr std::array<const char*, 6> kComponents = {"X", "Y", "Z", "XY", "YZ", "XZ"};
using Stress = std::array<double, 6>;

/// The section: its end nodes, thickness and the stress components at its n + 1 equally spaced
/// points (AVG nodal stresses interpolated).
struct Section {
  int inside = 0, outside = 0;
  double t = 0.0;
  std::vector<double> s;
  std::array<std::vector<double>, 6> stress;
};

Section section_stresses(DeckReader& r, const Command& c, int rho_field) {
  const PathDefinition& p = complete_path(r, c);
  const PathPoint& a = p.points[0];
  const PathPoint& b = p.points[1];
  if (a.node == 0 || b.node == 0)
    r.fail(c, fmt::format("the first two points of path {} must be nodes (PPATH,POINT,NODE) for a "
                          "linearized stress section",
                          p.name));
  const double rho = r.real(c, rho_field, 0.0);
  if (rho != 0.0)
    r.fail(c, fmt::format("RHO = {}: the axisymmetric linearization (RHO ≠ 0) is not "
                          "implemented; plane and 3-D sections (RHO = 0 or blank) are",
                          rho));
  if (r.integer(c, rho_field + 1, 0) != 0)
    r.fail(c, "KBR applies to axisymmetric sections (RHO ≠ 0) only");
  Section sec;
  sec.inside = a.node;
  sec.outside = b.node;
  sec.t = (b.x - a.x).norm();
  if (!(sec.t > 0.0)) r.fail(c, "the section's two nodes coincide");
  std::vector<Vec3> points;
  for (int j = 0; j <= p.n_div; ++j) {
    const double f = static_cast<double>(j) / p.n_div;
    points.push_back(a.x + f * (b.x - a.x));
    sec.s.push_back(f * sec.t);
  }
  for (std::size_t k = 0; k < 6; ++k)
    sec.stress[k] = interpolate_at(r, c, points, "S", kComponents[k], true);
  return sec;
}

/// Weights of a composite Newton-Cotes rule over n + 1 equally spaced points of spacing h:
/// Simpson's rule, its last three intervals by the 3/8 rule when n is odd (both exact for cubics,
/// so a linear stress's membrane and bending parts are exact), the trapezoidal rule for n = 1.
std::vector<double> cotes_weights(std::size_t n, double h) {
  std::vector<double> w(n + 1, 0.0);
  if (n == 1) {
    w[0] = w[1] = 0.5 * h;
    return w;
  }
  const std::size_t simpson = n % 2 == 0 ? n : n - 3;
  for (std::size_t i = 0; i + 2 <= simpson; i += 2) {
    w[i] += h / 3.0;
    w[i + 1] += 4.0 * h / 3.0;
    w[i + 2] += h / 3.0;
  }
  if (simpson != n) {
    const double e = 3.0 * h / 8.0;
    w[n - 3] += e;
    w[n - 2] += 3.0 * e;
    w[n - 1] += 3.0 * e;
    w[n] += e;
  }
  return w;
}

/// Membrane and outside bending values of each component.
struct Linearized {
  Stress membrane{}, bending{};
};

Linearized linearize(const Section& sec) {
  Linearized out;
  const std::size_t n = sec.s.size() - 1;
  const std::vector<double> w = cotes_weights(n, sec.t / static_cast<double>(n));
  for (std::size_t k = 0; k < 6; ++k) {
    const auto& v = sec.stress[k];
    double m = 0.0, b = 0.0;
    for (std::size_t i = 0; i <= n; ++i) {
      m += w[i] * v[i];
      b += w[i] * v[i] * (sec.s[i] - 0.5 * sec.t);
    }
    out.membrane[k] = m / sec.t;
    out.bending[k] = 6.0 * b / (sec.t * sec.t);
  }
  return out;
}

/// S1, S2, S3, SINT, SEQV of a stress given by its six components.
std::array<double, 5> principal(const Stress& s) {
  Eigen::Matrix3d m;
  m << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
  const Eigen::Vector3d e = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m).eigenvalues();
  const double s1 = e[2], s2 = e[1], s3 = e[0];
  const double eqv =
      std::sqrt(0.5 * ((s1 - s2) * (s1 - s2) + (s2 - s3) * (s2 - s3) + (s3 - s1) * (s3 - s1)));
  return {s1, s2, s3, s1 - s3, eqv};
}

Stress combine(const Stress& a, const Stress& b, double f) {
  Stress o{};
  for (std::size_t k = 0; k < 6; ++k) o[k] = a[k] + f * b[k];
  return o;
}

std::string row(const char* tag, const Stress& s) {
  std::string out = fmt::format(" {:<2}", tag);
  for (double v : s) out += " " + listing_number(v);
  out += "\n   ";
  for (double v : principal(s)) out += " " + listing_number(v);
  return out + "\n";
}

/// The value of component `comp` (X..XZ, 1, 2, 3, INT, EQV) of a stress.
double component(const Stress& s, const std::string& comp) {
  for (std::size_t k = 0; k < 6; ++k)
    if (comp == kComponents[k]) return s[k];
  const auto p = principal(s);
  if (comp == "1") return p[0];
  if (comp == "2") return p[1];
  if (comp == "3") return p[2];
  if (comp == "INT") return p[3];
  return p[4];  // EQV (the caller checks the label)
}

// PRSECT,RHO,KBR
void cmd_prsect(DeckReader& r, const Command& c) {
  const Section sec = section_stresses(r, c, 1);
  const Linearized lin = linearize(sec);
  Stress total_i{}, total_c{}, total_o{};
  const std::size_t last = sec.s.size() - 1, mid = last / 2;
  for (std::size_t k = 0; k < 6; ++k) {
    total_i[k] = sec.stress[k].front();
    total_o[k] = sec.stress[k].back();
    // The centre: the middle point, or the mean of the two about it.
    total_c[k] =
        last % 2 == 0 ? sec.stress[k][mid] : 0.5 * (sec.stress[k][mid] + sec.stress[k][mid + 1]);
  }
  const Stress zero{};
  const Stress bend_i = combine(zero, lin.bending, -1.0), bend_o = lin.bending;
  const Stress mb_i = combine(lin.membrane, bend_i, 1.0), mb_o = combine(lin.membrane, bend_o, 1.0);
  std::string out = fmt::format(
      "\n ***** POST1 LINEARIZED STRESS LISTING *****\n INSIDE NODE = {:8}   OUTSIDE NODE = {:8}"
      "   THICKNESS = {}\n THE X,Y,Z STRESSES ARE IN THE RESULTS COORDINATE SYSTEM (RSYS).\n\n",
      sec.inside, sec.outside, listing_number(sec.t));
  std::string heading = "   ";
  for (const char* k : kComponents) heading += fmt::format(" {:>12}", std::string("S") + k);
  heading += "\n   ";
  for (const char* k : {"S1", "S2", "S3", "SINT", "SEQV"}) heading += fmt::format(" {:>12}", k);
  heading += "\n";
  out += " ** MEMBRANE **\n" + heading + row("", lin.membrane);
  out += " ** BENDING **  I=INSIDE C=CENTER O=OUTSIDE\n" + heading + row("I", bend_i) +
         row("C", zero) + row("O", bend_o);
  out += " ** MEMBRANE PLUS BENDING **\n" + heading + row("I", mb_i) + row("C", lin.membrane) +
         row("O", mb_o);
  out += " ** PEAK **\n" + heading + row("I", combine(total_i, mb_i, -1.0)) +
         row("C", combine(total_c, lin.membrane, -1.0)) + row("O", combine(total_o, mb_o, -1.0));
  out += " ** TOTAL **\n" + heading + row("I", total_i) + row("C", total_c) + row("O", total_o);
  print(r, out);
}

// PLSECT,Item,Comp,RHO,KBR: total, membrane and membrane-plus-bending along the section.
void cmd_plsect(DeckReader& r, const Command& c) {
  const std::string item = r.label(c, 1), comp = r.label(c, 2);
  if (item != "S") r.fail(c, fmt::format("Item '{}': S", c.text(1)));
  static const std::vector<std::string> kComps = {"X", "Y", "Z", "XY",  "YZ", "XZ",
                                                  "1", "2", "3", "INT", "EQV"};
  if (std::find(kComps.begin(), kComps.end(), comp) == kComps.end())
    r.fail(c, fmt::format("Comp '{}': X, Y, Z, XY, YZ, XZ, 1, 2, 3, INT or EQV", c.text(2)));
  const Section sec = section_stresses(r, c, 3);
  const Linearized lin = linearize(sec);
  GraphCurve total{"TOTAL", sec.s, {}}, membrane{"MEMBRANE", sec.s, {}},
      mb{"MEMBRANE+BENDING", sec.s, {}};
  for (std::size_t i = 0; i < sec.s.size(); ++i) {
    Stress t{}, b{};
    const double f = 2.0 * sec.s[i] / sec.t - 1.0;  // −1 inside, +1 outside
    for (std::size_t k = 0; k < 6; ++k) {
      t[k] = sec.stress[k][i];
      b[k] = lin.membrane[k] + f * lin.bending[k];
    }
    total.y.push_back(component(t, comp));
    membrane.y.push_back(component(lin.membrane, comp));
    mb.y.push_back(component(b, comp));
  }
  PostState& ps = post_state(r);
  GraphOptions o;
  o.header = {"impactfe",
              fmt::format("LINEARIZED STRESS S{} NODES {} TO {}", comp, sec.inside, sec.outside)};
  o.x_label = "DIST";
  o.y_label = "S" + comp;
  o.grid = ps.grid;
  write_graph(r, c, {membrane, mb, total}, o);
}

}  // namespace section_ops

void register_post1_section_commands(std::vector<CommandSpec>& t) {
  t.push_back({"PRSECT", section_ops::cmd_prsect, kPost1});
  t.push_back({"PLSECT", section_ops::cmd_plsect, kPost1});
}

}  // namespace impactfe::deck
