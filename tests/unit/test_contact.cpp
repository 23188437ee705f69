// Contact elements (issue 16, APDL_MODELING §8.4): CONTA178 point law (statuses, tangent against
// finite differences, equilibrium of the element forces), the TARGE170 bucket-grid search
// against a brute-force search, and CONTA175 against a two-facet rigid target.
#include <gtest/gtest.h>

#include "../support/element_checks.h"
#include "../support/model_records.h"

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "core/errors.h"
#include "elements/element.h"
#include "elements/element_registry.h"
#include "elements/target_surface.h"

namespace impactfe::test_contact {
namespace {

ElementRecord record(int id, int type_id, int real, int mat, std::vector<int> nodes) {
  return testing::element_record(id, type_id, real, mat, std::move(nodes), "contact.inp");
}

/// Two coincident nodes, contact normal +Y, penalty FKN = 1000 (absolute), FKS = 500, MU = 0.3.
Model conta178_model(int keyopt2 = 1, int keyopt12 = 0, double mu = 0.3) {
  Model m;
  m.nodes[1] = Node{1, Vec3::Zero()};
  m.nodes[2] = Node{2, Vec3::Zero()};
  m.element_types[1] = testing::element_type(1, "CONTA178", keyopt2, keyopt12);
  m.real_sets[1] = RealSet{1, {-1000.0, 0.0, 0.0, 500.0, 0.0, 0.0, 1.0, 0.0}};
  Material mat;
  mat.id = 1;
  mat.props["MU"] = mu;
  m.materials[1] = mat;
  m.elements[7] = record(7, 1, 1, 1, {1, 2});
  return m;
}

std::unique_ptr<Element> build(const Model& m, int id) {
  return create_element(ElementBuildContext{m, {}}, m.elements.at(id));
}

Eigen::VectorXd uj(double x, double y, double z) {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(6);
  u << 0.0, 0.0, 0.0, x, y, z;
  return u;
}

std::vector<double> results(const Element& e, const Eigen::VectorXd& u) {
  ElementResultValues out;
  e.results(ElementContext{}, u, Eigen::VectorXd::Zero(6), out);
  return out;  // STAT FN PENE GAP FT SLIDE
}

TEST(Conta178, OpenClosedStickSlideStatuses) {
  const Model m = conta178_model();
  auto e = build(m, 7);
  const ElementContext ctx;
  EXPECT_TRUE(e->has_status());
  // Separated by 0.01 along the normal: open, no force.
  e->update_status(ctx, uj(0.0, 0.01, 0.0));
  EXPECT_EQ(e->status(), GapStatus::Open);
  EXPECT_DOUBLE_EQ(results(*e, uj(0.0, 0.01, 0.0))[1], 0.0);
  // Pressed 0.01 into I with a small tangential offset: closed and sticking, p = k_n 0.01.
  const Eigen::VectorXd u = uj(0.001, -0.01, 0.0);
  EXPECT_TRUE(e->update_status(ctx, u));
  EXPECT_EQ(e->status(), GapStatus::Closed);
  const auto r = results(*e, u);
  EXPECT_DOUBLE_EQ(r[0], 3.0);
  EXPECT_NEAR(r[1], 10.0, 1e-12);
  EXPECT_NEAR(r[2], 0.01, 1e-15);
  EXPECT_NEAR(r[4], 0.5, 1e-12);
  // Far along the surface: the friction limit mu p = 3 is exceeded, sliding.
  const Eigen::VectorXd w = uj(0.1, -0.01, 0.02);
  EXPECT_TRUE(e->update_status(ctx, w));
  EXPECT_EQ(e->status(), GapStatus::Sliding);
  EXPECT_NEAR(results(*e, w)[4], 3.0, 1e-12);
}

TEST(Conta178, StickTangentEqualsFiniteDifferencesAndForcesBalance) {
  const Model m = conta178_model();
  auto e = build(m, 7);
  const ElementContext ctx;
  const Eigen::VectorXd u = uj(0.002, -0.01, -0.001);
  e->update_status(ctx, u);
  ASSERT_EQ(e->status(), GapStatus::Closed);
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  e->tangent(ctx, u, K, f);
  EXPECT_LT((K - testing::fd_tangent(*e, ctx, u, 1e-7)).norm(), 1e-6 * K.norm());
  EXPECT_LT((K - K.transpose()).norm(), 1e-12 * K.norm());
  // Action and reaction; a rigid translation of both nodes changes nothing.
  EXPECT_LT((f.head(3) + f.tail(3)).norm(), 1e-12);
  Eigen::VectorXd shifted = u;
  for (int i = 0; i < 6; ++i) shifted(i) += (i % 3 == 0) ? 0.3 : -0.2;
  Eigen::MatrixXd K2;
  Eigen::VectorXd f2;
  e->tangent(ctx, shifted, K2, f2);
  EXPECT_LT((f2 - f).norm(), 1e-12);
}

TEST(Conta178, SlideTangentIsTheSymmetricPartOfTheFiniteDifferences) {
  const Model m = conta178_model();
  auto e = build(m, 7);
  const ElementContext ctx;
  const Eigen::VectorXd u = uj(0.1, -0.01, 0.02);
  e->update_status(ctx, u);
  ASSERT_EQ(e->status(), GapStatus::Sliding);
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  e->tangent(ctx, u, K, f);
  const Eigen::MatrixXd fd = testing::fd_tangent(*e, ctx, u, 1e-7);
  EXPECT_LT((K - K.transpose()).norm(), 1e-12 * K.norm());
  // Rows and columns of J's tangential (x, z) and normal (y) DOFs: equal except the dropped
  // coupling d f_t / d u_n = μ k_n d (Wriggers eq. 5.61's non-symmetric term).
  for (int a : {3, 5})
    for (int b : {3, 5}) EXPECT_NEAR(K(a, b), fd(a, b), 1e-5 * K.norm()) << a << "," << b;
  EXPECT_NEAR(K(4, 4), fd(4, 4), 1e-5 * K.norm());
  const Eigen::Vector2d dir = Eigen::Vector2d(0.1, 0.02).normalized();
  EXPECT_NEAR(fd(3, 4), -0.3 * 1000.0 * dir(0), 1e-4);
  EXPECT_DOUBLE_EQ(K(3, 4), 0.0);
}

TEST(Conta178, BondedHoldsInTensionAndStandardOpens) {
  const ElementContext ctx;
  const Eigen::VectorXd pull = uj(0.0, 0.01, 0.0);
  auto bonded = build(conta178_model(1, 5), 7);
  bonded->update_status(ctx, pull);
  EXPECT_NE(bonded->status(), GapStatus::Open);
  EXPECT_NEAR(results(*bonded, pull)[1], -10.0, 1e-12);  // tension carried
  auto standard = build(conta178_model(1, 0), 7);
  standard->update_status(ctx, pull);
  EXPECT_EQ(standard->status(), GapStatus::Open);
}

TEST(Conta178, AugmentedLagrangeRemovesThePenetrationOfAFixedLoad) {
  // One node pressed by F = 10 against a fixed one: the multiplier update λ ← λ − k_n g makes the
  // next equilibrium iterate exact (penetration 0), in at most two augmentations.
  auto e = build(conta178_model(0), 7);
  const ElementContext ctx;
  const double F = 10.0, kn = 1000.0;
  double y = -F / kn;  // penalty equilibrium
  int updates = 0;
  while (e->update_status(ctx, uj(0.0, y, 0.0)) && updates < 5) {
    ++updates;
    const double p = results(*e, uj(0.0, y, 0.0))[1];
    y += (p - F) / kn;  // Newton on the contact spring alone: kn Δy = p − F
  }
  EXPECT_LE(updates, 2);
  EXPECT_NEAR(y, 0.0, 1e-12);
  EXPECT_NEAR(results(*e, uj(0.0, y, 0.0))[1], F, 1e-9);
}

TEST(Conta178, RejectsLagrangeAndUnknownKeyopts) {
  EXPECT_THROW(build(conta178_model(4), 7), InputError);
  Model m = conta178_model();
  m.element_types[1].keyopt[10] = 1;
  EXPECT_THROW(build(m, 7), InputError);
  Model c = conta178_model();
  c.real_sets[1].values = {-1000.0};  // coincident nodes and no NX, NY, NZ
  EXPECT_THROW(build(c, 7), InputError);
}

TEST(TargetSurface, BucketSearchEqualsBruteForce) {
  // A bumpy 20 x 20 triangulated surface z = 0.3 sin x cos y over [0, 10]².
  std::vector<TargetSurface::Triangle> tris;
  const auto p = [](int i, int j) {
    const double x = 0.5 * i, y = 0.5 * j;
    return Vec3(x, y, 0.3 * std::sin(x) * std::cos(y));
  };
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j) {
      const Vec3 a = p(i, j), b = p(i + 1, j), c = p(i + 1, j + 1), d = p(i, j + 1);
      tris.push_back({a, b, c, (b - a).cross(c - a).normalized()});
      tris.push_back({a, c, d, (c - a).cross(d - a).normalized()});
    }
  const TargetSurface surface(99, tris);
  std::mt19937 rng(16);
  std::uniform_real_distribution<double> xy(-1.0, 11.0), z(-0.8, 0.8);
  int hits = 0;
  for (int q = 0; q < 2000; ++q) {
    const Vec3 y(xy(rng), xy(rng), z(rng));
    const double reach = 0.4;
    std::optional<double> best;
    for (const auto& t : tris) {
      const double g = (y - t.a).dot(t.normal);
      if (std::abs(g) > reach) continue;
      const Vec3 pr = y - g * t.normal;
      const Vec3 v0 = t.b - t.a, v1 = t.c - t.a, v2 = pr - t.a;
      const double d00 = v0.dot(v0), d01 = v0.dot(v1), d11 = v1.dot(v1);
      const double den = d00 * d11 - d01 * d01;
      const double v = (d11 * v2.dot(v0) - d01 * v2.dot(v1)) / den;
      const double w = (d00 * v2.dot(v1) - d01 * v2.dot(v0)) / den;
      if (v < -1e-9 || w < -1e-9 || v + w > 1.0 + 1e-9) continue;
      if (!best || std::abs(g) < std::abs(*best)) best = g;
    }
    const auto hit = surface.closest(y, reach);
    ASSERT_EQ(hit.has_value(), best.has_value()) << q;
    if (hit) {
      ++hits;
      EXPECT_NEAR(std::abs(hit->gap), std::abs(*best), 1e-12) << q;
    }
  }
  EXPECT_GT(hits, 500);
}

/// A valley of two quads meeting at x = 0 (z = |x|, slopes of 45°), its pilot node 50, and
/// CONTA175 on node 1.
Model conta175_model(const Vec3& x1) {
  Model m;
  m.nodes[1] = Node{1, x1};
  m.nodes[50] = Node{50, Vec3(0, 0, -5)};
  m.nodes[51] = Node{51, Vec3(-2, -2, 2)};
  m.nodes[52] = Node{52, Vec3(0, -2, 0)};
  m.nodes[53] = Node{53, Vec3(0, 2, 0)};
  m.nodes[54] = Node{54, Vec3(-2, 2, 2)};
  m.nodes[55] = Node{55, Vec3(2, -2, 2)};
  m.nodes[56] = Node{56, Vec3(2, 2, 2)};
  m.element_types[1] = testing::element_type(1, "TARGE170");
  m.element_types[2] = testing::element_type(2, "CONTA175", 1);
  // FKN = -1000 (absolute), PINB = -1 (absolute), FTOLN = -1e-6.
  m.real_sets[3] = RealSet{3, {0.0, 0.0, -1000.0, -1e-6, 0.0, -1.0}};
  m.elements[1] = record(1, 1, 3, 1, {50, 50, 50, 50});
  m.elements[2] = record(2, 1, 3, 1, {51, 52, 53, 54});  // left slope, normal (1, 0, 1)/√2
  m.elements[3] = record(3, 1, 3, 1, {52, 55, 56, 53});  // right slope, normal (-1, 0, 1)/√2
  m.elements[4] = record(4, 2, 3, 1, {1});
  return m;
}

TEST(Conta175, FindsTheFacetUnderTheNodeAndFollowsThePilot) {
  const ElementContext ctx;
  // Node above the right slope (z = x there), 0.1 below its surface: penetration 0.1/√2.
  auto e = build(conta175_model(Vec3(1.0, 0.0, 0.9)), 4);
  ASSERT_EQ(e->dofs().front().node, 50);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(6);
  e->update_status(ctx, zero);
  EXPECT_NE(e->status(), GapStatus::Open);
  auto r = results(*e, zero);
  EXPECT_NEAR(r[3], -0.1 / std::sqrt(2.0), 1e-12);
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  e->tangent(ctx, zero, K, f);
  // The force on the node is along the right slope's normal (-1, 0, 1)/√2, magnitude k_n pen.
  const Vec3 fn(f(3), f(4), f(5));
  EXPECT_NEAR(fn.x(), 1000.0 * 0.1 / std::sqrt(2.0) / std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(fn.z(), -1000.0 * 0.1 / 2.0, 1e-9);
  // Moving the pilot (the target) down by 1 opens the contact.
  Eigen::VectorXd down = zero;
  down(2) = -1.0;
  e->update_status(ctx, down);
  EXPECT_EQ(e->status(), GapStatus::Open);
  // The node moved over the left slope, into it by 0.2: that facet's normal now.
  Eigen::VectorXd left = zero;
  left(3) = -2.0;
  left(5) = -0.1;  // node at (-1, 0, 0.8): left slope z = -x = 1, gap (0.8 - 1)/√2
  e->update_status(ctx, left);
  EXPECT_NE(e->status(), GapStatus::Open);
  r = results(*e, left);
  EXPECT_NEAR(r[3], -0.2 / std::sqrt(2.0), 1e-12);
}

TEST(Conta175, NeedsAPilotAndATarget) {
  Model m = conta175_model(Vec3(1.0, 0.0, 0.9));
  m.elements.erase(1);
  EXPECT_THROW(build(m, 4), InputError);
  Model n = conta175_model(Vec3(1.0, 0.0, 0.9));
  n.elements[4].real = 4;
  n.real_sets[4] = n.real_sets[3];
  EXPECT_THROW(build(n, 4), InputError);
}

TEST(Contact, ElementsMatchTheirRegistration) {
  const Model a = conta178_model();
  const Model b = conta175_model(Vec3(1.0, 0.0, 0.9));
  const std::vector<std::pair<const Model*, int>> cases = {{&a, 7}, {&b, 4}, {&b, 1}, {&b, 2}};
  for (const auto& [m, id] : cases) {
    const auto e = build(*m, id);
    const ElementTypeDescriptor& d =
        element_type_descriptor(m->element_types.at(m->elements.at(id).type));
    SCOPED_TRACE(d.name);
    EXPECT_EQ(e->result_names(), d.result_names);
    EXPECT_EQ(e->family(), d.family);
    EXPECT_EQ(e->has_status(), d.has_status);
    EXPECT_GE(d.number, 1);
  }
}

}  // namespace
}  // namespace impactfe::test_contact
