// Unit tests of the SHELL63 / SHELL181 element (src/elements/shell4.*, shell_kernel.*).
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/errors.h"
#include "elements/shell4.h"
#include "elements/shell_frame.h"
#include "shell4_test_helpers.h"

namespace impactfe::test_shell4 {
namespace {

using testing::build;
using testing::DenseSystem;
using testing::make_shell;
using testing::plate_data;
using testing::ShellMesh;
using testing::solve_prescribed;

const std::vector<Vec3> kQuad = {
    {0.1, -0.05, 0.0}, {2.2, 0.1, 0.0}, {1.9, 1.3, 0.0}, {-0.2, 1.0, 0.0}};
const std::vector<Vec3> kTri = {{0.1, -0.05, 0.0}, {2.2, 0.3, 0.0}, {0.7, 1.4, 0.0}};
// A quad in general position in space, warped: corner 3 lifted off the plane of 0, 1, 2.
std::vector<Vec3> warped_quad() {
  const Eigen::Matrix3d R =
      (Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()) * Eigen::AngleAxisd(0.3, Vec3::UnitX()))
          .toRotationMatrix();
  std::vector<Vec3> x = kQuad;
  x[2].z() = 0.15;
  for (auto& p : x) p = R * p + Vec3(3.0, -1.0, 2.0);
  return x;
}

std::unique_ptr<Element> quad(const shell::KernelData& k, const std::vector<Vec3>& x = kQuad) {
  return make_shell(1, {1, 2, 3, 4}, x, k);
}
std::unique_ptr<Element> tri(const shell::KernelData& k, const std::vector<Vec3>& x = kTri) {
  return make_shell(1, {1, 2, 3}, x, k);
}

Eigen::MatrixXd stiffness(const Element& e, const ElementContext& ctx = {},
                          Eigen::VectorXd u = Eigen::VectorXd()) {
  if (u.size() == 0) u.setZero(e.n_dofs());
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  e.tangent(ctx, u, K, f);
  return K;
}

/// Rigid-body motion vector: translation t plus infinitesimal rotation w about the origin.
Eigen::VectorXd rigid(const std::vector<Vec3>& x, const Vec3& t, const Vec3& w) {
  Eigen::VectorXd r(6 * static_cast<int>(x.size()));
  for (std::size_t a = 0; a < x.size(); ++a) {
    r.segment<3>(6 * static_cast<int>(a)) = t + w.cross(x[a]);
    r.segment<3>(6 * static_cast<int>(a) + 3) = w;
  }
  return r;
}

// ---- DK rotation fields: exact for quadratic w (the basis of the plate patch test) ---------
TEST(Shell4Kernel, DkFieldsReproduceQuadraticDeflection) {
  // w = c0 + c1 x + c2 y + c3 x² + c4 xy + c5 y²; nodal θx = w,y, θy = −w,x; β must be −∇w.
  const double c[6] = {0.3, -0.2, 0.5, 0.7, -0.4, 0.25};
  auto w_x = [&](double x, double y) { return c[1] + 2 * c[3] * x + c[4] * y; };
  auto w_y = [&](double x, double y) { return c[2] + c[4] * x + 2 * c[5] * y; };
  for (int n : {3, 4}) {
    std::vector<Eigen::Vector2d> xy;
    for (int a = 0; a < n; ++a) xy.emplace_back((n == 3 ? kTri : kQuad)[a].head<2>());
    shell::FlatShellKernel k(xy, plate_data(1.0, 0.3, 0.1));
    Eigen::VectorXd U(3 * n);
    for (int a = 0; a < n; ++a) {
      const double x = xy[a].x(), y = xy[a].y();
      U(3 * a) = c[0] + c[1] * x + c[2] * y + c[3] * x * x + c[4] * x * y + c[5] * y * y;
      U(3 * a + 1) = w_y(x, y);
      U(3 * a + 2) = -w_x(x, y);
    }
    for (auto [xi, eta] : {std::pair{0.2, 0.3}, std::pair{0.6, 0.1}, std::pair{0.1, 0.7}}) {
      if (n == 4) xi = 2 * xi - 1, eta = 2 * eta - 1;
      Eigen::VectorXd Hx, Hy;
      k.dk_rotations(xi, eta, Hx, Hy);
      // Physical point of (ξ, η).
      Eigen::Vector2d p = Eigen::Vector2d::Zero();
      if (n == 3) {
        p = (1 - xi - eta) * xy[0] + xi * xy[1] + eta * xy[2];
      } else {
        const double s[4] = {-1, 1, 1, -1}, t[4] = {-1, -1, 1, 1};
        for (int a = 0; a < 4; ++a) p += 0.25 * (1 + xi * s[a]) * (1 + eta * t[a]) * xy[a];
      }
      EXPECT_NEAR(Hx.dot(U), -w_x(p.x(), p.y()), 1e-12) << "n=" << n;
      EXPECT_NEAR(Hy.dot(U), -w_y(p.x(), p.y()), 1e-12) << "n=" << n;
    }
  }
}

// ---- symmetry and rigid-body modes -----------------------------------------------------------
TEST(Shell4, StiffnessSymmetricWithExactlySixZeroEnergyModes) {
  // Moderately thick (t/L ≈ 0.1) so that the smallest deformation eigenvalue (drilling penalty
  // γ = 1e-3 G t) is ~1e-5 of the largest, far above the 1e-10 threshold; rigid-body
  // eigenvalues are round-off (~1e-16 relative).
  const auto k = plate_data(2.0e5, 0.3, 0.2);
  std::vector<std::pair<std::string, std::unique_ptr<Element>>> cases;
  cases.emplace_back("quad", quad(k));
  cases.emplace_back("triangle", tri(k));
  cases.emplace_back("warped quad", quad(k, warped_quad()));
  for (auto& [name, e] : cases) {
    const Eigen::MatrixXd K = stiffness(*e);
    const double kmax = K.cwiseAbs().maxCoeff();
    EXPECT_LE((K - K.transpose()).cwiseAbs().maxCoeff(), 1e-13 * kmax) << name;
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(K);
    const Eigen::VectorXd ev = es.eigenvalues();
    const double lmax = ev.maxCoeff();
    int zeros = 0;
    for (int i = 0; i < ev.size(); ++i) zeros += std::abs(ev(i)) < 1e-10 * lmax;
    EXPECT_EQ(zeros, 6) << name;
    std::printf("%s: |largest rigid eigenvalue| / max = %.1e, smallest deformation / max = %.1e\n",
                name.c_str(), ev.head(6).cwiseAbs().maxCoeff() / lmax, ev(6) / lmax);
    // The six rigid motions are among them (finite translations / infinitesimal rotations).
    const auto x = name == "triangle" ? kTri : name == "quad" ? kQuad : warped_quad();
    for (int i = 0; i < 6; ++i) {
      Vec3 t = Vec3::Zero(), w = Vec3::Zero();
      (i < 3 ? t : w)(i % 3) = 1.0;
      const Eigen::VectorXd r = rigid(x, t, w);
      EXPECT_LE((K * r).norm(), 1e-12 * kmax * r.norm()) << name << " rigid mode " << i;
    }
  }
}

TEST(Shell4, TriangleFromRepeatedNodeHasEighteenDofs) {
  Model m;
  m.nodes[1] = Node{1, kTri[0]};
  m.nodes[2] = Node{2, kTri[1]};
  m.nodes[3] = Node{3, kTri[2]};
  ElementType et;
  et.id = 1;
  et.ansys_name = "SHELL63";
  m.element_types[1] = et;
  m.materials[1] = Material{1, {{"EX", 3.0e7}, {"NUXY", 0.3}, {"DENS", 7.3e-4}}};
  m.real_sets[1] = RealSet{1, {0.1}};
  ElementRecord rec;
  rec.id = 7;
  rec.nodes = {1, 2, 3, 3};
  rec.where = SourceLocation{"deck.inp", 12, "E"};
  const auto e = create_element(ElementBuildContext{m, {}}, rec);
  EXPECT_EQ(e->n_dofs(), 18);
  EXPECT_STREQ(e->family(), "Shell4");

  // SHELL181 with a SECTYPE SHELL thickness gives the stiffness of SHELL181 with the same
  // thickness as a real constant (SHELL181 is the Mindlin kernel, SHELL63 the DK one).
  ElementType et181 = et;
  et181.id = 2;
  et181.ansys_name = "SHELL181";
  m.element_types[2] = et181;
  m.sections[5] = Section{5, "SHELL", "", {0.1}};
  ElementRecord rec181 = rec;
  rec181.type = 2;
  rec181.real = 99;  // not defined: the section must be used
  rec181.secnum = 5;
  const auto e181 = create_element(ElementBuildContext{m, {}}, rec181);
  ElementRecord rec181_real = rec;
  rec181_real.type = 2;
  const auto e181_real = create_element(ElementBuildContext{m, {}}, rec181_real);
  EXPECT_LE((stiffness(*e181_real) - stiffness(*e181)).norm(), 1e-12 * stiffness(*e181).norm());
  EXPECT_GT((stiffness(*e) - stiffness(*e181)).norm(), 1e-3 * stiffness(*e).norm());

  // Input errors carry the element's location.
  auto expect_error = [&](const ElementRecord& r, const std::string& what) {
    try {
      create_element(ElementBuildContext{m, {}}, r);
      ADD_FAILURE() << "no error for " << what;
    } catch (const InputError& err) {
      EXPECT_EQ(err.where().line, 12) << what;
      EXPECT_NE(std::string(err.what()).find("element 7"), std::string::npos) << err.what();
    }
  };
  ElementRecord bad = rec;
  bad.nodes = {1, 2, 2, 3};
  expect_error(bad, "repeated node");
  m.nodes[4] = Node{4, 0.5 * (kTri[0] + kTri[1])};
  bad.nodes = {1, 2, 4, 4};
  expect_error(bad, "collinear nodes");
  bad = rec;
  bad.mat = 2;
  m.materials[2] = Material{2, {{"DENS", 1.0}}};
  expect_error(bad, "missing EX");
  bad = rec;
  bad.real = 3;
  m.real_sets[3] = RealSet{3, {0.0}};
  expect_error(bad, "zero thickness");
}

// ---- mass -----------------------------------------------------------------------------------
TEST(Shell4, MassSumsEqualRhoTArea) {
  // Per direction Σ_ij M(u_i, u_j) = ∫(ρt + ADMSUA) dA, consistent and lumped.
  // Triangle with linearly varying thickness: ∫t dA = A (t1 + t2 + t3)/3 exactly.
  auto k = plate_data(2.0e5, 0.3, 0.1, 7.8e-9);
  k.t = {0.1, 0.2, 0.3, 0.0};
  k.added_mass = 2.0e-10;
  const auto e = tri(k);
  const double A = 0.5 * (kTri[1] - kTri[0]).cross(kTri[2] - kTri[0]).norm();
  const double expect_tri = (7.8e-9 * 0.2 + 2.0e-10) * A;
  // Rectangle 2 × 1.5, uniform t.
  const auto kq = plate_data(2.0e5, 0.3, 0.1, 7.8e-9);
  const auto q = quad(kq, {{0, 0, 0}, {2, 0, 0}, {2, 1.5, 0}, {0, 1.5, 0}});
  const double expect_quad = 7.8e-9 * 0.1 * 3.0;
  for (bool lumped : {false, true}) {
    ElementContext ctx;
    ctx.lumped_mass = lumped;
    for (auto [el, expect] : {std::pair{e.get(), expect_tri}, std::pair{q.get(), expect_quad}}) {
      Eigen::MatrixXd M;
      el->mass(ctx, M);
      EXPECT_LE((M - M.transpose()).cwiseAbs().maxCoeff(), 1e-14 * M.cwiseAbs().maxCoeff());
      for (int c = 0; c < 3; ++c) {
        Eigen::VectorXd r = Eigen::VectorXd::Zero(el->n_dofs());
        for (int a = c; a < el->n_dofs(); a += 6) r(a) = 1.0;
        EXPECT_NEAR(r.dot(M * r), expect, 1e-13 * expect) << "lumped=" << lumped << " dir " << c;
      }
      // Mass is positive semi-definite; consistent mass is positive definite (rotary inertia).
      const double lmin = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues()(0);
      if (lumped)
        EXPECT_GE(lmin, 0.0);
      else
        EXPECT_GT(lmin, 0.0);
    }
  }
}

// ---- patch tests (distorted 5-element patch of MacNeal & Harder 1985) -----------------------
/// In-plane tensor (Sx, Sy, Sxy) in axes rotated by phi (element x axis along I→J).
Eigen::Vector3d rotate_tensor(const Eigen::Vector3d& s, double phi) {
  const double c = std::cos(phi), n = std::sin(phi);
  return {s(0) * c * c + s(1) * n * n + 2 * s(2) * n * c,
          s(0) * n * n + s(1) * c * c - 2 * s(2) * n * c,
          (s(1) - s(0)) * n * c + s(2) * (c * c - n * n)};
}
double element_angle(const ShellMesh& m, const Element& e) {
  const Vec3 d = m.nodes.at(e.dofs()[6].node) - m.nodes.at(e.dofs()[0].node);
  return std::atan2(d.y(), d.x());
}

ShellMesh patch(bool triangles) {
  ShellMesh m;
  const double c[8][2] = {{0, 0},       {0.24, 0},    {0.24, 0.12}, {0, 0.12},
                          {0.04, 0.02}, {0.18, 0.03}, {0.16, 0.08}, {0.08, 0.08}};
  for (int i = 0; i < 8; ++i) m.nodes[i + 1] = Vec3(c[i][0], c[i][1], 0.0);
  const std::vector<std::vector<int>> quads = {
      {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 4, 8, 7}, {4, 1, 5, 8}, {5, 6, 7, 8}};
  for (const auto& q : quads) {
    if (triangles) {
      m.elements.push_back({q[0], q[1], q[2]});
      m.elements.push_back({q[0], q[2], q[3]});
    } else {
      m.elements.push_back(q);
    }
  }
  return m;
}

TEST(Shell4, MembraneConstantStrainPatchTest) {
  const double E = 1.0e6, nu = 0.25, t = 0.001;
  for (bool triangles : {false, true}) {
    const ShellMesh mesh = patch(triangles);
    const auto els = build(mesh, plate_data(E, nu, t));
    DenseSystem s(els);
    // u = 1e-3 (x + y/2), v = 1e-3 (y + x/2): ε = (1e-3, 1e-3, 1e-3), rotation 0.
    auto exact = [](const Vec3& x) {
      return Vec3(1e-3 * (x.x() + 0.5 * x.y()), 1e-3 * (x.y() + 0.5 * x.x()), 0.0);
    };
    std::map<DofKey, double> bc;
    for (int n = 1; n <= 8; ++n) {
      for (Dof d : {Dof::UZ, Dof::ROTX, Dof::ROTY}) bc[{n, d}] = 0.0;
      if (n <= 4) {
        bc[{n, Dof::UX}] = exact(mesh.nodes.at(n)).x();
        bc[{n, Dof::UY}] = exact(mesh.nodes.at(n)).y();
        bc[{n, Dof::ROTZ}] = 0.0;
      }
    }
    const Eigen::VectorXd u = solve_prescribed(s, Eigen::VectorXd::Zero(s.n()), bc);
    for (int n = 5; n <= 8; ++n) {
      EXPECT_NEAR(u(s.index(n, Dof::UX)), exact(mesh.nodes.at(n)).x(), 1e-15) << n;
      EXPECT_NEAR(u(s.index(n, Dof::UY)), exact(mesh.nodes.at(n)).y(), 1e-15) << n;
      EXPECT_NEAR(u(s.index(n, Dof::ROTZ)), 0.0, 1e-14) << n;
    }
    const double f = E * t / (1 - nu * nu);
    for (const auto& e : els) {
      ElementResultValues r;
      e->results({}, testing::gather(s, *e, u), Eigen::VectorXd(), r);
      // Resultants are in element axes (x along I→J).
      const Eigen::Vector3d ref = rotate_tensor(
          f * 1e-3 * Eigen::Vector3d(1 + nu, 1 + nu, 0.5 * (1 - nu)), element_angle(mesh, *e));
      EXPECT_NEAR(r[0], ref(0), 1e-10 * f * 1e-3);
      EXPECT_NEAR(r[1], ref(1), 1e-10 * f * 1e-3);
      EXPECT_NEAR(r[2], ref(2), 1e-10 * f * 1e-3);
      EXPECT_NEAR(r[9], r[0] / t, 1e-9 * std::abs(r[0] / t));  // SX_MID = TX/t
    }
  }
}

TEST(Shell4, PlateConstantCurvaturePatchTest) {
  const double E = 1.0e6, nu = 0.25, t = 0.001;
  const double D = E * t * t * t / (12 * (1 - nu * nu));
  // w = 1e-3 (x² + xy + y²)/2: κ = −(w,xx, w,yy, 2w,xy) = −1e-3 (1, 1, 1).
  auto w = [](const Vec3& x) { return 0.5e-3 * (x.x() * x.x() + x.x() * x.y() + x.y() * x.y()); };
  auto wx = [](const Vec3& x) { return 0.5e-3 * (2 * x.x() + x.y()); };
  auto wy = [](const Vec3& x) { return 0.5e-3 * (x.x() + 2 * x.y()); };
  for (bool triangles : {false, true}) {
    const ShellMesh mesh = patch(triangles);
    const auto els = build(mesh, plate_data(E, nu, t));
    DenseSystem s(els);
    std::map<DofKey, double> bc;
    for (int n = 1; n <= 8; ++n) {
      for (Dof d : {Dof::UX, Dof::UY, Dof::ROTZ}) bc[{n, d}] = 0.0;
      if (n <= 4) {
        const Vec3& x = mesh.nodes.at(n);
        bc[{n, Dof::UZ}] = w(x);
        bc[{n, Dof::ROTX}] = wy(x);
        bc[{n, Dof::ROTY}] = -wx(x);
      }
    }
    const Eigen::VectorXd u = solve_prescribed(s, Eigen::VectorXd::Zero(s.n()), bc);
    for (int n = 5; n <= 8; ++n) {
      const Vec3& x = mesh.nodes.at(n);
      EXPECT_NEAR(u(s.index(n, Dof::UZ)), w(x), 1e-15) << n;
      EXPECT_NEAR(u(s.index(n, Dof::ROTX)), wy(x), 1e-14) << n;
      EXPECT_NEAR(u(s.index(n, Dof::ROTY)), -wx(x), 1e-14) << n;
    }
    const double m_ref = D * 1e-3;
    for (const auto& e : els) {
      ElementResultValues r;
      e->results({}, testing::gather(s, *e, u), Eigen::VectorXd(), r);
      const Eigen::Vector3d ref = rotate_tensor(
          -m_ref * Eigen::Vector3d(1 + nu, 1 + nu, 0.5 * (1 - nu)), element_angle(mesh, *e));
      EXPECT_NEAR(r[3], ref(0), 1e-9 * m_ref) << "MX";
      EXPECT_NEAR(r[4], ref(1), 1e-9 * m_ref) << "MY";
      EXPECT_NEAR(r[5], ref(2), 1e-9 * m_ref) << "MXY";
      // Top fibre: σ = 6M/t² (z up), bottom the opposite.
      EXPECT_NEAR(r[6], 6 * r[3] / (t * t), 1e-9 * std::abs(r[6]));
      EXPECT_NEAR(r[12], -6 * r[3] / (t * t), 1e-9 * std::abs(r[6]));
    }
  }
}

// ---- co-rotational large deflection ----------------------------------------------------------
Eigen::VectorXd finite_rotation(const std::vector<Vec3>& x, const Eigen::Matrix3d& R,
                                const Vec3& t) {
  const Eigen::AngleAxisd aa(R);
  Eigen::VectorXd u(6 * static_cast<int>(x.size()));
  for (std::size_t a = 0; a < x.size(); ++a) {
    u.segment<3>(6 * static_cast<int>(a)) = R * x[a] + t - x[a];
    u.segment<3>(6 * static_cast<int>(a) + 3) = aa.angle() * aa.axis();
  }
  return u;
}

TEST(Shell4, WarpedQuadResultsVanishUnderRigidMotionsAndMatchTheCorotationalOnes) {
  // The results rotate the corner displacements to element axes corner by corner instead of
  // forming A = W T (issue 11). A wrong rotation strains the element under rigid motions and
  // parts the linear results from the co-rotational ones (rotated by the corotated frame) at
  // small displacements. (The rigid links move a warped quad's corners in an hourglass pattern,
  // which the centroidal results do not see.)
  const auto k = plate_data(2.0e5, 0.3, 0.05);
  const auto x = warped_quad();
  const auto e = quad(k, x);
  Eigen::VectorXd u(24);
  for (int i = 0; i < 24; ++i) u(i) = 1e-6 * std::sin(1.0 + 0.7 * i);
  ElementResultValues linear, corotational;
  e->results({}, u, Eigen::VectorXd(), linear);
  ElementContext large;
  large.large_deflection = true;
  e->results(large, u, Eigen::VectorXd(), corotational);
  ASSERT_EQ(linear.size(), corotational.size());
  double scale = 0.0;
  for (double v : linear) scale = std::max(scale, std::abs(v));
  ASSERT_GT(scale, 0.0);
  for (std::size_t i = 0; i < linear.size(); ++i)
    EXPECT_NEAR(linear[i], corotational[i], 1e-4 * scale) << "result " << i;
  for (int i = 0; i < 6; ++i) {
    Vec3 t = Vec3::Zero(), w = Vec3::Zero();
    (i < 3 ? t : w)(i % 3) = 1e-6;
    ElementResultValues r;
    e->results({}, rigid(x, t, w), Eigen::VectorXd(), r);
    for (double v : r) EXPECT_LE(std::abs(v), 1e-8 * scale) << "rigid mode " << i;
  }
}

TEST(Shell4, CorotationalZeroForceUnderRigidRotation) {
  ElementContext ctx;
  ctx.large_deflection = true;
  const auto k = plate_data(2.0e5, 0.3, 0.05);
  for (const auto& x : {kQuad, kTri, warped_quad()}) {
    const auto e = make_shell(
        1, x.size() == 3 ? std::vector<int>{1, 2, 3} : std::vector<int>{1, 2, 3, 4}, x, k);
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(M_PI / 2, Vec3(1, -2, 0.5).normalized()).toRotationMatrix();
    const Eigen::VectorXd u = finite_rotation(x, R, Vec3(0.3, -1.0, 2.0));
    Eigen::MatrixXd K;
    Eigen::VectorXd f;
    e->tangent(ctx, u, K, f);
    const double kmax = stiffness(*e).cwiseAbs().maxCoeff();
    // Round-off level: |f| / (kmax · L) ~ 1e-15; the linear element would give O(1).
    EXPECT_LE(f.cwiseAbs().maxCoeff(), 1e-12 * kmax) << x.size();
    Eigen::VectorXd f_lin = stiffness(*e) * u;
    EXPECT_GT(f_lin.cwiseAbs().maxCoeff(), 1e-2 * kmax);
    // Stresses vanish too.
    ElementResultValues r;
    e->results(ctx, u, Eigen::VectorXd(), r);
    for (double v : r) EXPECT_LE(std::abs(v), 1e-9 * 2.0e5);
  }
}

/// Fourth-order central difference (−g(2h) + 8g(h) − 8g(−h) + g(−2h))/(12h) of a vector function
/// of u along each DOF: truncation O(h⁴), so ~1e-11 relative with h = 1e-3 (lengths ~1, rotations
/// < π). Test-only: the element's tangent itself is analytic.
template <class F>
Eigen::MatrixXd jacobian_fd(const F& g, const Eigen::VectorXd& u, double h = 1e-3) {
  const int n = static_cast<int>(u.size());
  Eigen::MatrixXd J(g(u).size(), n);
  for (int j = 0; j < n; ++j) {
    auto at = [&](double s) {
      Eigen::VectorXd up = u;
      up(j) += s * h;
      return Eigen::VectorXd(g(up));
    };
    J.col(j) = (8.0 * (at(1) - at(-1)) - (at(2) - at(-2))) / (12.0 * h);
  }
  return J;
}

/// A co-rotational test state: corners x, a rigid rotation of `angle` about `axis`, plus a
/// deformation of amplitude `strain` on translations and `bend` on rotations.
struct CorotationalCase {
  const char* name;
  std::vector<Vec3> x;
  double angle;
  Vec3 axis;
  double strain, bend;
};

std::vector<CorotationalCase> corotational_cases() {
  const Vec3 axis = Vec3(0.2, 1, 0.4).normalized();
  return {
      {"quad", kQuad, 0.8, axis, 0.03, 0.05},
      {"triangle", kTri, 0.8, axis, 0.03, 0.05},
      {"warped quad", warped_quad(), 0.8, axis, 0.03, 0.05},
      {"quad near pi/2, tiny strain", kQuad, M_PI / 2 - 1e-3, Vec3(1, -2, 0.5).normalized(), 1e-6,
       1e-6},
      {"warped near pi/2, tiny strain", warped_quad(), M_PI / 2 + 1e-3, axis, 1e-6, 1e-6},
      {"triangle, psi = 0", kTri, 0.0, axis, 0.02, 0.0},
      {"quad, psi ~ 0", kQuad, 0.0, axis, 0.02, 1e-9},
      {"warped, large deformational rotation", warped_quad(), 1.2, axis, 0.05, 0.5},
  };
}

Eigen::VectorXd corotational_state(const CorotationalCase& c) {
  const int nd = 6 * static_cast<int>(c.x.size());
  Eigen::VectorXd u =
      finite_rotation(c.x, Eigen::AngleAxisd(c.angle, c.axis).toRotationMatrix(), Vec3::Zero());
  const Eigen::VectorXd pert = Eigen::VectorXd::LinSpaced(nd, -1.0, 1.0).array().sin();
  for (int i = 0; i < nd; ++i) u(i) += pert(i) * (i % 6 < 3 ? c.strain : c.bend);
  return u;
}

/// `mindlin`: SHELL181's kernel (Mindlin bending, MITC shear, drilling factor 1).
std::unique_ptr<Shell4> make_case_shell(const CorotationalCase& c, bool mindlin = false) {
  Shell4Data d;
  d.node_ids = c.x.size() == 3 ? std::vector<int>{1, 2, 3} : std::vector<int>{1, 2, 3, 4};
  d.positions = c.x;
  d.kernel = plate_data(2.0e5, 0.3, 0.05);
  d.kernel.mindlin = mindlin;
  if (mindlin) d.kernel.drill_factor = 1.0;
  return std::make_unique<Shell4>(1, d, SourceLocation{"test", 1, "E"});
}

TEST(Shell4, CorotationalTangentMatchesFiniteDifferences) {
  ElementContext ctx;
  ctx.large_deflection = true;
  for (bool mindlin : {false, true})
    for (const CorotationalCase& c : corotational_cases()) {
      const auto e = make_case_shell(c, mindlin);
      // At u = 0 the co-rotational tangent is the linear stiffness.
      const Eigen::MatrixXd K0 = stiffness(*e);
      EXPECT_LE((stiffness(*e, ctx) - K0).norm(), 1e-12 * K0.norm()) << c.name;
      const Eigen::VectorXd u = corotational_state(c);
      Eigen::MatrixXd K;
      Eigen::VectorXd f;
      e->tangent(ctx, u, K, f);
      const auto f_int = [&](const Eigen::VectorXd& v) {
        Eigen::MatrixXd dummy;
        Eigen::VectorXd fv;
        e->tangent(ctx, v, dummy, fv);
        return fv;
      };
      // The step scales with the deformation so that the differences stay within round-off of f.
      const double h = std::max(1e-3 * std::max(c.strain, c.bend), 1e-6);
      const Eigen::MatrixXd Kfd = jacobian_fd(f_int, u, h);
      const double err = (K - Kfd).norm() / K.norm();
      EXPECT_LE(err, 1e-8) << c.name << (mindlin ? " (Mindlin)" : "");
      std::printf("%-40s %s |K - K_fd| / |K| = %.2e\n", c.name, mindlin ? "Mindlin" : "DK     ",
                  err);
    }
}

TEST(Shell4, InternalForceAloneIsBitwiseTheForceOfTheTangent) {
  // Element::internal_force serves the residuals that need no tangent (issue 11).
  ElementContext small, large;
  large.large_deflection = true;
  for (const CorotationalCase& c : corotational_cases()) {
    const auto e = make_case_shell(c);
    const Eigen::VectorXd u = corotational_state(c);
    for (const ElementContext& ctx : {small, large}) {
      Eigen::MatrixXd K;
      Eigen::VectorXd f_tangent, f;
      e->tangent(ctx, u, K, f_tangent);
      e->internal_force(ctx, u, f);
      EXPECT_EQ(f, f_tangent) << c.name;
    }
    EXPECT_TRUE(e->separate_internal_force(large));
    EXPECT_FALSE(e->separate_internal_force(small));
  }
}

TEST(Shell4, KeptCorotationalStiffnessGivesTheSameAnswersAsFormedOnDemand) {
  // Built for large deflection a shell keeps K̄ = Wᵀ K_l W; otherwise it forms K̄ (and K_l, M_l)
  // at each call (issue 11: memory). Both must give the same tangent, force and mass bitwise.
  ElementContext small, large;
  large.large_deflection = true;
  for (const CorotationalCase& c : corotational_cases()) {
    Shell4Data d;
    d.node_ids = c.x.size() == 3 ? std::vector<int>{1, 2, 3} : std::vector<int>{1, 2, 3, 4};
    d.positions = c.x;
    d.kernel = plate_data(2.0e5, 0.3, 0.05);
    const Shell4 formed(1, d, SourceLocation{"test", 1, "E"});
    d.keep_corotational_stiffness = true;
    const Shell4 kept(1, d, SourceLocation{"test", 1, "E"});
    const Eigen::VectorXd u = corotational_state(c);
    for (const ElementContext& ctx : {small, large}) {
      Eigen::MatrixXd K_formed, K_kept, M_formed, M_kept;
      Eigen::VectorXd f_formed, f_kept, g_formed, g_kept;
      formed.tangent(ctx, u, K_formed, f_formed);
      kept.tangent(ctx, u, K_kept, f_kept);
      formed.internal_force(ctx, u, g_formed);
      kept.internal_force(ctx, u, g_kept);
      formed.mass(ctx, M_formed);
      kept.mass(ctx, M_kept);
      EXPECT_EQ(K_formed, K_kept) << c.name;
      EXPECT_EQ(f_formed, f_kept) << c.name;
      EXPECT_EQ(g_formed, g_kept) << c.name;
      EXPECT_EQ(M_formed, M_kept) << c.name;
      EXPECT_GT(K_kept.norm(), 0.0) << c.name;
    }
  }
}

TEST(Shell4, TriangleFastPathEqualsTheGeneralCorotationalPath) {
  // CorotationalTriangle works in the facet's frame with the triangle's closed forms; it must
  // give the element-independent path's tangent and force to round-off, at rigid rotations up
  // to π/2, large deformational rotations, tiny strains and ψ = 0.
  ElementContext large;
  large.large_deflection = true;
  std::vector<CorotationalCase> cases;
  for (const CorotationalCase& c : corotational_cases())
    if (c.x.size() == 3) cases.push_back(c);
  const Vec3 axis = Vec3(-0.3, 0.5, 1.0).normalized();
  cases.push_back({"triangle near pi/2, tiny strain", kTri, M_PI / 2 - 1e-3, axis, 1e-6, 1e-6});
  cases.push_back({"triangle, large deformational rotation", kTri, 1.2, axis, 0.05, 0.5});
  cases.push_back({"triangle, strain only", kTri, 0.0, axis, 0.03, 0.0});
  for (bool mindlin : {false, true})
    for (const CorotationalCase& c : cases) {
      const auto e = make_case_shell(c, mindlin);
      ASSERT_TRUE(e->fast_triangle()) << c.name;
      const Eigen::VectorXd u = corotational_state(c);
      Eigen::MatrixXd K, K_general;
      Eigen::VectorXd f, f_general, f_alone;
      e->tangent(large, u, K, f);
      e->corotational_tangent_general(u, K_general, f_general);
      e->internal_force(large, u, f_alone);
      EXPECT_EQ(f_alone, f) << c.name;
      // The deformation the stresses come from: the general path's d (its out-of-plane
      // translations are round-off).
      ShellCorners X(3, 3);
      for (int a = 0; a < 3; ++a) X.col(a) = c.x[static_cast<std::size_t>(a)];
      const ShellFrame frame0 = shell_frame(X, false);
      const CorotationalTriangle fast({c.x[0], c.x[1], c.x[2]}, frame0.R, frame0.c,
                                      e->kernel().stiffness());
      Eigen::VectorXd d_general;
      e->corotational_kinematics(u, d_general, nullptr);
      EXPECT_LE((fast.deformation(u) - d_general).cwiseAbs().maxCoeff(), 1e-13) << c.name;
      // Round-off of f: d = Rcᵀ r − R0ᵀ(X − c0) cancels coordinates of order L to a deformation
      // of order strain·L, so f carries ~ε |K| L of noise, the whole of f at tiny strains.
      const double L = (c.x[1] - c.x[0]).norm();
      const double f_scale = f_general.norm() + 1e-3 * K_general.norm() * L;
      EXPECT_LE((f - f_general).norm(), 1e-11 * f_scale) << c.name;
      EXPECT_LE((K - K_general).norm(), 1e-11 * K_general.norm()) << c.name;
      std::printf("%-40s |K - K_general| / |K| = %.2e, |f - f_general| / |f| = %.2e\n", c.name,
                  (K - K_general).norm() / K_general.norm(), (f - f_general).norm() / f_scale);
    }
}

TEST(Shell4, TriangleReusesItsLastStateOnlyAtTheSameDisplacement) {
  // CorotationalTriangle keeps the state of its last evaluation for the next one at the same u
  // (issue 11). Whatever the order of the calls, every answer must be bitwise that of an
  // element evaluated once, at that u alone.
  const CorotationalCase c{"triangle", kTri, 0.8, Vec3(0.2, 1, 0.4).normalized(), 0.03, 0.05};
  const auto e = make_case_shell(c);
  ShellCorners X(3, 3);
  for (int a = 0; a < 3; ++a) X.col(a) = c.x[static_cast<std::size_t>(a)];
  const ShellFrame frame0 = shell_frame(X, false);
  const auto fresh = [&] {
    return std::make_unique<CorotationalTriangle>(std::array<Vec3, 3>{c.x[0], c.x[1], c.x[2]},
                                                  frame0.R, frame0.c, e->kernel().stiffness());
  };
  const Eigen::VectorXd u1 = corotational_state(c);
  Eigen::VectorXd u2 = u1;
  u2(4) += 1e-3;  // a rotation only: the frame is the same, the corner's state is not
  Eigen::VectorXd u3 = u1;
  u3(0) = u3(0) == 0.0 ? 1e-3 : 0.0;
  for (const Eigen::VectorXd& u : {u1, u2, u3}) {
    Eigen::MatrixXd K_once, K;
    Eigen::VectorXd f_once, g_once, f, g;
    fresh()->tangent(u, K_once, f_once);
    fresh()->internal_force(u, g_once);
    const Eigen::VectorXd d_once = fresh()->deformation(u);
    const auto t = fresh();
    // After an evaluation at another u, then after one at the same u (deformation alone, then
    // the force, then the tangent, then the deformation again).
    for (const Eigen::VectorXd& other : {u1, u2, u3}) {
      t->internal_force(other, g);
      EXPECT_EQ(t->deformation(u), d_once);
      t->internal_force(u, g);
      EXPECT_EQ(g, g_once);
      t->tangent(u, K, f);
      EXPECT_EQ(K, K_once);
      EXPECT_EQ(f, f_once);
      EXPECT_EQ(t->deformation(u), d_once);
      t->tangent(other, K, f);
      t->tangent(u, K, f);
      EXPECT_EQ(K, K_once);
    }
  }
}

TEST(Shell4, CorotationalGeometricStiffnessIsTheDerivativeOfBTransposed) {
  // K_G = ∂(B(u)ᵀ f)/∂u at a fixed f of order one: independent of the strain level, so it checks
  // the geometric part exactly even in the tiny-strain cases, where it is invisible in K.
  for (const CorotationalCase& c : corotational_cases()) {
    const auto e = make_case_shell(c);
    const int nd = e->n_dofs();
    const Eigen::VectorXd u = corotational_state(c);
    const Eigen::VectorXd f_l = Eigen::VectorXd::LinSpaced(nd, 0.3, 2.9).array().cos();
    Eigen::MatrixXd KG;
    e->corotational_geometric_stiffness(u, f_l, KG);
    const auto Bt_f = [&](const Eigen::VectorXd& v) {
      Eigen::VectorXd d;
      Eigen::MatrixXd B;
      e->corotational_kinematics(v, d, &B);
      return Eigen::VectorXd(B.transpose() * f_l);
    };
    const Eigen::MatrixXd KGfd = jacobian_fd(Bt_f, u);
    const double err = (KG - KGfd).norm() / KGfd.norm();
    EXPECT_LE(err, 1e-9) << c.name;
    std::printf("%-40s |K_G - K_G,fd| / |K_G| = %.2e\n", c.name, err);
  }
}

TEST(Shell4, StressStiffeningAddsMembraneGeometricStiffness) {
  // Square plate stretched in x: the geometric stiffness must raise the energy of a transverse
  // mode w = x (slope 1 over the element) by ∫ TX (w,x)² dA = TX · A.
  const std::vector<Vec3> x = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const double E = 1.0e3, nu = 0.0, t = 0.1;
  const auto e = quad(plate_data(E, nu, t), x);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(24);
  for (int a = 0; a < 4; ++a) u(6 * a) = 1e-2 * x[a].x();  // ε_x = 0.01 → TX = E t ε
  ElementContext ss;
  ss.stress_stiffening = true;
  EXPECT_TRUE(e->is_nonlinear(ss));
  const Eigen::MatrixXd Kg = stiffness(*e, ss, u) - stiffness(*e);
  Eigen::VectorXd mode = Eigen::VectorXd::Zero(24);
  for (int a = 0; a < 4; ++a) mode(6 * a + 2) = x[a].x();
  EXPECT_NEAR(mode.dot(Kg * mode), E * t * 1e-2 * 1.0, 1e-12);
}

TEST(Shell4, KeyoptionsAndThetaThroughTheModel) {
  // Unit square, stretched in x (ε_x = 1e-3) and bent (w = x²/2 · 1e-3).
  Model m;
  const std::vector<Vec3> x = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  for (int i = 0; i < 4; ++i) m.nodes[i + 1] = Node{i + 1, x[i]};
  m.materials[1] = Material{1, {{"EX", 1.0e6}, {"NUXY", 0.0}}};
  m.real_sets[1] = RealSet{1, {0.1, 0, 0, 0, 0, 90.0}};  // THETA = 90° (6th constant)
  m.real_sets[2] = RealSet{2, {0.1}};
  for (int key1 : {0, 1, 2}) {
    ElementType et;
    et.id = key1 + 1;
    et.ansys_name = "SHELL63";
    et.keyopt[1] = key1;
    m.element_types[et.id] = et;
  }
  Eigen::VectorXd u = Eigen::VectorXd::Zero(24);
  for (int a = 0; a < 4; ++a) {
    u(6 * a) = 1e-3 * x[a].x();
    u(6 * a + 2) = 0.5e-3 * x[a].x() * x[a].x();
    u(6 * a + 4) = -1e-3 * x[a].x();  // θy = −w,x
  }
  auto res = [&](int type, int real) {
    ElementRecord rec;
    rec.id = 1;
    rec.type = type;
    rec.real = real;
    rec.nodes = {1, 2, 3, 4};
    ElementResultValues r;
    create_element(ElementBuildContext{m, {}}, rec)->results({}, u, Eigen::VectorXd(), r);
    return r;
  };
  const double TX = 1.0e6 * 0.1 * 1e-3, MX = -1.0e6 * 1e-3 / 12 * 1e-3;  // ν = 0
  const auto full = res(1, 2), membrane = res(2, 2), bending = res(3, 2), rotated = res(1, 1);
  EXPECT_NEAR(full[0], TX, 1e-9 * TX);
  EXPECT_NEAR(full[3], MX, 1e-9 * std::abs(MX));
  EXPECT_NEAR(membrane[0], TX, 1e-9 * TX);  // KEYOPT(1)=1: membrane only
  EXPECT_EQ(membrane[3], 0.0);
  EXPECT_EQ(bending[0], 0.0);  // KEYOPT(1)=2: bending only
  EXPECT_NEAR(bending[3], MX, 1e-9 * std::abs(MX));
  // THETA = 90°: the x result axis is the element y axis.
  EXPECT_NEAR(rotated[1], TX, 1e-9 * TX);
  EXPECT_NEAR(rotated[0], 0.0, 1e-9 * TX);
  EXPECT_NEAR(rotated[4], MX, 1e-9 * std::abs(MX));
}

}  // namespace
}  // namespace impactfe::test_shell4
