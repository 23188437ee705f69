// DofGraph (symbolic assembly from the element DOF lists) against the triplet assembly it
// replaced: the same lower pattern, the same matrices bit for bit (structure, exact zeros left
// out, cancelled entries kept), and SharedPatternProducts built from the graph equal to the one
// built from the assembled matrices.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "../support/model_records.h"
#include "assembly/dof_graph.h"
#include "linalg/shared_pattern_products.h"

namespace impactfe::test_dof_graph {
namespace {

/// A random LINK1 net: 40 nodes in a plane, 90 bars between random pairs (some nodes left
/// without any bar, some pairs repeated).
struct Net {
  Model model;
  std::vector<std::unique_ptr<Element>> elements;
  DofMap dofs;
};

Net random_net(unsigned seed) {
  Net net;
  Model& m = net.model;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coord(0.0, 10.0);
  for (int i = 1; i <= 40; ++i)
    m.nodes[i] = Node{i, Vec3(coord(rng), coord(rng), 0.0), Vec3::Zero()};
  m.element_types[1] = testing::element_type(1, "LINK1");
  m.real_sets[1] = RealSet{1, {2.0}};
  Material mat;
  mat.id = 1;
  mat.props = {{"EX", 1000.0}, {"DENS", 0.5}};
  m.materials[1] = mat;
  std::uniform_int_distribution<int> node(1, 36);
  for (int e = 1; e <= 90; ++e) {
    ElementRecord r;
    r.id = e;
    const int a = node(rng);
    int b = node(rng);
    if (b == a) b = a % 36 + 1;
    r.nodes = {a, b};
    m.elements[r.id] = r;
  }
  ElementBuildContext ctx{m, {}};
  for (const auto& [id, r] : m.elements) net.elements.push_back(create_element(ctx, r));
  net.dofs = DofMap(net.elements, {{1, Dof::UX}, {2, Dof::UY}, {7, Dof::UX}, {7, Dof::UY}});
  return net;
}

TEST(DofGraph, RowsAreTheDofPairsOfTheElements) {
  const Net net = random_net(1);
  const DofGraph graph(net.dofs, net.elements.size());
  const int n = net.dofs.n_active();
  std::vector<std::set<int>> expected(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) expected[static_cast<std::size_t>(i)].insert(i);
  for (std::size_t e = 0; e < net.elements.size(); ++e)
    for (int a : net.dofs.element_indices(e))
      for (int b : net.dofs.element_indices(e)) expected[static_cast<std::size_t>(a)].insert(b);
  ASSERT_EQ(graph.size(), n);
  for (int i = 0; i < n; ++i) {
    const std::vector<int> row(graph.column().begin() + graph.row_start()[i],
                               graph.column().begin() + graph.row_start()[i + 1]);
    const auto& want = expected[static_cast<std::size_t>(i)];
    EXPECT_EQ(row, std::vector<int>(want.begin(), want.end())) << "row " << i;
  }
}

TEST(DofGraph, LowerPatternEqualsTheTripletPattern) {
  const Net net = random_net(2);
  const DofGraph graph(net.dofs, net.elements.size());
  const int nf = net.dofs.n_free();
  std::vector<Eigen::Triplet<double, int>> triplets;
  for (std::size_t e = 0; e < net.elements.size(); ++e)
    for (int a : net.dofs.element_indices(e))
      for (int b : net.dofs.element_indices(e))
        if (a < nf && b < nf && a >= b) triplets.emplace_back(a, b, 0.0);
  for (int i = 0; i < nf; ++i) triplets.emplace_back(i, i, 0.0);
  SparseMatrix want(nf, nf);
  want.setFromTriplets(triplets.begin(), triplets.end());
  want.makeCompressed();
  const SparseMatrix got = graph.lower_pattern(nf).zero_matrix();
  ASSERT_EQ(got.nonZeros(), want.nonZeros());
  for (int c = 0; c <= nf; ++c) EXPECT_EQ(got.outerIndexPtr()[c], want.outerIndexPtr()[c]);
  for (int k = 0; k < want.nonZeros(); ++k)
    EXPECT_EQ(got.innerIndexPtr()[k], want.innerIndexPtr()[k]);
}

/// Random unsymmetric element matrices with exact zeros, and one pair of elements whose
/// contributions to an entry cancel exactly.
std::vector<MatrixXd> element_matrices(const Net& net, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<MatrixXd> out;
  for (std::size_t e = 0; e < net.elements.size(); ++e) {
    const int n = static_cast<int>(net.dofs.element_indices(e).size());
    MatrixXd m(n, n);
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b)
        m(a, b) = (a + b + static_cast<int>(e)) % 3 == 0 ? 0.0 : value(rng);
    out.push_back(m);
  }
  return out;
}

TEST(DofGraph, AssembledMatrixEqualsTheTripletAssemblyBitForBit) {
  const Net net = random_net(3);
  const DofGraph graph(net.dofs, net.elements.size());
  std::vector<MatrixXd> matrices = element_matrices(net, 4);
  const int na = net.dofs.n_active();
  std::vector<Eigen::Triplet<double, int>> triplets;
  GraphMatrix assembled(graph);
  std::vector<int> slots;
  for (std::size_t e = 0; e < net.elements.size(); ++e) {
    const auto& idx = net.dofs.element_indices(e);
    const MatrixXd& m = matrices[e];
    for (std::size_t a = 0; a < idx.size(); ++a)
      for (std::size_t b = 0; b < idx.size(); ++b)
        if (m(a, b) != 0.0) triplets.emplace_back(idx[a], idx[b], m(a, b));
    graph.element_slots(idx, slots);
    assembled.add(slots, m, true);
  }
  // A contribution and its negative on one entry: kept as an explicit zero by both.
  MatrixXd plus =
      MatrixXd::Zero(net.dofs.element_indices(0).size(), net.dofs.element_indices(0).size());
  plus(0, 1) = 0.75;
  graph.element_slots(net.dofs.element_indices(0), slots);
  assembled.add(slots, plus, true);
  assembled.add(slots, -plus, true);
  const auto& idx0 = net.dofs.element_indices(0);
  triplets.emplace_back(idx0[0], idx0[1], 0.75);
  triplets.emplace_back(idx0[0], idx0[1], -0.75);
  SparseMatrix want(na, na);
  want.setFromTriplets(triplets.begin(), triplets.end());
  const SparseMatrix got = assembled.to_sparse(graph);
  ASSERT_EQ(got.nonZeros(), want.nonZeros());
  for (int c = 0; c <= na; ++c) ASSERT_EQ(got.outerIndexPtr()[c], want.outerIndexPtr()[c]);
  for (int k = 0; k < want.nonZeros(); ++k) {
    EXPECT_EQ(got.innerIndexPtr()[k], want.innerIndexPtr()[k]);
    EXPECT_EQ(got.valuePtr()[k], want.valuePtr()[k]);  // bitwise: same summation order
  }
}

TEST(DofGraph, SharedProductsFromTheGraphEqualThoseFromTheMatrices) {
  const Net net = random_net(5);
  const DofGraph graph(net.dofs, net.elements.size());
  const std::vector<MatrixXd> k_e = element_matrices(net, 6), m_e = element_matrices(net, 7);
  GraphMatrix k_graph(graph), m_graph(graph), k_col(graph), m_col(graph);
  std::vector<int> slots;
  for (std::size_t e = 0; e < net.elements.size(); ++e) {
    graph.element_slots(net.dofs.element_indices(e), slots);
    k_graph.add(slots, k_e[e], false);
    k_col.add(slots, k_e[e], true);
    if (e % 2 == 0) {  // the mass on half of the elements: a different pattern
      m_graph.add(slots, m_e[e], false);
      m_col.add(slots, m_e[e], true);
    }
  }
  const SparseMatrix k = k_col.to_sparse(graph), m = m_col.to_sparse(graph);
  std::vector<unsigned char> kept(k_graph.touched);
  for (std::size_t s = 0; s < kept.size(); ++s) kept[s] |= m_graph.touched[s];
  const SharedPatternProducts from_graph(graph.row_start(), graph.column(), kept,
                                         {k_graph.value, {}, m_graph.value});
  EXPECT_EQ(from_graph.nonzeros(), SharedPatternProducts({&k, &m}).nonzeros());
  const int n = net.dofs.n_active();
  VectorXd x = VectorXd::LinSpaced(n, -1.0, 2.0), z = VectorXd::LinSpaced(n, 3.0, -0.5);
  VectorXd y_k, y_c, y_m;
  from_graph.multiply({&x, &x, &z}, {&y_k, &y_c, &y_m});
  const VectorXd want_k = k * x, want_m = m * z;
  EXPECT_LE((y_k - want_k).cwiseAbs().maxCoeff(), 1e-13 * want_k.cwiseAbs().maxCoeff());
  EXPECT_LE((y_m - want_m).cwiseAbs().maxCoeff(), 1e-13 * want_m.cwiseAbs().maxCoeff());
  EXPECT_EQ(y_c.size(), n);
  EXPECT_EQ(y_c.cwiseAbs().maxCoeff(), 0.0);  // the null matrix is a zero
}

}  // namespace
}  // namespace impactfe::test_dof_graph
