// Contact against a deformable TARGE170 target (issue 16, small sliding): the element's DOFs are
// the contact node's and the candidate facets' nodes', its node-to-segment tangent equals finite
// differences of its force (frictionless: consistent and symmetric), forces and moments balance,
// the search follows the node over the candidates, and a node that slides out of them is a
// clear solution error.
#include <gtest/gtest.h>

#include "../support/element_checks.h"
#include "../support/model_records.h"

#include <Eigen/Dense>
#include <random>

#include "assembly/element_adapters.h"
#include "core/errors.h"
#include "elements/element.h"
#include "elements/element_registry.h"
#include "elements/target_surface.h"

namespace impactfe::test_contact_deformable {
namespace {

ElementRecord record(int id, int type_id, int real, int mat, std::vector<int> nodes) {
  return testing::element_record(id, type_id, real, mat, std::move(nodes), "deformable.inp");
}

/// Target body: two unit SOLID185 bricks side by side, x ∈ [0, 2], y ∈ [0, 1], z ∈ [−1, 0]; its
/// top faces are the TARGE170 facets (normal +Z, no pilot). CONTA175 (element 20) on node 100 at
/// `x100`; FKN = −1000 (absolute), FTOLN = −1e-6, PINB = −0.5 (absolute).
Model model(const Vec3& x100, int keyopt2 = 1, double mu = 0.0, int keyopt18 = 0) {
  Model m;
  int id = 1;
  for (double z : {-1.0, 0.0})
    for (double y : {0.0, 1.0})
      for (double x : {0.0, 1.0, 2.0}) m.nodes[id] = Node{id, Vec3(x, y, z)}, ++id;
  // Bottom layer 1..6, top layer 7..12: node(i, j, k) = 1 + i + 3 j + 6 k.
  m.nodes[100] = Node{100, x100};
  m.element_types[1] = testing::element_type(1, "SOLID185");
  m.element_types[2] = testing::element_type(2, "TARGE170");
  m.element_types[3] = testing::element_type(3, "CONTA175", keyopt2);
  m.element_types[3].keyopt[18] = keyopt18;  // 1: small sliding
  Material mat;
  mat.id = 1;
  mat.props["EX"] = 1000.0;
  mat.props["PRXY"] = 0.3;
  mat.props["MU"] = mu;
  m.materials[1] = mat;
  m.real_sets[3] = RealSet{3, {0.0, 0.0, -1000.0, -1e-6, 0.0, -0.5}};
  m.elements[1] = record(1, 1, 1, 1, {1, 2, 5, 4, 7, 8, 11, 10});
  m.elements[2] = record(2, 1, 1, 1, {2, 3, 6, 5, 8, 9, 12, 11});
  m.elements[3] = record(3, 2, 3, 1, {7, 8, 11, 10});
  m.elements[4] = record(4, 2, 3, 1, {8, 9, 12, 11});
  m.elements[20] = record(20, 3, 3, 1, {100});
  return m;
}

std::unique_ptr<Element> build(const Model& m, int id) {
  return create_element(ElementBuildContext{m, {}}, m.elements.at(id));
}

/// Current positions of the element's nodes (UX, UY, UZ triples in DOF order).
std::vector<Vec3> positions(const Model& m, const Element& e, const Eigen::VectorXd& u) {
  std::vector<Vec3> x;
  for (int a = 0; a < e.n_dofs(); a += 3)
    x.push_back(m.nodes.at(e.dofs()[static_cast<std::size_t>(a)].node).x + u.segment<3>(a));
  return x;
}

/// A penetrating contact node over the first facet pair and a randomly distorted target.
Eigen::VectorXd distorted(const Element& e, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> r(-0.05, 0.05);
  Eigen::VectorXd u(e.n_dofs());
  for (int a = 0; a < e.n_dofs(); ++a) u(a) = r(rng);
  return u;
}

TEST(DeformableTarget, DofsAreTheContactNodeAndTheCandidateFacetNodes) {
  const Model m = model(Vec3(0.4, 0.3, -0.05), 1, 0.0, 1);  // small sliding
  const auto e = build(m, 20);
  // PINB 0.5 around (0.4, 0.3) reaches the first quad only (x ≤ 1): nodes 7, 8, 11, 10.
  ASSERT_EQ(e->n_dofs(), 15);
  EXPECT_EQ(e->dofs().front().node, 100);
  std::vector<int> nodes;
  for (int a = 3; a < 15; a += 3) nodes.push_back(e->dofs()[static_cast<std::size_t>(a)].node);
  std::sort(nodes.begin(), nodes.end());
  EXPECT_EQ(nodes, (std::vector<int>{7, 8, 10, 11}));
}

TEST(DeformableTarget, FrictionlessTangentIsConsistentSymmetricAndBalanced) {
  const Model m = model(Vec3(0.4, 0.3, -0.05));
  auto e = build(m, 20);
  const ElementContext ctx;
  for (unsigned seed : {1u, 2u, 3u}) {
    SCOPED_TRACE(seed);
    Eigen::VectorXd u = distorted(*e, seed);
    u(2) -= 0.1;  // the contact node 0.05 … 0.2 into the distorted facet
    e->update_status(ctx, u);
    ASSERT_NE(e->status(), GapStatus::Open);
    Eigen::MatrixXd K;
    Eigen::VectorXd f;
    e->tangent(ctx, u, K, f);
    ASSERT_GT(f.norm(), 1.0);
    const Eigen::MatrixXd fd = testing::fd_tangent(*e, ctx, u, 1e-6);
    EXPECT_LT((K - fd).norm(), 1e-6 * K.norm());
    EXPECT_LT((K - K.transpose()).norm(), 1e-12 * K.norm());
    // The geometric part −p H is there: the tangent is not just k_n G Gᵀ (rank one).
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(K);
    EXPECT_GT(svd.singularValues()(1), 1e-3 * svd.singularValues()(0));
    // Σ f = 0 and Σ x × f = 0 in the current configuration.
    const std::vector<Vec3> x = positions(m, *e, u);
    Vec3 force = Vec3::Zero(), moment = Vec3::Zero();
    for (std::size_t i = 0; i < x.size(); ++i) {
      const Vec3 fi = f.segment<3>(3 * static_cast<Eigen::Index>(i));
      force += fi;
      moment += x[i].cross(fi);
    }
    EXPECT_LT(force.norm(), 1e-12 * f.norm());
    EXPECT_LT(moment.norm(), 1e-12 * f.norm());
    // A rigid translation of everything changes nothing.
    Eigen::VectorXd shifted = u;
    for (int a = 0; a < u.size(); ++a) shifted(a) += a % 3 == 0 ? 0.2 : (a % 3 == 1 ? -0.1 : 0.05);
    Eigen::MatrixXd K2;
    Eigen::VectorXd f2;
    e->tangent(ctx, shifted, K2, f2);
    EXPECT_LT((f2 - f).norm(), 1e-10 * f.norm());
  }
}

TEST(DeformableTarget, StickingTangentIsConsistentSymmetricAndBalanced) {
  const Model m = model(Vec3(0.4, 0.3, -0.05), 1, 0.5);
  auto e = build(m, 20);
  const ElementContext ctx;
  for (unsigned seed : {7u, 8u, 9u}) {
    SCOPED_TRACE(seed);
    Eigen::VectorXd u = distorted(*e, seed) * 0.1;
    u(0) += 0.01;  // a small tangential offset of the contact node: sticking (|f_t| < μ p)
    e->update_status(ctx, u);
    ASSERT_EQ(e->status(), GapStatus::Closed);
    Eigen::MatrixXd K;
    Eigen::VectorXd f;
    e->tangent(ctx, u, K, f);
    Vec3 force = Vec3::Zero();
    for (int a = 0; a < e->n_dofs(); a += 3) force += f.segment<3>(a);
    EXPECT_LT(force.norm(), 1e-12 * f.norm());
    EXPECT_GT(std::abs(f(0)), 1.0);  // the sticking force is there
    // With the curvature term Σ f_t,k ∂²u_t,k/∂u² the sticking tangent is the exact one (it was
    // within 5 % before, issue 16), and symmetric: f_t = k_t (u_t − s) derives from a potential.
    const Eigen::MatrixXd fd = testing::fd_tangent(*e, ctx, u, 1e-6);
    EXPECT_LT((K - fd).norm(), 1e-6 * K.norm());
    EXPECT_LT((K - K.transpose()).norm(), 1e-10 * K.norm());
  }
}

TEST(DeformableTarget, SlidingTangentIsConsistentButForTheNonSymmetricCoupling) {
  // Sliding: f_t = μ p d, d = ξ/|ξ|. The tangent keeps everything but the non-symmetric
  // −μ k_n Tᵀ d Gᵀ (the linear solvers are symmetric, contact_point.h); with the friction part
  // of the force f − f₀ = μ p Tᵀ d (f₀ the frictionless force −p G) that term is
  // k_n (f − f₀) f₀ᵀ / p², so K_fd = K + k_n (f − f₀) f₀ᵀ / p² exactly.
  const Model m = model(Vec3(0.4, 0.3, -0.05), 1, 0.3);
  const Model m0 = model(Vec3(0.4, 0.3, -0.05), 1, 0.0);
  auto e = build(m, 20);
  auto e0 = build(m0, 20);
  const ElementContext ctx;
  for (unsigned seed : {4u, 5u, 6u}) {
    SCOPED_TRACE(seed);
    Eigen::VectorXd u = distorted(*e, seed) * 0.1;
    u(0) += 0.05;  // a tangential offset beyond the friction limit: sliding
    u(1) -= 0.03;
    e->update_status(ctx, u);
    e0->update_status(ctx, u);
    ASSERT_EQ(e->status(), GapStatus::Sliding);
    Eigen::MatrixXd K, K0;
    Eigen::VectorXd f, f0;
    e->tangent(ctx, u, K, f);
    e0->tangent(ctx, u, K0, f0);
    ElementResultValues r;
    e->results(ctx, u, Eigen::VectorXd::Zero(u.size()), r);
    const double p = r[1], kn = 1000.0;
    ASSERT_GT(p, 1.0);
    const Eigen::MatrixXd dropped = kn * (f - f0) * f0.transpose() / (p * p);
    const Eigen::MatrixXd fd = testing::fd_tangent(*e, ctx, u, 1e-7);
    EXPECT_GT(dropped.norm(), 1e-3 * K.norm());  // the coupling is not negligible here
    EXPECT_LT((K + dropped - fd).norm(), 1e-6 * K.norm());
    EXPECT_LT((K - K.transpose()).norm(), 1e-10 * K.norm());
  }
}

/// Newton on the element with every DOF on a ground spring k_s and a load on the contact node
/// (sticking, inside the friction cone): the residual norms of each iteration.
std::vector<double> sticking_newton(Element& e, const Eigen::VectorXd& load, double ks) {
  const ElementContext ctx;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(e.n_dofs());
  u(2) = -0.02;  // start closed
  std::vector<double> norms;
  for (int it = 0; it < 30; ++it) {
    e.update_status(ctx, u);
    Eigen::MatrixXd K;
    Eigen::VectorXd f;
    e.tangent(ctx, u, K, f);
    const Eigen::VectorXd r = f + ks * u - load;
    norms.push_back(r.norm());
    if (r.norm() < 1e-10 * load.norm()) break;
    K.diagonal().array() += ks;
    u -= K.lu().solve(r);
  }
  return norms;
}

TEST(DeformableTarget, StickingNewtonConvergesQuadratically) {
  // A soft target (ground springs k_s = 20 on its nodes) under a node pushed down and sideways
  // inside the friction cone: the facet tilts and stretches, so T varies and the curvature term
  // Σ f_t,k ∂²u_t,k/∂u² matters (f_t / facet size against k_t). With it the iteration is Newton's:
  // the residual falls quadratically (r_{k+1} ≤ C r_k² on the last iterations).
  const Model m = model(Vec3(0.4, 0.3, -0.01), 1, 0.8);
  auto e = build(m, 20);
  Eigen::VectorXd load = Eigen::VectorXd::Zero(e->n_dofs());
  load(0) = 4.0;
  load(1) = -2.0;
  load(2) = -10.0;
  const std::vector<double> r = sticking_newton(*e, load, 20.0);
  ASSERT_EQ(e->status(), GapStatus::Closed);
  ASSERT_LT(r.back(), 1e-10 * load.norm());
  EXPECT_LE(r.size(), 8u);
  // Quadratic: the last full step squares the error (with a generous constant).
  const std::size_t n = r.size();
  ASSERT_GE(n, 4u);
  EXPECT_LT(r[n - 2], 1e3 * r[n - 3] * r[n - 3] / load.norm());
}

TEST(DeformableTarget, SearchFollowsTheNodeAndReportsSlidingOutOfTheCandidates) {
  const Model m = model(Vec3(0.4, 0.3, -0.05), 1, 0.0, 1);  // small sliding
  auto e = build(m, 20);
  const ElementContext ctx;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(e->n_dofs());
  e->update_status(ctx, u);
  ASSERT_NE(e->status(), GapStatus::Open);
  // Over the other triangle of the quad (x < y): still closed, the gap follows a lifted node.
  u(0) = -0.3;
  u(1) = 0.6;  // node at (0.1, 0.9)
  e->update_status(ctx, u);
  EXPECT_NE(e->status(), GapStatus::Open);
  // Off the free edge x = 0: open, no error.
  u(0) = -0.6;
  u(1) = 0.0;
  e->update_status(ctx, u);
  EXPECT_EQ(e->status(), GapStatus::Open);
  // Across the edge x = 1 onto the second quad, which was not within the pinball: error.
  u(0) = 0.8;
  EXPECT_THROW(e->update_status(ctx, u), SolutionError);
}

/// Positions at a refresh pass: node 100 (the contact node at (0.2, 0.3, −0.05)) displaced by
/// `d`, the target at rest.
NodePositions slid(const Model& m, const Vec3& d, long long pass) {
  return NodePositions{
      [&m, d](int n) { return n == 100 ? Vec3(Vec3(0.2, 0.3, -0.05) + d) : m.nodes.at(n).x; },
      pass};
}

/// The contact node of element `e` (model(), PINB 0.5, margin 1.5) closed at rest, then slid to
/// x = 0.7: at rest the candidates (the first quad) stay; at x = 0.7 the second quad comes within
/// the pinball and is re-found (6 facet nodes more).
void slide_onto_the_second_quad(Element& e, const Model& m) {
  auto* refresh = dynamic_cast<ConnectivityUpdate*>(&e);
  ASSERT_NE(refresh, nullptr);
  ASSERT_EQ(e.n_dofs(), 15);
  const Eigen::VectorXd u = Eigen::VectorXd::Zero(e.n_dofs());
  e.update_status(ElementContext{}, u);
  ASSERT_NE(e.status(), GapStatus::Open);
  EXPECT_FALSE(refresh->refresh_dofs(u, slid(m, Vec3::Zero(), 1)));  // still covered
  EXPECT_TRUE(refresh->refresh_dofs(u, slid(m, Vec3(0.5, 0.0, 0.0), 2)));
  ASSERT_EQ(e.n_dofs(), 3 * 7);
}

TEST(DeformableTarget, LargeSlidingRefindsTheCandidatesAsTheNodeSlides) {
  // PINB 0.5, margin 1.5: around (0.2, 0.3) the facets within 0.75 are the first quad only.
  const Model m = model(Vec3(0.2, 0.3, -0.05));
  auto e = build(m, 20);
  slide_onto_the_second_quad(*e, m);
  if (HasFatalFailure()) return;
  const ElementContext ctx;
  // The new list is consistent: the node over the second quad at x = 1.6 is closed on it, no
  // PINB error (small sliding would throw here).
  Eigen::VectorXd u = Eigen::VectorXd::Zero(e->n_dofs());
  u(0) = 1.4;
  e->update_status(ctx, u);
  EXPECT_NE(e->status(), GapStatus::Open);
  auto* point = dynamic_cast<DeformableTargetPoint*>(e.get());
  ASSERT_NE(point, nullptr);
  EXPECT_GE(point->facet(), 2);  // a triangle of the second quad (facets 2 and 3)
  // Slid on to x = 1.9: everything within the pinball is a candidate already, so the list
  // stays (a stale candidate costs nothing; a change costs a renumbering).
  EXPECT_FALSE(
      dynamic_cast<ConnectivityUpdate&>(*e).refresh_dofs(u, slid(m, Vec3(1.7, 0.0, 0.0), 3)));
  EXPECT_EQ(e->n_dofs(), 3 * 7);
}

TEST(DeformableTarget, LargeSlidingSurvivesMaterialDampingAndRotatedNodes) {
  // The contact node's material has MP,ALPD and the node a rotated nodal system: the element
  // the structure builds (adapt_element) still re-finds its candidates as it slides, in global
  // axes (u_global = T u_nodal), and T follows its new DOF list. (Before, material damping and
  // nodal axes were wrappers that dropped the search update: a large-sliding CONTA175 model with
  // MP,ALPD stopped with "slid across all its candidate target facets".)
  Model m = model(Vec3(0.2, 0.3, -0.05));
  m.materials[1].props["ALPD"] = 0.5;
  m.nodes[100].angles_deg = Vec3(90.0, 0.0, 0.0);  // nodal x = global y, nodal y = −global x
  const auto e = adapt_element(build(m, 20), m, m.elements.at(20));
  EXPECT_EQ(e->material_damping().alpha, 0.5);
  ASSERT_TRUE(dynamic_cast<ConnectivityUpdate&>(*e).updates_connectivity());
  slide_onto_the_second_quad(*e, m);
  if (HasFatalFailure()) return;
  // The node at global x = 1.6 (nodal −y = global x: u_nodal(1) = −1.4) lies over the second
  // quad: closed there, no PINB error, and the adapter's matrices have the new size.
  const ElementContext ctx;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(e->n_dofs());
  u(1) = -1.4;
  e->update_status(ctx, u);
  EXPECT_NE(e->status(), GapStatus::Open);
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  e->tangent(ctx, u, K, f);
  EXPECT_EQ(K.rows(), 21);
}

TEST(DeformableTarget, AnAdapterOverAnElementWithoutSearchUpdatesNone) {
  Model m = model(Vec3(0.2, 0.3, -0.05));
  m.nodes[7].angles_deg = Vec3(30.0, 0.0, 0.0);
  const auto brick = adapt_element(build(m, 1), m, m.elements.at(1));
  const auto* refresh = dynamic_cast<const ConnectivityUpdate*>(brick.get());
  ASSERT_NE(refresh, nullptr);  // the adapter implements every optional interface
  EXPECT_FALSE(refresh->updates_connectivity());
}

TEST(DeformableTarget, FacetsOnNoBodyNeedAPilot) {
  Model m = model(Vec3(0.4, 0.3, -0.05));
  m.elements.erase(2);  // nodes 9 and 12 of the second facet now belong to no body
  EXPECT_THROW(build(m, 20), InputError);
}

}  // namespace
}  // namespace impactfe::test_contact_deformable
