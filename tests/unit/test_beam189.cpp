// BEAM189 (3-node quadratic beam, elements/beam189.h): rigid-body modes of straight and curved
// elements, symmetry, mass sums, patch tests (constant axial force, constant moment), one-element
// cantilever against the Timoshenko closed form, quarter-circle cantilever against Castigliano,
// cantilever frequencies against Euler–Bernoulli, LMESH midside nodes on an arc, input errors.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>

#include "core/errors.h"
#include "deck/deck_reader.h"
#include "elements/beam189.h"
#include "elements/element.h"
#include "elements/element_registry.h"

namespace impactfe::test_beam189 {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kE = 200e3;      // N/mm²
constexpr double kNu = 0.3;       //
constexpr double kRho = 7.85e-9;  // t/mm³

/// ET 1 BEAM189, MAT 1, section 1 (subtype, data); nodes are added by the tests.
Model beam_model(const std::string& subtype, const std::vector<double>& data) {
  Model m;
  ElementType et;
  et.id = 1;
  et.ansys_name = "BEAM189";
  m.element_types[1] = et;
  Material mat;
  mat.id = 1;
  mat.props = {{"EX", kE}, {"PRXY", kNu}, {"DENS", kRho}};
  m.materials[1] = mat;
  Section s;
  s.id = 1;
  s.type = "BEAM";
  s.subtype = subtype;
  s.data = data;
  m.sections[1] = s;
  return m;
}

ElementRecord record(int id, std::vector<int> nodes) {
  ElementRecord r;
  r.id = id;
  r.secnum = 1;
  r.nodes = std::move(nodes);
  r.where = SourceLocation{"beam189.inp", 7, "E"};
  return r;
}

std::unique_ptr<Element> build(const Model& m, const ElementRecord& r, bool nlgeom = false) {
  ElementBuildContext ctx{m, {}};
  ctx.large_deflection = nlgeom;
  return create_element(ctx, r);
}

/// A chain of n elements through the points x(s), s ∈ [0, 1] (node 2k+1 at s = k/n, midside
/// node 2k+2 at the middle parameter); elements e = 1..n with nodes (2e−1, 2e+1, 2e). With
/// `orientation`, node 1000 there is every element's L.
struct Chain {
  Model model;
  int n = 0;
  std::vector<std::unique_ptr<Element>> elements;
  int n_dofs() const { return 6 * (2 * n + 1); }
  /// Global position of DOF c of node id (node ids 1..2n+1, DOFs node-major).
  static int dof(int node, int c) { return 6 * (node - 1) + c; }
};

template <class Curve>
Chain chain(const std::string& subtype, const std::vector<double>& data, int n, Curve x,
            const Vec3* orientation = nullptr) {
  Chain c;
  c.model = beam_model(subtype, data);
  c.n = n;
  for (int k = 0; k <= 2 * n; ++k) c.model.nodes[k + 1] = Node{k + 1, x(k / (2.0 * n))};
  if (orientation) c.model.nodes[1000] = Node{1000, *orientation};
  for (int e = 1; e <= n; ++e) {
    std::vector<int> nodes{2 * e - 1, 2 * e + 1, 2 * e};
    if (orientation) nodes.push_back(1000);
    c.elements.push_back(build(c.model, record(e, nodes)));
  }
  return c;
}

/// Global K and M of a chain (element DOFs: I, J, K nodes, 6 each).
void assemble(const Chain& c, const ElementContext& ctx, Eigen::MatrixXd& K, Eigen::MatrixXd& M) {
  K.setZero(c.n_dofs(), c.n_dofs());
  M.setZero(c.n_dofs(), c.n_dofs());
  for (int e = 1; e <= c.n; ++e) {
    const int nodes[3] = {2 * e - 1, 2 * e + 1, 2 * e};
    Eigen::MatrixXd Ke, Me;
    Eigen::VectorXd f;
    c.elements[static_cast<std::size_t>(e - 1)]->tangent(ctx, Eigen::VectorXd::Zero(18), Ke, f);
    c.elements[static_cast<std::size_t>(e - 1)]->mass(ctx, Me);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        K.block<6, 6>(Chain::dof(nodes[a], 0), Chain::dof(nodes[b], 0)) +=
            Ke.block<6, 6>(6 * a, 6 * b);
        M.block<6, 6>(Chain::dof(nodes[a], 0), Chain::dof(nodes[b], 0)) +=
            Me.block<6, 6>(6 * a, 6 * b);
      }
  }
}

/// Static solution of a chain clamped at node 1 under nodal loads F (global vector).
Eigen::VectorXd clamped_solution(const Chain& c, const Eigen::VectorXd& F) {
  Eigen::MatrixXd K, M;
  assemble(c, ElementContext{}, K, M);
  const int n = c.n_dofs() - 6;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(c.n_dofs());
  u.tail(n) = K.bottomRightCorner(n, n).ldlt().solve(F.tail(n));
  return u;
}

/// Element DOF vector of element e of a chain from the global one.
Eigen::VectorXd element_u(const Chain& c, int e, const Eigen::VectorXd& u) {
  const int nodes[3] = {2 * e - 1, 2 * e + 1, 2 * e};
  Eigen::VectorXd ue(18);
  for (int a = 0; a < 3; ++a) ue.segment<6>(6 * a) = u.segment<6>(Chain::dof(nodes[a], 0));
  return ue;
}

double result(const Element& el, const Eigen::VectorXd& ue, const std::string& name) {
  ElementResultValues out;
  el.results(ElementContext{}, ue, Eigen::VectorXd::Zero(18), out);
  const auto& names = el.result_names();
  const auto it = std::find(names.begin(), names.end(), name);
  EXPECT_NE(it, names.end()) << name;
  return out[static_cast<std::size_t>(it - names.begin())];
}

TEST(Beam189, RigidBodyModesSymmetryAndMassOfStraightAndCurvedElements) {
  // A skew straight element with an orientation node and a curved one (midside node off the
  // chord by a fifth of its length): six zero eigenvalues each, the seventh clearly not.
  const Vec3 a(1, 2, 3), b(4, 0, 5), l(0, 0, 9);
  const Vec3 off = 0.2 * (b - a).norm() * (b - a).cross(Vec3(0, 0, 1)).normalized();
  for (const Vec3 bow : {Vec3::Zero().eval(), off}) {
    Model m = beam_model("RECT", {0.3, 0.5});
    m.nodes[1] = Node{1, a};
    m.nodes[2] = Node{2, b};
    m.nodes[3] = Node{3, 0.5 * (a + b) + bow};
    m.nodes[4] = Node{4, l};
    const auto el = build(m, record(1, {1, 2, 3, 4}));
    for (bool lumped : {false, true}) {
      ElementContext ctx;
      ctx.lumped_mass = lumped;
      Eigen::MatrixXd K, M;
      Eigen::VectorXd f;
      el->tangent(ctx, Eigen::VectorXd::Zero(18), K, f);
      el->mass(ctx, M);
      EXPECT_LT((K - K.transpose()).norm(), 1e-12 * K.norm());
      EXPECT_LT((M - M.transpose()).norm(), 1e-12 * M.norm());
      const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(K).eigenvalues();
      for (int k = 0; k < 6; ++k) EXPECT_LT(std::abs(ev(k)), 1e-10 * ev(17)) << k;
      EXPECT_GT(ev(6), 1e-7 * ev(17));
      // Rigid rotation about an arbitrary axis through an arbitrary point: no force.
      const Vec3 w(0.3, -0.2, 0.7), p(5, 1, -2);
      Eigen::VectorXd r(18);
      for (int n = 0; n < 3; ++n) {
        r.segment<3>(6 * n) = w.cross(m.nodes.at(n + 1).x - p);
        r.segment<3>(6 * n + 3) = w;
      }
      EXPECT_LT((K * r).norm(), 1e-10 * K.norm() * r.norm());
      // Mass of a rigid translation: ρ A times the arc length.
      const double mtot = kRho * 0.15 * dynamic_cast<const QuadraticBeam&>(*el).length();
      for (int d = 0; d < 3; ++d) {
        Eigen::VectorXd t = Eigen::VectorXd::Zero(18);
        t(d) = t(6 + d) = t(12 + d) = 1.0;
        EXPECT_NEAR(t.dot(M * t), mtot, 1e-12 * mtot);
      }
      const Eigen::VectorXd evm = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues();
      EXPECT_GT(evm(0), 0.0);
    }
  }
  // The straight element's length is the chord; the lumped masses are 1/6, 2/3, 1/6.
  Model m = beam_model("RECT", {0.3, 0.5});
  m.nodes[1] = Node{1, a};
  m.nodes[2] = Node{2, b};
  m.nodes[3] = Node{3, 0.5 * (a + b)};
  const auto el = build(m, record(1, {1, 2, 3}));
  const double L = (b - a).norm();
  EXPECT_NEAR(dynamic_cast<const QuadraticBeam&>(*el).length(), L, 1e-14 * L);
  ElementContext lumped;
  lumped.lumped_mass = true;
  Eigen::MatrixXd M;
  el->mass(lumped, M);
  EXPECT_NEAR(M(0, 0), kRho * 0.15 * L / 6, 1e-15);
  EXPECT_NEAR(M(12, 12), kRho * 0.15 * L * 2 / 3, 1e-15);
}

TEST(Beam189, PatchConstantAxialForceAndConstantMoment) {
  // Three elements along a skew axis, midside nodes off the element centres (axial patch: the
  // linear axial displacement is in the isoparametric space for any midside position).
  const Vec3 dir = Vec3(2, 1, -1).normalized();
  const double L = 300.0, P = 1500.0, M0 = 2.0e5;
  const std::vector<double> s{0, 0.10, 0.3, 0.43, 0.6, 0.85, 1.0};
  const Chain axial = chain("RECT", {10, 20}, 3, [&](double t) {
    const auto k = static_cast<std::size_t>(std::lround(t * 6));
    return Vec3(L * s[k] * dir);
  });
  Eigen::VectorXd F = Eigen::VectorXd::Zero(axial.n_dofs());
  F.segment<3>(Chain::dof(7, 0)) = P * dir;
  const Eigen::VectorXd u = clamped_solution(axial, F);
  const double EA = kE * 200.0;
  for (int k = 1; k <= 7; ++k)
    EXPECT_NEAR(u.segment<3>(Chain::dof(k, 0)).dot(dir),
                P * L * s[static_cast<std::size_t>(k - 1)] / EA, 1e-10 * P * L / EA);
  for (int e = 1; e <= 3; ++e)
    for (const char* name : {"FX_I", "FX_J", "FX_K"})
      EXPECT_NEAR(
          result(*axial.elements[static_cast<std::size_t>(e - 1)], element_u(axial, e, u), name), P,
          1e-8 * P)
          << e << name;

  // Constant moment about the element z (along the default axes of a line in the X-Y plane):
  // θ = M x / EI, v = M x² / (2 EI), the quadratic field of centred midside nodes.
  const Chain bend = chain("RECT", {10, 20}, 3, [&](double t) { return Vec3(L * t, 0, 0); });
  Eigen::VectorXd Fm = Eigen::VectorXd::Zero(bend.n_dofs());
  Fm(Chain::dof(7, 5)) = M0;
  const Eigen::VectorXd um = clamped_solution(bend, Fm);
  const double EIz = kE * 20.0 * 1000.0 / 12.0;  // H B³/12 with B = 10 along y
  for (int k = 1; k <= 7; ++k) {
    const double x = L * (k - 1) / 6.0;
    EXPECT_NEAR(um(Chain::dof(k, 5)), M0 * x / EIz, 1e-10 * M0 * L / EIz);
    EXPECT_NEAR(um(Chain::dof(k, 1)), M0 * x * x / (2 * EIz), 1e-10 * M0 * L * L / EIz);
  }
  for (int e = 1; e <= 3; ++e) {
    const Element& el = *bend.elements[static_cast<std::size_t>(e - 1)];
    for (const char* name : {"MZ_I", "MZ_J", "MZ_K"})
      EXPECT_NEAR(result(el, element_u(bend, e, um), name), M0, 1e-8 * M0) << e << name;
    // Extreme fibre at y = ±B/2: σ = ∓M (B/2)/Izz.
    EXPECT_NEAR(result(el, element_u(bend, e, um), "SBYT_I"), -M0 * 5.0 / (EIz / kE), 1e-8 * M0);
  }
}

TEST(Beam189, OneElementCantileverIsNodallyTheTimoshenkoSolution) {
  // Stocky RECT cantilever (L/H = 2, shear deflection ≈ 1/5 of the total) under tip loads in y
  // and z. With the shear strain sampled at the 2 Gauss points the element is exact at its
  // nodes for an end load: δ = PL³/(3EI) + PL/(kGA), θ = PL²/(2EI).
  const double B = 10, H = 20, L = 40, P = 1000;
  const Chain c = chain("RECT", {B, H}, 1, [&](double t) { return Vec3(L * t, 0, 0); });
  Eigen::VectorXd F = Eigen::VectorXd::Zero(c.n_dofs());
  F(Chain::dof(3, 1)) = P;
  F(Chain::dof(3, 2)) = P;
  const Eigen::VectorXd u = clamped_solution(c, F);
  const double G = kE / (2 * (1 + kNu)), kA = 5.0 / 6.0 * B * H;
  const double Izz = H * B * B * B / 12, Iyy = B * H * H * H / 12;
  const double dy = P * L * L * L / (3 * kE * Izz) + P * L / (G * kA);
  const double dz = P * L * L * L / (3 * kE * Iyy) + P * L / (G * kA);
  EXPECT_NEAR(u(Chain::dof(3, 1)), dy, 1e-10 * dy);
  EXPECT_NEAR(u(Chain::dof(3, 2)), dz, 1e-10 * dz);
  EXPECT_NEAR(u(Chain::dof(3, 5)), P * L * L / (2 * kE * Izz), 1e-10 * dy / L);
  EXPECT_NEAR(u(Chain::dof(3, 4)), -P * L * L / (2 * kE * Iyy), 1e-10 * dy / L);
  // Midside rotation and deflection exact too: θ is the exact quadratic, and w' = Πθ + γ with
  // Πθ its linear projection, whose error (a multiple of the Legendre P2) integrates to zero
  // over each half of the element.
  const double x = L / 2;
  EXPECT_NEAR(u(Chain::dof(2, 5)), P * (L * x - x * x / 2) / (kE * Izz), 1e-10 * dy / L);
  const double v_exact = P * x * x * (3 * L - x) / (6 * kE * Izz) + P * x / (G * kA);
  EXPECT_NEAR(u(Chain::dof(2, 1)), v_exact, 1e-10 * dy);
  // Section forces (default axes y = Y, z = Z): Mz = P (L − x), My = −Pz (L − x), Vy = P.
  const Eigen::VectorXd ue = element_u(c, 1, u);
  EXPECT_NEAR(result(*c.elements[0], ue, "MZ_I"), P * L, 1e-8 * P * L);
  EXPECT_NEAR(result(*c.elements[0], ue, "MY_I"), -P * L, 1e-8 * P * L);
  EXPECT_NEAR(result(*c.elements[0], ue, "MZ_J"), 0.0, 1e-8 * P * L);
  EXPECT_NEAR(result(*c.elements[0], ue, "MZ_K"), P * L / 2, 1e-8 * P * L);
  EXPECT_NEAR(result(*c.elements[0], ue, "SFY_I"), P, 1e-8 * P);
  EXPECT_NEAR(result(*c.elements[0], ue, "SFY_K"), P, 1e-8 * P);
}

TEST(Beam189, QuarterCircleCantileverMatchesCastigliano) {
  // Quarter circle of radius R in the X-Y plane, clamped at (R, 0), free at (0, R); tip loads
  // Fx = P (in plane) and Fz = P (out of plane). Castigliano with the rod's energy
  // ∫ (N²/EA + V²/kGA + M²/EI + T²/GJ)/2 ds:
  //   δx = P R³ (3π/4 − 2)/EIz + π P R/(4 EA) + π P R/(4 kGA)
  //   δz = π P R³/(4 EIy) + P R³ (3π/4 − 2)/GJ + π P R/(2 kGA).
  const double R = 100, B = 6, H = 8, P = 10;
  const BeamSectionProperties p = beam_section_properties("RECT", {B, H});
  const double G = kE / (2 * (1 + kNu)), kGA = G * p.shear_area_y, EA = kE * p.area;
  const double dx = P * R * R * R * (0.75 * kPi - 2) / (kE * p.izz) + kPi * P * R / (4 * EA) +
                    kPi * P * R / (4 * kGA);
  const double dz = kPi * P * R * R * R / (4 * kE * p.iyy) +
                    P * R * R * R * (0.75 * kPi - 2) / (G * p.torsion) + kPi * P * R / (2 * kGA);
  double previous_error = 1.0;
  for (int n : {2, 4, 8}) {
    const Chain c = chain("RECT", {B, H}, n, [&](double t) {
      return Vec3(R * std::cos(kPi / 2 * t), R * std::sin(kPi / 2 * t), 0);
    });
    const int tip = 2 * n + 1;
    Eigen::VectorXd F = Eigen::VectorXd::Zero(c.n_dofs());
    F(Chain::dof(tip, 0)) = P;
    F(Chain::dof(tip, 2)) = P;
    const Eigen::VectorXd u = clamped_solution(c, F);
    const double ex = std::abs(u(Chain::dof(tip, 0)) / dx - 1);
    const double ez = std::abs(u(Chain::dof(tip, 2)) / dz - 1);
    std::printf("quarter circle, %d elements: dx/closed form - 1 = %.3e, dz: %.3e\n", n,
                u(Chain::dof(tip, 0)) / dx - 1, u(Chain::dof(tip, 2)) / dz - 1);
    if (n == 8) {
      EXPECT_LT(ex, 1e-4);
      EXPECT_LT(ez, 1e-4);
    }
    EXPECT_LT(std::max(ex, ez), previous_error);
    previous_error = std::max(ex, ez);
  }
}

TEST(Beam189, CantileverFrequenciesMatchEulerBernoulli) {
  // Slender CSOLID cantilever (L/D = 100), 10 elements, consistent and lumped mass: the first
  // three bending frequencies within 0.5 % of β_n² √(EI/(ρA L⁴)) (βL = 1.875104, 4.694091,
  // 7.854757), each appearing twice (y and z).
  const double r = 5, L = 1000;
  const Chain c = chain("CSOLID", {r}, 10, [&](double t) { return Vec3(0, 0, L * t); });
  const double A = kPi * r * r, I = kPi * std::pow(r, 4) / 4;
  const double beta[3] = {1.875104, 4.694091, 7.854757};
  for (bool lumped : {false, true}) {
    ElementContext ctx;
    ctx.lumped_mass = lumped;
    Eigen::MatrixXd K, M;
    assemble(c, ctx, K, M);
    const int n = c.n_dofs() - 6;
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K.bottomRightCorner(n, n),
                                                                 M.bottomRightCorner(n, n));
    const Eigen::VectorXd w = es.eigenvalues().cwiseSqrt();
    for (int k = 0; k < 3; ++k) {
      const double exact = beta[k] * beta[k] * std::sqrt(kE * I / (kRho * A)) / (L * L);
      for (int j = 0; j < 2; ++j) {
        const double got = w(2 * k + j);  // torsion (4918 rad/s) and axial lie above
        EXPECT_NEAR(got / exact, 1.0, 5e-3) << (lumped ? "lumped " : "consistent ") << k;
      }
    }
  }
}

TEST(Beam189, LmeshPutsTheMidsideNodesOnTheArc) {
  const Model m = read_deck_text(
                      "/PREP7\nET,1,BEAM189\nMP,EX,1,2e5\nSECTYPE,1,BEAM,RECT\nSECDATA,1,1\n"
                      "K,1,10,0,0\nK,2,0,10,0\nK,3,0,0,0\nLARC,1,2,3,10\nLESIZE,1,,,3\nLMESH,1\n",
                      "lmesh189.inp", DeckOptions{})
                      .model;
  ASSERT_EQ(m.elements.size(), 3u);
  for (const auto& [id, e] : m.elements) {
    ASSERT_EQ(e.nodes.size(), 3u);
    const Vec3 xi = m.nodes.at(e.nodes[0]).x, xj = m.nodes.at(e.nodes[1]).x,
               xk = m.nodes.at(e.nodes[2]).x;
    EXPECT_NEAR(xk.norm(), 10.0, 1e-9) << id;  // on the arc
    EXPECT_NEAR((xk - xi).norm(), (xk - xj).norm(), 1e-9) << id;
    EXPECT_NEAR(xi.norm(), 10.0, 1e-9);
  }
  EXPECT_EQ(m.nodes.size(), 7u);
}

TEST(Beam189, ThermalStrainOfACurvedElement) {
  // A curved element heated by ΔT (uniform): the free expansion u = α ΔT (x − x_I), θ = 0 is
  // force free (f_int = f_th, results 0); held at all nodes the section force is −E A α ΔT.
  Model m = beam_model("RECT", {2, 3});
  m.nodes[1] = Node{1, Vec3(0, 0, 0)};
  m.nodes[2] = Node{2, Vec3(10, 2, 0)};
  m.nodes[3] = Node{3, Vec3(5, 2.5, 0.5)};
  auto el = build(m, record(1, {1, 2, 3}));
  const double alpha = 1.2e-5, dT = 50;
  Element::ThermalExpansion th;
  th.alpha = Vec3::Constant(alpha);
  th.nodes = {1, 2, 3};
  el->set_thermal_expansion(th);
  el->set_temperature_change({dT, dT, dT});
  Eigen::VectorXd fth, u = Eigen::VectorXd::Zero(18);
  el->thermal_load(ElementContext{}, fth);
  for (int a = 0; a < 3; ++a) u.segment<3>(6 * a) = alpha * dT * m.nodes.at(a + 1).x;
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  el->tangent(ElementContext{}, u, K, f);
  EXPECT_LT((f - fth).norm(), 1e-10 * fth.norm());
  const double N = kE * 6.0 * alpha * dT;
  for (const char* name : {"FX_I", "FX_J", "FX_K", "MZ_I"})
    EXPECT_NEAR(result(*el, u, name), 0.0, 1e-9 * N) << name;
  for (const char* name : {"FX_I", "FX_J", "FX_K"})
    EXPECT_NEAR(result(*el, Eigen::VectorXd::Zero(18), name), -N, 1e-9 * N) << name;
}

TEST(Beam189, BadInputIsRefused) {
  Model m = beam_model("RECT", {1, 2});
  m.nodes[1] = Node{1, Vec3(0, 0, 0)};
  m.nodes[2] = Node{2, Vec3(10, 0, 0)};
  m.nodes[3] = Node{3, Vec3(5, 0, 0)};
  m.nodes[4] = Node{4, Vec3(9.5, 0, 0)};                           // beyond the middle half
  EXPECT_THROW(build(m, record(1, {1, 2})), InputError);           // no midside node
  EXPECT_THROW(build(m, record(1, {1, 2, 4})), InputError);        // folded
  EXPECT_THROW(build(m, record(1, {1, 2, 2})), InputError);        // K = J
  EXPECT_THROW(build(m, record(1, {1, 2, 3}), true), InputError);  // NLGEOM
  m.element_types[1].keyopt[1] = 1;
  EXPECT_THROW(build(m, record(1, {1, 2, 3})), InputError);  // warping DOF
}

TEST(Beam189, StressStiffeningTangentAndEulerBuckling) {
  // The stress-stiffened tangent is the derivative of f_int (central difference, curved element).
  Model m = beam_model("RECT", {2, 3});
  m.nodes[1] = Node{1, Vec3(0, 0, 0)};
  m.nodes[2] = Node{2, Vec3(10, 2, 1)};
  m.nodes[3] = Node{3, Vec3(5, 2.5, 1.5)};
  const auto el = build(m, record(1, {1, 2, 3}));
  ElementContext ss;
  ss.stress_stiffening = true;
  Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(18, -0.01, 0.02);
  Eigen::MatrixXd K, Kd;
  Eigen::VectorXd f;
  el->tangent(ss, u, K, f);
  for (int j = 0; j < 18; ++j) {
    Eigen::VectorXd up = u, um = u, fp, fm;
    up(j) += 1e-6;
    um(j) -= 1e-6;
    el->tangent(ss, up, Kd, fp);
    el->tangent(ss, um, Kd, fm);
    EXPECT_LT(((fp - fm) / 2e-6 - K.col(j)).norm(), 1e-6 * K.norm()) << j;
  }
  // Cantilever column (CSOLID, L/r = 400, 6 elements) under an axial compression: the smallest
  // load factor of K + λ K_G(P) is the Euler load π² EI/(4 L²) (within 1e-3; the shear
  // flexibility lowers it by 1e-5 here).
  const double r = 5, L = 1000, P = 1.0;
  const Chain c = chain("CSOLID", {r}, 6, [&](double t) { return Vec3(L * t, 0, 0); });
  Eigen::VectorXd F = Eigen::VectorXd::Zero(c.n_dofs());
  F(Chain::dof(13, 0)) = -P;
  const Eigen::VectorXd u0 = clamped_solution(c, F);
  Eigen::MatrixXd K0 = Eigen::MatrixXd::Zero(c.n_dofs(), c.n_dofs()), Ks = K0;
  for (int e = 1; e <= c.n; ++e) {
    const int nodes[3] = {2 * e - 1, 2 * e + 1, 2 * e};
    Eigen::MatrixXd Ke0, Kes;
    Eigen::VectorXd fe;
    const Element& el_e = *c.elements[static_cast<std::size_t>(e - 1)];
    el_e.tangent(ElementContext{}, element_u(c, e, u0), Ke0, fe);
    el_e.tangent(ss, element_u(c, e, u0), Kes, fe);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        K0.block<6, 6>(Chain::dof(nodes[a], 0), Chain::dof(nodes[b], 0)) +=
            Ke0.block<6, 6>(6 * a, 6 * b);
        Ks.block<6, 6>(Chain::dof(nodes[a], 0), Chain::dof(nodes[b], 0)) +=
            Kes.block<6, 6>(6 * a, 6 * b);
      }
  }
  const int n = c.n_dofs() - 6;
  const Eigen::MatrixXd Kg = (Ks - K0).bottomRightCorner(n, n);
  // K φ = λ (−K_G) φ: the smallest positive λ.
  Eigen::GeneralizedEigenSolver<Eigen::MatrixXd> ges(-Kg, K0.bottomRightCorner(n, n));
  double lambda = 1e300;
  for (Eigen::Index k = 0; k < ges.eigenvalues().size(); ++k) {
    const std::complex<double> mu = ges.eigenvalues()(k);  // μ = 1/λ
    if (std::abs(mu.imag()) < 1e-12 && mu.real() > 1e-12) lambda = std::min(lambda, 1 / mu.real());
  }
  const double euler = kPi * kPi * kE * kPi * std::pow(r, 4) / 4 / (4 * L * L);
  EXPECT_NEAR(lambda * P / euler, 1.0, 1e-3);
}

}  // namespace
}  // namespace impactfe::test_beam189
