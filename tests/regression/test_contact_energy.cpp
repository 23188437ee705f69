// An elastic bar hits a rigid wall end on and rebounds (tests/decks/energy/bar_wall_conta178.inp:
// 20 LINK180, L = 10, v0 = 100, m v0^2 / 2 = 36.5, m v0 = 0.73). The one-dimensional wave
// solution (Graff §2.1) gives the bar back its kinetic energy and reverses its momentum; contact
// must neither create energy nor keep pushing across an open gap, with the default KEYOPTs
// (augmented Lagrange) as with the penalty method, for node-to-node (CONTA178) and node-to-rigid
// surface (CONTA175) contact and for each time integrator.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <fstream>
#include <regex>
#include <sstream>

#include "../support/run_deck.h"
#include "core/errors.h"

namespace impactfe::test_contact_energy {
namespace {

using testing::run_deck_text;

constexpr double kInitialKinetic = 0.5 * 7.3e-4 * 10.0 * 100.0 * 100.0;  // 36.5
constexpr double kMomentum = 7.3e-4 * 10.0 * 100.0;                      // 0.73

std::string base_deck() {
  std::ifstream in(std::string(IMPACTFE_TEST_DECKS) + "/energy/bar_wall_conta178.inp");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// `from` replaced by `to` in `text` (once; a test failure when absent).
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

/// The default deck with KEYOPT(2) = 1 (penalty).
std::string penalty(const std::string& deck) {
  return replaced(deck, "ET,2,CONTA178", "ET,2,CONTA178,,1");
}

/// The wall as a rigid TARGE170 plane at x = 10 (normal -X, towards the bar) with the bar end
/// node 21 as a CONTA175 contact node, KEYOPT(2) = `algorithm`.
std::string rigid_surface(std::string deck, int algorithm) {
  deck = replaced(deck, "ET,2,CONTA178\nR,2,,,,,,1.0\n",
                  fmt::format("ET,2,TARGE170\nET,3,CONTA175,,{}\nR,2\n", algorithm));
  deck = replaced(deck, "N,22,10\n",
                  "N,22,11\nN,23,10,-1,-1\nN,24,10,-1,1\nN,25,10,1,1\nN,26,10,1,-1\n");
  deck = replaced(deck, "E,21,22\n", "E,22\nE,23,24,25,26\nTYPE,3\nE,21\n");
  return replaced(deck, "D,22,UX\n", "D,22,UX,0,,,,UY,UZ\n");
}

struct Rebound {
  double kinetic_plus_strain = 0.0;  // at the end
  double gap_work = 0.0;
  double momentum = 0.0;  // Σ m v_x at the end (lumped masses)
};

Rebound rebound(const std::string& tag, const std::string& deck) {
  const auto run = run_deck_text(tag, deck);
  const int n = run.reader->analyses().front().n_time_points;
  const TimePoint end = run.reader->time_point(1, n - 1);
  Rebound r;
  r.kinetic_plus_strain = end.energy.at("kinetic") + end.energy.at("strain");
  r.gap_work = end.energy.at("gap_work");
  const double m = 7.3e-4 * 0.5;  // rho A dx
  for (int node = 1; node <= 21; ++node) {
    const double vx = run.reader->nodal_series(node, "VX").back().second;
    r.momentum += (node == 1 || node == 21 ? 0.5 * m : m) * vx;
  }
  return r;
}

void expect_elastic_rebound(const Rebound& r, double energy_tol, double momentum_tol) {
  EXPECT_NEAR(r.kinetic_plus_strain, kInitialKinetic, energy_tol * kInitialKinetic);
  EXPECT_GT(r.gap_work, -0.01 * kInitialKinetic);  // the contact created nothing
  EXPECT_NEAR(r.momentum, -kMomentum, momentum_tol * kMomentum);
}

TEST(ContactEnergy, AugmentedLagrangeConta178CreatingEnergyStopsTheRun) {
  // The multiplier drives the bar end towards a rigid constraint the step does not resolve: the
  // end node bounces on the wall every step, and the contact gives back about 13.5 more than it
  // took (kinetic + strain 109.4 of 36.5 while the multiplier pushed across the opening gap).
  // The energy check stops the run at the step where the contact's creation passes 10 %.
  try {
    rebound("bar_wall_al", base_deck());
    ADD_FAILURE() << "the energy created by the contact did not stop the run";
  } catch (const SolutionError& e) {
    EXPECT_NE(std::string(e.what()).find("energy created: the gap/contact work grew"),
              std::string::npos)
        << e.what();
  }
}

TEST(ContactEnergy, PenaltyConta178KeepsTheEnergyOfTheRebound) {
  expect_elastic_rebound(rebound("bar_wall_penalty", penalty(base_deck())), 0.02, 0.03);
}

TEST(ContactEnergy, AugmentedLagrangeConta175OnARigidWall) {
  expect_elastic_rebound(rebound("bar_wall_175_al", rigid_surface(base_deck(), 0)), 0.02, 0.03);
}

TEST(ContactEnergy, PenaltyConta175OnARigidWall) {
  expect_elastic_rebound(rebound("bar_wall_175_penalty", rigid_surface(base_deck(), 1)), 0.02,
                         0.03);
}

TEST(ContactEnergy, PenaltyConta178UnderHht) {
  const std::string deck =
      replaced(penalty(base_deck()), "TRNOPT,FULL\nTINTP,,0.25,0.5\n", "TRNOPT,FULL,,,,,HHT\n");
  expect_elastic_rebound(rebound("bar_wall_hht", deck), 0.02, 0.03);
}

TEST(ContactEnergy, PenaltyConta178UnderHoubolt) {
  // Houbolt damps the high modes (Bathe §9.4): the kinetic + strain energy may only fall
  // (measured 34.08 of 36.5).
  const std::string deck =
      replaced(penalty(base_deck()), "TRNOPT,FULL\nTINTP,,0.25,0.5\n", "TRNOPT,FULL,,,,,HOUB\n");
  const Rebound r = rebound("bar_wall_houbolt", deck);
  EXPECT_LT(r.kinetic_plus_strain, 1.02 * kInitialKinetic);
  EXPECT_GT(r.kinetic_plus_strain, 0.5 * kInitialKinetic);
  EXPECT_GT(r.gap_work, -0.01 * kInitialKinetic);
  EXPECT_LT(r.momentum, -0.5 * kMomentum);
}

}  // namespace
}  // namespace impactfe::test_contact_energy
