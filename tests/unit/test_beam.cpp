// Beam elements (BEAM188 with sections, BEAM4, BEAM3): rigid-body modes, symmetry, mass sums,
// cantilever closed forms (Euler–Bernoulli and Timoshenko, slender and stocky), bending and
// torsional frequencies, consistent tangents (stress stiffening, co-rotational), rigid rotation,
// results and input errors. APDL_MODELING §7.2, §8.1, §8.2.
#include <gtest/gtest.h>

#include "../support/element_checks.h"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <cmath>

#include "core/errors.h"
#include "elements/beam.h"
#include "elements/beam_section.h"
#include "elements/element.h"
#include "elements/element_registry.h"

namespace impactfe::test_beam {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kE = 200e3;      // N/mm²
constexpr double kNu = 0.3;       //
constexpr double kRho = 7.85e-9;  // t/mm³

/// Nodes 1..n+1 from `a` to `b`, node 100 = orientation node at `k` (when given); ET 1 BEAM188,
/// MAT 1, section 1 (subtype, data).
Model beam_model(const Vec3& a, const Vec3& b, int n, const std::string& subtype,
                 const std::vector<double>& data, const char* type = "BEAM188") {
  Model m;
  for (int i = 0; i <= n; ++i) m.nodes[i + 1] = Node{i + 1, a + (b - a) * (double(i) / n)};
  ElementType et;
  et.id = 1;
  et.ansys_name = type;
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
  r.where = SourceLocation{"beam.inp", 12, "E"};
  return r;
}

std::unique_ptr<Element> build(const Model& m, const ElementRecord& r) {
  return create_element(ElementBuildContext{m, {}}, r);
}

/// Global stiffness and mass of the n elements of beam_model (DOFs node-major, 6 per node).
void assemble(const Model& m, int n, const ElementContext& ctx, Eigen::MatrixXd& K,
              Eigen::MatrixXd& M) {
  const int nd = 6 * (n + 1);
  K.setZero(nd, nd);
  M.setZero(nd, nd);
  for (int e = 0; e < n; ++e) {
    const auto el = build(m, record(e + 1, {e + 1, e + 2}));
    Eigen::MatrixXd Ke, Me;
    Eigen::VectorXd f;
    el->tangent(ctx, Eigen::VectorXd::Zero(12), Ke, f);
    el->mass(ctx, Me);
    K.block(6 * e, 6 * e, 12, 12) += Ke;
    M.block(6 * e, 6 * e, 12, 12) += Me;
  }
}

/// Rows/columns `keep` of a matrix.
Eigen::MatrixXd sub(const Eigen::MatrixXd& A, const std::vector<int>& keep) {
  Eigen::MatrixXd S(keep.size(), keep.size());
  for (std::size_t i = 0; i < keep.size(); ++i)
    for (std::size_t j = 0; j < keep.size(); ++j) S(i, j) = A(keep[i], keep[j]);
  return S;
}

TEST(BeamSection, PropertiesMatchClosedForms) {
  // RECT B = 2, H = 3: the spec's SLIST example (A = 6, Iyy = 4.5, Izz = 2).
  const auto r = beam_section_properties("RECT", {2, 3});
  EXPECT_NEAR(r.area, 6.0, 1e-12);
  EXPECT_NEAR(r.iyy, 4.5, 1e-12);
  EXPECT_NEAR(r.izz, 2.0, 1e-12);
  EXPECT_NEAR(r.iyz, 0.0, 1e-12);
  // Square: J = 0.140577 a⁴ (Timoshenko & Goodier §109, table: k1 = 0.141 for a/b = 1).
  EXPECT_NEAR(beam_section_properties("RECT", {1, 1}).torsion, 0.140577, 2e-6);
  // Thin strip b/a → 0: J → a b³/3 (1 − 0.630 b/a).
  const double jt = beam_section_properties("RECT", {100, 1}).torsion;
  EXPECT_NEAR(jt, 100.0 / 3.0 * (1.0 - 0.630249 / 100.0), 1e-4);

  const double R = 2.5;
  const auto c = beam_section_properties("CSOLID", {R});
  EXPECT_NEAR(c.area, kPi * R * R, 1e-12 * c.area);
  EXPECT_NEAR(c.iyy, kPi * std::pow(R, 4) / 4, 1e-12 * c.iyy);
  EXPECT_NEAR(c.izz, kPi * std::pow(R, 4) / 4, 1e-12 * c.izz);
  EXPECT_NEAR(c.torsion, kPi * std::pow(R, 4) / 2, 1e-12 * c.torsion);

  const double ri = 1.5, ro = 2.0;
  const auto t = beam_section_properties("CTUBE", {ri, ro, 12});
  const double it = kPi * (std::pow(ro, 4) - std::pow(ri, 4)) / 4;
  EXPECT_NEAR(t.area, kPi * (ro * ro - ri * ri), 1e-12 * t.area);
  EXPECT_NEAR(t.iyy, it, 1e-12 * it);
  EXPECT_NEAR(t.izz, it, 1e-12 * it);
  EXPECT_NEAR(t.torsion, 2 * it, 1e-12 * it);
  EXPECT_EQ(t.fibres.size(), 36u);  // 12 sectors × 3 Simpson points (Ri, mid, Ro)

  // I (vm134 proportions, unequal flanges to move the centroid): parallel-axis sums by hand.
  const double w1 = 10, w2 = 6, w3 = 12, t1 = 1, t2 = 2, t3 = 0.5;
  const auto i = beam_section_properties("I", {w1, w2, w3, t1, t2, t3});
  const double a1 = w1 * t1, a2 = w2 * t2, hw = w3 - t1 - t2, a3 = t3 * hw;
  const double z1 = t1 / 2, z2 = w3 - t2 / 2, z3 = t1 + hw / 2;
  const double A = a1 + a2 + a3, zc = (a1 * z1 + a2 * z2 + a3 * z3) / A;
  const double iyy = w1 * t1 * t1 * t1 / 12 + a1 * (z1 - zc) * (z1 - zc) + w2 * t2 * t2 * t2 / 12 +
                     a2 * (z2 - zc) * (z2 - zc) + t3 * hw * hw * hw / 12 +
                     a3 * (z3 - zc) * (z3 - zc);
  const double izz = t1 * w1 * w1 * w1 / 12 + t2 * w2 * w2 * w2 / 12 + hw * t3 * t3 * t3 / 12;
  EXPECT_NEAR(i.area, A, 1e-12 * A);
  EXPECT_NEAR(i.centroid_z, zc, 1e-12 * w3);
  EXPECT_NEAR(i.iyy, iyy, 1e-12 * iyy);
  EXPECT_NEAR(i.izz, izz, 1e-12 * izz);
  EXPECT_NEAR(i.z_max, w3 - zc, 1e-12);
  EXPECT_NEAR(i.z_min, -zc, 1e-12);

  // HREC with equal walls: outer minus inner rectangle; Bredt's J on the centre line.
  const auto h = beam_section_properties("HREC", {4, 6, 0.5, 0.5, 0.5, 0.5});
  EXPECT_NEAR(h.area, 24 - 3 * 5, 1e-12);
  EXPECT_NEAR(h.iyy, (4 * 216 - 3 * 125) / 12.0, 1e-11);
  EXPECT_NEAR(h.izz, (6 * 64 - 5 * 27) / 12.0, 1e-11);
  EXPECT_NEAR(h.torsion, 4 * std::pow(3.5 * 5.5, 2) / (2 * 5.5 / 0.5 + 2 * 3.5 / 0.5), 1e-11);

  // ASEC: the fibres reproduce the given properties, Iyz included.
  const auto s = beam_section_properties("ASEC", {18, 1350, 3, 0.54, 0, 2.16, 0, 0, 0, 0, 10, 8});
  Eigen::Vector3d s0;
  Eigen::Matrix3d D;
  integrate_fibres(
      s.fibres, Eigen::Vector3d::Zero(),
      [](int, double e, double& sig, double& et) {
        sig = e;
        et = 1.0;
      },
      s0, D);
  EXPECT_NEAR(D(0, 0), 18, 1e-12);
  EXPECT_NEAR(D(1, 1), 1350, 1e-9);
  EXPECT_NEAR(D(2, 2), 0.54, 1e-12);
  EXPECT_NEAR(D(1, 2), -3, 1e-12);  // g = (1, z, −y): D12 = −Σ a y z
  EXPECT_NEAR(s.z_max, 5, 0);
  EXPECT_NEAR(s.y_min, -4, 0);
}

TEST(BeamSection, BadDataIsRefused) {
  EXPECT_THROW(beam_section_properties("RECT", {0, 3}), std::invalid_argument);
  EXPECT_THROW(beam_section_properties("CTUBE", {2, 1}), std::invalid_argument);
  EXPECT_THROW(beam_section_properties("I", {1, 1, 1, 0.6, 0.6, 0.1}), std::invalid_argument);
  EXPECT_THROW(beam_section_properties("ASEC", {1, 1, 0, 1, 0, 1, 0, 0, 0.2, 0}),
               std::invalid_argument);
  EXPECT_THROW(beam_section_properties("CHAN", {1, 1}), std::invalid_argument);
}

TEST(Beam188, RigidBodyModesSymmetryAndMassSums) {
  // A skew element with an orientation node: six zero eigenvalues, the seventh clearly not.
  Model m = beam_model(Vec3(1, 2, 3), Vec3(4, 0, 5), 1, "RECT", {0.3, 0.5});
  m.nodes[100] = Node{100, Vec3(0, 0, 9)};
  const auto el = build(m, record(1, {1, 2, 100}));
  for (bool lumped : {false, true}) {
    ElementContext ctx;
    ctx.lumped_mass = lumped;
    Eigen::MatrixXd K, M;
    Eigen::VectorXd f;
    el->tangent(ctx, Eigen::VectorXd::Zero(12), K, f);
    el->mass(ctx, M);
    EXPECT_LT((K - K.transpose()).norm(), 1e-12 * K.norm());
    EXPECT_LT((M - M.transpose()).norm(), 1e-12 * M.norm());
    const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(K).eigenvalues();
    for (int k = 0; k < 6; ++k) EXPECT_LT(std::abs(ev(k)), 1e-9 * ev(11));
    EXPECT_GT(ev(6), 1e-6 * ev(11));
    // Mass sums: rigid translation along each axis carries ρAL.
    const double L = (Vec3(4, 0, 5) - Vec3(1, 2, 3)).norm(), mtot = kRho * 0.15 * L;
    for (int d = 0; d < 3; ++d) {
      Eigen::VectorXd r = Eigen::VectorXd::Zero(12);
      r(d) = r(6 + d) = 1.0;
      EXPECT_NEAR(r.dot(M * r), mtot, 1e-12 * mtot);
    }
    const Eigen::VectorXd evm = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues();
    EXPECT_GT(evm(0), 0.0);
  }
}

/// Tip deflection and rotation of a cantilever (n elements along a skew axis) under a tip force
/// along the element's local y or z, against δ = PL³/(3EI) + PL/(kGA), θ = PL²/(2EI).
void check_cantilever(const std::string& subtype, const std::vector<double>& data, double L, int n,
                      bool along_z, double ks, double rel_tol) {
  const Vec3 a(0, 0, 0), dir = Vec3(1, 1, 0.5).normalized();
  Model m = beam_model(a, a + L * dir, n, subtype, data);
  const BeamSectionProperties p = beam_section_properties(subtype, data);
  Eigen::MatrixXd K, M;
  assemble(m, n, ElementContext{}, K, M);
  // Element axes without K: y = Z × x / |·|, z = x × y.
  const Vec3 ey = Vec3::UnitZ().cross(dir).normalized(), ez = dir.cross(ey);
  const Vec3 load_dir = along_z ? ez : ey;
  const double P = 1000.0;
  std::vector<int> free;
  for (int i = 6; i < K.rows(); ++i) free.push_back(i);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(K.rows());
  f.segment<3>(6 * n) = P * load_dir;
  Eigen::VectorXd fr(free.size());
  for (std::size_t i = 0; i < free.size(); ++i) fr(i) = f(free[i]);
  const Eigen::VectorXd u = sub(K, free).ldlt().solve(fr);
  const Eigen::Vector3d tip = u.segment<3>(6 * n - 6), rot = u.segment<3>(6 * n - 3);
  const double EI = kE * (along_z ? p.iyy : p.izz);
  const double G = kE / (2 * (1 + kNu));
  const double delta = P * L * L * L / (3 * EI) + (ks > 0 ? P * L / (ks * p.area * G) : 0.0);
  const double theta = P * L * L / (2 * EI);
  EXPECT_NEAR(tip.dot(load_dir), delta, rel_tol * delta) << subtype << " n=" << n;
  // θ about −y for a load along z (θy = −w'), about +z for a load along y.
  const Vec3 axis = along_z ? Vec3(-ey) : ez;
  EXPECT_NEAR(rot.dot(axis), theta, rel_tol * theta) << subtype << " n=" << n;
}

TEST(Beam188, CantileverMatchesEulerBernoulliAndTimoshenko) {
  // Slender (L/H = 100) and stocky (L/H = 2) rectangles, 1 and 7 elements, both planes: the
  // one-point element with the residual-bending-flexibility shear is exact for tip loads.
  for (int n : {1, 7})
    for (bool z : {false, true}) {
      check_cantilever("RECT", {10, 20}, 2000, n, z, 5.0 / 6.0, 1e-9);
      check_cantilever("RECT", {10, 20}, 40, n, z, 5.0 / 6.0, 1e-9);
      check_cantilever("CSOLID", {5}, 30, n, z, 0.9, 1e-9);
    }
  // Shear-rigid section (ASEC): Euler–Bernoulli.
  check_cantilever("ASEC", {100, 5000, 0, 2000, 0, 3000}, 50, 3, true, 0.0, 1e-9);
}

/// Lowest generalized eigenvalues ω² of a cantilever along X restricted to DOFs `dofs` (of
/// UX..ROTZ) at every node but the clamped node 1.
Eigen::VectorXd cantilever_omega2(const Model& m, int n, const std::vector<int>& dofs) {
  Eigen::MatrixXd K, M;
  assemble(m, n, ElementContext{}, K, M);
  std::vector<int> keep;
  for (int i = 1; i <= n; ++i)
    for (int d : dofs) keep.push_back(6 * i + d);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(sub(K, keep), sub(M, keep));
  return es.eigenvalues();
}

TEST(Beam188, CantileverFrequenciesConverge) {
  // Slender circular cantilever (L/r_g = 400): Euler–Bernoulli ω_k = (β_k L)² √(EI/(ρAL⁴)),
  // β_k L = 1.875104, 4.694091, 7.854757; torsion ω = (π/2L) √(GJ/(ρ Ip)). 20 elements; the
  // Timoshenko (shear + rotary inertia) shift of mode 3 is ≈ 8e-4, so the tolerance is 2e-3.
  const double L = 1000, R = 5;
  const int n = 20;
  const Model m = beam_model(Vec3::Zero(), Vec3(L, 0, 0), n, "CSOLID", {R, 12, 3});
  const double A = kPi * R * R, I = kPi * std::pow(R, 4) / 4;
  const Eigen::VectorXd w2 = cantilever_omega2(m, n, {1, 5});
  const double c = std::sqrt(kE * I / (kRho * A * std::pow(L, 4)));
  const double beta[3] = {1.875104069, 4.694091133, 7.854757438};
  for (int k = 0; k < 3; ++k) {
    const double exact = beta[k] * beta[k] * c;
    EXPECT_NEAR(std::sqrt(w2(k)), exact, 2e-3 * exact) << "bending mode " << k + 1;
  }
  const Eigen::VectorXd t2 = cantilever_omega2(m, n, {3});
  const double G = kE / (2 * (1 + kNu));
  const double wt = kPi / (2 * L) * std::sqrt(G * 2 * I / (kRho * 2 * I));
  EXPECT_NEAR(std::sqrt(t2(0)), wt, 2e-3 * wt);
}

TEST(Beam188, StressStiffeningTangentIsTheDerivativeOfTheInternalForce) {
  Model m = beam_model(Vec3(0, 0, 0), Vec3(3, 1, 2), 1, "RECT", {0.2, 0.3});
  const auto el = build(m, record(1, {1, 2}));
  ElementContext ctx;
  ctx.stress_stiffening = true;
  Eigen::VectorXd u(12);
  u << 0.001, -0.02, 0.03, 0.01, -0.02, 0.005, 0.004, 0.05, -0.01, -0.01, 0.03, 0.02;
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  el->tangent(ctx, u, K, f);
  const Eigen::MatrixXd Kfd = testing::fd_tangent(*el, ctx, u, 1e-7);
  EXPECT_LT((K - Kfd).norm(), 1e-6 * K.norm());
}

TEST(Beam188, CorotationalTangentAndRigidMotion) {
  Model m = beam_model(Vec3(0, 0, 0), Vec3(3, 1, 2), 1, "RECT", {0.2, 0.3});
  const auto el = build(m, record(1, {1, 2}));
  ElementContext ctx;
  ctx.large_deflection = true;
  // A large rigid motion (rotation of 1.2 rad about a skew axis + translation): no force.
  const Vec3 psi = 1.2 * Vec3(0.3, -0.5, 0.8).normalized(), t(0.5, -1, 2);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(psi.norm(), psi.normalized()).toRotationMatrix();
  Eigen::VectorXd u(12);
  const Vec3 xi(0, 0, 0), xj(3, 1, 2);
  u << R * xi + t - xi, psi, R * xj + t - xj, psi;
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  el->tangent(ctx, u, K, f);
  EXPECT_LT(f.norm(), 1e-9 * K.norm());
  // Deformed state: the symmetric part of the (analytic) tangent equals that of the FD
  // derivative (measured 3e-11 relative at h = 1e-5; the FD truncation error is ~h²).
  u(7) += 0.1, u(10) += 0.2, u(3) -= 0.15, u(6) += 0.01;
  el->tangent(ctx, u, K, f);
  const Eigen::MatrixXd Kfd = testing::fd_tangent(*el, ctx, u, 1e-5);
  const Eigen::MatrixXd Ks = 0.5 * (Kfd + Kfd.transpose());
  EXPECT_LT((K - Ks).norm(), 1e-8 * K.norm());
  // Small displacement: the co-rotational force equals the linear one to second order.
  ElementContext lin;
  Eigen::VectorXd du(12);
  du << 1e-6, 2e-6, -1e-6, 3e-6, -2e-6, 1e-6, -1e-6, 1e-6, 2e-6, -1e-6, 3e-6, 2e-6;
  Eigen::VectorXd fl, fc;
  el->tangent(lin, du, K, fl);
  el->tangent(ctx, du, K, fc);
  EXPECT_LT((fl - fc).norm(), 1e-4 * fl.norm());
}

TEST(Beam188, ResultsAreSectionForcesAndFibreStresses) {
  // Single cantilever element along X, RECT B = 10 (y), H = 20 (z); node J displaced so that
  // the section carries tension N, and a moment about z.
  Model m = beam_model(Vec3::Zero(), Vec3(100, 0, 0), 1, "RECT", {10, 20});
  const auto el = build(m, record(1, {1, 2}));
  Eigen::VectorXd u = Eigen::VectorXd::Zero(12);
  u(6) = 0.01;   // stretch
  u(11) = 1e-3;  // θz at J: curvature κz = 1e-5
  ElementResultValues r;
  el->results(ElementContext{}, u, u, r);
  const auto& names = el->result_names();
  auto get = [&](const std::string& n) {
    return r[static_cast<std::size_t>(std::find(names.begin(), names.end(), n) - names.begin())];
  };
  const double A = 200, Izz = 20.0 * 1000 / 12, N = kE * A * 0.01 / 100;
  EXPECT_NEAR(get("FX_I"), N, 1e-9 * N);
  EXPECT_NEAR(get("FX_J"), N, 1e-9 * N);
  EXPECT_NEAR(get("SDIR_I"), N / A, 1e-9 * N / A);
  // The shear force Vy = −dMz/dx: Mz varies along the element; at each end the fibre stress is
  // −Mz y / Izz with y = ±5.
  EXPECT_NEAR(get("SBYT_J"), -get("MZ_J") * 5 / Izz, 1e-9 * std::abs(get("SBYT_J")));
  EXPECT_NEAR(get("SBYB_I"), get("MZ_I") * 5 / Izz, 1e-9 * std::abs(get("SBYB_I")));
  EXPECT_NEAR(get("SMAX_J"), N / A + std::abs(get("MZ_J")) * 5 / Izz, 1e-9 * get("SMAX_J"));
  // Equilibrium of the element: Mz_J − Mz_I = −Vy L ... with Vy the section shear.
  EXPECT_NEAR(get("MZ_J") - get("MZ_I"), -get("SFY_J") * 100, 1e-9 * std::abs(get("MZ_J")));
  const ElementTypeDescriptor* d = find_element_type("BEAM188");
  ASSERT_NE(d, nullptr);
  const auto seq = find_result_sequence(*d, "SMISC", "16");
  ASSERT_TRUE(seq.has_value());
  EXPECT_EQ(seq->name, "MZ_J");
  EXPECT_EQ(find_result_sequence(*d, "SMISC", "36")->name, "SDIR_J");
  // BEAM4 / BEAM3 numbers (APDL_MODELING §8.2).
  const ElementTypeDescriptor* b4 = find_element_type("4");
  ASSERT_NE(b4, nullptr);
  EXPECT_EQ(b4->name, "BEAM4");
  EXPECT_EQ(find_result_sequence(*b4, "NMISC", "1")->name, "SMAX_I");
  EXPECT_EQ(find_result_sequence(*b4, "LS", "6")->name, "SDIR_J");
  EXPECT_EQ(find_result_sequence(*b4, "SMISC", "5")->name, "MY_I");
  const ElementTypeDescriptor* b3 = find_element_type("BEAM3");
  ASSERT_NE(b3, nullptr);
  EXPECT_EQ(find_result_sequence(*b3, "SMISC", "12")->name, "MZ_J");
  EXPECT_EQ(find_result_sequence(*b3, "LS", "5")->name, "SBYT_J");
  EXPECT_FALSE(find_result_sequence(*b3, "SMISC", "3").has_value());
}

TEST(Beam188, InputErrors) {
  Model m = beam_model(Vec3::Zero(), Vec3(1, 0, 0), 1, "RECT", {1, 1});
  m.element_types[1].keyopt[1] = 1;
  EXPECT_THROW(build(m, record(1, {1, 2})), InputError);
  m.element_types[1].keyopt[1] = 0;
  m.nodes[100] = Node{100, Vec3(2, 0, 0)};
  EXPECT_THROW(build(m, record(1, {1, 2, 100})), InputError);  // K on the axis
  ElementRecord r = record(1, {1, 2});
  r.secnum = 7;
  EXPECT_THROW(build(m, r), InputError);  // no such section
}

TEST(Beam4, RealConstantsAndShearDeflection) {
  // BEAM4 cantilever element along Y with SHEARZ: δz = PL³/(3E IYY) + P L SHEARZ/(G A).
  Model m = beam_model(Vec3::Zero(), Vec3(0, 50, 0), 1, "RECT", {1, 1}, "BEAM4");
  const double A = 12, Izz = 9, Iyy = 16, shearz = 1.2;
  m.real_sets[1] = RealSet{1, {A, Izz, Iyy, 4, 3, 0, 0, 0, shearz, 0, 0, 0}};
  const auto el = build(m, record(1, {1, 2}));
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  el->tangent(ElementContext{}, Eigen::VectorXd::Zero(12), K, f);
  // Element x = +Y, y = Z × x = −X, z = x × y = +Z: the load along global Z bends with IYY.
  const Eigen::MatrixXd Kjj = K.bottomRightCorner(6, 6);
  Eigen::VectorXd load = Eigen::VectorXd::Zero(6);
  load(2) = 10;
  const Eigen::VectorXd u = Kjj.ldlt().solve(load);
  const double G = kE / (2 * (1 + kNu)), L = 50;
  const double exact = 10 * L * L * L / (3 * kE * Iyy) + 10 * L * shearz / (G * A);
  EXPECT_NEAR(u(2), exact, 1e-9 * exact);
  // And along −X (element y) with IZZ, no shear deformation (SHEARY = 0).
  load.setZero();
  load(0) = -10;
  const Eigen::VectorXd v = Kjj.ldlt().solve(load);
  EXPECT_NEAR(-v(0), 10 * L * L * L / (3 * kE * Izz), 1e-9 * 10 * L * L * L / (3 * kE * Izz));
  EXPECT_EQ(*el->volume(), A * L);
}

TEST(Beam3, PlanarDofsAndMass) {
  Model m = beam_model(Vec3::Zero(), Vec3(3, 4, 0), 1, "RECT", {1, 1}, "BEAM3");
  m.real_sets[1] = RealSet{1, {2.0, 1.5, 2.0, 0, 0, 0.1}};
  const auto el = build(m, record(1, {1, 2}));
  ASSERT_EQ(el->n_dofs(), 6);
  EXPECT_EQ(el->dofs()[2].dof, Dof::ROTZ);
  Eigen::MatrixXd M;
  el->mass(ElementContext{}, M);
  Eigen::VectorXd r = Eigen::VectorXd::Zero(6);
  r(0) = r(3) = 1;
  const double mt = (kRho * 2.0 + 0.1) * 5.0;  // ρA + ADDMAS per length
  EXPECT_NEAR(r.dot(M * r), mt, 1e-12 * mt);
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  el->tangent(ElementContext{}, Eigen::VectorXd::Zero(6), K, f);
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(K).eigenvalues();
  for (int k = 0; k < 3; ++k) EXPECT_LT(std::abs(ev(k)), 1e-9 * ev(5));
  EXPECT_GT(ev(3), 1e-6 * ev(5));
  // Out of the X-Y plane: refused.
  m.nodes[2].x.z() = 1;
  EXPECT_THROW(build(m, record(1, {1, 2})), InputError);
}

}  // namespace
}  // namespace impactfe::test_beam
