// The deck side of implicit creep: MAPDL's value of an undefined parameter in a numeric field
// (TUNIF,HOT in the Verification Manual's creep decks), RATE switching creep per load step, and
// TOFF entering the creep law's temperature term, each against the closed form of time
// hardening at constant uniaxial stress; and SF on the nodes of a shell edge (the creep decks'
// loading) as MAPDL's in-plane edge pressure.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "../support/run_deck.h"
#include "core/log.h"
#include "deck/deck_reader.h"

namespace test_creep_deck {

using namespace impactfe;

namespace {

constexpr double kTiny = 7.888609052210118e-31;  // 2^-100

Job read(const std::string& text) {
  std::ostringstream sink;
  DeckOptions o;
  o.dialect = Dialect::Modern;
  o.output = &sink;
  return read_deck_text(text, "mem.inp", o);
}

std::string error_of(const std::string& text) {
  try {
    read(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

/// The warnings logged while `f` runs.
template <class F>
std::vector<std::string> warnings_of(F f) {
  Log::clear();
  f();
  return Log::warnings();
}

bool any_contains(const std::vector<std::string>& lines, const std::string& what) {
  for (const auto& l : lines)
    if (l.find(what) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST(UndefinedParameter, ANumericFieldNamingOneTakesTwoToTheMinus100AndWarns) {
  Job job;
  const auto warnings = warnings_of([&] { job = read("/PREP7\nN,1,HOT,2\n"); });
  EXPECT_EQ(job.model.nodes.at(1).x(0), kTiny);
  EXPECT_EQ(job.model.nodes.at(1).x(1), 2.0);
  EXPECT_EQ(kTiny, std::ldexp(1.0, -100));
  EXPECT_TRUE(any_contains(warnings, "mem.inp:2")) << (warnings.empty() ? "" : warnings[0]);
  EXPECT_TRUE(any_contains(warnings, "'HOT' is not defined"));
}

TEST(UndefinedParameter, AnAssignmentFromOneTakesTheTinyValue) {
  Job job;
  const auto warnings = warnings_of([&] { job = read("/PREP7\nA=UNSET\nN,1,A*2**100\n"); });
  EXPECT_DOUBLE_EQ(job.model.nodes.at(1).x(0), 1.0);
  EXPECT_TRUE(any_contains(warnings, "'UNSET' is not defined"));
}

TEST(UndefinedParameter, InsideAnExpressionItStaysAnError) {
  EXPECT_NE(error_of("/PREP7\nN,1,2*WIDTH\n").find("'WIDTH' is not a defined parameter"),
            std::string::npos);
}

TEST(UndefinedParameter, DefinedAndLocalNamesAreNotAffected) {
  const Job job = read("/PREP7\nHOT=300\nN,1,HOT\n");
  EXPECT_EQ(job.model.nodes.at(1).x(0), 300.0);
}

namespace {

/// One SOLID185 unit cube in a tension test at σx = 100 (nodal forces 25 on x = 1), time
/// hardening C1 = 1e-10, C2 = 3, C3 = −0.5, C4 as given; load step 1 to t = 1 with RATE `rate1`,
/// load step 2 to t = 16 (4 substeps) with RATE ON; `temperature_lines` set TUNIF / TOFF.
/// Returns EPCRX at t = 1 and t = 16.
std::pair<double, double> cube_creep(const std::string& tag, const std::string& rate1, double c4,
                                     const std::string& temperature_lines) {
  std::ostringstream d;
  d << "/PREP7\nET,1,SOLID185\nMP,EX,1,200e3\nMP,NUXY,1,0.3\nTB,CREEP,1,,,2\nTBDATA,1,1e-10,3,"
       "-0.5,"
    << c4 << "\n"
    << temperature_lines
    << "N,1,0,0,0\nN,2,1,0,0\nN,3,1,1,0\nN,4,0,1,0\nN,5,0,0,1\nN,6,1,0,1\nN,7,1,1,1\nN,8,0,1,1\n"
       "E,1,2,3,4,5,6,7,8\nD,1,UX,,,4,3\nD,5,UX,,,8,3\nD,1,UY,,,2,1\nD,5,UY,,,6,1\n"
       "D,1,UZ,,,4,1\nF,2,FX,25\nF,3,FX,25\nF,6,FX,25\nF,7,FX,25\nFINISH\n/SOLU\n"
       "CNVTOL,F,,1E-10\nKBC,1\nRATE,"
    << rate1 << "\nTIME,1\nSOLVE\nRATE,ON\nTIME,16\nNSUBST,4\nSOLVE\nFINISH\n";
  const auto run = impactfe::testing::run_deck_text(tag, d.str());
  const auto series = run.reader->element_series(1, "EPCRX");
  return {impactfe::testing::value_stored_at(series, 1.0),
          impactfe::testing::value_stored_at(series, 16.0)};
}

/// Time hardening ε̇ = C1 σ^C2 t^C3 e^(−C4/T) (C3 = −0.5) integrated from t0 to t1 in `substeps`
/// equal substeps by backward Euler, the rate at the end of each (MAPDL's implicit creep).
double time_hardening(double t0, double t1, double arrhenius, int substeps) {
  const double h = (t1 - t0) / substeps;
  double strain = 0.0;
  for (int k = 1; k <= substeps; ++k) strain += 1e-10 * 1e6 * arrhenius * h / std::sqrt(t0 + k * h);
  return strain;
}

}  // namespace

TEST(CreepDeck, RateOffLeavesALoadStepWithoutCreep) {
  // RATE,OFF in load step 1 (the load applied at once, KBC 1): no creep by t = 1; creep from
  // t = 1 on in load step 2.
  const auto [at1, at16] = cube_creep("creep_rate_off", "OFF", 0.0, "");
  EXPECT_EQ(at1, 0.0);
  EXPECT_NEAR(at16, time_hardening(1.0, 16.0, 1.0, 4), 1e-9 * time_hardening(1.0, 16.0, 1.0, 4));
}

TEST(CreepDeck, RateOnCreepsFromTheStart) {
  const auto [at1, at16] = cube_creep("creep_rate_on", "ON", 0.0, "");
  const double at1_expected = time_hardening(0.0, 1.0, 1.0, 1);
  const double at16_expected = at1_expected + time_hardening(1.0, 16.0, 1.0, 4);
  EXPECT_NEAR(at1, at1_expected, 1e-9 * at1_expected);
  EXPECT_NEAR(at16, at16_expected, 1e-9 * at16_expected);
}

TEST(CreepDeck, ToffShiftsTheTemperatureOfTheArrheniusTerm) {
  // T = TUNIF + TOFF = 400 + 273.15: e^(−C4/T) with C4 = 2000; without TOFF the law would read
  // e^(−2000/400), a factor e^(2000/673.15 − 5) ≈ 0.13 smaller.
  const double arrhenius = std::exp(-2000.0 / 673.15);
  const auto [at1, at16] = cube_creep("creep_toff", "OFF", 2000.0, "TUNIF,400\nTOFF,273.15\n");
  EXPECT_EQ(at1, 0.0);
  EXPECT_NEAR(at16, time_hardening(1.0, 16.0, arrhenius, 4),
              1e-9 * time_hardening(1.0, 16.0, arrhenius, 4));
}

TEST(CreepDeck, RateTakesOnOrOff) {
  EXPECT_NE(error_of("/SOLU\nRATE,MAYBE\n").find("expected ON or OFF"), std::string::npos);
  EXPECT_NE(error_of("/SOLU\nRATE,ON,OFF\n").find("differs from the option"), std::string::npos);
  EXPECT_EQ(error_of("/SOLU\nRATE,ON,ON\nRATE,OFF\n"), "no error");
}

TEST(CreepDeck, TbCreepRefusesExplicitAndUnknownEquations) {
  EXPECT_NE(error_of("/PREP7\nTB,CREEP,1\n").find("explicit creep"), std::string::npos);
  EXPECT_NE(error_of("/PREP7\nTB,CREEP,1,,,5\n").find("creep equation not supported"),
            std::string::npos);
  EXPECT_NE(error_of("/PREP7\nTB,CREEP,1,2,,6\n").find("temperature-dependent creep"),
            std::string::npos);
  EXPECT_EQ(error_of("/PREP7\nTB,CREEP,1,,,6.0\nTBDATA,1,1E-10,3\n"), "no error");
}

TEST(ShellEdgePressure, SfOnTheNodesOfAShellEdgeLoadsTheEdgeInPlane) {
  // SHELL181 square 100 × 100, t = 1, held at x = 0 (UX) and node 1 (UY); SF,ALL,PRES,−200 on
  // the nodes of x = 100 (MAPDL's in-plane edge pressure, positive into the element): uniaxial
  // σx = 200, u_x(100) = 200 · 100 / E = 0.1. The surface (face 1) of no element is selected.
  const std::string deck =
      "/PREP7\nET,1,SHELL181\nSECTYPE,1,SHELL\nSECDATA,1\nMP,EX,1,200e3\nMP,NUXY,1,0.3\n"
      "N,1,0,0\nN,2,100,0\nN,3,100,100\nN,4,0,100\nE,1,2,3,4\nD,1,UX\nD,4,UX\nD,1,UY\n"
      "D,ALL,UZ\nD,ALL,ROTX\nD,ALL,ROTY\nD,ALL,ROTZ\nFINISH\n/SOLU\nNSEL,S,LOC,X,100\n"
      "SF,ALL,PRES,-200\nNSEL,ALL\nSOLVE\nFINISH\n";
  const auto run = impactfe::testing::run_deck_text("shell_edge_pressure", deck);
  EXPECT_NEAR(impactfe::testing::value_stored_at(run.reader->nodal_series(3, "UX"), 1.0), 0.1,
              1e-9);
  EXPECT_NEAR(impactfe::testing::value_stored_at(run.reader->element_series(1, "SX_TOP"), 1.0),
              200.0, 1e-6);
  // One node of the edge selected: no face and no edge has all its nodes selected.
  EXPECT_NE(error_of("/PREP7\nET,1,SHELL181\nN,1\nN,2,1\nN,3,1,1\nE,1,2,3\nNSEL,S,NODE,,3\n"
                     "SF,ALL,PRES,1\n")
                .find("no element face has all its nodes selected"),
            std::string::npos);
}

TEST(ConvergenceSettings, AChangeAfterTheFirstSolveOfAnAnalysisIsSaid) {
  // The analysis keeps the Newton settings of its first SOLVE (vmr049-cr1b tightens CNVTOL
  // between load steps): the change is said at the SOLVE it would have acted on.
  const std::string deck =
      "/PREP7\nET,1,LINK180\nR,1,1\nMP,EX,1,1000\nN,1\nN,2,1\nE,1,2\nD,1,ALL\nD,2,UY,,,,,UZ\n"
      "FINISH\n/SOLU\nF,2,FX,1\nTIME,1\nSOLVE\nCNVTOL,F,,1E-8\nTIME,2\nSOLVE\n";
  const auto warnings = warnings_of([&] { read(deck); });
  EXPECT_TRUE(any_contains(warnings,
                           "mem.inp:17: SOLVE: CNVTOL, NEQIT, NROPT or LNSRCH changed since "
                           "this analysis began at mem.inp:14"))
      << (warnings.empty() ? "" : warnings.back());
  // Before the first SOLVE a change acts and is not warned.
  const std::string before =
      "/PREP7\nET,1,LINK180\nR,1,1\nMP,EX,1,1000\nN,1\nN,2,1\nE,1,2\n"
      "D,1,ALL\nD,2,UY,,,,,UZ\nFINISH\n/SOLU\nCNVTOL,F,,1E-8\nF,2,FX,1\n"
      "SOLVE\n";
  EXPECT_FALSE(any_contains(warnings_of([&] { read(before); }), "CNVTOL"));
}

}  // namespace test_creep_deck
