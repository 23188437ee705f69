// SHELL281 (shell281.cpp): rigid-body modes, symmetry, patch tests, thin-plate limit without
// locking, thick plate against the Mindlin series, cantilever strip against Euler–Bernoulli.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <set>

#include "../support/dense_assembly.h"
#include "elements/shell281.h"

namespace impactfe::test_shell281 {
namespace {

using testing::DenseSystem;

struct Mesh8 {
  std::map<int, Vec3> nodes;
  std::vector<std::vector<int>> elements;  // I J K L M N O P
};

Shell281Data data(double E, double nu, double t, double rho = 0.0) {
  Shell281Data d;
  d.E = E;
  d.nu = nu;
  d.rho = rho;
  d.thickness.assign(8, t);
  return d;
}

std::unique_ptr<Element> make(int id, const std::vector<int>& ids, const std::vector<Vec3>& x,
                              Shell281Data d) {
  d.node_ids = ids;
  d.positions = x;
  d.thickness.resize(ids.size(), d.thickness.front());
  return std::make_unique<Shell281>(id, d, SourceLocation{"test", 1, "E"});
}

std::vector<std::unique_ptr<Element>> build(const Mesh8& m, const Shell281Data& d) {
  std::vector<std::unique_ptr<Element>> out;
  int id = 1;
  for (const auto& e : m.elements) {
    std::vector<Vec3> x;
    for (int n : e) x.push_back(m.nodes.at(n));
    out.push_back(make(id++, e, x, d));
  }
  return out;
}

/// nx × ny 8-node elements on [0, lx] × [0, ly] (z = 0), the nodes of a (2nx+1) × (2ny+1)
/// lattice; `map` may move the lattice points.
Mesh8 rect_mesh(int nx, int ny, double lx, double ly,
                const std::function<Vec3(const Vec3&)>& map = nullptr) {
  Mesh8 m;
  auto id = [&](int i, int j) { return 1 + i + j * (2 * nx + 1); };
  for (int j = 0; j <= 2 * ny; ++j)
    for (int i = 0; i <= 2 * nx; ++i) {
      if (i % 2 == 1 && j % 2 == 1) continue;
      const Vec3 x(lx * i / (2 * nx), ly * j / (2 * ny), 0.0);
      m.nodes[id(i, j)] = map ? map(x) : x;
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = 2 * i, b = 2 * j;
      m.elements.push_back({id(a, b), id(a + 2, b), id(a + 2, b + 2), id(a, b + 2), id(a + 1, b),
                            id(a + 2, b + 1), id(a + 1, b + 2), id(a, b + 1)});
    }
  return m;
}

bool near(double a, double b) {
  return std::abs(a - b) < 1e-9;
}

std::set<DofKey> fix(const Mesh8& m, const std::function<std::vector<Dof>(const Vec3&)>& rule) {
  std::set<DofKey> out;
  for (const auto& [id, x] : m.nodes)
    for (Dof d : rule(x)) out.insert({id, d});
  return out;
}

/// Consistent load of a uniform pressure q on face 1 of every element (along +N).
Eigen::VectorXd pressure(const DenseSystem& s, const std::vector<std::unique_ptr<Element>>& els,
                         double q) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(s.n());
  for (const auto& e : els) {
    Eigen::VectorXd fe;
    e->pressure_load(ElementContext{}, 1, {q, q, q, q}, Eigen::VectorXd::Zero(e->n_dofs()), fe);
    for (int a = 0; a < e->n_dofs(); ++a) {
      const DofKey& k = e->dofs()[static_cast<std::size_t>(a)];
      f(s.index(k.node, k.dof)) += fe(a);
    }
  }
  return f;
}

Eigen::MatrixXd element_stiffness(const Element& e) {
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  e.tangent(ElementContext{}, Eigen::VectorXd::Zero(e.n_dofs()), K, f);
  return K;
}

// ---- rigid-body modes, symmetry ---------------------------------------------------------------
TEST(Shell281, FreeElementHasExactlySixZeroEnergyModes) {
  // A distorted flat quadrilateral tilted in space, a curved one (cylindrical patch) and a
  // triangle: six rigid-body modes (drilling penalty included) and no spurious mechanism.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  std::vector<std::vector<Vec3>> shapes;
  {
    const std::vector<Vec3> c = {Vec3(0, 0, 0), Vec3(2.0, 0.2, 0), Vec3(2.3, 1.6, 0),
                                 Vec3(-0.2, 1.2, 0)};
    std::vector<Vec3> q = c;
    for (int k = 0; k < 4; ++k) q.push_back(0.5 * (c[k] + c[(k + 1) % 4]));
    shapes.push_back(q);
  }
  {
    std::vector<Vec3> q;  // 30° of a cylinder of radius 3, length 2
    const double xi[8][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {0, -1}, {1, 0}, {0, 1}, {-1, 0}};
    for (const auto& p : xi) {
      const double phi = p[0] * M_PI / 12;
      q.emplace_back(3 * std::sin(phi), p[1], 3 * std::cos(phi));
    }
    shapes.push_back(q);
  }
  shapes.push_back({Vec3(0, 0, 0), Vec3(2.0, 0.3, 0), Vec3(0.7, 1.5, 0), Vec3(1.0, 0.15, 0),
                    Vec3(1.35, 0.9, 0), Vec3(0.35, 0.75, 0)});
  for (double t : {0.01, 0.3}) {
    for (const auto& shape : shapes) {
      std::vector<Vec3> x;
      std::vector<int> ids;
      for (const Vec3& p : shape)
        x.push_back(R * p), ids.push_back(static_cast<int>(ids.size()) + 1);
      const auto e = make(1, ids, x, data(2e11, 0.3, t));
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(element_stiffness(*e));
      const Eigen::VectorXd lam = es.eigenvalues();
      const double scale = lam.maxCoeff();
      std::printf("free %zu-node SHELL281 t = %.2f: lambda_6/max = %.2e, lambda_7/max = %.2e\n",
                  shape.size(), t, lam(5) / scale, lam(6) / scale);
      EXPECT_LT(std::abs(lam(5)) / scale, 1e-11);
      EXPECT_GT(lam(6) / scale, 1e-10);  // the seventh is a deformation mode, not a mechanism
    }
  }
}

TEST(Shell281, StiffnessAndMassAreSymmetricAndMassIsConserved) {
  const std::vector<Vec3> c = {Vec3(0, 0, 0), Vec3(2.0, 0.2, 0.1), Vec3(2.3, 1.6, 0.3),
                               Vec3(-0.2, 1.2, 0.05)};
  std::vector<Vec3> x = c;
  for (int k = 0; k < 4; ++k) x.push_back(0.5 * (c[k] + c[(k + 1) % 4]) + Vec3(0, 0, 0.05));
  const auto e = make(1, {1, 2, 3, 4, 5, 6, 7, 8}, x, data(2e11, 0.3, 0.05, 7800));
  const Eigen::MatrixXd K = element_stiffness(*e);
  Eigen::MatrixXd M;
  e->mass(ElementContext{}, M);
  EXPECT_LT((K - K.transpose()).norm(), 1e-12 * K.norm());
  EXPECT_LT((M - M.transpose()).norm(), 1e-12 * M.norm());
  // A rigid translation carries the mass ρ V in each direction (consistent and lumped).
  for (bool lumped : {false, true}) {
    ElementContext ctx;
    ctx.lumped_mass = lumped;
    e->mass(ctx, M);
    for (int i = 0; i < 3; ++i) {
      Eigen::VectorXd r = Eigen::VectorXd::Zero(48);
      for (int a = 0; a < 8; ++a) r(6 * a + i) = 1.0;
      EXPECT_NEAR(r.dot(M * r), 7800 * *e->volume(), 1e-9 * 7800 * *e->volume());
    }
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(M);
    EXPECT_GT(es.eigenvalues().minCoeff(), 0.0) << lumped;  // positive definite
  }
}

// ---- patch tests ------------------------------------------------------------------------------
/// A distorted 2 × 2 patch of [0, 2]²: the interior corner moved to (0.8, 1.2), the midside
/// nodes of the interior sides at their (straight) sides' middles.
Mesh8 patch() {
  Mesh8 m = rect_mesh(2, 2, 2.0, 2.0);
  auto id = [](int i, int j) { return 1 + i + 5 * j; };
  m.nodes[id(2, 2)] = Vec3(0.8, 1.2, 0.0);
  for (const auto& [mid, end] : std::vector<std::pair<int, int>>{
           {id(2, 1), id(2, 0)}, {id(2, 3), id(2, 4)}, {id(1, 2), id(0, 2)}, {id(3, 2), id(4, 2)}})
    m.nodes[mid] = 0.5 * (m.nodes[end] + m.nodes[id(2, 2)]);
  return m;
}

void run_patch(const Mesh8& m, bool membrane, bool bending) {
  // u = εx x + γ y/2, v = γ x/2 + εy y (θz = ½ curl = 0) and w = ½(kx x² + ky y² + kxy x y) with
  // θx = ∂w/∂y, θy = −∂w/∂x prescribed on the boundary nodes: the interior nodes take the exact
  // values, every element N = A ε and M = −D(κ) (M = ∫zσ dz, z toward the top), Q = 0.
  const double E = 1e7, nu = 0.25, t = 0.2;
  const double s1 = membrane ? 1.0 : 0.0, s2 = bending ? 1.0 : 0.0;
  const double ex = 1e-3 * s1, ey = -4e-4 * s1, g = 6e-4 * s1;
  const double kx = 2e-3 * s2, ky = -1e-3 * s2, kxy = 1.5e-3 * s2;
  const auto els = build(m, data(E, nu, t));
  DenseSystem s(els);
  auto exact = [&](const Vec3& x) {
    std::array<double, 6> v{};
    v[0] = ex * x.x() + 0.5 * g * x.y();
    v[1] = 0.5 * g * x.x() + ey * x.y();
    v[2] = 0.5 * (kx * x.x() * x.x() + ky * x.y() * x.y() + kxy * x.x() * x.y());
    v[3] = ky * x.y() + 0.5 * kxy * x.x();     // ∂w/∂y
    v[4] = -(kx * x.x() + 0.5 * kxy * x.y());  // −∂w/∂x
    return v;
  };
  std::vector<int> free, fixed;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(s.n());
  for (int i = 0; i < s.n(); ++i) {
    const DofKey& k = s.dofs()[static_cast<std::size_t>(i)];
    const Vec3& x = m.nodes.at(k.node);
    // The lattice's outer nodes (ids 1 + i + 5 j of the 5 × 5 lattice).
    const int i5 = (k.node - 1) % 5, j5 = (k.node - 1) / 5;
    const bool boundary = i5 == 0 || i5 == 4 || j5 == 0 || j5 == 4;
    u(i) = exact(x)[static_cast<std::size_t>(static_cast<int>(k.dof))];
    (boundary ? fixed : free).push_back(i);
  }
  const int nf = static_cast<int>(free.size());
  Eigen::MatrixXd Kff(nf, nf);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(nf);
  for (int a = 0; a < nf; ++a) {
    for (int i : fixed) rhs(a) -= s.K(free[a], i) * u(i);
    for (int b = 0; b < nf; ++b) Kff(a, b) = s.K(free[a], free[b]);
  }
  const Eigen::VectorXd uf = Kff.ldlt().solve(rhs);
  for (int a = 0; a < nf; ++a) EXPECT_NEAR(uf(a), u(free[a]), 1e-12) << a;
  for (int a = 0; a < nf; ++a) u(free[a]) = uf(a);
  const double A = E * t / (1 - nu * nu), D = E * t * t * t / (12 * (1 - nu * nu));
  const std::vector<double> want = {A * (ex + nu * ey),   A * (ey + nu * ex),
                                    A * (1 - nu) / 2 * g, -D * (kx + nu * ky),
                                    -D * (ky + nu * kx),  -D * (1 - nu) / 2 * kxy};
  for (std::size_t n = 0; n < els.size(); ++n) {
    const auto& e = els[n];
    ElementResultValues r;
    e->results(ElementContext{}, testing::gather(s, *e, u), Eigen::VectorXd(), r);
    // Element axes: e1 along ∂x/∂ξ at the centre, x_N − x_P (midside nodes 6 and 8).
    const auto& ids = m.elements[n];
    const Vec3 d = m.nodes.at(ids[5]) - m.nodes.at(ids[7]);
    const double c = d.x() / d.norm(), sn = d.y() / d.norm();
    auto rot = [&](double sx, double sy, double sxy) {
      return std::array<double, 3>{sx * c * c + sy * sn * sn + 2 * sxy * sn * c,
                                   sx * sn * sn + sy * c * c - 2 * sxy * sn * c,
                                   (sy - sx) * sn * c + sxy * (c * c - sn * sn)};
    };
    const auto Nl = rot(want[0], want[1], want[2]), Ml = rot(want[3], want[4], want[5]);
    const std::vector<double> local = {Nl[0], Nl[1], Nl[2], Ml[0], Ml[1], Ml[2]};
    for (std::size_t k = 0; k < 6; ++k) EXPECT_NEAR(r[k], local[k], 1e-9 * A * 1e-3) << k;
    EXPECT_NEAR(r[18], 0.0, 1e-9);  // QXZ
    EXPECT_NEAR(r[19], 0.0, 1e-9);  // QYZ
    // SX at the top: N/t + 6 M/t².
    EXPECT_NEAR(r[6], local[0] / t + 6 * local[3] / (t * t), 1e-6);
    // The nodal values extrapolated from the Gauss points reproduce the constant field at every
    // node (corners and midsides), the surfaces' SEQV from the extrapolated components.
    std::map<int, ElementResultValues> at;
    ASSERT_TRUE(e->nodal_results(ElementContext{}, testing::gather(s, *e, u), at));
    ASSERT_EQ(at.size(), 8u);
    for (const auto& [node, v] : at) {
      for (std::size_t k = 0; k < 15; ++k) EXPECT_NEAR(v[k], r[k], 1e-9 * (1.0 + std::abs(r[k])));
      EXPECT_NEAR(v[15], r[15], 1e-9 * (1.0 + r[15])) << node;
      EXPECT_NEAR(v[17], r[17], 1e-9 * (1.0 + r[17])) << node;
    }
  }
}

TEST(Shell281, ConstantMembranePatchTestOnADistortedPatch) {
  run_patch(patch(), true, false);
}

TEST(Shell281, ConstantBendingPatchTestOnADistortedPatch) {
  run_patch(patch(), false, true);
}

TEST(Shell281, ConstantMembraneAndBendingPatchTestOnASkewPatch) {
  run_patch(rect_mesh(2, 2, 2.0, 2.0,
                      [](const Vec3& x) {
                        return Vec3(x.x() + 0.3 * x.y(), 0.9 * x.y() + 0.1 * x.x(), 0.0);
                      }),
            true, true);
}

// ---- plates ---------------------------------------------------------------------------------
/// Square plate a × a, n × n elements under uniform q (face 1), all edges clamped or hard
/// simply supported (w and the tangential rotation held); w at the centre.
double plate_centre(int n, bool clamped, const Shell281Data& d, double a, double q) {
  const Mesh8 m = rect_mesh(n, n, a, a);
  const auto els = build(m, d);
  DenseSystem s(els);
  const auto fixed = fix(m, [&](const Vec3& x) {
    std::vector<Dof> dofs = {Dof::UX, Dof::UY, Dof::ROTZ};
    const bool ex = near(x.x(), 0) || near(x.x(), a), ey = near(x.y(), 0) || near(x.y(), a);
    if (ex || ey) dofs.push_back(Dof::UZ);
    if (ex || (clamped && ey)) dofs.push_back(Dof::ROTX);
    if (ey || (clamped && ex)) dofs.push_back(Dof::ROTY);
    return dofs;
  });
  const Eigen::VectorXd u = s.solve_static(pressure(s, els, q), fixed);
  const int centre = 1 + n + n * (2 * n + 1);
  EXPECT_TRUE(m.nodes.at(centre).isApprox(Vec3(a / 2, a / 2, 0)));
  return u(s.index(centre, Dof::UZ));
}

TEST(Shell281, ThinPlatesMatchKirchhoffWithoutLocking) {
  // Clamped: w = 0.00126532 q a⁴/D, simply supported: 0.00406235 q a⁴/D (Timoshenko &
  // Woinowsky-Krieger Tables 8 and 35). No locking: w/ref the same at a/t = 100 and 1000 (with
  // 2 × 2 Gauss shear instead of the tied one the clamped 8 × 8 plate gave 0.66 at 1000); the
  // error falls as h² from above (8 × 8: 5.0 % clamped, 0.9 % simply supported; 16 × 16: 1.2 %,
  // 0.2 %, measured).
  const double a = 1.0, E = 1e7, nu = 0.3, q = 1.0;
  for (bool clamped : {true, false}) {
    for (int n : clamped ? std::vector<int>{8, 16} : std::vector<int>{8}) {
      double ratio_100 = 0.0;
      for (double ratio : {100.0, 1000.0}) {
        const double t = a / ratio, D = E * t * t * t / (12 * (1 - nu * nu));
        const double ref = (clamped ? 0.00126532 : 0.00406235) * q * a * a * a * a / D;
        const double w = plate_centre(n, clamped, data(E, nu, t), a, q) / ref;
        std::printf("%s plate a/t = %4.0f %dx%d SHELL281: w/ref = %.5f\n",
                    clamped ? "clamped" : "simply supported", ratio, n, n, w);
        if (ratio == 100.0) ratio_100 = w;
        if (ratio == 1000.0) EXPECT_NEAR(w / ratio_100, 1.0, 3e-3);
        const double tol = n == 8 ? (clamped ? 0.06 : 0.012) : (clamped ? 0.015 : 0.004);
        EXPECT_NEAR(w, 1.0, tol) << n;
      }
    }
  }
}

/// Navier series of the hard simply supported Mindlin plate under uniform q (Reddy, Theory and
/// Analysis of Elastic Plates and Shells, §10.2), w at the centre.
double mindlin_ss_centre(double a, double t, double E, double nu, double q, double k) {
  const double D = E * t * t * t / (12 * (1 - nu * nu)), G = E / (2 * (1 + nu));
  double w = 0.0;
  for (int m = 1; m < 400; m += 2)
    for (int n = 1; n < 400; n += 2) {
      const double l2 = M_PI * M_PI * (m * m + n * n) / (a * a);
      const double sign = ((m + n) / 2 - 1) % 2 == 0 ? 1.0 : -1.0;
      w += sign * 16 * q / (M_PI * M_PI * m * n) / (D * l2 * l2) * (1 + D * l2 / (k * G * t));
    }
  return w;
}

TEST(Shell281, ThickSimplySupportedPlateMatchesTheMindlinSolution) {
  // a/t = 10: 4.2728e-3 q a⁴/D (Reddy Table 10.2.1, k = 5/6), 5 % above Kirchhoff's 4.062e-3,
  // so the test tells a Mindlin plate from a Kirchhoff one.
  const double a = 1.0, E = 1e7, nu = 0.3, q = 1.0;
  for (double ratio : {10.0, 5.0}) {
    const double t = a / ratio, D = E * t * t * t / (12 * (1 - nu * nu));
    const double ref = mindlin_ss_centre(a, t, E, nu, q, 5.0 / 6.0);
    const double w = plate_centre(8, false, data(E, nu, t), a, q);
    std::printf("thick SS plate a/t = %2.0f: w D/(q a^4) = %.6f, Mindlin %.6f\n", ratio, w * D / q,
                ref * D / q);
    EXPECT_NEAR(w / ref, 1.0, 1.2e-2);  // 8 × 8: +0.9 % (measured)
  }
}

TEST(Shell281, CantileverStripMatchesEulerBernoulli) {
  // L = 10, b = 1, t = 0.1, ν = 0: tip load P on the end nodes (consistent: P/6, 2P/3, P/6):
  // w = P L³/(3 E I) (shear deflection P L/(k G A) is 4e-5 of it); root moment P L.
  const double L = 10, b = 1, t = 0.1, E = 2e11, P = 100;
  for (bool tilted : {false, true}) {
    // Tilted: the strip turned about its axis by 30°, loaded along its normal.
    const double c = std::cos(tilted ? M_PI / 6 : 0), sn = std::sin(tilted ? M_PI / 6 : 0);
    const Mesh8 m =
        rect_mesh(10, 1, L, b, [&](const Vec3& x) { return Vec3(x.x(), c * x.y(), sn * x.y()); });
    const Vec3 normal(0, -sn, c);
    const auto els = build(m, data(E, 0.0, t));
    DenseSystem s(els);
    const auto fixed = fix(m, [&](const Vec3& x) {
      if (near(x.x(), 0))
        return std::vector<Dof>{Dof::UX, Dof::UY, Dof::UZ, Dof::ROTX, Dof::ROTY, Dof::ROTZ};
      return std::vector<Dof>{};
    });
    Eigen::VectorXd f = Eigen::VectorXd::Zero(s.n());
    const Dof dirs[3] = {Dof::UX, Dof::UY, Dof::UZ};
    for (const auto& [id, x] : m.nodes)
      if (near(x.x(), L)) {
        const double share = near(x.y(), 0) || near(x.y(), c * b) ? P / 6 : 2 * P / 3;
        for (int i = 0; i < 3; ++i) f(s.index(id, dirs[i])) += share * normal(i);
      }
    const Eigen::VectorXd u = s.solve_static(f, fixed);
    const double I = b * t * t * t / 12, ref = P * L * L * L / (3 * E * I);
    for (const auto& [id, x] : m.nodes)
      if (near(x.x(), L)) {
        const Vec3 w(u(s.index(id, Dof::UX)), u(s.index(id, Dof::UY)), u(s.index(id, Dof::UZ)));
        EXPECT_NEAR(w.dot(normal) / ref, 1.0, 2e-3) << id;
      }
    // Root element moment per width ≈ P (L − x_c)/b at its centre x_c = 0.5.
    ElementResultValues r;
    els.front()->results(ElementContext{}, testing::gather(s, *els.front(), u), Eigen::VectorXd(),
                         r);
    EXPECT_NEAR(std::abs(r[3]), P * (L - 0.5) / b, 5e-3 * P * L);  // 947.3 (measured)
  }
}

TEST(Shell281, SimplySupportedPlateFrequencyMatchesKirchhoff) {
  // f11 = (π/2) (2/a²) √(D/(ρt)) for the simply supported thin square plate (Leissa 1969).
  const double a = 1.0, E = 2e11, nu = 0.3, t = 0.005, rho = 7800;
  const Mesh8 m = rect_mesh(8, 8, a, a);
  const auto els = build(m, data(E, nu, t, rho));
  DenseSystem s(els);
  const auto fixed = fix(m, [&](const Vec3& x) {
    std::vector<Dof> dofs = {Dof::UX, Dof::UY, Dof::ROTZ};
    const bool ex = near(x.x(), 0) || near(x.x(), a), ey = near(x.y(), 0) || near(x.y(), a);
    if (ex || ey) dofs.push_back(Dof::UZ);
    if (ex) dofs.push_back(Dof::ROTX);
    if (ey) dofs.push_back(Dof::ROTY);
    return dofs;
  });
  const double D = E * t * t * t / (12 * (1 - nu * nu));
  const double f11 = M_PI / 2 * 2 / (a * a) * std::sqrt(D / (rho * t));
  const double f = std::sqrt(s.eigenvalues(fixed)(0)) / (2 * M_PI);
  std::printf("SS plate f11 = %.4f Hz, Kirchhoff %.4f Hz\n", f, f11);
  EXPECT_NEAR(f / f11, 1.0, 1e-2);  // 0.9949 (measured)
}

}  // namespace
}  // namespace impactfe::test_shell281

namespace impactfe::test_shell281 {
namespace {

TEST(Shell281, StressStiffnessGivesTheEulerBucklingLoadOfACantileverStrip) {
  // L = 10, b = 1, t = 0.1, ν = 0, clamped at x = 0, axial compression P at the free end:
  // K u0 = f, then (K + λ K_G(u0)) x = 0 gives λ P = π² E I / (4 L²) (Euler's first case; the
  // shear correction P/(kGA) is 1e-7 of it). The plate strip's width b = 10 t: EI = E b t³/12.
  const double L = 10, b = 1, t = 0.1, E = 2e11, P = 1000;
  const Mesh8 m = rect_mesh(10, 1, L, b);
  const auto els = build(m, data(E, 0.0, t));
  DenseSystem s(els);
  const auto fixed = fix(m, [&](const Vec3& x) {
    if (near(x.x(), 0))
      return std::vector<Dof>{Dof::UX, Dof::UY, Dof::UZ, Dof::ROTX, Dof::ROTY, Dof::ROTZ};
    return std::vector<Dof>{Dof::UY};  // no in-plane sway: the out-of-plane mode only
  });
  Eigen::VectorXd f = Eigen::VectorXd::Zero(s.n());
  for (const auto& [id, x] : m.nodes)
    if (near(x.x(), L))
      f(s.index(id, Dof::UX)) -= (near(x.y(), 0) || near(x.y(), b) ? P / 6 : 2 * P / 3);
  const Eigen::VectorXd u0 = s.solve_static(f, fixed);
  Eigen::MatrixXd KG = Eigen::MatrixXd::Zero(s.n(), s.n());
  for (const auto& e : els) {
    const auto* shell = dynamic_cast<const Shell281*>(e.get());
    const Eigen::MatrixXd kg = shell->geometric_stiffness(testing::gather(s, *e, u0));
    const auto& d = e->dofs();
    for (int a = 0; a < e->n_dofs(); ++a)
      for (int c = 0; c < e->n_dofs(); ++c)
        KG(s.index(d[a].node, d[a].dof), s.index(d[c].node, d[c].dof)) += kg(a, c);
  }
  // With SSTIF the element adds the same K_G to its tangent.
  {
    ElementContext ctx;
    ctx.stress_stiffening = true;
    Eigen::MatrixXd K1, K0;
    Eigen::VectorXd f1;
    const Eigen::VectorXd ue = testing::gather(s, *els.front(), u0);
    els.front()->tangent(ctx, ue, K1, f1);
    K0 = dynamic_cast<const Shell281*>(els.front().get())->stiffness();
    EXPECT_LT((K1 - K0 - dynamic_cast<const Shell281*>(els.front().get())->geometric_stiffness(ue))
                  .norm(),
              1e-12 * K0.norm());
  }
  std::vector<int> free;
  for (int i = 0; i < s.n(); ++i)
    if (!fixed.count(s.dofs()[static_cast<std::size_t>(i)])) free.push_back(i);
  const int nf = static_cast<int>(free.size());
  Eigen::MatrixXd Kf(nf, nf), Gf(nf, nf);
  for (int i = 0; i < nf; ++i)
    for (int j = 0; j < nf; ++j) Kf(i, j) = s.K(free[i], free[j]), Gf(i, j) = -KG(free[i], free[j]);
  // K x = λ (−K_G) x: −K_G is not definite, so take the eigenvalues of K⁻¹(−K_G), the largest
  // μ = 1/λ being the first buckling load factor.
  const Eigen::MatrixXd A = Kf.ldlt().solve(Gf);
  Eigen::EigenSolver<Eigen::MatrixXd> es(A);
  double mu = 0.0;
  for (int i = 0; i < nf; ++i) mu = std::max(mu, es.eigenvalues()(i).real());
  const double I = b * t * t * t / 12, Pcr = M_PI * M_PI * E * I / (4 * L * L);
  std::printf("cantilever strip buckling: %.6g, Euler %.6g\n", P / mu, Pcr);
  EXPECT_NEAR(P / mu / Pcr, 1.0, 3e-3);  // 0.9985 (measured, 10 elements)
}

}  // namespace
}  // namespace impactfe::test_shell281
