// RSYS in POST1: nodal vector results and element stress components in the global, a
// cylindrical, a LOCAL or the solution systems (MAPDL RSYS). Node 2 at (0, 10) is held by a bar
// along Y (to node 1) and one along X (to node 3): F = (1000, 500) gives U = (FX L/EA, FY L/EA) =
// (1e-3, 5e-4) in global axes. At node 2 the cylindrical radial axis is +Y and the tangential axis
// −X: (U_R, U_T) = (UY, −UX); LOCAL,11 rotated 90 degrees about Z has x' = Y, y' = −X alike.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "../support/run_deck.h"

namespace impactfe::test_post1_rsys {
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

// A SHELL181 strip in the vertical plane through d = (cos 30°, sin 30°, 0) and w = Z, I-J along
// w: element axes x = w, y = d. ν = 0 and the edge I-J held: the strip pulled along d by F is in
// uniaxial stress σ = F/(b t) d ⊗ d. In global axes SX = σ cos²30°, SY = σ sin²30°,
// SXY = σ cos30° sin30°, SZ = 0; as the element stores it (RSYS,SOLU) SX = 0, SY = σ; in the
// global cylindrical system (RSYS,1) at the centroid, whose radial axis is d, SX = σ, SY = 0.
const char* kShellStrip =
    "/PREP7\nET,1,SHELL181\nSECTYPE,1,SHELL\nSECDATA,0.1\nMP,EX,1,2E5\nMP,PRXY,1,0\n"
    "CA=COS(30*ACOS(-1)/180)\nSA=SIN(30*ACOS(-1)/180)\n"
    "N,1,0,0,0\nN,2,0,0,1\nN,3,2*CA,2*SA,1\nN,4,2*CA,2*SA,0\nE,1,2,3,4\n"
    "D,1,ALL\nD,2,ALL\nFINISH\n/SOLU\nF,3,FX,5*CA\nF,3,FY,5*SA\nF,4,FX,5*CA\nF,4,FY,5*SA\n"
    "SOLVE\nFINISH\n/POST1\nSET,LAST\n";

TEST(Post1Rsys, ShellStressesAreRotatedFromTheElementAxesIntoTheResultsSystem) {
  const auto run = testing::run_deck_text(
      "post1_rsys_shell",
      std::string(kShellStrip) +
          "ETABLE,GX,S,X\nETABLE,GY,S,Y\nETABLE,GXY,S,XY\nETABLE,GZ,S,Z\n"
          "*GET,GX,ETAB,1,ELEM,1\n*GET,GY,ETAB,2,ELEM,1\n*GET,GXY,ETAB,3,ELEM,1\n"
          "*GET,GZ,ETAB,4,ELEM,1\n*GET,NX,NODE,3,S,X\n*GET,NXY,NODE,3,S,XY\n"
          "RSYS,SOLU\n*GET,SOLX,ELEM,1,S,X\n*GET,SOLY,ELEM,1,S,Y\n"
          "RSYS,1\n*GET,CX,ELEM,1,S,X\n*GET,CY,ELEM,1,S,Y\n*GET,CEQV,ELEM,1,S,EQV\n"
          "/OUT,rsys,txt\n*VWRITE,GX,GY,GXY,GZ\n(4E20.11)\n*VWRITE,NX,NXY,SOLX,SOLY\n(4E20.11)\n"
          "*VWRITE,CX,CY,CEQV\n(3E20.11)\n/OUT\n");
  const auto v = numbers_in(run, "rsys.txt");
  ASSERT_EQ(v.size(), 11u);
  const double sigma = 10.0 / (1.0 * 0.1), c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  const double tol = 1e-9 * sigma;
  EXPECT_NEAR(v[0], sigma * c * c, tol);  // ETABLE under the default RSYS,0: global
  EXPECT_NEAR(v[1], sigma * s * s, tol);
  EXPECT_NEAR(v[2], sigma * c * s, tol);
  EXPECT_NEAR(v[3], 0.0, tol);
  EXPECT_NEAR(v[4], sigma * c * c, tol);  // nodal average (one element): global
  EXPECT_NEAR(v[5], sigma * c * s, tol);
  EXPECT_NEAR(v[6], 0.0, tol);  // RSYS,SOLU: element axes x = w, y = d
  EXPECT_NEAR(v[7], sigma, tol);
  EXPECT_NEAR(v[8], sigma, tol);  // RSYS,1: radial = d
  EXPECT_NEAR(v[9], 0.0, tol);
  EXPECT_NEAR(v[10], sigma, tol);  // invariants do not depend on the system
}

// A SOLID185 cube pulled along X (ν = 0): σ = F/A X ⊗ X in global axes; in LOCAL,11 rotated
// 30° about Z (x' = (cos30°, sin30°, 0), y' = (−sin30°, cos30°, 0)) SX = σ cos²30°,
// SXY = −σ cos30° sin30°, both for the element value and the nodal average.
TEST(Post1Rsys, SolidStressesAreRotatedIntoALocalSystem) {
  const auto run = testing::run_deck_text(
      "post1_rsys_solid",
      "/PREP7\nET,1,SOLID185\nMP,EX,1,2E5\nMP,PRXY,1,0\nBLOCK,0,1,0,1,0,1\nESIZE,1\n"
      "VMESH,1\nNSEL,S,LOC,X,0\nD,ALL,UX\nNSEL,R,LOC,Y,0\nD,ALL,UY\nNSEL,R,LOC,Z,0\nD,ALL,UZ\n"
      "NSEL,S,LOC,X,0\nNSEL,R,LOC,Y,0\nD,ALL,UZ\nNSEL,S,LOC,X,0\nNSEL,R,LOC,Z,0\nD,ALL,UY\n"
      "NSEL,S,LOC,X,1\nF,ALL,FX,2.5\nALLSEL\nLOCAL,11,0,0,0,0,30\nCSYS,0\nFINISH\n"
      "/SOLU\nSOLVE\nFINISH\n/POST1\nSET,LAST\n*GET,GX,ELEM,1,S,X\nRSYS,11\n"
      "*GET,LX,ELEM,1,S,X\n*GET,LXY,ELEM,1,S,XY\nNSEL,S,LOC,X,1\n*GET,NMAX,NODE,0,NUM,MAX\n"
      "ALLSEL\n*GET,NX,NODE,NMAX,S,X\n*GET,NXY,NODE,NMAX,S,XY\n"
      "/OUT,rsys,txt\n*VWRITE,GX,LX,LXY,NX,NXY\n(5E20.11)\n/OUT\n");
  const auto v = numbers_in(run, "rsys.txt");
  ASSERT_EQ(v.size(), 5u);
  const double sigma = 10.0, c = std::cos(M_PI / 6), s = std::sin(M_PI / 6), tol = 1e-8;
  EXPECT_NEAR(v[0], sigma, tol);
  EXPECT_NEAR(v[1], sigma * c * c, tol);
  EXPECT_NEAR(v[2], -sigma * c * s, tol);
  EXPECT_NEAR(v[3], sigma * c * c, tol);
  EXPECT_NEAR(v[4], -sigma * c * s, tol);
}

TEST(Post1Rsys, RefusesWhatItDoesNotCarryOut) {
  for (const char* tail : {"RSYS,LSYS\n", "RSYS,12\n"}) {
    SCOPED_TRACE(tail);
    EXPECT_THROW(testing::run_deck_text("post1_rsys_refused", std::string(kTruss) + tail),
                 InputError);
  }
}

}  // namespace
}  // namespace impactfe::test_post1_rsys
