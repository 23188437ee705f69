// A rigid TARGE170 target turning with its pilot's rotations (issue 16): the pilot's ROTX..ROTZ
// join the contact element's DOFs when an element with rotations sits on the pilot; the gap of a
// node against the rotated plate and the moment on the pilot against their closed forms, the
// tangent with the rotation terms against finite differences (frictionless, sticking, sliding),
// and an unrotated pilot is the translating target of before.
#include <gtest/gtest.h>

#include "../support/element_checks.h"
#include "../support/model_records.h"

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "elements/element.h"
#include "elements/element_registry.h"
#include "elements/so3.h"

namespace impactfe::test_contact_rotating {
namespace {

ElementRecord record(int id, int type_id, int real, int mat, std::vector<int> nodes) {
  return testing::element_record(id, type_id, real, mat, std::move(nodes), "rotating.inp");
}

constexpr double kA = 2.0, kH = 0.05, kKn = 1000.0;

/// Pilot 1 at the origin carrying a MASS21 (KEYOPT(3) `mass_keyopt3`: 0 with rotary inertia, 2
/// without); a rigid plate z = 0 (one quad ±3, normal +Z) on it; CONTA175 (element 20) on node
/// 10 at (kA, 0, kH), penalty FKN = −kKn, FKT = −500, PINB −1, MU `mu`.
Model model(double mu = 0.0, int mass_keyopt3 = 0) {
  Model m;
  m.nodes[1] = Node{1, Vec3::Zero()};
  m.nodes[2] = Node{2, Vec3(-3, -3, 0)};
  m.nodes[3] = Node{3, Vec3(3, -3, 0)};
  m.nodes[4] = Node{4, Vec3(3, 3, 0)};
  m.nodes[5] = Node{5, Vec3(-3, 3, 0)};
  m.nodes[10] = Node{10, Vec3(kA, 0, kH)};
  m.element_types[1] = testing::element_type(1, "MASS21");
  m.element_types[1].keyopt[3] = mass_keyopt3;
  m.element_types[2] = testing::element_type(2, "TARGE170");
  m.element_types[3] = testing::element_type(3, "CONTA175", 1);
  Material mat;
  mat.id = 1;
  mat.props["MU"] = mu;
  m.materials[1] = mat;
  m.real_sets[1] = RealSet{1, {1.0, 1.0, 1.0, 1.0, 1.0, 1.0}};
  m.real_sets[3] = RealSet{3, {0.0, 0.0, -kKn, -1e-6, 0.0, -1.0, 0.0, 0.0, 0.0, 0.0, 0.0, -500.0}};
  m.elements[1] = record(1, 1, 1, 1, {1});
  m.elements[2] = record(2, 2, 3, 1, {1});
  m.elements[3] = record(3, 2, 3, 1, {2, 3, 4, 5});
  m.elements[20] = record(20, 3, 3, 1, {10});
  return m;
}

std::unique_ptr<Element> build(const Model& m, int id) {
  return create_element(ElementBuildContext{m, {}}, m.elements.at(id));
}

/// DOF order: pilot UX UY UZ, node UX UY UZ, pilot ROTX ROTY ROTZ.
Eigen::VectorXd dofs(const Vec3& pilot, const Vec3& node, const Vec3& psi) {
  Eigen::VectorXd u(9);
  u << pilot, node, psi;
  return u;
}

/// The pilot moved by `up` and turned by ψ, the node carried along with the plate, then moved by
/// R (`along` − depth e_z) from its initial place on the plate (a slip `along`, a penetration).
Eigen::VectorXd on_plate(const Vec3& up, const Vec3& psi, const Vec3& along, double depth) {
  const Eigen::Matrix3d R = so3::exp_map(psi);
  const Vec3 xs0(kA, 0.0, kH);
  const Vec3 xs = up + R * (xs0 + along - Vec3(0.0, 0.0, depth));
  return dofs(up, xs - xs0, psi);
}

TEST(RotatingTarget, PilotRotationsJoinTheDofsOnlyWhenThePilotCarriesThem) {
  const auto e = build(model(), 20);
  ASSERT_EQ(e->n_dofs(), 9);
  EXPECT_EQ(e->dofs()[6].node, 1);
  EXPECT_EQ(e->dofs()[6].dof, Dof::ROTX);
  EXPECT_EQ(e->dofs()[8].dof, Dof::ROTZ);
  // A pilot without rotations (MASS21 KEYOPT(3) = 2): the translating target of before.
  EXPECT_EQ(build(model(0.0, 2), 20)->n_dofs(), 6);
}

TEST(RotatingTarget, GapAndMomentOfAPlateTurnedAboutThePilot) {
  // The plate turned by φ about +Y: n = (sin φ, 0, cos φ); the node at (a, 0, h) has the gap
  // g = a sin φ + h cos φ, so φ = −θ with a tan θ > h presses it. The contact pushes the node
  // with p n, p = k_n (−g); the pilot takes −p n through the contact point, whose moment about
  // the pilot is −p x_s × n: |M_y| = p × arm with arm = a cos φ − h sin φ (the distance of the
  // line of action from the pilot). The force conjugate to ψ is T(ψ)ᵀ m, whose component
  // along the rotation axis is m_y itself (T(ψ) ψ = ψ).
  auto e = build(model(), 20);
  const ElementContext ctx;
  for (double theta : {0.03, 0.2, 0.4}) {  // |g| within the pinball (1)
    SCOPED_TRACE(theta);
    const double phi = -theta;
    const Eigen::VectorXd u = dofs(Vec3::Zero(), Vec3::Zero(), Vec3(0, phi, 0));
    e->update_status(ctx, u);
    const double g = kA * std::sin(phi) + kH * std::cos(phi);
    ASSERT_LT(g, 0.0);
    ASSERT_NE(e->status(), GapStatus::Open);
    ElementResultValues r;
    e->results(ctx, u, Eigen::VectorXd::Zero(9), r);
    EXPECT_NEAR(r[3], g, 1e-12);        // GAP
    EXPECT_NEAR(r[1], -kKn * g, 1e-9);  // FN
    Eigen::MatrixXd K;
    Eigen::VectorXd f;
    e->tangent(ctx, u, K, f);
    const double p = -kKn * g;
    const Vec3 n(std::sin(phi), 0.0, std::cos(phi));
    // Internal forces: −p n on the node, +p n on the pilot, the moment on the pilot ROTY.
    EXPECT_LT((f.segment<3>(3) + p * n).norm(), 1e-9 * p);
    EXPECT_LT((f.segment<3>(0) - p * n).norm(), 1e-9 * p);
    const double arm = kA * std::cos(phi) - kH * std::sin(phi);
    EXPECT_NEAR(std::abs(f(7)), p * arm, 1e-9 * p);
    EXPECT_NEAR(f(6), 0.0, 1e-9 * p);
    EXPECT_NEAR(f(8), 0.0, 1e-9 * p);
    // The pilot rotation that lifts the plate (φ < 0) meets the reaction: the moment resists it.
    EXPECT_LT(f(7), 0.0);
  }
}

TEST(RotatingTarget, FrictionlessTangentWithRotationsIsConsistentAndSymmetric) {
  auto e = build(model(), 20);
  const ElementContext ctx;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> r(-0.05, 0.05);
  for (const Vec3 psi : {Vec3(0.0, -0.1, 0.0), Vec3(0.2, -0.3, 0.4), Vec3(1e-9, -0.05, 2.0)}) {
    SCOPED_TRACE(psi.transpose());
    const Eigen::VectorXd u =
        on_plate(Vec3(r(rng), r(rng), r(rng)), psi, Vec3(r(rng), r(rng), 0.0), 0.3);
    e->update_status(ctx, u);
    ASSERT_NE(e->status(), GapStatus::Open);
    Eigen::MatrixXd K;
    Eigen::VectorXd f;
    e->tangent(ctx, u, K, f);
    const Eigen::MatrixXd fd = testing::fd_tangent(*e, ctx, u, 1e-7);
    EXPECT_LT((K - fd).norm(), 1e-6 * K.norm());
    EXPECT_LT((K - K.transpose()).norm(), 1e-12 * K.norm());
    // Force balance of the translations: Σ f over pilot and node vanishes.
    EXPECT_LT((f.segment<3>(0) + f.segment<3>(3)).norm(), 1e-12 * f.norm());
  }
}

TEST(RotatingTarget, FrictionTangentWithRotationsStickingAndSliding) {
  // Sticking: exact and symmetric. Sliding: exact but for the dropped −μ k_n Tᵀ d Gᵀ
  // (contact_point.h), which is k_n (f − f₀) f₀ᵀ / p² with f₀ the frictionless force.
  const Model m = model(0.3), m0 = model(0.0);
  const ElementContext ctx;
  const Vec3 psi(0.1, -0.2, 0.3);
  for (const double offset : {1e-3, 0.2}) {
    SCOPED_TRACE(offset);
    auto e = build(m, 20);
    auto e0 = build(m0, 20);
    const Eigen::VectorXd u =
        on_plate(Vec3(0.01, -0.02, 0.03), psi, Vec3(offset, 0.5 * offset, 0.0), 0.3);
    e->update_status(ctx, u);
    e0->update_status(ctx, u);
    ASSERT_EQ(e->status(), offset < 0.01 ? GapStatus::Closed : GapStatus::Sliding);
    Eigen::MatrixXd K, K0;
    Eigen::VectorXd f, f0;
    e->tangent(ctx, u, K, f);
    e0->tangent(ctx, u, K0, f0);
    ElementResultValues r;
    e->results(ctx, u, Eigen::VectorXd::Zero(9), r);
    const double p = r[1];
    ASSERT_GT(r[4], 1e-3 * p);  // a friction force is there
    const Eigen::MatrixXd dropped =
        offset < 0.01 ? Eigen::MatrixXd::Zero(9, 9)
                      : Eigen::MatrixXd(kKn * (f - f0) * f0.transpose() / (p * p));
    const Eigen::MatrixXd fd = testing::fd_tangent(*e, ctx, u, 1e-7);
    EXPECT_LT((K + dropped - fd).norm(), 1e-6 * K.norm());
    EXPECT_LT((K - K.transpose()).norm(), 1e-10 * K.norm());
  }
}

TEST(RotatingTarget, UnrotatedPilotGivesTheTranslatingTargetsForces) {
  // ψ = 0: the same gap, forces and translational tangent as the 6-DOF point pair.
  auto e = build(model(0.3), 20);
  auto t = build(model(0.3, 2), 20);
  const ElementContext ctx;
  const Vec3 up(0.01, 0.02, -0.01), un(0.003, -0.002, -0.2);
  Eigen::VectorXd u9 = dofs(up, un, Vec3::Zero());
  Eigen::VectorXd u6(6);
  u6 << up, un;
  e->update_status(ctx, u9);
  t->update_status(ctx, u6);
  Eigen::MatrixXd K9, K6;
  Eigen::VectorXd f9, f6;
  e->tangent(ctx, u9, K9, f9);
  t->tangent(ctx, u6, K6, f6);
  EXPECT_LT((f9.head(6) - f6).norm(), 1e-12 * f6.norm());
  EXPECT_LT((K9.topLeftCorner(6, 6) - K6).norm(), 1e-12 * K6.norm());
}

}  // namespace
}  // namespace impactfe::test_contact_rotating
