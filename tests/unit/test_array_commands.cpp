// Parameters and arrays (APDL_SCRIPTING §A.2, §A.6–§A.8) and the vector / matrix commands
// (APDL_MODELING §10.1, §10.2), checked through decks and the parameter table they leave.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "deck/deck_context.h"
#include "deck/get_hooks.h"
#include "deck/parameters.h"

namespace test_array_commands {

using namespace impactfe;
using namespace impactfe::deck;

namespace {

/// Runs a modern deck in a reader kept alive, so the test can read the parameters.
struct Session {
  std::ostringstream out;
  DeckOptions options;
  DeckReader reader;
  Session() : options(make_options(out)), reader(options, Dialect::Modern, "mem") {}
  static DeckOptions make_options(std::ostringstream& o) {
    DeckOptions d;
    d.output = &o;
    return d;
  }
  Session& run(const std::string& text) {
    reader.run_text(text, "mem.inp");
    return *this;
  }
  double num(const std::string& expr) { return evaluate(expr, reader.params); }
  std::vector<double> column(const std::string& name, int j = 1) {
    const Param* p = reader.params.find(name);
    std::vector<double> v;
    for (int i = p->low(); i <= p->imax; ++i) v.push_back(p->values[p->offset(i, j, 1)]);
    return v;
  }
  std::string text(const std::string& expr) {
    return std::get<std::string>(evaluate_value(expr, reader.params));
  }
};

std::string error_of(const std::string& text) {
  try {
    Session().run(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

using V = std::vector<double>;

TEST(GetActive, WallAndCpuTimersOfWorkbenchFiles) {
  // *GET,Par,ACTIVE,,TIME,WALL (hours since the run began) and CPU (seconds), as Workbench input
  // files read them around SOLVE.
  Session s;
  s.run(
      "*GET,W0,ACTIVE,,TIME,WALL\n*GET,C0,ACTIVE,,TIME,CPU\n*GET,W1,ACTIVE,,TIME,WALL\n"
      "DW=(W1-W0)*3600\n");
  EXPECT_GE(s.num("W0"), 0.0);
  EXPECT_LT(s.num("W0"), 1.0);  // elapsed hours, not a time of day
  EXPECT_GE(s.num("DW"), 0.0);
  EXPECT_LT(s.num("DW"), 60.0);
  EXPECT_GT(s.num("C0"), 0.0);
}

}  // namespace

TEST(ArrayCommands, ScalarsTextsAndLists) {
  Session s;
  s.run(
      "L = 10.0\nA = L/4+2**3\nTXT = 'HELLO'\n*DIM,V,ARRAY,4\nV(2) = 1.5,2.5\n*SET,W,3\n"
      "*DIM,LBL,CHAR,3\nLBL(1) = 'UX','UY','ROTZ'\n*SET,LBL(3),'R3'\nB = LBL(2)\nA =\n");
  EXPECT_EQ(s.reader.params.find("A"), nullptr);  // deleted
  EXPECT_EQ(s.column("V"), (V{0, 1.5, 2.5, 0}));
  EXPECT_EQ(s.text("TXT"), "HELLO");
  EXPECT_EQ(s.text("LBL(3)"), "R3");
  EXPECT_EQ(s.text("B"), "UY");
  EXPECT_DOUBLE_EQ(s.num("W"), 3.0);
  // Number and text swap kinds; a long text is cut with a warning.
  s.run("TXT = 4\nNUM = 'abcdefghijklmnopqrstuvwxyz0123456789'\n");
  EXPECT_DOUBLE_EQ(s.num("TXT"), 4.0);
  EXPECT_EQ(s.text("NUM").size(), 32u);
}

TEST(ArrayCommands, DimAndSubscriptErrors) {
  EXPECT_NE(error_of("*DIM,V,,3\nV(4) = 1\n").find("mem.inp:2: *SET: V(4,1,1) is out of range"),
            std::string::npos);
  EXPECT_NE(error_of("*DIM,V,,3\nV(2) = 1,2,3\n").find("V(4,1,1) is out of range"),
            std::string::npos);
  EXPECT_NE(error_of("W(1) = 1\n").find("array W is not defined (*DIM it first)"),
            std::string::npos);
  EXPECT_NE(error_of("*DIM,V,,3\nX = V(0)\n").find("out of range"), std::string::npos);
  EXPECT_NE(error_of("*DIM,V,,3\nV = 2\n").find("V is an array"), std::string::npos);
  EXPECT_NE(error_of("*DIM,V,,3\n*DIM,V,,4\n").find("V is already defined"), std::string::npos);
  EXPECT_NE(error_of("*DIM,V,,0\n").find("extent 0"), std::string::npos);
  EXPECT_NE(error_of("*DIM,V,ARR4,2\n").find("ARR4 is not supported"), std::string::npos);
  EXPECT_NE(error_of("*DIM,V,,100000,100000,100\n").find("too large"), std::string::npos);
  EXPECT_NE(error_of("*DIM,C,CHAR,2\nC(1) = 5\n").find("CHAR array"), std::string::npos);
  EXPECT_NE(error_of("ALL = 1\n").find("'ALL' is a label"), std::string::npos);
  EXPECT_NE(error_of("SIN = 1\n").find("function name"), std::string::npos);
  Session s;
  s.run("*DIM,V,,3\n*DIM,V,,3\n*DIM,G,ARRAY,2,3,4\n*DEL,V\n*DIM,V,,5\n");  // same again: no-op
  EXPECT_EQ(s.reader.params.find("V")->imax, 5);
  EXPECT_EQ(s.reader.params.find("G")->kmax, 4);
}

TEST(ArrayCommands, TableWithIndexRowAndColumn) {
  Session s;
  s.run(
      "*DIM,F,TABLE,3,1,1,TIME\nF(1,0) = 0,1,2\nF(1,1) = 0,100,100\nV = F(0.5)\n"
      "*DIM,G,TABLE,2,2\nG(1,0) = 0,10\nG(0,1) = 0\nG(0,2) = 1\nG(1,1) = 1,2\nG(1,2) = 3,4\n"
      "W = G(5,0.5)\n");
  EXPECT_DOUBLE_EQ(s.num("V"), 50.0);
  EXPECT_DOUBLE_EQ(s.num("W"), 2.5);
  EXPECT_EQ(s.reader.params.find("F")->variables[0], "TIME");
  // A %TABLE% load needs a time history (Var1 = TIME, one value column); the table loads
  // themselves are tested by tests/verification/table_load_ramp.inp.
  EXPECT_NE(
      error_of("/PREP7\nN,1\n*DIM,F,TABLE,2\nF,1,FX,%F%\n").find("has primary variable 'ROW'"),
      std::string::npos);
  EXPECT_NE(
      error_of("/PREP7\nN,1\n*DIM,F,TABLE,2,2,1,TIME\nF,1,FX,%F%\n").find("one column of values"),
      std::string::npos);
  EXPECT_NE(error_of("/PREP7\nN,1\nF,1,FX,%NOSUCH%\n").find("table %NOSUCH% is not defined"),
            std::string::npos);
}

TEST(ArrayCommands, Vfill) {
  Session s;
  s.run(
      "*DIM,A,,5\n*VFILL,A,RAMP,1,10\n*DIM,B,,5\n*VFILL,B(4),DATA,7,8\n*DIM,R,,100\n"
      "*VFILL,R,RAND,2,3\n*DIM,M,,3,2\n*VFILL,M(1,2),DATA,1,2,3\n");
  EXPECT_EQ(s.column("A"), (V{1, 11, 21, 31, 41}));
  EXPECT_EQ(s.column("B"), (V{0, 0, 0, 7, 8}));
  EXPECT_EQ(s.column("M", 2), (V{1, 2, 3}));
  for (double r : s.column("R")) {
    EXPECT_GE(r, 2.0);
    EXPECT_LE(r, 3.0);
  }
  // Values past the column's last row are not stored (nor carried into the next column), as
  // MAPDL runs vmr049-pl2a-181; a `=` list past the end stays an error.
  Session t;
  t.run("*DIM,W,,2,2\n*VFILL,W(2,1),DATA,5,6,7\n");
  EXPECT_EQ(t.column("W", 1), (V{0, 5}));
  EXPECT_EQ(t.column("W", 2), (V{0, 0}));
  EXPECT_NE(error_of("*DIM,A,,2\nA(1) = 1,2,3\n").find("out of range"), std::string::npos);
  EXPECT_NE(error_of("*DIM,A,,2\n*VFILL,A,TRIA,1\n").find("TRIA"), std::string::npos);
}

TEST(ArrayCommands, VoperArithmeticAndComparisons) {
  Session s;
  s.run(
      "*DIM,A,,4\n*DIM,B,,4\nA(1) = 1,2,3,4\nB(1) = 2,0,1,8\n*DIM,C,,4\n"
      "*VOPER,C,A(1),ADD,B(1)\n*DIM,D,,4\n*VOPER,D,A(1),DIV,B(1)\n*DIM,E,,4\n"
      "*VOPER,E,A(1),GT,B(1)\n*DIM,F,,4\n*VOPER,F,A(1),MULT,10\n*DIM,G,,4\n"
      "*VOPER,G,A(1),MAX,B(1)\n*VOPER,H(1),A(1),SUB,B(1)\n");
  EXPECT_EQ(s.column("C"), (V{3, 2, 4, 12}));
  EXPECT_EQ(s.column("D"), (V{0.5, 0, 3, 0.5}));  // x/0 gives 0
  EXPECT_EQ(s.column("E"), (V{0, 1, 1, 0}));
  EXPECT_EQ(s.column("F"), (V{10, 20, 30, 40}));
  EXPECT_EQ(s.column("G"), (V{2, 2, 3, 8}));
  EXPECT_EQ(s.column("H"), (V{-1, 2, 2, -4}));  // created by the command
}

TEST(ArrayCommands, VoperCalculus) {
  // y = x^2 on x = 0..4: INT1 (trapezoid) and DER1 (central differences, ends extrapolated).
  Session s;
  s.run(
      "*DIM,X,,5\n*DIM,Y,,5\n*VFILL,X,RAMP,0,1\n*VOPER,Y,X(1),MULT,X(1)\n*DIM,I,,5\n"
      "*VOPER,I,Y(1),INT1,X(1),1\n*DIM,D,,5\n*VOPER,D,Y(1),DER1,X(1)\n*DIM,D2,,5\n"
      "*VOPER,D2,Y(1),DER2,X(1)\n*DIM,A,,5\n*VOPER,A,X(1),INT2,X(1),0,0\n");
  EXPECT_EQ(s.column("I"), (V{1, 1.5, 4, 10.5, 23}));
  EXPECT_EQ(s.column("D"), (V{0, 2, 4, 6, 8}));  // exact for a parabola
  EXPECT_EQ(s.column("D2"), (V{2, 2, 2, 2, 2}));
  const V a = s.column("A");  // ∫∫ x = x^3/6, trapezoid errors stay small
  EXPECT_NEAR(a[4], 64.0 / 6.0, 0.35);
}

TEST(ArrayCommands, VoperVectorsAndGatherScatter) {
  Session s;
  s.run(
      "*DIM,U,,2,3\n*DIM,W,,2,3\nU(1,1) = 1,0\nU(1,2) = 0,1\nW(1,2) = 1,0\nW(1,3) = 0,1\n"
      "*DIM,DP,,2\n*VOPER,DP,U(1,1),DOT,W(1,1)\n*DIM,DU,,2\n*VOPER,DU,U(1,1),DOT,U(1,1)\n*DIM,CR,,"
      "2,3\n*VOPER,CR,U(1,1),CROSS,W(1,1)\n"
      "*DIM,P,,3\nP(1) = 3,1,2\n*DIM,S,,3\nS(1) = 10,20,30\n*DIM,GA,,3\n"
      "*VOPER,GA,S(1),GATH,P(1)\n*DIM,SC,,3\n*VOPER,SC,S(1),SCAT,P(1)\n");
  // Rows of U: e_x, e_y; rows of W: e_y, e_z.
  EXPECT_EQ(s.column("DP"), (V{0, 0}));
  EXPECT_EQ(s.column("DU"), (V{1, 1}));
  EXPECT_EQ(s.column("CR", 1), (V{0, 1}));  // e_y × e_z = e_x
  EXPECT_EQ(s.column("CR", 3), (V{1, 0}));  // e_x × e_y = e_z
  EXPECT_EQ(s.column("GA"), (V{30, 10, 20}));
  EXPECT_EQ(s.column("SC"), (V{20, 30, 10}));
}

TEST(ArrayCommands, SettingsApplyOnceThenReset) {
  Session s;
  s.run(
      "*DIM,A,,4\nA(1) = 1,-2,3,-4\n*DIM,M,,4\nM(1) = 1,0,1,0\n*DIM,B,,4\n"
      "*VFACT,10,2\n*VMASK,M(1)\n*VOPER,B,A(1),ADD,1\n*DIM,C,,4\n*VOPER,C,A(1),ADD,1\n"
      "*DIM,D,,4\n*VABS,1,1\n*VOPER,D,A(1),SUB,0\n*DIM,E,,4\nE(1) = 100,100,100,100\n"
      "*VCUM,1\n*VOPER,E,A(1),ADD,0\n*DIM,F,,6\n*VLEN,2,2\n*VFILL,F,RAMP,1,1\n");
  EXPECT_EQ(s.column("B"), (V{10 * (2 + 1), 0, 10 * (6 + 1), 0}));  // masked rows unchanged
  EXPECT_EQ(s.column("C"), (V{2, -1, 4, -3}));                      // settings were reset
  EXPECT_EQ(s.column("D"), (V{1, 2, 3, 4}));
  EXPECT_EQ(s.column("E"), (V{101, 98, 103, 96}));
  EXPECT_EQ(s.column("F"), (V{1, 0, 2, 0, 0, 0}));  // NROW 2, every second row
  s.run("*VFACT,2\n*VSTAT\n");
  EXPECT_NE(s.out.str().find("FACTR=2"), std::string::npos);
}

TEST(ArrayCommands, VfunAndVscfun) {
  Session s;
  s.run(
      "*DIM,A,,5\nA(1) = 4,1,9,16,-2\n*DIM,SQ,,4\n*VFUN,SQ,SQRT,A(1)\n*DIM,SO,,5\n"
      "*VFUN,SO,ASORT,A(1)\n*DIM,P,,5\n*VFUN,P,PWR,A(1),2\n*DIM,N,,5\n*VFUN,N,NOT,A(1)\n"
      "*VSCFUN,MXA,MAX,A(1)\n*VSCFUN,LMN,LMIN,A(1)\n*VSCFUN,SM,SUM,A(1)\n"
      "*VSCFUN,ME,MEAN,A(1)\n*VSCFUN,MD,MEDI,A(1)\n*VSCFUN,VA,VARI,A(1)\n"
      "*VSCFUN,SD,STDV,A(1)\n*VSCFUN,RM,RMS,A(1)\n*DIM,K,,5\nK(1) = 0,1,0,1,1\n*VMASK,K(1)\n"
      "*VSCFUN,NU,NUM,A(1)\n*VSCFUN,FI,FIRST,K(1)\n*VSCFUN,LA,LAST,K(1)\n*DIM,CP,,5\n"
      "*VMASK,K(1)\n*VFUN,CP,COMP,A(1)\n");
  EXPECT_EQ(s.column("SQ"), (V{2, 1, 3, 4}));
  EXPECT_EQ(s.column("SO"), (V{-2, 1, 4, 9, 16}));
  EXPECT_EQ(s.column("P"), (V{16, 1, 81, 256, -4}));  // negative base: -(|x|**2)
  EXPECT_EQ(s.column("N"), (V{0, 0, 0, 0, 1}));
  EXPECT_DOUBLE_EQ(s.num("MXA"), 16);
  EXPECT_DOUBLE_EQ(s.num("LMN"), 5);
  EXPECT_DOUBLE_EQ(s.num("SM"), 28);
  EXPECT_DOUBLE_EQ(s.num("ME"), 5.6);
  EXPECT_DOUBLE_EQ(s.num("MD"), 4);
  EXPECT_NEAR(s.num("VA"), (16 + 1 + 81 + 256 + 4) / 5.0 - 5.6 * 5.6, 1e-12);  // population
  EXPECT_NEAR(s.num("SD"), std::sqrt(s.num("VA")), 1e-12);
  EXPECT_NEAR(s.num("RM"), std::sqrt((16 + 1 + 81 + 256 + 4) / 5.0), 1e-12);
  EXPECT_DOUBLE_EQ(s.num("NU"), 3);  // masked count
  EXPECT_DOUBLE_EQ(s.num("FI"), 2);
  EXPECT_DOUBLE_EQ(s.num("LA"), 5);
  EXPECT_EQ(s.column("CP"), (V{1, 16, -2, 0, 0}));
  EXPECT_NE(error_of("*DIM,A,,2\nA(1)=-1,1\n*DIM,B,,2\n*VFUN,B,SQRT,A(1)\n").find("row 1"),
            std::string::npos);
}

TEST(ArrayCommands, PrincipalStresses) {
  Session s;
  s.run(
      "*DIM,ST,,1,6\nST(1,1) = 100\nST(1,2) = 0\nST(1,4) = 0\n*DIM,PR,,1,5\n"
      "*VFUN,PR(1,1),PRIN,ST(1,1)\n");
  const Param* p = s.reader.params.find("PR");
  EXPECT_DOUBLE_EQ(p->values[p->offset(1, 1, 1)], 100.0);  // S1
  EXPECT_DOUBLE_EQ(p->values[p->offset(1, 4, 1)], 100.0);  // SINT
  EXPECT_DOUBLE_EQ(p->values[p->offset(1, 5, 1)], 100.0);  // SEQV
}

TEST(ArrayCommands, MatrixOperations) {
  Session s;
  s.run(
      "*DIM,A,,2,2\nA(1,1) = 2,1\nA(1,2) = 1,3\n*DIM,B,,2,1\nB(1,1) = 3,5\n"
      "*MOPER,X(1,1),A(1,1),SOLV,B(1,1)\n*MOPER,AI(1,1),A(1,1),INVERT\n"
      "*MOPER,P(1,1),A(1,1),MULT,B(1,1)\n*MFUN,T(1,1),TRAN,A(1,1)\n*MFUN,CPY(1,1),COPY,A(1,1)\n");
  EXPECT_NEAR(s.num("X(1,1)"), 0.8, 1e-15);
  EXPECT_NEAR(s.num("X(2,1)"), 1.4, 1e-15);
  EXPECT_NEAR(s.num("AI(1,1)"), 0.6, 1e-15);
  EXPECT_NEAR(s.num("AI(1,2)"), -0.2, 1e-15);
  EXPECT_EQ(s.column("P"), (V{11, 18}));
  EXPECT_DOUBLE_EQ(s.num("T(1,2)"), 1.0);
  EXPECT_DOUBLE_EQ(s.num("CPY(2,2)"), 3.0);
  EXPECT_NE(error_of("*DIM,A,,2,2\n*MOPER,X(1,1),A(1,1),INVERT\n").find("singular"),
            std::string::npos);
}

TEST(ArrayCommands, VgetFromTheModelAndAssignmentInterface) {
  Session s;
  s.run(
      "/PREP7\nET,1,LINK180\nN,1,0,0,0\nN,2,2,0,0\nN,4,5,1,0\nE,1,2\nE,2,4\n"
      "*VGET,X,NODE,1,LOC,X\n*DIM,NS,,4\n*VGET,NS,NODE,1,NSEL\n*DIM,EN,,2\n"
      "*VGET,EN,ELEM,1,NODE,2\n*DIM,AT,,2\n*VGET,AT(1),ELEM,1,ATTR,TYPE\n"
      "*DIM,NN,,3\n*VGET,NN,ELEM,2,NODE,1,,,4\n");
  EXPECT_EQ(s.column("X"), (V{0, 2, 0, 5}));  // created: length = highest node; missing → 0
  EXPECT_EQ(s.column("NS"), (V{1, 1, 0, 1}));
  EXPECT_EQ(s.column("EN"), (V{2, 4}));
  EXPECT_EQ(s.column("AT"), (V{1, 1}));
  EXPECT_EQ(s.column("NN"), (V{2, 4, 0}));  // KLOOP 4: IT1NUM = 1, 2, 3
  // The assignment interface used by *GET / POST26 VGET.
  Command c;
  c.name = "*GET";
  c.where = {"mem.inp", 9, "*GET"};
  assign_parameter(s.reader, c, "Q", 2.5);
  assign_parameter(s.reader, c, "NS(1+1)", 7.0);
  assign_text_parameter(s.reader, c, "LAB", "UX");
  assign_vector(s.reader, c, "X(2)", {8, 9});
  EXPECT_DOUBLE_EQ(s.num("Q"), 2.5);
  EXPECT_EQ(s.column("NS"), (V{1, 7, 0, 1}));
  EXPECT_EQ(s.text("LAB"), "UX");
  EXPECT_EQ(s.column("X"), (V{0, 8, 9, 5}));
  EXPECT_EQ(read_vector(s.reader, c, "X(3)", 2), (V{9, 5}));
  EXPECT_THROW(assign_vector(s.reader, c, "X(3)", {1, 2, 3}), InputError);
  assign_vector(s.reader, c, "NOPE(1)", {1});  // created, as POST26 VGET creates its array
  EXPECT_EQ(s.column("NOPE"), (V{1}));
  EXPECT_THROW(read_vector(s.reader, c, "X(4)", 2), InputError);
  try {
    assign_parameter(s.reader, c, "NS(9)", 1.0);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("mem.inp:9: *GET: NS(9,1,1) is out of range"),
              std::string::npos);
  }
  // PARM items and *GET-style items through the provider table.
  GetItem q;
  q.entity = "PARM";
  q.entname = "NS";
  q.item1 = "DIM";
  q.it1num = "X";
  EXPECT_EQ(std::get<double>(get_item(s.reader, c, q)), 4.0);
  q.item1 = "TYPE";
  EXPECT_EQ(std::get<double>(get_item(s.reader, c, q)), 1.0);
  q.entity = "NODE";
  q.entnum = 4;
  q.item1 = "LOC";
  q.it1num = "Y";
  EXPECT_EQ(std::get<double>(get_item(s.reader, c, q)), 1.0);
  q.item1 = "U";
  EXPECT_THROW(get_item(s.reader, c, q), InputError);  // a results item: not the model's
  EXPECT_NE(error_of("*DIM,V,,2\n*VPUT,V,NODE,1,U,X\n").find("cannot be stored into"),
            std::string::npos);
}

// The assignment interface the *GET / POST26 handlers of the post branch store through.
TEST(ArrayCommands, ElementLengthOfLineAndPointElements) {
  // LENG of a point element is 0 (found by the fuzzer: a MATRIX50 record, whose nodes come from
  // its file, has none, and LENG read past its empty node list).
  Session s;
  s.run(
      "/PREP7\nET,1,LINK180\nET,2,MASS21\nN,1,0,0,0\nN,2,3,4,0\nE,1,2\nTYPE,2\nE,2\n"
      "*GET,L1,ELEM,1,LENG\n*GET,L2,ELEM,2,LENG\n");
  EXPECT_DOUBLE_EQ(s.num("L1"), 5.0);
  EXPECT_DOUBLE_EQ(s.num("L2"), 0.0);
}

TEST(ArrayCommands, AssignmentInterface) {
  Session s;
  s.run("*DIM,A,ARRAY,4,2\n*DIM,L,CHAR,2\nT = 'AB'\n");
  Command c;
  c.name = "*GET";
  c.where = {"mem.inp", 9, "*GET"};
  assign_parameter(s.reader, c, "X", 2.5);
  assign_parameter(s.reader, c, "A(2,2)", -1.0);
  assign_text_parameter(s.reader, c, "L(2)", "R2");
  assign_vector(s.reader, c, "A(2,1)", {7, 8, 9});
  assign_vector(s.reader, c, "NEWV(3)", {1, 2});  // created, 4 rows
  EXPECT_DOUBLE_EQ(s.num("X"), 2.5);
  EXPECT_EQ(s.column("A", 1), (V{0, 7, 8, 9}));
  EXPECT_EQ(s.column("A", 2), (V{0, -1, 0, 0}));
  EXPECT_EQ(s.text("L(2)"), "R2");
  EXPECT_EQ(s.column("NEWV"), (V{0, 0, 1, 2}));
  EXPECT_EQ(read_vector(s.reader, c, "A(3,1)", 2), (V{8, 9}));
  EXPECT_THROW(read_vector(s.reader, c, "A(3,1)", 3), InputError);  // too short
  EXPECT_THROW(assign_vector(s.reader, c, "A(1,1)", {1, 2, 3, 4, 5}), InputError);
  EXPECT_THROW(assign_vector(s.reader, c, "L(1)", {1}), InputError);   // CHAR array
  EXPECT_THROW(assign_parameter(s.reader, c, "Q(1)", 1), InputError);  // not dimensioned
  const ParameterInfo a = parameter_info(s.reader, "a");
  EXPECT_EQ(a.type, 1);
  EXPECT_EQ(a.dims[0], 4);
  EXPECT_EQ(a.dims[1], 2);
  EXPECT_EQ(a.dims[2], 1);
  EXPECT_EQ(parameter_info(s.reader, "L").type, 4);
  EXPECT_EQ(parameter_info(s.reader, "T").type, 3);
  EXPECT_EQ(parameter_info(s.reader, "X").type, 0);
  EXPECT_EQ(parameter_info(s.reader, "NOPE").type, -1);
  const auto [all, basic] = parameter_counts(s.reader);
  EXPECT_EQ(all, 5);  // A L T X NEWV
  EXPECT_EQ(basic, 1);
  write_output(s.reader, "  line 1\n  line 2\n");
  EXPECT_NE(s.out.str().find("  line 1\n  line 2\n"), std::string::npos);
}

// *MFOURI (vm130): FIT finds the coefficients of a curve made of known terms (least squares,
// exact here), EVAL writes the curve back; the saw tooth of vm130 gives its Fourier
// coefficients 8/π² (−1)^k / (2k+1)² (Timoshenko).
TEST(ArrayCommands, FourierSeriesFitAndEvaluation) {
  Session s;
  s.run(
      "*DIM,TH,,37\n*VFILL,TH(1),RAMP,0,10\n*DIM,CI,,37\n*DIM,CO,,37\n"
      "*DO,I,1,37\nCI(I) = 2+3*SIN(TH(I)*3.14159265358979/180)-0.5*COS(2*TH(I)*3.14159265358979/"
      "180)\n*ENDDO\n*DIM,M,,3\nM(1) = 0,1,2\n*DIM,K,,3\nK(1) = 1,-1,0\n*DIM,A,,3\n"
      "*MFOURI,FIT,A(1),M(1),K(1),TH(1),CI(1)\n*MFOURI,EVAL,A(1),M(1),K(1),TH(1),CO(1)\n");
  const V a = s.column("A");
  EXPECT_NEAR(a[0], 2.0, 1e-12);
  EXPECT_NEAR(a[1], 3.0, 1e-12);
  EXPECT_NEAR(a[2], -0.5, 1e-12);
  const V in = s.column("CI"), out = s.column("CO");
  for (std::size_t i = 0; i < in.size(); ++i) EXPECT_NEAR(out[i], in[i], 1e-12);
  // The saw tooth of vm130 (0 → 1 → −1 → 0 over 360°, 121 points), odd sine modes 1, 3, 5.
  Session w;
  w.run(
      "*DIM,TH,,121\n*VFILL,TH(1),RAMP,0,3\n*DIM,C,,121\n*VFILL,C(1),RAMP,0,1/30\n"
      "*VFILL,C(31),RAMP,1,-1/30\n*VFILL,C(91),RAMP,-1,1/30\n*DIM,M,,4\nM(1) = 0,1,3,5\n"
      "*DIM,K,,4\nK(1) = 0,-1,-1,-1\n*DIM,A,,4\n*MFOURI,FIT,A(1),M(1),K(1),TH(1),C(1)\n");
  const V b = w.column("A");
  const double pi2 = 3.14159265358979 * 3.14159265358979;
  EXPECT_NEAR(b[0], 0.0, 1e-12);
  EXPECT_NEAR(b[1], 8.0 / pi2, 2e-3);
  EXPECT_NEAR(b[2], -8.0 / (9.0 * pi2), 2e-3);
  EXPECT_NEAR(b[3], 8.0 / (25.0 * pi2), 2e-3);
  EXPECT_NE(error_of("*DIM,A,,2\n*DIM,M,,3\n*DIM,K,,3\n*DIM,T,,5\n*DIM,C,,5\n"
                     "*MFOURI,FIT,A(1),M(1),K(1),T(1),C(1)\n")
                .find("same length"),
            std::string::npos);
  EXPECT_NE(error_of("*DIM,A,,2\nM = 1\n*DIM,K,,2\n*DIM,T,,5\n*DIM,C,,5\n"
                     "*MFOURI,FIT,A(1),M,K(1),T(1),C(1)\n")
                .find("MODE must be an array"),
            std::string::npos);
}

// A get function in a numeric field of *GET or *VGET (vmfebsta-le5 with N2 = NODE(...) written
// in place): evaluated like any other field, not taken for a label.
TEST(GetActive, GetFunctionInTheEntityField) {
  Session s;
  s.run(
      "/PREP7\nN,1\nN,2,10,0,-1\nN,3,10,1,-1\n*GET,X2,NODE,NODE(10,0.1,-1),LOC,X\n"
      "*GET,Y3,NODE,NODE(10,0.9,-1),LOC,Y\n*DIM,V,,2\n*VGET,V(1),NODE,NODE(9,0,-1),LOC,X\n");
  EXPECT_DOUBLE_EQ(s.num("X2"), 10.0);
  EXPECT_DOUBLE_EQ(s.num("Y3"), 1.0);
  EXPECT_DOUBLE_EQ(s.column("V")[0], 10.0);
  EXPECT_DOUBLE_EQ(s.column("V")[1], 10.0);  // node 3, the next in order
}

}  // namespace test_array_commands
