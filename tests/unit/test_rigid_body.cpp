// Rigid bodies of explicit dynamics (explicit/rigid_body.h, docs/explicit_dynamics.md): the
// constraint codes of EDMP,RIGID, the inertia about the centre (parallel axes), the angular
// acceleration about free axes only, and the second moment of a brick against its closed form.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "elements/hexahedron_volume.h"
#include "explicit/rigid_body.h"

namespace impactfe::test_rigid_body {
namespace {

TEST(RigidBody, ConstraintCodesFixTheAxesOfTheCommand) {
  using A = std::array<bool, 3>;
  EXPECT_EQ(rigid_constraint_axes(0), (A{false, false, false}));
  EXPECT_EQ(rigid_constraint_axes(1), (A{true, false, false}));
  EXPECT_EQ(rigid_constraint_axes(2), (A{false, true, false}));
  EXPECT_EQ(rigid_constraint_axes(3), (A{false, false, true}));
  EXPECT_EQ(rigid_constraint_axes(4), (A{true, true, false}));
  EXPECT_EQ(rigid_constraint_axes(5), (A{false, true, true}));
  EXPECT_EQ(rigid_constraint_axes(6), (A{true, false, true}));
  EXPECT_EQ(rigid_constraint_axes(7), (A{true, true, true}));
}

TEST(RigidBody, BrickSecondMomentIsTheClosedForm) {
  // A 2 x 3 x 4 box with its corner at (1, 2, 3): ∫x_i x_j dV = V (c_i c_j + δ_ij a_i²/12).
  const double a[3] = {2.0, 3.0, 4.0}, lo[3] = {1.0, 2.0, 3.0};
  double x[8], y[8], z[8];
  const int corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                            {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int k = 0; k < 8; ++k) {
    x[k] = lo[0] + a[0] * corner[k][0];
    y[k] = lo[1] + a[1] * corner[k][1];
    z[k] = lo[2] + a[2] * corner[k][2];
  }
  double s[9];
  hexahedron::second_moment(x, y, z, s);
  const double v = a[0] * a[1] * a[2];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double ci = lo[i] + a[i] / 2, cj = lo[j] + a[j] / 2;
      const double exact = v * (ci * cj + (i == j ? a[i] * a[i] / 12.0 : 0.0));
      EXPECT_NEAR(s[3 * i + j], exact, 1e-12 * v * 100.0) << i << " " << j;
    }
}

TEST(RigidBody, InertiaIsTakenAboutTheCentreOfMass) {
  // Two point masses 1 and 3 at x = 0 and x = 4: centre x = 3, J_yy = J_zz = 1·9 + 3·1 = 12.
  RigidBody body;
  body.nodes = {0, 1};
  const std::vector<double> mass{1.0, 3.0}, x0{0.0, 4.0}, y0{0.0, 0.0}, z0{0.0, 0.0};
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  second(0, 0) = 1.0 * 0.0 + 3.0 * 16.0;
  set_rigid_body_inertia(body, mass, x0, y0, z0, second);
  EXPECT_DOUBLE_EQ(body.mass, 4.0);
  EXPECT_NEAR(body.centre0.x(), 3.0, 1e-15);
  EXPECT_NEAR(body.inertia0(0, 0), 0.0, 1e-12);
  EXPECT_NEAR(body.inertia0(1, 1), 12.0, 1e-12);
  EXPECT_NEAR(body.inertia0(2, 2), 12.0, 1e-12);
  EXPECT_NEAR((body.offsets[1] - Eigen::Vector3d(1.0, 0.0, 0.0)).norm(), 0.0, 1e-15);
}

TEST(RigidBody, AngularAccelerationActsAboutTheFreeAxesOnly) {
  Eigen::Matrix3d J;
  J << 4.0, 1.0, 0.0, 1.0, 3.0, 0.5, 0.0, 0.5, 2.0;
  const Eigen::Vector3d m(1.0, -2.0, 3.0);
  // Free: J α = m.
  const Eigen::Vector3d free = rigid_angular_acceleration(J, m, {false, false, false});
  EXPECT_NEAR((J * free - m).norm(), 0.0, 1e-12);
  // z fixed: α_z = 0 and the x, y rows of J α = m hold.
  const Eigen::Vector3d held = rigid_angular_acceleration(J, m, {false, false, true});
  EXPECT_EQ(held.z(), 0.0);
  EXPECT_NEAR((J * held - m).head<2>().norm(), 0.0, 1e-12);
  // A body on a line (no inertia about it): no acceleration about that axis, J α = m about the
  // others.
  Eigen::Matrix3d line = Eigen::Vector3d(0.0, 5.0, 5.0).asDiagonal();
  const Eigen::Vector3d on_line = rigid_angular_acceleration(line, m, {false, false, false});
  EXPECT_EQ(on_line.x(), 0.0);
  EXPECT_NEAR(on_line.y(), -0.4, 1e-15);
  EXPECT_NEAR(on_line.z(), 0.6, 1e-15);
}

}  // namespace
}  // namespace impactfe::test_rigid_body
