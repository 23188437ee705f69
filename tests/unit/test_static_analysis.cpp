// Static analysis through the job runner: an unrestrained model stops with a message naming the
// node and DOF (issue 2), and a regular one solves (the verification decks cover the values).
#include <gtest/gtest.h>

#include <fstream>

#include "../support/run_deck.h"

namespace impactfe {
namespace {

std::string run_text_expecting_error(const std::string& text) {
  const auto dir = testing::fresh_directory("static_singular");
  const std::string deck = (dir / "singular.inp").string();
  {
    std::ofstream out(deck);
    out << text;
  }
  try {
    testing::run_deck_in(deck, dir);
  } catch (const ModelError& e) {
    return e.what();
  }
  return "";
}

TEST(StaticAnalysis, UnrestrainedModelNamesTheNodeAndDof) {
  // A spar along X fixed only in UY/UZ at both ends and in UX nowhere: rigid in X.
  const std::string message = run_text_expecting_error(
      "/PREP7\nET,1,LINK180\nSECTYPE,1,LINK\nSECDATA,1\nMP,EX,1,30E6\nN,1\nN,2,10\nE,1,2\n"
      "FINISH\n/SOLU\nANTYPE,STATIC\nD,1,UY,,,2,1,UZ\nF,2,FX,100\nSOLVE\nFINISH\n");
  EXPECT_NE(message.find("singular"), std::string::npos) << message;
  EXPECT_TRUE(message.find("node 1 UX") != std::string::npos ||
              message.find("node 2 UX") != std::string::npos)
      << message;
}

TEST(StaticAnalysis, MassOnlyDofIsSingularInAStaticSolve) {
  // A point mass hanging on nothing in Y: mass but no stiffness is legitimate in a transient and
  // singular in a static solve (spec §10.1 item 5).
  const std::string message = run_text_expecting_error(
      "/PREP7\nET,1,COMBIN14,,1\nET,2,MASS21,,,4\nR,1,100\nR,2,1\nN,1\nN,2,1\nTYPE,1\nREAL,1\n"
      "E,1,2\nTYPE,2\nREAL,2\nE,2\nFINISH\n/SOLU\nANTYPE,STATIC\nD,1,ALL\nF,2,FX,10\nSOLVE\n"
      "FINISH\n");
  EXPECT_NE(message.find("node 2 UY"), std::string::npos) << message;
}

}  // namespace
}  // namespace impactfe
