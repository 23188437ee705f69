// Spar (LINK1 / LINK8 / LINK180): stiffness, rigid-body modes, mass, consistent tangents,
// co-rotational rigid rotation, results and input errors. Spec §11.1.
#include <gtest/gtest.h>

#include "../support/element_checks.h"

#include <Eigen/Dense>
#include <cmath>

#include "core/errors.h"
#include "elements/element.h"
#include "elements/spar.h"
#include "materials/linear_elastic.h"

namespace impactfe::test_spar {
namespace {

constexpr double kE = 30e6;      // psi
constexpr double kA = 0.1;       // in²
constexpr double kRho = 7.3e-4;  // lbf·s²/in⁴

SourceLocation e_command() {
  return SourceLocation{"spar.inp", 17, "E"};
}

/// Two-node model: node 1 at xi, node 2 at xj; ET 1 of `type_name`, R 1 (AREA, ISTRN), MAT 1.
Model spar_model(const Vec3& xi, const Vec3& xj, const char* type_name = "LINK8",
                 double istrn = 0.0) {
  Model m;
  m.nodes[1] = Node{1, xi};
  m.nodes[2] = Node{2, xj};
  ElementType et;
  et.id = 1;
  et.ansys_name = type_name;
  m.element_types[1] = et;
  m.real_sets[1] = RealSet{1, {kA, istrn}};
  Material mat;
  mat.id = 1;
  mat.props = {{"EX", kE}, {"DENS", kRho}};
  m.materials[1] = mat;
  return m;
}

ElementRecord spar_record() {
  ElementRecord r;
  r.id = 5;
  r.nodes = {1, 2};
  r.where = e_command();
  return r;
}

std::unique_ptr<Element> build(const Model& m, const ElementRecord& r = spar_record()) {
  return create_element(ElementBuildContext{m, {}}, r);
}

/// Central finite-difference derivative of f_int.
using testing::fd_tangent;

/// Displacements of the two nodes for an infinitesimal rotation w × x (3-D).
Eigen::VectorXd small_rotation(const Vec3& w, const Vec3& xi, const Vec3& xj) {
  Eigen::VectorXd r(6);
  r << w.cross(xi), w.cross(xj);
  return r;
}

TEST(Spar, Link8StiffnessMatchesEAoverLTimesDirectionBlocks) {
  const Vec3 xi(1, 1, 1), xj(2, 3, 3);  // L = 3, n = (1,2,2)/3
  auto e = build(spar_model(xi, xj));
  ASSERT_EQ(e->n_dofs(), 6);
  EXPECT_STREQ(e->family(), "Spar");
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  e->tangent(ElementContext{}, Eigen::VectorXd::Zero(6), K, f);
  const Eigen::Vector3d n = Eigen::Vector3d(1, 2, 2) / 3.0;
  const double k = kE * kA / 3.0;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      EXPECT_NEAR(K(a, b), k * n(a) * n(b), 1e-9 * k);
      EXPECT_NEAR(K(a, 3 + b), -k * n(a) * n(b), 1e-9 * k);
    }
  EXPECT_TRUE(K.isApprox(K.transpose(), 1e-14));
  EXPECT_LT(f.norm(), 1e-12);
}

TEST(Spar, PendulumCase1AxialStiffnessIs3e5) {
  // Spec §11.1: A = 0.1, E = 30e6, L = 10 -> EA/L = 3e5 lb/in.
  auto e = build(spar_model(Vec3(0, 0, 0), Vec3(10, 0, 0)));
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  e->tangent(ElementContext{}, Eigen::VectorXd::Zero(6), K, f);
  EXPECT_NEAR(K(0, 0), 3e5, 1e-6);
  EXPECT_NEAR(K(0, 3), -3e5, 1e-6);
  EXPECT_NEAR(K(1, 1), 0.0, 1e-9);
}

TEST(Spar, RigidBodyModesHaveNoForce3D) {
  const Vec3 xi(0.5, -1, 2), xj(3, 1, -1);
  auto e = build(spar_model(xi, xj));
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  e->tangent(ElementContext{}, Eigen::VectorXd::Zero(6), K, f);
  for (int c = 0; c < 3; ++c) {
    Eigen::VectorXd r = Eigen::VectorXd::Zero(6);
    r(c) = r(3 + c) = 1.0;
    EXPECT_LT((K * r).norm(), 1e-9 * K.norm()) << "translation " << c;
    EXPECT_LT((K * small_rotation(Vec3::Unit(c), xi, xj)).norm(), 1e-9 * K.norm())
        << "rotation " << c;
  }
}

TEST(Spar, Link1IsPlanarWithTwoDofsPerNode) {
  const Vec3 xi(0, 0, 4), xj(3, 4, 4);  // in the plane z = 4, L = 5
  auto e = build(spar_model(xi, xj, "LINK1"));
  ASSERT_EQ(e->n_dofs(), 4);
  EXPECT_EQ(e->dofs()[1].dof, Dof::UY);
  EXPECT_EQ(e->dofs()[2].node, 2);
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  e->tangent(ElementContext{}, Eigen::VectorXd::Zero(4), K, f);
  const double k = kE * kA / 5.0;
  EXPECT_NEAR(K(0, 0), k * 0.36, 1e-9 * k);
  EXPECT_NEAR(K(0, 1), k * 0.48, 1e-9 * k);
  EXPECT_NEAR(K(1, 3), -k * 0.64, 1e-9 * k);
  // Translations and the in-plane rotation (−y, x) are free of force.
  Eigen::VectorXd tx(4), ty(4), rz(4);
  tx << 1, 0, 1, 0;
  ty << 0, 1, 0, 1;
  rz << -xi.y(), xi.x(), -xj.y(), xj.x();
  EXPECT_LT((K * tx).norm(), 1e-9 * k);
  EXPECT_LT((K * ty).norm(), 1e-9 * k);
  EXPECT_LT((K * rz).norm(), 1e-9 * k);
}

TEST(Spar, ConsistentMassSumsToRhoALPerDirection) {
  const Vec3 xi(0, 0, 0), xj(2, 3, 6);  // L = 7
  auto e = build(spar_model(xi, xj));
  Eigen::MatrixXd M;
  e->mass(ElementContext{}, M);
  const double total = kRho * kA * 7.0;
  EXPECT_TRUE(M.isApprox(M.transpose()));
  for (int c = 0; c < 3; ++c) {
    Eigen::VectorXd r = Eigen::VectorXd::Zero(6);
    r(c) = r(3 + c) = 1.0;
    EXPECT_NEAR(r.dot(M * r), total, 1e-12 * total);
  }
  EXPECT_NEAR(M(0, 0), total / 3.0, 1e-15);
  EXPECT_NEAR(M(0, 3), total / 6.0, 1e-15);
  EXPECT_NEAR(M(0, 1), 0.0, 1e-15);
}

TEST(Spar, LumpedMassIsHalfPerNode) {
  auto e = build(spar_model(Vec3(0, 0, 0), Vec3(10, 0, 0), "LINK1"));
  ElementContext ctx;
  ctx.lumped_mass = true;
  Eigen::MatrixXd M;
  e->mass(ctx, M);
  ASSERT_EQ(M.rows(), 4);
  const double half = 0.5 * kRho * kA * 10.0;
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(M(i, i), half, 1e-15);
  EXPECT_NEAR((M - Eigen::MatrixXd(M.diagonal().asDiagonal())).norm(), 0.0, 1e-15);
}

TEST(Spar, LinearInternalForceIsKuPlusInitialStrainForce) {
  const double istrn = 1e-3;
  auto e = build(spar_model(Vec3(0, 0, 0), Vec3(10, 0, 0), "LINK8", istrn));
  Eigen::VectorXd u(6);
  u << 0.001, 0.2, 0.0, 0.004, -0.1, 0.3;
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  e->tangent(ElementContext{}, u, K, f);
  const double N = kE * kA * (0.003 / 10.0 + istrn);  // = 900 + 3000 lbf
  EXPECT_NEAR(f(3), N, 1e-9 * N);
  EXPECT_NEAR(f(0), -N, 1e-9 * N);
  EXPECT_NEAR(f(1), 0.0, 1e-9);
  ElementResultValues out;
  e->results(ElementContext{}, u, Eigen::VectorXd::Zero(6), out);
  ASSERT_EQ(out.size(), e->result_names().size());
  EXPECT_EQ(e->result_names()[1], "SAXL");
  EXPECT_NEAR(out[0], 3900.0, 1e-9);
  EXPECT_NEAR(out[1], 39000.0, 1e-8);
  EXPECT_NEAR(out[2], 0.0013, 1e-15);
}

TEST(Spar, StressStiffnessAtPrestressIsNOverL) {
  const double istrn = 2e-3;  // N = EA·ISTRN = 6000 lbf
  auto e = build(spar_model(Vec3(0, 0, 0), Vec3(10, 0, 0), "LINK8", istrn));
  ElementContext ctx;
  ctx.stress_stiffening = true;
  EXPECT_TRUE(e->is_nonlinear(ctx));
  // Nonlinear also without stress stiffening: the initial strain's force f0 = EA ISTRN makes the
  // internal force K u + f0, which the assembler's linear products K u would miss.
  EXPECT_TRUE(e->is_nonlinear(ElementContext{}));
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  e->tangent(ctx, Eigen::VectorXd::Zero(6), K, f);
  EXPECT_NEAR(K(0, 0), 3e5, 1e-6);
  EXPECT_NEAR(K(1, 1), 600.0, 1e-9);
  EXPECT_NEAR(K(2, 5), -600.0, 1e-9);
  EXPECT_NEAR(K(0, 1), 0.0, 1e-9);
}

TEST(Spar, TangentEqualsFiniteDifferenceOfInternalForce) {
  const Vec3 xi(0.3, -0.2, 0.1), xj(4.0, 2.5, -1.7);
  auto e = build(spar_model(xi, xj, "LINK8", 1.5e-3));
  Eigen::VectorXd u(6);
  u << 0.02, -0.05, 0.03, -0.04, 0.08, 0.01;
  for (int mode = 0; mode < 3; ++mode) {
    ElementContext ctx;
    ctx.stress_stiffening = mode == 1;
    ctx.large_deflection = mode == 2;
    Eigen::MatrixXd K;
    Eigen::VectorXd f;
    e->tangent(ctx, u, K, f);
    const Eigen::MatrixXd Kfd = fd_tangent(*e, ctx, u, 1e-5);
    EXPECT_LT((K - Kfd).norm(), 1e-6 * K.norm()) << "mode " << mode;
    EXPECT_TRUE(K.isApprox(K.transpose(), 1e-12)) << "mode " << mode;
  }
  // Large displacement: a finite rotation plus stretch; the geometric term is significant.
  ElementContext ctx;
  ctx.large_deflection = true;
  u << 0.5, -1.0, 2.0, -3.0, 1.0, 0.7;
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  e->tangent(ctx, u, K, f);
  EXPECT_LT((K - fd_tangent(*e, ctx, u, 1e-5)).norm(), 1e-6 * K.norm());
}

TEST(Spar, Link1LargeDeflectionTangentMatchesFiniteDifference) {
  auto e = build(spar_model(Vec3(0, 0, 0), Vec3(10, 0, 0), "LINK1", 1e-3));
  ElementContext ctx;
  ctx.large_deflection = true;
  Eigen::VectorXd u(4);
  u << 0.1, 0.2, -3.0, 5.0;
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  e->tangent(ctx, u, K, f);
  EXPECT_LT((K - fd_tangent(*e, ctx, u, 1e-5)).norm(), 1e-6 * K.norm());
}

TEST(Spar, CorotationalRigidRotationOf90DegreesHasNoForce) {
  // Pendulum geometry: rotate the bar rigidly by 90° about z through node I, and by 90° about
  // an oblique axis through its midpoint; the small-deflection force would be EA.
  const Vec3 xi(0, 0, 0), xj(10, 0, 0);
  auto e = build(spar_model(xi, xj));
  ElementContext ctx;
  ctx.large_deflection = true;
  Eigen::VectorXd u(6);
  u << 0, 0, 0, -10, 10, 0;
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  e->tangent(ctx, u, K, f);
  EXPECT_LT(f.norm(), 1e-9 * kE * kA);
  // The tangent is EA/L along the new direction (y), zero transverse (N = 0).
  EXPECT_NEAR(K(1, 1), 3e5, 1e-6);
  EXPECT_NEAR(K(0, 0), 0.0, 1e-6);

  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d(1, 1, 1).normalized()).toRotationMatrix();
  const Vec3 c = 0.5 * (xi + xj);
  u << R * (xi - c) + c - xi, R * (xj - c) + c - xj;
  e->tangent(ctx, u, K, f);
  EXPECT_LT(f.norm(), 1e-9 * kE * kA);
  ElementResultValues out;
  e->results(ctx, u, Eigen::VectorXd::Zero(6), out);
  EXPECT_NEAR(out[3], 10.0, 1e-12);
  EXPECT_NEAR(out[0], 0.0, 1e-6);
}

TEST(Spar, CorotationalStretchGivesEngineeringStrainForce) {
  auto e = build(spar_model(Vec3(0, 0, 0), Vec3(0, 0, 10)));
  ElementContext ctx;
  ctx.large_deflection = true;
  // Rotate to the x axis and stretch by 0.01: ℓ = 10.01, N = EA·0.01/10 = 3000 along +x.
  Eigen::VectorXd u(6);
  u << 0, 0, 0, 10.01, 0, -10;
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  e->tangent(ctx, u, K, f);
  EXPECT_NEAR(f(3), 3000.0, 1e-6);
  EXPECT_NEAR(f(5), 0.0, 1e-6);
  EXPECT_NEAR(K(4, 4), 3000.0 / 10.01, 1e-6);  // geometric term N/ℓ
  ElementResultValues out;
  e->results(ctx, u, Eigen::VectorXd::Zero(6), out);
  EXPECT_NEAR(out[0], 3000.0, 1e-6);
  EXPECT_NEAR(out[2], 1e-3, 1e-12);
  EXPECT_NEAR(out[3], 10.01, 1e-12);
}

TEST(Spar, Link180TakesAreaFromLinkSection) {
  Model m = spar_model(Vec3(0, 0, 0), Vec3(10, 0, 0), "LINK180");
  m.real_sets.clear();
  m.sections[3] = Section{3, "LINK", "", {0.25}};
  ElementRecord r = spar_record();
  r.secnum = 3;
  auto e = create_element(ElementBuildContext{m, {}}, r);
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  e->tangent(ElementContext{}, Eigen::VectorXd::Zero(6), K, f);
  EXPECT_NEAR(K(0, 0), kE * 0.25 / 10.0, 1e-6);
}

void expect_input_error_at_e(const Model& m, const char* fragment) {
  try {
    build(m);
    FAIL() << "no InputError for: " << fragment;
  } catch (const InputError& err) {
    EXPECT_EQ(err.where().line, 17);
    EXPECT_EQ(err.where().command, "E");
    EXPECT_NE(std::string(err.what()).find("spar.inp:17: E:"), std::string::npos);
    EXPECT_NE(err.message().find(fragment), std::string::npos) << err.message();
  }
}

TEST(Spar, InputErrorsNameTheECommand) {
  Model no_ex = spar_model(Vec3(0, 0, 0), Vec3(1, 0, 0));
  no_ex.materials[1].props.erase("EX");
  expect_input_error_at_e(no_ex, "EX");

  Model no_mat = spar_model(Vec3(0, 0, 0), Vec3(1, 0, 0));
  no_mat.materials.clear();
  expect_input_error_at_e(no_mat, "material 1");

  expect_input_error_at_e(spar_model(Vec3(1, 2, 3), Vec3(1, 2, 3)), "zero length");

  Model no_area = spar_model(Vec3(0, 0, 0), Vec3(1, 0, 0));
  no_area.real_sets[1].values = {0.0};
  expect_input_error_at_e(no_area, "AREA");

  Model no_real = spar_model(Vec3(0, 0, 0), Vec3(1, 0, 0));
  no_real.real_sets.clear();
  expect_input_error_at_e(no_real, "real constant set 1");

  expect_input_error_at_e(spar_model(Vec3(0, 0, 0), Vec3(1, 0, 1), "LINK1"), "X-Y plane");
}

TEST(Spar, DefaultDensityIsZero) {
  Model m = spar_model(Vec3(0, 0, 0), Vec3(1, 0, 0));
  m.materials[1].props.erase("DENS");
  auto e = build(m);
  Eigen::MatrixXd M;
  e->mass(ElementContext{}, M);
  EXPECT_EQ(M.norm(), 0.0);
}

TEST(LinearElastic, DefaultsAndPrxyAlias) {
  Model m = spar_model(Vec3(0, 0, 0), Vec3(1, 0, 0));
  m.materials[1].props = {{"EX", 2.6e6}};
  ElasticMaterial mat = elastic_material(m, spar_record(), "Spar");
  EXPECT_DOUBLE_EQ(mat.youngs_modulus, 2.6e6);
  EXPECT_DOUBLE_EQ(mat.poisson_ratio, 0.3);
  EXPECT_DOUBLE_EQ(mat.density, 0.0);
  m.materials[1].props["PRXY"] = 0.25;
  EXPECT_DOUBLE_EQ(elastic_material(m, spar_record(), "Spar").poisson_ratio, 0.25);
  m.materials[1].props["NUXY"] = 0.33;
  EXPECT_DOUBLE_EQ(elastic_material(m, spar_record(), "Spar").poisson_ratio, 0.33);
  m.materials[1].props["EX"] = 0.0;
  EXPECT_THROW(elastic_material(m, spar_record(), "Spar"), InputError);
}

}  // namespace
}  // namespace impactfe::test_spar
