// PointMass (MASS21): DOF sets by KEYOPT(3), diagonal mass, no stiffness. Spec §11.3.
#include <gtest/gtest.h>

#include "../support/dense_assembly.h"
#include "core/errors.h"
#include "elements/element.h"
#include "elements/point_mass.h"

namespace impactfe::test_point_mass {
namespace {

Model mass_model(int keyopt3, std::vector<double> reals) {
  Model m;
  m.nodes[2] = Node{2, Vec3(0, 0, -10)};
  ElementType et;
  et.id = 2;
  et.ansys_name = "MASS21";
  et.keyopt[3] = keyopt3;
  m.element_types[2] = et;
  m.real_sets[2] = RealSet{2, std::move(reals)};
  return m;
}

std::unique_ptr<Element> build(const Model& m) {
  ElementRecord r;
  r.id = 2;
  r.type = 2;
  r.real = 2;
  r.nodes = {2};
  r.where = SourceLocation{"mass.inp", 11, "E"};
  return create_element(ElementBuildContext{m, {}}, r);
}

TEST(PointMass, PendulumMassOnThreeTranslations) {
  // Pendulum deck: ET,2,21,,,2 and R,2,1 -> 1 lbf·s²/in at node 2 on UX, UY, UZ.
  auto e = build(mass_model(2, {1.0}));
  EXPECT_STREQ(e->family(), "PointMass");
  ASSERT_EQ(e->n_dofs(), 3);
  EXPECT_EQ(e->dofs()[2], (DofKey{2, Dof::UZ}));
  Eigen::MatrixXd M, K;
  Eigen::VectorXd f;
  e->mass(ElementContext{}, M);
  EXPECT_TRUE(M.isApprox(Eigen::MatrixXd::Identity(3, 3)));
  Eigen::VectorXd u = Eigen::VectorXd::Constant(3, 0.7);
  e->tangent(ElementContext{}, u, K, f);
  EXPECT_EQ(K.rows(), 3);
  EXPECT_EQ(K.norm(), 0.0);
  EXPECT_EQ(f.size(), 3);
  EXPECT_EQ(f.norm(), 0.0);
  ElementContext large;
  large.large_deflection = true;
  EXPECT_FALSE(e->is_nonlinear(large));
  // Its one result is the kinetic energy KENE = ½ vᵀ M v (ETABLE,,KENE; vm65).
  EXPECT_EQ(e->result_names(), (std::vector<std::string>{"KENE"}));
  ElementResultValues out;
  Eigen::VectorXd v(3);
  v << 1.0, -2.0, 3.0;
  e->results(ElementContext{}, u, v, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_DOUBLE_EQ(out[0], 0.5 * (1.0 + 4.0 + 9.0));
}

TEST(PointMass, SixDofDiagonal) {
  auto e = build(mass_model(0, {1, 2, 3, 4, 5, 6}));
  ASSERT_EQ(e->n_dofs(), 6);
  Eigen::MatrixXd M;
  e->mass(ElementContext{}, M);
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(e->dofs()[static_cast<std::size_t>(i)].dof, static_cast<Dof>(i));
    EXPECT_DOUBLE_EQ(M(i, i), i + 1.0);
  }
  EXPECT_DOUBLE_EQ(M.sum(), 21.0);
}

TEST(PointMass, PlanarWithRotaryInertia) {
  auto e = build(mass_model(3, {2.5, 0.4}));
  ASSERT_EQ(e->n_dofs(), 3);
  EXPECT_EQ(e->dofs()[2].dof, Dof::ROTZ);
  Eigen::MatrixXd M;
  e->mass(ElementContext{}, M);
  EXPECT_DOUBLE_EQ(M(0, 0), 2.5);
  EXPECT_DOUBLE_EQ(M(1, 1), 2.5);
  EXPECT_DOUBLE_EQ(M(2, 2), 0.4);
  EXPECT_DOUBLE_EQ(M.sum(), 5.4);
}

TEST(PointMass, PlanarWithoutRotaryInertia) {
  auto e = build(mass_model(4, {3.0}));
  ASSERT_EQ(e->n_dofs(), 2);
  EXPECT_EQ(e->dofs()[1].dof, Dof::UY);
  Eigen::MatrixXd M;
  e->mass(ElementContext{}, M);
  EXPECT_DOUBLE_EQ(M.sum(), 6.0);
}

TEST(PointMass, InputErrors) {
  auto expect_error = [](const Model& m, const char* fragment) {
    try {
      build(m);
      FAIL() << fragment;
    } catch (const InputError& err) {
      EXPECT_EQ(err.where().line, 11);
      EXPECT_NE(err.message().find(fragment), std::string::npos) << err.message();
    }
  };
  expect_error(mass_model(1, {1.0}), "KEYOPT(3)");
  expect_error(mass_model(2, {-1.0}), "negative");
  Model no_real = mass_model(2, {1.0});
  no_real.real_sets.clear();
  expect_error(no_real, "real constant set 2");
  Model no_node = mass_model(2, {1.0});
  no_node.nodes.clear();
  expect_error(no_node, "node 2");
}

TEST(PointMass, SparWithEndMassVibratesAtSqrtKOverM) {
  // Pendulum case 1 bar (EA/L = 3e5 lb/in, massless) with the 1 lbf·s²/in bob, pivot fixed:
  // the axial mode has ω² = 3e5 s⁻²; the two transverse modes have no stiffness (ω² = 0).
  Model m = mass_model(2, {1.0});
  m.nodes[1] = Node{1, Vec3(0, 0, 0)};
  ElementType link;
  link.id = 1;
  link.ansys_name = "LINK8";
  m.element_types[1] = link;
  m.real_sets[1] = RealSet{1, {0.1}};
  m.materials[1].props = {{"EX", 30e6}};
  ElementRecord bar;
  bar.id = 1;
  bar.nodes = {1, 2};
  std::vector<std::unique_ptr<Element>> elements;
  elements.push_back(create_element(ElementBuildContext{m, {}}, bar));
  elements.push_back(build(m));
  testing::DenseSystem sys(elements);
  const std::set<DofKey> fixed = {{1, Dof::UX}, {1, Dof::UY}, {1, Dof::UZ}};
  const Eigen::VectorXd w2 = sys.eigenvalues(fixed);
  ASSERT_EQ(w2.size(), 3);
  EXPECT_NEAR(w2(0), 0.0, 1e-6);
  EXPECT_NEAR(w2(1), 0.0, 1e-6);
  EXPECT_NEAR(w2(2), 3e5, 1e-6 * 3e5);
}

}  // namespace
}  // namespace impactfe::test_point_mass
