// Unit tests of the quadratic solids SOLID186 / SOLID187 (src/elements/solid_quadratic.*):
// symmetry, rigid-body modes, patch tests on distorted meshes with curved edges, mass (total,
// HRZ positivity), consistent pressure loads, and a cantilever against Timoshenko beam theory.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <set>

#include "../support/dense_assembly.h"
#include "core/errors.h"
#include "elements/cell_topology.h"
#include "elements/solid_quadratic.h"

namespace impactfe::test_solid_quadratic {
namespace {

constexpr double kE = 200e3;
constexpr double kRho = 7.85e-9;

std::vector<std::vector<int>> no_faces() {
  return {};
}

std::vector<std::vector<int>> hex_faces() {
  const CellTopology& c = cell_topology(VtkCell::QuadraticHexahedron);
  std::vector<std::vector<int>> out;
  const auto& f = c.faces;
  for (const auto& face :
       {std::vector<int>{f[0][3], f[0][0], f[0][1], f[0][2]}, f[2], f[3], f[4], f[5], f[1]})
    out.push_back(face_with_midsides(c, face));
  return out;
}

/// The nodes of an element at natural positions mapped by `map` (node ids 1..n).
std::vector<Vec3> mapped_nodes(QuadraticShape shape, const std::function<Vec3(Vec3)>& map) {
  std::vector<Vec3> x;
  for (const Eigen::Vector3d& xi : quadratic_shape_nodes_xi(shape)) x.push_back(map(xi));
  return x;
}

std::vector<int> ids(int n, int first = 1) {
  std::vector<int> out;
  for (int i = 0; i < n; ++i) out.push_back(first + i);
  return out;
}

/// A curved, non-affine brick: trilinear distortion plus a bulge of the midside nodes.
Vec3 distorted_brick(const Vec3& xi) {
  return Vec3(1.0 * xi(0) + 0.1 * xi(1) * xi(2) + 0.05 * (1 - xi(1) * xi(1)),
              0.8 * xi(1) + 0.07 * xi(0) * xi(1) + 0.04 * (1 - xi(0) * xi(0)),
              0.6 * xi(2) + 0.05 * xi(0) + 0.03 * xi(0) * xi(1) * xi(2));
}

Vec3 distorted_tet(const Vec3& xi) {
  return Vec3(2.0 * xi(0) + 0.3 * xi(1) + 0.05 * xi(0) * xi(1), 1.5 * xi(1) + 0.2 * xi(2),
              1.2 * xi(2) + 0.1 * xi(0) + 0.04 * xi(1) * xi(2));
}

std::unique_ptr<QuadraticSolid> brick(int order, const std::function<Vec3(Vec3)>& map) {
  return std::make_unique<QuadraticSolid>(
      1, QuadraticShape::Hex20, ids(20), mapped_nodes(QuadraticShape::Hex20, map),
      IsotropicElasticity{kE, 0.3, kRho}, gauss_cube(order), hex_faces());
}

std::unique_ptr<QuadraticSolid> tet(const std::function<Vec3(Vec3)>& map) {
  return std::make_unique<QuadraticSolid>(
      1, QuadraticShape::Tet10, ids(10), mapped_nodes(QuadraticShape::Tet10, map),
      IsotropicElasticity{kE, 0.3, kRho}, tetrahedron_4_point(), no_faces());
}

Eigen::MatrixXd stiffness(const Element& e) {
  Eigen::MatrixXd k;
  Eigen::VectorXd f;
  e.tangent({}, Eigen::VectorXd::Zero(e.n_dofs()), k, f);
  return k;
}

int zero_eigenvalues(const Eigen::MatrixXd& k) {
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(k).eigenvalues();
  const double top = ev.cwiseAbs().maxCoeff();
  int zeros = 0;
  for (int i = 0; i < ev.size(); ++i) {
    EXPECT_GT(ev(i), -1e-9 * top) << "negative eigenvalue " << i;
    if (std::abs(ev(i)) < 1e-9 * top) ++zeros;
  }
  return zeros;
}

/// Rigid translation and rotation fields at the element's nodes.
Eigen::MatrixXd rigid_modes(const std::vector<Vec3>& x) {
  const int n = static_cast<int>(x.size());
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(3 * n, 6);
  for (int a = 0; a < n; ++a) {
    for (int i = 0; i < 3; ++i) r(3 * a + i, i) = 1.0;
    for (int i = 0; i < 3; ++i) {
      Vec3 w = Vec3::Zero();
      w(i) = 1.0;
      r.block<3, 1>(3 * a, 3 + i) = w.cross(x[a]);
    }
  }
  return r;
}

TEST(QuadraticSolid, StiffnessSymmetricWithSixRigidModes) {
  for (int order : {2, 3}) {
    const auto e = brick(order, distorted_brick);
    const Eigen::MatrixXd k = stiffness(*e);
    EXPECT_LT((k - k.transpose()).norm(), 1e-12 * k.norm());
    const Eigen::MatrixXd r = rigid_modes(mapped_nodes(QuadraticShape::Hex20, distorted_brick));
    EXPECT_LT((k * r).norm(), 1e-9 * k.norm() * r.norm()) << "order " << order;
    // 3x3x3: exactly the 6 rigid modes. 2x2x2 (uniform reduced): 6 more zero-energy modes of a
    // lone element (48 strain samples for 54 deformation modes), which a mesh of more than
    // one element does not communicate (MAPDL's default; Bathe §5.5.6).
    EXPECT_EQ(zero_eigenvalues(k), order == 3 ? 6 : 12) << "order " << order;
  }
  const auto t = tet(distorted_tet);
  const Eigen::MatrixXd kt = stiffness(*t);
  EXPECT_LT((kt - kt.transpose()).norm(), 1e-12 * kt.norm());
  EXPECT_EQ(zero_eigenvalues(kt), 6);
}

/// Linear displacement field u = A x + c and its strain (engineering shear).
struct LinearField {
  Eigen::Matrix3d a;
  Vec3 c;
  Vec3 at(const Vec3& x) const { return a * x + c; }
  Vector6d strain() const {
    Vector6d e;
    e << a(0, 0), a(1, 1), a(2, 2), a(0, 1) + a(1, 0), a(1, 2) + a(2, 1), a(0, 2) + a(2, 0);
    return e;
  }
};

LinearField probe_field() {
  LinearField f;
  f.a << 1e-3, 2e-4, -3e-4, 5e-4, -8e-4, 1e-4, -2e-4, 3e-4, 6e-4;
  f.c = Vec3(0.01, -0.02, 0.005);
  return f;
}

/// Lattice (2n + 1)³ of a distorted block: corner and midside positions of n³ 20-node bricks
/// (node id = lattice index + 1), the interior lattice points moved and the edges curved.
struct BrickPatch {
  int n = 2;
  int id(int i, int j, int k) const { return 1 + i + (2 * n + 1) * (j + (2 * n + 1) * k); }
  Vec3 x(int i, int j, int k) const {
    const double s = 1.0 / (2 * n);
    Vec3 p(i * s, j * s, k * s);
    auto interior = [&](int v) { return v > 0 && v < 2 * n; };
    if (interior(i) && interior(j) && interior(k))
      p +=
          Vec3(0.07 * std::sin(3.0 * i + j), 0.05 * std::cos(2.0 * j + k), 0.06 * std::sin(k + i)) *
          s;
    return p;
  }
  std::vector<std::unique_ptr<Element>> elements(int order) const {
    std::vector<std::unique_ptr<Element>> out;
    const auto xi = quadratic_shape_nodes_xi(QuadraticShape::Hex20);
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          std::vector<int> nodes;
          std::vector<Vec3> xe;
          for (const auto& q : xi) {
            const int a = 2 * i + 1 + static_cast<int>(q(0)),
                      b = 2 * j + 1 + static_cast<int>(q(1)),
                      c = 2 * k + 1 + static_cast<int>(q(2));
            nodes.push_back(id(a, b, c));
            xe.push_back(x(a, b, c));
          }
          out.push_back(std::make_unique<QuadraticSolid>(
              static_cast<int>(out.size()) + 1, QuadraticShape::Hex20, nodes, xe,
              IsotropicElasticity{kE, 0.3, kRho}, gauss_cube(order), hex_faces()));
        }
    return out;
  }
  bool boundary(int i, int j, int k) const {
    auto edge = [&](int v) { return v == 0 || v == 2 * n; };
    return edge(i) || edge(j) || edge(k);
  }
};

TEST(QuadraticSolid, PatchTestDistortedBricks) {
  const BrickPatch patch;
  const LinearField field = probe_field();
  for (int order : {2, 3}) {
    const auto elements = patch.elements(order);
    const testing::DenseSystem sys(elements);
    // Boundary nodes carry the linear field; the interior is solved with no load.
    std::set<DofKey> fixed;
    Eigen::VectorXd u = Eigen::VectorXd::Zero(sys.n());
    std::map<int, Vec3> exact;
    const int m = 2 * patch.n;
    for (int k = 0; k <= m; ++k)
      for (int j = 0; j <= m; ++j)
        for (int i = 0; i <= m; ++i) {
          const int node = patch.id(i, j, k);
          if (!sys.has(node, Dof::UX)) continue;
          exact[node] = field.at(patch.x(i, j, k));
          if (!patch.boundary(i, j, k)) continue;
          for (int d = 0; d < 3; ++d) {
            const Dof dof = d == 0 ? Dof::UX : (d == 1 ? Dof::UY : Dof::UZ);
            fixed.insert({node, dof});
            u(sys.index(node, dof)) = exact[node](d);
          }
        }
    const Eigen::VectorXd solved = sys.solve_static(-sys.K * u, fixed) + u;
    for (const auto& [node, v] : exact)
      for (int d = 0; d < 3; ++d) {
        const Dof dof = d == 0 ? Dof::UX : (d == 1 ? Dof::UY : Dof::UZ);
        EXPECT_NEAR(solved(sys.index(node, dof)), v(d), 1e-12) << "node " << node;
      }
    // The stress is the constant D ε everywhere (centre of each element).
    const Vector6d sigma = isotropic_elasticity_matrix(kE, 0.3) * field.strain();
    for (const auto& e : elements) {
      Eigen::VectorXd ue(e->n_dofs());
      for (int a = 0; a < e->n_dofs(); ++a)
        ue(a) = solved(sys.index(e->dofs()[a].node, e->dofs()[a].dof));
      ElementResultValues out;
      e->results({}, ue, ue, out);
      for (int c = 0; c < 6; ++c) EXPECT_NEAR(out[c], sigma(c), 1e-8 * sigma.norm());
    }
  }
}

TEST(QuadraticSolid, ConstantStrainOfOneTetrahedron) {
  // The linear field is reproduced exactly by a curved 10-node tetrahedron: K u = 0 would not
  // hold (it is loaded by boundary tractions), but the stress at every point is D ε.
  const auto t = tet(distorted_tet);
  const LinearField field = probe_field();
  const auto x = mapped_nodes(QuadraticShape::Tet10, distorted_tet);
  Eigen::VectorXd u(30);
  for (int a = 0; a < 10; ++a) u.segment<3>(3 * a) = field.at(x[a]);
  const Vector6d sigma = isotropic_elasticity_matrix(kE, 0.3) * field.strain();
  for (const auto& q : collapsed_tetrahedron(3))
    EXPECT_LT((t->stress_at(q.xi, u) - sigma).norm(), 1e-9 * sigma.norm());
  const auto b = brick(2, distorted_brick);
  const auto xb = mapped_nodes(QuadraticShape::Hex20, distorted_brick);
  Eigen::VectorXd ub(60);
  for (int a = 0; a < 20; ++a) ub.segment<3>(3 * a) = field.at(xb[a]);
  for (const auto& q : gauss_cube(3))
    EXPECT_LT((b->stress_at(q.xi, ub) - sigma).norm(), 1e-9 * sigma.norm());
}

/// The exact pure-bending field about z (σx = −Eκy, every other stress 0): u = −κxy,
/// v = κ(x² + ν(y² − z²))/2, w = κνyz.
Vec3 pure_bending_field(const Vec3& x, double kappa) {
  return Vec3(-kappa * x(0) * x(1), 0.5 * kappa * (x(0) * x(0) + 0.3 * (x(1) * x(1) - x(2) * x(2))),
              0.3 * kappa * x(1) * x(2));
}

TEST(QuadraticSolid, NodalStressesAreExtrapolatedFromTheStiffnessPoints) {
  // A straight-sided (affine) element reproduces the quadratic pure-bending field exactly, so
  // its stiffness points carry the linear σx = −Eκy, and the nodes must get that linear field
  // at their own y: the 20-node brick (2x2x2 and, fitted by least squares, 3x3x3) and the
  // 10-node tetrahedron. The centroid value (σx at the centroid's y) is wrong at every node.
  const auto skewed = [](const Vec3& xi) {
    return Vec3(2.0 * xi(0) + 0.3 * xi(1), 0.7 * xi(1) + 0.1 * xi(2) - 0.2,
                0.5 * xi(2) + 0.1 * xi(0));
  };
  const double kappa = 1e-4;
  std::vector<std::unique_ptr<QuadraticSolid>> elements;
  elements.push_back(brick(2, skewed));
  elements.push_back(brick(3, skewed));
  elements.push_back(tet(skewed));
  for (const auto& e : elements) {
    const auto x = mapped_nodes(e->shape(), skewed);
    Eigen::VectorXd u(e->n_dofs());
    for (std::size_t a = 0; a < x.size(); ++a)
      u.segment<3>(3 * a) = pure_bending_field(x[a], kappa);
    std::map<int, ElementResultValues> at;
    ASSERT_TRUE(e->nodal_results({}, u, at));
    ASSERT_EQ(at.size(), x.size());
    const double scale = kE * kappa;
    for (std::size_t a = 0; a < x.size(); ++a) {
      const ElementResultValues& r = at.at(static_cast<int>(a) + 1);
      EXPECT_NEAR(r[0], -kE * kappa * x[a](1), 1e-9 * scale) << "node " << a + 1;
      for (int c = 1; c < 6; ++c) EXPECT_NEAR(r[static_cast<std::size_t>(c)], 0.0, 1e-9 * scale);
      EXPECT_NEAR(r[10], std::abs(r[0]), 1e-9 * scale);  // SEQV of uniaxial stress
    }
  }
}

TEST(QuadraticSolid, MassTotalsAndPositiveLumpedMass) {
  const auto box = [](const Vec3& xi) {
    return Vec3(1.0 + xi(0), 0.5 * (1 + xi(1)), 0.75 * (1 + xi(2)));
  };
  const auto e = brick(2, box);
  EXPECT_NEAR(*e->volume(), 2.0 * 1.0 * 1.5, 1e-12);
  Eigen::MatrixXd m;
  e->mass({}, m);
  const double total = kRho * 3.0;
  EXPECT_NEAR(m.sum() / 3.0, total, 1e-12 * total);
  // Row sums of the consistent 20-node mass are negative at the corners (why HRZ is used).
  EXPECT_LT(m.row(0).sum(), 0.0);
  ElementContext lumped;
  lumped.lumped_mass = true;
  e->mass(lumped, m);
  EXPECT_NEAR(m.sum() / 3.0, total, 1e-12 * total);
  EXPECT_TRUE((m - Eigen::MatrixXd(m.diagonal().asDiagonal())).isZero(0.0));
  EXPECT_GT(m.diagonal().minCoeff(), 0.0);
  const auto t = tet([](const Vec3& xi) { return Vec3(2 * xi(0), 1.5 * xi(1), 1.2 * xi(2)); });
  EXPECT_NEAR(*t->volume(), 0.6, 1e-12);
  t->mass({}, m);
  EXPECT_NEAR(m.sum() / 3.0, kRho * 0.6, 1e-12 * kRho);
  // The closed-form consistent mass of the straight 10-node tetrahedron: ρV/420 × 6 on a corner
  // diagonal, 32 on a midside diagonal, −4 between a corner and a midside node of its edges.
  EXPECT_NEAR(m(0, 0), kRho * 0.6 * 6 / 420, 1e-12 * kRho);
  EXPECT_NEAR(m(12, 12), kRho * 0.6 * 32 / 420, 1e-12 * kRho);
  EXPECT_NEAR(m(0, 12), kRho * 0.6 * -4 / 420, 1e-12 * kRho);
  t->mass(lumped, m);
  EXPECT_GT(m.diagonal().minCoeff(), 0.0);
}

TEST(QuadraticSolid, UniformPressureOnAnEightNodeFace) {
  // Face 6 (M-N-O-P, the top z = 1.5) of a 2 x 1 x 1.5 box: total −p A e_z, corners −1/12 and
  // midside nodes 1/3 of p A (the consistent loads of the 8-node face).
  const auto box = [](const Vec3& xi) {
    return Vec3(1.0 + xi(0), 0.5 * (1 + xi(1)), 0.75 * (1 + xi(2)));
  };
  const auto e = brick(2, box);
  Eigen::VectorXd f;
  e->pressure_load({}, 6, {10.0, 10.0, 10.0, 10.0}, Eigen::VectorXd::Zero(60), f);
  double fz = 0.0;
  for (int a = 0; a < 20; ++a) fz += f(3 * a + 2);
  EXPECT_NEAR(fz, -10.0 * 2.0, 1e-10);
  EXPECT_NEAR(f(3 * 4 + 2), 10.0 * 2.0 / 12.0, 1e-10);   // corner M: +pA/12
  EXPECT_NEAR(f(3 * 12 + 2), -10.0 * 2.0 / 3.0, 1e-10);  // midside U: −pA/3
  EXPECT_NEAR(f.norm(), std::sqrt(4 * std::pow(20.0 / 12, 2) + 4 * std::pow(20.0 / 3, 2)), 1e-10);
}

TEST(QuadraticSolid, RefusesLargeDeflectionAndBadShapes) {
  const auto e = brick(2, distorted_brick);
  ElementContext nl;
  nl.large_deflection = true;
  Eigen::MatrixXd k;
  Eigen::VectorXd f;
  EXPECT_THROW(e->tangent(nl, Eigen::VectorXd::Zero(60), k, f), ElementSolutionError);
  // A midside node pulled past the quarter point inverts the Jacobian at the corner.
  auto x = mapped_nodes(QuadraticShape::Hex20, distorted_brick);
  x[8] = x[0] + 0.2 * (x[1] - x[0]);
  EXPECT_THROW(QuadraticSolid(1, QuadraticShape::Hex20, ids(20), x,
                              IsotropicElasticity{kE, 0.3, kRho}, gauss_cube(2), hex_faces()),
               InputError);
}

}  // namespace
}  // namespace impactfe::test_solid_quadratic
