// Unit tests of the finite-strain PLANE182 / PLANE183 (large deflection,
// src/elements/plane_solid_finite.cpp): uniaxial stretch to 50 % against the closed form of the
// hypoelastic law with logarithmic strain (plane stress, plane strain, axisymmetry), quadratic
// Newton convergence, a rigid rotation by 90° (no stress; a prestress rotates with the body),
// the finite-difference check of the tangent (elastic and plastic), and the tangent at the
// undeformed state equal to the symmetric small-strain stiffness.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include "elements/plane_solid.h"
#include "materials/j2_plasticity.h"

namespace impactfe::test_plane_finite_strain {
namespace {

constexpr double kE = 200e3;
constexpr double kNu = 0.3;
constexpr double kPi = 3.141592653589793;

std::vector<Vec3> square(double x0, double y0, PlaneShape shape) {
  std::vector<Vec3> x;
  for (const Eigen::Vector2d& xi : plane_shape_nodes_xi(shape)) {
    // Quadrilaterals on [-1, 1]², triangles on the unit triangle: both mapped onto a unit cell.
    const bool tri = shape == PlaneShape::Tri3 || shape == PlaneShape::Tri6;
    const double s = tri ? xi(0) : 0.5 * (xi(0) + 1.0);
    const double t = tri ? xi(1) : 0.5 * (xi(1) + 1.0);
    x.emplace_back(x0 + s + 0.1 * t * s, y0 + t + 0.05 * s, 0.0);
  }
  return x;
}

std::unique_ptr<PlaneSolid> element(PlaneShape shape, PlaneBehaviour behaviour,
                                    PlaneTechnology technology, std::vector<Vec3> x,
                                    std::optional<J2Plasticity> plasticity = std::nullopt) {
  PlaneSolidOptions o;
  o.shape = shape;
  o.behaviour = behaviour;
  o.technology = technology;
  o.large_deflection = true;
  std::vector<int> ids;
  for (std::size_t a = 0; a < x.size(); ++a) ids.push_back(static_cast<int>(a) + 1);
  return std::make_unique<PlaneSolid>(1, ids, x, IsotropicElasticity{kE, kNu, 0.0}, o,
                                      std::vector<std::vector<int>>{}, SourceLocation{},
                                      std::move(plasticity));
}

const ElementContext kLarge{true, true, false};

/// The homogeneous displacement u = (F − I) X at the nodes.
Eigen::VectorXd homogeneous(const std::vector<Vec3>& x, const Eigen::Matrix2d& f) {
  Eigen::VectorXd u(2 * x.size());
  for (std::size_t a = 0; a < x.size(); ++a)
    u.segment<2>(2 * static_cast<Eigen::Index>(a)) =
        (f - Eigen::Matrix2d::Identity()) * x[a].head<2>();
  return u;
}

/// Newton on the free DOFs (`free`) with the exact tangent, the others prescribed in u; the
/// residual norms of the iterations go to `history`.
void solve(const PlaneSolid& e, Eigen::VectorXd& u, const std::vector<int>& free,
           std::vector<double>* history = nullptr) {
  const auto nf = static_cast<Eigen::Index>(free.size());
  for (int it = 0; it < 30; ++it) {
    Eigen::MatrixXd k;
    Eigen::VectorXd f;
    e.finite_tangent(u, k, f, false);
    Eigen::VectorXd r(nf);
    Eigen::MatrixXd kff(nf, nf);
    for (Eigen::Index i = 0; i < nf; ++i) {
      r(i) = f(free[static_cast<std::size_t>(i)]);
      for (Eigen::Index j = 0; j < nf; ++j)
        kff(i, j) = k(free[static_cast<std::size_t>(i)], free[static_cast<std::size_t>(j)]);
    }
    if (history) history->push_back(r.norm());
    if (r.norm() < 1e-9 * kE) return;
    const Eigen::VectorXd du = kff.partialPivLu().solve(-r);
    for (Eigen::Index i = 0; i < nf; ++i) u(free[static_cast<std::size_t>(i)]) += du(i);
  }
  FAIL() << "Newton did not converge";
}

struct Stretch {
  PlaneBehaviour behaviour;
  PlaneTechnology technology;
};

TEST(PlaneFiniteStrain, UniaxialStretchMatchesTheLogarithmicClosedForm) {
  // A rectangle stretched to λ = 1.5 along the loaded axis in 25 increments, free laterally:
  // the hypoelastic law with the rotated-log strain gives σ = E' ln λ (E' = E in plane stress
  // and axisymmetry, E/(1 − ν²) in plane strain) and the lateral stretch λ^(−ν'), ν' = ν or
  // ν/(1 − ν), to the second-order accuracy of the midpoint increments.
  for (const Stretch& c : {Stretch{PlaneBehaviour::PlaneStress, PlaneTechnology::Standard},
                           Stretch{PlaneBehaviour::PlaneStrain, PlaneTechnology::Standard},
                           Stretch{PlaneBehaviour::PlaneStrain, PlaneTechnology::BBar},
                           Stretch{PlaneBehaviour::Axisymmetric, PlaneTechnology::BBar}}) {
    SCOPED_TRACE(static_cast<int>(c.behaviour) * 10 + static_cast<int>(c.technology));
    const bool axi = c.behaviour == PlaneBehaviour::Axisymmetric;
    // Nodes I J K L of the unit square at X = 1..2 (axisymmetry: radius ≥ 1).
    const std::vector<Vec3> x = {Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(2, 1, 0), Vec3(1, 1, 0)};
    auto e = element(PlaneShape::Quad4, c.behaviour, c.technology, x);
    // Plane: stretched along X (UX of I, L = 0; J, K prescribed; UY of I fixed, the rest free).
    // Axisymmetric: stretched along the axis Y (UY of I, J = 0; K, L prescribed; UX free).
    const std::vector<int> free = axi ? std::vector<int>{0, 2, 4, 6} : std::vector<int>{3, 5, 7};
    Eigen::VectorXd u = Eigen::VectorXd::Zero(8);
    const int steps = 25;
    const double lambda = 1.5;
    std::vector<double> history;
    for (int s = 1; s <= steps; ++s) {
      const double d = (lambda - 1.0) * s / steps;
      if (axi) {
        u(5) = u(7) = d;
      } else {
        u(2) = u(4) = d;
      }
      history.clear();
      solve(*e, u, free, &history);
      e->commit_history(kLarge, u);
    }
    const bool strain = c.behaviour == PlaneBehaviour::PlaneStrain;
    const double e_eff = strain ? kE / (1 - kNu * kNu) : kE;
    const double nu_eff = strain ? kNu / (1 - kNu) : kNu;
    ElementResultValues r;
    e->results(kLarge, u, u, r);
    const double log_stretch = std::log(lambda);
    const double axial = axi ? r[1] : r[0], lateral = axi ? r[0] : r[1];
    EXPECT_NEAR(axial, e_eff * log_stretch, 2e-4 * e_eff * log_stretch);
    EXPECT_NEAR(lateral, 0.0, 1e-6 * e_eff);
    if (axi) EXPECT_NEAR(r[2], 0.0, 1e-6 * e_eff);  // hoop
    // The lateral stretch λ^(−ν'): node K's lateral displacement.
    const double lateral_u = axi ? u(4) / 2.0 : u(5);
    EXPECT_NEAR(1.0 + lateral_u, std::pow(lambda, -nu_eff), 2e-4);
    // EPEL: the logarithmic elastic strain.
    EXPECT_NEAR(axi ? r[24] : r[23], log_stretch, 2e-4 * log_stretch);
    // Quadratic convergence of the last increment: with ρ = |r| / E, log ρ_{k+1} ≈ 2 log ρ_k
    // once ρ_k is small (down to round-off).
    ASSERT_GE(history.size(), 3u);
    int checked = 0;
    for (std::size_t k = 0; k + 1 < history.size(); ++k) {
      const double now = history[k] / kE, next = history[k + 1] / kE;
      if (now < 1e-3 && next > 1e-13) {
        EXPECT_GT(std::log(next) / std::log(now), 1.8) << "iteration " << k;
        ++checked;
      }
    }
    EXPECT_GE(checked, 1);
  }
}

TEST(PlaneFiniteStrain, RigidRotationBy90DegreesCarriesTheStress) {
  // Stretch by 10 % (all nodes prescribed, homogeneous), then a rigid rotation by 90° in one
  // increment: the stress of the stretch rotates with the body (σ' = Q σ Qᵀ), no more; from the
  // undeformed state the rotation alone gives no stress.
  for (PlaneBehaviour b :
       {PlaneBehaviour::PlaneStress, PlaneBehaviour::PlaneStrain, PlaneBehaviour::Axisymmetric}) {
    if (b == PlaneBehaviour::Axisymmetric) continue;  // a rotation is no axisymmetric motion
    for (PlaneShape shape : {PlaneShape::Quad4, PlaneShape::Quad8, PlaneShape::Tri3}) {
      const std::vector<Vec3> x = square(1.0, 0.0, shape);
      Eigen::Matrix2d q;
      q << 0.0, -1.0, 1.0, 0.0;
      {
        auto e = element(shape, b, PlaneTechnology::Standard, x);
        const Eigen::VectorXd u = homogeneous(x, q);
        Eigen::MatrixXd k;
        Eigen::VectorXd f;
        e->finite_tangent(u, k, f, false);
        EXPECT_LT(f.norm(), 1e-9 * kE);
        for (int p = 0; p < e->n_points(); ++p)
          EXPECT_LT(e->finite_point_stress(u, p).norm(), 1e-9 * kE);
      }
      auto e = element(shape, b, PlaneTechnology::Standard, x);
      Eigen::Matrix2d stretch = Eigen::Matrix2d::Identity();
      stretch(0, 0) = 1.1;
      Eigen::VectorXd u = homogeneous(x, stretch);
      const Eigen::Vector4d before = e->finite_point_stress(u, 0);
      e->commit_history(kLarge, u);
      u = homogeneous(x, q * stretch);
      const Eigen::Vector4d after = e->finite_point_stress(u, 0);
      EXPECT_NEAR(after(1), before(0), 1e-9 * kE);
      EXPECT_NEAR(after(0), before(1), 1e-9 * kE);
      EXPECT_NEAR(after(3), -before(3), 1e-9 * kE);
      EXPECT_NEAR(after(2), before(2), 1e-9 * kE);
    }
  }
}

struct Case {
  PlaneShape shape;
  PlaneBehaviour behaviour;
  PlaneTechnology technology;
  bool plastic;
};

TEST(PlaneFiniteStrain, TangentIsTheDerivativeOfTheInternalForce) {
  // After a committed increment (plastic points yielding), a second increment with stretch,
  // shear and rotation: K against central differences of f_int.
  const std::vector<Case> cases = {
      {PlaneShape::Quad4, PlaneBehaviour::PlaneStress, PlaneTechnology::Standard, false},
      {PlaneShape::Quad4, PlaneBehaviour::PlaneStrain, PlaneTechnology::BBar, false},
      {PlaneShape::Quad4, PlaneBehaviour::PlaneStrain, PlaneTechnology::BBar, true},
      {PlaneShape::Quad4, PlaneBehaviour::Axisymmetric, PlaneTechnology::BBar, true},
      {PlaneShape::Quad4, PlaneBehaviour::Axisymmetric, PlaneTechnology::Standard, false},
      {PlaneShape::Tri3, PlaneBehaviour::PlaneStrain, PlaneTechnology::Standard, true},
      {PlaneShape::Quad8, PlaneBehaviour::Axisymmetric, PlaneTechnology::Standard, true},
      {PlaneShape::Quad8, PlaneBehaviour::PlaneStress, PlaneTechnology::Standard, false},
      {PlaneShape::Tri6, PlaneBehaviour::PlaneStrain, PlaneTechnology::Standard, false},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(static_cast<int>(c.shape) * 100 + static_cast<int>(c.behaviour) * 10 +
                 static_cast<int>(c.technology) + (c.plastic ? 1000 : 0));
    const std::vector<Vec3> x = square(1.0, 0.5, c.shape);
    std::optional<J2Plasticity> law;
    if (c.plastic) law = J2Plasticity::bilinear(kE, kNu, 250.0, 2000.0, false);
    auto e = element(c.shape, c.behaviour, c.technology, x, law);
    Eigen::Matrix2d f1;
    f1 << 1.004, 0.002, -0.001, 0.997;
    Eigen::VectorXd u = homogeneous(x, f1);
    // A non-homogeneous part, so that the points differ.
    for (Eigen::Index i = 0; i < u.size(); ++i) u(i) += 1e-4 * std::sin(1.3 * i + 0.2);
    e->commit_history(kLarge, u);
    {
      // At the committed state (Δu = 0) the non-symmetric part is the rotation terms of the
      // order of σ/E: small beside K.
      Eigen::MatrixXd k0;
      Eigen::VectorXd f0;
      e->finite_tangent(u, k0, f0, false);
      EXPECT_LT((k0 - k0.transpose()).norm(), 0.02 * k0.norm());
    }
    const double angle = 0.3;
    Eigen::Matrix2d f2;
    f2 << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
    Eigen::Matrix2d s2;
    s2 << 1.15, 0.05, 0.02, 0.93;
    u = homogeneous(x, f2 * s2 * f1);
    for (Eigen::Index i = 0; i < u.size(); ++i) u(i) += 2e-3 * std::cos(0.7 * i);
    Eigen::MatrixXd k;
    Eigen::VectorXd f;
    e->finite_tangent(u, k, f, false);
    const double h = 1e-7;
    Eigen::MatrixXd fd(k.rows(), k.cols());
    for (Eigen::Index j = 0; j < u.size(); ++j) {
      Eigen::VectorXd up = u, um = u;
      up(j) += h;
      um(j) -= h;
      Eigen::MatrixXd kk;
      Eigen::VectorXd fp, fm;
      e->finite_tangent(up, kk, fp, false);
      e->finite_tangent(um, kk, fm, false);
      fd.col(j) = (fp - fm) / (2.0 * h);
    }
    EXPECT_LT((k - fd).norm(), 1e-6 * k.norm()) << (k - fd).norm() / k.norm();
  }
}

TEST(PlaneFiniteStrain, UndeformedTangentIsTheSmallStrainStiffness) {
  // At u = 0 from the virgin state: no stress, L = 0, so K is ∫BᵀDB dV, symmetric.
  for (PlaneShape shape :
       {PlaneShape::Quad4, PlaneShape::Quad8, PlaneShape::Tri3, PlaneShape::Tri6}) {
    for (PlaneBehaviour b :
         {PlaneBehaviour::PlaneStress, PlaneBehaviour::PlaneStrain, PlaneBehaviour::Axisymmetric}) {
      const PlaneTechnology t = shape == PlaneShape::Quad4 && b != PlaneBehaviour::PlaneStress
                                    ? PlaneTechnology::BBar
                                    : PlaneTechnology::Standard;
      auto e = element(shape, b, t, square(1.0, 0.0, shape));
      Eigen::MatrixXd k;
      Eigen::VectorXd f;
      e->finite_tangent(Eigen::VectorXd::Zero(e->n_dofs()), k, f, false);
      EXPECT_LT((k - k.transpose()).norm(), 1e-12 * k.norm());
      EXPECT_LT((k - e->stiffness()).norm(), 1e-10 * k.norm());
      EXPECT_LT(f.norm(), 1e-12 * kE);
    }
  }
  (void)kPi;
}

}  // namespace
}  // namespace impactfe::test_plane_finite_strain
