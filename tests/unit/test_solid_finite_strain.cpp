// Unit tests of the finite-strain 3-D solids (large deflection,
// src/elements/solid_finite_strain.cpp through SOLID185 with plasticity and SOLID186 / SOLID187):
// the tangent against central differences of the internal force (elastic and plastic states, with
// rotation), rigid rotations beyond 90° (no stress; a prestress rotates with the body), a uniaxial
// stretch to 50 % logarithmic strain against the closed form of the hypoelastic law (elastic,
// perfectly plastic and linear hardening), the patch test of a distorted element and the undeformed
// tangent equal to the small-strain stiffness.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include "elements/brick8.h"
#include "elements/quadratic_shapes.h"
#include "elements/solid_quadratic.h"
#include "materials/j2_plasticity.h"

namespace impactfe::test_solid_finite_strain {
namespace {

constexpr double kE = 200e3;
constexpr double kNu = 0.3;

const ElementContext kLarge{true, true, false};
const ElementContext kSmall{false, false, false};

enum class Kind { Brick, Hex20Reduced, Hex20Full, Tet10 };

/// Reference positions of the nodes: the unit cell, mildly distorted (`distort` = 0: exact
/// cube or unit tetrahedron), shifted to `origin`.
std::vector<Vec3> cell(Kind kind, double distort, const Vec3& origin = Vec3(1.0, 0.5, 0.2)) {
  std::vector<Eigen::Vector3d> xi;
  if (kind == Kind::Brick) {
    const double c[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                            {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
    for (const auto& p : c) xi.emplace_back(p[0], p[1], p[2]);
  } else {
    xi = quadratic_shape_nodes_xi(kind == Kind::Tet10 ? QuadraticShape::Tet10
                                                      : QuadraticShape::Hex20);
  }
  std::vector<Vec3> x;
  for (const Eigen::Vector3d& p : xi) {
    const Eigen::Vector3d s = kind == Kind::Tet10 ? p : Eigen::Vector3d(0.5 * (p.array() + 1.0));
    x.push_back(origin + s +
                distort * Vec3(0.1 * s(1) * s(0), 0.05 * s(2) + 0.08 * s(0) * s(2), 0.07 * s(1)));
  }
  return x;
}

std::unique_ptr<Element> element(Kind kind, const std::vector<Vec3>& x,
                                 std::optional<J2Plasticity> law, bool large = true) {
  const IsotropicElasticity mat{kE, kNu, 0.0};
  if (kind == Kind::Brick) {
    std::array<int, 8> ids{};
    std::array<Vec3, 8> xa;
    for (int a = 0; a < 8; ++a) {
      ids[static_cast<std::size_t>(a)] = a + 1;
      xa[static_cast<std::size_t>(a)] = x[static_cast<std::size_t>(a)];
    }
    // The finite-strain brick is the plastic one (B-bar, SOLID185 KEYOPT(2) = 0).
    return std::make_unique<Brick8>(1, ids, xa, mat, false, SourceLocation{}, std::move(law), large,
                                    BrickStrain::BBar);
  }
  std::vector<int> ids;
  for (std::size_t a = 0; a < x.size(); ++a) ids.push_back(static_cast<int>(a) + 1);
  const QuadraticShape shape = kind == Kind::Tet10 ? QuadraticShape::Tet10 : QuadraticShape::Hex20;
  std::vector<QuadraturePoint> rule = kind == Kind::Tet10       ? tetrahedron_4_point()
                                      : kind == Kind::Hex20Full ? gauss_cube(3)
                                                                : gauss_cube(2);
  return std::make_unique<QuadraticSolid>(1, shape, ids, x, mat, std::move(rule),
                                          std::vector<std::vector<int>>{}, SourceLocation{},
                                          std::move(law), large);
}

void finite_tangent(const Element& e, const Eigen::VectorXd& u, Eigen::MatrixXd& k,
                    Eigen::VectorXd& f, bool symmetric = false) {
  if (const auto* b = dynamic_cast<const Brick8*>(&e)) {
    b->finite_tangent(u, k, f, symmetric);
  } else {
    dynamic_cast<const QuadraticSolid&>(e).finite_tangent(u, k, f, symmetric);
  }
}

Vector6d point_stress(const Element& e, const Eigen::VectorXd& u, int p) {
  if (const auto* b = dynamic_cast<const Brick8*>(&e)) return b->finite_point_stress(u, p);
  return dynamic_cast<const QuadraticSolid&>(e).finite_point_stress(u, p);
}

int n_points(const Element& e) {
  if (dynamic_cast<const Brick8*>(&e)) return 8;
  return dynamic_cast<const QuadraticSolid&>(e).stiffness_points();
}

/// The homogeneous displacement u = (F − I) X + c at the nodes.
Eigen::VectorXd homogeneous(const std::vector<Vec3>& x, const Eigen::Matrix3d& f,
                            const Vec3& c = Vec3::Zero()) {
  Eigen::VectorXd u(3 * x.size());
  for (std::size_t a = 0; a < x.size(); ++a)
    u.segment<3>(3 * static_cast<Eigen::Index>(a)) = (f - Eigen::Matrix3d::Identity()) * x[a] + c;
  return u;
}

Eigen::Matrix3d tensor(const Vector6d& s) {
  Eigen::Matrix3d t;
  t << s(0), s(3), s(5), s(3), s(1), s(4), s(5), s(4), s(2);
  return t;
}

J2Plasticity bilinear(double et) {
  return J2Plasticity::bilinear(kE, kNu, 250.0, et, false);
}

TEST(SolidFiniteStrain, TangentIsTheDerivativeOfTheInternalForce) {
  // After a committed increment (plastic points yielding), a second increment with stretch,
  // shear and a rotation of 0.4 rad about an oblique axis: K against central differences of f.
  struct Case {
    Kind kind;
    std::optional<J2Plasticity> law;
  };
  const std::vector<Case> cases = {
      {Kind::Brick, bilinear(2000.0)},
      {Kind::Brick, J2Plasticity::bilinear(kE, kNu, 1e9, 0.0, false)},  // elastic range
      {Kind::Hex20Reduced, std::nullopt},
      {Kind::Hex20Full, bilinear(2000.0)},
      {Kind::Hex20Reduced, J2Plasticity::bilinear(kE, kNu, 250.0, 5000.0, true)},
      {Kind::Tet10, bilinear(0.0)},
      {Kind::Tet10, std::nullopt},
  };
  int index = 0;
  for (const Case& c : cases) {
    SCOPED_TRACE(index++);
    const std::vector<Vec3> x = cell(c.kind, 1.0);
    auto e = element(c.kind, x, c.law);
    Eigen::Matrix3d f1;
    f1 << 1.004, 0.002, -0.001, 0.001, 0.997, 0.002, 0.0015, -0.001, 1.002;
    Eigen::VectorXd u = homogeneous(x, f1);
    for (Eigen::Index i = 0; i < u.size(); ++i) u(i) += 1e-4 * std::sin(1.3 * i + 0.2);
    e->commit_history(kLarge, u);
    {
      // At the committed state (Δu = 0) the non-symmetric part is of the order of σ/E.
      Eigen::MatrixXd k0;
      Eigen::VectorXd f0;
      finite_tangent(*e, u, k0, f0);
      EXPECT_LT((k0 - k0.transpose()).norm(), 0.02 * k0.norm());
    }
    const Eigen::Matrix3d rot =
        Eigen::AngleAxisd(0.4, Eigen::Vector3d(1.0, 2.0, 0.5).normalized()).toRotationMatrix();
    Eigen::Matrix3d s2;
    s2 << 1.12, 0.05, 0.01, 0.02, 0.95, -0.03, 0.0, 0.01, 1.04;
    u = homogeneous(x, rot * s2 * f1);
    for (Eigen::Index i = 0; i < u.size(); ++i) u(i) += 2e-3 * std::cos(0.7 * i);
    Eigen::MatrixXd k;
    Eigen::VectorXd f;
    finite_tangent(*e, u, k, f);
    const double h = 1e-7;
    Eigen::MatrixXd fd(k.rows(), k.cols());
    for (Eigen::Index j = 0; j < u.size(); ++j) {
      Eigen::VectorXd up = u, um = u;
      up(j) += h;
      um(j) -= h;
      Eigen::MatrixXd kk;
      Eigen::VectorXd fp, fm;
      finite_tangent(*e, up, kk, fp);
      finite_tangent(*e, um, kk, fm);
      fd.col(j) = (fp - fm) / (2.0 * h);
    }
    EXPECT_LT((k - fd).norm(), 1e-6 * k.norm()) << (k - fd).norm() / k.norm();
  }
}

TEST(SolidFiniteStrain, RigidRotationBeyond90DegreesCarriesTheStress) {
  // A rotation by 120° about an oblique axis: from the virgin state no stress (one increment:
  // Hughes-Winget is exact below 180°); after a committed stretch (plastic, 10 %) the rotation
  // in one or in three increments leaves σ' = Q σ Qᵀ.
  const Eigen::Vector3d axis = Eigen::Vector3d(1.0, -1.0, 2.0).normalized();
  const double angle = 2.0 * 3.141592653589793 / 3.0;
  for (Kind kind : {Kind::Brick, Kind::Hex20Reduced, Kind::Tet10}) {
    SCOPED_TRACE(static_cast<int>(kind));
    const std::vector<Vec3> x = cell(kind, 1.0);
    const Eigen::Matrix3d q = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
    {
      auto e = element(kind, x, bilinear(2000.0));
      const Eigen::VectorXd u = homogeneous(x, q, Vec3(0.3, -0.2, 0.1));
      Eigen::MatrixXd k;
      Eigen::VectorXd f;
      finite_tangent(*e, u, k, f);
      EXPECT_LT(f.norm(), 1e-9 * kE);
      for (int p = 0; p < n_points(*e); ++p) EXPECT_LT(point_stress(*e, u, p).norm(), 1e-9 * kE);
    }
    for (int increments : {1, 3}) {
      auto e = element(kind, x, bilinear(2000.0));
      Eigen::Matrix3d stretch = Eigen::Matrix3d::Identity();
      stretch(0, 0) = 1.1;
      stretch(0, 1) = 0.02;
      Eigen::VectorXd u = homogeneous(x, stretch);
      const Vector6d before = point_stress(*e, u, 0);
      EXPECT_GT(before(0), 250.0);  // yielded
      e->commit_history(kLarge, u);
      for (int s = 1; s <= increments; ++s) {
        const Eigen::Matrix3d qs =
            Eigen::AngleAxisd(angle * s / increments, axis).toRotationMatrix();
        u = homogeneous(x, qs * stretch);
        if (s < increments) e->commit_history(kLarge, u);
      }
      const Eigen::Matrix3d expected = q * tensor(before) * q.transpose();
      for (int p = 0; p < n_points(*e); ++p)
        EXPECT_LT((tensor(point_stress(*e, u, p)) - expected).norm(), 1e-8 * kE)
            << increments << " increments, point " << p;
    }
  }
}

/// Newton on the free DOFs with the exact (or the symmetric) tangent, the others prescribed in
/// u; the number of iterations into `iterations` when given.
void solve(const Element& e, Eigen::VectorXd& u, const std::vector<int>& free,
           bool symmetric = false, int* iterations = nullptr) {
  const auto nf = static_cast<Eigen::Index>(free.size());
  for (int it = 0; it < 40; ++it) {
    if (iterations) *iterations = it;
    Eigen::MatrixXd k;
    Eigen::VectorXd f;
    finite_tangent(e, u, k, f, symmetric);
    Eigen::VectorXd r(nf);
    Eigen::MatrixXd kff(nf, nf);
    for (Eigen::Index i = 0; i < nf; ++i) {
      r(i) = f(free[static_cast<std::size_t>(i)]);
      for (Eigen::Index j = 0; j < nf; ++j)
        kff(i, j) = k(free[static_cast<std::size_t>(i)], free[static_cast<std::size_t>(j)]);
    }
    if (r.norm() < 1e-10 * kE) return;
    const Eigen::VectorXd du = kff.partialPivLu().solve(-r);
    for (Eigen::Index i = 0; i < nf; ++i) u(free[static_cast<std::size_t>(i)]) += du(i);
  }
  FAIL() << "Newton did not converge";
}

TEST(SolidFiniteStrain, UniaxialStretchTo50PercentLogStrainMatchesTheClosedForm) {
  // The unit cell stretched along X to λ = e^0.5 (logarithmic strain 0.5) in 50 increments,
  // free laterally (symmetry planes Y = 0, Z = 0). The hypoelastic law with the
  // midpoint increments integrates the logarithmic strain ε = ln λ (second order per
  // increment), so σ_xx (Cauchy) = E ε elastic, the flow stress σ_y + E_t (ε − σ_y / E) with a
  // bilinear law (E_t = 0: perfectly plastic), the lateral stresses zero.
  struct Case {
    Kind kind;
    double yield;  // 0: elastic
    double et;
  };
  const double eps = 0.5;
  const double lambda = std::exp(eps);
  for (const Case& c : {Case{Kind::Brick, 250.0, 0.0}, Case{Kind::Brick, 250.0, 2000.0},
                        Case{Kind::Hex20Reduced, 250.0, 0.0}, Case{Kind::Hex20Full, 250.0, 2000.0},
                        Case{Kind::Tet10, 250.0, 2000.0}, Case{Kind::Hex20Reduced, 0.0, 0.0}}) {
    SCOPED_TRACE(static_cast<int>(c.kind) * 10 + (c.et > 0.0 ? 1 : 0));
    const std::vector<Vec3> x = cell(c.kind, 0.0, Vec3::Zero());
    std::optional<J2Plasticity> law;
    if (c.yield > 0.0) law = J2Plasticity::bilinear(kE, kNu, c.yield, c.et, false);
    auto e = element(c.kind, x, law);
    // UX prescribed at every node, (λ − 1) X (the tetrahedron has a single node at X = 1);
    // UY, UZ free off the symmetry planes.
    std::vector<int> free;
    for (std::size_t a = 0; a < x.size(); ++a) {
      const int base = 3 * static_cast<int>(a);
      if (std::abs(x[a](1)) > 1e-12) free.push_back(base + 1);
      if (std::abs(x[a](2)) > 1e-12) free.push_back(base + 2);
    }
    Eigen::VectorXd u = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(3 * x.size()));
    const int steps = 50;
    for (int s = 1; s <= steps; ++s) {
      for (std::size_t a = 0; a < x.size(); ++a)
        u(3 * static_cast<Eigen::Index>(a)) = (lambda - 1.0) * x[a](0) * s / steps;
      solve(*e, u, free);
      e->commit_history(kLarge, u);
    }
    const double expected = c.yield > 0.0 ? c.yield + c.et * (eps - c.yield / kE) : kE * eps;
    ElementResultValues r;
    e->results(kLarge, u, u, r);
    EXPECT_NEAR(r[0], expected, 1e-3 * expected);
    EXPECT_NEAR(r[1], 0.0, 1e-6 * expected);
    EXPECT_NEAR(r[2], 0.0, 1e-6 * expected);
    for (int p = 0; p < n_points(*e); ++p)
      EXPECT_NEAR(point_stress(*e, u, p)(0), expected, 1e-3 * expected);
    if (c.yield > 0.0) {
      // EPEQ: the logarithmic plastic strain ε − σ / E; EPPLX the same, EPPLY = −½ EPPLX.
      const double ep = eps - expected / kE;
      EXPECT_NEAR(r[17], ep, 2e-3 * ep);
      EXPECT_NEAR(r[11], ep, 2e-3 * ep);
      EXPECT_NEAR(r[12], -0.5 * ep, 2e-3 * ep);
    }
  }
}

TEST(SolidFiniteStrain, SymmetricTangentConvergesThroughPlasticFlow) {
  // The solvers' symmetric tangent (material + initial-stress terms): the unit cube of one
  // 20-node brick (3x3x3, and 2x2x2) and of one 8-node brick stretched along X by UX on the
  // face X = 1 alone, the other nodes free off the symmetry planes, to a logarithmic strain of
  // 0.2 in 20 increments with hardening E_t = 2000 (the plastic modulus comparable with σ):
  // every increment converges, and the stress is the closed form.
  for (Kind kind : {Kind::Brick, Kind::Hex20Full, Kind::Hex20Reduced}) {
    SCOPED_TRACE(static_cast<int>(kind));
    const std::vector<Vec3> x = cell(kind, 0.0, Vec3::Zero());
    auto e = element(kind, x, bilinear(2000.0));
    std::vector<int> free, stretched;
    for (std::size_t a = 0; a < x.size(); ++a) {
      const int base = 3 * static_cast<int>(a);
      if (std::abs(x[a](0) - 1.0) < 1e-12)
        stretched.push_back(base);
      else if (std::abs(x[a](0)) > 1e-12)
        free.push_back(base);
      if (std::abs(x[a](1)) > 1e-12) free.push_back(base + 1);
      if (std::abs(x[a](2)) > 1e-12) free.push_back(base + 2);
    }
    const double eps = 0.2;
    Eigen::VectorXd u = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(3 * x.size()));
    int worst = 0;
    for (int s = 1; s <= 20; ++s) {
      for (int dof : stretched) u(dof) = (std::exp(eps) - 1.0) * s / 20;
      int iterations = 0;
      solve(*e, u, free, true, &iterations);
      worst = std::max(worst, iterations);
      e->commit_history(kLarge, u);
    }
    EXPECT_LE(worst, 15);
    const double expected = 250.0 + 2000.0 * (eps - 250.0 / kE);
    ElementResultValues r;
    e->results(kLarge, u, u, r);
    EXPECT_NEAR(r[0], expected, 1e-3 * expected);
  }
}

TEST(SolidFiniteStrain, HomogeneousDeformationOfADistortedElementPassesThePatchTest) {
  // A homogeneous finite deformation (stretch, shear, rotation) in 4 increments of a distorted
  // element: every point has the same stress, and a rigid translation adds no force.
  for (Kind kind : {Kind::Brick, Kind::Hex20Reduced, Kind::Hex20Full, Kind::Tet10}) {
    SCOPED_TRACE(static_cast<int>(kind));
    const std::vector<Vec3> x = cell(kind, 2.0);
    auto e = element(kind, x, bilinear(1000.0));
    Eigen::Matrix3d g;
    g << 0.2, 0.1, 0.0, -0.05, -0.08, 0.04, 0.02, 0.0, 0.1;
    Eigen::VectorXd u;
    for (int s = 1; s <= 4; ++s) {
      const Eigen::Matrix3d rot =
          Eigen::AngleAxisd(0.3 * s, Eigen::Vector3d(0.0, 1.0, 1.0).normalized())
              .toRotationMatrix();
      u = homogeneous(x, rot * (Eigen::Matrix3d::Identity() + 0.25 * s * g));
      if (s < 4) e->commit_history(kLarge, u);
    }
    const Vector6d s0 = point_stress(*e, u, 0);
    EXPECT_GT(s0.norm(), 250.0);
    for (int p = 1; p < n_points(*e); ++p)
      EXPECT_LT((point_stress(*e, u, p) - s0).norm(), 1e-9 * s0.norm()) << p;
    Eigen::MatrixXd k;
    Eigen::VectorXd f, f_moved;
    finite_tangent(*e, u, k, f);
    const Eigen::VectorXd shift = homogeneous(x, Eigen::Matrix3d::Identity(), Vec3(0.4, -1.0, 2.0));
    finite_tangent(*e, u + shift, k, f_moved);
    EXPECT_LT((f_moved - f).norm(), 1e-10 * f.norm());
    // The nodal forces of a homogeneous stress balance: Σ f = 0.
    Vec3 sum = Vec3::Zero();
    for (Eigen::Index a = 0; a < f.size() / 3; ++a) sum += f.segment<3>(3 * a);
    EXPECT_LT(sum.norm(), 1e-10 * f.norm());
  }
}

TEST(SolidFiniteStrain, UndeformedTangentIsTheSmallStrainStiffness) {
  // At u = 0 from the virgin state: no stress, L = 0, so K is ∫B̄ᵀDB̄ dV (the brick's B-bar) or
  // ∫BᵀDB dV, symmetric.
  for (Kind kind : {Kind::Brick, Kind::Hex20Reduced, Kind::Hex20Full, Kind::Tet10}) {
    SCOPED_TRACE(static_cast<int>(kind));
    const std::vector<Vec3> x = cell(kind, 1.0);
    auto e = element(kind, x, bilinear(2000.0));
    Eigen::MatrixXd k, k_small;
    Eigen::VectorXd f, f_small;
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(e->n_dofs());
    finite_tangent(*e, zero, k, f);
    auto small = element(kind, x, bilinear(2000.0), false);
    small->tangent(kSmall, zero, k_small, f_small);
    EXPECT_LT((k - k.transpose()).norm(), 1e-12 * k.norm());
    EXPECT_LT((k - k_small).norm(), 1e-10 * k.norm());
    EXPECT_LT(f.norm(), 1e-12 * kE);
  }
}

}  // namespace
}  // namespace impactfe::test_solid_finite_strain
