// BEAM161 (docs/explicit_dynamics.md): a rigid translation and rotation make no strain and no
// force, also after a finite rotation of a spinning free beam; a uniform axial stretch (patch)
// gives σ = Eε̇dt in every element and leaves the interior nodes in equilibrium; the first bending
// period of a cantilever against Euler–Bernoulli; the response does not depend on the order of
// the nodes I, J (symmetry); the 1-D plastic return of the section points; the refusals.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include <cmath>

#include "deck/deck_reader.h"
#include "explicit/central_difference.h"
#include "explicit/explicit_system.h"

namespace impactfe::test_explicit_beam161 {
namespace {

constexpr double kE = 2e11, kNu = 0.3, kRho = 7800.0, kH = 0.02;

/// The deck's head: the element type with `extra` KEYOPTs, real set 1 (`real`, or the square
/// section h × h), steel.
std::string head(const std::string& extra = "", const std::string& real = "") {
  return fmt::format("/PREP7\nET,1,BEAM161\n{}{}\nMP,EX,1,{}\nMP,NUXY,1,{}\nMP,DENS,1,{}\n", extra,
                     real.empty() ? fmt::format("R,1,0.8333333,{},{},{},{}", kH, kH, kH, kH) : real,
                     kE, kNu, kRho);
}

/// A straight beam of `n` elements from a to b, orientation node K off the line.
Model beam(int n, const Vec3& a, const Vec3& b, const std::string& extra = "",
           bool reversed = false, const std::string& after = "", const std::string& real = "") {
  std::string deck = head(extra, real);
  for (int i = 0; i <= n; ++i) {
    const Vec3 p = a + (b - a) * (static_cast<double>(i) / n);
    deck += fmt::format("N,{},{:.17g},{:.17g},{:.17g}\n", i + 1, p.x(), p.y(), p.z());
  }
  const Vec3 side = (b - a).cross(Vec3(0.3, 0.5, 0.7)).normalized();
  const Vec3 k = a + side;
  deck += fmt::format("N,1000,{:.17g},{:.17g},{:.17g}\n", k.x(), k.y(), k.z());
  for (int i = 1; i <= n; ++i)
    deck += reversed ? fmt::format("E,{},{},1000\n", i + 1, i)
                     : fmt::format("E,{},{},1000\n", i, i + 1);
  return read_deck_text(deck + after, "beam.inp").model;
}

struct Beams {
  ExplicitSystem system;
  std::vector<double> x, y, z, vx, vy, vz, wx, wy, wz, forces, moments;
  explicit Beams(const Model& m) : system(build_explicit_system(m)) {
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

TEST(ExplicitBeam, RigidBodyMotionMakesNoStrain) {
  // The mesh is the midpoint configuration x_{n+1/2} of the step; v_{n+1/2} = v0 + ω × x_{n+1/2}
  // and x_{n+1} = x_{n+1/2} + dt/2 v_{n+1/2} (the element takes its rates at the midpoint).
  Beams run(beam(3, Vec3(0.1, -0.2, 0.3), Vec3(0.8, 0.4, -0.5)));
  ASSERT_TRUE(run.system.has_rotations());
  const Vec3 v0(1.0, -2.0, 0.5), w(3.0, -1.0, 2.0);
  const double dt = 1e-3;
  for (std::size_t n = 0; n < run.system.n_nodes(); ++n) {
    const Vec3 v = v0 + w.cross(Vec3(run.x[n], run.y[n], run.z[n]));
    run.vx[n] = v.x(), run.vy[n] = v.y(), run.vz[n] = v.z();
    run.wx[n] = w.x(), run.wy[n] = w.y(), run.wz[n] = w.z();
    run.x[n] += 0.5 * dt * v.x(), run.y[n] += 0.5 * dt * v.y(), run.z[n] += 0.5 * dt * v.z();
  }
  run.evaluate(dt);
  for (double f : run.forces) EXPECT_NEAR(f, 0.0, 1e-9);
  for (double m : run.moments) EXPECT_NEAR(m, 0.0, 1e-9);
  EXPECT_NEAR(run.set().energies().internal, 0.0, 1e-15);
}

TEST(ExplicitBeam, FiniteRotationOfAFreeBeamMakesNoStrain) {
  // A free beam spinning at ω about a general axis through its centre (every node's v = ω × r,
  // angular velocity ω) turns by 2 rad; its strain energy stays a round-off of the kinetic one.
  Model m = beam(4, Vec3(-0.5, 0.1, 0.0), Vec3(0.5, -0.1, 0.2));
  ExplicitSystem system = build_explicit_system(m);
  CentralDifference cd(system, m.explicit_dynamics);
  const Vec3 w = Vec3(0.2, 1.0, 0.4).normalized() * 50.0, c(0.0, 0.0, 0.1);
  for (std::size_t n = 0; n < system.n_nodes(); ++n) {
    if (!cd.has_rotations(n)) continue;
    cd.set_velocity(n, w.cross(Vec3(system.x0[n], system.y0[n], system.z0[n]) - c));
    cd.set_angular_velocity(n, w);
  }
  cd.set_loads(std::vector<std::uint8_t>(3 * system.n_nodes(), 0), Vec3::Zero());
  cd.start();
  while (cd.time() < 2.0 / w.norm()) cd.cycle(cd.stable_step());
  const ExplicitEnergies e = cd.energies();
  EXPECT_GT(cd.rotation(0).norm(), 1.9);
  // What strain there is comes from the centrifugal stretch and from the nodes' spin
  // component along the axis, which the isotropic rotary inertia keeps fixed in space while the
  // axis turns: 2e-8 of the kinetic energy (a finite rotation taken for strain would be of order
  // 1; with the rates taken at x_{n+1} instead of the midpoint, each step shortened the beam by
  // (ω dt)²/2 and the kinetic energy grew by 0.4 % over the 2 rad).
  EXPECT_LT(e.internal, 1e-7 * e.put_in());
  EXPECT_LT(std::abs(e.drift()), 1e-6 * e.put_in());
}

TEST(ExplicitBeam, UniformAxialStretchIsExact) {
  // v = ε̇ (x − a) along a beam of 4 elements in a general direction: each element has
  // σ = E d dt at every section point with the rate d = ε̇/(1 − ε̇ dt/2) on the midpoint length
  // L − dt/2 ε̇ L, N = σA, and the interior nodes are in equilibrium.
  const Vec3 a(0.1, 0.2, 0.3), b(1.1, -0.4, 0.8);
  Beams run(beam(4, a, b));
  const double rate = 0.1, dt = 1e-6;
  for (std::size_t n = 0; n < run.system.n_nodes(); ++n) {
    const Vec3 v = rate * (Vec3(run.x[n], run.y[n], run.z[n]) - a);
    run.vx[n] = v.x(), run.vy[n] = v.y(), run.vz[n] = v.z();
  }
  run.evaluate(dt);
  Eigen::MatrixXd r;
  run.set().results(r);
  const double n_expected = kE * rate / (1.0 - 0.5 * rate * dt) * dt * kH * kH;
  for (Eigen::Index k = 0; k < r.rows(); ++k) {
    EXPECT_NEAR(r(k, 0), n_expected, 1e-9 * n_expected);  // FORC
    for (int c = 1; c < 6; ++c) EXPECT_NEAR(r(k, c), 0.0, 1e-9 * n_expected);
  }
  const Vec3 e = (b - a).normalized();
  const std::size_t first = static_cast<std::size_t>(run.system.index_of(1));
  const std::size_t last = static_cast<std::size_t>(run.system.index_of(5));
  for (std::size_t n = 0; n < run.system.n_nodes(); ++n) {
    const Vec3 f = run.nodal(run.forces, n);
    if (n == first)
      EXPECT_NEAR((f + n_expected * e).norm(), 0.0, 1e-9 * n_expected);
    else if (n == last)
      EXPECT_NEAR((f - n_expected * e).norm(), 0.0, 1e-9 * n_expected);
    else
      EXPECT_NEAR(f.norm(), 0.0, 1e-9 * n_expected);
    EXPECT_NEAR(run.nodal(run.moments, n).norm(), 0.0, 1e-12 * n_expected);
  }
}

/// The tip's UY of a cantilever (clamped at node 1, all DOFs) of 20 elements, L = 1, started
/// with the velocity field of its static deflection shape, sampled every cycle.
struct Cantilever {
  std::vector<double> t, uy;
  double energy_drift = 0.0, put_in = 0.0;
};

Cantilever cantilever(bool reversed) {
  constexpr int kN = 20;
  Model m = beam(kN, Vec3(0, 0, 0), Vec3(1, 0, 0), "", reversed);
  ExplicitSystem system = build_explicit_system(m);
  CentralDifference cd(system, m.explicit_dynamics);
  std::vector<std::uint8_t> fixed(3 * system.n_nodes(), 0), turns = fixed;
  const std::size_t clamp = static_cast<std::size_t>(system.index_of(1));
  const std::size_t tip = static_cast<std::size_t>(system.index_of(kN + 1));
  for (int i = 0; i < 3; ++i) fixed[3 * clamp + i] = turns[3 * clamp + i] = 1;
  for (std::size_t n = 0; n < system.n_nodes(); ++n) {
    const double x = system.x0[n];
    // The static shape of a tip load, x²(3 − x)/2 (L = 1), and its slope.
    cd.set_velocity(n, Vec3(0.0, 0.01 * x * x * (3.0 - x) / 2.0, 0.0));
    if (cd.has_rotations(n))
      cd.set_angular_velocity(n, Vec3(0, 0, 0.01 * (6.0 * x - 3 * x * x) / 2));
  }
  cd.set_loads(fixed, Vec3::Zero());
  cd.set_rotation_fixes(turns);
  cd.start();
  Cantilever out;
  while (cd.time() < 0.2) {
    cd.cycle(cd.stable_step());
    out.t.push_back(cd.time());
    out.uy.push_back(cd.displacement(tip).y());
  }
  const ExplicitEnergies e = cd.energies();
  out.energy_drift = e.drift();
  out.put_in = e.put_in();
  return out;
}

TEST(ExplicitBeam, CantileverVibratesAtTheEulerBernoulliFrequency) {
  const Cantilever c = cantilever(false);
  // The period from the upward zero crossings of the tip's UY (linear interpolation).
  std::vector<double> crossings;
  for (std::size_t i = 1; i < c.uy.size(); ++i)
    if (c.uy[i - 1] < 0.0 && c.uy[i] >= 0.0)
      crossings.push_back(c.t[i - 1] +
                          (c.t[i] - c.t[i - 1]) * (-c.uy[i - 1]) / (c.uy[i] - c.uy[i - 1]));
  ASSERT_GE(crossings.size(), 2u);
  const double period = (crossings.back() - crossings.front()) / (crossings.size() - 1);
  // Euler–Bernoulli: f1 = (1.8751²/2π) √(EI/(ρAL⁴)), I/A = h²/12 (h/L = 0.02: Timoshenko's
  // shear and rotary inertia lower it by ~1e-4).
  const double f1 = 1.8751 * 1.8751 / (2.0 * M_PI) * std::sqrt(kE * kH * kH / (12.0 * kRho));
  EXPECT_NEAR(1.0 / period, f1, 0.01 * f1) << "f1 = " << f1;
  EXPECT_LT(std::abs(c.energy_drift), 1e-3 * c.put_in);
}

TEST(ExplicitBeam, ResponseDoesNotDependOnTheNodeOrder) {
  const Cantilever a = cantilever(false), b = cantilever(true);
  ASSERT_EQ(a.uy.size(), b.uy.size());
  double largest = 0.0;
  for (double u : a.uy) largest = std::max(largest, std::abs(u));
  for (std::size_t i = 0; i < a.uy.size(); ++i) EXPECT_NEAR(a.uy[i], b.uy[i], 1e-9 * largest);
}

TEST(ExplicitBeam, AxialPlasticFlowFollowsTheHardeningLine) {
  // A single free element stretched at a constant rate beyond yield (BISO σy = 250e6,
  // Et = 2e9): N/A follows σy + E_t(ε − σy/E) (the 1-D return of every section point).
  Model m = beam(1, Vec3(0, 0, 0), Vec3(1, 0, 0), "", false, "TB,BISO,1\nTBDATA,1,250E6,2E9\n");
  Beams run(m);
  const double rate = 1.0, dt = 1e-6;
  const std::size_t j = static_cast<std::size_t>(run.system.index_of(2));
  run.vx[j] = rate;
  double strain = 0.0;
  for (int i = 0; i < 5000; ++i) {
    // The length is kept: the rate, on the midpoint length, acts on the stress only.
    run.evaluate(dt);
    strain += rate * dt / (1.0 - 0.5 * rate * dt);
  }
  Eigen::MatrixXd r;
  run.set().results(r);
  const double stress = 250e6 + 2e9 * (strain - 250e6 / kE);
  EXPECT_NEAR(r(0, 0) / (kH * kH), stress, 1e-6 * 250e6);
  EXPECT_NEAR(r(0, 7), strain - stress / kE, 1e-9);
  EXPECT_GT(run.set().energies().plastic_work, 0.0);
}

TEST(ExplicitBeam, BendingReachesTheSectionLimit) {
  // One element bent about s at a constant curvature rate (ω_J along s, perfectly plastic BISO
  // σy = 250e6): every point of the 2×2 rule yields at ±σy, so M_s = 4 (A/4) σy h/(2√3)
  // = σy A h/(2√3) (the rule's limit: the exact rectangle's σy A h/4 needs more points), the
  // other resultants stay 0, EPEQ = κ h/(2√3) − σy/E.
  Model m = beam(1, Vec3(0, 0, 0), Vec3(1, 0, 0), "", false, "TB,BISO,1\nTBDATA,1,250E6,0\n");
  Beams run(m);
  const std::size_t j = static_cast<std::size_t>(run.system.index_of(2));
  // The s axis of the element: K's direction normal to the axis.
  const Vec3 k = Vec3(run.x[static_cast<std::size_t>(run.system.index_of(1000))],
                      run.y[static_cast<std::size_t>(run.system.index_of(1000))],
                      run.z[static_cast<std::size_t>(run.system.index_of(1000))]);
  const Vec3 s = (k - k.dot(Vec3::UnitX()) * Vec3::UnitX()).normalized();
  // Opposite nodal spins ±κ̇L/2 about s: the mean spin, and so the transverse shear, is 0.
  const double rate = 1000.0, dt = 1e-6;  // κ̇ over L = 1: κ = 1 after 1000 steps
  const std::size_t i = static_cast<std::size_t>(run.system.index_of(1));
  run.wx[j] = 0.5 * rate * s.x(), run.wy[j] = 0.5 * rate * s.y(), run.wz[j] = 0.5 * rate * s.z();
  run.wx[i] = -run.wx[j], run.wy[i] = -run.wy[j], run.wz[i] = -run.wz[j];
  for (int step = 0; step < 1000; ++step) run.evaluate(dt);
  Eigen::MatrixXd r;
  run.set().results(r);
  const double c = kH / (2.0 * std::sqrt(3.0));
  EXPECT_NEAR(r(0, 4), 250e6 * kH * kH * c, 1e-9 * 250e6 * kH * kH * c);  // MS
  for (int col : {0, 1, 2, 3, 5}) EXPECT_NEAR(r(0, col), 0.0, 1e-6);
  EXPECT_NEAR(r(0, 6), 250e6, 1e-3);
  EXPECT_NEAR(r(0, 7), 1.0 * c - 250e6 / kE, 1e-12);
}

TEST(ExplicitBeam, RefusesWhatItDoesNotCarryOut) {
  const auto build = [&](const std::string& extra, const std::string& real = "") {
    return build_explicit_system(beam(2, Vec3(0, 0, 0), Vec3(1, 0, 0), extra, false, "", real));
  };
  EXPECT_NO_THROW(build(""));
  EXPECT_NO_THROW(build("KEYOPT,1,1,1\n"));
  EXPECT_NO_THROW(build("KEYOPT,1,5,1\n", "R,1,0.8333,0.02,0.02,0.01,0.01"));  // tube
  EXPECT_THROW(build("KEYOPT,1,5,1\n"), InputError);  // inner diameter = outer
  EXPECT_THROW(build("KEYOPT,1,1,2\n"), InputError);  // Belytschko–Schwer resultant
  EXPECT_THROW(build("KEYOPT,1,2,1\n"), InputError);  // another quadrature
  EXPECT_THROW(build("KEYOPT,1,4,1\n"), InputError);  // standard sections
  EXPECT_THROW(build("KEYOPT,1,5,2\n"), InputError);
  EXPECT_THROW(build("", "R,1,0.8333,0.02,0.02,0.02,0.02,1"), InputError);  // NSLOC
  EXPECT_THROW(build("", "R,1,0.8333,0,0,0.02,0.02"), InputError);          // no TS
  // Without K.
  EXPECT_THROW(build_explicit_system(read_deck_text(head() + "N,1\nN,2,1\nE,1,2\n", "k.inp").model),
               InputError);
}

TEST(ExplicitBeam, TubeSectionHasTheAreaAndInertiaOfTheClosedForm) {
  // A tube D = 0.02, d = 0.01 (KEYOPT(5) = 1) in elements of L = 0.01: the nodal mass
  // ρ π (D² − d²)/4 L/2 and rotary inertia (ρ L/2) π (D⁴ − d⁴)/64, the bending inertia of the
  // section (above the raised bound κGAL²/(4(E − κG)) at this length).
  Model m = beam(1, Vec3(0, 0, 0), Vec3(0.01, 0, 0), "KEYOPT,1,5,1\n", false, "",
                 "R,1,0.8333,0.02,0.02,0.01,0.01");
  ExplicitSystem s = build_explicit_system(m);
  const double area = M_PI * (0.02 * 0.02 - 0.01 * 0.01) / 4.0;
  const double inertia = M_PI * (std::pow(0.02, 4) - std::pow(0.01, 4)) / 64.0;
  const std::size_t i = static_cast<std::size_t>(s.index_of(1));
  EXPECT_NEAR(s.mass[i], 0.005 * kRho * area, 1e-12);
  EXPECT_NEAR(s.inertia[i], 0.005 * kRho * inertia, 1e-9 * kRho * inertia);
}

}  // namespace
}  // namespace impactfe::test_explicit_beam161
