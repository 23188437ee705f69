// 2-D contact (TARGE169 with CONTA175 and CONTA171/172, elements/target_line.h): UX, UY only;
// the penalty force against a fixed rigid line is k × penetration; the 2-D normal rule
// n = (t_y, −t_x); a pilot target carries its contact with it (and turns it with ROTZ, with a
// consistent tangent); the node-to-segment tangent against a deformable PLANE182 block equals
// central differences of the force; sliding friction is μ × the normal force; a CONTA172 line
// carries |FKN| × its length × the penetration.
#include <gtest/gtest.h>

#include "../support/element_checks.h"
#include "../support/model_records.h"
#include "../support/run_deck.h"

#include <Eigen/Dense>
#include <random>

#include "core/errors.h"
#include "deck/deck_reader.h"
#include "elements/contact_point.h"
#include "elements/element.h"
#include "elements/element_registry.h"

namespace impactfe::test_contact_2d {
namespace {

constexpr double kStiffness = 1973.92088;  // vm65's absolute FKN (force/length)

ElementRecord record(int id, int type_id, int real, int mat, std::vector<int> nodes) {
  return testing::element_record(id, type_id, real, mat, std::move(nodes), "contact2d.inp");
}

std::unique_ptr<Element> build(const Model& m, int id) {
  return create_element(ElementBuildContext{m, {}}, m.elements.at(id));
}

/// vm65's pair: a MASS21 (2-D mass) ball at node 1 = (0, 0.5), a CONTA175 (element 2, KEYOPT(2)
/// = `keyopt2`) on it, and a TARGE169 LINE segment on nodes 3 = (1, 0) and 2 = (−1, 0), given as
/// E,3,2 (`reversed`: E,2,3), on no body and without a pilot: a fixed rigid target. FKN = −k,
/// PINB = −1.2 (absolute); MU of material 1.
Model rigid_model(bool reversed = false, double mu = 0.0, int keyopt2 = 1) {
  Model m;
  m.nodes[1] = Node{1, Vec3(0.0, 0.5, 0.0)};
  m.nodes[2] = Node{2, Vec3(-1.0, 0.0, 0.0)};
  m.nodes[3] = Node{3, Vec3(1.0, 0.0, 0.0)};
  m.element_types[1] = testing::element_type(1, "MASS21");
  m.element_types[1].keyopt[3] = 4;
  m.element_types[2] = testing::element_type(2, "CONTA175", keyopt2);
  m.element_types[3] = testing::element_type(3, "TARGE169");
  m.real_sets[1] = RealSet{1, {0.5}};
  m.real_sets[2] = RealSet{2, {0.0, 0.0, -kStiffness, 0.0, 0.0, -1.2}};
  Material mat;
  mat.id = 1;
  mat.props["MU"] = mu;
  m.materials[1] = mat;
  m.elements[1] = record(1, 1, 1, 1, {1});
  m.elements[2] = record(2, 2, 2, 1, {1});
  m.elements[3] = record(3, 3, 2, 1, reversed ? std::vector<int>{2, 3} : std::vector<int>{3, 2});
  return m;
}

TEST(Contact2d, FixedRigidLinePenaltyForceIsStiffnessTimesPenetration) {
  const Model m = rigid_model();
  auto e = build(m, 2);
  // The contact node's UX, UY only: no UZ, no target node (held fixed).
  ASSERT_EQ(e->n_dofs(), 2);
  EXPECT_EQ(e->dofs()[0].node, 1);
  EXPECT_EQ(e->dofs()[0].dof, Dof::UX);
  EXPECT_EQ(e->dofs()[1].dof, Dof::UY);
  const ElementContext ctx;
  Eigen::VectorXd u(2);
  u << 0.1, -0.5 - 0.0375;  // 0.0375 below the line
  e->update_status(ctx, u);
  ASSERT_NE(e->status(), GapStatus::Open);
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  e->tangent(ctx, u, K, f);
  // f_int = −p G with G = ∂g/∂u = n = (0, 1): the contact pushes the node up.
  EXPECT_NEAR(f(0), 0.0, 1e-12);
  EXPECT_NEAR(f(1), -kStiffness * 0.0375, 1e-9);
  EXPECT_NEAR(K(1, 1), kStiffness, 1e-9);
  EXPECT_NEAR(K(0, 0), 0.0, 1e-12);
  ElementResultValues r;
  e->results(ctx, u, Eigen::VectorXd::Zero(2), r);
  EXPECT_NEAR(r[1], kStiffness * 0.0375, 1e-9);  // FN
  EXPECT_NEAR(r[2], 0.0375, 1e-12);              // PENE
  // Lifted off: open, no force.
  u(1) = -0.4;
  e->update_status(ctx, u);
  EXPECT_EQ(e->status(), GapStatus::Open);
  e->tangent(ctx, u, K, f);
  EXPECT_EQ(f.norm(), 0.0);
}

TEST(Contact2d, NormalIsTangentCrossEzPointingOutOfACounterClockwiseBody) {
  // vm65: E,3,2 with node 3 at x = +1, node 2 at x = −1: t = (−1, 0), n = (0, +1) towards the
  // ball above, which starts 0.5 away. E,2,3 turns the normal down: the ball is behind it.
  const ElementContext ctx;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(2);
  ElementResultValues r;
  auto up = build(rigid_model(false), 2);
  up->results(ctx, zero, zero, r);
  EXPECT_NEAR(r[3], 0.5, 1e-14);  // GAP
  EXPECT_EQ(up->status(), GapStatus::Open);
  auto down = build(rigid_model(true), 2);
  down->results(ctx, zero, zero, r);
  EXPECT_NEAR(r[3], -0.5, 1e-14);
  EXPECT_NE(down->status(), GapStatus::Open);
}

TEST(Contact2d, SlidingFrictionForceIsMuTimesNormalForce) {
  const double mu = 0.3;
  const Model m = rigid_model(false, mu);
  auto e = build(m, 2);
  const ElementContext ctx;
  Eigen::VectorXd u(2);
  u << 0.4, -0.55;  // 0.05 deep, slid 0.4 along the line (trial friction k × 0.4 ≫ μ k × 0.05)
  for (int i = 0; i < 3; ++i) e->update_status(ctx, u);
  ASSERT_EQ(e->status(), GapStatus::Sliding);
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  e->tangent(ctx, u, K, f);
  const double fn = kStiffness * 0.05;
  EXPECT_NEAR(f(1), -fn, 1e-9 * fn);
  // The friction force resists the slide (+x): on the node it acts along −x, f_int along +x.
  EXPECT_NEAR(f(0), mu * fn, 1e-9 * fn);
  ElementResultValues r;
  e->results(ctx, u, Eigen::VectorXd::Zero(2), r);
  EXPECT_NEAR(r[4], mu * r[1], 1e-9 * fn);  // FT = μ FN
  EXPECT_EQ(r[0], 2.0);                     // STAT sliding
}

/// A rigid target with a pilot: node 4 = (0, −1) is the pilot (TSHAP,PILO), `rotating`: a
/// MASS21 with rotary inertia (KEYOPT(3) = 3: UX, UY, ROTZ) on it.
Model pilot_model(bool rotating, double mu = 0.0) {
  Model m = rigid_model(false, mu);
  m.nodes[4] = Node{4, Vec3(0.0, -1.0, 0.0)};
  m.elements[4] = record(4, 3, 2, 1, {4});
  if (rotating) {
    m.element_types[4] = testing::element_type(4, "MASS21");
    m.element_types[4].keyopt[3] = 3;
    m.real_sets[4] = RealSet{4, {1.0, 1.0}};
    m.elements[5] = record(5, 4, 4, 1, {4});
  }
  return m;
}

TEST(Contact2d, PilotTargetCarriesItsContactWithIt) {
  const Model m = pilot_model(false);
  auto e = build(m, 2);
  ASSERT_EQ(e->n_dofs(), 4);  // node 1 UX UY, pilot 4 UX UY
  EXPECT_EQ(e->dofs()[2].node, 4);
  const ElementContext ctx;
  ElementResultValues r;
  // Node and pilot moved together: the same gap.
  Eigen::VectorXd u(4);
  u << 0.3, -0.2, 0.3, -0.2;
  e->update_status(ctx, u);
  e->results(ctx, u, Eigen::VectorXd::Zero(4), r);
  EXPECT_NEAR(r[3], 0.5, 1e-14);
  // The pilot lifted 0.6 under the resting node: 0.1 penetration; the forces balance.
  u << 0.0, 0.0, 0.0, 0.6;
  e->update_status(ctx, u);
  ASSERT_NE(e->status(), GapStatus::Open);
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  e->tangent(ctx, u, K, f);
  EXPECT_NEAR(f(1), -kStiffness * 0.1, 1e-9);
  EXPECT_NEAR(f(3), kStiffness * 0.1, 1e-9);
  EXPECT_NEAR(f(0) + f(2), 0.0, 1e-12);
}

TEST(Contact2d, RotatingPilotTangentIsConsistent) {
  const Model m = pilot_model(true, 1.0);
  auto e = build(m, 2);
  ASSERT_EQ(e->n_dofs(), 5);  // + the pilot's ROTZ
  EXPECT_EQ(e->dofs()[4].dof, Dof::ROTZ);
  const ElementContext ctx;
  Eigen::VectorXd u(5);
  u << -0.018, -0.56, 0.01, -0.02, 0.03;  // turned 0.03 rad, the node ~0.04 deep, sticking
  for (int i = 0; i < 3; ++i) e->update_status(ctx, u);
  ASSERT_EQ(e->status(), GapStatus::Closed);  // sticking
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  e->tangent(ctx, u, K, f);
  const Eigen::MatrixXd fd = testing::fd_tangent(*e, ctx, u, 1e-7);
  EXPECT_LT((K - fd).norm(), 1e-6 * K.norm());
  // Turning the target by θ about the pilot changes the gap of the node by the lever arm.
  Eigen::VectorXd w = Eigen::VectorXd::Zero(5);
  w(4) = 1e-3;
  ElementResultValues r;
  e->results(ctx, w, Eigen::VectorXd::Zero(5), r);
  const Vec3 xs(0.0, 0.5, 0.0), xp(0.0, -1.0, 0.0);
  const Vec3 n(-std::sin(1e-3), std::cos(1e-3), 0.0);
  // The line through (±1, 0) turned about xp: n·(xs − (xp + R(X₂ − X_P))).
  const Vec3 x2 = xp + Vec3(-std::cos(1e-3) - std::sin(1e-3), -std::sin(1e-3) + std::cos(1e-3), 0);
  EXPECT_NEAR(r[3], n.dot(xs - x2), 1e-12);
}

/// A deformable target: two PLANE182 (plane strain) squares, x ∈ [0, 2], y ∈ [0, 1], whose top
/// edges are TARGE169 segments given counter-clockwise (E,5,4 and E,6,5: normal +y); a CONTA175
/// (element 20) on node 100 at `x100`; FKN = −1000, FTOLN = −1e-6, PINB = −0.5.
Model deformable_model(const Vec3& x100, double mu = 0.0) {
  Model m;
  const double xy[6][2] = {{0, 0}, {1, 0}, {2, 0}, {0, 1}, {1, 1}, {2, 1}};
  for (int i = 0; i < 6; ++i) m.nodes[i + 1] = Node{i + 1, Vec3(xy[i][0], xy[i][1], 0.0)};
  m.nodes[100] = Node{100, x100};
  m.element_types[1] = testing::element_type(1, "PLANE182");
  m.element_types[1].keyopt[3] = 2;
  m.element_types[2] = testing::element_type(2, "TARGE169");
  m.element_types[3] = testing::element_type(3, "CONTA175", 1);
  Material mat;
  mat.id = 1;
  mat.props["EX"] = 1000.0;
  mat.props["PRXY"] = 0.3;
  mat.props["MU"] = mu;
  m.materials[1] = mat;
  m.real_sets[3] = RealSet{3, {0.0, 0.0, -1000.0, -1e-6, 0.0, -0.5}};
  m.elements[1] = record(1, 1, 1, 1, {1, 2, 5, 4});
  m.elements[2] = record(2, 1, 1, 1, {2, 3, 6, 5});
  m.elements[3] = record(3, 2, 3, 1, {5, 4});
  m.elements[4] = record(4, 2, 3, 1, {6, 5});
  m.elements[20] = record(20, 3, 3, 1, {100});
  return m;
}

TEST(Contact2d, DeformableTargetTangentEqualsCentralDifferences) {
  for (const double mu : {0.0, 1.0}) {
    SCOPED_TRACE(mu);
    const Model m = deformable_model(Vec3(0.4, 1.02, 0.0), mu);
    auto e = build(m, 20);
    // Node 100 then the candidate segments' nodes (PINB 0.5 × 1.5 reaches both), UX, UY each.
    ASSERT_EQ(e->n_dofs(), 8);
    for (const DofKey& k : e->dofs()) EXPECT_NE(k.dof, Dof::UZ);
    const ElementContext ctx;
    for (unsigned seed : {1u, 2u, 3u}) {
      SCOPED_TRACE(seed);
      std::mt19937 rng(seed);
      std::uniform_real_distribution<double> r(-0.02, 0.02);
      Eigen::VectorXd u(e->n_dofs());
      for (int a = 0; a < e->n_dofs(); ++a) u(a) = r(rng);
      u(1) -= 0.1;  // the node into the distorted edge
      for (int i = 0; i < 3; ++i) e->update_status(ctx, u);
      ASSERT_NE(e->status(), GapStatus::Open);
      if (mu > 0.0) ASSERT_EQ(e->status(), GapStatus::Closed);  // sticking: consistent
      Eigen::MatrixXd K;
      Eigen::VectorXd f;
      e->tangent(ctx, u, K, f);
      ASSERT_GT(f.norm(), 1.0);
      const Eigen::MatrixXd fd = testing::fd_tangent(*e, ctx, u, 1e-6);
      EXPECT_LT((K - fd).norm(), 1e-6 * K.norm());
      // Σ f = 0: the contact's forces balance between node and segment.
      double fx = 0.0, fy = 0.0;
      for (int a = 0; a < e->n_dofs(); a += 2) fx += f(a), fy += f(a + 1);
      EXPECT_LT(std::abs(fx) + std::abs(fy), 1e-10 * f.norm());
    }
  }
}

TEST(Contact2d, LineContactCarriesStiffnessTimesLengthTimesPenetration) {
  // A CONTA172 (midside node dropped: E,I,J) on the bottom edge of a PLANE182 square resting on
  // the fixed line of rigid_model's target; FKN = −k is a pressure per penetration, force/length³,
  // times the edge length 1 and the plane-strain unit thickness.
  Model m = rigid_model();
  m.nodes[11] = Node{11, Vec3(-0.5, 0.0, 0.0)};
  m.nodes[12] = Node{12, Vec3(0.5, 0.0, 0.0)};
  m.nodes[13] = Node{13, Vec3(0.5, 1.0, 0.0)};
  m.nodes[14] = Node{14, Vec3(-0.5, 1.0, 0.0)};
  m.element_types[5] = testing::element_type(5, "PLANE182");
  m.element_types[5].keyopt[3] = 2;
  m.element_types[6] = testing::element_type(6, "CONTA172", 1);
  m.materials[1].props["EX"] = 1000.0;
  m.materials[1].props["PRXY"] = 0.3;
  m.elements.erase(1);
  m.elements.erase(2);
  m.elements[10] = record(10, 5, 1, 1, {11, 12, 13, 14});
  m.elements[11] = record(11, 6, 2, 1, {11, 12, 12});
  auto e = build(m, 11);
  ASSERT_EQ(e->n_dofs(), 4);  // nodes 11 and 12, UX, UY
  const ElementContext ctx;
  Eigen::VectorXd u(4);
  u << 0.0, -0.01, 0.0, -0.01;
  e->update_status(ctx, u);
  ASSERT_NE(e->status(), GapStatus::Open);
  ElementResultValues r;
  e->results(ctx, u, Eigen::VectorXd::Zero(4), r);
  EXPECT_NEAR(r[1], kStiffness * 1.0 * 0.01, 1e-9);  // FN summed over the two nodes
  // A distinct midside node is refused, as CONTA174 refuses 8-node faces.
  m.nodes[15] = Node{15, Vec3(0.0, 0.0, 0.0)};
  m.elements[11] = record(11, 6, 2, 1, {11, 12, 15});
  EXPECT_THROW(build(m, 11), InputError);
}

TEST(Contact2d, ElementsMatchTheirRegistrations) {
  Model m = rigid_model();
  m.element_types[6] = testing::element_type(6, "CONTA171", 1);
  m.nodes[11] = Node{11, Vec3(-0.5, 0.1, 0.0)};
  m.nodes[12] = Node{12, Vec3(0.5, 0.1, 0.0)};
  m.elements[11] = record(11, 6, 2, 1, {11, 12});
  for (const auto& [id, name] : std::vector<std::pair<int, std::string>>{
           {2, "CONTA175"}, {3, "TARGE169"}, {11, "CONTA171"}}) {
    SCOPED_TRACE(name);
    const ElementTypeDescriptor* d = find_element_type(name);
    ASSERT_NE(d, nullptr);
    const auto e = build(m, id);
    EXPECT_EQ(std::string(e->family()), d->family);
    EXPECT_EQ(e->result_names(), d->result_names);
    for (const DofKey& k : e->dofs()) EXPECT_TRUE(k.dof == Dof::UX || k.dof == Dof::UY);
  }
  EXPECT_EQ(build(m, 3)->n_dofs(), 4);  // the segment's nodes, UX, UY
}

/// Two PLANE182 squares side by side (x 0..2, y 0..1, nodes 1-6 counter-clockwise), and
/// `tail` (a TYPE, a selection and ESURF).
Model esurf_deck(const std::string& head, const std::string& tail) {
  const std::string text =
      "/PREP7\n" + head +
      "ET,2,TARGE169\nET,3,CONTA172\nET,4,TARGE170\nR,3\n"
      "N,1,0,0\nN,2,1,0\nN,3,2,0\nN,4,0,1\nN,5,1,1\nN,6,2,1\n" +
      (head.find("PLANE183") != std::string::npos
           ? "N,7,0.5,0\nN,8,1,0.5\nN,9,0.5,1\nN,10,0,0.5\nE,1,2,5,4,7,8,9,10\n"
           : "E,1,2,5,4\nE,2,3,6,5\n") +
      "REAL,3\n" + tail;
  return read_deck_text(text, "esurf2d.inp", DeckOptions{}).model;
}

TEST(Contact2d, EsurfPutsSegmentsAndLinesOnPlaneEdgesCounterClockwise) {
  const Model m = esurf_deck("ET,1,PLANE182\n",
                             "TYPE,2\nNSEL,S,LOC,Y,1\nESURF\nTYPE,3\n"
                             "NSEL,S,LOC,Y,0\nESURF\n");
  std::vector<std::vector<int>> targets, lines;
  for (const auto& [id, e] : m.elements) {
    if (e.type == 2) targets.push_back(e.nodes);
    if (e.type == 3) lines.push_back(e.nodes);
  }
  std::sort(targets.begin(), targets.end());
  std::sort(lines.begin(), lines.end());
  // The top edges run right to left (counter-clockwise around the squares): normal +y, out.
  EXPECT_EQ(targets, (std::vector<std::vector<int>>{{5, 4}, {6, 5}}));
  EXPECT_EQ(lines, (std::vector<std::vector<int>>{{1, 2}, {2, 3}}));
  const auto fails = [](const std::string& head, const std::string& tail, const char* message) {
    try {
      esurf_deck(head, tail);
      ADD_FAILURE() << "accepted: " << tail;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  };
  // A 3-D target type finds no solid or shell face on plane elements; a quadratic edge is refused.
  fails("ET,1,PLANE182\n", "TYPE,4\nNSEL,S,LOC,Y,1\nESURF\n",
        "a 3-D TYPE takes the faces of solids and shells");
  fails("ET,1,PLANE183\n", "TYPE,2\nNSEL,S,LOC,Y,1\nESURF\n", "midside node on the edge");
}

TEST(Contact2d, BadTargetsAreLocatedErrors) {
  // A curved (3-node) segment, and a rigid pilot-less target with user constraints.
  Model m = rigid_model();
  m.nodes[5] = Node{5, Vec3(0.0, -0.1, 0.0)};
  m.elements[3].nodes = {3, 2, 5};
  EXPECT_THROW(build(m, 2), InputError);
  Model k = rigid_model();
  k.element_types[3].keyopt[2] = 1;
  try {
    build(k, 2);
    FAIL() << "expected an InputError";
  } catch (const InputError& err) {
    EXPECT_NE(std::string(err.what()).find("KEYOPT(2) = 1"), std::string::npos) << err.what();
    EXPECT_NE(std::string(err.what()).find("contact2d.inp"), std::string::npos) << err.what();
  }
}

}  // namespace
}  // namespace impactfe::test_contact_2d
