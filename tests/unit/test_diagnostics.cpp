// Diagnostics that are warnings or summary notes rather than errors (issue 12); the errors are
// malformed decks (tests/decks/malformed/, each with its exit status and message). Also the
// rule that every error escaping a solution names a deck command, and the translation of
// library failures into the program's words.
#include <gtest/gtest.h>

#include <fstream>
#include <new>
#include <sstream>

#include "../support/run_deck.h"
#include "core/log.h"

namespace impactfe::test_diagnostics {
namespace {

namespace fs = std::filesystem;

/// Runs deck text through the job session; returns the warnings logged.
std::vector<std::string> run_collecting_warnings(const std::string& tag, const std::string& text,
                                                 testing::DeckRun* run_out = nullptr) {
  const fs::path dir = testing::fresh_directory(tag);
  const fs::path deck = dir / (tag + ".inp");
  std::ofstream(deck) << text;
  Log::clear();
  testing::DeckRun run = testing::run_deck_in(deck.string(), dir);
  if (run_out) *run_out = std::move(run);
  return Log::warnings();
}

bool any_contains(const std::vector<std::string>& lines, const std::string& part) {
  for (const auto& l : lines)
    if (l.find(part) != std::string::npos) return true;
  return false;
}

TEST(Diagnostics, TransientWithMasslessDofsWarnsAndNamesThem) {
  // A mass on node 2, a massless node 3 between two springs: UX@3 has stiffness but no mass.
  const auto warnings = run_collecting_warnings(
      "massless",
      "/PREP7\nET,1,COMBIN14,,1\nET,2,MASS21,,,4\nR,1,100\nR,2,1\nN,1\nN,2,1\nN,3,2\nE,1,2\n"
      "E,2,3\nTYPE,2\nREAL,2\nE,2\nFINISH\n/SOLU\nANTYPE,TRANS\nD,1,ALL\nD,ALL,UY\nF,3,FX,1\n"
      "TIME,0.01\nDELTIM,0.001\nSOLVE\nFINISH\n");
  EXPECT_TRUE(any_contains(warnings, "1 free translational DOF(s) have stiffness but no mass"))
      << warnings.size();
  EXPECT_TRUE(any_contains(warnings, "UX@3"));
  EXPECT_FALSE(any_contains(warnings, "UX@2"));
}

TEST(Diagnostics, StaticWithMasslessDofsDoesNotWarn) {
  const auto warnings = run_collecting_warnings(
      "massless_static",
      "/PREP7\nET,1,COMBIN14,,1\nR,1,100\nN,1\nN,2,1\nE,1,2\nFINISH\n/SOLU\nANTYPE,STATIC\n"
      "D,1,ALL\nD,ALL,UY\nF,2,FX,1\nSOLVE\nFINISH\n");
  EXPECT_FALSE(any_contains(warnings, "but no mass"));
}

TEST(Diagnostics, NegativePivotOfTransientEffectiveMatrixWarns) {
  // Two collinear springs with stress stiffening and a large compressive preload P: the
  // transverse tangent at node 2 is -2P/L, the mass term m/(beta h^2) is smaller with h = 1, so
  // the effective matrix has a negative pivot there (the Euler buckling mode of the chain).
  const auto warnings = run_collecting_warnings(
      "negative_pivot",
      "/PREP7\nET,1,LINK180\nSECTYPE,1,LINK\nSECDATA,1\nMP,EX,1,1E6\nET,2,MASS21,,,4\nR,2,1\n"
      "N,1\nN,2,1\nN,3,2\nE,1,2\nE,2,3\nTYPE,2\nREAL,2\nE,2\nE,3\nFINISH\n/SOLU\n"
      "ANTYPE,TRANS\nSSTIF,ON\nD,1,ALL\nD,ALL,UZ\nD,3,UY\nF,3,FX,-1000\nTIME,3\nDELTIM,1\n"
      "SOLVE\nFINISH\n");
  EXPECT_TRUE(any_contains(warnings, "negative pivot")) << (warnings.empty() ? "" : warnings[0]);
  EXPECT_TRUE(any_contains(warnings, "node 2 UY"));
  EXPECT_TRUE(any_contains(warnings, "smaller time step"));
}

TEST(Diagnostics, GapThatNeverClosesIsSaidSoInTheSummary) {
  // The thesis car crash with its gap widened so that the car never reaches the wall.
  std::ifstream in(std::string(IMPACTFE_TEST_DECKS) + "/modern/crash1_modern.inp");
  std::stringstream s;
  s << in.rdbuf();
  std::string text = s.str();
  const std::string gap = "GP,10,7,FX,1000,0.1";
  text.replace(text.find(gap), gap.size(), "GP,10,7,FX,1000,100");
  testing::DeckRun run;
  run_collecting_warnings("gap_never_closed", text, &run);
  bool said = false;
  for (const auto& a : run.statistics.analyses)
    for (const auto& note : a.notes) {
      EXPECT_EQ(note.find("nan"), std::string::npos) << note;
      said = said || note.find("gap 1: never closed") != std::string::npos;
    }
  EXPECT_TRUE(said);
}

TEST(Diagnostics, ErrorsWithoutALocationGainTheCommandsLocation) {
  const SourceLocation solve{"deck.inp", 12, "SOLVE"};
  const auto located = [&](auto thrower) -> std::string {
    try {
      try {
        thrower();
      } catch (...) {
        rethrow_at(solve);
      }
    } catch (const SolutionError& e) {
      return "2 " + std::string(e.what());
    } catch (const LocatedError& e) {
      return "1 " + std::string(e.what());
    } catch (const InternalError& e) {
      return "3 " + std::string(e.what());
    }
    return "";
  };
  EXPECT_EQ(located([] { throw ModelError("singular"); }), "1 deck.inp:12: SOLVE: singular");
  EXPECT_EQ(located([] { throw SolutionError("diverged"); }), "2 deck.inp:12: SOLVE: diverged");
  // A location of its own is kept (the F command that put a load on a mechanism).
  EXPECT_EQ(located([] {
              throw ModelError(SourceLocation{"deck.inp", 7, "F"}, "mechanism");
            }),
            "1 deck.inp:7: F: mechanism");
  EXPECT_EQ(located([] { throw std::bad_alloc(); }).substr(0, 32),
            "2 deck.inp:12: SOLVE: out of mem");
  EXPECT_EQ(located([] { throw std::runtime_error("cannot write row"); }),
            "2 deck.inp:12: SOLVE: the solution failed: cannot write row");
  EXPECT_EQ(located([] { throw std::out_of_range("map::at"); }).substr(0, 2), "3 ");
}

}  // namespace
}  // namespace impactfe::test_diagnostics
