// RSYS in POST1: nodal vector results in the global, a cylindrical or a LOCAL system (MAPDL
// RSYS). Node 2 at (0, 10) is held by a bar along Y (to node 1) and one along X (to node 3):
// F = (1000, 500) gives U = (FX L/EA, FY L/EA) = (1e-3, 5e-4) in global axes. At node 2 the
// cylindrical radial axis is +Y and the tangential axis −X: (U_R, U_T) = (UY, −UX); LOCAL,11
// rotated 90 degrees about Z has x' = Y, y' = −X alike.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "../support/run_deck.h"

namespace impactfe {
namespace {

const char* kTruss =
    "/PREP7\nET,1,LINK180\nSECTYPE,1,LINK\nSECDATA,1\nMP,EX,1,1E7\nN,1\nN,2,0,10\nN,3,10,10\n"
    "E,1,2\nE,3,2\nD,1,ALL\nD,3,ALL\nD,2,UZ\nLOCAL,11,0,0,0,0,90\nCSYS,0\nFINISH\n"
    "/SOLU\nF,2,FX,1000\nF,2,FY,500\nSOLVE\nFINISH\n/POST1\nSET,LAST\n";

std::vector<double> numbers_in(const testing::DeckRun& run, const std::string& name) {
  std::ifstream in(run.directory / name);
  std::vector<double> out;
  double v = 0.0;
  while (in >> v) out.push_back(v);
  return out;
}

TEST(Post1Rsys, NodalDisplacementsInGlobalCylindricalAndLocalSystems) {
  const auto run =
      testing::run_deck_text("post1_rsys", std::string(kTruss) +
                                               "*GET,GX,NODE,2,U,X\n*GET,GY,NODE,2,U,Y\n"
                                               "RSYS,1\n*GET,CR,NODE,2,U,X\n*GET,CT,NODE,2,U,Y\n"
                                               "RSYS,11\n*GET,LX,NODE,2,U,X\n*GET,LY,NODE,2,U,Y\n"
                                               "RSYS,0\n*GET,BX,NODE,2,U,X\n"
                                               "/OUT,rsys,txt\n*VWRITE,GX,GY,CR,CT\n(4E20.11)\n"
                                               "*VWRITE,LX,LY,BX\n(3E20.11)\n/OUT\n");
  const auto v = numbers_in(run, "rsys.txt");
  ASSERT_EQ(v.size(), 7u);
  const double ux = 1e-3, uy = 5e-4;
  EXPECT_NEAR(v[0], ux, 1e-9);
  EXPECT_NEAR(v[1], uy, 1e-9);
  EXPECT_NEAR(v[2], uy, 1e-9);   // radial
  EXPECT_NEAR(v[3], -ux, 1e-9);  // tangential
  EXPECT_NEAR(v[4], uy, 1e-9);
  EXPECT_NEAR(v[5], -ux, 1e-9);
  EXPECT_NEAR(v[6], ux, 1e-9);
}

TEST(Post1Rsys, RefusesWhatItDoesNotCarryOut) {
  for (const char* tail : {"RSYS,SOLU\n", "RSYS,12\n", "RSYS,1\nETABLE,SX,S,X\n"}) {
    SCOPED_TRACE(tail);
    EXPECT_THROW(testing::run_deck_text("post1_rsys_refused", std::string(kTruss) + tail),
                 InputError);
  }
}

}  // namespace
}  // namespace impactfe
