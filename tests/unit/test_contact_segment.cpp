// CONTA174 segment-to-segment integration (KEYOPT(4) = 0, elements/contact_segment.h): a contact
// face over two bilinear target facets gets the exact mortar distribution ∫φ_i p dA, ∫N_a p dA of
// a uniform pressure (the bilinear shape functions, not those of the facets' triangles), its
// frictionless tangent equals finite differences on warped facets and is symmetric, forces and
// moments balance, KEYOPT(4) = 1 keeps the nodal law, and a face on a rigid target uses its
// Gauss points.
#include <gtest/gtest.h>

#include "../support/element_checks.h"
#include "../support/model_records.h"

#include <Eigen/Dense>
#include <map>
#include <random>

#include "core/errors.h"
#include "elements/element.h"
#include "elements/element_registry.h"

namespace impactfe::test_contact_segment {
namespace {

ElementRecord record(int id, int type_id, int real, int mat, std::vector<int> nodes) {
  return testing::element_record(id, type_id, real, mat, std::move(nodes), "segment.inp");
}

/// Target body: two unit SOLID185 bricks, x ∈ [0, 2], y ∈ [0, 1], z ∈ [−1, 0], their top faces the
/// TARGE170 facets (quadrilaterals 3 and 4, normal +Z, no pilot). Contact body: one brick
/// x ∈ [0.6, 1.4], y ∈ [0.2, 0.8], z ∈ [0, 0.5] whose bottom face (normal −Z) is CONTA174 element
/// 20, across the edge x = 1 between the two facets. FKN = −1000 (absolute, force/length³),
/// FTOLN = −1e-6, PINB = −0.5; penalty (KEYOPT(2) = 1). `rigid`: a pilot (node 200) makes the
/// target rigid; `pinb` the pinball (real constant 6).
Model model(int keyopt4 = 0, double mu = 0.0, bool rigid = false, double pinb = -0.5) {
  Model m;
  int id = 1;
  for (double z : {-1.0, 0.0})
    for (double y : {0.0, 1.0})
      for (double x : {0.0, 1.0, 2.0}) m.nodes[id] = Node{id, Vec3(x, y, z)}, ++id;
  id = 101;
  for (double z : {0.0, 0.5})
    for (const auto& [x, y] : {std::pair{0.6, 0.2}, {1.4, 0.2}, {1.4, 0.8}, {0.6, 0.8}})
      m.nodes[id] = Node{id, Vec3(x, y, z)}, ++id;
  m.element_types[1] = testing::element_type(1, "SOLID185");
  m.element_types[2] = testing::element_type(2, "TARGE170");
  m.element_types[3] = testing::element_type(3, "CONTA174", 1);
  m.element_types[3].keyopt[4] = keyopt4;
  Material mat;
  mat.id = 1;
  mat.props["EX"] = 1000.0;
  mat.props["PRXY"] = 0.3;
  mat.props["MU"] = mu;
  m.materials[1] = mat;
  m.real_sets[3] = RealSet{3, {0.0, 0.0, -1000.0, -1e-6, 0.0, pinb}};
  m.elements[1] = record(1, 1, 1, 1, {1, 2, 5, 4, 7, 8, 11, 10});
  m.elements[2] = record(2, 1, 1, 1, {2, 3, 6, 5, 8, 9, 12, 11});
  m.elements[3] = record(3, 2, 3, 1, {7, 8, 11, 10});
  m.elements[4] = record(4, 2, 3, 1, {8, 9, 12, 11});
  m.elements[5] = record(5, 1, 1, 1, {101, 102, 103, 104, 105, 106, 107, 108});
  m.elements[20] = record(20, 3, 3, 1, {101, 104, 103, 102});
  if (rigid) {
    m.nodes[200] = Node{200, Vec3(1.0, 0.5, -2.0)};
    m.elements[6] = record(6, 2, 3, 1, {200});
  }
  return m;
}

std::unique_ptr<Element> build(const Model& m, int id) {
  return create_element(ElementBuildContext{m, {}}, m.elements.at(id));
}

/// The element's force at each node (sum over the node's UX, UY, UZ).
std::map<int, Vec3> nodal_forces(const Element& e, const Eigen::VectorXd& f) {
  std::map<int, Vec3> out;
  for (int a = 0; a < e.n_dofs(); ++a) {
    const DofKey& k = e.dofs()[static_cast<std::size_t>(a)];
    Vec3& v = out.try_emplace(k.node, Vec3::Zero()).first->second;
    v(static_cast<int>(k.dof)) += f(a);
  }
  return out;
}

/// A displacement that pushes the contact face δ down (−Z) into the target.
Eigen::VectorXd pushed(const Element& e, double delta) {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(e.n_dofs());
  for (int a = 0; a < e.n_dofs(); ++a) {
    const DofKey& k = e.dofs()[static_cast<std::size_t>(a)];
    if (k.node > 100 && k.node < 200 && k.dof == Dof::UZ) u(a) = -delta;
  }
  return u;
}

void uniform_pressure(int keyopt4);

TEST(SegmentContact, UniformPressureGoesToTheNodesByTheBilinearShapeFunctions) {
  for (int keyopt4 : {0, 3}) {  // Gauss-point and surface-projection detection
    SCOPED_TRACE(keyopt4);
    uniform_pressure(keyopt4);
  }
}

void uniform_pressure(int keyopt4) {
  const Model m = model(keyopt4);
  auto e = build(m, 20);
  ASSERT_EQ(e->n_dofs(), 30);  // the face's 4 nodes and the 6 nodes of the two facets
  const ElementContext ctx;
  const Eigen::VectorXd u = pushed(*e, 0.01);
  e->update_status(ctx, u);
  ASSERT_NE(e->status(), GapStatus::Open);
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  e->tangent(ctx, u, K, f);
  // p = 1000 · 0.01 = 10 over A = 0.8 · 0.6: the face nodes get pA/4 = 1.2 each (upwards, the
  // internal force points into the target: −Z), the target nodes ∫N_a p dA over the overlap:
  // corner nodes 7, 9, 10, 12: 10 · (0.08 · 0.3) = 0.24; middle nodes 8, 11: 10 · 2 (0.32 · 0.3)
  // = 1.92 (x-integrals ∫(1 − x) dx over [0.6, 1] = 0.08, ∫x dx = 0.32; y-integrals 0.3).
  const std::map<int, Vec3> fn = nodal_forces(*e, f);
  const std::map<int, double> expected = {{101, -1.2}, {102, -1.2}, {103, -1.2}, {104, -1.2},
                                          {7, 0.24},   {9, 0.24},   {10, 0.24},  {12, 0.24},
                                          {8, 1.92},   {11, 1.92}};
  for (const auto& [node, fz] : expected) {
    EXPECT_NEAR(fn.at(node).z(), fz, 1e-12) << "node " << node;
    EXPECT_NEAR(fn.at(node).head<2>().norm(), 0.0, 1e-12) << "node " << node;
  }
  ElementResultValues r;
  e->results(ctx, u, Eigen::VectorXd::Zero(e->n_dofs()), r);
  EXPECT_NEAR(r[1], 4.8, 1e-12);   // FN: the total normal force pA
  EXPECT_NEAR(r[2], 0.01, 1e-12);  // PENE
  EXPECT_NEAR(e->contact_stiffness(), 1000.0 * 0.48, 1e-9);
}

TEST(SegmentContact, FrictionlessTangentEqualsFiniteDifferencesOnWarpedFacets) {
  const Model m = model();
  auto e = build(m, 20);
  const ElementContext ctx;
  for (unsigned seed : {1u, 2u, 3u}) {
    SCOPED_TRACE(seed);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> r(-0.05, 0.05);
    Eigen::VectorXd u = pushed(*e, 0.15);
    for (int a = 0; a < u.size(); ++a) u(a) += r(rng);  // warped (non-planar) bilinear facets
    e->update_status(ctx, u);
    ASSERT_NE(e->status(), GapStatus::Open);
    Eigen::MatrixXd K;
    Eigen::VectorXd f;
    e->tangent(ctx, u, K, f);
    ASSERT_GT(f.norm(), 1.0);
    const Eigen::MatrixXd fd = testing::fd_tangent(*e, ctx, u, 1e-6);
    const double error = (K - fd).norm() / K.norm();
    EXPECT_LT(error, 1e-6);
    RecordProperty("fd_relative_error_seed_" + std::to_string(seed), std::to_string(error));
    std::printf("seed %u: |K - K_fd| / |K| = %.2e\n", seed, error);
    EXPECT_LT((K - K.transpose()).norm(), 1e-10 * K.norm());
    // Σ f = 0 and Σ x × f = 0 in the current configuration (x_s − x_m ∥ n at every point).
    Vec3 force = Vec3::Zero(), moment = Vec3::Zero();
    for (const auto& [node, fi] : nodal_forces(*e, f)) {
      Vec3 x = m.nodes.at(node).x;
      for (int a = 0; a < e->n_dofs(); ++a)
        if (e->dofs()[static_cast<std::size_t>(a)].node == node)
          x(static_cast<int>(e->dofs()[static_cast<std::size_t>(a)].dof)) += u(a);
      force += fi;
      moment += x.cross(fi);
    }
    EXPECT_LT(force.norm(), 1e-12 * f.norm());
    EXPECT_LT(moment.norm(), 1e-11 * f.norm());
  }
}

TEST(SegmentContact, StickingFrictionBalancesAndItsNormalPartIsConsistent) {
  const Model m = model(0, 0.5);
  auto e = build(m, 20);
  const ElementContext ctx;
  Eigen::VectorXd u = pushed(*e, 0.02);
  for (int a = 0; a < u.size(); ++a)
    if (e->dofs()[static_cast<std::size_t>(a)].node > 100 &&
        e->dofs()[static_cast<std::size_t>(a)].dof == Dof::UX)
      u(a) += 0.001;  // a small tangential offset of the face: sticking (|f_t| < μ p)
  e->update_status(ctx, u);
  ASSERT_EQ(e->status(), GapStatus::Closed);
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  e->tangent(ctx, u, K, f);
  Vec3 force = Vec3::Zero();
  for (const auto& [node, fi] : nodal_forces(*e, f)) force += fi;
  EXPECT_LT(force.norm(), 1e-12 * f.norm());
  // The sticking force: k_t · 0.001 · A = 1000 · 0.001 · 0.48 (internal force of the face +X).
  double fx = 0.0;
  for (const auto& [node, fi] : nodal_forces(*e, f))
    if (node > 100) fx += fi.x();
  EXPECT_NEAR(fx, 0.48, 1e-9);
  const Eigen::MatrixXd fd = testing::fd_tangent(*e, ctx, u, 1e-7);
  EXPECT_LT((K - fd).norm(), 0.05 * K.norm());
  EXPECT_LT((K - K.transpose()).norm(), 1e-12 * K.norm());
}

TEST(SegmentContact, APointThatSlidesOutOfItsCandidatesIsASolutionError) {
  // PINB 0.15: the points with x < 0.85 see only the first facet (x ≤ 1). Sliding the face by
  // 0.1 along y keeps every point on its facets; sliding it by 0.8 along x takes the points near
  // x = 0.6 across x = 1 onto a facet that is not theirs: error (small sliding, enlarge PINB).
  const Model m = model(0, 0.0, false, -0.15);
  auto e = build(m, 20);
  const ElementContext ctx;
  Eigen::VectorXd u = pushed(*e, 0.01);
  for (int a = 0; a < u.size(); ++a)
    if (e->dofs()[static_cast<std::size_t>(a)].node > 100 &&
        e->dofs()[static_cast<std::size_t>(a)].dof == Dof::UY)
      u(a) = 0.1;
  EXPECT_NO_THROW(e->update_status(ctx, u));
  EXPECT_NE(e->status(), GapStatus::Open);
  for (int a = 0; a < u.size(); ++a)
    if (e->dofs()[static_cast<std::size_t>(a)].node > 100 &&
        e->dofs()[static_cast<std::size_t>(a)].dof == Dof::UX)
      u(a) = 0.8;
  EXPECT_THROW(e->update_status(ctx, u), SolutionError);
}

TEST(SegmentContact, KeyoptFourOneKeepsTheNodalLaw) {
  const Model m = model(1);
  auto e = build(m, 20);
  const ElementContext ctx;
  const Eigen::VectorXd u = pushed(*e, 0.01);
  e->update_status(ctx, u);
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  e->tangent(ctx, u, K, f);
  // Nodal: each corner carries k a δ = 1000 · 0.12 · 0.01 = 1.2 and hands it to the corners of
  // the triangle it lies in (node 101 at (0.6, 0.2) in triangle 7-8-11: N = (0.4, 0.4, 0.2); node
  // 104 at (0.6, 0.8) in 7-11-10: N = (0.2, 0.6, 0.2)), so node 7 gets 1.2 (0.4 + 0.2) = 0.72,
  // not the segment-to-segment 0.24.
  const std::map<int, Vec3> fn = nodal_forces(*e, f);
  EXPECT_NEAR(fn.at(101).z(), -1.2, 1e-12);
  EXPECT_NEAR(fn.at(7).z(), 0.72, 1e-12);
}

TEST(SegmentContact, RigidTargetUsesTheFaceGaussPoints) {
  const Model m = model(0, 0.0, true);
  auto e = build(m, 20);
  ASSERT_EQ(e->n_dofs(), 15);  // the pilot and the face's 4 nodes
  const ElementContext ctx;
  const Eigen::VectorXd u = pushed(*e, 0.01);
  e->update_status(ctx, u);
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  e->tangent(ctx, u, K, f);
  const std::map<int, Vec3> fn = nodal_forces(*e, f);
  for (int node : {101, 102, 103, 104}) EXPECT_NEAR(fn.at(node).z(), -1.2, 1e-12);
  EXPECT_NEAR(fn.at(200).z(), 4.8, 1e-12);
  const Eigen::MatrixXd fd = testing::fd_tangent(*e, ctx, u, 1e-6);
  EXPECT_LT((K - fd).norm(), 1e-8 * K.norm());
}

}  // namespace
}  // namespace impactfe::test_contact_segment
