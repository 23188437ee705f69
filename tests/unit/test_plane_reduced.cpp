// PLANE182 KEYOPT(1) = 1 (uniform reduced integration, src/elements/plane_solid_reduced.cpp):
// the one-point part against Flanagan & Belytschko's closed-form gradient vectors, the
// stabilisation confined to their two hourglass vectors γ, the elastic stiffness equal to the
// incompatible-mode element's, and a 10 x 2 cantilever against beam theory (no locking, no
// hourglass). Rigid modes, the distorted patch test, mass and the plastic material point are
// in test_plane_solid.cpp and test_plastic_planes.cpp (their variants include Reduced).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <memory>
#include <set>
#include <string>

#include "../support/dense_assembly.h"
#include "elements/plane_solid.h"

namespace impactfe::test_plane_reduced {
namespace {

constexpr double kE = 200e3, kNu = 0.3, kT = 0.7;

std::unique_ptr<PlaneSolid> quad(PlaneTechnology tech, PlaneBehaviour b,
                                 const std::vector<int>& ids, const std::vector<Vec3>& x) {
  PlaneSolidOptions o{PlaneShape::Quad4, b, tech, kT};
  return std::make_unique<PlaneSolid>(ids.front(), ids, x, IsotropicElasticity{kE, kNu, 0.0}, o,
                                      std::vector<std::vector<int>>{});
}

const std::vector<Vec3> kDistorted = {Vec3(1.0, 0.2, 0), Vec3(3.1, 0.0, 0), Vec3(2.6, 1.9, 0),
                                      Vec3(1.2, 1.4, 0)};

int rank(const Eigen::MatrixXd& k) {
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(k).eigenvalues();
  int r = 0;
  for (int i = 0; i < ev.size(); ++i) r += std::abs(ev(i)) > 1e-9 * ev.cwiseAbs().maxCoeff();
  return r;
}

TEST(PlaneReduced, OnePointPartAndHourglassVectors) {
  for (PlaneBehaviour b : {PlaneBehaviour::PlaneStress, PlaneBehaviour::PlaneStrain}) {
    const auto e = quad(PlaneTechnology::Reduced, b, {1, 2, 3, 4}, kDistorted);
    // Flanagan & Belytschko (1981) eq. (17): b_x = ½ (y24, y31, y42, y13) / A at the centre,
    // b_y = ½ (x42, x13, x24, x31) / A, A the exact area of the quadrilateral.
    Eigen::Vector4d x, y, bx, by;
    for (int a = 0; a < 4; ++a) x(a) = kDistorted[a](0), y(a) = kDistorted[a](1);
    const double area = 0.5 * ((x(2) - x(0)) * (y(3) - y(1)) + (x(1) - x(3)) * (y(2) - y(0)));
    bx << y(1) - y(3), y(2) - y(0), y(3) - y(1), y(0) - y(2);
    by << x(3) - x(1), x(0) - x(2), x(1) - x(3), x(2) - x(0);
    bx /= 2 * area;
    by /= 2 * area;
    Eigen::MatrixXd b0 = Eigen::MatrixXd::Zero(4, 8);
    for (int a = 0; a < 4; ++a) {
      b0(0, 2 * a) = bx(a), b0(1, 2 * a + 1) = by(a);
      b0(3, 2 * a) = by(a), b0(3, 2 * a + 1) = bx(a);
    }
    Eigen::Matrix4d d = Eigen::Matrix4d::Zero();
    if (b == PlaneBehaviour::PlaneStress) {
      const double c = kE / (1 - kNu * kNu);
      d(0, 0) = d(1, 1) = c, d(0, 1) = d(1, 0) = c * kNu, d(3, 3) = c * (1 - kNu) / 2;
    } else {
      const double l = kE * kNu / ((1 + kNu) * (1 - 2 * kNu)), m = kE / (2 * (1 + kNu));
      d.topLeftCorner<3, 3>().setConstant(l);
      d(0, 0) = d(1, 1) = d(2, 2) = l + 2 * m, d(3, 3) = m;
    }
    const Eigen::MatrixXd k0 = area * kT * b0.transpose() * d * b0;
    const Eigen::MatrixXd hg = e->stiffness() - k0;
    // γ = h − (h·x) b_x − (h·y) b_y (their eq. (30)): orthogonal to 1, x and y.
    const Eigen::Vector4d h(1, -1, 1, -1);
    const Eigen::Vector4d gamma = h - h.dot(x) * bx - h.dot(y) * by;
    EXPECT_EQ(rank(hg), 2);
    Eigen::MatrixXd basis = Eigen::MatrixXd::Zero(8, 2);  // γ on UX, γ on UY
    for (int a = 0; a < 4; ++a) basis(2 * a, 0) = basis(2 * a + 1, 1) = gamma(a);
    // Every column of the stabilisation lies in span{γ ⊗ e_x, γ ⊗ e_y} (symmetric: rows too).
    const Eigen::MatrixXd projector =
        basis * (basis.transpose() * basis).inverse() * basis.transpose();
    EXPECT_LT((hg - projector * hg).norm(), 1e-10 * hg.norm());
    EXPECT_GT(hg.norm(), 1e-3 * k0.norm());
  }
}

TEST(PlaneReduced, ElasticStiffnessEqualsTheIncompatibleModeElement) {
  // Σ_q dV_q (B_q − B̄ + G_q α) = 0: the mean strain plus the stabilisation is the
  // incompatible-mode element's elastic energy, for any shape and behaviour; the formulations
  // differ once the one point is inelastic (test_plastic_planes).
  const std::vector<Vec3> parallelogram = {Vec3(1, 0, 0), Vec3(3, 0.4, 0), Vec3(3.5, 1.4, 0),
                                           Vec3(1.5, 1.0, 0)};
  for (const auto& x : {parallelogram, kDistorted})
    for (PlaneBehaviour b :
         {PlaneBehaviour::PlaneStress, PlaneBehaviour::PlaneStrain, PlaneBehaviour::Axisymmetric}) {
      const auto r = quad(PlaneTechnology::Reduced, b, {1, 2, 3, 4}, x);
      const auto m = quad(PlaneTechnology::IncompatibleModes, b, {1, 2, 3, 4}, x);
      EXPECT_LT((r->stiffness() - m->stiffness()).norm(), 1e-12 * m->stiffness().norm());
    }
}

TEST(PlaneReduced, CantileverTenByTwoNeitherLocksNorHourglasses) {
  // A cantilever L = 10, depth h = 1, 10 x 2 elements, a tip shear P distributed 1/4, 1/2,
  // 1/4 over the three tip nodes, plane stress,
  // clamped end. Timoshenko & Goodier §21: v(L) = PL³/(3EI) + (4 + 5ν) P L h² / (24 E I) at
  // the axis (its clamp differs from this fully clamped end by a fraction of the shear term).
  // Tolerance 3 %; full 2x2 integration (Standard) locks to below 80 %.
  const double length = 10.0, h = 1.0, load = 10.0;
  const int nx = 10, ny = 2;
  auto id = [&](int i, int j) { return 1 + i + (nx + 1) * j; };
  auto xy = [&](int i, int j) { return Vec3(length * i / nx, h * j / ny, 0.0); };
  const double inertia = kT * h * h * h / 12.0;
  const double exact = load * length * length * length / (3 * kE * inertia) +
                       (4 + 5 * kNu) * load * length * h * h / (24 * kE * inertia);
  for (PlaneTechnology tech : {PlaneTechnology::Reduced, PlaneTechnology::Standard}) {
    std::vector<std::unique_ptr<Element>> elements;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        elements.push_back(quad(tech, PlaneBehaviour::PlaneStress,
                                {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)},
                                {xy(i, j), xy(i + 1, j), xy(i + 1, j + 1), xy(i, j + 1)}));
    testing::DenseSystem sys(elements);
    std::set<DofKey> fixed;
    for (int j = 0; j <= ny; ++j) fixed.insert({{id(0, j), Dof::UX}, {id(0, j), Dof::UY}});
    Eigen::VectorXd f = Eigen::VectorXd::Zero(sys.n());
    f(sys.index(id(nx, 0), Dof::UY)) = 0.25 * load;
    f(sys.index(id(nx, 1), Dof::UY)) = 0.5 * load;
    f(sys.index(id(nx, 2), Dof::UY)) = 0.25 * load;
    const Eigen::VectorXd u = sys.solve_static(f, fixed);
    const double tip = u(sys.index(id(nx, 1), Dof::UY));
    RecordProperty(tech == PlaneTechnology::Reduced ? "reduced_tip_ratio" : "full_tip_ratio",
                   std::to_string(tip / exact));
    if (tech == PlaneTechnology::Standard) {
      EXPECT_LT(tip / exact, 0.8);
      continue;
    }
    EXPECT_NEAR(tip / exact, 1.0, 0.03);
    // No hourglass pattern: the deflection is the same across the depth at every station, and
    // the bending strain UX is antisymmetric about the axis (top = −bottom, axis 0).
    for (int i = 1; i <= nx; ++i) {
      const double mid = u(sys.index(id(i, 1), Dof::UY));
      for (int j : {0, 2}) EXPECT_NEAR(u(sys.index(id(i, j), Dof::UY)), mid, 0.01 * tip) << i;
      const double top = u(sys.index(id(i, 2), Dof::UX)), bottom = u(sys.index(id(i, 0), Dof::UX));
      EXPECT_NEAR(top / -bottom, 1.0, 1e-6) << i;
      EXPECT_LT(std::abs(u(sys.index(id(i, 1), Dof::UX))), 1e-6 * std::abs(top)) << i;
    }
  }
}

}  // namespace
}  // namespace impactfe::test_plane_reduced
