// Element coordinate systems (ESYS; docs/modeling.md): a shell's element x axis is the local
// system's x axis projected on the surface. Checked through the deck reader and the static
// driver: a laminate's layer angles measured from a local x axis along global Y are the angles
// + 90° measured from a local x axis along global X (both through ESYS, so that the check does
// not depend on which side of an element the mesher makes I-J).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "../support/run_deck.h"

namespace impactfe::test_element_esys {
namespace {

using testing::last_nodal_value;
using testing::run_deck_error;

/// A 1 x 0.5 cantilever plate of an orthotropic three-layer section (angles a/b/a), clamped at
/// x = 0, a transverse force and an in-plane shear force at the corner (1, 0.5); `esys_lines`
/// set the element coordinate system before the mesh.
std::string plate(const std::string& element, double a, double b, const std::string& esys_lines) {
  return "/PREP7\nET,1," + element +
         "\nMP,EX,1,140e9\nMP,EY,1,10e9\nMP,EZ,1,10e9\nMP,PRXY,1,0.3\nMP,PRYZ,1,0.3\n"
         "MP,PRXZ,1,0.3\nMP,GXY,1,5e9\nMP,GYZ,1,3.5e9\nMP,GXZ,1,5e9\n"
         "SECTYPE,1,SHELL\nSECDATA,0.002,1," +
         std::to_string(a) + "\nSECDATA,0.004,1," + std::to_string(b) + "\nSECDATA,0.002,1," +
         std::to_string(a) + "\n" + esys_lines +
         "RECTNG,0,1,0,0.5\nESIZE,0.125\nAMESH,ALL\n"
         "NSEL,S,LOC,X,0\nD,ALL,ALL\nNSEL,S,LOC,X,1\nNSEL,R,LOC,Y,0.5\n*GET,tip,NODE,0,NUM,MAX\n"
         "F,tip,FZ,10\nF,tip,FY,2000\nALLSEL\nFINISH\n/SOLU\nANTYPE,STATIC\nSOLVE\nFINISH\n";
}

/// UX, UY, UZ of the loaded corner node (the highest-numbered node at (1, 0.5)).
std::array<double, 3> tip_displacement(const std::string& tag, const std::string& deck) {
  const testing::DeckRun run = testing::run_deck_text(tag, deck);
  const Eigen::MatrixXd x = run.reader->node_coordinates();
  const std::vector<int> ids = run.reader->node_ids();
  int tip = 0;
  for (Eigen::Index k = 0; k < x.rows(); ++k)
    if (std::abs(x(k, 0) - 1.0) < 1e-9 && std::abs(x(k, 1) - 0.5) < 1e-9)
      tip = ids[static_cast<std::size_t>(k)];
  EXPECT_GT(tip, 0);
  return {last_nodal_value(*run.reader, tip, "UX"), last_nodal_value(*run.reader, tip, "UY"),
          last_nodal_value(*run.reader, tip, "UZ")};
}

void expect_same(const std::array<double, 3>& u, const std::array<double, 3>& v) {
  const double scale = std::max({std::abs(u[0]), std::abs(u[1]), std::abs(u[2])});
  ASSERT_GT(scale, 0.0);
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(u[static_cast<std::size_t>(i)], v[static_cast<std::size_t>(i)], 1e-9 * scale)
        << "component " << i;
}

// A local system parallel to the global one, and one turned 90° about Z (x along global Y).
const char* kAlongX = "LOCAL,11,0,0,0,0,0\nCSYS,0\nESYS,11\n";
const char* kAlongY = "LOCAL,12,0,0,0,0,90\nCSYS,0\nESYS,12\n";

class ShellEsys : public ::testing::TestWithParam<const char*> {};

TEST_P(ShellEsys, LocalXAlongGlobalYTurnsTheLayersByNinetyDegrees) {
  const std::string element = GetParam();
  const auto own = tip_displacement("esys_own_" + element, plate(element, 0.0, 90.0, kAlongX));
  const auto turned =
      tip_displacement("esys_turned_" + element, plate(element, 90.0, 0.0, kAlongY));
  expect_same(own, turned);
  // The loading is not symmetric in the two directions: the angles do matter.
  const auto swapped =
      tip_displacement("esys_swapped_" + element, plate(element, 90.0, 0.0, kAlongX));
  EXPECT_GT(std::abs(swapped[2] - own[2]), 0.05 * std::abs(own[2]));
}

TEST_P(ShellEsys, LocalXAlongTheNormalTakesTheLocalYAsElementY) {
  // THZX = 90 turns the local x axis onto the plate normal (global −Z); its y axis stays global
  // Y, which becomes the element y axis: the element x axis is then global X.
  const std::string element = GetParam();
  const auto own =
      tip_displacement("esys_normal_own_" + element, plate(element, 30.0, -60.0, kAlongX));
  const auto normal =
      tip_displacement("esys_normal_" + element,
                       plate(element, 30.0, -60.0, "LOCAL,11,0,0,0,0,0,0,90\nCSYS,0\nESYS,11\n"));
  expect_same(own, normal);
}

TEST_P(ShellEsys, EmodifSetsTheSystemOfMeshedElements) {
  const std::string element = GetParam();
  std::string deck = plate(element, 90.0, 0.0, kAlongX);
  const std::string marker = "NSEL,S,LOC,X,0\n";
  deck.insert(deck.find(marker), "LOCAL,12,0,0,0,0,90\nCSYS,0\nEMODIF,ALL,ESYS,12\n");
  const auto own =
      tip_displacement("esys_emodif_own_" + element, plate(element, 0.0, 90.0, kAlongX));
  expect_same(own, tip_displacement("esys_emodif_" + element, deck));
}

INSTANTIATE_TEST_SUITE_P(Shells, ShellEsys, ::testing::Values("SHELL181", "SHELL281"));

TEST(ElementEsys, ResultAxesOfAnIsotropicShellFollowTheSystem) {
  // An isotropic plate stretched along X: SX in axes along X is SY in axes turned 90° (local x
  // along global Y, element y along −X), SXY changes sign.
  const auto deck = [](const std::string& esys_lines) {
    return "/PREP7\nET,1,SHELL181\nMP,EX,1,200e9\nMP,PRXY,1,0.3\nSECTYPE,1,SHELL\n"
           "SECDATA,0.01\n" +
           esys_lines +
           "RECTNG,0,1,0,0.5\nESIZE,0.25\nAMESH,ALL\nNSEL,S,LOC,X,0\nD,ALL,UX\nD,ALL,UZ\n"
           "D,ALL,ROTX\nD,ALL,ROTY\nD,ALL,ROTZ\nNSEL,R,LOC,Y,0\nD,ALL,UY\nNSEL,S,LOC,X,1\n"
           "F,ALL,FX,1000\nALLSEL\nFINISH\n/SOLU\nANTYPE,STATIC\nSOLVE\nFINISH\n";
  };
  const testing::DeckRun own = testing::run_deck_text("esys_iso_own", deck(kAlongX));
  const testing::DeckRun turned = testing::run_deck_text("esys_iso_turned", deck(kAlongY));
  const auto at = [](const testing::DeckRun& run, const std::string& item) {
    const auto series = run.reader->element_series(1, item);
    EXPECT_FALSE(series.empty()) << item;
    return series.empty() ? std::nan("") : series.back().second;
  };
  const double sx = at(own, "SX_TOP");
  EXPECT_GT(std::abs(sx), 1e3);
  EXPECT_NEAR(at(turned, "SY_TOP"), sx, 1e-9 * std::abs(sx));
  EXPECT_NEAR(at(turned, "SX_TOP"), at(own, "SY_TOP"), 1e-9 * std::abs(sx));
  EXPECT_NEAR(at(turned, "SXY_TOP"), -at(own, "SXY_TOP"), 1e-9 * std::abs(sx));
}

TEST(ElementEsys, RefusedWhereItIsNotCarriedOut) {
  EXPECT_NE(run_deck_error("esys_low", "/PREP7\nESYS,5\n").find("ESYS 5"), std::string::npos);
  const std::string solid =
      "/PREP7\nET,1,SOLID185\nMP,EX,1,1e5\nMP,PRXY,1,0.3\nLOCAL,11,0,0,0,0,30\nCSYS,0\nESYS,11\n"
      "BLOCK,0,1,0,1,0,1\nESIZE,1\nVMESH,ALL\nNSEL,S,LOC,X,0\nD,ALL,ALL\nNSEL,S,LOC,X,1\n"
      "F,ALL,FX,1\nALLSEL\nFINISH\n/SOLU\nSOLVE\n";
  const std::string message = run_deck_error("esys_solid", solid);
  EXPECT_NE(message.find("SOLID185 takes its axes from its nodes"), std::string::npos) << message;
  const std::string undefined =
      "/PREP7\nET,1,SHELL181\nMP,EX,1,1e5\nMP,PRXY,1,0.3\nSECTYPE,1,SHELL\nSECDATA,0.1\n"
      "ESYS,12\nRECTNG,0,1,0,1\nESIZE,1\nAMESH,ALL\nNSEL,S,LOC,X,0\nD,ALL,ALL\nALLSEL\nFINISH\n"
      "/SOLU\nSOLVE\n";
  const std::string why = run_deck_error("esys_undefined", undefined);
  EXPECT_NE(why.find("ESYS 12 is not a defined local coordinate system"), std::string::npos) << why;
}

}  // namespace
}  // namespace impactfe::test_element_esys
