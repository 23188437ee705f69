// Layered shell sections (shell_laminate.cpp) and the layered SHELL281: classical lamination
// A B D against closed forms, the equivalent-energy shear correction, a two-layer section of one
// material against the homogeneous one, the B coupling of an unsymmetric [0/90] element, and a
// simply supported cross-ply plate against the Navier solution.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <functional>
#include <map>
#include <set>

#include "../support/dense_assembly.h"
#include "elements/shell281.h"
#include "elements/shell_kernel.h"
#include "elements/shell_laminate.h"

namespace impactfe::test_shell_laminate {
namespace {

using shell::LayerElasticity;
using shell::LayerInput;
using testing::DenseSystem;

/// The ply of vm82's laminate: E1 = 25e6, E2 = 1e6, ν12 = 0.25, G12 = G13 = 5e5, G23 = 2e5.
LayerElasticity ply() {
  LayerElasticity e;
  e.E1 = 25e6, e.E2 = 1e6, e.nu12 = 0.25, e.G12 = 5e5, e.G13 = 5e5, e.G23 = 2e5;
  e.isotropic = false;
  return e;
}

LayerElasticity isotropic(double E, double nu) {
  LayerElasticity e;
  e.E1 = e.E2 = E, e.nu12 = nu, e.G12 = e.G13 = e.G23 = E / (2 * (1 + nu));
  return e;
}

std::vector<LayerInput> layup(const std::vector<double>& angles, double t, LayerElasticity e) {
  std::vector<LayerInput> out;
  for (double a : angles) out.push_back({t / static_cast<double>(angles.size()), e, a, 1, 3});
  return out;
}

TEST(ShellLaminate, CrossPlyMatchesClassicalLamination) {
  // [0/90/90/0], t = 0.1: B = 0; A = Σ Q̄ t_k; D11 = Q11 (t³/12)(7/8) + Q22 (t³/12)(1/8)
  // (outer plies carry 7/8 of the bending, Jones §4.3).
  const double t = 0.1;
  const auto lam = shell::make_laminate(layup({0, 90, 90, 0}, t, ply()));
  const LayerElasticity e = ply();
  const double den = 1 - e.nu12 * e.nu12 * e.E2 / e.E1;
  const double Q11 = e.E1 / den, Q22 = e.E2 / den, Q12 = e.nu12 * e.E2 / den, Q66 = e.G12;
  const double I = t * t * t / 12;
  EXPECT_LT(lam.B.norm(), 1e-9 * lam.A.norm());
  EXPECT_NEAR(lam.A(0, 0), (Q11 + Q22) * t / 2, 1e-6 * Q11 * t);
  EXPECT_NEAR(lam.A(0, 1), Q12 * t, 1e-6 * Q11 * t);
  EXPECT_NEAR(lam.D(0, 0), I * (7 * Q11 + Q22) / 8, 1e-9 * Q11 * I);
  EXPECT_NEAR(lam.D(1, 1), I * (Q11 + 7 * Q22) / 8, 1e-9 * Q11 * I);
  EXPECT_NEAR(lam.D(0, 1), I * Q12, 1e-9 * Q11 * I);
  EXPECT_NEAR(lam.D(2, 2), I * Q66, 1e-9 * Q11 * I);
  EXPECT_NEAR(lam.D(0, 2), 0.0, 1e-9 * Q11 * I);
  EXPECT_FALSE(lam.homogeneous);
  // The 0° plies outside stiffen bending in x and carry the shear stress near the middle in
  // the soft 90° plies: the x factor falls below 5/6 (0.69 for this lay-up, computed).
  EXPECT_LT(lam.shear_factor(0), 5.0 / 6.0);
  EXPECT_GT(lam.shear_factor(0), 0.5);
}

TEST(ShellLaminate, EnergyShearFactorOfAHomogeneousSectionIsFiveSixths) {
  // The equivalent-energy factor of two layers of one material at different angles of an
  // isotropic material (not flagged homogeneous: the angle differs) is the parabola's 5/6.
  auto layers = layup({0, 30, 60}, 0.3, isotropic(2e11, 0.3));
  layers[1].elasticity.E1 *= 1.0 + 1e-15;  // not bitwise one material
  const auto lam = shell::make_laminate(layers);
  EXPECT_FALSE(lam.homogeneous);
  EXPECT_NEAR(lam.shear_factor(0), 5.0 / 6.0, 1e-12);
  EXPECT_NEAR(lam.shear_factor(1), 5.0 / 6.0, 1e-12);
}

TEST(ShellLaminate, UnsymmetricCrossPlyCouplesStretchingAndBending) {
  // [0/90]: B11 = (t²/8)(Q22 − Q11) = −B22, B12 = B66 = 0 (Jones eq. 4.93).
  const double t = 0.2;
  const auto lam = shell::make_laminate(layup({0, 90}, t, ply()));
  const LayerElasticity e = ply();
  const double den = 1 - e.nu12 * e.nu12 * e.E2 / e.E1;
  const double Q11 = e.E1 / den, Q22 = e.E2 / den;
  EXPECT_NEAR(lam.B(0, 0), t * t / 8 * (Q22 - Q11), 1e-9 * Q11 * t * t);
  EXPECT_NEAR(lam.B(1, 1), -lam.B(0, 0), 1e-9 * Q11 * t * t);
  EXPECT_NEAR(lam.B(0, 1), 0.0, 1e-9 * Q11 * t * t);
  EXPECT_NEAR(lam.B(2, 2), 0.0, 1e-9 * Q11 * t * t);
}

TEST(ShellLaminate, RotatedStiffnessOfAQuarterTurnSwapsTheAxes) {
  const Eigen::Matrix3d Q0 = shell::rotated_plane_stiffness(ply(), 0.0);
  const Eigen::Matrix3d Q90 = shell::rotated_plane_stiffness(ply(), 90.0);
  EXPECT_NEAR(Q90(0, 0), Q0(1, 1), 1e-6);
  EXPECT_NEAR(Q90(1, 1), Q0(0, 0), 1e-6);
  EXPECT_NEAR(Q90(0, 1), Q0(0, 1), 1e-6);
  EXPECT_NEAR(Q90(2, 2), Q0(2, 2), 1e-6);
  const Eigen::Matrix2d G90 = shell::rotated_shear_stiffness(ply(), 90.0);
  EXPECT_NEAR(G90(0, 0), 2e5, 1e-9);
  EXPECT_NEAR(G90(1, 1), 5e5, 1e-9);
}

TEST(ShellLaminate, OffAxisPlyMatchesTheTransformedReducedStiffness) {
  // Q̄ of a ply at θ = 30° against Jones eq. 2.85 written out term by term (m = cos θ,
  // n = sin θ): a wrong sense of θ flips the sign of Q̄16 and Q̄26.
  const LayerElasticity e = ply();
  const double den = 1 - e.nu12 * e.nu12 * e.E2 / e.E1;
  const double Q11 = e.E1 / den, Q22 = e.E2 / den, Q12 = e.nu12 * e.E2 / den, Q66 = e.G12;
  const double m = std::cos(M_PI / 6), n = std::sin(M_PI / 6);
  const double m2 = m * m, n2 = n * n;
  const Eigen::Matrix3d Q = shell::rotated_plane_stiffness(e, 30.0);
  const double tol = 1e-12 * Q11;
  EXPECT_NEAR(Q(0, 0), Q11 * m2 * m2 + 2 * (Q12 + 2 * Q66) * n2 * m2 + Q22 * n2 * n2, tol);
  EXPECT_NEAR(Q(1, 1), Q11 * n2 * n2 + 2 * (Q12 + 2 * Q66) * n2 * m2 + Q22 * m2 * m2, tol);
  EXPECT_NEAR(Q(0, 1), (Q11 + Q22 - 4 * Q66) * n2 * m2 + Q12 * (n2 * n2 + m2 * m2), tol);
  EXPECT_NEAR(Q(2, 2), (Q11 + Q22 - 2 * Q12 - 2 * Q66) * n2 * m2 + Q66 * (n2 * n2 + m2 * m2), tol);
  EXPECT_NEAR(Q(0, 2), (Q11 - Q12 - 2 * Q66) * n * m2 * m + (Q12 - Q22 + 2 * Q66) * n2 * n * m,
              tol);
  EXPECT_NEAR(Q(1, 2), (Q11 - Q12 - 2 * Q66) * n2 * n * m + (Q12 - Q22 + 2 * Q66) * n * m2 * m,
              tol);
  EXPECT_GT(Q(0, 2), 0.0);  // the stiff fibre at +30° couples εx to τxy positively
  EXPECT_NEAR(Q(2, 0), Q(0, 2), tol);
  // Transverse shear: G13 along the fibre, G23 across it; Gxz = G13 m² + G23 n².
  const Eigen::Matrix2d G = shell::rotated_shear_stiffness(e, 30.0);
  EXPECT_NEAR(G(0, 0), e.G13 * m2 + e.G23 * n2, 1e-9);
  EXPECT_NEAR(G(1, 1), e.G13 * n2 + e.G23 * m2, 1e-9);
  EXPECT_NEAR(G(0, 1), (e.G13 - e.G23) * m * n, 1e-9);
}

/// The equivalent-energy shear correction factor of direction `dir` by brute force: the section
/// cut into `slices` thin slices of constant E = Q̄(dir, dir) and G, the first moment S(z) of the
/// bending stiffness below z about the neutral axis summed slice by slice, and
/// k = (EI)² / (∫G dz · ∫S²/G dz) (the shear stress of cylindrical bending τ = Q S / EI carries
/// the energy of a constant shear strain over k ∫G dz).
double brute_force_shear_factor(const shell::Laminate& lam, int dir, int slices) {
  const double h = lam.thickness, dz = h / slices;
  auto ply_at = [&](double z) -> const shell::Ply& {
    for (const auto& p : lam.plies)
      if (z <= p.z_top) return p;
    return lam.plies.back();
  };
  double EA = 0, ES = 0, GA = 0;
  for (int i = 0; i < slices; ++i) {
    const double z = -h / 2 + (i + 0.5) * dz;
    const auto& p = ply_at(z);
    EA += p.Q(dir, dir) * dz, ES += p.Q(dir, dir) * z * dz, GA += p.G(dir, dir) * dz;
  }
  const double z0 = ES / EA;
  double EI = 0;
  for (int i = 0; i < slices; ++i) {
    const double z = -h / 2 + (i + 0.5) * dz;
    EI += ply_at(z).Q(dir, dir) * ((z - z0) * (z - z0) * dz + dz * dz * dz / 12);
  }
  double S = 0, energy = 0;
  for (int i = 0; i < slices; ++i) {
    const double z = -h / 2 + (i + 0.5) * dz;
    const auto& p = ply_at(z);
    const double half = 0.5 * p.Q(dir, dir) * (z - z0) * dz;  // S at the slice's middle
    energy += (S + half) * (S + half) / p.G(dir, dir) * dz;
    S += 2 * half;
  }
  return EI * EI / (GA * energy);
}

TEST(ShellLaminate, ShearCorrectionMatchesABruteForceEnergyBalance) {
  // A symmetric cross-ply, an unsymmetric two-ply (neutral axis off the middle) and a sandwich
  // (stiff thin faces, soft thick core): the factors far from 5/6 show the layering counts.
  const double t = 0.1;
  LayerElasticity face = isotropic(70e9, 0.3), core = isotropic(0.2e9, 0.3);
  core.G13 = core.G23 = 0.05e9;
  core.isotropic = false;
  std::vector<LayerInput> sandwich = {
      {0.1 * t, face, 0, 1, 3}, {0.8 * t, core, 0, 2, 3}, {0.1 * t, face, 0, 1, 3}};
  const std::vector<shell::Laminate> cases = {shell::make_laminate(layup({0, 90, 90, 0}, t, ply())),
                                              shell::make_laminate(layup({0, 90}, t, ply())),
                                              shell::make_laminate(sandwich)};
  for (const auto& lam : cases)
    for (int dir = 0; dir < 2; ++dir) {
      const double k = brute_force_shear_factor(lam, dir, 40000);
      EXPECT_NEAR(lam.shear_factor(dir), k, 1e-5 * k) << "direction " << dir;
      double GA = 0;
      for (const auto& p : lam.plies) GA += p.G(dir, dir) * (p.z_top - p.z_bot);
      EXPECT_NEAR(lam.shear(dir, dir), k * GA, 1e-5 * k * GA);
    }
  // The sandwich's core carries nearly all of the shear at a nearly uniform stress: k ≈ the
  // core's share of ∫G dz, far below 5/6.
  EXPECT_LT(cases[2].shear_factor(0), 0.2);
}

TEST(ShellLaminate, MinorPoissonRatioGivesTheMajorOne) {
  // MP,NUXY is the minor ratio (vm60: NUXY = 0.01, EX/EY = 25): ν12 = 0.25.
  Material m;
  m.props = {{"EX", 25e6}, {"EY", 1e6}, {"NUXY", 0.01}, {"GXY", 5e5}};
  const LayerElasticity e = shell::layer_elasticity(m, 1);
  EXPECT_NEAR(e.nu12, 0.25, 1e-12);
  EXPECT_EQ(e.G13, 5e5);
  EXPECT_FALSE(e.isotropic);
}

// ---- the layered SHELL281 -----------------------------------------------------------------

struct Mesh8 {
  std::map<int, Vec3> nodes;
  std::vector<std::vector<int>> elements;
};

Mesh8 rect_mesh(int nx, int ny, double lx, double ly) {
  Mesh8 m;
  auto id = [&](int i, int j) { return 1 + i + j * (2 * nx + 1); };
  for (int j = 0; j <= 2 * ny; ++j)
    for (int i = 0; i <= 2 * nx; ++i)
      if (i % 2 == 0 || j % 2 == 0)
        m.nodes[id(i, j)] = Vec3(lx * i / (2 * nx), ly * j / (2 * ny), 0);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = 2 * i, b = 2 * j;
      m.elements.push_back({id(a, b), id(a + 2, b), id(a + 2, b + 2), id(a, b + 2), id(a + 1, b),
                            id(a + 2, b + 1), id(a + 1, b + 2), id(a, b + 1)});
    }
  return m;
}

Shell281Data section_data(const std::vector<LayerInput>& layers, double t) {
  Shell281Data d;
  d.E = layers.front().elasticity.E1;
  d.nu = layers.front().elasticity.nu12;
  d.thickness.assign(8, t);
  if (layers.size() > 1 || !layers.front().elasticity.isotropic)
    d.laminate = shell::make_laminate(layers, d.shear_factor);
  return d;
}

std::vector<std::unique_ptr<Element>> build(const Mesh8& m, Shell281Data d) {
  std::vector<std::unique_ptr<Element>> out;
  int id = 1;
  for (const auto& e : m.elements) {
    d.node_ids = e;
    d.positions.clear();
    for (int n : e) d.positions.push_back(m.nodes.at(n));
    out.push_back(std::make_unique<Shell281>(id++, d, SourceLocation{"test", 1, "E"}));
  }
  return out;
}

Eigen::MatrixXd stiffness(const Element& e) {
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  e.tangent(ElementContext{}, Eigen::VectorXd::Zero(e.n_dofs()), K, f);
  return K;
}

TEST(ShellLaminate, TwoLayersOfOneMaterialAreTheHomogeneousShell) {
  const Mesh8 m = rect_mesh(1, 1, 2.0, 1.5);
  const double t = 0.1;
  const auto one = build(m, section_data(layup({0}, t, isotropic(2e11, 0.3)), t));
  auto layers = layup({0, 0}, t, isotropic(2e11, 0.3));
  layers[1].elasticity.isotropic = false;  // force the laminate path
  Shell281Data d = section_data(layers, t);
  ASSERT_FALSE(d.laminate.plies.empty());
  const auto two = build(m, d);
  const Eigen::MatrixXd K1 = stiffness(*one.front()), K2 = stiffness(*two.front());
  EXPECT_LT((K1 - K2).norm(), 1e-12 * K1.norm());
}

TEST(ShellLaminate, UnsymmetricElementCarriesTheCouplingMoment) {
  // A uniform stretch εx of a flat [0/90] element: N = A ε, M = B ε exactly (the field is in
  // the element's space), M_x = B11 εx ≠ 0.
  const double t = 0.2, eps = 1e-4;
  const auto layers = layup({0, 90}, t, ply());
  const auto lam = shell::make_laminate(layers);
  const Mesh8 m = rect_mesh(1, 1, 2.0, 1.0);
  const auto els = build(m, section_data(layers, t));
  Eigen::VectorXd u = Eigen::VectorXd::Zero(els.front()->n_dofs());
  const auto& nodes = m.elements.front();
  for (std::size_t a = 0; a < nodes.size(); ++a)
    u(static_cast<Eigen::Index>(6 * a)) = eps * m.nodes.at(nodes[a]).x();
  ElementResultValues r;
  els.front()->results(ElementContext{}, u, Eigen::VectorXd(), r);
  EXPECT_NEAR(r[0], lam.A(0, 0) * eps, 1e-9 * lam.A(0, 0) * eps);
  EXPECT_NEAR(r[1], lam.A(1, 0) * eps, 1e-9 * lam.A(0, 0) * eps);
  EXPECT_NEAR(r[3], lam.B(0, 0) * eps, 1e-9 * std::abs(lam.B(0, 0)) * eps);
  EXPECT_NEAR(r[4], lam.B(1, 0) * eps, 1e-9 * std::abs(lam.B(0, 0)) * eps);
  // Layer 1 (0°) and layer 2 (90°) stresses: Q̄ ε of each.
  const std::size_t l1 = Shell281::names().size(), l2 = l1 + 12;
  EXPECT_EQ(r.size(), Shell281::layered_names().size());
  EXPECT_NEAR(r[l1], lam.plies[0].Q(0, 0) * eps, 1e-6 * lam.plies[0].Q(0, 0) * eps);
  EXPECT_NEAR(r[l2], lam.plies[1].Q(0, 0) * eps, 1e-6 * lam.plies[0].Q(0, 0) * eps);
}

/// First-order shear deformation Navier series of the simply supported cross-ply plate under
/// uniform q (Reddy, Mechanics of Laminated Composite Plates and Shells, §6.3): the 3 × 3
/// system of each term for (W, X, Y), w at the centre.
double navier_centre(double a, const shell::Laminate& l, double q) {
  const Eigen::Matrix3d& D = l.D;
  double A44 = 0, A55 = 0;
  for (const auto& p : l.plies) {
    A55 += p.G(0, 0) * (p.z_top - p.z_bot);
    A44 += p.G(1, 1) * (p.z_top - p.z_bot);
  }
  A55 *= l.shear_factor(0);
  A44 *= l.shear_factor(1);
  double w = 0;
  for (int m = 1; m < 200; m += 2)
    for (int n = 1; n < 200; n += 2) {
      const double al = m * M_PI / a, be = n * M_PI / a;
      Eigen::Matrix3d S;
      S << A55 * al * al + A44 * be * be, A55 * al, A44 * be,  //
          A55 * al, D(0, 0) * al * al + D(2, 2) * be * be + A55, (D(0, 1) + D(2, 2)) * al * be,
          A44 * be, (D(0, 1) + D(2, 2)) * al * be, D(2, 2) * al * al + D(1, 1) * be * be + A44;
      const double Q = 16 * q / (M_PI * M_PI * m * n);
      const double W = S.lu().solve(Eigen::Vector3d(Q, 0, 0))(0);
      w += W * std::sin(m * M_PI / 2) * std::sin(n * M_PI / 2);
    }
  return w;
}

TEST(ShellLaminate, SimplySupportedCrossPlyPlateMatchesNavier) {
  // [0/90/90/0], a/t = 20 (E1/G13 = 50: shear deflection ~10 % of the bending one). 8 × 8.
  const double a = 1.0, t = 0.05, q = 1.0;
  const auto layers = layup({0, 90, 90, 0}, t, ply());
  const Shell281Data d = section_data(layers, t);
  const int n = 8;
  const Mesh8 m = rect_mesh(n, n, a, a);
  const auto els = build(m, d);
  DenseSystem s(els);
  std::set<DofKey> fixed;
  auto near = [](double x, double y) { return std::abs(x - y) < 1e-9; };
  for (const auto& [id, x] : m.nodes) {
    std::vector<Dof> dofs = {Dof::UX, Dof::UY, Dof::ROTZ};
    const bool ex = near(x.x(), 0) || near(x.x(), a), ey = near(x.y(), 0) || near(x.y(), a);
    if (ex || ey) dofs.push_back(Dof::UZ);
    if (ex) dofs.push_back(Dof::ROTX);
    if (ey) dofs.push_back(Dof::ROTY);
    for (Dof dof : dofs) fixed.insert({id, dof});
  }
  Eigen::VectorXd f = Eigen::VectorXd::Zero(s.n());
  for (const auto& e : els) {
    Eigen::VectorXd fe;
    e->pressure_load(ElementContext{}, 1, {q, q, q, q}, Eigen::VectorXd::Zero(e->n_dofs()), fe);
    for (int k = 0; k < e->n_dofs(); ++k) {
      const DofKey& key = e->dofs()[static_cast<std::size_t>(k)];
      f(s.index(key.node, key.dof)) += fe(k);
    }
  }
  const Eigen::VectorXd u = s.solve_static(f, fixed);
  const int centre = 1 + n + n * (2 * n + 1);
  const double w = u(s.index(centre, Dof::UZ));
  const double ref = navier_centre(a, d.laminate, q);
  std::printf("SS [0/90/90/0] plate a/t = 20: w = %.6e, Navier (FSDT) %.6e\n", w, ref);
  EXPECT_NEAR(w / ref, 1.0, 1.5e-2);
}

}  // namespace
}  // namespace impactfe::test_shell_laminate

namespace impactfe::test_shell_laminate {
namespace {

// ---- SHELL181's kernel with a symmetric laminate -------------------------------------------

TEST(ShellLaminate, KernelWithATwoLayerSectionIsTheHomogeneousKernel) {
  const std::vector<Eigen::Vector2d> xy = {{0, 0}, {2, 0.1}, {2.2, 1.5}, {-0.1, 1.2}};
  const double t = 0.1, E = 2e11, nu = 0.3;
  shell::KernelData one;
  one.E = E, one.nu = nu, one.mindlin = true, one.drill_factor = 1.0;
  one.t.fill(t);
  shell::KernelData two = one;
  two.laminate =
      std::make_shared<shell::Laminate>(shell::make_laminate(layup({0, 0}, t, isotropic(E, nu))));
  const Eigen::MatrixXd K1 = shell::FlatShellKernel(xy, one).stiffness();
  const Eigen::MatrixXd K2 = shell::FlatShellKernel(xy, two).stiffness();
  EXPECT_LT((K1 - K2).norm(), 1e-12 * K1.norm());
}

TEST(ShellLaminate, KernelBendingStiffnessIsTheLaminateD) {
  // A constant curvature κx of a [0/90/90/0] facet: M = D κ exactly (the field is in the space).
  const std::vector<Eigen::Vector2d> xy = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  const double t = 0.1, kx = 1e-3;
  shell::KernelData d;
  d.E = 25e6, d.nu = 0.25, d.mindlin = true, d.drill_factor = 1.0;
  d.t.fill(t);
  auto lam =
      std::make_shared<shell::Laminate>(shell::make_laminate(layup({0, 90, 90, 0}, t, ply())));
  d.laminate = lam;
  const shell::FlatShellKernel k(xy, d);
  // w = −κx x²/2, θy = −∂w/∂x = κx x (βx = θy: κx = ∂βx/∂x).
  Eigen::VectorXd u = Eigen::VectorXd::Zero(24);
  for (int a = 0; a < 4; ++a) {
    const double x = xy[static_cast<std::size_t>(a)].x();
    u(6 * a + 2) = -0.5 * kx * x * x;
    u(6 * a + 4) = kx * x;
  }
  const shell::Resultants r = k.resultants(u);
  EXPECT_NEAR(r.M(0), lam->D(0, 0) * kx, 1e-9 * lam->D(0, 0) * kx);
  EXPECT_NEAR(r.M(1), lam->D(1, 0) * kx, 1e-9 * lam->D(0, 0) * kx);
}

}  // namespace
}  // namespace impactfe::test_shell_laminate
