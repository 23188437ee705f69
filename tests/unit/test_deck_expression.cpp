// The expression grammar (APDL_SCRIPTING §A.3), every built-in function (§A.4), array and table
// references (§A.7) and the get functions (APDL_MODELING §10.3).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <vector>

#include "deck/deck_reader.h"
#include "deck/expression.h"
#include "deck/parameters.h"

namespace test_deck_expression {

using namespace impactfe;
using namespace impactfe::deck;

namespace {

double ev(const std::string& e, const Parameters& p) {
  return evaluate(e, p);
}

/// Runs a modern deck; its printed output is returned through `out`.
Job run(const std::string& text, std::string* out = nullptr) {
  std::ostringstream sink;
  DeckOptions o;
  o.dialect = Dialect::Modern;
  o.output = &sink;
  Job job = read_deck_text(text, "mem.inp", o);
  if (out) *out = sink.str();
  return job;
}

std::string error_of(const std::string& text) {
  try {
    run(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(DeckExpression, PrecedenceAndAssociativity) {
  Parameters p;
  p.set("A", 3.0);
  p.set("B", 4.0);
  EXPECT_DOUBLE_EQ(ev("2**3**2", p), 512.0);  // ** is right-associative
  EXPECT_DOUBLE_EQ(ev("-4**2", p), -16.0);    // unary minus below **
  EXPECT_DOUBLE_EQ(ev("(-4)**2", p), 16.0);
  EXPECT_DOUBLE_EQ(ev("-A*B", p), -12.0);
  EXPECT_DOUBLE_EQ(ev("2*3+4*5", p), 26.0);
  EXPECT_DOUBLE_EQ(ev("10-4-3", p), 3.0);  // left-associative
  EXPECT_DOUBLE_EQ(ev("16/4/2", p), 2.0);
  EXPECT_DOUBLE_EQ(ev("2**-1", p), 0.5);   // signed exponent (extension)
  EXPECT_DOUBLE_EQ(ev("A*-B", p), -12.0);  // sign after * (extension)
  EXPECT_DOUBLE_EQ(ev(" ( A + B ) * 2 ", p), 14.0);
  EXPECT_DOUBLE_EQ(ev("A<B", p), 3.0);      // conditional operators: minimum ...
  EXPECT_DOUBLE_EQ(ev("A>B", p), 4.0);      // ... and maximum
  EXPECT_DOUBLE_EQ(ev("A+1>B+2", p), 6.0);  // lowest precedence
  EXPECT_DOUBLE_EQ(ev("1<2>0", p), 1.0);    // left to right: (1<2)>0
}

namespace {

/// One row of the order-of-operations table: the expression, the same with every implied
/// parenthesis written out, and its value (APDL Programmer's Guide §3.7: `**` right to left, then
/// `*` `/`, then unary `+` `-`, then `+` `-`, then `<` `>` (minimum, maximum), left to right).
struct OperatorPair {
  const char* expression;
  const char* parenthesized;
  double value;
};

void check_rows(const std::vector<OperatorPair>& rows) {
  Parameters p;
  for (const auto& row : rows) {
    SCOPED_TRACE(row.expression);
    EXPECT_NEAR(ev(row.expression, p), row.value, 1e-14 * std::fabs(row.value));
    EXPECT_NEAR(ev(row.parenthesized, p), row.value, 1e-14 * std::fabs(row.value));
  }
}

}  // namespace

// Every ordered pair of the binary operators `a op1 b op2 c`: which one binds first.
TEST(DeckExpression, EveryPairOfBinaryOperators) {
  check_rows({
      {"2+3+4", "(2+3)+4", 9},           {"2+3-4", "(2+3)-4", 1},
      {"2+3*4", "2+(3*4)", 14},          {"2+3/4", "2+(3/4)", 2.75},
      {"2+3**4", "2+(3**4)", 83},        {"2+3<4", "(2+3)<4", 4},
      {"2+3>4", "(2+3)>4", 5},           {"2-3+4", "(2-3)+4", 3},
      {"2-3-4", "(2-3)-4", -5},          {"2-3*4", "2-(3*4)", -10},
      {"2-3/4", "2-(3/4)", 1.25},        {"2-3**4", "2-(3**4)", -79},
      {"2-3<4", "(2-3)<4", -1},          {"2-3>4", "(2-3)>4", 4},
      {"2*3+4", "(2*3)+4", 10},          {"2*3-4", "(2*3)-4", 2},
      {"2*3*4", "(2*3)*4", 24},          {"2*3/4", "(2*3)/4", 1.5},
      {"2*3**4", "2*(3**4)", 162},       {"2*3<4", "(2*3)<4", 4},
      {"2*3>4", "(2*3)>4", 6},           {"2/3+4", "(2/3)+4", 2.0 / 3 + 4},
      {"2/3-4", "(2/3)-4", 2.0 / 3 - 4}, {"2/3*4", "(2/3)*4", 8.0 / 3},
      {"2/3/4", "(2/3)/4", 1.0 / 6},     {"2/3**4", "2/(3**4)", 2.0 / 81},
      {"2/3<4", "(2/3)<4", 2.0 / 3},     {"2/3>4", "(2/3)>4", 4},
      {"2**3+4", "(2**3)+4", 12},        {"2**3-4", "(2**3)-4", 4},
      {"2**3*4", "(2**3)*4", 32},        {"2**3/4", "(2**3)/4", 2},
      {"2**3**2", "2**(3**2)", 512},     {"2**3<4", "(2**3)<4", 4},
      {"2**3>4", "(2**3)>4", 8},         {"2<3+4", "2<(3+4)", 2},
      {"2<3-4", "2<(3-4)", -1},          {"2<3*4", "2<(3*4)", 2},
      {"2<3/4", "2<(3/4)", 0.75},        {"2<3**4", "2<(3**4)", 2},
      {"2<3<4", "(2<3)<4", 2},           {"2<3>4", "(2<3)>4", 4},
      {"2>3+4", "2>(3+4)", 7},           {"2>3-4", "2>(3-4)", 2},
      {"2>3*4", "2>(3*4)", 12},          {"2>3/4", "2>(3/4)", 2},
      {"2>3**4", "2>(3**4)", 81},        {"2>3<4", "(2>3)<4", 3},
      {"2>3>4", "(2>3)>4", 4},
  });
}

// The unary sign against every binary operator, on either side, and a sign after an operator
// that applies to the one operand that follows it (`2/-3*4` is (2/(-3))*4, never 2/(-(3*4))).
TEST(DeckExpression, UnarySignAgainstEveryOperator) {
  check_rows({
      {"-2+3", "(-2)+3", 1},
      {"2+-3", "2+(-3)", -1},
      {"-2-3", "(-2)-3", -5},
      {"2--3", "2-(-3)", 5},
      {"-2*3", "-(2*3)", -6},
      {"2*-3", "2*(-3)", -6},
      {"-2/3", "-(2/3)", -2.0 / 3},
      {"2/-3", "2/(-3)", -2.0 / 3},
      {"-2**2", "-(2**2)", -4},
      {"2**-3", "2**(-3)", 0.125},
      {"-2<3", "(-2)<3", -2},
      {"2<-3", "2<(-3)", -3},
      {"-2>3", "(-2)>3", 3},
      {"2>-3", "2>(-3)", 2},
      {"2*-3*4", "(2*(-3))*4", -24},
      {"2*-3/4", "(2*(-3))/4", -1.5},
      {"2*-3+4", "(2*(-3))+4", -2},
      {"2*-3**2", "2*(-(3**2))", -18},
      {"2/-3*4", "(2/(-3))*4", -8.0 / 3},
      {"2/-3/4", "(2/(-3))/4", -1.0 / 6},
      {"2/-3+4", "(2/(-3))+4", 4 - 2.0 / 3},
      {"2/-3**2", "2/(-(3**2))", -2.0 / 9},
      {"2**-3*4", "(2**(-3))*4", 0.5},
      {"2**-3/4", "(2**(-3))/4", 0.03125},
      {"2**-3+4", "(2**(-3))+4", 4.125},
      {"2**-1**2", "2**(-(1**2))", 0.5},
      {"--2**2", "-(-(2**2))", 4},
  });
}

// `A=I**2*3` with I=2 gave 64: the exponent swallowed `2*3`. The documented example
// Y2=A+B**C/D*E is B**C first, /D second, *E third, +A last.
TEST(DeckExpression, PowerThenProductInADeck) {
  const Job job =
      run("/PREP7\nI=2\nA=I**2*3\nB=I**2/4\nH=3\nIZ=2*H**3/12\n"
          "P=1\nQ=2\nR=3\nS=4\nT=5\nY2=P+Q**R/S*T\n"
          "MP,EX,1,A\nMP,EX,2,B\nMP,EX,3,IZ\nMP,EX,4,Y2\nMP,EX,5,I**2*3\n");
  EXPECT_DOUBLE_EQ(job.model.materials.at(1).get("EX", 0), 12.0);
  EXPECT_DOUBLE_EQ(job.model.materials.at(2).get("EX", 0), 1.0);
  EXPECT_DOUBLE_EQ(job.model.materials.at(3).get("EX", 0), 4.5);
  EXPECT_DOUBLE_EQ(job.model.materials.at(4).get("EX", 0), 11.0);  // 1 + 8/4*5
  EXPECT_DOUBLE_EQ(job.model.materials.at(5).get("EX", 0), 12.0);  // in a command field too
}

TEST(DeckExpression, Numbers) {
  Parameters p;
  EXPECT_DOUBLE_EQ(ev("1.5E3", p), 1500.0);
  EXPECT_DOUBLE_EQ(ev("1.5D-3", p), 1.5e-3);
  EXPECT_DOUBLE_EQ(ev(".5", p), 0.5);
  EXPECT_DOUBLE_EQ(ev("2.", p), 2.0);
  EXPECT_DOUBLE_EQ(ev("123-002", p), 1.23);  // MAPDL: a sign and 0nn is an exponent: 123E-2
  EXPECT_DOUBLE_EQ(ev("5+03", p), 5000.0);
  EXPECT_DOUBLE_EQ(ev("1.5-01", p), 0.15);
  EXPECT_DOUBLE_EQ(ev("123-2", p), 121.0);  // ... but 123-2 is a subtraction
  EXPECT_DOUBLE_EQ(ev("2-0.5", p), 1.5);
}

TEST(DeckExpression, EveryBuiltinFunction) {
  Parameters p;
  EXPECT_DOUBLE_EQ(ev("ABS(-2.5)", p), 2.5);
  EXPECT_DOUBLE_EQ(ev("SIGN(3,-1)", p), -3.0);
  EXPECT_DOUBLE_EQ(ev("SIGN(-3,0)", p), 3.0);
  EXPECT_DOUBLE_EQ(ev("SQRT(2.25)", p), 1.5);
  EXPECT_NEAR(ev("EXP(1)", p), std::numbers::e, 1e-15);
  EXPECT_NEAR(ev("LOG(EXP(2))", p), 2.0, 1e-15);
  EXPECT_DOUBLE_EQ(ev("LOG10(0.01)", p), -2.0);
  EXPECT_NEAR(ev("SIN(0.5)", p), std::sin(0.5), 1e-15);
  EXPECT_NEAR(ev("COS(0.5)", p), std::cos(0.5), 1e-15);
  EXPECT_NEAR(ev("TAN(0.5)", p), std::tan(0.5), 1e-15);
  EXPECT_NEAR(ev("ASIN(0.5)", p), std::asin(0.5), 1e-15);
  EXPECT_NEAR(ev("ACOS(0.5)", p), std::acos(0.5), 1e-15);
  EXPECT_NEAR(ev("ATAN(2)", p), std::atan(2.0), 1e-15);
  EXPECT_NEAR(ev("ATAN2(1,-1)", p), 0.75 * std::numbers::pi, 1e-15);
  EXPECT_NEAR(ev("SINH(1)", p), std::sinh(1.0), 1e-15);
  EXPECT_NEAR(ev("COSH(1)", p), std::cosh(1.0), 1e-15);
  EXPECT_NEAR(ev("TANH(1)", p), std::tanh(1.0), 1e-15);
  EXPECT_DOUBLE_EQ(ev("NINT(2.5)", p), 3.0);  // halves away from zero
  EXPECT_DOUBLE_EQ(ev("NINT(-2.5)", p), -3.0);
  EXPECT_DOUBLE_EQ(ev("NINT(2.49)", p), 2.0);
  EXPECT_DOUBLE_EQ(ev("MOD(7,3)", p), 1.0);
  EXPECT_DOUBLE_EQ(ev("MOD(-7,3)", p), -1.0);  // Fortran: sign of x
  EXPECT_DOUBLE_EQ(ev("MOD(7.5,2)", p), 1.5);
  EXPECT_DOUBLE_EQ(ev("MIN(3,1,2)", p), 1.0);
  EXPECT_DOUBLE_EQ(ev("MAX(3,1,2)", p), 3.0);
  EXPECT_DOUBLE_EQ(ev("CXABS(3,4)", p), 5.0);
  const double r = ev("RAND(2,3)", p);
  EXPECT_GE(r, 2.0);
  EXPECT_LE(r, 3.0);
  EXPECT_DOUBLE_EQ(ev("GDIS(5,0)", p), 5.0);
  // *AFUN,DEG: SIN/COS/TAN take degrees, the inverse functions give degrees; SINH does not care.
  p.degrees = true;
  EXPECT_NEAR(ev("COS(60)", p), 0.5, 1e-15);
  EXPECT_NEAR(ev("SIN(30)", p), 0.5, 1e-15);
  EXPECT_NEAR(ev("TAN(45)", p), 1.0, 1e-15);
  EXPECT_NEAR(ev("ASIN(1)", p), 90.0, 1e-12);
  EXPECT_NEAR(ev("ACOS(0)", p), 90.0, 1e-12);
  EXPECT_NEAR(ev("ATAN(1)", p), 45.0, 1e-12);
  EXPECT_NEAR(ev("ATAN2(1,-1)", p), 135.0, 1e-12);
  EXPECT_NEAR(ev("SINH(1)", p), std::sinh(1.0), 1e-15);
}

TEST(DeckExpression, RandomNumbersRepeatFromRunToRun) {
  Parameters a, b;
  EXPECT_EQ(ev("RAND(0,1)", a), ev("RAND(0,1)", b));
  EXPECT_EQ(ev("GDIS(0,1)", a), ev("GDIS(0,1)", b));
}

TEST(DeckExpression, ErrorsNameTheProblem) {
  Parameters p;
  auto message = [&](const std::string& e) {
    try {
      ev(e, p);
    } catch (const ExpressionError& x) {
      return std::string(x.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("WIDTH*2").find("'WIDTH' is not a defined parameter"), std::string::npos);
  EXPECT_NE(message("1/0").find("division by zero"), std::string::npos);
  EXPECT_NE(message("(1+2").find("missing ')'"), std::string::npos);
  EXPECT_NE(message("SQRT(-1)").find("SQRT"), std::string::npos);
  EXPECT_NE(message("LOG(0)").find("LOG"), std::string::npos);
  EXPECT_NE(message("ASIN(2)").find("ASIN"), std::string::npos);
  EXPECT_NE(message("MOD(1,0)").find("MOD by zero"), std::string::npos);
  EXPECT_NE(message("(-8)**(1/3)").find("invalid power"), std::string::npos);
  EXPECT_NE(message("SIN(1,2)").find("SIN takes 1 argument"), std::string::npos);
  EXPECT_NE(message("FOO(1)").find("neither an array parameter nor a function"), std::string::npos);
  EXPECT_NE(message("2 3").find("unexpected"), std::string::npos);
  EXPECT_NE(message("'abc'+1").find("text 'abc'"), std::string::npos);
  EXPECT_NE(message("EXP(1000)").find("EXP"), std::string::npos);
}

TEST(DeckExpression, TextsAndLocals) {
  Parameters p;
  p.set_text("LAB", "UY");
  EXPECT_EQ(std::get<std::string>(evaluate_value("LAB", p)), "UY");
  EXPECT_EQ(std::get<std::string>(evaluate_value("'it''s'", p)), "it's");
  EXPECT_THROW(evaluate("LAB", p), ExpressionError);
  EXPECT_DOUBLE_EQ(ev("ARG3+AR25", p), 0.0);  // unset macro locals are 0
  p.set("ARG1", 4.0);
  EXPECT_DOUBLE_EQ(ev("ARG1", p), 4.0);
  p.push_level();
  EXPECT_DOUBLE_EQ(ev("ARG1", p), 0.0);  // each macro level has its own
  p.pop_level();
  EXPECT_DOUBLE_EQ(ev("ARG1", p), 4.0);
}

TEST(DeckExpression, ArraysWithUpToThreeSubscripts) {
  Parameters p;
  Param a = Param::array(ParamType::Array, 4, 3, 2);
  a.values[a.offset(4, 3, 2)] = 7.0;
  a.values[a.offset(2, 1, 1)] = 5.0;
  p.define("F", a);
  EXPECT_DOUBLE_EQ(ev("F(4,3,2)", p), 7.0);
  EXPECT_DOUBLE_EQ(ev("F(2)", p), 5.0);  // missing subscripts are 1
  EXPECT_DOUBLE_EQ(ev("F(1+1,1,1)*2", p), 10.0);
  EXPECT_DOUBLE_EQ(ev("F (2,1,1)", p), 5.0);  // a blank before the parenthesis
  EXPECT_DOUBLE_EQ(ev("F(1.6)", p), 5.0);     // subscripts round to the nearest integer
  EXPECT_THROW(ev("F(5,1,1)", p), ExpressionError);
  EXPECT_THROW(ev("F(0)", p), ExpressionError);
  EXPECT_THROW(ev("F(1,1,1,1)", p), ExpressionError);
  EXPECT_THROW(ev("F", p), ExpressionError);  // an array needs subscripts
  Param c = Param::array(ParamType::CharArray, 2, 1, 1);
  c.texts[1] = "R2";
  p.define("LBL", c);
  EXPECT_EQ(std::get<std::string>(evaluate_value("LBL(2)", p)), "R2");
}

TEST(DeckExpression, TableInterpolation) {
  // One-dimensional: F(1,0)=0,1,2 (index), F(1,1)=0,100,100; linear between, end values outside.
  Param t = Param::array(ParamType::Table, 3, 1, 1);
  const double x[] = {0, 1, 2}, y[] = {0, 100, 100};
  for (int i = 1; i <= 3; ++i) {
    t.values[t.offset(i, 0, 1)] = x[i - 1];
    t.values[t.offset(i, 1, 1)] = y[i - 1];
  }
  EXPECT_DOUBLE_EQ(table_lookup(t, 0.5, 0, 0), 50.0);
  EXPECT_DOUBLE_EQ(table_lookup(t, 1.5, 0, 0), 100.0);
  EXPECT_DOUBLE_EQ(table_lookup(t, -3, 0, 0), 0.0);
  EXPECT_DOUBLE_EQ(table_lookup(t, 9, 0, 0), 100.0);
  Parameters p;
  p.define("F", t);
  EXPECT_DOUBLE_EQ(ev("F(0.25)", p), 25.0);
  EXPECT_DOUBLE_EQ(ev("F(1,1)", p), 100.0);  // subscripts are variable values, not positions
  // Two-dimensional: bilinear between rows and columns.
  Param g = Param::array(ParamType::Table, 2, 2, 1);
  g.values[g.offset(1, 0, 1)] = 0;
  g.values[g.offset(2, 0, 1)] = 10;
  g.values[g.offset(0, 1, 1)] = 0;
  g.values[g.offset(0, 2, 1)] = 1;
  g.values[g.offset(1, 1, 1)] = 1;
  g.values[g.offset(2, 1, 1)] = 2;
  g.values[g.offset(1, 2, 1)] = 3;
  g.values[g.offset(2, 2, 1)] = 4;
  EXPECT_DOUBLE_EQ(table_lookup(g, 5, 0.5, 0), 2.5);
  EXPECT_DOUBLE_EQ(table_lookup(g, 10, 1, 0), 4.0);
  EXPECT_DOUBLE_EQ(table_lookup(g, 2.5, 0, 0), 1.25);
  // Three-dimensional: planes at z = 0 and 2; the midplane is the average.
  Param h = Param::array(ParamType::Table, 1, 1, 2);
  h.values[h.offset(1, 0, 1)] = 0;
  h.values[h.offset(0, 1, 1)] = 0;
  h.values[h.offset(0, 0, 1)] = 0;
  h.values[h.offset(0, 0, 2)] = 2;
  h.values[h.offset(1, 1, 1)] = 10;
  h.values[h.offset(1, 1, 2)] = 20;
  EXPECT_DOUBLE_EQ(table_lookup(h, 0, 0, 1), 15.0);
}

TEST(DeckExpression, FormatNumber) {
  EXPECT_EQ(format_number(3.0), "3");
  EXPECT_EQ(format_number(-12.0), "-12");
  EXPECT_EQ(format_number(0.25), "0.25");
  EXPECT_EQ(format_number(1.5e-6), "1.5E-06");
  EXPECT_EQ(std::stod(format_number(1.0 / 3.0)), 1.0 / 3.0);  // reads back exactly
}

TEST(DeckExpression, GetFunctionsFromTheModel) {
  std::string out;
  run(R"(/PREP7
ET,1,LINK180
N,1,0,0,0
N,2,3,0,0
N,3,3,4,0
N,7,0,-100,0
E,1,2
E,2,3
A = 6
B = 50
*VWRITE,NX(3),NY(3),NZ(3),DISTND(1,3)
(4F8.3)
*VWRITE,NODE(0,-100,0),NODE (A/2,-B+54.2,0 ),NODE(1,0,0),NNEAR(2),ENEARN(1)
(5I4)
*VWRITE,CENTRX(2),CENTRY(2),CENTRZ(2),NELEM(2,2),NELEM(2,5)
(3F8.3,2I4)
*VWRITE,NSEL(3),NSEL(4),ESEL(2),NDNEXT(3),NDNEXT(7),ELNEXT(1),ELNEXT(2)
(7I4)
)",
      &out);
  EXPECT_EQ(out,
            "   3.000   4.000   0.000   5.000\n"
            "   7   3   1   1   1\n"
            "   3.000   2.000   0.000   3   0\n"
            "   1   0   1   7   0   2   0\n");
  EXPECT_NE(error_of("/PREP7\nN,1\nX = NX(9)\n")
                .find("mem.inp:3: *SET: bad expression 'NX(9)' "
                      "(NX(9): node 9 is not defined)"),
            std::string::npos);
  EXPECT_NE(error_of("/PREP7\nN,1\nX = DISTND(1)\n").find("DISTND takes 2 arguments, 1 given"),
            std::string::npos);
}

TEST(DeckExpression, ArraysAreNotTakenForFunctions) {
  // F(37,1,1) and COEFF(2,1,1) are array elements, not calls of one-argument functions.
  std::string out;
  run(R"(*DIM,F,ARRAY,40,2,2
*DIM,COEFF,,3,1,1
F(37,1,1) = 2.5
COEFF(2,1,1) = 4
X = F(37,1,1)*COEFF(2,1,1)
*DIM,NODE,ARRAY,2
NODE(2) = 9
Y = NODE(2)
*VWRITE,X,Y
(2F6.1)
)",
      &out);
  EXPECT_EQ(out, "  10.0   9.0\n");
}

}  // namespace test_deck_expression
