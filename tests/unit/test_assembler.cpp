// DofMap + Assembler: free DOFs first and constrained after them; the sparse effective matrix
// equals the dense sum cK K + cM M of the element matrices on the free DOFs; internal forces of
// linear elements are K u; the frame-acceleration load is -M r a.
#include <gtest/gtest.h>

#ifdef _OPENMP
#endif

#include "../support/dense_assembly.h"
#include "assembly/assembler.h"
#include "assembly/loads.h"
#include "core/errors.h"
#include "core/thread_pool.h"

namespace impactfe::test_assembler {
namespace {

/// A plane truss of LINK1 bars with lumped masses: a square with one diagonal.
Model truss() {
  Model m;
  const double xy[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int i = 0; i < 4; ++i)
    m.nodes[i + 1] = Node{i + 1, Vec3(xy[i][0], xy[i][1], 0.0), Vec3::Zero()};
  ElementType t;
  t.id = 1;
  t.ansys_name = "LINK1";
  m.element_types[1] = t;
  m.real_sets[1] = RealSet{1, {2.0}};
  Material mat;
  mat.id = 1;
  mat.props = {{"EX", 1000.0}, {"DENS", 0.5}};
  m.materials[1] = mat;
  const int conn[5][2] = {{1, 2}, {2, 3}, {3, 4}, {4, 1}, {1, 3}};
  for (int e = 0; e < 5; ++e) {
    ElementRecord r;
    r.id = e + 1;
    r.nodes = {conn[e][0], conn[e][1]};
    m.elements[r.id] = r;
  }
  return m;
}

std::vector<std::unique_ptr<Element>> build(const Model& m) {
  std::vector<std::unique_ptr<Element>> out;
  ElementBuildContext ctx{m, {}};
  for (const auto& [id, r] : m.elements) out.push_back(create_element(ctx, r));
  return out;
}

TEST(DofMap, FreeFirstConstrainedAfter) {
  const Model m = truss();
  const auto elements = build(m);
  const std::set<DofKey> fixed = {{1, Dof::UX}, {1, Dof::UY}, {4, Dof::UX}};
  const DofMap dofs(elements, fixed);
  EXPECT_EQ(dofs.n_active(), 8);
  EXPECT_EQ(dofs.n_free(), 5);
  for (const auto& key : fixed) EXPECT_GE(dofs.index(key), dofs.n_free());
  EXPECT_EQ(dofs.index(DofKey{2, Dof::UZ}), -1);  // LINK1 has no UZ
}

TEST(Assembler, EffectiveMatrixEqualsDenseSum) {
  const Model m = truss();
  const auto elements = build(m);
  const std::set<DofKey> fixed = {{1, Dof::UX}, {1, Dof::UY}, {4, Dof::UX}};
  const DofMap dofs(elements, fixed);
  ElementContext ctx;
  ctx.lumped_mass = true;
  const Assembler assembler(elements, dofs, ctx);
  const testing::DenseSystem dense(elements);  // independent dense K over all DOFs

  const IntegrationCoefficients coeff{1.0, 0.0, 250.0};
  const VectorXd u = VectorXd::LinSpaced(dofs.n_active(), -0.01, 0.02);
  SparseMatrix eff;
  VectorXd f_int, f_damp;
  assembler.assemble(coeff, u, u, Assembler::Output{&eff, &f_int, &f_damp});
  const SparseMatrix mass = assembler.mass_matrix();
  const SparseMatrix stiff = assembler.stiffness_matrix(u);
  const MatrixXd lower = MatrixXd(eff);
  for (int i = 0; i < dofs.n_free(); ++i)
    for (int j = 0; j <= i; ++j)
      EXPECT_NEAR(lower(i, j), stiff.coeff(i, j) + 250.0 * mass.coeff(i, j), 1e-9)
          << describe(dofs.key(i)) << " / " << describe(dofs.key(j));
  // Stiffness against the independent dense assembly, DOF by DOF.
  for (int i = 0; i < dofs.n_active(); ++i)
    for (int j = 0; j < dofs.n_active(); ++j) {
      const DofKey a = dofs.key(i), b = dofs.key(j);
      EXPECT_NEAR(stiff.coeff(i, j),
                  dense.K(dense.index(a.node, a.dof), dense.index(b.node, b.dof)), 1e-9);
    }
  // Linear elements: f_int = K u over all active DOFs; no damping anywhere.
  EXPECT_LT((f_int - stiff * u).norm(), 1e-10 * f_int.norm());
  EXPECT_EQ(f_damp.norm(), 0.0);
  // Lumped mass sums to rho A L over the five bars, per direction.
  const double total = 0.5 * 2.0 * (4.0 + std::sqrt(2.0));
  EXPECT_NEAR(mass.sum(), 2.0 * total, 1e-12);  // two translational directions
  // Frame acceleration: -M r a sums to -total * a in Y.
  const VectorXd f_acel = FrameAccelerationLoad(elements, dofs, ctx)(Vec3(0.0, 386.4, 0.0));
  EXPECT_NEAR(f_acel.sum(), -total * 386.4, 1e-9);
}

/// A 3 x 2 SHELL63 plate (consistent mass) with a COMBIN14 damper at one corner and a COMBIN40
/// gap (UZ, nonlinear; GAP -1e-4: closed) from ground node 100 to node 6, the edge x = 0 clamped.
Model shell_plate_with_gap() {
  Model m;
  for (int j = 0; j <= 2; ++j)
    for (int i = 0; i <= 3; ++i) {
      const int id = 1 + i + 4 * j;
      m.nodes[id] = Node{id, Vec3(0.5 * i, 0.4 * j, 0.02 * i * j), Vec3::Zero()};
    }
  m.nodes[100] = Node{100, Vec3(0.5, 0.4, -1.0), Vec3::Zero()};
  m.nodes[101] = Node{101, Vec3(1.5, 0.8, 1.0), Vec3::Zero()};
  auto type = [&](int id, const char* name, int keyopt3) {
    ElementType t;
    t.id = id;
    t.ansys_name = name;
    t.keyopt[3] = keyopt3;
    m.element_types[id] = t;
  };
  type(1, "SHELL63", 0);
  type(2, "COMBIN14", 0);
  type(3, "COMBIN40", 3);  // UZ
  m.real_sets[1] = RealSet{1, {0.05}};
  m.real_sets[2] = RealSet{2, {300.0, 2.5}};
  m.real_sets[3] = RealSet{3, {5000.0, 0.0, 0.0, -1e-4}};
  Material mat;
  mat.id = 1;
  mat.props = {{"EX", 3.0e7}, {"NUXY", 0.3}, {"DENS", 7.3e-4}};
  m.materials[1] = mat;
  int id = 1;
  auto add = [&](int type_id, int real, std::vector<int> nodes) {
    ElementRecord r;
    r.id = id++;
    r.type = type_id;
    r.real = real;
    r.mat = 1;
    r.nodes = std::move(nodes);
    m.elements[r.id] = r;
  };
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) {
      const int n1 = 1 + i + 4 * j;
      add(1, 1, {n1, n1 + 1, n1 + 5, n1 + 4});
    }
  add(2, 2, {12, 101});
  add(3, 3, {100, 6});
  return m;
}

/// The plate's clamped edge x = 0 and the ground nodes, every DOF.
std::set<DofKey> shell_plate_supports() {
  std::set<DofKey> fixed;
  for (int node : {1, 5, 9, 100, 101})
    for (Dof d : {Dof::UX, Dof::UY, Dof::UZ, Dof::ROTX, Dof::ROTY, Dof::ROTZ})
      fixed.insert({node, d});
  return fixed;
}

TEST(Assembler, EffectiveMatrixFromTheProductsEqualsTheElementSum) {
  // The linear elements' K, C and M are kept only as global products; the constant part of
  // every effective matrix is formed from them. It must equal the element-by-element sum
  // (stiffness_matrix etc. evaluate the elements again) on the free DOFs, with Rayleigh damping,
  // a damper, constrained DOFs and a nonlinear (closed) gap.
  const Model m = shell_plate_with_gap();
  const auto elements = build(m);
  const DofMap dofs(elements, shell_plate_supports());
  const Assembler assembler(elements, dofs, ElementContext{}, 0.3, 2e-4);
  ASSERT_EQ(assembler.n_nonlinear_elements(), 1);
  const IntegrationCoefficients coeff{1.0, 2.0e3, 4.0e6};
  const int nf = dofs.n_free();
  const VectorXd u = VectorXd::LinSpaced(dofs.n_active(), -1e-3, 2e-3);
  SparseMatrix eff, linear;
  assembler.assemble(coeff, u, u, Assembler::Output{&eff, nullptr, nullptr});
  assembler.assemble_linear_part(coeff, linear);
  const MatrixXd sum = coeff.cK * MatrixXd(assembler.stiffness_matrix(u)) +
                       coeff.cC * MatrixXd(assembler.damping_matrix(u)) +
                       coeff.cM * MatrixXd(assembler.mass_matrix());
  const MatrixXd lower = MatrixXd(eff), linear_lower = MatrixXd(linear);
  const double scale = sum.cwiseAbs().maxCoeff();
  const int gap_dof = dofs.index(DofKey{6, Dof::UZ});
  for (int i = 0; i < nf; ++i)
    for (int j = 0; j <= i; ++j) {
      EXPECT_NEAR(lower(i, j), sum(i, j), 1e-13 * scale)
          << describe(dofs.key(i)) << " / " << describe(dofs.key(j));
      // The linear part lacks only the closed gap's cK k + cC β k on its DOF.
      const double gap = (i == gap_dof && j == gap_dof) ? 5000.0 * (1.0 + 2e3 * 2e-4) : 0.0;
      EXPECT_NEAR(linear_lower(i, j) + gap, sum(i, j), 1e-13 * scale)
          << describe(dofs.key(i)) << " / " << describe(dofs.key(j));
    }
  EXPECT_EQ(MatrixXd(lower.triangularView<Eigen::StrictlyUpper>()).norm(), 0.0);
}

TEST(Assembler, LinearPartReleasesThePatternAndAFullAssemblyFormsItAgain) {
  // The condensed transient's linear part holds the only copy of the pattern while CHOLMOD
  // factors it (issue 11: memory); a full Newton iteration after it (a step the condensation
  // hands back) needs the pattern again, with the nonlinear elements' slots still valid in it.
  const Model m = shell_plate_with_gap();
  const auto elements = build(m);
  const DofMap dofs(elements, shell_plate_supports());
  const Assembler assembler(elements, dofs, ElementContext{}, 0.3, 2e-4);
  const SparsePattern first = assembler.pattern();
  ASSERT_GT(first.nonzeros(), 0);
  const IntegrationCoefficients coeff{1.0, 2.0e3, 4.0e6};
  const VectorXd u = VectorXd::LinSpaced(dofs.n_active(), -1e-3, 2e-3);
  SparseMatrix before, linear, after;
  assembler.assemble(coeff, u, u, Assembler::Output{&before, nullptr, nullptr});
  assembler.assemble_linear_part(coeff, linear);
  // Its structure is the pattern's.
  ASSERT_EQ(linear.nonZeros(), first.nonzeros());
  EXPECT_TRUE(std::equal(first.row.begin(), first.row.end(), linear.innerIndexPtr()));
  const SparsePattern& again = assembler.pattern();
  EXPECT_EQ(again.column_start, first.column_start);
  EXPECT_EQ(again.row, first.row);
  assembler.assemble(coeff, u, u, Assembler::Output{&after, nullptr, nullptr});
  EXPECT_EQ(MatrixXd(after - before).norm(), 0.0);
  EXPECT_GT(MatrixXd(after).norm(), 0.0);
}

TEST(Assembler, MassDiagonalAndMassBlockFromTheProductsEqualTheElementSum) {
  // The initial acceleration reads M from the global products (no copy of M is kept): its
  // diagonal, and its lower triangle on the massive free DOFs, renumbered (here in reverse, so
  // that entries turn over the diagonal), without the exact zeros of the union pattern.
  const Model m = shell_plate_with_gap();
  const auto elements = build(m);
  const DofMap dofs(elements, shell_plate_supports());
  const Assembler assembler(elements, dofs, ElementContext{});
  const MatrixXd mass = MatrixXd(assembler.mass_matrix());
  const VectorXd diagonal = assembler.mass_diagonal();
  ASSERT_EQ(diagonal.size(), dofs.n_active());
  EXPECT_EQ(diagonal, mass.diagonal());
  const int nf = dofs.n_free();
  std::vector<int> position(static_cast<std::size_t>(nf), -1), massive;
  for (int i = 0; i < nf; ++i)
    if (diagonal(i) > 0.0) massive.push_back(i);
  const int nm = static_cast<int>(massive.size());
  ASSERT_GT(nm, 10);
  for (int k = 0; k < nm; ++k) position[static_cast<std::size_t>(massive[k])] = nm - 1 - k;
  const SparseMatrix block = assembler.mass_block_lower(position, nm);
  ASSERT_EQ(block.rows(), nm);
  for (int c = 0; c < block.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(block, c); it; ++it) {
      EXPECT_GE(it.row(), it.col());
      EXPECT_NE(it.value(), 0.0);
    }
  const MatrixXd dense = MatrixXd(block);
  const double scale = mass.cwiseAbs().maxCoeff();
  for (int a = 0; a < nm; ++a)
    for (int b = 0; b < nm; ++b) {
      const int pa = nm - 1 - a, pb = nm - 1 - b;
      const double expected = pa >= pb ? mass(massive[a], massive[b]) : 0.0;
      EXPECT_NEAR(dense(pa, pb), expected, 1e-14 * scale)
          << describe(dofs.key(massive[a])) << " / " << describe(dofs.key(massive[b]));
    }
}

TEST(Assembler, PatternIsBuiltOnceAndReused) {
  const Model m = truss();
  const auto elements = build(m);
  const DofMap dofs(elements, {{1, Dof::UX}, {1, Dof::UY}, {4, Dof::UX}});
  const Assembler assembler(elements, dofs, ElementContext{});
  SparseMatrix eff = assembler.pattern().zero_matrix();
  const int* inner = eff.innerIndexPtr();
  const VectorXd zero = VectorXd::Zero(dofs.n_active());
  assembler.assemble({1.0, 0.0, 0.0}, zero, zero, Assembler::Output{&eff, nullptr, nullptr});
  assembler.assemble({2.0, 0.0, 0.0}, zero, zero, Assembler::Output{&eff, nullptr, nullptr});
  EXPECT_EQ(eff.innerIndexPtr(), inner);  // same storage: values refilled in place
  EXPECT_EQ(eff.nonZeros(), assembler.pattern().nonzeros());
}

/// `n` separate LINK1 bars of unit length along X: bar e joins nodes 2e-1 and 2e.
Model separate_bars(int n) {
  Model m;
  ElementType t;
  t.id = 1;
  t.ansys_name = "LINK1";
  m.element_types[1] = t;
  m.real_sets[1] = RealSet{1, {0.1}};
  Material mat;
  mat.id = 1;
  mat.props = {{"EX", 100.0}};
  m.materials[1] = mat;
  for (int e = 1; e <= n; ++e) {
    m.nodes[2 * e - 1] = Node{2 * e - 1, Vec3(0.0, e, 0.0), Vec3::Zero()};
    m.nodes[2 * e] = Node{2 * e, Vec3(1.0, e, 0.0), Vec3::Zero()};
    ElementRecord r;
    r.id = e;
    r.nodes = {2 * e - 1, 2 * e};
    m.elements[r.id] = r;
  }
  return m;
}

TEST(Assembler, ElementFailureInParallelTangentPhaseIsRethrownForTheFirstElement) {
  // Large deflection: the bars are co-rotational (nonlinear), so their tangents are evaluated in
  // the tangent phase, here forced onto several threads. Bars 37 and 150 collapse (node j moved
  // onto node i): the exception must leave the parallel region as a SolutionError of bar 37, the
  // first in element order, whatever thread met which bar first, and never terminate.
  const int n = 200;
  const Model m = separate_bars(n);
  const auto elements = build(m);
  const DofMap dofs(elements, {});
  ElementContext ctx;
  ctx.large_deflection = true;
  const Assembler assembler(elements, dofs, ctx);
  ASSERT_EQ(assembler.n_nonlinear_elements(), n);
  assembler.force_parallel_tangents();
  const int threads_before = threads::max_threads();
  threads::set_max_threads(4);
  VectorXd u = VectorXd::Zero(dofs.n_active());
  for (int e : {150, 37}) u(dofs.index(DofKey{2 * e, Dof::UX})) = -1.0;
  const VectorXd v = VectorXd::Zero(dofs.n_active());
  VectorXd f_int;
  for (int repeat = 0; repeat < 20; ++repeat) {
    try {
      assembler.assemble({1.0, 0.0, 0.0}, u, v, Assembler::Output{nullptr, &f_int, nullptr});
      ADD_FAILURE() << "no error for the collapsed bars";
    } catch (const ElementSolutionError& e) {
      EXPECT_EQ(e.element(), 37);
      EXPECT_NE(std::string(e.what()).find("element 37 collapsed"), std::string::npos);
    }
  }
  // Without a collapsed bar the parallel phase gives the serial internal forces: bar 37
  // shortened by half carries -EA/2 at its end node.
  u(dofs.index(DofKey{2 * 150, Dof::UX})) = 0.0;
  u(dofs.index(DofKey{2 * 37, Dof::UX})) = -0.5;
  assembler.assemble({1.0, 0.0, 0.0}, u, v, Assembler::Output{nullptr, &f_int, nullptr});
  EXPECT_NEAR(f_int(dofs.index(DofKey{2 * 37, Dof::UX})), -5.0, 1e-12);
  threads::set_max_threads(threads_before);
}

/// A nonlinear spring between two nodes' UX (f = k (u2 − u1)³ / 3 per node pair) that counts
/// its tangent evaluations; with `status` it reports a status like a gap.
class CountingSpring final : public Element {
 public:
  CountingSpring(int id, int n1, int n2, bool status)
      : Element(id), dofs_{{n1, Dof::UX}, {n2, Dof::UX}}, status_(status) {}
  const char* family() const override { return "CountingSpring"; }
  const std::vector<DofKey>& dofs() const override { return dofs_; }
  bool is_nonlinear(const ElementContext&) const override { return true; }
  bool has_status() const override { return status_; }
  void tangent(const ElementContext&, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
               Eigen::VectorXd& f) const override {
    ++evaluations;
    const double d = u(1) - u(0);
    K.resize(2, 2);
    K << d * d, -d * d, -d * d, d * d;
    f.resize(2);
    f << -d * d * d / 3.0, d * d * d / 3.0;
  }
  void mass(const ElementContext&, Eigen::MatrixXd& M) const override {
    M = Eigen::MatrixXd::Identity(2, 2);
  }
  const std::vector<std::string>& result_names() const override { return names_; }
  void results(const ElementContext&, const Eigen::VectorXd&, const Eigen::VectorXd&,
               ElementResultValues& out) const override {
    out.clear();
  }
  mutable int evaluations = 0;

 private:
  std::vector<DofKey> dofs_;
  std::vector<std::string> names_;
  bool status_;
};

/// The same spring with a force of its own (Element::separate_internal_force), counting the
/// force-only evaluations apart from the tangents.
class SeparatingSpring final : public Element {
 public:
  SeparatingSpring(int id, int n1, int n2) : Element(id), spring_(id, n1, n2, false) {}
  const char* family() const override { return "SeparatingSpring"; }
  const std::vector<DofKey>& dofs() const override { return spring_.dofs(); }
  bool is_nonlinear(const ElementContext&) const override { return true; }
  void tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
               Eigen::VectorXd& f) const override {
    spring_.tangent(ctx, u, K, f);
  }
  void internal_force(const ElementContext& ctx, const Eigen::VectorXd& u,
                      Eigen::VectorXd& f) const override {
    ++force_evaluations;
    Eigen::MatrixXd K;
    spring_.tangent(ctx, u, K, f);
    --spring_.evaluations;  // not a tangent
  }
  bool separate_internal_force(const ElementContext&) const override { return true; }
  void mass(const ElementContext& ctx, Eigen::MatrixXd& M) const override { spring_.mass(ctx, M); }
  const std::vector<std::string>& result_names() const override { return spring_.result_names(); }
  void results(const ElementContext& ctx, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
               ElementResultValues& out) const override {
    spring_.results(ctx, u, v, out);
  }
  int tangents() const { return spring_.evaluations; }
  mutable int force_evaluations = 0;

 private:
  CountingSpring spring_;
};

TEST(Assembler, ResidualsFormNoTangentForElementsWithAForceOfTheirOwn) {
  // A residual evaluates the force alone; the factorization at the same u then adds the
  // tangent, and a second one at that u reuses it. The outputs are a fresh assembler's.
  std::vector<std::unique_ptr<Element>> elements;
  elements.push_back(std::make_unique<SeparatingSpring>(1, 1, 2));
  elements.push_back(std::make_unique<SeparatingSpring>(2, 2, 3));
  const DofMap dofs(elements, {{1, Dof::UX}});
  const Assembler assembler(elements, dofs, ElementContext{});
  const auto& spring = [&](int e) -> const SeparatingSpring& {
    return static_cast<const SeparatingSpring&>(*elements[static_cast<std::size_t>(e)]);
  };
  VectorXd u = VectorXd::LinSpaced(dofs.n_active(), 0.0, 0.3);
  const VectorXd v = VectorXd::Zero(dofs.n_active());
  const IntegrationCoefficients coeff{1.0, 0.0, 0.0};
  VectorXd f_residual, f_tangent;
  SparseMatrix eff;
  assembler.assemble(coeff, u, v, Assembler::Output{nullptr, &f_residual, nullptr});
  EXPECT_EQ(spring(0).force_evaluations, 1);
  EXPECT_EQ(spring(0).tangents(), 0);
  assembler.assemble(coeff, u, v, Assembler::Output{&eff, &f_tangent, nullptr});
  EXPECT_EQ(spring(0).force_evaluations, 1);
  EXPECT_EQ(spring(0).tangents(), 1);
  EXPECT_EQ(f_residual, f_tangent);
  assembler.assemble(coeff, u, v, Assembler::Output{nullptr, &f_residual, nullptr});
  assembler.assemble(coeff, u, v, Assembler::Output{&eff, nullptr, nullptr});
  EXPECT_EQ(spring(0).force_evaluations, 1);  // both reuse the buffers of that u
  EXPECT_EQ(spring(0).tangents(), 1);
  // A new iterate: a residual, the converged check, forms no tangent.
  u(dofs.index(DofKey{3, Dof::UX})) += 0.05;
  assembler.assemble(coeff, u, v, Assembler::Output{nullptr, &f_residual, nullptr});
  EXPECT_EQ(spring(0).force_evaluations, 1);  // element 1 (nodes 1-2) did not move
  EXPECT_EQ(spring(1).force_evaluations, 2);
  EXPECT_EQ(spring(1).tangents(), 1);
  const Assembler fresh(elements, dofs, ElementContext{});
  VectorXd f_fresh;
  SparseMatrix eff_fresh;
  fresh.assemble(coeff, u, v, Assembler::Output{&eff_fresh, &f_fresh, nullptr});
  EXPECT_EQ(f_residual, f_fresh);
  assembler.assemble(coeff, u, v, Assembler::Output{&eff, nullptr, nullptr});
  EXPECT_EQ(spring(1).tangents(), 3);  // the fresh assembler's and this one's
  EXPECT_EQ(MatrixXd(eff), MatrixXd(eff_fresh));
}

/// The forces and effective matrix that a fresh assembler forms at (u, v) equal f and eff.
void expect_as_a_fresh_assembler(const std::vector<std::unique_ptr<Element>>& elements,
                                 const DofMap& dofs, const IntegrationCoefficients& coeff,
                                 const VectorXd& u, const VectorXd& v, const VectorXd& f,
                                 const SparseMatrix& eff) {
  const Assembler fresh(elements, dofs, ElementContext{});
  VectorXd f_fresh;
  SparseMatrix eff_fresh;
  fresh.assemble(coeff, u, v, Assembler::Output{&eff_fresh, &f_fresh, nullptr});
  EXPECT_EQ(f, f_fresh);
  EXPECT_EQ(MatrixXd(eff), MatrixXd(eff_fresh));
}

TEST(Assembler, AResidualAheadOfAFactorizationFormsTheReusableTangentsOnce) {
  // The residual of a step's predictor, which a factorization at the same u follows
  // (Output::tangent_follows): an element with a force of its own forms its tangent there, and
  // the factorization reuses it; a status element is evaluated by both. Forces and matrix are
  // a fresh assembler's.
  std::vector<std::unique_ptr<Element>> elements;
  elements.push_back(std::make_unique<SeparatingSpring>(1, 1, 2));
  elements.push_back(std::make_unique<CountingSpring>(2, 2, 3, true));
  const DofMap dofs(elements, {{1, Dof::UX}});
  const Assembler assembler(elements, dofs, ElementContext{});
  const auto& spring = static_cast<const SeparatingSpring&>(*elements[0]);
  const auto& gap = static_cast<const CountingSpring&>(*elements[1]);
  const VectorXd u = VectorXd::LinSpaced(dofs.n_active(), 0.0, 0.3);
  const VectorXd v = VectorXd::Zero(dofs.n_active());
  const IntegrationCoefficients coeff{1.0, 0.0, 0.0};
  VectorXd f_residual;
  SparseMatrix eff;
  assembler.assemble(coeff, u, v, Assembler::Output{nullptr, &f_residual, nullptr, nullptr, true});
  EXPECT_EQ(spring.force_evaluations, 0);
  EXPECT_EQ(spring.tangents(), 1);
  EXPECT_EQ(gap.evaluations, 1);
  assembler.assemble(coeff, u, v, Assembler::Output{&eff, nullptr, nullptr});
  EXPECT_EQ(spring.force_evaluations, 0);
  EXPECT_EQ(spring.tangents(), 1);  // from the residual's pass
  EXPECT_EQ(gap.evaluations, 2);
  expect_as_a_fresh_assembler(elements, dofs, coeff, u, v, f_residual, eff);
}

TEST(Assembler, TangentPhaseReusesBuffersOnlyForStatelessElementsAtTheSameDofValues) {
  // Residual and tangent of a Newton iteration assemble at the same u: an element without
  // status or history is evaluated once, a status element (gap) every time; an element whose
  // own DOF values changed is evaluated again, the others not; the outputs are those of a fresh
  // evaluation.
  std::vector<std::unique_ptr<Element>> elements;
  elements.push_back(std::make_unique<CountingSpring>(1, 1, 2, false));
  elements.push_back(std::make_unique<CountingSpring>(2, 2, 3, false));
  elements.push_back(std::make_unique<CountingSpring>(3, 3, 4, true));
  const DofMap dofs(elements, {{1, Dof::UX}});
  const Assembler assembler(elements, dofs, ElementContext{});
  const auto count = [&](int e) {
    return static_cast<const CountingSpring&>(*elements[static_cast<std::size_t>(e)]).evaluations;
  };
  VectorXd u = VectorXd::LinSpaced(dofs.n_active(), 0.0, 0.3);
  const VectorXd v = VectorXd::Zero(dofs.n_active());
  const IntegrationCoefficients coeff{1.0, 0.0, 0.0};
  VectorXd f_first, f_second;
  SparseMatrix eff;
  assembler.assemble(coeff, u, v, Assembler::Output{nullptr, &f_first, nullptr});
  assembler.assemble(coeff, u, v, Assembler::Output{&eff, &f_second, nullptr});
  EXPECT_EQ(count(0), 1);
  EXPECT_EQ(count(1), 1);
  EXPECT_EQ(count(2), 2);
  EXPECT_EQ(f_first, f_second);
  // Move node 4 only: element 3 (nodes 3-4) changes, elements 1 and 2 keep their buffers.
  u(dofs.index(DofKey{4, Dof::UX})) += 0.05;
  assembler.assemble(coeff, u, v, Assembler::Output{nullptr, &f_second, nullptr});
  EXPECT_EQ(count(0), 1);
  EXPECT_EQ(count(1), 1);
  EXPECT_EQ(count(2), 3);
  // Move node 3: elements 2 and 3 are evaluated again; the forces equal a fresh assembler's.
  u(dofs.index(DofKey{3, Dof::UX})) -= 0.02;
  assembler.assemble(coeff, u, v, Assembler::Output{&eff, &f_second, nullptr});
  EXPECT_EQ(count(0), 1);
  EXPECT_EQ(count(1), 2);
  EXPECT_EQ(count(2), 4);
  expect_as_a_fresh_assembler(elements, dofs, coeff, u, v, f_second, eff);
}

}  // namespace
}  // namespace impactfe::test_assembler
