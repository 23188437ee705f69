// SOLID185 element technologies of the brick (src/elements/brick8.*): B-bar (KEYOPT(2) = 0) and
// enhanced strain (KEYOPT(2) = 2) against the patch test, rigid-body modes, the thick-walled
// cylinder (Lamé) for nearly incompressible material and a cantilever against beam theory.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <string>

#include "../support/dense_assembly.h"
#include "elements/brick8.h"
#include "elements/element_registry.h"
#include "materials/isotropic_elasticity.h"
#include "materials/j2_plasticity.h"

namespace impactfe::test_brick8_technologies {
namespace {

constexpr double kE = 30e6;  // psi
constexpr std::array<int, 8> kDistinct = {1, 2, 3, 4, 5, 6, 7, 8};

std::array<Vec3, 8> distorted() {
  return {Vec3(0.1, -0.05, 0.0), Vec3(2.1, 0.2, -0.1), Vec3(2.3, 1.7, 0.15), Vec3(-0.2, 1.4, 0.05),
          Vec3(0.05, 0.1, 1.2),  Vec3(1.9, -0.1, 0.9), Vec3(2.0, 1.5, 1.3),  Vec3(0.2, 1.6, 1.0)};
}

Eigen::MatrixXd stiffness(const Element& e) {
  Eigen::MatrixXd k;
  Eigen::VectorXd f;
  e.tangent({}, Eigen::VectorXd::Zero(e.n_dofs()), k, f);
  return k;
}

std::unique_ptr<Element> brick(int id, const std::array<int, 8>& nodes,
                               const std::array<Vec3, 8>& x, double nu, BrickStrain strain,
                               bool extra = false) {
  return std::make_unique<Brick8>(id, nodes, x, IsotropicElasticity{kE, nu, 7.3e-4}, extra,
                                  SourceLocation{}, std::nullopt, false, strain);
}

const char* name(BrickStrain s) {
  return s == BrickStrain::BBar ? "B-bar" : s == BrickStrain::Enhanced ? "enhanced" : "standard";
}

TEST(Brick8Technology, SixRigidBodyModesNoSpuriousModesSymmetric) {
  for (BrickStrain s : {BrickStrain::BBar, BrickStrain::Enhanced}) {
    const auto e = brick(1, kDistinct, distorted(), 0.3, s);
    const Eigen::MatrixXd k = stiffness(*e);
    EXPECT_LE((k - k.transpose()).cwiseAbs().maxCoeff(), 1e-13 * k.cwiseAbs().maxCoeff());
    const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(k).eigenvalues();
    const double top = ev.cwiseAbs().maxCoeff();
    int zeros = 0;
    for (int i = 0; i < ev.size(); ++i)
      if (std::abs(ev(i)) < 1e-10 * top) ++zeros;
    EXPECT_EQ(zeros, 6) << name(s);
    EXPECT_GT(ev(6) / top, 1e-6) << name(s);  // no hourglass (zero-energy) mode
    EXPECT_GT(ev.minCoeff(), -1e-10 * top) << name(s);
  }
  const auto e = brick(1, kDistinct, distorted(), 0.3, BrickStrain::Enhanced);
  EXPECT_EQ(dynamic_cast<const Brick8&>(*e).n_internal(), 13);
  // A collapsed brick (prism) cannot carry the modes: enhanced falls back to B-bar.
  const Vec3 o(0, 0, 0), a(2, 0, 0), b(0, 1.5, 0), c(0, 0, 1.2), ac(2, 0, 1.2), bc(0, 1.5, 1.2);
  const auto prism =
      brick(1, {1, 2, 3, 3, 5, 6, 7, 7}, {o, a, b, b, c, ac, bc, bc}, 0.3, BrickStrain::Enhanced);
  EXPECT_EQ(dynamic_cast<const Brick8&>(*prism).strain(), BrickStrain::BBar);
  EXPECT_EQ(dynamic_cast<const Brick8&>(*prism).n_internal(), 0);
}

/// Eigenvalues of K above 1e-2 of the largest: at ν = 0.4999 the bulk modulus is 1700 times
/// the shear modulus, so these are the element's volumetric constraints.
int volumetric_constraints(const Element& e) {
  const Eigen::VectorXd ev =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(stiffness(e)).eigenvalues();
  return static_cast<int>((ev.array() > 1e-2 * ev.maxCoeff()).count());
}

TEST(Brick8Technology, OneVolumetricConstraintPerElement) {
  // Full 2x2x2 constrains the dilatation at the 8 points (locking); the incompatible modes
  // free 3 of them; B-bar and enhanced strain (with its 4 volumetric modes) leave the element
  // mean only.
  const double nu = 0.4999;
  const int full =
      volumetric_constraints(*brick(1, kDistinct, distorted(), nu, BrickStrain::Standard));
  const int modes =
      volumetric_constraints(*brick(1, kDistinct, distorted(), nu, BrickStrain::Standard, true));
  const int bbar = volumetric_constraints(*brick(1, kDistinct, distorted(), nu, BrickStrain::BBar));
  const int enhanced =
      volumetric_constraints(*brick(1, kDistinct, distorted(), nu, BrickStrain::Enhanced));
  std::printf("volumetric constraints: full %d, incompatible %d, B-bar %d, enhanced %d\n", full,
              modes, bbar, enhanced);
  EXPECT_GT(full, 4);
  EXPECT_GT(modes, 1);
  EXPECT_EQ(bbar, 1);
  EXPECT_EQ(enhanced, 1);
}

/// MacNeal & Harder (1985) solid patch (7 elements, distorted inner hexahedron): the outer nodes
/// follow a linear field; the inner nodes and the element stresses must be exact.
void patch_test(BrickStrain strain, double nu) {
  SCOPED_TRACE(std::string(name(strain)) + " nu " + std::to_string(nu));
  std::map<int, Vec3> x;
  const std::array<Vec3, 8> outer = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0),
                                     Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1), Vec3(0, 1, 1)};
  const std::array<Vec3, 8> inner = {Vec3(0.249, 0.342, 0.192), Vec3(0.826, 0.288, 0.288),
                                     Vec3(0.850, 0.649, 0.263), Vec3(0.273, 0.750, 0.230),
                                     Vec3(0.320, 0.186, 0.643), Vec3(0.677, 0.305, 0.683),
                                     Vec3(0.788, 0.693, 0.644), Vec3(0.165, 0.745, 0.702)};
  for (int c = 0; c < 8; ++c) {
    x[c + 1] = outer[c];
    x[c + 11] = inner[c];
  }
  const std::vector<std::array<int, 8>> conn = {
      {11, 12, 13, 14, 15, 16, 17, 18}, {1, 2, 3, 4, 11, 12, 13, 14}, {15, 16, 17, 18, 5, 6, 7, 8},
      {1, 2, 12, 11, 5, 6, 16, 15},     {14, 13, 3, 4, 18, 17, 7, 8}, {1, 11, 14, 4, 5, 15, 18, 8},
      {12, 2, 3, 13, 16, 6, 7, 17}};
  std::vector<std::unique_ptr<Element>> elements;
  for (std::size_t i = 0; i < conn.size(); ++i) {
    std::array<Vec3, 8> xe;
    for (int c = 0; c < 8; ++c) xe[c] = x[conn[i][c]];
    elements.push_back(brick(static_cast<int>(i + 1), conn[i], xe, nu, strain));
  }
  const testing::DenseSystem sys(elements);
  Eigen::Matrix3d grad;
  grad << 1.0e-3, 0.5e-3, 0.5e-3, 0.2e-3, 1.0e-3, -0.4e-3, 0.5e-3, 0.3e-3, -0.8e-3;
  // K u = 0 on the inner nodes with the outer ones prescribed.
  std::vector<int> free, fixed;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(sys.n());
  for (int i = 0; i < sys.n(); ++i) {
    const DofKey& key = sys.dofs()[static_cast<std::size_t>(i)];
    if (key.node <= 8) {
      fixed.push_back(i);
      u(i) = (grad * x[key.node])(static_cast<int>(key.dof));
    } else {
      free.push_back(i);
    }
  }
  Eigen::MatrixXd kff(free.size(), free.size());
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(static_cast<int>(free.size()));
  for (std::size_t a = 0; a < free.size(); ++a) {
    for (std::size_t b = 0; b < free.size(); ++b) kff(a, b) = sys.K(free[a], free[b]);
    for (int j : fixed) rhs(a) -= sys.K(free[a], j) * u(j);
  }
  const Eigen::VectorXd uf = kff.ldlt().solve(rhs);
  for (std::size_t a = 0; a < free.size(); ++a) {
    const DofKey& key = sys.dofs()[static_cast<std::size_t>(free[a])];
    EXPECT_NEAR(uf(a), (grad * x[key.node])(static_cast<int>(key.dof)), 1e-12)
        << "node " << key.node;
    u(free[a]) = uf(a);
  }
  Vector6d eps;
  eps << grad(0, 0), grad(1, 1), grad(2, 2), grad(0, 1) + grad(1, 0), grad(1, 2) + grad(2, 1),
      grad(0, 2) + grad(2, 0);
  const Vector6d sigma = isotropic_elasticity_matrix(kE, nu) * eps;
  for (const auto& e : elements) {
    Eigen::VectorXd ue(e->n_dofs());
    for (int a = 0; a < e->n_dofs(); ++a) ue(a) = u(sys.index(e->dofs()[a].node, e->dofs()[a].dof));
    const Vector6d s = dynamic_cast<const Brick8&>(*e).centroid_stress({}, ue);
    EXPECT_LE((s - sigma).cwiseAbs().maxCoeff(), 1e-7 * sigma.cwiseAbs().maxCoeff())
        << "element " << e->id();
  }
}

TEST(Brick8Technology, DistortedPatchReproducesConstantStrain) {
  for (BrickStrain s : {BrickStrain::BBar, BrickStrain::Enhanced})
    for (double nu : {0.3, 0.4999}) patch_test(s, nu);
}

/// Thick-walled cylinder a = 1, b = 2 under internal pressure p, plane strain (UZ held on the
/// one layer's both faces), quarter model with symmetry; nr x nt bricks, nodes on the exact
/// circles. Returns the computed radial displacement at r = a over the closed form (Lamé):
/// u_r(r) = (1 + ν) p a² / (E (b² − a²)) ((1 − 2ν) r + b² / r).
double lame_ratio(BrickStrain strain, double nu, bool extra = false) {
  const int nr = 6, nt = 12;
  const double a = 1.0, b = 2.0, t = 0.1, p = 1000.0;
  auto node = [&](int i, int j, int k) { return 1 + i + (nr + 1) * (j + (nt + 1) * k); };
  auto pos = [&](int i, int j, int k) {
    const double r = a + (b - a) * i / nr, th = 0.5 * M_PI * j / nt;
    return Vec3(r * std::cos(th), r * std::sin(th), t * k);
  };
  const int di[8] = {0, 1, 1, 0, 0, 1, 1, 0}, dj[8] = {0, 0, 1, 1, 0, 0, 1, 1},
            dk[8] = {0, 0, 0, 0, 1, 1, 1, 1};
  std::vector<std::unique_ptr<Element>> elements;
  for (int j = 0; j < nt; ++j)
    for (int i = 0; i < nr; ++i) {
      std::array<int, 8> nodes;
      std::array<Vec3, 8> xe;
      for (int c = 0; c < 8; ++c) {
        nodes[c] = node(i + di[c], j + dj[c], dk[c]);
        xe[c] = pos(i + di[c], j + dj[c], dk[c]);
      }
      elements.push_back(
          brick(static_cast<int>(elements.size() + 1), nodes, xe, nu, strain, extra));
    }
  const testing::DenseSystem sys(elements);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(sys.n());
  // Face 5 (L-I-M-P, ξ = −1) is the inner surface r = a; positive pressure pushes into the wall.
  for (int j = 0; j < nt; ++j) {
    const Element& e = *elements[static_cast<std::size_t>(j * nr)];
    Eigen::VectorXd fe;
    e.pressure_load({}, 5, {p, p, p, p}, Eigen::VectorXd::Zero(e.n_dofs()), fe);
    for (int q = 0; q < e.n_dofs(); ++q) f(sys.index(e.dofs()[q].node, e.dofs()[q].dof)) += fe(q);
  }
  std::set<DofKey> fixed;
  for (int k = 0; k <= 1; ++k)
    for (int j = 0; j <= nt; ++j)
      for (int i = 0; i <= nr; ++i) {
        fixed.insert({node(i, j, k), Dof::UZ});
        if (j == 0) fixed.insert({node(i, j, k), Dof::UY});
        if (j == nt) fixed.insert({node(i, j, k), Dof::UX});
      }
  const Eigen::VectorXd u = sys.solve_static(f, fixed);
  const double exact =
      (1 + nu) * p * a * a / (kE * (b * b - a * a)) * ((1 - 2 * nu) * a + b * b / a);
  double ur = 0.0;  // mean over the inner nodes
  for (int j = 0; j <= nt; ++j) {
    const Vec3 x = pos(0, j, 0);
    ur += (u(sys.index(node(0, j, 0), Dof::UX)) * x(0) +
           u(sys.index(node(0, j, 0), Dof::UY)) * x(1)) /
          x.norm();
  }
  return ur / (nt + 1) / exact;
}

TEST(Brick8Technology, ThickCylinderNearlyIncompressibleDoesNotLock) {
  const double bbar = lame_ratio(BrickStrain::BBar, 0.4999);
  const double enhanced = lame_ratio(BrickStrain::Enhanced, 0.4999);
  const double full = lame_ratio(BrickStrain::Standard, 0.4999);
  const double modes = lame_ratio(BrickStrain::Standard, 0.4999, true);
  RecordProperty("ur_ratio_bbar", std::to_string(bbar));
  RecordProperty("ur_ratio_enhanced", std::to_string(enhanced));
  RecordProperty("ur_ratio_full", std::to_string(full));
  RecordProperty("ur_ratio_incompatible", std::to_string(modes));
  std::printf("Lame nu=0.4999: B-bar %.5f enhanced %.5f full %.5f incompatible %.5f\n", bbar,
              enhanced, full, modes);
  EXPECT_NEAR(bbar, 1.0, 0.01);
  EXPECT_NEAR(enhanced, 1.0, 0.01);
  EXPECT_LT(full, 0.5);  // full 2x2x2 integration locks volumetrically
  // Compressible: all agree with the closed form.
  EXPECT_NEAR(lame_ratio(BrickStrain::BBar, 0.3), 1.0, 0.01);
  EXPECT_NEAR(lame_ratio(BrickStrain::Enhanced, 0.3), 1.0, 0.01);
}

/// Clamped cantilever of length L, h = b = 1, one row of 10 bricks (aspect ratio L / 10), end
/// shear P over the end nodes: mean tip deflection over Timoshenko's
/// δ = PL³/(3EI) + PL/(κGA), κ = 5/6.
double cantilever_ratio(BrickStrain strain, double nu, double length) {
  const int nx = 10;
  const double p = 100.0;
  auto node = [&](int i, int j, int k) { return 1 + i + (nx + 1) * (j + 2 * k); };
  const int di[8] = {0, 1, 1, 0, 0, 1, 1, 0}, dj[8] = {0, 0, 1, 1, 0, 0, 1, 1},
            dk[8] = {0, 0, 0, 0, 1, 1, 1, 1};
  std::vector<std::unique_ptr<Element>> elements;
  for (int i = 0; i < nx; ++i) {
    std::array<int, 8> nodes;
    std::array<Vec3, 8> xe;
    for (int c = 0; c < 8; ++c) {
      nodes[c] = node(i + di[c], dj[c], dk[c]);
      xe[c] = Vec3(length * (i + di[c]) / nx, dj[c], dk[c]);
    }
    elements.push_back(brick(i + 1, nodes, xe, nu, strain));
  }
  const testing::DenseSystem sys(elements);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(sys.n());
  std::set<DofKey> fixed;
  for (int k = 0; k <= 1; ++k)
    for (int j = 0; j <= 1; ++j) {
      f(sys.index(node(nx, j, k), Dof::UY)) = p / 4;
      for (Dof d : {Dof::UX, Dof::UY, Dof::UZ}) fixed.insert({node(0, j, k), d});
    }
  const Eigen::VectorXd u = sys.solve_static(f, fixed);
  double tip = 0.0;
  for (int k = 0; k <= 1; ++k)
    for (int j = 0; j <= 1; ++j) tip += 0.25 * u(sys.index(node(nx, j, k), Dof::UY));
  const double g = kE / (2 * (1 + nu));
  return tip / (p * std::pow(length, 3) / (3 * kE / 12.0) + p * length / (5.0 / 6.0 * g));
}

TEST(Brick8Technology, EnhancedStrainCantileverDoesNotLockInBending) {
  // One element through the depth, element aspect ratio 1 (L = 10) and 10 (L = 100).
  for (double length : {10.0, 100.0}) {
    const double enhanced = cantilever_ratio(BrickStrain::Enhanced, 0.3, length);
    const double incompressible = cantilever_ratio(BrickStrain::Enhanced, 0.4999, length);
    const double full = cantilever_ratio(BrickStrain::Standard, 0.3, length);
    const double bbar = cantilever_ratio(BrickStrain::BBar, 0.3, length);
    std::printf("cantilever L=%g: enhanced %.4f (nu 0.4999: %.4f) full %.4f B-bar %.4f\n", length,
                enhanced, incompressible, full, bbar);
    const std::string tag = length == 10.0 ? "_aspect1" : "_aspect10";
    RecordProperty("tip_ratio_enhanced" + tag, std::to_string(enhanced));
    RecordProperty("tip_ratio_full" + tag, std::to_string(full));
    RecordProperty("tip_ratio_bbar" + tag, std::to_string(bbar));
    EXPECT_NEAR(enhanced, 1.0, 0.03) << length;
    EXPECT_NEAR(incompressible, 1.0, 0.05) << length;
    if (length == 100.0) {
      EXPECT_LT(full, 0.1);  // full integration locks in bending (parasitic shear)
      EXPECT_LT(bbar, 0.1);  // and so does B-bar: it only treats the dilatation
    }
  }
}

TEST(Brick8Technology, PlasticEnhancedBrickIsElasticBelowYield) {
  // Below yield the plastic brick's tangent is the linear one of the same technology.
  const auto law = J2Plasticity::bilinear(kE, 0.3, 1e12, 0.0, false);
  for (BrickStrain s : {BrickStrain::BBar, BrickStrain::Enhanced}) {
    const Brick8 plastic(1, kDistinct, distorted(), {kE, 0.3, 0.0}, false, {}, law, false, s);
    const Brick8 elastic(1, kDistinct, distorted(), {kE, 0.3, 0.0}, false, {}, std::nullopt, false,
                         s);
    Eigen::VectorXd u(24);
    for (int i = 0; i < 24; ++i) u(i) = 1e-4 * std::sin(1.0 + i);
    Eigen::MatrixXd kp, ke;
    Eigen::VectorXd fp, fe;
    plastic.tangent({}, u, kp, fp);
    elastic.tangent({}, u, ke, fe);
    EXPECT_LE((kp - ke).cwiseAbs().maxCoeff(), 1e-9 * ke.cwiseAbs().maxCoeff()) << name(s);
    EXPECT_LE((fp - fe).cwiseAbs().maxCoeff(), 1e-9 * fe.cwiseAbs().maxCoeff()) << name(s);
  }
}

}  // namespace
}  // namespace impactfe::test_brick8_technologies
