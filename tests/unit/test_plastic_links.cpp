// Elastic-plastic LINK180 through the deck reader and the drivers: a bar cycled by load steps
// follows the closed-form BISO / BKIN loops (history committed per converged step), a three-bar
// truss reaches its closed-form first-yield, contained-plastic and collapse loads, and a bar
// striking a rigid wall through a COMBIN40 gap keeps a permanent set whose size and energy
// balance agree with a run at a ten times smaller time step.
#include <gtest/gtest.h>

#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>

#include "../support/bilinear_closed_form.h"
#include "../support/run_deck.h"

namespace impactfe::test_plastic_links {
namespace {

constexpr double kE = 200e3, kSy = 250.0, kEt = 20e3;
/// TB,PLAS's second constant: the plastic tangent modulus E Et/(E − Et) of the tangent kEt.
constexpr double kEp = kE * kEt / (kE - kEt);

void cyclic_bar(const char* law, bool kinematic) {
  // Two LINK180 in series (L = 10 each), node 3 pulled by D,UX load steps along a cyclic path;
  // node 2 is free, so Newton solves for it. Strain path ±4 εy in steps of 0.37 εy.
  const double length = 10.0, ey = kSy / kE;
  const auto path = testing::cyclic_strain_path(4.0 * ey, 0.37 * ey);
  std::ostringstream deck;
  deck << std::setprecision(17);  // kEp is not a short decimal
  deck << "/PREP7\nET,1,LINK180\nSECTYPE,1,LINK\nSECDATA,2.0\nMP,EX,1," << kE
       << "\nMP,PRXY,1,0.3\nTB,PLAS,1,,," << law << "\nTBDATA,1," << kSy << "," << kEp
       << "\nN,1\nN,2," << length << "\nN,3," << 2 * length
       << "\nE,1,2\nE,2,3\nFINISH\n/SOLU\nANTYPE,STATIC\nCNVTOL,F,,1E-8\n"
          "D,ALL,UY\nD,ALL,UZ\nD,1,UX\n";
  for (std::size_t k = 0; k < path.size(); ++k)
    deck << "TIME," << k + 1 << "\nD,3,UX," << path[k] * 2 * length << "\nSOLVE\n";
  deck << "FINISH\n";
  const auto run = testing::run_deck_text(std::string("cyclic_") + law, deck.str());
  const auto expected = testing::bilinear_closed_form(path, kE, kSy, kEt, kinematic);
  for (int element : {1, 2}) {
    const auto saxl = run.reader->element_series(element, "SAXL");
    double max_error = 0.0;
    for (std::size_t k = 0; k < path.size(); ++k)
      max_error =
          std::max(max_error, std::abs(testing::value_stored_at(saxl, k + 1.0) - expected[k]));
    // Point by point: Newton converges to round-off on the piecewise-linear response.
    EXPECT_LT(max_error, 1e-6 * kSy) << law << " element " << element;
  }
  // Plastic strain = total − σ/E at the last point.
  const auto eppl = run.reader->element_series(1, "EPPL");
  EXPECT_NEAR(eppl.back().second, path.back() - expected.back() / kE, 1e-9);
  EXPECT_GT(run.reader->element_series(1, "EPEQ").back().second, 10.0 * ey);
}

TEST(PlasticLinks, CyclicBarFollowsTheBisoLoop) {
  cyclic_bar("BISO", false);
}

TEST(PlasticLinks, CyclicBarFollowsTheBkinLoop) {
  cyclic_bar("BKIN", true);
}

/// Symmetric three-bar truss: vertical bar (length L) and two bars at θ = 45° from it, joined at
/// node 4 under a downward load P. Elastic-perfectly plastic (BISO, Et = 0), area A.
std::string three_bar_truss(const std::vector<double>& loads) {
  std::ostringstream deck;
  deck << "/PREP7\nET,1,LINK180\nSECTYPE,1,LINK\nSECDATA,1.0\nMP,EX,1," << kE
       << "\nTB,BISO,1\nTBDATA,1," << kSy << ",0\n"
       << "N,1,-100,100\nN,2,0,100\nN,3,100,100\nN,4,0,0\nE,1,4\nE,2,4\nE,3,4\nFINISH\n"
       << "/SOLU\nANTYPE,STATIC\nCNVTOL,F,,1E-9\nD,1,ALL\nD,2,ALL\nD,3,ALL\nD,4,UZ\n";
  for (std::size_t k = 0; k < loads.size(); ++k)
    deck << "TIME," << k + 1 << "\nF,4,FY," << -loads[k] << "\nSOLVE\n";
  deck << "FINISH\n";
  return deck.str();
}

TEST(PlasticLinks, ThreeBarTrussFirstYieldContainedFlowAndCollapse) {
  // Closed forms (A = 1, L = 100, c = cos 45°): first yield of the vertical bar at
  // P_y = σy (1 + 2c³); collapse at P_c = σy (1 + 2c). Between them the vertical bar carries
  // σy and the side bars (elastic) (P − σy)/(2c), so δ = (P − σy) L / (2 E c³).
  const double c = std::sqrt(0.5), length = 100.0;
  const double p_yield = kSy * (1.0 + 2.0 * c * c * c), p_collapse = kSy * (1.0 + 2.0 * c);
  const std::vector<double> loads = {0.99 * p_yield, 1.01 * p_yield, 0.9 * p_collapse,
                                     0.99 * p_collapse};
  const auto run = testing::run_deck_text("three_bar", three_bar_truss(loads));
  const auto uy = run.reader->nodal_series(4, "UY");
  const auto epeq = run.reader->element_series(2, "EPEQ");
  // Elastic below P_y: δ = P L / (E (1 + 2c³)).
  const double elastic = loads[0] * length / (kE * (1.0 + 2.0 * c * c * c));
  EXPECT_NEAR(-testing::value_stored_at(uy, 1.0), elastic, 1e-6 * elastic);
  EXPECT_EQ(testing::value_stored_at(epeq, 1.0), 0.0);
  EXPECT_GT(testing::value_stored_at(epeq, 2.0), 0.0);
  for (int k = 1; k < 4; ++k) {
    const double p = loads[static_cast<std::size_t>(k)];
    const double delta = (p - kSy) * length / (2.0 * kE * c * c * c);
    // Newton stops at a force residual of 1e-9 of the load: δ to 1e-5 relative.
    EXPECT_NEAR(-testing::value_stored_at(uy, k + 1.0), delta, 1e-5 * delta) << "P = " << p;
  }
  EXPECT_NEAR(testing::value_stored_at(run.reader->element_series(2, "SAXL"), 4.0), kSy,
              1e-6 * kSy);
  EXPECT_EQ(testing::value_stored_at(run.reader->element_series(1, "EPEQ"), 4.0),
            0.0);  // side bars elastic

  // Above P_c there is no equilibrium: the step fails (exit status 2) and says why.
  try {
    testing::run_deck_text(
        "three_bar_collapse",
        three_bar_truss({0.9 * p_collapse, 0.99 * p_collapse, 1.02 * p_collapse}));
    ADD_FAILURE() << "a load above the collapse load was accepted";
  } catch (const SolutionError& e) {
    EXPECT_NE(std::string(e.what()).find("load step 3"), std::string::npos) << e.what();
  }
}

/// A LINK180 bar (10 elements, L = 10, A = 1, ρ = 1, E = 1e4: c = 100) moving at v0 = 2 toward
/// a rigid wall through a COMBIN40 gap (GAP = 0.01, K1 = 1e5) at its front node; BISO σy = 100,
/// Et = 1000 (the elastic impact stress ρ c v0 = 200 exceeds σy). Trapezoidal Newmark, lumped
/// mass, 0.5 s (impact, plastic wave, rebound, free flight).
testing::DeckRun car_crash(const std::string& tag, double dt) {
  std::ostringstream deck;
  deck << "/PREP7\nET,1,LINK180\nET,2,COMBIN40,,,1\nSECTYPE,1,LINK\nSECDATA,1.0\n"
          "MP,EX,1,1E4\nMP,DENS,1,1.0\nTB,BISO,1\nTBDATA,1,100,1000\nR,2,1E5,,,0.01\n";
  for (int i = 0; i <= 10; ++i) deck << "N," << i + 1 << "," << i << "\n";
  deck << "N,20,11\nTYPE,1\n";
  for (int i = 1; i <= 10; ++i) deck << "E," << i << "," << i + 1 << "\n";
  deck << "TYPE,2\nREAL,2\nE,11,20\nFINISH\n/SOLU\nANTYPE,TRANS\nTRNOPT,FULL\n"
          "TINTP,,0.25,0.5\nLUMPM,ON\nD,ALL,UY\nD,ALL,UZ\nD,20,UX\n";
  for (int i = 1; i <= 11; ++i) deck << "IC," << i << ",UX,0,2.0\n";
  deck << "TIME,0.5\nDELTIM," << dt << "\nOUTRES,ALL,ALL\nSOLVE\nFINISH\n";
  return testing::run_deck_text(tag, deck.str());
}

struct CrashFigures {
  double permanent_set = 0.0;  // Σ ε_p h: the bar's plastic shortening
  std::map<std::string, double> energy;
};

CrashFigures crash_figures(const testing::DeckRun& run) {
  CrashFigures out;
  for (int e = 1; e <= 10; ++e)
    out.permanent_set += run.reader->element_series(e, "EPPL").back().second * 1.0;
  const int n = run.reader->analyses()[0].n_time_points;
  out.energy = run.reader->time_point(1, n - 1).energy;
  return out;
}

TEST(PlasticLinks, BarStrikingAWallKeepsAPermanentSetAndBalancesItsEnergy) {
  const double initial_kinetic = 0.5 * 10.0 * 2.0 * 2.0;  // ½ ρ A L v0² = 20
  const auto coarse = crash_figures(car_crash("crash_coarse", 5e-4));
  const auto fine = crash_figures(car_crash("crash_fine", 5e-5));
  for (const auto* f : {&coarse, &fine}) {
    // Shortened, and a substantial part of the kinetic energy went into plastic work.
    EXPECT_LT(f->permanent_set, -1e-3);
    EXPECT_GT(f->energy.at("plastic_work"), 0.2 * initial_kinetic);
    // Balance: initial kinetic = kinetic + elastic strain + plastic + gap + numerical; the
    // trapezoidal rule keeps the numerical part within 1 % of the energy put in.
    const double accounted = f->energy.at("kinetic") + f->energy.at("strain") +
                             f->energy.at("plastic_work") + f->energy.at("gap_work");
    EXPECT_NEAR(accounted, initial_kinetic, 0.01 * initial_kinetic);
  }
  // Δt = 5e-4 (T/28 of the closed contact) against the Δt = 5e-5 reference: permanent set and
  // plastic work within 1 % (measured: 0.1 %). At Δt = 1e-3 the gap closes and opens inside
  // steps and the gap work is off by 12 % of the energy: the time-step advice of the run flags it.
  EXPECT_NEAR(coarse.permanent_set, fine.permanent_set, 0.01 * std::abs(fine.permanent_set));
  EXPECT_NEAR(coarse.energy.at("plastic_work"), fine.energy.at("plastic_work"),
              0.01 * fine.energy.at("plastic_work"));
  RecordProperty("permanent_set_coarse", std::to_string(coarse.permanent_set));
  RecordProperty("permanent_set_fine", std::to_string(fine.permanent_set));
  RecordProperty("plastic_work_coarse", std::to_string(coarse.energy.at("plastic_work")));
  RecordProperty("plastic_work_fine", std::to_string(fine.energy.at("plastic_work")));
}

}  // namespace
}  // namespace impactfe::test_plastic_links
