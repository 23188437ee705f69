// Coordinate systems (APDL_MODELING §2): conversions, the three-angle rotation and its inverse,
// the predefined systems 5 and 6, local axes for NROTAT, and the deck commands CSYS, LOCAL,
// CLOCAL, the working plane and N/NGEN/FILL in the active system.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "core/coordinate_system.h"
#include "deck/deck_reader.h"

namespace impactfe::test_coordinate_system {
namespace {

TEST(CoordinateSystem, RotationAnglesRoundTrip) {
  for (const Vec3 a : {Vec3(30, 0, 0), Vec3(10, 20, 30), Vec3(-120, 45, 170), Vec3(0, -60, -15)}) {
    const Mat3 r = rotation_from_angles(a);
    EXPECT_TRUE((r.transpose() * r).isIdentity(1e-12));
    EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
    EXPECT_TRUE(angles_from_rotation(r).isApprox(a, 1e-10)) << a.transpose();
  }
  // THXY about Z first: x goes toward y.
  EXPECT_TRUE(
      (rotation_from_angles(Vec3(90, 0, 0)) * Vec3::UnitX()).isApprox(Vec3::UnitY(), 1e-12));
  // THYZ about the new X: y goes toward z.
  EXPECT_TRUE(
      (rotation_from_angles(Vec3(0, 90, 0)) * Vec3::UnitY()).isApprox(Vec3::UnitZ(), 1e-12));
  // THZX about the new Y: z goes toward x.
  EXPECT_TRUE(
      (rotation_from_angles(Vec3(0, 0, 90)) * Vec3::UnitZ()).isApprox(Vec3::UnitX(), 1e-12));
  // Gimbal lock: THYZ = 90 keeps a valid inverse.
  const Mat3 g = rotation_from_angles(Vec3(20, 90, 0));
  EXPECT_TRUE(rotation_from_angles(angles_from_rotation(g)).isApprox(g, 1e-10));
}

TEST(CoordinateSystem, CylindricalAndSphericalConversions) {
  CoordinateSystems cs;
  const CoordinateSystem cyl = cs.get(1), sph = cs.get(2);
  EXPECT_TRUE(cyl.to_global(Vec3(2, 90, 3)).isApprox(Vec3(0, 2, 3), 1e-12));
  EXPECT_TRUE(cyl.from_global(Vec3(-1, 0, 5)).isApprox(Vec3(1, 180, 5), 1e-12));
  EXPECT_TRUE(sph.to_global(Vec3(2, 0, 90)).isApprox(Vec3(0, 0, 2), 1e-12));
  EXPECT_TRUE(sph.from_global(Vec3(1, 1, std::sqrt(2.0))).isApprox(Vec3(2, 45, 45), 1e-12));
  // CSYS 5: axis +Y, θ = 0 along +X, local y = −Z. CSYS 6: axis +X, θ = 0 along +Y.
  EXPECT_TRUE(cs.get(5).to_global(Vec3(1, 90, 2)).isApprox(Vec3(0, 2, -1), 1e-12));
  EXPECT_TRUE(cs.get(6).to_global(Vec3(1, 90, 2)).isApprox(Vec3(2, 0, 1), 1e-12));
  // Nodal axes of a cylindrical system: radial, tangential, axial.
  Mat3 axes;
  ASSERT_TRUE(cyl.axes_at(Vec3(0, 3, 1), axes));
  EXPECT_TRUE(axes.col(0).isApprox(Vec3::UnitY(), 1e-12));
  EXPECT_TRUE(axes.col(1).isApprox(-Vec3::UnitX(), 1e-12));
  EXPECT_FALSE(cyl.axes_at(Vec3(0, 0, 4), axes));  // on the axis
  ASSERT_TRUE(sph.axes_at(Vec3(1, 0, 1), axes));
  EXPECT_NEAR(axes.determinant(), 1.0, 1e-12);
  EXPECT_TRUE(axes.col(0).isApprox(Vec3(1, 0, 1).normalized(), 1e-12));
}

Model read(const std::string& text) {
  return read_deck_text(text, "csys.inp", DeckOptions{}).model;
}

TEST(CoordinateSystem, DeckCommandsPlaceNodesInTheActiveSystem) {
  const Model m = read(
      "/PREP7\nLOCAL,11,1,10,0,0\nN,1,2,90,1\nN,2,2,0,1\nFILL,2,1,1,3\n"
      "CSYS,0\nLOCAL,12,0,0,0,0,90\nN,5,1,0,0\nNGEN,2,10,5,5,1,0,1,0\n"
      "CSYS,11\nCLOCAL,13,0,2,90,0\nN,30,1,0,0\n");
  EXPECT_TRUE(m.nodes.at(1).x.isApprox(Vec3(10, 2, 1), 1e-12));
  EXPECT_TRUE(m.nodes.at(2).x.isApprox(Vec3(12, 0, 1), 1e-12));
  // FILL interpolates in the active cylindrical system: the middle node is on the arc at 45°.
  EXPECT_TRUE(m.nodes.at(3).x.isApprox(Vec3(10 + std::sqrt(2.0), std::sqrt(2.0), 1), 1e-12));
  // LOCAL,12 rotated 90° about Z: local x = global y.
  EXPECT_TRUE(m.nodes.at(5).x.isApprox(Vec3(0, 1, 0), 1e-12));
  EXPECT_TRUE(m.nodes.at(15).x.isApprox(Vec3(-1, 1, 0), 1e-12));
  // CLOCAL at R = 2, θ = 90 of system 11: origin (10, 2, 0), x axis radial (+Y).
  EXPECT_TRUE(m.nodes.at(30).x.isApprox(Vec3(10, 3, 0), 1e-12));
  EXPECT_EQ(m.coordinate_systems.active, 13);
}

TEST(CoordinateSystem, WorkingPlanePrimitivesAndNrotat) {
  const Model m = read(
      "/PREP7\nWPOFFS,5,0,0\nWPROTA,0,90\nBLOCK,0,1,0,2,0,3\n"
      "CSYS,1\nN,1,4,30,0\nNROTAT,1\nN,2,0,0,0,0,0,90\n");
  // The WP is rotated 90° about its X: WP y = global z, WP z = global −y.
  Vec3 lo = Vec3::Constant(1e9), hi = Vec3::Constant(-1e9);
  for (const auto& [id, k] : m.solid.keypoints) {
    lo = lo.cwiseMin(k.x);
    hi = hi.cwiseMax(k.x);
  }
  EXPECT_TRUE(lo.isApprox(Vec3(5, -3, 0), 1e-12));
  EXPECT_TRUE(hi.isApprox(Vec3(6, 0, 2), 1e-12));
  // NROTAT in CSYS 1: nodal x radial at θ = 30°.
  EXPECT_NEAR(m.nodes.at(1).angles_deg(0), 30.0, 1e-10);
  EXPECT_NEAR(m.nodes.at(1).angles_deg(1), 0.0, 1e-10);
  EXPECT_TRUE(m.nodes.at(2).rotated());
  // On the axis of a cylindrical system (no radial direction): rotated as at θ = 0, nodal x
  // along the system's X axis (LOCAL,11 turned 40° about Z), as MAPDL runs vmr049-cr5-185.
  const Model axis = read("/PREP7\nLOCAL,11,1,0,0,0,40\nN,1,0,0,5\nNROTAT,1\n");
  EXPECT_NEAR(axis.nodes.at(1).angles_deg(0), 40.0, 1e-10);
  EXPECT_NEAR(axis.nodes.at(1).angles_deg(1), 0.0, 1e-10);
  EXPECT_NEAR(axis.nodes.at(1).angles_deg(2), 0.0, 1e-10);
  EXPECT_THROW(read("/PREP7\nLOCAL,11,3\n"), InputError);  // toroidal
  EXPECT_THROW(read("/PREP7\nCSYS,15\n"), InputError);     // undefined
}

}  // namespace
}  // namespace impactfe::test_coordinate_system
