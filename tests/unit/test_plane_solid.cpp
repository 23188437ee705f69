// Unit tests of the 2-D solids PLANE182 / PLANE183 (src/elements/plane_solid.*): rigid-body
// modes, patch tests on distorted meshes (plane stress, plane strain, axisymmetry; every
// formulation), pure bending, mass totals, edge pressures and the refusals.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <set>

#include "../support/dense_assembly.h"
#include "core/errors.h"
#include "elements/plane_solid.h"

namespace impactfe::test_plane_solid {
namespace {

constexpr double kE = 200e3;
constexpr double kNu = 0.3;
constexpr double kRho = 7.85e-9;
constexpr double kPi = 3.141592653589793;

struct Variant {
  PlaneShape shape;
  PlaneTechnology technology;
  PlaneBehaviour behaviour;
};

std::vector<Variant> variants() {
  std::vector<Variant> out;
  for (PlaneBehaviour b :
       {PlaneBehaviour::PlaneStress, PlaneBehaviour::PlaneStrain, PlaneBehaviour::Axisymmetric}) {
    out.push_back({PlaneShape::Quad4, PlaneTechnology::Standard, b});
    out.push_back({PlaneShape::Quad4, PlaneTechnology::IncompatibleModes, b});
    out.push_back({PlaneShape::Quad4, PlaneTechnology::Reduced, b});
    if (b != PlaneBehaviour::PlaneStress)
      out.push_back({PlaneShape::Quad4, PlaneTechnology::BBar, b});
    out.push_back({PlaneShape::Quad8, PlaneTechnology::Standard, b});
    out.push_back({PlaneShape::Tri3, PlaneTechnology::Standard, b});
    out.push_back({PlaneShape::Tri6, PlaneTechnology::Standard, b});
  }
  return out;
}

std::string name(const Variant& v) {
  return fmt::format("shape {} technology {} behaviour {}", static_cast<int>(v.shape),
                     static_cast<int>(v.technology), static_cast<int>(v.behaviour));
}

/// A smooth distortion of the plane (curved edges for the quadratic shapes), at X >= 1.
Vec3 distort(double s, double t) {
  return Vec3(2.0 + 1.0 * s + 0.15 * s * t + 0.05 * (1 - t * t),
              0.5 + 0.8 * t + 0.1 * s + 0.06 * (1 - s * s) * t, 0.0);
}

std::unique_ptr<PlaneSolid> element(const Variant& v, const std::vector<int>& ids,
                                    const std::vector<Vec3>& x) {
  PlaneSolidOptions o{v.shape, v.behaviour, v.technology, 0.7};
  return std::make_unique<PlaneSolid>(static_cast<int>(ids.front()), ids, x,
                                      IsotropicElasticity{kE, kNu, kRho}, o,
                                      std::vector<std::vector<int>>{});
}

/// One element of the shape mapped by `distort` from its natural nodes.
std::unique_ptr<PlaneSolid> single(const Variant& v) {
  std::vector<int> ids;
  std::vector<Vec3> x;
  int id = 1;
  for (const Eigen::Vector2d& xi : plane_shape_nodes_xi(v.shape)) {
    ids.push_back(id++);
    x.push_back(distort(0.8 * xi(0), 0.9 * xi(1)));
  }
  return element(v, ids, x);
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

TEST(PlaneSolid, StiffnessSymmetricWithRigidModes) {
  for (const Variant& v : variants()) {
    // 2x2 Gauss on the 8-node quadrilateral leaves one zero-energy mode of a lone element
    // in plane stress and plane strain (it does not propagate through a mesh: Bathe §5.5.6),
    // as in MAPDL. In axisymmetry that mode moves the Gauss points radially, so its hoop
    // strain u_r / r stores energy: only the axial translation is free there.
    const auto e = single(v);
    const Eigen::MatrixXd& k = e->stiffness();
    EXPECT_LT((k - k.transpose()).norm(), 1e-12 * k.norm()) << name(v);
    const bool axisymmetric = v.behaviour == PlaneBehaviour::Axisymmetric;
    const int rigid = axisymmetric ? 1 : 3;
    const int spurious = v.shape == PlaneShape::Quad8 && !axisymmetric ? 1 : 0;
    EXPECT_EQ(zero_eigenvalues(k), rigid + spurious) << name(v);
  }
}

/// A 2x2 patch of elements over the natural square [-1, 1]² mapped by `distort`, with the
/// inner corner moved off the lattice; the lattice has (2m + 1)² positions (m = 2 elements per
/// side, doubled for the midside nodes).
struct Patch {
  Variant v;
  int m = 4;  // lattice intervals per side
  int id(int i, int j) const { return 1 + i + (m + 1) * j; }
  /// Midside nodes at the middle of straight sides (see the patch test).
  bool straight = false;
  Vec3 x(int i, int j) const {
    if (straight && (i % 2 == 1 || j % 2 == 1)) {
      const int di = i % 2, dj = j % 2;  // the side's direction: along i, j or the diagonal
      const Vec3 a = corner(i - di, j - dj), b = corner(i + di, j + dj);
      return 0.5 * (a + b);
    }
    return corner(i, j);
  }
  Vec3 corner(int i, int j) const {
    double s = -1.0 + 2.0 * i / m, t = -1.0 + 2.0 * j / m;
    if (i == m / 2 && j == m / 2) s += 0.17, t -= 0.11;        // the interior corner node
    if (i == m / 2 + 1 && j == m / 2) s += 0.085, t -= 0.055;  // keep its midsides between
    if (i == m / 2 - 1 && j == m / 2) s += 0.085, t -= 0.055;
    if (i == m / 2 && j == m / 2 + 1) s += 0.085, t -= 0.055;
    if (i == m / 2 && j == m / 2 - 1) s += 0.085, t -= 0.055;
    return distort(s, t);
  }
  std::vector<std::unique_ptr<Element>> elements() const {
    std::vector<std::unique_ptr<Element>> out;
    // Every lattice position is a node of the quadratic shapes; the linear ones use the
    // even positions (their elements span two intervals).
    for (int j = 0; j < m; j += 2)
      for (int i = 0; i < m; i += 2) {
        std::vector<std::pair<int, int>> p;
        if (v.shape == PlaneShape::Quad4)
          p = {{i, j}, {i + 2, j}, {i + 2, j + 2}, {i, j + 2}};
        else if (v.shape == PlaneShape::Quad8)
          p = {{i, j},     {i + 2, j},     {i + 2, j + 2}, {i, j + 2},
               {i + 1, j}, {i + 2, j + 1}, {i + 1, j + 2}, {i, j + 1}};
        if (!p.empty()) {
          add(out, p);
          continue;
        }
        // Two triangles per square.
        if (v.shape == PlaneShape::Tri3) {
          add(out, {{i, j}, {i + 2, j}, {i + 2, j + 2}});
          add(out, {{i, j}, {i + 2, j + 2}, {i, j + 2}});
        } else {
          add(out,
              {{i, j}, {i + 2, j}, {i + 2, j + 2}, {i + 1, j}, {i + 2, j + 1}, {i + 1, j + 1}});
          add(out,
              {{i, j}, {i + 2, j + 2}, {i, j + 2}, {i + 1, j + 1}, {i + 1, j + 2}, {i, j + 1}});
        }
      }
    return out;
  }
  void add(std::vector<std::unique_ptr<Element>>& out,
           const std::vector<std::pair<int, int>>& p) const {
    std::vector<int> ids;
    std::vector<Vec3> xs;
    for (const auto& [i, j] : p) {
      ids.push_back(id(i, j));
      xs.push_back(x(i, j));
    }
    out.push_back(element(v, ids, xs));
  }
  bool boundary(int i, int j) const { return i == 0 || j == 0 || i == m || j == m; }
};

/// A linear displacement field of constant strain: plane problems any; axisymmetry
/// u_r = a r, u_z = b z (σr = σθ, τ = 0: an equilibrium state of the ring).
Eigen::Vector2d field(const Vec3& x, PlaneBehaviour b) {
  if (b == PlaneBehaviour::Axisymmetric) return {1e-3 * x(0), -4e-4 * x(1)};
  return {1e-4 + 1e-3 * x(0) + 4e-4 * x(1), -2e-4 + 3e-4 * x(0) - 6e-4 * x(1)};
}

Eigen::Vector4d field_strain(PlaneBehaviour b) {
  if (b == PlaneBehaviour::Axisymmetric) return {1e-3, -4e-4, 1e-3, 0.0};
  return {1e-3, -6e-4, 0.0, 7e-4};
}

TEST(PlaneSolid, PatchTestDistortedMeshes) {
  for (const Variant& v : variants()) {
    // In axisymmetry the nodal residual of a constant stress, ∫ Bᵀσ 2πr dA, carries the
    // extra factor r in its integrand: 2x2 Gauss (8-node) and the 3-point rule (6-node) integrate
    // it exactly only on straight-sided elements (bilinear, resp. affine, geometry); on curved
    // sides the quadratic shapes pass the patch test only in the limit of refinement.
    Patch patch{v};
    patch.straight = v.behaviour == PlaneBehaviour::Axisymmetric &&
                     (v.shape == PlaneShape::Quad8 || v.shape == PlaneShape::Tri6);
    const auto elements = patch.elements();
    const testing::DenseSystem sys(elements);
    std::set<DofKey> fixed;
    Eigen::VectorXd u = Eigen::VectorXd::Zero(sys.n());
    std::map<int, Eigen::Vector2d> exact;
    for (int j = 0; j <= patch.m; ++j)
      for (int i = 0; i <= patch.m; ++i) {
        const int node = patch.id(i, j);
        if (!sys.has(node, Dof::UX)) continue;
        exact[node] = field(patch.x(i, j), v.behaviour);
        if (!patch.boundary(i, j)) continue;
        for (int d = 0; d < 2; ++d) {
          const Dof dof = d == 0 ? Dof::UX : Dof::UY;
          fixed.insert({node, dof});
          u(sys.index(node, dof)) = exact[node](d);
        }
      }
    const Eigen::VectorXd solved = sys.solve_static(-sys.K * u, fixed) + u;
    for (const auto& [node, w] : exact) {
      EXPECT_NEAR(solved(sys.index(node, Dof::UX)), w(0), 1e-11) << name(v) << " node " << node;
      EXPECT_NEAR(solved(sys.index(node, Dof::UY)), w(1), 1e-11) << name(v) << " node " << node;
    }
    // The centroid stress is the constant D ε (plane stress: σzz = 0; plane strain: ν(σx+σy)).
    Eigen::Vector4d eps = field_strain(v.behaviour);
    const double lambda = kE * kNu / ((1 + kNu) * (1 - 2 * kNu)), mu = kE / (2 * (1 + kNu));
    Eigen::Vector4d sigma;
    if (v.behaviour == PlaneBehaviour::PlaneStress) {
      const double c = kE / (1 - kNu * kNu);
      sigma << c * (eps(0) + kNu * eps(1)), c * (eps(1) + kNu * eps(0)), 0.0, mu * eps(3);
    } else {
      const double tr = eps(0) + eps(1) + eps(2);
      sigma << lambda * tr + 2 * mu * eps(0), lambda * tr + 2 * mu * eps(1),
          lambda * tr + 2 * mu * eps(2), mu * eps(3);
    }
    for (const auto& e : elements) {
      Eigen::VectorXd ue(e->n_dofs());
      for (int a = 0; a < e->n_dofs(); ++a)
        ue(a) = solved(sys.index(e->dofs()[a].node, e->dofs()[a].dof));
      ElementResultValues out;
      e->results({}, ue, ue, out);
      for (int c = 0; c < 4; ++c) EXPECT_NEAR(out[c], sigma(c), 1e-8 * sigma.norm()) << name(v);
    }
  }
}

TEST(PlaneSolid, IncompatibleModesBendExactly) {
  // A cantilever strip of rectangles under an end couple: the incompatible modes represent
  // pure bending exactly (Taylor, Beresford & Wilson 1976); full 2x2 locks in shear.
  const double length = 10.0, h = 1.0, t = 0.7, moment = 100.0;
  for (PlaneTechnology tech : {PlaneTechnology::IncompatibleModes, PlaneTechnology::Standard}) {
    std::vector<std::unique_ptr<Element>> elements;
    const int n = 5;
    auto id = [](int i, int j) { return 1 + i + 100 * j; };
    auto xy = [&](int i, int j) { return Vec3(length * i / n, h * j, 0.0); };
    for (int i = 0; i < n; ++i)
      elements.push_back(element({PlaneShape::Quad4, tech, PlaneBehaviour::PlaneStress},
                                 {id(i, 0), id(i + 1, 0), id(i + 1, 1), id(i, 1)},
                                 {xy(i, 0), xy(i + 1, 0), xy(i + 1, 1), xy(i, 1)}));
    testing::DenseSystem sys(elements);
    std::set<DofKey> fixed = {{id(0, 0), Dof::UX}, {id(0, 1), Dof::UX}, {id(0, 0), Dof::UY}};
    Eigen::VectorXd f = Eigen::VectorXd::Zero(sys.n());
    f(sys.index(id(n, 0), Dof::UX)) = moment / h;  // a couple: ±M/h at the end's nodes
    f(sys.index(id(n, 1), Dof::UX)) = -moment / h;
    const Eigen::VectorXd u = sys.solve_static(f, fixed);
    // Beam theory with the fibres free to contract across (plane stress): v(L) = M L²/(2EI),
    // upwards: the couple stretches the bottom fibre and shortens the top one (curvature > 0).
    const double inertia = t * h * h * h / 12.0;
    const double tip = 0.5 * (u(sys.index(id(n, 0), Dof::UY)) + u(sys.index(id(n, 1), Dof::UY)));
    const double exact = moment * length * length / (2.0 * kE * inertia);
    if (tech == PlaneTechnology::IncompatibleModes) {
      EXPECT_NEAR(tip / exact, 1.0, 1e-9);
      // The bending stress is linear across the depth: extrapolated from the 2x2 points to
      // the nodes it is exact there, σx = ±6M/(t h²) (tension at the bottom), also at the
      // clamped end where the centroid value is 0.
      const double fibre = 6.0 * moment / (t * h * h);
      for (int i = 0; i < n; ++i) {
        const auto& e = elements[static_cast<std::size_t>(i)];
        Eigen::VectorXd ue(e->n_dofs());
        for (int a = 0; a < e->n_dofs(); ++a)
          ue(a) = u(sys.index(e->dofs()[a].node, e->dofs()[a].dof));
        std::map<int, ElementResultValues> at;
        ASSERT_TRUE(e->nodal_results({}, ue, at));
        EXPECT_NEAR(at.at(id(i, 0))[0], fibre, 1e-9 * fibre);
        EXPECT_NEAR(at.at(id(i + 1, 1))[0], -fibre, 1e-9 * fibre);
      }
    } else
      EXPECT_LT(tip / exact, 0.5);  // shear locking of the bilinear element
  }
}

TEST(PlaneSolid, MassTotalsAndLumping) {
  for (const Variant& v : variants()) {
    const auto e = single(v);
    const double mass = kRho * *e->volume();
    for (bool lumped : {false, true}) {
      ElementContext ctx;
      ctx.lumped_mass = lumped;
      Eigen::MatrixXd m;
      e->mass(ctx, m);
      double ux = 0.0;
      for (int a = 0; a < m.rows(); a += 2)
        for (int b = 0; b < m.cols(); b += 2) ux += m(a, b);
      EXPECT_NEAR(ux, mass, 1e-12 * mass) << name(v);
      if (lumped)
        for (int a = 0; a < m.rows(); ++a) EXPECT_GT(m(a, a), 0.0) << name(v);
    }
  }
  // A ring of rectangular section: V = 2π r̄ A.
  const auto ring =
      element({PlaneShape::Quad8, PlaneTechnology::Standard, PlaneBehaviour::Axisymmetric},
              {1, 2, 3, 4, 5, 6, 7, 8},
              {Vec3(1, 0, 0), Vec3(3, 0, 0), Vec3(3, 1, 0), Vec3(1, 1, 0), Vec3(2, 0, 0),
               Vec3(3, 0.5, 0), Vec3(2, 1, 0), Vec3(1, 0.5, 0)});
  EXPECT_NEAR(*ring->volume(), 2 * kPi * 2.0 * 2.0, 1e-12);
}

TEST(PlaneSolid, EdgePressureOnQuadraticAndLinearEdges) {
  // Face 1 (J-I) of a unit square, p = 10 into the element: the load points along −n = +Y.
  const std::vector<Vec3> x8 = {Vec3(0, 0, 0), Vec3(2, 0, 0),   Vec3(2, 1, 0), Vec3(0, 1, 0),
                                Vec3(1, 0, 0), Vec3(2, 0.5, 0), Vec3(1, 1, 0), Vec3(0, 0.5, 0)};
  PlaneSolidOptions o{PlaneShape::Quad8, PlaneBehaviour::PlaneStress, PlaneTechnology::Standard,
                      0.5};
  PlaneSolid quad8(1, {1, 2, 3, 4, 5, 6, 7, 8}, x8, {kE, kNu, kRho}, o,
                   {{1, 0, 4}, {2, 1, 5}, {3, 2, 6}, {0, 3, 7}});
  Eigen::VectorXd f;
  quad8.pressure_load({}, 1, {10, 10, 10, 10}, Eigen::VectorXd::Zero(16), f);
  const double total = 10 * 2 * 0.5;
  EXPECT_NEAR(f(1), total / 6, 1e-12);
  EXPECT_NEAR(f(3), total / 6, 1e-12);
  EXPECT_NEAR(f(9), 2 * total / 3, 1e-12);
  EXPECT_NEAR(f.sum(), total, 1e-12);
  // Face 2 (K-J) of the same element: along −X.
  quad8.pressure_load({}, 2, {10, 10, 10, 10}, Eigen::VectorXd::Zero(16), f);
  EXPECT_NEAR(f(2) + f(4) + f(10), -10 * 1 * 0.5, 1e-12);
  // Axisymmetric 4-node element, face 2 at r = 2 (K-J), p linear from 0 at K to 6 at J:
  // total −∫ p 2π r dz = −2π · 2 · 3.
  PlaneSolidOptions a{PlaneShape::Quad4, PlaneBehaviour::Axisymmetric, PlaneTechnology::BBar, 1};
  PlaneSolid quad4(2, {1, 2, 3, 4}, {x8[0], x8[1], x8[2], x8[3]}, {kE, kNu, kRho}, a,
                   {{1, 0}, {2, 1}, {3, 2}, {0, 3}});
  quad4.pressure_load({}, 2, {0, 6, 0, 0}, Eigen::VectorXd::Zero(8), f);
  EXPECT_NEAR(f(2) + f(4), -2 * kPi * 2 * 3, 1e-12);
  EXPECT_NEAR(f(4), -2 * kPi * 2 * 1, 1e-12);  // K (z = 1, UX = f(4)) gets 1/3 of the load
  EXPECT_NEAR(f(2), -2 * kPi * 2 * 2, 1e-12);  // J (z = 0, p = 6) gets 2/3
}

TEST(PlaneSolid, RefusesBadShapes) {
  PlaneSolidOptions o{PlaneShape::Quad4, PlaneBehaviour::Axisymmetric, PlaneTechnology::Standard,
                      1};
  const std::vector<Vec3> x = {Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0)};
  EXPECT_THROW(PlaneSolid(1, {1, 2, 3, 4}, x, {kE, kNu, kRho}, o, {}), InputError);
  o.behaviour = PlaneBehaviour::PlaneStress;
  const std::vector<Vec3> bow = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)};
  EXPECT_THROW(PlaneSolid(1, {1, 2, 3, 4}, bow, {kE, kNu, kRho}, o, {}), InputError);
  PlaneSolid ok(1, {1, 2, 3, 4}, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)},
                {kE, kNu, kRho}, o, {});
  ElementContext ctx;
  ctx.large_deflection = true;
  Eigen::MatrixXd k;
  Eigen::VectorXd f;
  EXPECT_THROW(ok.tangent(ctx, Eigen::VectorXd::Zero(8), k, f), ElementSolutionError);
}

}  // namespace
}  // namespace impactfe::test_plane_solid
