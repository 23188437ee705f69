// Valid input of the Mechanical APDL Verification Manual decks that the reader refused: each
// form as the VM decks write it, carried out as MAPDL defines it (MAPDL Command Reference).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../support/run_deck.h"
#include "core/dof.h"
#include "deck/deck_reader.h"

namespace impactfe::test_deck_vm_inputs {
namespace {

Job read_modern(const std::string& text) {
  std::ostringstream sink;
  DeckOptions o;
  o.dialect = Dialect::Modern;
  o.output = &sink;
  return read_deck_text(text, "mem.inp", o);
}

std::string error_of(const std::string& text) {
  try {
    read_modern(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

/// The numbers a deck wrote with *VWRITE to `name` in the run's directory, in order.
std::vector<double> numbers_in(const testing::DeckRun& run, const std::string& name) {
  std::ifstream in(run.directory / name);
  std::vector<double> out;
  double v = 0.0;
  while (in >> v) out.push_back(v);
  return out;
}

// A bar pulled by 100 then by 200 in two load steps: u = FL/(EA) = 1e-5 and 2e-5.
const char* const kTwoLoadSteps =
    "/PREP7\nET,1,LINK180\nSECTYPE,1,LINK\nSECDATA,1\nMP,EX,1,1E7\nN,1\nN,2,1\nE,1,2\n"
    "FINISH\n/SOLU\nANTYPE,STATIC\nD,1,ALL\nD,2,UY,,,,,UZ\nF,2,FX,100\nSOLVE\nF,2,FX,200\n"
    "SOLVE\nFINISH\n";

// SET,n,0 (vm136): a zero Sbstep is a blank one, the last substep of load step n (MAPDL SET);
// FILE with a blank Fname names the jobname's file (FILE,,RDSP in vm71, vm72, vm84).
TEST(DeckVmInputs, SetWithSubstepZeroAndFileWithBlankName) {
  const auto run = testing::run_deck_text(
      "vm_set_zero", std::string(kTwoLoadSteps) +
                         "/POST1\nFILE,,RST\nSET,2,0\n*GET,U2,NODE,2,U,X\nSET,1,0\n"
                         "*GET,U1,NODE,2,U,X\n/OUT,set_zero,txt\n*VWRITE,U1,U2\n(2E18.9)\n/OUT\n");
  const auto v = numbers_in(run, "set_zero.txt");
  ASSERT_EQ(v.size(), 2u);
  EXPECT_NEAR(v[0], 1e-5, 1e-12);
  EXPECT_NEAR(v[1], 2e-5, 1e-12);
}

// *GET,Par,NODE,n,S,X (vm5): the nodal stress, the elements' integration-point stresses
// extrapolated to the node and averaged. A strip of two PLANE182 (incompatible modes, unit
// thickness) under an end couple M = 100: σx = 6M/h² = 600 at the bottom fibre, exact at the
// clamped node (one element) and at the node the two elements share.
TEST(DeckVmInputs, GetNodeStressOfPlaneSolids) {
  const auto run = testing::run_deck_text(
      "vm_get_node_s",
      "/PREP7\nET,1,PLANE182,3\nMP,EX,1,2E5\nMP,NUXY,1,0.3\nN,1\nN,2,2\nN,3,4\nN,4,0,1\n"
      "N,5,2,1\nN,6,4,1\nE,1,2,5,4\nE,2,3,6,5\nFINISH\n/SOLU\nD,1,UX,,,,,UY\nD,4,UX\n"
      "F,3,FX,100\nF,6,FX,-100\nSOLVE\nFINISH\n/POST1\nSET,LAST\n*GET,S1,NODE,1,S,X\n"
      "*GET,S2,NODE,2,S,X\n*GET,S5,NODE,5,S,X\n/OUT,node_s,txt\n*VWRITE,S1,S2,S5\n(3E18.9)\n"
      "/OUT\n");
  const auto v = numbers_in(run, "node_s.txt");
  ASSERT_EQ(v.size(), 3u);
  EXPECT_NEAR(v[0], 600.0, 1e-6);
  EXPECT_NEAR(v[1], 600.0, 1e-6);
  EXPECT_NEAR(v[2], -600.0, 1e-6);
}

// *GET,Par,PLNSOL,0,MIN|MAX (14 VM decks): the extremes of the last contour picture. Three
// plane-stress PLANE182 in a row, thicknesses 1, 2, 1, ν = 0, pulled by 100: σx = 100, 50, 100
// exactly. PLNSOL averages the elements at a node (75 where the thin and thick meet), PLESOL
// draws each element's own values (50 in the middle one).
TEST(DeckVmInputs, GetExtremesOfTheLastContourPicture) {
  const auto run = testing::run_deck_text(
      "vm_get_plnsol",
      "/PREP7\nET,1,PLANE182,,,3\nR,1,1\nR,2,2\nMP,EX,1,2E5\nMP,NUXY,1,0\nN,1\nN,2,1\nN,3,2\n"
      "N,4,3\nN,5,0,1\nN,6,1,1\nN,7,2,1\nN,8,3,1\nREAL,1\nE,1,2,6,5\nREAL,2\nE,2,3,7,6\n"
      "REAL,1\nE,3,4,8,7\nFINISH\n/SOLU\nD,1,UX,,,,,UY\nD,5,UX\nF,4,FX,50\nF,8,FX,50\n"
      "SOLVE\nFINISH\n/POST1\nSET,LAST\nPLNSOL,S,X\n*GET,NMIN,PLNSOL,0,MIN\n"
      "*GET,NMAX,PLNSOL,0,MAX\nPLESOL,S,X\n*GET,EMIN,PLNSOL,0,MIN\n*GET,EMAX,PLNSOL,0,MAX\n"
      "/OUT,contour_range,txt\n*VWRITE,NMIN,NMAX,EMIN,EMAX\n(4E18.9)\n/OUT\n");
  const auto v = numbers_in(run, "contour_range.txt");
  ASSERT_EQ(v.size(), 4u);
  EXPECT_NEAR(v[0], 75.0, 1e-7);
  EXPECT_NEAR(v[1], 100.0, 1e-7);
  EXPECT_NEAR(v[2], 50.0, 1e-7);
  EXPECT_NEAR(v[3], 100.0, 1e-7);
  EXPECT_NE(error_of("/POST1\n*GET,X,PLNSOL,0,MIN\n").find("no contour picture"),
            std::string::npos);
}

// DERIV with a blank IX (vm84, vm85) differentiates with respect to variable 1, the time; RESUME
// in POST26 (vm81, vm182) brings back the parameters a SAVE kept.
TEST(DeckVmInputs, DerivWithBlankArgumentAndResumeInPost26) {
  // A free mass of 2 pushed by 4 from rest: x = t^2, v = 2t (average-acceleration Newmark is
  // exact for a constant force).
  const auto run = testing::run_deck_text(
      "vm_deriv_blank",
      "/PREP7\nET,1,MASS21,,,4\nR,1,2\nN,1\nE,1\nFINISH\n/SOLU\nANTYPE,TRANS\nD,1,UY\n"
      "F,1,FX,4\nKBC,1\nTIME,1\nNSUBST,20\nOUTRES,ALL,ALL\nSOLVE\nFINISH\n"
      "/POST26\nNSOL,2,1,U,X\nDERIV,3,2,,,VX\nINT1,4,3,,,XAGAIN\n*GET,V,VARI,3,RTIME,0.5\n"
      "*GET,X,VARI,4,RTIME,0.5\nKEPT=1\nSAVE,vm_kept,db\nKEPT=2\nRESUME,vm_kept,db\n"
      "/OUT,deriv,txt\n*VWRITE,V,X,KEPT\n(3E18.9)\n/OUT\n");
  const auto v = numbers_in(run, "deriv.txt");
  ASSERT_EQ(v.size(), 3u);
  EXPECT_NEAR(v[0], 1.0, 1e-9);   // v(0.5) = 2 t
  EXPECT_NEAR(v[1], 0.25, 1e-9);  // the integral of v back: x(0.5) = t^2
  EXPECT_EQ(v[2], 1.0);           // the value SAVE kept
}

// NPRINT,N (vm74, which writes NPRINT,.25): PRVAR lists every Nth stored point from the
// first; a value below 1 lists every point.
// vm217: a BEAM188's orientation node has no DOFs; PRNSOL and *GET list 0 there, as MAPDL
// does, instead of stopping. vm139: SHELL,MID with the principal stresses of a SHELL181, which
// stores its von Mises stress at the top only: S,EQV at the mid-surface from the mid-surface
// components. A plate strip of SHELL181 pulled in X by 100 per unit width (t = 1): σx = 100 at
// every surface, so SEQV = 100 at MID (and the top), S1 = 100.
TEST(DeckVmInputs, OrientationNodeListsZeroAndMidSurfaceEquivalentStress) {
  const auto run = testing::run_deck_text(
      "vm_orientation_mid_eqv",
      "/PREP7\nET,1,BEAM188\nSECTYPE,1,BEAM,RECT\nSECDATA,1,2\nMP,EX,1,2E5\nMP,PRXY,1,0.3\n"
      "N,1\nN,2,10\nN,3,0,5\nE,1,2,3\nET,2,SHELL181\nSECTYPE,2,SHELL\nSECDATA,1\nTYPE,2\n"
      "SECNUM,2\nN,11,0,20\nN,12,10,20\nN,13,10,30\nN,14,0,30\nE,11,12,13,14\nFINISH\n"
      "/SOLU\nD,1,ALL\nF,2,FY,1\nD,11,ALL\nD,14,UX,,,,,UZ,ROTX,ROTY,ROTZ\nD,12,UZ,,,,,ROTX,"
      "ROTY,ROTZ\nD,13,UZ,,,,,ROTX,ROTY,ROTZ\nF,12,FX,500\nF,13,FX,500\nSOLVE\nFINISH\n"
      "/POST1\nSET,LAST\nNSEL,S,NODE,,3\nPRNSOL,U,COMP\n*GET,U3,NODE,3,U,Y\nNSEL,ALL\n"
      "SHELL,MID\n*GET,SEQV,ELEM,2,S,EQV\n*GET,S1,ELEM,2,S,1\n/OUT,mid,txt\n"
      "*VWRITE,U3,SEQV,S1\n(3E18.9)\n/OUT\n");
  const auto v = numbers_in(run, "mid.txt");
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v[0], 0.0);
  EXPECT_NEAR(v[1], 100.0, 1e-9);
  EXPECT_NEAR(v[2], 100.0, 1e-9);
}

TEST(DeckVmInputs, NprintSetsTheStrideOfPrvar) {
  const std::string model =
      "/PREP7\nET,1,MASS21,,,4\nR,1,2\nN,1\nE,1\nFINISH\n/SOLU\nANTYPE,TRANS\nD,1,UY\n"
      "F,1,FX,4\nKBC,1\nTIME,1\nNSUBST,10\nOUTRES,ALL,ALL\nSOLVE\nFINISH\n"
      "/POST26\nNSOL,2,1,U,X\n";
  const auto listed_times = [](const testing::DeckRun& run) {
    std::ifstream in(run.directory / "list.txt");
    std::vector<double> times;
    for (std::string line; std::getline(in, line);) {
      std::istringstream fields(line);
      double t = 0.0, x = 0.0;
      if (fields >> t >> x) times.push_back(t);
    }
    return times;
  };
  const auto every_third = listed_times(
      testing::run_deck_text("vm_nprint_3", model + "NPRINT,3\n/OUT,list,txt\nPRVAR,2\n/OUT\n"));
  ASSERT_EQ(every_third.size(), 4u);  // stored points 0, 0.1, ..., 1: the 1st, 4th, 7th, 10th
  EXPECT_NEAR(every_third[0], 0.0, 1e-12);
  EXPECT_NEAR(every_third[1], 0.3, 1e-12);
  EXPECT_NEAR(every_third[3], 0.9, 1e-12);
  const auto all = listed_times(testing::run_deck_text(
      "vm_nprint_all", model + "NPRINT,.25\n/OUT,list,txt\nPRVAR,2\n/OUT\n"));
  EXPECT_EQ(all.size(), 11u);
}

// GP to a node that is not defined (vm79, vm81, vm85): a ground point (MAPDL GP: "grounded gap
// nodes need not appear elsewhere in the model"), stored as node 0; both ends undefined is an
// error.
TEST(DeckVmInputs, GapToAGroundNode) {
  const Job job = read_modern(
      "/PREP7\nET,1,MASS21,,,4\nR,1,1\nN,1\nE,1\nGP,1,20,FX,3E7,.64\n"
      "GP,3,1,FY,-200,.75\n");
  ASSERT_EQ(job.model.gap_conditions.size(), 2u);
  EXPECT_EQ(job.model.gap_conditions[0].node_i, 1);
  EXPECT_EQ(job.model.gap_conditions[0].node_j, 0);
  EXPECT_EQ(job.model.gap_conditions[1].node_i, 0);
  EXPECT_EQ(job.model.gap_conditions[1].node_j, 1);
  EXPECT_NE(error_of("/PREP7\nN,1\nGP,2,3,FX,1\n").find("neither node 2 nor node 3"),
            std::string::npos);
  EXPECT_NE(error_of("/PREP7\nN,1\nGP,1,1,FX,1\n").find("both node 1"), std::string::npos);
}

// NSEL,S,LOC,X with a blank VMIN (vm42, vm307): a blank numeric field is 0, the nodes at x = 0.
TEST(DeckVmInputs, SelectionWithBlankVmin) {
  const Job job = read_modern("/PREP7\nN,1\nN,2,1\nN,3,0,1\nNSEL,S,LOC,X\n");
  EXPECT_TRUE(job.model.selection.nodes.selected(1));
  EXPECT_FALSE(job.model.selection.nodes.selected(2));
  EXPECT_TRUE(job.model.selection.nodes.selected(3));
}

// ET,1,ETYP (vmp09-t33): a parameter gives the element number or name.
TEST(DeckVmInputs, ElementTypeGivenAsAParameter) {
  const Job job = read_modern("/PREP7\nETYP=180\nET,1,ETYP\nNAME='COMBIN14'\nET,2,NAME\n");
  EXPECT_EQ(job.model.element_types.at(1).ansys_name, "LINK180");
  EXPECT_EQ(job.model.element_types.at(2).ansys_name, "COMBIN14");
  EXPECT_NE(error_of("/PREP7\nETYP=999\nET,1,ETYP\n").find("unknown element type '999'"),
            std::string::npos);
  EXPECT_NE(error_of("/PREP7\nET,1,NOSUCH\n").find("unknown element type 'NOSUCH'"),
            std::string::npos);
}

}  // namespace
}  // namespace impactfe::test_deck_vm_inputs

namespace impactfe::test_deck_vm_inputs {
namespace {

// SHELL,Loc (vm39) chooses the surface of the shell stresses POST1 reports (TOP by default), and
// PRETAB,GRP1 prints the first group of ten element-table columns (MAPDL PRETAB). A cantilever
// strip bent by an end moment: SX at the bottom is minus SX at the top, zero at the middle.
TEST(DeckVmInputs, ShellSurfaceAndElementTableGroups) {
  const auto run = testing::run_deck_text(
      "vm_shell_surface",
      "/PREP7\nET,1,SHELL63\nR,1,0.1\nMP,EX,1,2E11\nMP,NUXY,1,0.3\nN,1\nN,2,1\nN,3,1,0.2\n"
      "N,4,0,0.2\nE,1,2,3,4\nD,1,ALL,,,4,3\nF,2,MY,-10,,3\nFINISH\n/SOLU\nSOLVE\nFINISH\n"
      "/POST1\nSET,LAST\nETABLE,STOP,S,X\nSHELL,MID\nETABLE,SMID,S,X\nSHELL,BOT\n"
      "ETABLE,SBOT,S,X\nSHELL\nETABLE,STOP2,S,X\n*GET,T,ETAB,1,ELEM,1\n*GET,M,ETAB,2,ELEM,1\n"
      "*GET,B,ETAB,3,ELEM,1\n*GET,T2,ETAB,4,ELEM,1\nPRETAB,GRP1\n"
      "/OUT,shell_surface,txt\n*VWRITE,T,M,B,T2\n(4E18.9)\n/OUT\n");
  const auto v = numbers_in(run, "shell_surface.txt");
  ASSERT_EQ(v.size(), 4u);
  EXPECT_GT(std::fabs(v[0]), 1e3);
  EXPECT_NEAR(v[2], -v[0], 1e-9 * std::fabs(v[0]));
  EXPECT_NEAR(v[1], 0.0, 1e-9 * std::fabs(v[0]));
  EXPECT_EQ(v[3], v[0]);  // SHELL with a blank Loc is TOP again
}

// The nodal values of a shell with values at its nodes (SHELL281) follow SHELL,Loc too (vm42
// read the same SX at TOP and BOT): the strip bent by an end moment, SX at a node.
TEST(DeckVmInputs, ShellSurfaceOfNodalStresses) {
  const auto run = testing::run_deck_text(
      "vm_shell_nodal_surface",
      "/PREP7\nET,1,SHELL281\nSECTYPE,1,SHELL\nSECDATA,0.1\nMP,EX,1,2E11\nMP,NUXY,1,0.3\n"
      "N,1\nN,2,1\nN,3,1,0.2\nN,4,0,0.2\nN,5,0.5\nN,6,1,0.1\nN,7,0.5,0.2\nN,8,0,0.1\n"
      "E,1,2,3,4,5,6,7,8\nD,1,ALL\nD,4,ALL\nD,8,ALL\nF,2,MY,-5\nF,3,MY,-5\nFINISH\n"
      "/SOLU\nSOLVE\nFINISH\n/POST1\nSET,LAST\n*GET,T,NODE,6,S,X\nSHELL,BOT\n"
      "*GET,B,NODE,6,S,X\nSHELL,MID\n*GET,M,NODE,6,S,X\n"
      "/OUT,nodal_surface,txt\n*VWRITE,T,B,M\n(3E18.9)\n/OUT\n");
  const auto v = numbers_in(run, "nodal_surface.txt");
  ASSERT_EQ(v.size(), 3u);
  EXPECT_GT(std::fabs(v[0]), 1e3);
  EXPECT_NEAR(v[1], -v[0], 1e-6 * std::fabs(v[0]));
  EXPECT_NEAR(v[2], 0.0, 1e-6 * std::fabs(v[0]));
}

}  // namespace
}  // namespace impactfe::test_deck_vm_inputs

namespace impactfe::test_deck_vm_inputs {
namespace {

// PARSAV / PARRES (14 VM decks stop there): SCALAR writes the scalars, ALL the arrays too;
// PARRES,NEW replaces the parameters by the file's, CHANGE adds them (MAPDL PARSAV, PARRES).
TEST(DeckVmInputs, ParametersSavedAndRestored) {
  const std::string dir = testing::fresh_directory("vm_parsav").string();
  const Job job = read_modern(
      "A = 1\n*DIM,V,,2\nV(1) = 5,6\nPARSAV,SCALAR," + dir + "/s,parm\nPARSAV,ALL," + dir +
      "/all,parm\nA = 2\nB = 3\nPARRES,NEW," + dir + "/s,parm\n*GET,NB,PARM,B,TYPE\n" +
      "/PREP7\nMP,EX,1,A\nMP,EX,2,NB\nPARRES,CHANGE," + dir + "/all,parm\nMP,EX,3,V(2)\n");
  EXPECT_DOUBLE_EQ(job.model.materials.at(1).get("EX", 0), 1.0);   // A back to 1
  EXPECT_DOUBLE_EQ(job.model.materials.at(2).get("EX", 0), -1.0);  // B gone (NEW)
  EXPECT_DOUBLE_EQ(job.model.materials.at(3).get("EX", 0), 6.0);   // the array (ALL, CHANGE)
  EXPECT_NE(error_of("PARRES,NEW," + dir + "/nothing,parm\n").find("no parameter file"),
            std::string::npos);
  // vmc5: a macro saves the parameters, clears the database and restores them; its own
  // arguments (ARG1) belong to the macro call and survive the /CLEAR.
  const Job cleared =
      read_modern("*CREATE,BASE\nPARSAV,ALL," + dir + "/m,parm\n/CLEAR,NOSTART\nPARRES,CHANGE," +
                  dir + "/m,parm\n/PREP7\nET,1,ARG1\nMP,EX,1,K\n*END\nK = 7\n*USE,BASE,180\n");
  EXPECT_EQ(cleared.model.element_types.at(1).ansys_name, "LINK180");
  EXPECT_DOUBLE_EQ(cleared.model.materials.at(1).get("EX", 0), 7.0);
}

}  // namespace
}  // namespace impactfe::test_deck_vm_inputs

namespace impactfe::test_deck_vm_inputs {
namespace {

// DSYM (vm6, vm21, vm24, vm36, vm42, ...): the selected nodes are rotated into KCN, then the
// displacement DOFs of the symmetry or antisymmetry plane are fixed (MAPDL DSYM table).
TEST(DeckVmInputs, SymmetryAndAntisymmetryConstraints) {
  auto fixed = [](const Job& job, int node) {
    std::string out;
    for (const auto& [key, value] : job.model.current.constraints)
      if (key.node == node && value == 0.0) out += dof_name(key.dof) + std::string(" ");
    return out;
  };
  const Job sym = read_modern("/PREP7\nN,1,1\nN,2,0,1\nN,3,5\nNSEL,S,NODE,,1,2\nDSYM,SYMM,X\n");
  EXPECT_EQ(fixed(sym, 1), "UX ROTY ROTZ ");
  EXPECT_EQ(fixed(sym, 2), "UX ROTY ROTZ ");
  EXPECT_EQ(fixed(sym, 3), "");  // not selected
  const Job anti = read_modern("/PREP7\nN,1,1\nDSYM,ASYM,Y\n");
  EXPECT_EQ(fixed(anti, 1), "UX UZ ROTY ");
  // KCN = 1: node 2 at θ = 90° gets its nodal x along global Y (rotated 90° about Z).
  const Job cyl = read_modern("/PREP7\nN,1,1\nN,2,0,1\nDSYM,SYMM,Y,1\n");
  EXPECT_NEAR(cyl.model.node(2).angles_deg.x(), 90.0, 1e-9);  // THXY
  EXPECT_EQ(fixed(cyl, 2), "UY ROTX ROTZ ");
  // Any earlier rotation is redefined: KCN = 0 brings the nodes back to the global axes.
  const Job back = read_modern("/PREP7\nN,2,0,1\nCSYS,1\nNROTAT,ALL\nCSYS,0\nDSYM,SYMM,Z\n");
  EXPECT_FALSE(back.model.node(2).rotated());
  EXPECT_NE(error_of("/PREP7\nN,1\nDSYM,SYMM,W\n").find("Normal 'W'"), std::string::npos);
  EXPECT_NE(error_of("/PREP7\nN,1\nDSYM,SYMM,X,12\n").find("system 12 is not defined"),
            std::string::npos);
}

}  // namespace
}  // namespace impactfe::test_deck_vm_inputs
