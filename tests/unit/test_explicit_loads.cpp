// Loads by curve of explicit dynamics beyond the nodal forces (docs/explicit_dynamics.md, "Loads
// by curve"): EDLOAD PRESS on the faces of SOLID164 and SHELL163 (MAPDL's face numbers and
// directions), the work of a pressure in the energy balance, the forces on a rigid body's centre
// of mass, and what EDLOAD still refuses.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "deck/deck_reader.h"
#include "explicit/central_difference.h"
#include "explicit/explicit_loads.h"
#include "explicit/explicit_system.h"

namespace impactfe::test_explicit_loads {
namespace {

std::string deck(const std::string& name) {
  std::ifstream in(std::string(IMPACTFE_TEST_VERIFICATION) + "/" + name);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A deck up to its /SOLU (the model without the run).
std::string prep(const std::string& name) {
  const std::string text = deck(name);
  return text.substr(0, text.find("FINISH\n/SOLU"));
}

/// The resultant of the loads of a model at its initial configuration, at rest, at time t.
Vec3 resultant(const Model& model, double t) {
  ExplicitSystem system = build_explicit_system(model);
  ExplicitCurveLoads loads(system, model.explicit_dynamics);
  const std::size_t n = system.n_nodes();
  std::vector<double> zero(n, 0.0), fx(n, 0.0), fy(n, 0.0), fz(n, 0.0);
  const ExplicitNodalView view{system.x0.data(), system.y0.data(), system.z0.data(),
                               zero.data(),      zero.data(),      zero.data()};
  loads.add_forces(view, system.mass.data(), t, 0.0, fx.data(), fy.data(), fz.data());
  Vec3 sum = Vec3::Zero();
  for (std::size_t i = 0; i < n; ++i) sum -= Vec3(fx[i], fy[i], fz[i]);  // f_int sign
  return sum;
}

const char* kBrick =
    "/PREP7\nET,1,SOLID164\nMP,EX,1,1E6\nMP,NUXY,1,0.3\nMP,DENS,1,1000\n"
    "N,1,0,0,0\nN,2,2,0,0\nN,3,2,1,0\nN,4,0,1,0\nN,5,0,0,3\nN,6,2,0,3\nN,7,2,1,3\nN,8,0,1,3\n"
    "E,1,2,3,4,5,6,7,8\nCM,BRICK,ELEM\n*DIM,T,ARRAY,2\n*DIM,P,ARRAY,2\nT(1)=0,1\nP(1)=0,10\n";

TEST(ExplicitPressure, BrickFacesFollowMapdlNumbersAndPushInward) {
  // A 2 × 1 × 3 brick I..P: face 1 J-I-L-K (z = 0), 2 I-J-N-M (y = 0), 3 J-K-O-N (x = 2),
  // 4 K-L-P-O (y = 1), 5 L-I-M-P (x = 0), 6 M-N-O-P (z = 3); a positive pressure pushes into
  // the element: p A along the inward normal. The curve is 10 t, so p = 5 at t = 0.5.
  const Vec3 inward[6] = {{0, 0, 1}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}, {1, 0, 0}, {0, 0, -1}};
  const double area[6] = {2, 6, 3, 6, 3, 2};
  for (int key = 1; key <= 6; ++key) {
    const Model model = read_deck_text(std::string(kBrick) + "EDLOAD,ADD,PRESS," +
                                           std::to_string(key) + ",BRICK,T,P\n",
                                       "p.inp")
                            .model;
    const Vec3 f = resultant(model, 0.5);
    const Vec3 expected = 5.0 * area[key - 1] * inward[key - 1];
    EXPECT_LT((f - expected).norm(), 1e-12) << "face " << key << ": " << f.transpose();
  }
}

TEST(ExplicitPressure, ShellFacesPushAlongPlusAndMinusN) {
  // explicit_edload_pressure_plates_shell163: plate A (4 quadrilaterals, z = 0, A = 0.04) on
  // face 1, along +N = +z; plate B (2 triangles, z = 1, A = 0.04) on face 2, along −N = −z: the
  // two resultants cancel, each alone is p A = 40.
  Model model = read_deck_text(prep("explicit_edload_pressure_plates_shell163.inp"), "s.inp").model;
  EXPECT_LT(resultant(model, 0.0).norm(), 1e-12);
  auto& loads = model.explicit_dynamics.loads;
  ASSERT_EQ(loads.size(), 2u);
  const ExplicitCurveLoad b = loads[1];
  loads.pop_back();
  EXPECT_LT((resultant(model, 0.0) - Vec3(0, 0, 40)).norm(), 1e-12);
  loads[0] = b;
  EXPECT_LT((resultant(model, 0.0) - Vec3(0, 0, -40)).norm(), 1e-12);
}

TEST(ExplicitPressure, WorkIsTheEnergyPutIn) {
  // explicit_edload_pressure_bar_solid164: p = 1e8 on the end of a free bar; the work p A v t
  // with v = p/(ρc), half of it kinetic, and a balance that closes.
  Model model = read_deck_text(prep("explicit_edload_pressure_bar_solid164.inp"), "b.inp").model;
  ExplicitSystem system = build_explicit_system(model);
  ExplicitCurveLoads loads(system, model.explicit_dynamics);
  CentralDifference cd(system, model.explicit_dynamics);
  cd.add_interaction(&loads);
  cd.set_loads(std::vector<std::uint8_t>(3 * system.n_nodes(), 0), Vec3::Zero());
  cd.start();
  const double end = 8e-5;
  while (cd.time() < end) cd.cycle(std::min(cd.stable_step(), end - cd.time()));
  const double v = 1e8 / std::sqrt(200e9 * 7800.0), work = 1e8 * 1e-4 * v * end;
  const ExplicitEnergies e = cd.energies();
  EXPECT_NEAR(e.external_work, work, 0.01 * work);
  EXPECT_NEAR(e.kinetic, 0.5 * work, 0.03 * work);
  EXPECT_LT(std::abs(e.drift()), 0.005 * work);
}

/// An explicit run of a model with its loads by curve and no fixed DOFs, started.
struct CurveLoadRun {
  explicit CurveLoadRun(const Model& m)
      : system(build_explicit_system(m)),
        loads(system, m.explicit_dynamics),
        cd(system, m.explicit_dynamics) {
    cd.add_interaction(&loads);
    cd.set_loads(std::vector<std::uint8_t>(3 * system.n_nodes(), 0), Vec3::Zero());
    cd.start();
  }
  void run_to(double end) {
    while (cd.time() < end) cd.cycle(std::min(cd.stable_step(), end - cd.time()));
  }
  Vec3 displacement(int node) {
    return cd.displacement(static_cast<std::size_t>(system.index_of(node)));
  }
  ExplicitSystem system;
  ExplicitCurveLoads loads;
  CentralDifference cd;
};

TEST(ExplicitRigidLoad, ForceActsOnTheCentreOfMass) {
  // explicit_edload_rigid_force_solid164: RBFX = 1000 and RBFY = 2000 t on the rigid cube
  // (part 2): the resultant is the curves' values and the body does not turn.
  const Model model =
      read_deck_text(prep("explicit_edload_rigid_force_solid164.inp"), "r.inp").model;
  EXPECT_LT((resultant(model, 0.25) - Vec3(1000, 500, 0)).norm(), 1e-9);
  // A moment (RBMZ) is nodal forces with no resultant and the moment M about the centre.
  const Model turned =
      read_deck_text(prep("explicit_edload_rigid_moment_solid164.inp"), "m.inp").model;
  EXPECT_LT(resultant(turned, 0.5).norm(), 1e-9);
  ExplicitSystem system = build_explicit_system(turned);
  ExplicitCurveLoads loads(system, turned.explicit_dynamics);
  const std::size_t n = system.n_nodes();
  std::vector<double> zero(n, 0.0), fx(n, 0.0), fy(n, 0.0), fz(n, 0.0);
  const ExplicitNodalView view{system.x0.data(), system.y0.data(), system.z0.data(),
                               zero.data(),      zero.data(),      zero.data()};
  loads.add_forces(view, system.mass.data(), 0.5, 0.0, fx.data(), fy.data(), fz.data());
  Vec3 moment = Vec3::Zero();
  for (std::size_t i = 0; i < n; ++i)
    moment -= (Vec3(system.x0[i], system.y0[i], system.z0[i]) - Vec3(2.5, 0.5, 0.5))
                  .cross(Vec3(fx[i], fy[i], fz[i]));
  EXPECT_LT((moment - Vec3(0, 0, 1000.0 / 6.0)).norm(), 1e-9);
}

TEST(ExplicitRigidLoad, PrescribedMotionDrivesTheBodyAndBooksItsWork) {
  // The rigid cube of explicit_edload_rigid_force_solid164 (M = 1000) driven instead: RBVX = 2
  // (the curve 1000 scaled by 0.002) and RBUY = 0.2 t (the ramp 2000 t scaled by 1e-4). The
  // body is where the curves put it at every node, and the work of the prescribed motion is its
  // kinetic energy ½ M (2² + 0.2²) = 2020.
  std::string text = prep("explicit_edload_rigid_force_solid164.inp");
  const auto swap = [&](const std::string& from, const std::string& to) {
    text.replace(text.find(from), from.size(), to);
  };
  swap("EDLOAD,ADD,RBFX,,2,T,PX", "EDLOAD,ADD,RBVX,,2,T,PX,0,,0.002");
  swap("EDLOAD,ADD,RBFY,,2,T,PY", "EDLOAD,ADD,RBUY,,2,T,PY,0,,1E-4");
  Model model = read_deck_text(text, "m.inp").model;
  CurveLoadRun run(model);
  run.run_to(1.0);
  for (int node : {101, 107}) {
    const Vec3 u = run.displacement(node);
    EXPECT_LT((u - Vec3(2.0, 0.2, 0.0)).norm(), 1e-12) << node << ": " << u.transpose();
  }
  const ExplicitEnergies e = run.cd.energies();
  EXPECT_NEAR(e.external_work, 2020.0, 1e-6 * 2020.0);
  EXPECT_NEAR(e.kinetic, 2020.0, 1e-6 * 2020.0);
  // A translation the body's EDMP constraint fixes cannot be prescribed.
  swap("EDMP,RIGID,2", "EDMP,RIGID,2,2");
  Model fixed = read_deck_text(text, "f.inp").model;
  ExplicitSystem s2 = build_explicit_system(fixed);
  EXPECT_THROW(ExplicitCurveLoads(s2, fixed.explicit_dynamics), InputError);
}

TEST(ExplicitRigidLoad, MergedBodiesMoveAsOneBody) {
  // explicit_edcrb_merged_bodies_solid164: the unit cubes of materials 2 (x 2 .. 3) and 3
  // (x 4 .. 5), 1000 each, merged by EDCRB: one body of mass 2000 centred at x = 3.5 with
  // J_zz = 2 (1000 (1 + 1)/12 + 1000 · 1²) = 2333.33 (parallel axes), the master's codes.
  std::string text = prep("explicit_edcrb_merged_bodies_solid164.inp");
  const auto swap = [&](const std::string& from, const std::string& to) {
    text.replace(text.find(from), from.size(), to);
  };
  const Model model = read_deck_text(text, "m.inp").model;
  const ExplicitSystem system = build_explicit_system(model);
  ASSERT_EQ(system.rigid_bodies.size(), 1u);
  const RigidBody& body = system.rigid_bodies[0];
  EXPECT_EQ(body.material, 2);
  EXPECT_EQ(body.materials, (std::vector<int>{2, 3}));
  EXPECT_EQ(body.nodes.size(), 16u);
  EXPECT_NEAR(body.mass, 2000.0, 1e-9);
  EXPECT_LT((body.centre0 - Eigen::Vector3d(3.5, 0.5, 0.5)).norm(), 1e-12);
  EXPECT_NEAR(body.inertia0(2, 2), 2.0 * (2000.0 / 12.0 + 1000.0), 1e-9);
  EXPECT_NEAR(body.inertia0(0, 0), 2.0 * 2000.0 / 12.0, 1e-9);
  EXPECT_FALSE(body.fixed_translation[1]);
  // A moment RBMZ = 2333.33 on the master turns both cubes at α = M/J_zz = 1 about the common
  // centre: after t = 0.1 the angle is αt²/2 = 0.005, the slave's far corner (207, at
  // r = (1.5, 0.5) from the centre) has moved by (R − 1) r.
  swap("PY(1) = 1000,1000", "PY(1) = 2333.333333333333,2333.333333333333");
  swap("EDLOAD,ADD,RBFY,,2,T,PY", "EDLOAD,ADD,RBMZ,,2,T,PY");
  Model turned = read_deck_text(text, "t.inp").model;
  CurveLoadRun run(turned);
  run.run_to(0.1);
  const double angle = 0.005;
  const Vec3 r(1.5, 0.5, 0.0);
  const Vec3 moved(std::cos(angle) * r.x() - std::sin(angle) * r.y() - r.x(),
                   std::sin(angle) * r.x() + std::cos(angle) * r.y() - r.y(), 0.0);
  const Vec3 u = run.displacement(207);
  EXPECT_LT((u - moved).norm(), 1e-3 * moved.norm()) << u.transpose();
}

TEST(ExplicitLoads, EdloadRefusesWhatItDoesNotCarryOut) {
  const std::string brick = kBrick;
  const auto refused = [&](const std::string& line) {
    EXPECT_ANY_THROW(read_deck_text(brick + line + "\n", "r.inp")) << line;
  };
  refused("EDLOAD,ADD,PRESS,7,BRICK,T,P");                     // SOLID164 has faces 1..6
  refused("CM,CORNER,NODE\nEDLOAD,ADD,PRESS,1,CORNER,T,P");    // a node component
  refused("EDLOAD,ADD,RBFX,,1,T,P");                           // part 1 is not rigid
  refused("EDLOAD,ADD,RBFX,,BRICK,T,P");                       // not a part number
  refused("EDMP,RIGID,1\nEDLOAD,ADD,RBOX,,1,T,P");             // rigid-body angular velocity
  refused("NSEL,ALL\nCM,ALLN,NODE\nEDLOAD,ADD,AX,,ALLN,T,P");  // nodal accelerations
  // A rotation prescribed at nodes without rotational DOFs (a brick's) is refused by the run.
  const Model rotated =
      read_deck_text(brick + "NSEL,ALL\nCM,ALLN,NODE\nEDLOAD,ADD,ROTX,,ALLN,T,P\n", "o.inp").model;
  const ExplicitSystem system = build_explicit_system(rotated);
  EXPECT_THROW(ExplicitCurveLoads(system, rotated.explicit_dynamics), InputError);
  EXPECT_NO_THROW(read_deck_text(brick + "EDMP,RIGID,1\nEDLOAD,ADD,RBFX,,1,T,P\n", "a.inp"));
  const std::string shell =
      "/PREP7\nET,1,SHELL163\nR,1,1,2,0.01\nMP,EX,1,1E6\nMP,NUXY,1,0.3\nMP,DENS,1,1000\n"
      "N,1\nN,2,1\nN,3,1,1\nN,4,0,1\nE,1,2,3,4\nCM,SHELL,ELEM\n*DIM,T,ARRAY,2\n*DIM,P,ARRAY,2\n"
      "T(1)=0,1\nP(1)=0,10\n";
  EXPECT_ANY_THROW(read_deck_text(shell + "EDLOAD,ADD,PRESS,3,SHELL,T,P\n", "e.inp"));
  EXPECT_NO_THROW(read_deck_text(shell + "EDLOAD,ADD,PRESS,2,SHELL,T,P\n", "f.inp"));
}

}  // namespace
}  // namespace impactfe::test_explicit_loads
