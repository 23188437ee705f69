// Face pressures (APDL_MODELING §5.1-§5.3) through Element::pressure_load: consistent nodal
// loads of SOLID185 faces and SHELL63/181 faces (totals, distribution, sign, tapered values,
// follower direction under large deflection), the refusal of elements without faces, and the
// rotated-node adapter of the same hook.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "assembly/element_adapters.h"
#include "deck/deck_reader.h"
#include "elements/brick8.h"
#include "elements/element_registry.h"
#include "shell4_test_helpers.h"

namespace impactfe::test_surface_loads {
namespace {

std::array<Vec3, 8> box(double lx, double ly, double lz) {
  return {Vec3(0, 0, 0),  Vec3(lx, 0, 0),  Vec3(lx, ly, 0),  Vec3(0, ly, 0),
          Vec3(0, 0, lz), Vec3(lx, 0, lz), Vec3(lx, ly, lz), Vec3(0, ly, lz)};
}

Brick8 brick(const std::array<Vec3, 8>& x) {
  return Brick8(1, {1, 2, 3, 4, 5, 6, 7, 8}, x, IsotropicElasticity{1e7, 0.3, 0.0}, false);
}

Vec3 total(const Eigen::VectorXd& f, int stride) {
  Vec3 t = Vec3::Zero();
  for (int a = 0; a < f.size() / stride; ++a) t += f.segment<3>(stride * a);
  return t;
}

TEST(SurfaceLoads, BrickFacesPushInwardWithTheirArea) {
  const Brick8 b = brick(box(2.0, 3.0, 5.0));
  const std::array<double, 4> p{10, 10, 10, 10};
  const Eigen::VectorXd u = Eigen::VectorXd::Zero(24);
  // Outward normals and areas of faces 1..6 (J-I-L-K, I-J-N-M, J-K-O-N, K-L-P-O, L-I-M-P, M-N-O-P).
  const Vec3 normal[6] = {-Vec3::UnitZ(), -Vec3::UnitY(), Vec3::UnitX(),
                          Vec3::UnitY(),  -Vec3::UnitX(), Vec3::UnitZ()};
  const double area[6] = {6, 10, 15, 10, 15, 6};
  const ElementContext ctx;
  for (int face = 1; face <= 6; ++face) {
    Eigen::VectorXd f;
    b.pressure_load(ctx, face, p, u, f);
    const Vec3 t = total(f, 3);
    EXPECT_TRUE(t.isApprox(-10.0 * area[face - 1] * normal[face - 1], 1e-12)) << face;
    // Uniform pressure on a rectangle: a quarter on each face node.
    int loaded = 0;
    for (int a = 0; a < 8; ++a)
      if (f.segment<3>(3 * a).norm() > 0) {
        ++loaded;
        EXPECT_NEAR(f.segment<3>(3 * a).norm(), 10.0 * area[face - 1] / 4, 1e-10);
      }
    EXPECT_EQ(loaded, 4);
  }
}

TEST(SurfaceLoads, TaperedPressureIsIntegratedConsistently) {
  // Linear pressure p = x on the top face of a unit cube: total ∫ x dA = 1/2; the nodal loads
  // of a bilinear face are ∫ N_a p dA = 1/12 at x = 0 and 1/6 at x = 1.
  const Brick8 b = brick(box(1.0, 1.0, 1.0));
  Eigen::VectorXd f;
  b.pressure_load(ElementContext{}, 6, {0.0, 1.0, 1.0, 0.0}, Eigen::VectorXd::Zero(24), f);
  EXPECT_NEAR(total(f, 3).z(), -0.5, 1e-12);
  EXPECT_NEAR(f(3 * 4 + 2), -1.0 / 12, 1e-12);  // M at x = 0
  EXPECT_NEAR(f(3 * 5 + 2), -1.0 / 6, 1e-12);   // N at x = 1
}

TEST(SurfaceLoads, DegenerateBrickFaceCarriesTheTriangleLoad) {
  // Prism (K = L, O = P): face 6 M-N-O-O is a right triangle of area 1/2.
  const std::array<Vec3, 8> x = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 1, 0),
                                 Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 1, 1), Vec3(0, 1, 1)};
  const Brick8 b(1, {1, 2, 3, 3, 5, 6, 7, 7}, x, IsotropicElasticity{1e7, 0.3, 0.0}, false);
  Eigen::VectorXd f;
  b.pressure_load(ElementContext{}, 6, {4, 4, 4, 4}, Eigen::VectorXd::Zero(b.n_dofs()), f);
  EXPECT_NEAR(total(f, 3).z(), -2.0, 1e-12);
}

TEST(SurfaceLoads, ShellFaceOnePushesAlongTheNormal) {
  const auto k = testing::plate_data(1e7, 0.3, 0.1);
  const auto quad = testing::make_shell(
      1, {1, 2, 3, 4}, {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2, 1, 0), Vec3(0, 1, 0)}, k);
  const auto tri =
      testing::make_shell(2, {1, 2, 3}, {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 1, 0)}, k);
  Eigen::VectorXd f;
  quad->pressure_load(ElementContext{}, 1, {3, 3, 3, 3}, Eigen::VectorXd::Zero(24), f);
  EXPECT_TRUE(total(f, 6).isApprox(Vec3(0, 0, 6), 1e-12));
  for (int a = 0; a < 4; ++a) EXPECT_NEAR(f(6 * a + 2), 1.5, 1e-12);
  EXPECT_EQ(f.segment<3>(3).norm(), 0.0);  // no moments
  quad->pressure_load(ElementContext{}, 2, {3, 3, 3, 3}, Eigen::VectorXd::Zero(24), f);
  EXPECT_TRUE(total(f, 6).isApprox(Vec3(0, 0, -6), 1e-12));
  tri->pressure_load(ElementContext{}, 1, {3, 3, 3, 3}, Eigen::VectorXd::Zero(18), f);
  EXPECT_TRUE(total(f, 6).isApprox(Vec3(0, 0, 3), 1e-12));
  EXPECT_THROW(quad->pressure_load(ElementContext{}, 7, {1, 1, 1, 1}, Eigen::VectorXd::Zero(24), f),
               ModelError);
}

// Faces 3..6 are the edges J-I, K-J, L-K, I-L: a force per unit length in the shell's plane,
// normal to the edge and into the element, linear between the edge's two values.
TEST(SurfaceLoads, ShellEdgePressureActsInThePlane) {
  const auto k = testing::plate_data(1e7, 0.3, 0.1);
  const auto quad = testing::make_shell(
      1, {1, 2, 3, 4}, {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2, 1, 0), Vec3(0, 1, 0)}, k);
  Eigen::VectorXd f;
  // Face 4, K-J (x = 2, length 1): 3 per unit length pushes in −X, 1.5 at J and at K.
  quad->pressure_load(ElementContext{}, 4, {3, 3, 0, 0}, Eigen::VectorXd::Zero(24), f);
  EXPECT_TRUE(total(f, 6).isApprox(Vec3(-3, 0, 0), 1e-12));
  EXPECT_NEAR(f(6 * 1), -1.5, 1e-12);
  EXPECT_NEAR(f(6 * 2), -1.5, 1e-12);
  // Face 3, J-I (y = 0, length 2), 0 at J and 6 at I: total 6 in +Y, 2/3 of it at I.
  quad->pressure_load(ElementContext{}, 3, {0, 6, 0, 0}, Eigen::VectorXd::Zero(24), f);
  EXPECT_TRUE(total(f, 6).isApprox(Vec3(0, 6, 0), 1e-12));
  EXPECT_NEAR(f(6 * 0 + 1), 4.0, 1e-12);
  EXPECT_NEAR(f(6 * 1 + 1), 2.0, 1e-12);
}

TEST(SurfaceLoads, FollowerPressureTurnsWithTheFace) {
  // Rigidly rotate the shell by 90° about X: the pressure now pushes along the rotated normal
  // under large deflection and along the initial one otherwise.
  const auto k = testing::plate_data(1e7, 0.3, 0.1);
  const std::vector<Vec3> x = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  const auto shell = testing::make_shell(1, {1, 2, 3, 4}, x, k);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()).toRotationMatrix();
  Eigen::VectorXd u = Eigen::VectorXd::Zero(24);
  for (int a = 0; a < 4; ++a)
    u.segment<3>(6 * a) = R * x[static_cast<std::size_t>(a)] - x[static_cast<std::size_t>(a)];
  Eigen::VectorXd f;
  ElementContext large;
  large.large_deflection = true;
  shell->pressure_load(large, 1, {1, 1, 1, 1}, u, f);
  EXPECT_TRUE(total(f, 6).isApprox(R * Vec3(0, 0, 1), 1e-12));
  shell->pressure_load(ElementContext{}, 1, {1, 1, 1, 1}, u, f);
  EXPECT_TRUE(total(f, 6).isApprox(Vec3(0, 0, 1), 1e-12));
}

TEST(SurfaceLoads, ElementsWithoutFacesRefuse) {
  const Model m = read_deck_text(
                      "/PREP7\nET,1,LINK180\nSECTYPE,1,LINK\nSECDATA,1\nMP,EX,1,1\nN,1\nN,2,1\n"
                      "E,1,2\n",
                      "t.inp", DeckOptions{})
                      .model;
  ElementBuildContext build{m, [](const ElementRecord&) { return std::string(); }};
  const auto link = create_element(build, m.elements.at(1));
  Eigen::VectorXd f;
  EXPECT_THROW(link->pressure_load(ElementContext{}, 1, {1, 1, 1, 1}, Eigen::VectorXd::Zero(6), f),
               ModelError);
}

TEST(SurfaceLoads, RotatedNodesGetThePressureInNodalAxes) {
  // A brick whose node 5 is rotated 90° about Z: the face-6 load at that node is the global load
  // seen in its nodal axes (x_nodal = +Y, y_nodal = −X).
  Model m = read_deck_text(
                "/PREP7\nET,1,SOLID185\nMP,EX,1,1E7\nN,1\nN,2,1\nN,3,1,1\nN,4,0,1\n"
                "N,5,0,0,1,90\nN,6,1,0,1\nN,7,1,1,1\nN,8,0,1,1\nE,1,2,3,4,5,6,7,8\n",
                "t.inp", DeckOptions{})
                .model;
  ElementBuildContext build{m, [](const ElementRecord&) { return std::string(); }};
  const auto plain = create_element(build, m.elements.at(1));
  const auto rotated = adapt_element(create_element(build, m.elements.at(1)), m, m.elements.at(1));
  Eigen::VectorXd fg, fn;
  plain->pressure_load(ElementContext{}, 5, {1, 1, 1, 1}, Eigen::VectorXd::Zero(24), fg);
  rotated->pressure_load(ElementContext{}, 5, {1, 1, 1, 1}, Eigen::VectorXd::Zero(24), fn);
  // Face 5 (L-I-M-P, x = 0) pushes along +X: at node 5 (position 4) nodal components (0, −f, 0).
  EXPECT_NEAR(fg(12), 0.25, 1e-12);
  EXPECT_NEAR(fn(12), 0.0, 1e-12);
  EXPECT_NEAR(fn(13), -0.25, 1e-12);
  EXPECT_NEAR(fn(0), fg(0), 1e-12);  // unrotated node 1 unchanged
}

}  // namespace
}  // namespace impactfe::test_surface_loads
