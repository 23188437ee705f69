// Fields that were accepted and ignored (silent wrong answers) are carried out or refused:
// LINK180's ADDMAS and TENSKEY (read as a LINK8 initial strain before), LINK8's initial strain in
// a linear static and a transient, MP / RMODIF / MPCHG between load steps (a new analysis after
// FINISH takes them), SOLID185 KEYOPT(6) = 1, orthotropic elastic constants (MP,EY, GXY ...)
// that the isotropic elements would have left out.
// Closed forms: a bar of EA/L with a tip load; a one-element fixed-free bar with consistent mass,
// ω² = 3EA / ((ρA + m) L²); a mass on a pre-strained bar oscillating about u = −ε₀L.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "../support/run_deck.h"

namespace impactfe::test_accepted_fields {
namespace {

namespace fs = std::filesystem;

constexpr double kE = 30e6, kA = 1.0, kRho = 0.001, kL = 100.0;

testing::DeckRun run_text(const std::string& tag, const std::string& deck) {
  const fs::path dir = testing::fresh_directory(tag);
  std::ofstream(dir / "deck.inp") << deck;
  return testing::run_deck_in((dir / "deck.inp").string(), dir);
}

/// The error a deck stops with ("" when it runs).
std::string error_of(const std::string& tag, const std::string& deck) {
  try {
    run_text(tag, deck);
  } catch (const std::exception& e) {
    return e.what();
  }
  return {};
}

double last(const std::vector<std::pair<double, double>>& series) {
  return series.empty() ? std::nan("") : series.back().second;
}

/// A fixed-free bar (node 1 fixed, node 2 free in X) of one element of `type` with real set
/// `real` and material DENS `dens`; `solution`: the /SOLU part.
std::string bar_deck(const std::string& type, const std::string& real, double dens,
                     const std::string& solution) {
  return fmt::format(
      "/PREP7\nET,1,{}\nR,1,{}\nMP,EX,1,{}\nMP,DENS,1,{}\nN,1\nN,2,{}\nE,1,2\n"
      "D,1,ALL\nD,2,UY\nD,2,UZ\nFINISH\n/SOLU\n{}FINISH\n",
      type, real, kE, dens, kL, solution);
}

TEST(AcceptedFields, Link180AddedMassActsOnTheMassNotOnTheForce) {
  // Static: the tip load alone sets the axial stress (SAXL = F / A), whatever ADDMAS is (it was
  // read as a LINK8 initial strain of 0.001: SAXL 31,000 for a load of 1,000).
  auto s = run_text("link180_addmas_static",
                    bar_deck("LINK180", "1,0.001", kRho, "ANTYPE,STATIC\nF,2,FX,1000\nSOLVE\n"));
  EXPECT_NEAR(last(s.reader->element_series(1, "SAXL")), 1000.0, 1e-9);
  EXPECT_NEAR(last(s.reader->nodal_series(2, "UX")), 1000.0 * kL / (kE * kA), 1e-15);
  // Modal: ω² = 3EA / ((ρA + m) L²) for one element with consistent mass; m = ρA doubles the mass.
  const std::string modal = "ANTYPE,MODAL\nMODOPT,LANB,1\nSOLVE\n";
  const auto frequency = [&](const std::string& tag, const std::string& real, double dens) {
    const auto run = run_text(tag, bar_deck("LINK180", real, dens, modal));
    const auto f = run.reader->frequencies();
    return f.empty() ? 0.0 : f.front();
  };
  const double f_bare = frequency("link180_bare", "1", kRho);
  const double f_added = frequency("link180_added", "1,0.001", kRho);
  const double f_dense = frequency("link180_dense", "1", 2.0 * kRho);
  const double expected = std::sqrt(3.0 * kE * kA / ((kRho * kA + 0.001) * kL * kL)) / (2 * M_PI);
  std::cout << "LINK180 ADDMAS: " << f_added << " Hz (closed form " << expected << " Hz; without "
            << f_bare << " Hz)\n";
  EXPECT_NEAR(f_added, expected, 1e-6 * expected);
  EXPECT_NEAR(f_added, f_dense, 1e-9 * f_dense);  // ADDMAS = ρA: the mass of twice the density
  EXPECT_NEAR(f_bare / f_added, std::sqrt(2.0), 1e-9);
}

/// A LINK180 in parallel with a soft COMBIN14 (k = 1e4) between node 1 (fixed) and node 2,
/// loaded by `force` in X at node 2: UX of node 2 and the link's FORC.
std::pair<double, double> parallel_bar(const std::string& tag, int tenskey, double force) {
  const std::string deck = fmt::format(
      "/PREP7\nET,1,LINK180\nET,2,COMBIN14\nR,1,1,0,{}\nR,2,1E4\nMP,EX,1,{}\nN,1\nN,2,{}\n"
      "TYPE,1\nREAL,1\nE,1,2\nTYPE,2\nREAL,2\nE,1,2\nD,1,ALL\nD,2,UY\nD,2,UZ\nFINISH\n/SOLU\n"
      "ANTYPE,STATIC\nF,2,FX,{}\nSOLVE\nFINISH\n",
      tenskey, kE, kL, force);
  const auto run = run_text(tag, deck);
  return {last(run.reader->nodal_series(2, "UX")), last(run.reader->element_series(1, "FORC"))};
}

TEST(AcceptedFields, Link180TensionOnlyAndCompressionOnly) {
  const double k_bar = kE * kA / kL, k_spring = 1e4;
  // Tension only: carries a pull with the spring, goes slack under a push (the spring alone).
  auto [u, n] = parallel_bar("tenskey_pull", 1, 1000.0);
  EXPECT_NEAR(u, 1000.0 / (k_bar + k_spring), 1e-12);
  EXPECT_NEAR(n, k_bar * u, 1e-6);
  std::tie(u, n) = parallel_bar("tenskey_push", 1, -1000.0);
  EXPECT_NEAR(u, -1000.0 / k_spring, 1e-12);
  EXPECT_EQ(n, 0.0);
  // Compression only: the reverse.
  std::tie(u, n) = parallel_bar("tenskey_c_push", -1, -1000.0);
  EXPECT_NEAR(u, -1000.0 / (k_bar + k_spring), 1e-12);
  std::tie(u, n) = parallel_bar("tenskey_c_pull", -1, 1000.0);
  EXPECT_NEAR(u, 1000.0 / k_spring, 1e-12);
  EXPECT_EQ(n, 0.0);
  // Both (the default).
  std::tie(u, n) = parallel_bar("tenskey_both", 0, -1000.0);
  EXPECT_NEAR(u, -1000.0 / (k_bar + k_spring), 1e-12);
  EXPECT_NE(error_of("tenskey_bad",
                     bar_deck("LINK180", "1,0,2", kRho, "ANTYPE,STATIC\nF,2,FX,1\nSOLVE\n"))
                .find("TENSKEY (real constant 3) = 2 must be 0"),
            std::string::npos);
}

TEST(AcceptedFields, Link8InitialStrainBalancesTheLoadInALinearStatic) {
  // N = EA (u/L + ε₀) = F at the free end: u = (F/EA − ε₀) L, SAXL = F/A, reaction −F.
  const double eps0 = 1e-4, force = 1000.0;
  auto s = run_text("link8_istrn_static",
                    bar_deck("LINK8", fmt::format("1,{}", eps0), kRho,
                             fmt::format("ANTYPE,STATIC\nF,2,FX,{}\nSOLVE\n", force)));
  EXPECT_NEAR(last(s.reader->nodal_series(2, "UX")), (force / (kE * kA) - eps0) * kL, 1e-12);
  EXPECT_NEAR(last(s.reader->element_series(1, "SAXL")), force / kA, 1e-6);
  EXPECT_NEAR(last(s.reader->nodal_series(1, "FX")), -force, 1e-6);
  // Both ends fixed: no motion, the prestress N = EA ε₀ and reactions ∓N.
  auto f = run_text("link8_istrn_fixed", bar_deck("LINK8", fmt::format("1,{}", eps0), kRho,
                                                  "ANTYPE,STATIC\nD,2,UX\nSOLVE\n"));
  EXPECT_NEAR(last(f.reader->element_series(1, "FORC")), kE * kA * eps0, 1e-6);
  EXPECT_NEAR(last(f.reader->nodal_series(2, "FX")), kE * kA * eps0, 1e-6);
}

TEST(AcceptedFields, Link8InitialStrainMovesTheMassInATransient) {
  // A massless pre-strained bar holding a mass M: it oscillates about u = −ε₀L between 0 and
  // −2ε₀L with ω² = (EA/L) / M (trapezoidal rule, 100 steps per period: within 0.5 %).
  const double eps0 = 1e-4, mass = 10.0;
  const double omega = std::sqrt(kE * kA / kL / mass);
  const double period = 2 * M_PI / omega;
  const std::string deck = fmt::format(
      "/PREP7\nET,1,LINK8\nET,2,MASS21,,,2\nR,1,1,{}\nR,2,{}\nMP,EX,1,{}\nN,1\nN,2,{}\n"
      "TYPE,1\nREAL,1\nE,1,2\nTYPE,2\nREAL,2\nE,2\nD,1,ALL\nD,2,UY\nD,2,UZ\nFINISH\n/SOLU\n"
      "ANTYPE,TRANS\nTRNOPT,FULL\nOUTRES,ALL,ALL\nDELTIM,{}\nTIME,{}\nSOLVE\nFINISH\n",
      eps0, mass, kE, kL, period / 100.0, period);
  const auto run = run_text("link8_istrn_transient", deck);
  const auto ux = run.reader->nodal_series(2, "UX");
  ASSERT_FALSE(ux.empty());
  double lowest = 0.0;
  for (const auto& [t, u] : ux) lowest = std::min(lowest, u);
  std::cout << "LINK8 ISTRN transient: lowest UX " << lowest << " (closed form " << -2 * eps0 * kL
            << ")\n";
  EXPECT_NEAR(lowest, -2 * eps0 * kL, 0.005 * 2 * eps0 * kL);
}

TEST(AcceptedFields, ModelChangesBetweenLoadStepsAreRefused) {
  const std::string two_steps = "ANTYPE,STATIC\nF,2,FX,1000\nSOLVE\n{}\nF,2,FX,2000\nSOLVE\n";
  for (const char* change : {"MP,EX,1,60E6", "RMODIF,1,1,2", "MPDATA,EX,1,1,60E6"}) {
    const std::string err =
        error_of("change_between_steps",
                 bar_deck("LINK8", "1", kRho, fmt::format(fmt::runtime(two_steps), change)));
    EXPECT_NE(err.find("deck.inp:19: SOLVE: "), std::string::npos) << change << ": " << err;
    EXPECT_NE(err.find("since this analysis began at"), std::string::npos) << err;
    EXPECT_NE(err.find(std::string(change).rfind("RMODIF", 0) == 0 ? "real constant set 1"
                                                                   : "material 1"),
              std::string::npos)
        << err;
  }
  // Before the analysis begins, MP in /SOLU acts: twice the modulus, half the extension.
  auto run =
      run_text("change_before_analysis", bar_deck("LINK8", "1", kRho,
                                                  "MP,EX,1,60E6\nANTYPE,STATIC\nF,2,FX,1000\n"
                                                  "SOLVE\n"));
  EXPECT_NEAR(last(run.reader->nodal_series(2, "UX")), 1000.0 * kL / (2 * kE * kA), 1e-15);
}

// The rest of the model between load steps, changed from /PREP7 without FINISH (which would end
// the analysis): refused at the next SOLVE, naming what changed, like MP and RMODIF above.
TEST(AcceptedFields, ElementTypeTableAndNodeChangesBetweenLoadStepsAreRefused) {
  const std::string two_steps =
      "ANTYPE,STATIC\nF,2,FX,1000\nSOLVE\n/PREP7\n{}\n/SOLU\nF,2,FX,2000\nSOLVE\n";
  const std::pair<const char*, const char*> cases[] = {
      {"ET,1,LINK8", "element type 1 changed (ET, KEYOPT)"},
      {"KEYOPT,1,2,1", "element type 1 changed (ET, KEYOPT)"},
      {"TB,BISO,1\nTBDATA,1,1E5,0", "TB table"},
      {"N,2,20", "node 2 changed"}};
  for (const auto& [change, message] : cases) {
    const std::string err =
        error_of("model_change_between_steps",
                 bar_deck("LINK180", "1", kRho, fmt::format(fmt::runtime(two_steps), change)));
    EXPECT_NE(err.find(": SOLVE: "), std::string::npos) << change << ": " << err;
    EXPECT_NE(err.find(message), std::string::npos) << change << ": " << err;
  }
}

/// The bar of bar_deck with a material 2 of twice the modulus; `rest`: the deck after the first
/// analysis's FINISH.
std::string two_analyses(const std::string& rest) {
  return bar_deck("LINK180", "1", kRho,
                  fmt::format("ANTYPE,STATIC\nF,2,FX,1000\nTIME,1\nSOLVE\nF,2,FX,2000\nTIME,2\n"
                              "SOLVE\nFINISH\n/PREP7\nMP,EX,2,{}\nMP,DENS,2,{}\n{}",
                              2 * kE, kRho, rest));
}

TEST(AcceptedFields, FinishEndsTheAnalysisAndTheNextSolveBeginsANewOne) {
  // MAPDL: leaving /SOLU with FINISH ends the analysis; the next SOLVE (no ANTYPE,,REST) begins
  // a new one on the model as it is then (MPCHG gives the bar twice the modulus), at load step 1
  // and a TIME below the earlier analysis's last. Its results replace <jobname>.h5; the earlier
  // analysis is kept in <jobname>.1.h5.
  auto run = run_text("new_analysis_after_finish",
                      two_analyses("MPCHG,2,ALL\nFINISH\n/SOLU\nF,2,FX,1000\nTIME,0.5\nSOLVE\n"));
  const auto ux = run.reader->nodal_series(2, "UX");
  ASSERT_EQ(ux.size(), 1u);
  EXPECT_EQ(ux[0].first, 0.5);
  EXPECT_NEAR(ux[0].second, 1000.0 * kL / (2 * kE * kA), 1e-15);
  EXPECT_EQ(run.reader->load_steps_of(1), (std::vector<std::pair<int, int>>{{1, 1}}));
  EXPECT_EQ(run.reader->elements().front().mat, 2);
  const ResultsReader earlier((run.directory / "deck.1.h5").string());
  const auto ux1 = earlier.nodal_series(2, "UX");
  ASSERT_EQ(ux1.size(), 2u);
  EXPECT_NEAR(ux1[1].second, 2000.0 * kL / (kE * kA), 1e-15);
  EXPECT_EQ(earlier.elements().front().mat, 1);
  // POST1 reads the new analysis: its load step 2 does not exist.
  const std::string err = error_of(
      "new_analysis_post1",
      two_analyses("MPCHG,2,1\nFINISH\n/SOLU\nF,2,FX,1000\nSOLVE\nFINISH\n/POST1\nSET,2\n"));
  EXPECT_NE(err.find("SET: load step 2 is not on the results file"), std::string::npos) << err;
}

TEST(AcceptedFields, RestartAfterFinishContinuesTheAnalysis) {
  // ANTYPE,,REST continues the analysis FINISH left: TIME must go on, results add to the file.
  auto run = run_text("restart_after_finish",
                      bar_deck("LINK180", "1", kRho,
                               "ANTYPE,STATIC\nRESCONTROL,DEFINE,ALL,LAST\nF,2,FX,1000\nTIME,1\n"
                               "SOLVE\nFINISH\n/SOLU\n"
                               "ANTYPE,,REST\nF,2,FX,2000\nTIME,2\nSOLVE\n"));
  const auto ux = run.reader->nodal_series(2, "UX");
  ASSERT_EQ(ux.size(), 2u);
  EXPECT_NEAR(ux[1].second, 2000.0 * kL / (kE * kA), 1e-15);
  EXPECT_FALSE(fs::exists(run.directory / "deck.1.h5"));
}

TEST(AcceptedFields, MpchgWithinOneAnalysisIsRefused) {
  // /PREP7 without FINISH (or MPCHG in /SOLU) between load steps: the analysis goes on, and it
  // keeps the model of its first SOLVE.
  for (const char* change : {"/PREP7\nMPCHG,2,ALL\n/SOLU", "MPCHG,2,1"}) {
    const std::string err =
        error_of("mpchg_between_steps",
                 bar_deck("LINK180", "1", kRho,
                          fmt::format("MP,EX,2,{}\nANTYPE,STATIC\nF,2,FX,1000\nSOLVE\n{}\nSOLVE\n",
                                      2 * kE, change)));
    EXPECT_NE(err.find("element 1 changed (type, real constants, material, section, ESYS or nodes) "
                       "since this analysis began at"),
              std::string::npos)
        << change << ": " << err;
  }
  for (const auto& [fields, message] : std::vector<std::pair<std::string, std::string>>{
           {"MPCHG,2", "MPCHG: ELEM missing"},
           {"MPCHG,,ALL", "MPCHG: MAT (the material number) missing"},
           {"MPCHG,-1,ALL", "MPCHG: material number -1 must be positive"},
           {"MPCHG,2,7", "MPCHG: element 7 is not defined"},
           {"MPCHG,2,P", "MPCHG: graphical picking (P)"},
           {"MPCHG,3,ALL", "element 1 (LINK180): material 3 is not defined"}}) {
    const std::string err =
        error_of("mpchg_bad", bar_deck("LINK180", "1", kRho,
                                       fmt::format("MP,EX,2,{}\n/PREP7\n{}\n/SOLU\nANTYPE,STATIC\n"
                                                   "F,2,FX,1000\nSOLVE\n",
                                                   2 * kE, fields)));
    EXPECT_NE(err.find(message), std::string::npos) << fields << ": " << err;
  }
}

TEST(AcceptedFields, Solid185MixedFormulationIsRefused) {
  const std::string deck =
      "/PREP7\nET,1,SOLID185\nKEYOPT,1,6,1\nMP,EX,1,200E9\nMP,NUXY,1,0.3\n"
      "N,1,0,0,0\nN,2,1,0,0\nN,3,1,1,0\nN,4,0,1,0\nN,5,0,0,1\nN,6,1,0,1\nN,7,1,1,1\nN,8,0,1,1\n"
      "E,1,2,3,4,5,6,7,8\nD,1,ALL\nD,2,ALL\nD,3,ALL\nD,4,ALL\nFINISH\n/SOLU\nANTYPE,STATIC\n"
      "F,7,FZ,1\nSOLVE\nFINISH\n";
  const std::string err = error_of("solid185_mixed", deck);
  EXPECT_NE(err.find("deck.inp:2: ET: element type 1: SOLID185 KEYOPT(6) = 1 is not carried out "
                     "(1 (mixed u-P formulation) is not implemented)"),
            std::string::npos)
      << err;
}

/// A one-element SOLID185 cube or SHELL181 square with material 1's extra MP line `extra`.
std::string elastic_deck(const std::string& type, const std::string& extra) {
  const bool shell = type == "SHELL181";
  std::string deck =
      fmt::format("/PREP7\nET,1,{}\nMP,EX,1,200E9\nMP,PRXY,1,0.3\n{}\n", type, extra);
  deck += shell ? "SECTYPE,1,SHELL\nSECDATA,0.01\n" : "";
  deck += "N,1,0,0,0\nN,2,1,0,0\nN,3,1,1,0\nN,4,0,1,0\n";
  deck += shell ? "E,1,2,3,4\n" : "N,5,0,0,1\nN,6,1,0,1\nN,7,1,1,1\nN,8,0,1,1\nE,1,2,3,4,5,6,7,8\n";
  deck += shell ? "D,1,ALL\nD,2,ALL\nD,4,ALL\n"
                : "D,1,ALL\nD,2,ALL\nD,4,ALL\nD,5,ALL\nD,6,ALL\nD,8,ALL\n";
  deck += "FINISH\n/SOLU\nF,3,FZ,1\n";
  deck += "SOLVE\nFINISH\n";
  return deck;
}

TEST(AcceptedFields, OrthotropicConstantsAreRefused) {
  // EY, PRYZ or a shear modulus other than EX / (2 (1 + PRXY)) would be left out by the
  // isotropic elements: each is refused, naming the constant.
  for (const std::string type : {"SOLID185", "SHELL181"}) {
    for (const auto& [extra, label] :
         std::vector<std::pair<std::string, std::string>>{{"MP,EY,1,100E9", "EY = 1e+11"},
                                                          {"MP,PRYZ,1,0.2", "PRYZ = 0.2"},
                                                          {"MP,GXY,1,50E9", "GXY = 5e+10"}}) {
      // SHELL181 carries out an orthotropic layer (EY, GXY) through its section
      // (shell_laminate.h, test_shell_laminate.cpp); PRYZ does not enter a shell and is refused.
      if (type == "SHELL181" && label != "PRYZ = 0.2") continue;
      const std::string err = error_of("orthotropic_" + type, elastic_deck(type, extra));
      EXPECT_NE(err.find("material 1 is anisotropic (" + label), std::string::npos)
          << type << " " << extra << ": " << err;
    }
  }
}

TEST(AcceptedFields, IsotropicValuesOfTheOrthotropicLabelsAreAccepted) {
  // EY = EX, PRXZ = PRXY and G = E / (2 (1 + nu)) rounded to four digits describe the isotropic
  // solid: the run goes on.
  const std::string extra = "MP,EY,1,200E9\nMP,EZ,1,200E9\nMP,PRXZ,1,0.3\nMP,GXY,1,76.92E9";
  for (const std::string type : {"SOLID185", "SHELL181"})
    EXPECT_EQ(error_of("isotropic_" + type, elastic_deck(type, extra)), "") << type;
}

}  // namespace
}  // namespace impactfe::test_accepted_fields
