// Explicit dynamics (docs/explicit_dynamics.md): the SOLID164 kernel (volume derivatives against
// Gauss quadrature, the patch test for a uniform strain rate on a distorted mesh, rigid-body
// motion free of strain, hourglass modes resisted), the Jaumann rotation and the radial return of
// materials/rate_plasticity.h, and the central-difference run (determinism, mass scaling).
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <Eigen/Geometry>

#include <cmath>

#include "deck/deck_reader.h"
#include "elements/element_registry.h"
#include "elements/hexahedron_volume.h"
#include "explicit/central_difference.h"
#include "explicit/explicit_system.h"
#include "explicit/part_energies.h"
#include "materials/rate_plasticity.h"

namespace impactfe::test_explicit_dynamics {
namespace {

// A distorted hexahedron (no two faces parallel).
const double kX[8] = {0.0, 1.1, 1.2, -0.1, 0.05, 1.0, 1.3, 0.1};
const double kY[8] = {0.0, 0.1, 1.0, 0.9, -0.05, 0.0, 1.2, 1.1};
const double kZ[8] = {0.0, 0.05, -0.1, 0.0, 1.0, 1.1, 0.9, 1.2};

TEST(Hexahedron, VolumeDerivativesAreThoseOfTheExactVolume) {
  double bx[8], by[8], bz[8];
  hexahedron::volume_derivatives(kX, kY, kZ, bx, by, bz);
  const double v = hexahedron::gauss_volume(kX, kY, kZ);
  EXPECT_NEAR(hexahedron::volume(kX, bx), v, 1e-14);
  EXPECT_NEAR(hexahedron::volume(kY, by), v, 1e-14);
  EXPECT_NEAR(hexahedron::volume(kZ, bz), v, 1e-14);
  // Central differences of the Gauss volume (a cubic in each coordinate: exact up to round-off).
  const double h = 1e-4;
  for (int a = 0; a < 8; ++a) {
    double* coords[3] = {const_cast<double*>(kX), const_cast<double*>(kY), const_cast<double*>(kZ)};
    const double* b[3] = {bx, by, bz};
    for (int i = 0; i < 3; ++i) {
      double x[3][8];
      for (int j = 0; j < 3; ++j)
        for (int c = 0; c < 8; ++c) x[j][c] = coords[j][c];
      x[i][a] += h;
      const double up = hexahedron::gauss_volume(x[0], x[1], x[2]);
      x[i][a] -= 2 * h;
      const double down = hexahedron::gauss_volume(x[0], x[1], x[2]);
      EXPECT_NEAR(b[i][a], (up - down) / (2 * h), 1e-9) << "corner " << a << " direction " << i;
    }
  }
}

/// A 2x2x2 block of SOLID164 with its centre node moved (distorted elements).
Model distorted_block(const std::string& extra = "") {
  std::string deck = "/PREP7\nET,1,SOLID164\nMP,EX,1,2E5\nMP,NUXY,1,0.3\nMP,DENS,1,7.8E-3\n";
  int id = 0;
  for (int k = 0; k <= 2; ++k)
    for (int j = 0; j <= 2; ++j)
      for (int i = 0; i <= 2; ++i) {
        double x = i, y = j, z = k;
        if (i == 1 && j == 1 && k == 1) x += 0.2, y -= 0.15, z += 0.1;
        deck += "N," + std::to_string(++id) + "," + std::to_string(x) + "," + std::to_string(y) +
                "," + std::to_string(z) + "\n";
      }
  const auto n = [](int i, int j, int k) { return 1 + i + 3 * j + 9 * k; };
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        deck += "E";
        for (int c :
             {n(i, j, k), n(i + 1, j, k), n(i + 1, j + 1, k), n(i, j + 1, k), n(i, j, k + 1),
              n(i + 1, j, k + 1), n(i + 1, j + 1, k + 1), n(i, j + 1, k + 1)})
          deck += "," + std::to_string(c);
        deck += "\n";
      }
  return read_deck_text(deck + extra, "block.inp").model;
}

struct Block {
  ExplicitSystem system;
  std::vector<double> x, y, z, vx, vy, vz, forces;
  explicit Block(const Model& m) : system(build_explicit_system(m)) {
    x = system.x0, y = system.y0, z = system.z0;
    vx.assign(system.n_nodes(), 0.0), vy = vx, vz = vx;
    forces.assign(3 * system.n_slots, 0.0);
  }
  ExplicitNodalView view() const {
    return {x.data(), y.data(), z.data(), vx.data(), vy.data(), vz.data()};
  }
  /// Nodal sums of the element forces.
  std::vector<Vec3> nodal() const {
    std::vector<Vec3> f(system.n_nodes(), Vec3::Zero());
    for (std::size_t n = 0; n < system.n_nodes(); ++n)
      for (std::size_t j = system.slot_start[n]; j < system.slot_start[n + 1]; ++j)
        f[n] += Vec3(forces[3 * system.slots[j]], forces[3 * system.slots[j] + 1],
                     forces[3 * system.slots[j] + 2]);
    return f;
  }
};

TEST(ExplicitSolid, UniformStrainRateIsExactOnADistortedMesh) {
  Block run(distorted_block());
  // v = G x with G symmetric: a uniform strain rate D = G, no spin.
  const double g[3][3] = {{1e-3, 2e-4, -3e-4}, {2e-4, -5e-4, 1e-4}, {-3e-4, 1e-4, 7e-4}};
  for (std::size_t n = 0; n < run.system.n_nodes(); ++n) {
    const double p[3] = {run.x[n], run.y[n], run.z[n]};
    run.vx[n] = g[0][0] * p[0] + g[0][1] * p[1] + g[0][2] * p[2];
    run.vy[n] = g[1][0] * p[0] + g[1][1] * p[1] + g[1][2] * p[2];
    run.vz[n] = g[2][0] * p[0] + g[2][1] * p[1] + g[2][2] * p[2];
  }
  auto& set = *run.system.sets.front();
  const double dt = 1.0;
  set.internal_forces(run.view(), dt, run.forces.data());
  Eigen::MatrixXd r;
  set.results(r);
  const double e = 2e5, nu = 0.3, lambda = e * nu / ((1 + nu) * (1 - 2 * nu)),
               mu = e / (2 * (1 + nu));
  const double trace = g[0][0] + g[1][1] + g[2][2];
  for (Eigen::Index k = 0; k < r.rows(); ++k) {
    EXPECT_NEAR(r(k, 0), lambda * trace + 2 * mu * g[0][0], 1e-9);
    EXPECT_NEAR(r(k, 1), lambda * trace + 2 * mu * g[1][1], 1e-9);
    EXPECT_NEAR(r(k, 2), lambda * trace + 2 * mu * g[2][2], 1e-9);
    EXPECT_NEAR(r(k, 3), 2 * mu * g[0][1], 1e-9);
    EXPECT_NEAR(r(k, 4), 2 * mu * g[1][2], 1e-9);
    EXPECT_NEAR(r(k, 5), 2 * mu * g[0][2], 1e-9);
  }
  // The interior node (14) is in equilibrium under the uniform stress; no hourglass work.
  const auto f = run.nodal();
  EXPECT_LT(f[static_cast<std::size_t>(run.system.index_of(14))].norm(), 1e-10);
  EXPECT_NEAR(set.energies().hourglass, 0.0, 1e-18);
}

TEST(ExplicitSolid, RigidBodyMotionMakesNoStrain) {
  Block run(distorted_block());
  const Vec3 omega(0.3, -0.2, 0.5), translation(1.0, -2.0, 0.5);
  for (std::size_t n = 0; n < run.system.n_nodes(); ++n) {
    const Vec3 v = translation + omega.cross(Vec3(run.x[n], run.y[n], run.z[n]));
    run.vx[n] = v.x(), run.vy[n] = v.y(), run.vz[n] = v.z();
  }
  auto& set = *run.system.sets.front();
  set.internal_forces(run.view(), 1e-3, run.forces.data());
  Eigen::MatrixXd r;
  set.results(r);
  EXPECT_LT(r.cwiseAbs().maxCoeff(), 1e-12);
  for (const Vec3& f : run.nodal()) EXPECT_LT(f.norm(), 1e-12);
  EXPECT_NEAR(set.energies().hourglass, 0.0, 1e-20);
  EXPECT_NEAR(set.energies().internal, 0.0, 1e-20);
}

const char* kCube =
    "/PREP7\nET,1,SOLID164\nMP,EX,1,2E5\nMP,NUXY,1,0.3\nMP,DENS,1,7.8E-3\n"
    "N,1,-.5,-.5,-.5\nN,2,.5,-.5,-.5\nN,3,.5,.5,-.5\nN,4,-.5,.5,-.5\n"
    "N,5,-.5,-.5,.5\nN,6,.5,-.5,.5\nN,7,.5,.5,.5\nN,8,-.5,.5,.5\nE,1,2,3,4,5,6,7,8\n";

TEST(ExplicitSolid, HourglassModesAreResisted) {
  // Each of the 12 hourglass velocity fields (Γ_α in x, y or z) of a cube has no mean strain
  // rate: no stress, and only the hourglass viscosity resists it (positive power).
  const double gamma[4][8] = {{1, 1, -1, -1, -1, -1, 1, 1},
                              {1, -1, -1, 1, -1, 1, 1, -1},
                              {1, -1, 1, -1, 1, -1, 1, -1},
                              {-1, 1, -1, 1, 1, -1, 1, -1}};
  for (int mode = 0; mode < 4; ++mode)
    for (int direction = 0; direction < 3; ++direction) {
      Block run(read_deck_text(kCube, "cube.inp").model);
      auto* v = direction == 0 ? &run.vx : direction == 1 ? &run.vy : &run.vz;
      for (int a = 0; a < 8; ++a) (*v)[static_cast<std::size_t>(a)] = 0.01 * gamma[mode][a];
      auto& set = *run.system.sets.front();
      set.internal_forces(run.view(), 1e-3, run.forces.data());
      Eigen::MatrixXd r;
      set.results(r);
      EXPECT_LT(r.cwiseAbs().maxCoeff(), 1e-12) << "mode " << mode;
      EXPECT_GT(set.energies().hourglass, 0.0) << "mode " << mode;
      double power = 0.0;
      const auto f = run.nodal();
      for (std::size_t n = 0; n < 8; ++n) power += f[n](direction) * (*v)[n];
      EXPECT_GT(power, 0.0) << "mode " << mode;
    }
}

/// Moves the nodes of `run` with its velocities over `steps` cycles of dt, evaluating the forces
/// at each configuration.
void advance(Block& run, int steps, double dt) {
  auto& set = *run.system.sets.front();
  for (int i = 0; i < steps; ++i) {
    for (std::size_t n = 0; n < run.x.size(); ++n)
      run.x[n] += dt * run.vx[n], run.y[n] += dt * run.vy[n], run.z[n] += dt * run.vz[n];
    set.internal_forces(run.view(), dt, run.forces.data());
  }
}

TEST(ExplicitSolid, StiffnessHourglassHoldsItsEnergyAndGivesItBack) {
  // The cube driven along an hourglass mode (v = 1e-4 Γ_1 in x) for 100 cycles and back: the
  // stiffness form (EDMP,HGLS type 4) holds ½κq² with κ = QM (λ + 2μ) Σb·b / (3V) = QM (λ + 2μ)
  // / 2 on the unit cube, q = Σ u·γ = 8 · 1e-4 · t, and gives it all back on the way home (forces
  // and energy to zero); the viscous form (type 0) dissipates twice the outgoing work.
  const double gamma[8] = {1, 1, -1, -1, -1, -1, 1, 1};
  const double e = 2e5, nu = 0.3, modulus = e * (1 - nu) / ((1 + nu) * (1 - 2 * nu));
  const double qm = 0.1, kappa = qm * modulus / 2.0, dt = 1e-3;
  const int steps = 100;
  for (const int type : {4, 0}) {
    Block run(read_deck_text(std::string(kCube) + fmt::format("EDMP,HGLS,1,{},{}\n", type, qm),
                             "cube.inp")
                  .model);
    for (std::size_t a = 0; a < 8; ++a) run.vx[a] = 1e-4 * gamma[a];
    advance(run, steps, dt);
    auto& set = *run.system.sets.front();
    const double q = 8 * 1e-4 * steps * dt, out = set.energies().hourglass;
    if (type == 4) {
      EXPECT_NEAR(out, 0.5 * kappa * q * q, 1e-9 * kappa * q * q);
      // Each node carries Q γ_I = κ q γ_I against the mode (to the change of shape, 1e-5).
      EXPECT_NEAR(run.nodal()[0].x(), kappa * q, 1e-4 * kappa * q);
    }
    for (std::size_t a = 0; a < 8; ++a) run.vx[a] = -run.vx[a];
    advance(run, steps, dt);
    if (type == 4) {
      EXPECT_NEAR(set.energies().hourglass, 0.0, 1e-9 * out);
      for (const Vec3& f : run.nodal()) EXPECT_LT(f.norm(), 1e-9 * kappa * q);
    } else {
      EXPECT_NEAR(set.energies().hourglass, 2.0 * out, 1e-9 * out);
    }
  }
}

TEST(ExplicitSolid, StiffnessHourglassForcesTurnWithTheElement) {
  // An hourglass deformation held (stiffness form), then the cube turned rigidly by 90° about z
  // in 2000 cycles (each cycle the exact rotation, the velocity ω × x: a pure spin): the stored
  // hourglass forces turn with it (Jaumann rate, first order in ω dt), and the rotation does no
  // hourglass work.
  const double gamma[8] = {1, 1, -1, -1, -1, -1, 1, 1};
  Block run(read_deck_text(std::string(kCube) + "EDMP,HGLS,1,5\n", "cube.inp").model);
  for (std::size_t a = 0; a < 8; ++a) run.vx[a] = 1e-4 * gamma[a];
  advance(run, 10, 1e-3);
  const std::vector<Vec3> before = run.nodal();
  const double stored = run.system.sets.front()->energies().hourglass;
  const int steps = 2000;
  const double omega = (M_PI / 2) / (steps * 1e-3);
  auto& set = *run.system.sets.front();
  for (int i = 0; i < steps; ++i) {
    const double c = std::cos(omega * 1e-3), s = std::sin(omega * 1e-3);
    for (std::size_t n = 0; n < 8; ++n) {
      const double x = c * run.x[n] - s * run.y[n], y = s * run.x[n] + c * run.y[n];
      run.x[n] = x, run.y[n] = y;
      run.vx[n] = -omega * y, run.vy[n] = omega * x, run.vz[n] = 0.0;
    }
    set.internal_forces(run.view(), 1e-3, run.forces.data());
  }
  const std::vector<Vec3> after = run.nodal();
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()).toRotationMatrix();
  for (std::size_t n = 0; n < 8; ++n)
    EXPECT_LT((after[n] - turn * before[n]).norm(), 2e-3 * before[n].norm()) << "node " << n;
  EXPECT_NEAR(set.energies().hourglass, stored, 2e-3 * stored);
}

TEST(ExplicitSolid, HourglassControlByMaterial) {
  // EDMP,HGLS: VAL1 0 to 5, coefficients >= 0, at most six values; QM 0 turns the control off
  // for that material alone.
  const auto model = [](const std::string& line) {
    return read_deck_text(std::string(kCube) + line, "cube.inp").model;
  };
  EXPECT_THROW(model("EDMP,HGLS,1,6\n"), InputError);
  EXPECT_THROW(model("EDMP,HGLS,1,4,-0.1\n"), InputError);
  EXPECT_THROW(model("EDMP,HGLS,1,4,0.1,1.5,0.06,0.1,0.1,7\n"), InputError);
  const ExplicitHourglass h = model("EDMP,HGLS,1,4,0.05\n").explicit_dynamics.hourglass_of(1);
  EXPECT_EQ(h.type, 4);
  EXPECT_EQ(h.membrane, 0.05);
  EXPECT_EQ(h.bending, 0.05);
  EXPECT_EQ(h.warping, 0.05);
  EXPECT_EQ(h.bulk_quadratic, 1.5);
  EXPECT_EQ(model("EDHGLS,0.07\n").explicit_dynamics.hourglass_of(1).membrane, 0.07);
  Block run(model("EDMP,HGLS,1,0,0\n"));
  const double gamma[8] = {1, 1, -1, -1, -1, -1, 1, 1};
  for (std::size_t a = 0; a < 8; ++a) run.vz[a] = 0.01 * gamma[a];
  advance(run, 1, 1e-3);
  EXPECT_EQ(run.system.sets.front()->energies().hourglass, 0.0);
}

TEST(ExplicitParts, KineticEnergyOfSharedNodesIsSplitByMass) {
  // Two unit bricks sharing a face, materials of density 1 and 3 (parts 1 and 2), moving at
  // v = (3, 4, 0): each part's kinetic energy is ½ m v² of its own brick (12.5 and 37.5), the
  // shared face's nodes split 1 : 3; a spin about the shared face's centre gives each part its
  // own ½ ∫ρ|ω × x|² only approximately (lumped), but the parts still add up to the total.
  const std::string deck =
      "/PREP7\nET,1,SOLID164\nMP,EX,1,1E3\nMP,DENS,1,1\nMP,EX,2,1E3\nMP,DENS,2,3\n"
      "N,1\nN,2,1\nN,3,1,1\nN,4,0,1\nN,5,,,1\nN,6,1,,1\nN,7,1,1,1\nN,8,0,1,1\n"
      "N,9,2\nN,10,2,1\nN,11,2,,1\nN,12,2,1,1\n"
      "MAT,1\nE,1,2,3,4,5,6,7,8\nMAT,2\nE,2,9,10,3,6,11,12,7\n";
  const Model model = read_deck_text(deck, "two.inp").model;
  ExplicitSystem system = build_explicit_system(model);
  CentralDifference cd(system, model.explicit_dynamics);
  for (std::size_t n = 0; n < system.n_nodes(); ++n) cd.set_velocity(n, Vec3(3, 4, 0));
  cd.set_loads(std::vector<std::uint8_t>(3 * system.n_nodes(), 0), Vec3::Zero());
  cd.start();
  const ExplicitPartEnergies parts(model, system);
  ASSERT_EQ(parts.size(), 2u);
  const Eigen::VectorXd e = parts.at(system, cd);
  EXPECT_NEAR(e(0), 12.5, 1e-12);
  EXPECT_NEAR(e(3), 37.5, 1e-12);
  EXPECT_NEAR(e(0) + e(3), cd.energies().kinetic, 1e-12);
  EXPECT_EQ(e(1), 0.0);  // no cycle yet: no internal or hourglass energy
  EXPECT_EQ(e(5), 0.0);
}

TEST(ExplicitSolid, KeyoptionsOfSolid164) {
  // KEYOPT(1) 0 and 1 are the same one-point element; 2 (full integration) is refused.
  EXPECT_NO_THROW(Block{distorted_block()});
  const Model one = read_deck_text(
                        "/PREP7\nET,1,SOLID164\nKEYOPT,1,1,1\nMP,EX,1,1\nMP,DENS,1,1\nN,1\nN,2,"
                        "1\nN,3,1,1\nN,4,0,1\n"
                        "N,5,0,0,1\nN,6,1,0,1\nN,7,1,1,1\nN,8,0,1,1\nE,1,2,3,4,5,6,7,8\n",
                        "one.inp")
                        .model;
  EXPECT_NO_THROW(build_explicit_system(one));
  Model two = one;
  two.element_types.at(1).keyopt[1] = 2;
  EXPECT_THROW(build_explicit_system(two), InputError);
}

TEST(ExplicitSolid, SetMatchesItsRegistration) {
  Block run(distorted_block());
  const ExplicitElementSet& set = *run.system.sets.front();
  const ElementTypeDescriptor& d = *find_element_type("SOLID164");
  EXPECT_EQ(set.family(), d.family);
  EXPECT_EQ(set.size(), 8u);
  Eigen::MatrixXd r;
  set.results(r);
  EXPECT_EQ(static_cast<std::size_t>(r.cols()), d.result_names.size());
  // The lumped masses add up to ρV of the block (8 unit bricks, the centre node moved: V = 8).
  double total = 0.0;
  for (double m : run.system.mass) total += m;
  EXPECT_NEAR(total, 7.8e-3 * 8.0, 1e-15);
  // The implicit analyses refuse the element with a message that says where it runs.
  const Model m = distorted_block();
  try {
    create_element(ElementBuildContext{m, {}}, m.elements.at(1));
    ADD_FAILURE() << "SOLID164 built as an implicit element";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("explicit"), std::string::npos) << e.what();
  }
}

TEST(RatePlasticity, JaumannRotationTurnsTheStressWithTheSpin) {
  // σ = s e_x⊗e_x under the spin of a rotation about z at rate ω for a time θ/ω: σ_xx = s cos²θ,
  // σ_xy = s sin θ cos θ (to the first-order accuracy of the forward update in the step).
  double s[6] = {100.0, 0, 0, 0, 0, 0};
  const double omega = 1.0, theta = 0.6;
  const int steps = 100000;
  const double dt = theta / omega / steps;
  for (int i = 0; i < steps; ++i) jaumann_rotate(s, -omega, 0.0, 0.0, dt);
  EXPECT_NEAR(s[0], 100.0 * std::cos(theta) * std::cos(theta), 1e-3);
  EXPECT_NEAR(s[1], 100.0 * std::sin(theta) * std::sin(theta), 1e-3);
  EXPECT_NEAR(s[3], 100.0 * std::sin(theta) * std::cos(theta), 1e-3);
  EXPECT_NEAR(s[0] + s[1], 100.0, 1e-7);  // the trace is invariant
}

TEST(RatePlasticity, UniaxialStrainReturnMatchesTheBilinearLaw) {
  // Pure shear strain rate, increments far past yield: the equivalent stress follows the
  // bilinear hardening σy + H α (H = E Et / (E − Et)), and the plastic work σy α + H α²/2.
  const double e = 2e5, nu = 0.3, sy = 250.0, et = 2e3;
  RateMaterial m;
  m.shear = e / (2 * (1 + nu));
  m.bulk = e / (3 * (1 - 2 * nu));
  m.density = 1.0;
  m.plasticity = J2Plasticity::bilinear(e, nu, sy, et, false);
  double s[6] = {}, beta[6] = {}, alpha = 0.0, work = 0.0;
  const double d[6] = {0, 0, 0, 1.0, 0, 0};
  for (int i = 0; i < 1000; ++i) {
    elastic_increment(s, d, 1e-5, m);
    work += radial_return(s, beta, alpha, m);
  }
  const double h = e * et / (e - et);
  EXPECT_GT(alpha, 0.0);
  EXPECT_NEAR(std::sqrt(3.0) * std::abs(s[3]), sy + h * alpha, 1e-8 * sy);
  EXPECT_NEAR(work, sy * alpha + 0.5 * h * alpha * alpha, 1e-3 * work);
}

TEST(CentralDifference, ResultsAreBitwiseRepeatable) {
  // The same run twice gives bitwise equal states (fixed-order force sums, no reductions
  // whose order depends on anything but the model).
  const auto once = [] {
    Model m = distorted_block();
    ExplicitSystem s = build_explicit_system(m);
    CentralDifference cd(s, m.explicit_dynamics);
    for (std::size_t n = 0; n < s.n_nodes(); ++n) cd.set_velocity(n, Vec3(s.x0[n], 0, -s.z0[n]));
    cd.set_loads(std::vector<std::uint8_t>(3 * s.n_nodes(), 0), Vec3(0, 0, 9.81));
    cd.start();
    for (int i = 0; i < 200; ++i) cd.cycle(cd.stable_step());
    return cd.displacement(5);
  };
  const Vec3 a = once(), b = once();
  EXPECT_EQ(a.x(), b.x());
  EXPECT_EQ(a.y(), b.y());
  EXPECT_EQ(a.z(), b.z());
}

TEST(CentralDifference, MassScalingRaisesTheStepAndReportsTheMass) {
  Model m = distorted_block();
  ExplicitSystem free = build_explicit_system(m);
  CentralDifference plain(free, m.explicit_dynamics);
  plain.set_loads(std::vector<std::uint8_t>(3 * free.n_nodes(), 0), Vec3::Zero());
  plain.start();
  const double natural = plain.stable_step() / m.explicit_dynamics.time_step_factor;
  for (const double sign : {1.0, -1.0}) {
    m.explicit_dynamics.mass_scaling_step = sign * 2.0 * natural;
    ExplicitSystem s = build_explicit_system(m);
    const double mass = s.physical_mass;
    CentralDifference cd(s, m.explicit_dynamics);
    cd.set_loads(std::vector<std::uint8_t>(3 * s.n_nodes(), 0), Vec3::Zero());
    cd.start();
    EXPECT_NEAR(cd.stable_step(), 0.9 * 2.0 * natural, 1e-9 * natural);
    EXPECT_GT(cd.added_mass(), 0.0);
    double total = 0.0;
    for (double v : s.mass) total += v;
    EXPECT_NEAR(total, mass + cd.added_mass(), 1e-9 * total);
  }
}

}  // namespace
}  // namespace impactfe::test_explicit_dynamics
