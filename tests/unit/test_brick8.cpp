// Unit tests of the SOLID45 / SOLID185 brick (src/elements/brick8.*): symmetry, rigid-body
// modes, mass, patch test, pure bending, total-Lagrangian tangent and objectivity, errors.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <memory>
#include <set>
#include <string>
#include <tuple>

#include "../support/dense_assembly.h"
#include "core/errors.h"
#include "elements/brick8.h"
#include "materials/isotropic_elasticity.h"

namespace impactfe::test_brick8 {
namespace {

constexpr double kE = 30e6;  // psi
constexpr double kNu = 0.3;
constexpr double kRho = 7.3e-4;  // lbf s²/in⁴

IsotropicElasticity steel() {
  return {kE, kNu, kRho};
}

std::array<Vec3, 8> box(double lx, double ly, double lz) {
  return {Vec3(0, 0, 0),  Vec3(lx, 0, 0),  Vec3(lx, ly, 0),  Vec3(0, ly, 0),
          Vec3(0, 0, lz), Vec3(lx, 0, lz), Vec3(lx, ly, lz), Vec3(0, ly, lz)};
}

/// A clearly non-affine hexahedron (no parallel faces).
std::array<Vec3, 8> distorted() {
  return {Vec3(0.1, -0.05, 0.0), Vec3(2.1, 0.2, -0.1), Vec3(2.3, 1.7, 0.15), Vec3(-0.2, 1.4, 0.05),
          Vec3(0.05, 0.1, 1.2),  Vec3(1.9, -0.1, 0.9), Vec3(2.0, 1.5, 1.3),  Vec3(0.2, 1.6, 1.0)};
}

constexpr std::array<int, 8> kDistinct = {1, 2, 3, 4, 5, 6, 7, 8};

/// Degenerate shapes from the spec §11.6: prism K = L, O = P; pyramid M = N = O = P;
/// tetrahedron K = L, M = N = O = P.
struct Shape {
  std::string name;
  std::array<int, 8> nodes;
  std::array<Vec3, 8> x;
  double volume;  // exact
  int n_nodes;
};

std::vector<Shape> degenerate_shapes() {
  const Vec3 o(0, 0, 0), a(2, 0, 0), b(0, 1.5, 0), c(0, 0, 1.2), ab(2, 1.5, 0), ac(2, 0, 1.2),
      bc(0, 1.5, 1.2), apex(0.9, 0.8, 1.1);
  return {
      // Right triangular prism: triangle (o, a, b), height 1.2.
      {"prism", {1, 2, 3, 3, 5, 6, 7, 7}, {o, a, b, b, c, ac, bc, bc}, 0.5 * 2 * 1.5 * 1.2, 6},
      // Pyramid on the 2 x 1.5 rectangle, apex height 1.1.
      {"pyramid",
       {1, 2, 3, 4, 5, 5, 5, 5},
       {o, a, ab, b, apex, apex, apex, apex},
       2 * 1.5 * 1.1 / 3,
       5},
      // Tetrahedron (o, a, b, c).
      {"tetrahedron", {1, 2, 3, 3, 5, 5, 5, 5}, {o, a, b, b, c, c, c, c}, 2 * 1.5 * 1.2 / 6, 4},
  };
}

Eigen::MatrixXd stiffness(const Element& e, const ElementContext& ctx = {}) {
  Eigen::MatrixXd k;
  Eigen::VectorXd f;
  e.tangent(ctx, Eigen::VectorXd::Zero(e.n_dofs()), k, f);
  return k;
}

int count_zero_eigenvalues(const Eigen::MatrixXd& k, double* next_ratio) {
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(k).eigenvalues();
  const double top = ev.cwiseAbs().maxCoeff();
  int zeros = 0;
  for (int i = 0; i < ev.size(); ++i)
    if (std::abs(ev(i)) < 1e-10 * top) ++zeros;
  if (next_ratio) *next_ratio = ev(zeros) / top;
  return zeros;
}

TEST(Brick8, StiffnessIsSymmetric) {
  for (bool extra : {false, true}) {
    const Brick8 e(1, kDistinct, distorted(), steel(), extra);
    EXPECT_EQ(e.extra_shapes(), extra);
    const Eigen::MatrixXd k = stiffness(e);
    ASSERT_EQ(k.rows(), 24);
    EXPECT_LE((k - k.transpose()).cwiseAbs().maxCoeff(), 1e-13 * k.cwiseAbs().maxCoeff());
  }
}

TEST(Brick8, DistortedBrickHasExactlySixRigidBodyModes) {
  for (bool extra : {false, true}) {
    const Brick8 e(1, kDistinct, distorted(), steel(), extra);
    double next = 0.0;
    EXPECT_EQ(count_zero_eigenvalues(stiffness(e), &next), 6) << "extra shapes " << extra;
    EXPECT_GT(next, 1e-6);  // no spurious (hourglass) mode
  }
}

TEST(Brick8, DegenerateShapesHaveSixRigidBodyModesAndNoExtraShapes) {
  for (const Shape& s : degenerate_shapes()) {
    const Brick8 e(1, s.nodes, s.x, steel(), /*extra_shapes=*/true);
    EXPECT_TRUE(e.degenerate()) << s.name;
    EXPECT_FALSE(e.extra_shapes()) << s.name;
    ASSERT_EQ(e.n_dofs(), 3 * s.n_nodes) << s.name;
    double next = 0.0;
    const Eigen::MatrixXd k = stiffness(e);
    EXPECT_LE((k - k.transpose()).cwiseAbs().maxCoeff(), 1e-13 * k.cwiseAbs().maxCoeff());
    EXPECT_EQ(count_zero_eigenvalues(k, &next), 6) << s.name;
    EXPECT_GT(next, 1e-6) << s.name;
  }
}

double total_mass(const Eigen::MatrixXd& m, int dir) {
  Eigen::VectorXd t = Eigen::VectorXd::Zero(m.rows());
  for (int i = dir; i < m.rows(); i += 3) t(i) = 1.0;
  return t.dot(m * t);
}

TEST(Brick8, MassSumsToDensityTimesVolume) {
  // Parallelepiped: volume = |det of the edge vectors|.
  const Eigen::Matrix3d edges =
      (Eigen::Matrix3d() << 2, 0.3, 0.1, 0.2, 1.5, -0.2, 0.1, 0.4, 1.2).finished();
  std::array<Vec3, 8> para;
  for (int c = 0; c < 8; ++c) {
    const Vec3 s = box(1, 1, 1)[c];
    para[c] = edges.col(0) * s(0) + edges.col(1) * s(1) + edges.col(2) * s(2);
  }
  std::vector<Shape> shapes = degenerate_shapes();
  shapes.push_back({"parallelepiped", kDistinct, para, std::abs(edges.determinant()), 8});
  for (const Shape& s : shapes) {
    const Brick8 e(1, s.nodes, s.x, steel(), true);
    EXPECT_NEAR(*e.volume(), s.volume, 1e-12 * s.volume) << s.name;
    for (bool lumped : {false, true}) {
      ElementContext ctx;
      ctx.lumped_mass = lumped;
      Eigen::MatrixXd m;
      e.mass(ctx, m);
      ASSERT_EQ(m.rows(), e.n_dofs());
      EXPECT_LE((m - m.transpose()).cwiseAbs().maxCoeff(), 1e-15 * m.cwiseAbs().maxCoeff());
      for (int dir = 0; dir < 3; ++dir)
        EXPECT_NEAR(total_mass(m, dir), kRho * s.volume, 1e-12 * kRho * s.volume)
            << s.name << " lumped " << lumped;
      if (lumped) {
        EXPECT_NEAR((m - Eigen::MatrixXd(m.diagonal().asDiagonal())).cwiseAbs().maxCoeff(), 0.0,
                    0.0);
        EXPECT_GT(m.diagonal().minCoeff(), 0.0) << s.name;
      }
    }
  }
  // Regular brick: HRZ gives ρV/8 per node and direction.
  const Brick8 e(1, kDistinct, box(2, 1, 0.5), steel(), true);
  ElementContext ctx;
  ctx.lumped_mass = true;
  Eigen::MatrixXd m;
  e.mass(ctx, m);
  for (int i = 0; i < 24; ++i) EXPECT_NEAR(m(i, i), kRho * 1.0 / 8, 1e-14);
}

// ---- patch test ---------------------------------------------------------------------------

/// Solves K u = 0 with the listed DOFs prescribed (indices into the DenseSystem numbering).
Eigen::VectorXd solve_prescribed(const Eigen::MatrixXd& k, const std::map<int, double>& fixed) {
  const int n = static_cast<int>(k.rows());
  std::vector<int> free;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < n; ++i) {
    const auto it = fixed.find(i);
    if (it == fixed.end())
      free.push_back(i);
    else
      u(i) = it->second;
  }
  const int nf = static_cast<int>(free.size());
  Eigen::MatrixXd kff(nf, nf);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(nf);
  for (int a = 0; a < nf; ++a) {
    for (int b = 0; b < nf; ++b) kff(a, b) = k(free[a], free[b]);
    for (const auto& [j, value] : fixed) rhs(a) -= k(free[a], j) * value;
  }
  const Eigen::VectorXd uf = kff.ldlt().solve(rhs);
  for (int a = 0; a < nf; ++a) u(free[a]) = uf(a);
  return u;
}

Eigen::VectorXd element_vector(const Element& e, const testing::DenseSystem& sys,
                               const Eigen::VectorXd& u) {
  Eigen::VectorXd ue(e.n_dofs());
  for (int a = 0; a < e.n_dofs(); ++a) ue(a) = u(sys.index(e.dofs()[a].node, e.dofs()[a].dof));
  return ue;
}

void run_patch_test(bool extra_shapes) {
  // MacNeal & Harder (1985) solid patch: unit cube, distorted inner hexahedron, 7 elements.
  std::map<int, Vec3> x;
  const std::array<Vec3, 8> outer = box(1, 1, 1);
  const std::array<Vec3, 8> inner = {Vec3(0.249, 0.342, 0.192), Vec3(0.826, 0.288, 0.288),
                                     Vec3(0.850, 0.649, 0.263), Vec3(0.273, 0.750, 0.230),
                                     Vec3(0.320, 0.186, 0.643), Vec3(0.677, 0.305, 0.683),
                                     Vec3(0.788, 0.693, 0.644), Vec3(0.165, 0.745, 0.702)};
  for (int c = 0; c < 8; ++c) {
    x[c + 1] = outer[c];   // outer nodes 1..8
    x[c + 11] = inner[c];  // inner nodes 11..18
  }
  const std::vector<std::array<int, 8>> conn = {
      {11, 12, 13, 14, 15, 16, 17, 18},  // inner
      {1, 2, 3, 4, 11, 12, 13, 14},      // z = 0
      {15, 16, 17, 18, 5, 6, 7, 8},      // z = 1
      {1, 2, 12, 11, 5, 6, 16, 15},      // y = 0
      {14, 13, 3, 4, 18, 17, 7, 8},      // y = 1
      {1, 11, 14, 4, 5, 15, 18, 8},      // x = 0
      {12, 2, 3, 13, 16, 6, 7, 17},      // x = 1
  };
  std::vector<std::unique_ptr<Element>> elements;
  for (std::size_t i = 0; i < conn.size(); ++i) {
    std::array<Vec3, 8> xe;
    for (int c = 0; c < 8; ++c) xe[c] = x[conn[i][c]];
    elements.push_back(
        std::make_unique<Brick8>(static_cast<int>(i + 1), conn[i], xe, steel(), extra_shapes));
  }
  const testing::DenseSystem sys(elements);
  // Linear field u = A x with a full (non-symmetric) gradient.
  Eigen::Matrix3d grad;
  grad << 1.0e-3, 0.5e-3, 0.5e-3, 0.2e-3, 1.0e-3, -0.4e-3, 0.5e-3, 0.3e-3, -0.8e-3;
  auto exact = [&](int node) -> Vec3 { return grad * x[node]; };
  std::map<int, double> fixed;
  for (int node = 1; node <= 8; ++node)
    for (Dof d : {Dof::UX, Dof::UY, Dof::UZ})
      fixed[sys.index(node, d)] = exact(node)(static_cast<int>(d));
  const Eigen::VectorXd u = solve_prescribed(sys.K, fixed);
  for (int node = 11; node <= 18; ++node)
    for (Dof d : {Dof::UX, Dof::UY, Dof::UZ})
      EXPECT_NEAR(u(sys.index(node, d)), exact(node)(static_cast<int>(d)), 1e-14)
          << "node " << node;
  // Constant stress D ε in every element (1e-9 relative: ε ~ 1e-3, σ ~ 3e4).
  Vector6d eps;
  eps << grad(0, 0), grad(1, 1), grad(2, 2), grad(0, 1) + grad(1, 0), grad(1, 2) + grad(2, 1),
      grad(0, 2) + grad(2, 0);
  const Vector6d sigma = isotropic_elasticity_matrix(kE, kNu) * eps;
  for (const auto& e : elements) {
    const auto& b = dynamic_cast<const Brick8&>(*e);
    const Vector6d s = b.centroid_stress({}, element_vector(*e, sys, u));
    EXPECT_LE((s - sigma).cwiseAbs().maxCoeff(), 1e-9 * sigma.cwiseAbs().maxCoeff())
        << "element " << e->id();
  }
  // Total Lagrangian: a homogeneous finite deformation (strains ~ 10 %, plus a 60° rotation)
  // leaves the inner nodes in equilibrium: their assembled internal forces vanish.
  ElementContext tl;
  tl.large_deflection = true;
  const Eigen::Matrix3d big =
      Eigen::AngleAxisd(M_PI / 3, Vec3(0.2, 0.5, 1).normalized()).toRotationMatrix() *
          (Eigen::Matrix3d::Identity() + 100.0 * grad) -
      Eigen::Matrix3d::Identity();
  Eigen::VectorXd fsum = Eigen::VectorXd::Zero(sys.n());
  for (const auto& e : elements) {
    Eigen::VectorXd ue(e->n_dofs());
    for (int a = 0; a < e->n_dofs(); ++a) {
      const DofKey& key = e->dofs()[a];
      ue(a) = (big * x[key.node])(static_cast<int>(key.dof));
    }
    Eigen::MatrixXd ke;
    Eigen::VectorXd fe;
    e->tangent(tl, ue, ke, fe);
    for (int a = 0; a < e->n_dofs(); ++a)
      fsum(sys.index(e->dofs()[a].node, e->dofs()[a].dof)) += fe(a);
  }
  const double fmax = fsum.cwiseAbs().maxCoeff();
  for (int node = 11; node <= 18; ++node)
    for (Dof d : {Dof::UX, Dof::UY, Dof::UZ})
      EXPECT_LE(std::abs(fsum(sys.index(node, d))), 1e-10 * fmax) << "TL, node " << node;
}

TEST(Brick8, DistortedSevenElementPatchReproducesConstantStrain) {
  SCOPED_TRACE("extra shapes (Taylor's modification)");
  run_patch_test(true);
}

TEST(Brick8, DistortedSevenElementPatchWithoutExtraShapes) {
  run_patch_test(false);
}

// ---- pure bending -------------------------------------------------------------------------

/// One L x h x b element, end moment applied as the consistent nodal forces of σxx = s (2y/h)
/// at x = L (and the opposite at x = 0); returns (end rotation ratio, deflection ratio) relative
/// to the exact 3-D pure-bending solution u = -κxy, v = κ(x² + ν(y² - z²))/2, w = κνyz.
std::pair<double, double> pure_bending(bool extra, double length) {
  const double h = 1.0, b = 0.8, s = 1000.0;
  std::array<Vec3, 8> x = box(length, h, b);
  for (auto& p : x) p -= Vec3(0, h / 2, b / 2);
  std::vector<std::unique_ptr<Element>> elements;
  elements.push_back(std::make_unique<Brick8>(1, kDistinct, x, steel(), extra));
  const testing::DenseSystem sys(elements);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(sys.n());
  const double nodal = s * h * b / 12.0;  // linear traction on a bilinear face
  for (int c = 0; c < 8; ++c) {
    const double sign_y = x[c](1) > 0 ? 1.0 : -1.0;
    const double sign_x = x[c](0) > 0 ? 1.0 : -1.0;
    f(sys.index(c + 1, Dof::UX)) = sign_x * sign_y * nodal;
  }
  // x = 0 face: UX fixed (exact u = 0 there); UY at two nodes, UZ at one (rigid body only).
  std::set<DofKey> fixed = {{1, Dof::UX}, {4, Dof::UX}, {5, Dof::UX}, {8, Dof::UX},
                            {1, Dof::UY}, {5, Dof::UY}, {1, Dof::UZ}};
  const Eigen::VectorXd u = sys.solve_static(f, fixed);
  const double kappa = s / (kE * h / 2);  // σ = -E κ y at the top fibre magnitude
  const double rot = u(sys.index(7, Dof::UX)) - u(sys.index(6, Dof::UX));
  const double defl = 0.5 * (u(sys.index(6, Dof::UY)) + u(sys.index(7, Dof::UY)) -
                             u(sys.index(1, Dof::UY)) - u(sys.index(4, Dof::UY)));
  return {rot / (kappa * length * h), defl / (-kappa * length * length / 2)};
}

TEST(Brick8, ExtraShapesGiveExactPureBending) {
  for (double length : {1.0, 4.0}) {
    const auto [rot, defl] = pure_bending(true, length);
    EXPECT_NEAR(rot, 1.0, 1e-10) << "L/h = " << length;
    EXPECT_NEAR(defl, 1.0, 1e-10) << "L/h = " << length;
  }
}

TEST(Brick8, WithoutExtraShapesPureBendingIsTooStiff) {
  // Parasitic shear of the trilinear brick: at L/h = 4 it recovers well under half the rotation.
  const auto [rot, defl] = pure_bending(false, 4.0);
  EXPECT_LT(rot, 0.5);
  EXPECT_GT(rot, 0.0);
  EXPECT_LT(defl, 0.5);
}

// ---- stresses -----------------------------------------------------------------------------

TEST(Brick8, NodalStressesOfPureBendingAreTheExactLinearField) {
  // With the incompatible modes (SOLID185 KEYOPT(2) = 2 or 3, SOLID45) a rectangular brick
  // bends exactly, so its Gauss points carry σx = −Eκy: the corners must get it at their own y
  // (±Eκh/2), where the centroid value is 0. The plain brick (parasitic shear) and the B-bar
  // brick extrapolate their own Gauss-point values.
  const double h = 1.0, kappa = 1e-4;
  std::array<Vec3, 8> x = box(2.0, h, 0.8);
  for (auto& p : x) p -= Vec3(0, h / 2, 0.4);
  Eigen::VectorXd u(24);
  for (int c = 0; c < 8; ++c)
    u.segment<3>(3 * c) =
        Vec3(-kappa * x[c](0) * x[c](1),
             0.5 * kappa * (x[c](0) * x[c](0) + kNu * (x[c](1) * x[c](1) - x[c](2) * x[c](2))),
             kNu * kappa * x[c](1) * x[c](2));
  for (BrickStrain strain : {BrickStrain::Standard, BrickStrain::Enhanced}) {
    const Brick8 e(1, kDistinct, x, steel(), true, {}, std::nullopt, false, strain);
    std::map<int, ElementResultValues> at;
    ASSERT_TRUE(e.nodal_results({}, u, at));
    ASSERT_EQ(at.size(), 8u);
    for (int c = 0; c < 8; ++c) {
      const ElementResultValues& r = at.at(c + 1);
      EXPECT_NEAR(r[0], -kE * kappa * x[c](1), 1e-9 * kE * kappa) << "corner " << c + 1;
      for (int i = 1; i < 6; ++i)
        EXPECT_NEAR(r[static_cast<std::size_t>(i)], 0.0, 1e-9 * kE * kappa);
    }
  }
  // Plastic, large-deflection and degenerate bricks keep their element values.
  const Brick8 plain(1, kDistinct, x, steel(), false);
  std::map<int, ElementResultValues> at;
  EXPECT_TRUE(plain.nodal_results({}, u, at));
  EXPECT_FALSE(plain.nodal_results({true, false, false}, u, at));
  const Shape prism = degenerate_shapes()[0];
  const Brick8 collapsed(1, prism.nodes, prism.x, steel(), false);
  EXPECT_FALSE(collapsed.nodal_results({}, Eigen::VectorXd::Zero(collapsed.n_dofs()), at));
}

TEST(Brick8, UniaxialStressResults) {
  const Brick8 e(1, kDistinct, distorted(), steel(), true);
  const double eps = 1e-3;
  const auto x = distorted();
  Eigen::VectorXd u(24);
  for (int c = 0; c < 8; ++c)
    u.segment<3>(3 * c) = Vec3(eps * x[c](0), -kNu * eps * x[c](1), -kNu * eps * x[c](2));
  ElementResultValues r;
  e.results({}, u, Eigen::VectorXd::Zero(24), r);
  ASSERT_EQ(r.size(), e.result_names().size());
  const double sx = kE * eps;
  const double tol = 1e-9 * sx;
  EXPECT_NEAR(r[0], sx, tol);                                // SX
  for (int i = 1; i <= 5; ++i) EXPECT_NEAR(r[i], 0.0, tol);  // SY SZ SXY SYZ SXZ
  EXPECT_NEAR(r[6], sx, tol);                                // S1
  EXPECT_NEAR(r[7], 0.0, tol);                               // S2
  EXPECT_NEAR(r[8], 0.0, tol);                               // S3
  EXPECT_NEAR(r[9], sx, tol);                                // SINT
  EXPECT_NEAR(r[10], sx, tol);                               // SEQV
}

TEST(Brick8, StressStiffnessOfATautBlockIsStringLike) {
  // Under σxx = T, the geometric stiffness of a transverse shear field v = θx stores
  // ½ T θ² V (Cook §18.2): qᵀ K_σ q = T θ² V.
  const auto x = box(2, 1, 0.5);
  const Brick8 e(1, kDistinct, x, steel(), true);
  const double eps = 1e-3;
  Eigen::VectorXd u(24), q(24);
  for (int c = 0; c < 8; ++c) {
    u.segment<3>(3 * c) = Vec3(eps * x[c](0), -kNu * eps * x[c](1), -kNu * eps * x[c](2));
    q.segment<3>(3 * c) = Vec3(0, 0.01 * x[c](0), 0);
  }
  ElementContext ss;
  ss.stress_stiffening = true;
  EXPECT_TRUE(e.is_nonlinear(ss));
  EXPECT_FALSE(e.is_nonlinear({}));
  Eigen::MatrixXd k0, ks;
  Eigen::VectorXd f0, fs;
  e.tangent({}, u, k0, f0);
  e.tangent(ss, u, ks, fs);
  const double expected = kE * eps * 0.01 * 0.01 * *e.volume();
  EXPECT_NEAR(q.dot((ks - k0) * q), expected, 1e-10 * expected);
  // f_int carries the stress stiffness of the current stress: f = (K + K_σ) u.
  EXPECT_LE((fs - ks * u).norm(), 1e-10 * fs.norm());
}

// ---- large deflection (total Lagrangian) --------------------------------------------------

Eigen::VectorXd internal_force(const Element& e, const ElementContext& ctx,
                               const Eigen::VectorXd& u) {
  Eigen::MatrixXd k;
  Eigen::VectorXd f;
  e.tangent(ctx, u, k, f);
  return f;
}

void expect_tangent_matches_finite_difference(const Brick8& e, const Eigen::VectorXd& u) {
  ElementContext ctx;
  ctx.large_deflection = true;
  Eigen::MatrixXd k;
  Eigen::VectorXd f;
  e.tangent(ctx, u, k, f);
  const int n = e.n_dofs();
  Eigen::MatrixXd kfd(n, n);
  const double h = 1e-6;
  for (int j = 0; j < n; ++j) {
    Eigen::VectorXd up = u, um = u;
    up(j) += h;
    um(j) -= h;
    kfd.col(j) = (internal_force(e, ctx, up) - internal_force(e, ctx, um)) / (2 * h);
  }
  // Central differences: truncation ~h², round-off ~1e-16 |f| / h; 1e-6 relative covers both.
  EXPECT_LE((k - kfd).cwiseAbs().maxCoeff(), 1e-6 * k.cwiseAbs().maxCoeff());
  EXPECT_LE((k - k.transpose()).cwiseAbs().maxCoeff(), 1e-12 * k.cwiseAbs().maxCoeff());
}

Eigen::VectorXd large_displacement(int n) {
  Eigen::VectorXd u(n);
  for (int i = 0; i < n; ++i) u(i) = 0.15 * std::sin(1.7 * i + 0.3);  // strains ~ 10-30 %
  return u;
}

TEST(Brick8, TotalLagrangianTangentMatchesFiniteDifference) {
  for (bool extra : {false, true}) {
    SCOPED_TRACE(extra ? "extra shapes" : "no extra shapes");
    const Brick8 e(1, kDistinct, distorted(), steel(), extra);
    expect_tangent_matches_finite_difference(e, large_displacement(24));
  }
  for (const Shape& s : degenerate_shapes()) {
    SCOPED_TRACE(s.name);
    const Brick8 e(1, s.nodes, s.x, steel(), true);
    expect_tangent_matches_finite_difference(e, large_displacement(e.n_dofs()));
  }
}

TEST(Brick8, InternalForceAloneIsBitwiseTheForceOfTheTangent) {
  // Element::internal_force serves the residuals that need no tangent (issue 11): the same
  // numbers as tangent()'s f_int, in every form of the element.
  ElementContext small, tl;
  tl.large_deflection = true;
  std::vector<std::unique_ptr<Brick8>> bricks;
  for (bool extra : {false, true})
    bricks.push_back(std::make_unique<Brick8>(1, kDistinct, distorted(), steel(), extra));
  for (const Shape& s : degenerate_shapes())
    bricks.push_back(std::make_unique<Brick8>(1, s.nodes, s.x, steel(), true));
  for (const auto& brick : bricks)
    for (const ElementContext& ctx : {small, tl}) {
      const Brick8& e = *brick;
      const Eigen::VectorXd u = large_displacement(e.n_dofs());
      Eigen::VectorXd f;
      e.internal_force(ctx, u, f);
      EXPECT_EQ(f, internal_force(e, ctx, u));
    }
  // The force has a path of its own only where it saves the stiffness sums.
  EXPECT_TRUE(bricks[0]->separate_internal_force(tl));
  EXPECT_FALSE(bricks[0]->separate_internal_force(small));
  EXPECT_FALSE(bricks[1]->separate_internal_force(tl));  // extra shapes: bubbles solved with K
}

TEST(Brick8, KeptModeRecoveryGivesTheSameAnswersAsFormedOnDemand) {
  // Built for large deflection (or plastic) a brick with extra shapes keeps the mode recovery
  // α = R u_c its tangent reads at every iteration; otherwise it forms R when asked (issue 11:
  // memory). Linear, stress-stiffened and total-Lagrangian tangents must agree bitwise.
  ElementContext linear, stiffened, large;
  stiffened.stress_stiffening = true;
  large.large_deflection = true;
  const Brick8 formed(1, kDistinct, distorted(), steel(), true);
  const Brick8 kept(1, kDistinct, distorted(), steel(), true, {}, std::nullopt, true);
  const Eigen::VectorXd u = large_displacement(24);
  for (const ElementContext& ctx : {linear, stiffened, large}) {
    Eigen::MatrixXd k_formed, k_kept;
    Eigen::VectorXd f_formed, f_kept;
    formed.tangent(ctx, u, k_formed, f_formed);
    kept.tangent(ctx, u, k_kept, f_kept);
    EXPECT_EQ(k_formed, k_kept);
    EXPECT_EQ(f_formed, f_kept);
    EXPECT_GT(k_kept.norm(), 0.0);
  }
  // A plastic brick keeps R and its Gauss points' states: the same answers through a yielding
  // step and its commit whether or not it was built for large deflection.
  const auto law = J2Plasticity::bilinear(kE, kNu, 36e3, 0.1 * kE, false);
  Brick8 plastic_a(1, kDistinct, distorted(), steel(), true, {}, law);
  Brick8 plastic_b(1, kDistinct, distorted(), steel(), true, {}, law, true);
  const Eigen::VectorXd u_yield = 0.01 * large_displacement(24);
  plastic_a.commit_history(linear, u_yield);
  plastic_b.commit_history(linear, u_yield);
  EXPECT_GT(plastic_a.plastic_work(), 0.0);
  EXPECT_EQ(plastic_a.history_state(), plastic_b.history_state());
}

TEST(Brick8, TotalLagrangianReducesToLinearAtZeroDisplacement) {
  ElementContext tl;
  tl.large_deflection = true;
  for (bool extra : {false, true}) {
    const Brick8 e(1, kDistinct, distorted(), steel(), extra);
    const Eigen::MatrixXd k0 = stiffness(e), k1 = stiffness(e, tl);
    EXPECT_LE((k0 - k1).cwiseAbs().maxCoeff(), 1e-12 * k0.cwiseAbs().maxCoeff());
  }
}

Eigen::Matrix3d rotation(const Vec3& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

TEST(Brick8, RigidRotationGivesZeroInternalForce) {
  ElementContext tl;
  tl.large_deflection = true;
  Eigen::Matrix3d rz90;
  rz90 << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  const auto x = distorted();
  for (bool extra : {false, true}) {
    const Brick8 e(1, kDistinct, x, steel(), extra);
    const double scale = kE * 4.0;  // E times a face area: force of a unit strain
    for (const Eigen::Matrix3d& r : {Eigen::Matrix3d(rz90), rotation(Vec3(1, 1, 1), M_PI / 2),
                                     rotation(Vec3(0.3, -1, 0.5), 2.5)}) {
      Eigen::VectorXd u(24);
      for (int c = 0; c < 8; ++c) u.segment<3>(3 * c) = (r - Eigen::Matrix3d::Identity()) * x[c];
      EXPECT_LE(internal_force(e, tl, u).norm(), 1e-12 * scale) << "extra " << extra;
      ElementResultValues res;
      e.results(tl, u, u, res);
      for (double v : res) EXPECT_LE(std::abs(v), 1e-12 * kE);
      // The linear element, by contrast, sees spurious strain under a finite rotation.
      EXPECT_GT(internal_force(e, {}, u).norm(), 1e-3 * scale);
    }
  }
}

TEST(Brick8, RotatedStretchGivesRotatedCauchyStress) {
  // F = R_z(90°) diag(λ, 1, 1): S11 = (λ_L + 2μ)(λ² - 1)/2, S22 = S33 = λ_L (λ² - 1)/2;
  // σ = F S Fᵀ / det F puts λ S11 on yy and S33/λ on xx and zz.
  const double lam = 1.2;
  const auto x = distorted();
  const Brick8 e(1, kDistinct, x, steel(), true);
  Eigen::Matrix3d f;
  f << 0, -1, 0, lam, 0, 0, 0, 0, 1;
  Eigen::VectorXd u(24);
  for (int c = 0; c < 8; ++c) u.segment<3>(3 * c) = (f - Eigen::Matrix3d::Identity()) * x[c];
  ElementContext tl;
  tl.large_deflection = true;
  const Vector6d s = e.centroid_stress(tl, u);
  const double lame = kE * kNu / ((1 + kNu) * (1 - 2 * kNu)), mu = kE / (2 * (1 + kNu));
  const double green = 0.5 * (lam * lam - 1);
  const double tol = 1e-10 * kE;
  EXPECT_NEAR(s(1), lam * (lame + 2 * mu) * green, tol);
  EXPECT_NEAR(s(0), lame * green / lam, tol);
  EXPECT_NEAR(s(2), lame * green / lam, tol);
  EXPECT_NEAR(s.tail<3>().cwiseAbs().maxCoeff(), 0.0, tol);
  // A homogeneous deformation is in equilibrium inside: f_int balances only boundary tractions,
  // so the sum of the nodal forces is zero.
  const Eigen::VectorXd fi = internal_force(e, tl, u);
  Vec3 sum = Vec3::Zero();
  for (int c = 0; c < 8; ++c) sum += fi.segment<3>(3 * c);
  EXPECT_LE(sum.norm(), 1e-9 * fi.norm());
}

// ---- input errors -------------------------------------------------------------------------

TEST(Brick8, InvertedElementIsAnInputErrorNamingTheElement) {
  auto x = box(1, 1, 1);
  std::swap(x[0], x[4]);  // I..L and M..P exchanged on one corner
  std::swap(x[1], x[5]);
  std::swap(x[2], x[6]);
  std::swap(x[3], x[7]);
  SourceLocation where{"deck.inp", 12, "E"};
  try {
    Brick8 e(42, kDistinct, x, steel(), true, where);
    FAIL() << "no error";
  } catch (const InputError& err) {
    EXPECT_NE(err.message().find("element 42"), std::string::npos) << err.what();
    EXPECT_NE(err.message().find("Jacobian"), std::string::npos) << err.what();
    EXPECT_EQ(err.where().line, 12);
  }
  // Flat element (all nodes in one plane).
  auto flat = box(1, 1, 1);
  for (int c = 4; c < 8; ++c) flat[c](2) = 0.0;
  EXPECT_THROW(Brick8(3, kDistinct, flat, steel(), true), InputError);
}

Model brick_model(const std::string& type_name, int keyopt1, int keyopt2, bool with_ex) {
  Model m;
  const auto x = box(1, 1, 1);
  for (int c = 0; c < 8; ++c) m.nodes[c + 1] = Node{c + 1, x[c], Vec3::Zero()};
  ElementType t;
  t.id = 1;
  t.ansys_name = type_name;
  t.keyopt[1] = keyopt1;
  t.keyopt[2] = keyopt2;
  m.element_types[1] = t;
  Material mat;
  mat.id = 1;
  if (with_ex) mat.props["EX"] = kE;
  mat.props["DENS"] = kRho;
  m.materials[1] = mat;
  ElementRecord rec;
  rec.id = 5;
  rec.nodes = {1, 2, 3, 4, 5, 6, 7, 8};
  rec.where = SourceLocation{"deck.inp", 30, "E"};
  m.elements[5] = rec;
  return m;
}

bool built_with_extra_shapes(const Model& m) {
  const ElementBuildContext ctx{m, nullptr};
  const auto e = create_element(ctx, m.elements.at(5));
  return dynamic_cast<const Brick8&>(*e).extra_shapes();
}

TEST(Brick8, KeyoptsSelectExtraShapes) {
  EXPECT_TRUE(built_with_extra_shapes(brick_model("SOLID45", 0, 0, true)));
  EXPECT_FALSE(built_with_extra_shapes(brick_model("SOLID45", 1, 0, true)));  // ET,2,45,1
  EXPECT_TRUE(built_with_extra_shapes(brick_model("SOLID185", 0, 3, true)));
  EXPECT_FALSE(built_with_extra_shapes(brick_model("SOLID185", 0, 0, true)));
  // KEYOPT(2) = 2: the incompatible modes plus 4 enhanced volumetric strains.
  EXPECT_TRUE(built_with_extra_shapes(brick_model("SOLID185", 0, 2, true)));
  for (const auto& [keyopt2, strain, internal] :
       {std::tuple{0, BrickStrain::BBar, 0}, std::tuple{2, BrickStrain::Enhanced, 13},
        std::tuple{3, BrickStrain::Standard, 9}}) {
    const Model m = brick_model("SOLID185", 0, keyopt2, true);
    const auto e = create_element(ElementBuildContext{m, nullptr}, m.elements.at(5));
    EXPECT_EQ(dynamic_cast<const Brick8&>(*e).strain(), strain) << keyopt2;
    EXPECT_EQ(dynamic_cast<const Brick8&>(*e).n_internal(), internal) << keyopt2;
  }
  EXPECT_THROW(built_with_extra_shapes(brick_model("SOLID185", 0, 5, true)), InputError);
  // Default NUXY = 0.3 and DENS are read: the mass is ρ for the unit cube.
  const Model m = brick_model("SOLID45", 0, 0, true);
  const auto e = create_element(ElementBuildContext{m, nullptr}, m.elements.at(5));
  Eigen::MatrixXd mass;
  e->mass({}, mass);
  EXPECT_NEAR(total_mass(mass, 0), kRho, 1e-15);
  EXPECT_EQ(e->family(), std::string("Brick8"));
}

TEST(Brick8, MissingYoungsModulusIsAnInputError) {
  const Model m = brick_model("SOLID45", 0, 0, false);
  try {
    create_element(ElementBuildContext{m, nullptr}, m.elements.at(5));
    FAIL() << "no error";
  } catch (const InputError& err) {
    EXPECT_NE(err.message().find("EX"), std::string::npos) << err.what();
    EXPECT_NE(err.message().find("element 5"), std::string::npos) << err.what();
    EXPECT_EQ(err.where().line, 30);
  }
}

}  // namespace
}  // namespace impactfe::test_brick8
