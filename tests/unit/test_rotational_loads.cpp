// Unit tests of the rotational inertia loads (OMEGA, DOMEGA, CGLOC, CGOMGA, DCGOMG): the
// acceleration field of core/rotating_frame.h (MAPDL Theory Reference, "Acceleration Effect")
// and the element load −M ā of Element::acceleration_field_load.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <vector>

#include "../support/run_deck.h"
#include "core/errors.h"
#include "core/rotating_frame.h"
#include "elements/brick8.h"
#include "elements/plane_solid.h"
#include "elements/point_mass.h"
#include "materials/isotropic_elasticity.h"

namespace impactfe::test_rotational_loads {
namespace {

constexpr double kRho = 7.85e-9;

std::function<Vec3(int)> positions(const std::map<int, Vec3>& x) {
  return [x](int node) { return x.at(node); };
}

Eigen::VectorXd load(const Element& e, const LinearAccelerationField& field,
                     const std::map<int, Vec3>& x, bool lumped = false) {
  ElementContext ctx;
  ctx.lumped_mass = lumped;
  Eigen::MatrixXd f;
  e.acceleration_field_load(ctx, {field}, positions(x), f);
  return f.col(0);
}

// vm131 (Beer & Johnston 15.13): the boom turns with ω = 0.5 about Z relative to the cab,
// which turns with Ω = 0.3 about Y; the point (34.64, 20, 0) accelerates by (−11.78, −5, 6).
TEST(RotationalLoads, CombinedFrameAndStructureRotation) {
  RotationalLoads loads;
  loads.omega = Vec3(0, 0, 0.5);
  loads.cg_omega = Vec3(0, 0.3, 0);
  const LinearAccelerationField field = rotational_acceleration(loads);
  const Vec3 a = field.at(Vec3(34.64, 20, 0));
  EXPECT_NEAR(a.x(), -0.3 * 0.3 * 34.64 - 0.5 * 0.5 * 34.64, 1e-12);  // −11.78
  EXPECT_NEAR(a.y(), -5.0, 1e-12);
  EXPECT_NEAR(a.z(), 6.0, 1e-12);  // the Coriolis term 2 Ω × (ω × r)
  // The material turns with Ω + ω, whose direction turns with Ω: α = Ω × ω.
  EXPECT_NEAR((field.angular - Vec3(0.15, 0, 0)).norm(), 0.0, 1e-15);
}

// CGLOC moves the centre of the frame's rotation: a point at the centre does not accelerate,
// and DCGOMG adds the tangential Ω̇ × (x − c).
TEST(RotationalLoads, FrameRotationAboutCgloc) {
  RotationalLoads loads;
  loads.cg_location = Vec3(1, 2, 3);
  loads.cg_omega = Vec3(0.2, -0.4, 0.7);
  loads.cg_domega = Vec3(0.3, 0.1, -0.2);
  const LinearAccelerationField field = rotational_acceleration(loads);
  EXPECT_LT(field.at(loads.cg_location).norm(), 1e-15);
  const Vec3 x(4, -1, 2), r = x - loads.cg_location;
  const Vec3 expected = loads.cg_domega.cross(r) + loads.cg_omega.cross(loads.cg_omega.cross(r));
  EXPECT_LT((field.at(x) - expected).norm(), 1e-14);
}

// MASS21 at r from the Z axis, OMEGA about Z: the load is the centrifugal force m ω² r
// outward, exactly; DOMEGA adds −m ω̇ × r.
TEST(RotationalLoads, PointMassCentrifugalForce) {
  const double m = 2.5, w = 31.4, dw = 7.0;
  std::vector<DofKey> dofs{{7, Dof::UX}, {7, Dof::UY}, {7, Dof::UZ}};
  const PointMass mass(1, dofs, Eigen::Vector3d::Constant(m));
  const Vec3 x(3.0, -4.0, 1.5);
  RotationalLoads loads;
  loads.omega = Vec3(0, 0, w);
  Eigen::VectorXd f = load(mass, rotational_acceleration(loads), {{7, x}});
  EXPECT_DOUBLE_EQ(f(0), m * w * w * x.x());
  EXPECT_DOUBLE_EQ(f(1), m * w * w * x.y());
  EXPECT_EQ(f(2), 0.0);
  loads.omega.setZero();
  loads.domega = Vec3(0, 0, dw);
  f = load(mass, rotational_acceleration(loads), {{7, x}});
  EXPECT_DOUBLE_EQ(f(0), m * dw * x.y());   // −m (ω̇ × r)_x = m ω̇ y
  EXPECT_DOUBLE_EQ(f(1), -m * dw * x.x());  // −m (ω̇ × r)_y = −m ω̇ x
}

// A distorted brick under every load at once: the consistent loads sum to −m a(x_c), x_c the
// centre of mass (a is linear in x); the lumped ones are each node's −m_i a(x_i); with the field
// of a rigid translation alone they equal the frame-acceleration load of ACEL.
TEST(RotationalLoads, BrickLoadSumsToMassTimesCentreAcceleration) {
  const std::array<int, 8> ids{1, 2, 3, 4, 5, 6, 7, 8};
  const std::array<Vec3, 8> x{Vec3(10, 1, 0),       Vec3(12.2, 1.1, 0.1), Vec3(12.5, 3, -0.2),
                              Vec3(9.8, 2.7, 0),    Vec3(10.1, 0.9, 1.4), Vec3(12.1, 1.2, 1.6),
                              Vec3(12.7, 3.3, 1.5), Vec3(10, 2.9, 1.2)};
  const Brick8 brick(1, ids, x, IsotropicElasticity{200e3, 0.3, kRho}, false);
  std::map<int, Vec3> at;
  for (int i = 0; i < 8; ++i) at[ids[static_cast<std::size_t>(i)]] = x[static_cast<std::size_t>(i)];
  RotationalLoads loads;
  loads.omega = Vec3(30, -10, 100);
  loads.domega = Vec3(5, 7, -3);
  loads.cg_location = Vec3(-4, 6, 1);
  loads.cg_omega = Vec3(2, 40, -8);
  loads.cg_domega = Vec3(-1, 2, 9);
  const LinearAccelerationField field = rotational_acceleration(loads);
  // Mass and centre of mass from the element's own mass matrix and its rigid translations.
  ElementContext ctx;
  Eigen::MatrixXd m;
  brick.mass(ctx, m);
  Eigen::VectorXd ex = Eigen::VectorXd::Zero(24), xs = Eigen::VectorXd::Zero(24);
  for (int i = 0; i < 8; ++i) ex(3 * i) = 1.0;
  const double total = ex.dot(m * ex);
  Vec3 centre;
  for (int d = 0; d < 3; ++d) {
    for (int i = 0; i < 8; ++i) xs(3 * i) = x[static_cast<std::size_t>(i)](d);
    centre(d) = ex.dot(m * xs) / total;
  }
  Vec3 sum = Vec3::Zero();
  const Eigen::VectorXd f = load(brick, field, at);
  for (int i = 0; i < 8; ++i) sum += f.segment<3>(3 * i);
  const Vec3 expected = -total * field.at(centre);
  EXPECT_LT((sum - expected).norm(), 1e-11 * expected.norm());
  // Lumped (LUMPM): each node's mass times the field at the node, exactly.
  ElementContext lumped;
  lumped.lumped_mass = true;
  Eigen::MatrixXd ml;
  brick.mass(lumped, ml);
  const Eigen::VectorXd fl = load(brick, field, at, true);
  for (int i = 0; i < 8; ++i) {
    const Vec3 node = -ml(3 * i, 3 * i) * field.at(x[static_cast<std::size_t>(i)]);
    EXPECT_LT((fl.segment<3>(3 * i) - node).norm(), 1e-12 * node.norm() + 1e-300);
  }
  LinearAccelerationField uniform;
  uniform.at_origin = Vec3(1.0, -2.0, 9.81);
  Eigen::MatrixXd g;
  brick.frame_acceleration_load(ctx, uniform.at_origin, g);
  EXPECT_LT((load(brick, uniform, at) - g.col(0)).norm(), 1e-15 * g.norm());
}

// An axisymmetric PLANE183 ring sector turning about Y: the radial loads sum to
// ∫ρ ω² r 2πr dA, the centrifugal force of the whole ring (its total is radial, around the
// circumference), and the axial ones vanish.
TEST(RotationalLoads, AxisymmetricRingCentrifugalForce) {
  const double a = 4.0, b = 8.0, h = 0.5, w = 1000.0;
  const std::vector<int> ids{1, 2, 3, 4, 5, 6, 7, 8};
  const std::vector<Vec3> x{Vec3(a, 0, 0),
                            Vec3(b, 0, 0),
                            Vec3(b, h, 0),
                            Vec3(a, h, 0),
                            Vec3(0.5 * (a + b), 0, 0),
                            Vec3(b, 0.5 * h, 0),
                            Vec3(0.5 * (a + b), h, 0),
                            Vec3(a, 0.5 * h, 0)};
  PlaneSolidOptions o{PlaneShape::Quad8, PlaneBehaviour::Axisymmetric, PlaneTechnology::Standard,
                      1.0};
  const PlaneSolid ring(1, ids, x, IsotropicElasticity{30e6, 0.3, 7.3e-4}, o, {});
  std::map<int, Vec3> at;
  for (std::size_t i = 0; i < ids.size(); ++i) at[ids[i]] = x[i];
  RotationalLoads loads;
  loads.omega = Vec3(0, w, 0);
  const Eigen::VectorXd f = load(ring, rotational_acceleration(loads), at);
  double radial = 0.0, axial = 0.0;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    radial += f(static_cast<Eigen::Index>(2 * i));
    axial += f(static_cast<Eigen::Index>(2 * i + 1));
  }
  const double exact = 7.3e-4 * w * w * 2.0 * M_PI * h * (b * b * b - a * a * a) / 3.0;
  EXPECT_NEAR(radial, exact, 1e-12 * exact);
  EXPECT_NEAR(axial, 0.0, 1e-12 * exact);
  // About X the load is not axisymmetric; DOMEGA about Y would push around the circumference,
  // which the element has no DOF for: both refused.
  loads.omega = Vec3(w, 0, 0);
  EXPECT_THROW(load(ring, rotational_acceleration(loads), at), ModelError);
  loads.omega = Vec3(0, w, 0);
  loads.domega = Vec3(0, 10.0, 0);
  EXPECT_THROW(load(ring, rotational_acceleration(loads), at), ModelError);
}

// What is not carried out stops the deck at a located line: OMEGA in a modal analysis (at its
// SOLVE, naming the OMEGA), spin softening (KSPIN), a plane element accelerated along Z.
TEST(RotationalLoads, RefusedWhereNotCarriedOut) {
  const std::string model =
      "/PREP7\nET,1,PLANE182\nMP,EX,1,200E3\nMP,DENS,1,7.85E-9\nN,1,1\nN,2,2\nN,3,2,1\n"
      "N,4,1,1\nE,1,2,3,4\nD,1,ALL\nD,2,ALL\nFINISH\n/SOLU\n";
  std::string why = testing::run_deck_error(
      "omega_modal", model + "ANTYPE,MODAL\nMODOPT,LANB,2\nOMEGA,0,0,100\nSOLVE\n");
  EXPECT_NE(why.find("static and full transient analyses only"), std::string::npos) << why;
  EXPECT_NE(why.find("omega_modal.inp:16"), std::string::npos) << why;
  why = testing::run_deck_error("omega_kspin", model + "OMEGA,0,0,100,1\n");
  EXPECT_NE(why.find("KSPIN"), std::string::npos) << why;
  why = testing::run_deck_error("omega_plane_z", model + "ANTYPE,STATIC\nDOMEGA,100\nSOLVE\n");
  EXPECT_NE(why.find("no DOF"), std::string::npos) << why;
  EXPECT_NE(why.find("omega_plane_z.inp:15"), std::string::npos) << why;
  // The in-plane case runs: OMEGA about Z on the plane element.
  EXPECT_EQ(
      testing::run_deck_error("omega_plane_ok", model + "ANTYPE,STATIC\nOMEGA,,,100\nSOLVE\n"), "");
}

}  // namespace
}  // namespace impactfe::test_rotational_loads
