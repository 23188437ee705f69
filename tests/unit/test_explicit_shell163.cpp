// SHELL163 (docs/explicit_dynamics.md): rigid-body motion free of strain and force, the membrane
// patch test (a uniform in-plane strain rate gives the exact plane stress on a distorted mesh,
// interior nodes in equilibrium), the hourglass modes resisted, the plane-stress plastic return
// (σ_zz = 0, on the yield surface), the refusals of the real constants and KEYOPTs, and a
// central-difference run with rotations.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include <cmath>

#include "deck/deck_reader.h"
#include "explicit/central_difference.h"
#include "explicit/explicit_system.h"

namespace impactfe::test_explicit_shell163 {
namespace {

const std::string kHead =
    "/PREP7\nET,1,SHELL163\nR,1,0.8333333,3,0.02\nMP,EX,1,2E5\nMP,NUXY,1,0.3\n"
    "MP,DENS,1,7.8E-3\n";

/// A 2x2 mesh of the unit square, its centre node moved (distorted quads), turned into a
/// general orientation in space by `turn`.
Model plate(const Eigen::Matrix3d& turn, const std::string& extra = "") {
  std::string deck = kHead;
  int id = 0;
  for (int j = 0; j <= 2; ++j)
    for (int i = 0; i <= 2; ++i) {
      Vec3 p(0.5 * i, 0.5 * j, 0.0);
      if (i == 1 && j == 1) p += Vec3(0.08, -0.06, 0.0);
      p = turn * p;
      deck += fmt::format("N,{},{:.17g},{:.17g},{:.17g}\n", ++id, p.x(), p.y(), p.z());
    }
  const auto n = [](int i, int j) { return 1 + i + 3 * j; };
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i)
      deck += fmt::format("E,{},{},{},{}\n", n(i, j), n(i + 1, j), n(i + 1, j + 1), n(i, j + 1));
  return read_deck_text(deck + extra, "plate.inp").model;
}

Eigen::Matrix3d general_turn() {
  return (Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()) *
          Eigen::AngleAxisd(-0.4, Vec3(0.3, -1, 0.5).normalized()))
      .toRotationMatrix();
}

struct Shells {
  ExplicitSystem system;
  std::vector<double> x, y, z, vx, vy, vz, wx, wy, wz, forces, moments;
  explicit Shells(const Model& m) : system(build_explicit_system(m)) {
    x = system.x0, y = system.y0, z = system.z0;
    vx.assign(system.n_nodes(), 0.0), vy = vx, vz = vx, wx = vx, wy = vx, wz = vx;
    forces.assign(3 * system.n_slots, 0.0);
    moments = forces;
  }
  ExplicitNodalView view() const {
    return {x.data(),  y.data(),  z.data(),  vx.data(), vy.data(),
            vz.data(), wx.data(), wy.data(), wz.data()};
  }
  ExplicitElementSet& set() { return *system.sets.front(); }
  void evaluate(double dt) {
    set().internal_forces_and_moments(view(), dt, forces.data(), moments.data());
  }
  Vec3 nodal(const std::vector<double>& f, std::size_t n) const {
    Vec3 s = Vec3::Zero();
    for (std::size_t j = system.slot_start[n]; j < system.slot_start[n + 1]; ++j)
      s += Vec3(f[3 * system.slots[j]], f[3 * system.slots[j] + 1], f[3 * system.slots[j] + 2]);
    return s;
  }
};

TEST(ExplicitShell, RigidBodyMotionMakesNoStrain) {
  for (const bool triangle : {false, true}) {
    const Eigen::Matrix3d turn = general_turn();
    Model m = plate(turn);
    if (triangle) m.elements.begin()->second.nodes[3] = m.elements.begin()->second.nodes[2];
    Shells run(m);
    ASSERT_TRUE(run.system.has_rotations());
    const Vec3 v0(0.3, -0.2, 0.5), omega(0.4, -0.7, 0.25);
    for (std::size_t n = 0; n < run.system.n_nodes(); ++n) {
      const Vec3 v = v0 + omega.cross(Vec3(run.x[n], run.y[n], run.z[n]));
      run.vx[n] = v.x(), run.vy[n] = v.y(), run.vz[n] = v.z();
      run.wx[n] = omega.x(), run.wy[n] = omega.y(), run.wz[n] = omega.z();
    }
    run.evaluate(1e-3);
    for (double f : run.forces) EXPECT_NEAR(f, 0.0, 1e-12) << "triangle " << triangle;
    for (double f : run.moments) EXPECT_NEAR(f, 0.0, 1e-12) << "triangle " << triangle;
    Eigen::MatrixXd r;
    run.set().results(r);
    EXPECT_LT(r.cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_NEAR(run.set().energies().internal, 0.0, 1e-15);
    EXPECT_NEAR(run.set().energies().hourglass, 0.0, 1e-15);
  }
}

TEST(ExplicitShell, UniformMembraneStrainRateIsExactOnADistortedMesh) {
  const Eigen::Matrix3d turn = general_turn();
  Shells run(plate(turn));
  // In the plate's own axes v = G x with G symmetric: a uniform in-plane strain rate, no spin.
  Eigen::Matrix3d g = Eigen::Matrix3d::Zero();
  g(0, 0) = 1e-3, g(1, 1) = -4e-4, g(0, 1) = g(1, 0) = 3e-4;
  for (std::size_t n = 0; n < run.system.n_nodes(); ++n) {
    const Vec3 local = turn.transpose() * Vec3(run.x[n], run.y[n], run.z[n]);
    const Vec3 v = turn * (g * local);
    run.vx[n] = v.x(), run.vy[n] = v.y(), run.vz[n] = v.z();
  }
  run.evaluate(1.0);
  Eigen::MatrixXd r;
  run.set().results(r);
  const double e = 2e5, nu = 0.3, c = e / (1 - nu * nu), t = 0.02;
  // The elements' local x axis is along their side IJ; σ in that frame: rotate D into it.
  const int node_i = run.system.sets.front()->nodes(0)[0],
            node_j = run.system.sets.front()->nodes(0)[1];
  const Vec3 side =
      turn.transpose() * Vec3(run.x[node_j] - run.x[node_i], run.y[node_j] - run.y[node_i],
                              run.z[node_j] - run.z[node_i]);
  const double angle = std::atan2(side.y(), side.x());
  Eigen::Matrix2d q;
  q << std::cos(angle), std::sin(angle), -std::sin(angle), std::cos(angle);
  const Eigen::Matrix2d d = q * g.topLeftCorner<2, 2>() * q.transpose();
  const double sx = c * (d(0, 0) + nu * d(1, 1)), sy = c * (d(1, 1) + nu * d(0, 0)),
               sxy = e / (1 + nu) * d(0, 1);
  EXPECT_NEAR(r(0, 0), sx, 1e-9);
  EXPECT_NEAR(r(0, 1), sy, 1e-9);
  EXPECT_NEAR(r(0, 2), sxy, 1e-9);
  for (Eigen::Index k = 0; k < r.rows(); ++k) {
    // The same membrane stress at every point: NX = σ t, no bending, no hourglass work.
    EXPECT_NEAR(r(k, 0), r(k, 3), 1e-9);
    EXPECT_NEAR(r(k, 8) * r(k, 8) + r(k, 9) * r(k, 9) + 2 * r(k, 10) * r(k, 10),
                t * t * (sx * sx + sy * sy + 2 * sxy * sxy), 1e-12);
    EXPECT_NEAR(r(k, 11), 0.0, 1e-12);
  }
  EXPECT_NEAR(run.set().energies().hourglass, 0.0, 1e-15);
  // The centre node (id 5) is interior: the element forces on it balance.
  const int centre = run.system.index_of(5);
  EXPECT_LT(run.nodal(run.forces, static_cast<std::size_t>(centre)).norm(), 1e-12);
  EXPECT_LT(run.nodal(run.moments, static_cast<std::size_t>(centre)).norm(), 1e-12);
}

TEST(ExplicitShell, HourglassModesAreResisted) {
  // One square element: each of the five BT hourglass fields (h = +1 −1 +1 −1 in v_x, v_y,
  // v_z, ω_x, ω_y) makes no strain rate at the centre and is resisted by a dissipative force.
  const std::string deck = kHead + "N,1,0,0,0\nN,2,1,0,0\nN,3,1,1,0\nN,4,0,1,0\nE,1,2,3,4\n";
  const double h[4] = {1, -1, 1, -1};
  for (int mode = 0; mode < 5; ++mode) {
    Shells run(read_deck_text(deck, "one.inp").model);
    std::vector<double>* field[5] = {&run.vx, &run.vy, &run.vz, &run.wx, &run.wy};
    for (int a = 0; a < 4; ++a) (*field[mode])[static_cast<std::size_t>(a)] = h[a];
    run.evaluate(1e-6);
    Eigen::MatrixXd r;
    run.set().results(r);
    EXPECT_LT(r.cwiseAbs().maxCoeff(), 1e-12) << "mode " << mode;
    EXPECT_GT(run.set().energies().hourglass, 0.0) << "mode " << mode;
    // The resisting force (moment) opposes the mode: its power on the field is positive.
    const std::vector<double>& out = mode < 3 ? run.forces : run.moments;
    double power = 0.0;
    for (int a = 0; a < 4; ++a) power += out[static_cast<std::size_t>(3 * a + mode % 3)] * h[a];
    EXPECT_GT(power, 0.0) << "mode " << mode;
  }
}

TEST(ExplicitShell, TwistIsNotAnHourglassMode) {
  // One square element twisting: v_z = xy with the rotations of a Kirchhoff twist (ω_x = ∂v_z/∂y
  // = x, ω_y = −∂v_z/∂x = −y), so v_z is γ's pattern but no transverse shear varies across the
  // element: no hourglass work (the transverse hourglass rate γ·v_z alone damped it). The same
  // v_z with ω = 0 is the hourglass mode and is resisted.
  const std::string deck = kHead + "N,1,-1,-1,0\nN,2,1,-1,0\nN,3,1,1,0\nN,4,-1,1,0\nE,1,2,3,4\n";
  for (const bool twist : {true, false}) {
    Shells run(read_deck_text(deck, "one.inp").model);
    for (std::size_t a = 0; a < 4; ++a) {
      run.vz[a] = run.x[a] * run.y[a];
      if (twist) run.wx[a] = run.x[a], run.wy[a] = -run.y[a];
    }
    run.evaluate(1e-6);
    if (twist) {
      EXPECT_NEAR(run.set().energies().hourglass, 0.0, 1e-15);
    } else {
      EXPECT_GT(run.set().energies().hourglass, 1e-12);
    }
  }
}

TEST(ExplicitShell, StiffnessHourglassHoldsItsEnergyAndGivesItBack) {
  // One unit square (EDMP,HGLS type 4) driven along each hourglass field for 50 cycles and back:
  // the stiffness form stores ½kq² (membrane: k = QM E t A/8 B·B = QM E t / 4, q = 4 u) and
  // returns it; the viscous form dissipates the same motion.
  const std::string deck = kHead + "N,1,0,0,0\nN,2,1,0,0\nN,3,1,1,0\nN,4,0,1,0\nE,1,2,3,4\n";
  const double h[4] = {1, -1, 1, -1}, dt = 1e-4, speed = 1e-3;
  const int steps = 50;
  for (const int type : {4, 1})
    for (int mode = 0; mode < 5; ++mode) {
      Shells run(read_deck_text(deck + fmt::format("EDMP,HGLS,1,{},0.1\n", type), "one.inp").model);
      std::vector<double>* field[5] = {&run.vx, &run.vy, &run.vz, &run.wx, &run.wy};
      const auto drive = [&](double sign) {
        for (std::size_t a = 0; a < 4; ++a) (*field[mode])[a] = sign * speed * h[a];
        for (int i = 0; i < steps; ++i) {
          for (std::size_t n = 0; n < 4; ++n)
            run.x[n] += dt * run.vx[n], run.y[n] += dt * run.vy[n], run.z[n] += dt * run.vz[n];
          run.evaluate(dt);
        }
      };
      drive(1.0);
      const double out = run.set().energies().hourglass;
      EXPECT_GT(out, 0.0) << "type " << type << " mode " << mode;
      if (type == 4 && mode == 0) {
        const double q = 4 * speed * steps * dt, k = 0.1 * 2e5 * 0.02 / 4;
        EXPECT_NEAR(out, 0.5 * k * q * q, 1e-6 * k * q * q);
      }
      drive(-1.0);
      if (type == 4)
        EXPECT_NEAR(run.set().energies().hourglass, 0.0, 1e-6 * out) << "mode " << mode;
      else
        EXPECT_NEAR(run.set().energies().hourglass, 2.0 * out, 1e-6 * out) << "mode " << mode;
    }
}

TEST(ExplicitShell, PlaneStressReturnStaysOnTheYieldSurface) {
  // Equal biaxial stretching of a plate far beyond yield (BISO, yield 250, tangent 1000): the
  // plane-stress return keeps σ_zz = 0 and σ_x = σ_y = the flow stress of the plastic strain.
  Shells run(plate(Eigen::Matrix3d::Identity(), "TB,BISO,1\nTBDATA,1,250,1000\n"));
  for (std::size_t n = 0; n < run.system.n_nodes(); ++n) {
    run.vx[n] = 1e-3 * run.x[n];
    run.vy[n] = 1e-3 * run.y[n];
  }
  for (int step = 0; step < 20; ++step) run.evaluate(0.5);
  Eigen::MatrixXd r;
  run.set().results(r);
  const double sigma = r(0, 0), epeq = r(0, 15);
  EXPECT_NEAR(r(0, 1), sigma, 1e-8 * sigma);
  // Equal biaxial plane stress: σ_eqv = σ; on the bilinear curve k = 250 + H α with
  // H = E Et / (E − Et).
  const double hardening = 2e5 * 1000 / (2e5 - 1000);
  EXPECT_GT(epeq, 0.0);
  EXPECT_NEAR(sigma, 250 + hardening * epeq, 1e-6 * sigma);
  EXPECT_NEAR(r(0, 14), sigma, 1e-6 * sigma);
  EXPECT_GT(run.set().energies().plastic_work, 0.0);
}

TEST(ExplicitShell, BendingReachesTheSectionLimit) {
  // One square element bent by a curvature rate κ̇_xx (ω_y = κ̇ x at the nodes, the centre at
  // x = 0: no membrane, transverse shear or hourglass rate), κ_yy = 0, elastic–perfectly
  // plastic (yield 250). Far beyond yield every point flows with ε̇_yy = 0, so s_yy = 0,
  // σ_yy = σ_xx/2 and σ_xx = ±2σ_y/√3 (Hill's plane-strain bending): the moment per unit
  // width is that stress block integrated by the 3-point Gauss rule of the thickness,
  // M = (2σ_y/√3)(t²/4) Σ w|ζ| = (2σ_y/√3)(t²/4)(10/9)√0.6 (0.861 of the exact block's t²/4).
  const std::string deck =
      "/PREP7\nET,1,SHELL163\nR,1,0.8333333,3,0.02\nMP,EX,1,2E5\nMP,NUXY,1,0.3\n"
      "MP,DENS,1,7.8E-3\nTB,BISO,1\nTBDATA,1,250,0\n"
      "N,1,-0.5,-0.5,0\nN,2,0.5,-0.5,0\nN,3,0.5,0.5,0\nN,4,-0.5,0.5,0\nE,1,2,3,4\n";
  Shells run(read_deck_text(deck, "bend.inp").model);
  const double rate = 0.08;  // curvature per step: 200 steps reach 16, 130 times first yield
  for (std::size_t n = 0; n < run.system.n_nodes(); ++n) run.wy[n] = rate * run.x[n];
  for (int step = 0; step < 200; ++step) run.evaluate(1.0);
  Eigen::MatrixXd r;
  run.set().results(r);
  const double t = 0.02, sigma = 2 * 250 / std::sqrt(3.0);
  EXPECT_NEAR(r(0, 11), sigma * t * t / 4 * (10.0 / 9.0) * std::sqrt(0.6), 1e-3 * sigma * t * t);
  EXPECT_NEAR(r(0, 0), sigma, 1e-3 * sigma);        // top point in tension
  EXPECT_NEAR(r(0, 1), 0.5 * sigma, 1e-3 * sigma);  // σ_yy = σ_xx/2
  EXPECT_NEAR(r(0, 3), -sigma, 1e-3 * sigma);
  EXPECT_NEAR(r(0, 8), 0.0, 1e-9);  // no membrane force
  // Nearly all the work goes into plastic work (the elastic part is bounded).
  const ExplicitSetEnergies e = run.set().energies();
  EXPECT_GT(e.plastic_work, 0.9 * e.internal);
  EXPECT_LE(e.plastic_work, e.internal);
}

TEST(ExplicitShell, RefusesWhatItDoesNotCarryOut) {
  const std::string mesh = "N,1,0,0,0\nN,2,1,0,0\nN,3,1,1,0\nN,4,0,1,0\nE,1,2,3,4\n";
  const auto build = [&](const std::string& head) {
    return build_explicit_system(read_deck_text(head + mesh, "s.inp").model);
  };
  EXPECT_NO_THROW(build(kHead));
  EXPECT_NO_THROW(build(kHead + "KEYOPT,1,1,2\n"));
  EXPECT_THROW(build(kHead + "KEYOPT,1,1,1\n"), InputError);       // Hughes-Liu
  EXPECT_THROW(build(kHead + "R,1,0.8333,1,0.02\n"), InputError);  // NIP 1 (membrane)
  EXPECT_THROW(build(kHead + "R,1,0.8333,11,0.02\n"), InputError);
  EXPECT_THROW(build(kHead + "R,1,0.8333,2,0\n"), InputError);  // no thickness
}

TEST(ExplicitShell, InitialAngularVelocityIsKineticEnergy) {
  // A free plate spun about its normal at every node: the energy put in is ½ Σ I ω² with the
  // rotary inertia I = m (A + t²)/6 of each node's share m; nodes without rotations ignore it.
  Model m = plate(Eigen::Matrix3d::Identity());
  ExplicitSystem system = build_explicit_system(m);
  CentralDifference cd(system, m.explicit_dynamics);
  double expected = 0.0;
  for (std::size_t n = 0; n < system.n_nodes(); ++n) {
    cd.set_angular_velocity(n, Vec3(0.0, 0.0, 3.0));
    expected += 0.5 * system.inertia[n] * 9.0;
  }
  // The plate's mass 7.8e-3 × 0.02 × 1 and elements of area 1/4 (the centre node moved keeps the
  // total area): Σ I = Σ m (A + t²)/6 over the elements' corners.
  EXPECT_NEAR(expected, 0.5 * 9.0 * 7.8e-3 * 0.02 * 1.0 * (0.25 + 0.02 * 0.02) / 6.0,
              0.05 * expected);
  cd.start();
  EXPECT_NEAR(cd.energies().initial_kinetic, expected, 1e-15);
  EXPECT_NEAR(cd.angular_velocity(0).z(), 3.0, 1e-12);
}

TEST(ExplicitShell, RunFixesRotationsAndReportsMoments) {
  // A clamped strip (D ALL at x = 0, rotations included) set moving by an initial velocity:
  // the clamped nodes keep zero rotation, carry a moment reaction, and the energy balances.
  Model m = plate(Eigen::Matrix3d::Identity());
  ExplicitSystem system = build_explicit_system(m);
  CentralDifference cd(system, m.explicit_dynamics);
  std::vector<std::uint8_t> fixed(3 * system.n_nodes(), 0), turns = fixed;
  for (std::size_t n = 0; n < system.n_nodes(); ++n)
    if (system.x0[n] == 0.0)
      for (int i = 0; i < 3; ++i) fixed[3 * n + i] = turns[3 * n + i] = 1;
    else
      cd.set_velocity(n, Vec3(0, 0, system.x0[n]));
  cd.set_loads(fixed, Vec3::Zero());
  cd.set_rotation_fixes(turns);
  cd.start();
  for (int k = 0; k < 2000; ++k) cd.cycle(cd.stable_step());
  bool moment = false;
  for (std::size_t n = 0; n < system.n_nodes(); ++n) {
    if (system.x0[n] == 0.0) {
      EXPECT_EQ(cd.rotation(n).norm(), 0.0);
      moment = moment || cd.moment_reaction(n).norm() > 0.0;
    } else {
      EXPECT_GT(cd.rotation(n).norm(), 0.0);
    }
  }
  EXPECT_TRUE(moment);
  const ExplicitEnergies e = cd.energies();
  // The abrupt start (a velocity jump at the clamped edge) costs ~3 % in the first half step;
  // after it the balance holds (kinetic + rotational kinetic + internal + hourglass).
  EXPECT_LT(std::abs(e.drift()), 0.05 * e.put_in());
  EXPECT_GT(e.internal, 0.0);
}

}  // namespace
}  // namespace impactfe::test_explicit_shell163
