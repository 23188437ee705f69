// Condensation of the linear part onto the nonlinear elements' DOFs
// (src/analysis/linear_part_condensation.h, thesis eqs. 4-16..4-20): the linear part A_L excludes
// exactly the nonlinear elements' stiffness and damping, S is the Schur complement of A_L onto
// their DOFs, and condense / recover solve A_L; checked against dense algebra on a spring chain
// with two gaps.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "analysis/linear_part_condensation.h"

namespace impactfe::test_linear_part_condensation {
namespace {

/// Nodes 1..6 on X; COMBIN14 springs 1-2 ... 5-6 (k = 100 + 10 i), masses 1e-3 per node (MASS21),
/// COMBIN40 gaps (k = 5000, GAP 0.01) from ground nodes 11, 13 to nodes 2 and 5, node 1 fixed.
Model chain() {
  Model m;
  for (int i = 1; i <= 6; ++i) m.nodes[i] = Node{i, Vec3(i, 0, 0)};
  m.nodes[11] = Node{11, Vec3(2, 1, 0)};
  m.nodes[13] = Node{13, Vec3(5, 1, 0)};
  auto type = [&](int id, const char* name, int keyopt3) {
    ElementType t;
    t.id = id;
    t.ansys_name = name;
    t.keyopt[3] = keyopt3;
    m.element_types[id] = t;
  };
  type(1, "COMBIN14", 0);
  type(2, "MASS21", 4);    // 3-D mass without rotary inertia
  type(3, "COMBIN40", 1);  // UX
  int id = 1;
  for (int i = 1; i <= 5; ++i) {
    m.real_sets[i] = RealSet{i, {100.0 + 10.0 * i}};
    ElementRecord r;
    r.id = id++;
    r.type = 1;
    r.real = i;
    r.nodes = {i, i + 1};
    m.elements[r.id] = r;
  }
  m.real_sets[20] = RealSet{20, {1e-3}};
  for (int i = 1; i <= 6; ++i) {
    ElementRecord r;
    r.id = id++;
    r.type = 2;
    r.real = 20;
    r.nodes = {i};
    m.elements[r.id] = r;
  }
  m.real_sets[30] = RealSet{30, {5000.0, 0.0, 0.0, 0.01}};
  for (const auto& [ground, node] : {std::pair{11, 2}, std::pair{13, 5}}) {
    ElementRecord r;
    r.id = id++;
    r.type = 3;
    r.real = 30;
    r.nodes = {ground, node};
    m.elements[r.id] = r;
  }
  return m;
}

TEST(LinearPartCondensation, SchurComplementAndSolvesMatchDenseAlgebra) {
  const Model m = chain();
  std::vector<std::unique_ptr<Element>> elements;
  for (const auto& [id, r] : m.elements) elements.push_back(create_element({m, {}}, r));
  std::set<DofKey> fixed = {{1, Dof::UX}, {11, Dof::UX}, {13, Dof::UX}};
  for (int n : {1, 2, 3, 4, 5, 6}) {
    fixed.insert({n, Dof::UY});
    fixed.insert({n, Dof::UZ});
  }
  const DofMap dofs(elements, fixed);
  const Assembler assembler(elements, dofs, ElementContext{});
  ASSERT_FALSE(LinearPartCondensation::refusal(assembler).has_value());
  LinearPartCondensation condensation(assembler);
  ASSERT_EQ(condensation.size(), 2);  // node 2 UX and node 5 UX
  const int nf = dofs.n_free();
  EXPECT_EQ(nf, 5);

  const IntegrationCoefficients coeff{1.0, 0.0, 4.0 / (1e-4 * 1e-4)};  // Newmark-like cM
  condensation.prepare(coeff);
  // Dense A_L: springs + masses only (the gaps are the nonlinear elements).
  SparseMatrix lower;
  assembler.assemble_linear_part(coeff, lower);
  const MatrixXd a = MatrixXd(lower).selfadjointView<Eigen::Lower>();
  std::vector<int> o;
  for (int i = 0; i < nf; ++i)
    if (condensation.position()[static_cast<std::size_t>(i)] < 0) o.push_back(i);
  const auto& c = condensation.dofs();
  auto block = [&](const std::vector<int>& rows, const std::vector<int>& cols) {
    MatrixXd b(rows.size(), cols.size());
    for (std::size_t i = 0; i < rows.size(); ++i)
      for (std::size_t j = 0; j < cols.size(); ++j) b(i, j) = a(rows[i], cols[j]);
    return b;
  };
  const MatrixXd schur = block(c, c) - block(c, o) * block(o, o).ldlt().solve(block(o, c));
  EXPECT_LT((condensation.schur() - schur).norm(), 1e-9 * schur.norm());
  VectorXd r0(nf);
  for (int i = 0; i < nf; ++i) r0(i) = 1.0 + 0.1 * i;
  const VectorXd y = condensation.condense(r0);
  const VectorXd exact = a.ldlt().solve(r0);
  EXPECT_NEAR(y(0), exact(c[0]), 1e-12 * exact.norm());
  EXPECT_NEAR(y(1), exact(c[1]), 1e-12 * exact.norm());
  EXPECT_LT((condensation.recover(y) - exact).norm(), 1e-12 * exact.norm());
  // The linear part has no gap stiffness: its c diagonal is the springs' plus the mass term.
  const double k2 = 110.0 + 120.0, mass_term = coeff.cM * 1e-3;
  EXPECT_NEAR(a(c[0], c[0]), k2 + mass_term, 1e-9 * mass_term);
  // Prepared once per coefficient set.
  const long factorizations = condensation.counters().factorizations;
  condensation.prepare(coeff);
  EXPECT_EQ(condensation.counters().factorizations, factorizations);
}

TEST(LinearPartCondensation, RefusedWhenEverythingIsNonlinearOrLinear) {
  const Model m = chain();
  std::vector<std::unique_ptr<Element>> elements;
  for (const auto& [id, r] : m.elements)
    if (r.type != 3) elements.push_back(create_element({m, {}}, r));
  const DofMap dofs(elements, {{1, Dof::UX}});
  const Assembler linear(elements, dofs, ElementContext{});
  EXPECT_EQ(LinearPartCondensation::refusal(linear).value_or(""), "the model is linear");
}

}  // namespace
}  // namespace impactfe::test_linear_part_condensation
