// *VWRITE / *MSG format lines (APDL_SCRIPTING §A.9): Fortran edit descriptors (values checked
// against the Fortran 2008 rules, as gfortran prints them) and the C-style form.
#include <gtest/gtest.h>

#include "deck/output_format.h"

namespace test_output_format {

using namespace impactfe::deck;

namespace {

std::vector<std::string> fmt_lines(const std::string& format, const std::vector<Value>& items) {
  return OutputFormat::parse(format).format(items);
}

std::string fmt1(const std::string& format, const std::vector<Value>& items) {
  const auto lines = fmt_lines(format, items);
  std::string out;
  for (std::size_t i = 0; i < lines.size(); ++i) out += (i ? "\n" : "") + lines[i];
  return out;
}

}  // namespace

TEST(OutputFormat, FixedPoint) {
  EXPECT_EQ(fortran_f(0.0015, 10, 4), "    0.0015");
  EXPECT_EQ(fortran_f(-0.0004, 10, 4), "   -0.0004");
  EXPECT_EQ(fortran_f(1.0, 4, 0), "  1.");       // F4.0 keeps the decimal point
  EXPECT_EQ(fortran_f(123.456, 5, 2), "*****");  // does not fit: asterisks
  EXPECT_EQ(fortran_f(0.5, 4, 2), "0.50");
  EXPECT_EQ(fortran_f(0.5, 3, 2), ".50");  // the optional leading zero goes first
  EXPECT_EQ(fortran_f(-0.5, 4, 2), "-.50");
  EXPECT_EQ(fortran_f(1234.5678, 10, 2), "   1234.57");
  EXPECT_EQ(fortran_f(1.5, 8, 3, 1), "  15.000");  // 1P scales F output by 10
}

TEST(OutputFormat, ExponentialWithNegativeAndLargeExponents) {
  EXPECT_EQ(fortran_e(1.5e-3, 12, 5), " 0.15000E-02");
  EXPECT_EQ(fortran_e(-1.5e-3, 12, 5), "-0.15000E-02");
  EXPECT_EQ(fortran_e(-1.5e-3, 11, 5), "-.15000E-02");
  EXPECT_EQ(fortran_e(0.0, 12, 5), " 0.00000E+00");
  EXPECT_EQ(fortran_e(12345.678, 12, 4), "  0.1235E+05");
  EXPECT_EQ(fortran_e(1e-120, 12, 4), "  0.1000-119");  // three-digit exponent drops the E
  EXPECT_EQ(fortran_e(1e120, 12, 4), "  0.1000+121");
  EXPECT_EQ(fortran_e(1.5e-3, 12, 4, 3), " 0.1500E-002");      // Ew.dEe
  EXPECT_EQ(fortran_e(1.5e-3, 12, 5, -1, 1), " 1.50000E-03");  // 1PE12.5
  EXPECT_EQ(fortran_e(1.5e-3, 12, 5, -1, 0, 'D'), " 0.15000D-02");
  EXPECT_EQ(fortran_e(1.5e-3, 8, 5), "********");
  // More decimals than a double has, and more than fit the field (the fuzzer's E18.68).
  EXPECT_EQ(fortran_e(3.110, 18, 68), std::string(18, '*'));
  EXPECT_EQ(fortran_e(0.5, 77, 70), " 0.5" + std::string(69, '0') + "E+00");
  EXPECT_EQ(fortran_es(12345.0, 12, 4), "  1.2345E+04");
  EXPECT_EQ(fortran_es(-0.00012, 11, 2), "  -1.20E-04");
}

TEST(OutputFormat, GeneralEditing) {
  EXPECT_EQ(fortran_g(50.0, 12, 5), "  50.000    ");
  EXPECT_EQ(fortran_g(0.5, 12, 5), " 0.50000    ");
  EXPECT_EQ(fortran_g(99999.0, 12, 5), "  99999.    ");
  EXPECT_EQ(fortran_g(1.5e-3, 12, 5), " 0.15000E-02");
  EXPECT_EQ(fortran_g(123456.0, 12, 5), " 0.12346E+06");
  EXPECT_EQ(fortran_g(0.0, 12, 5), "  0.0000    ");
  EXPECT_EQ(fortran_g(-2.25, 12, 5), " -2.2500    ");
}

TEST(OutputFormat, IntegersAndCharacters) {
  EXPECT_EQ(fortran_i(42.4, 5), "   42");
  EXPECT_EQ(fortran_i(-3.0, 5), "   -3");
  EXPECT_EQ(fortran_i(123.0, 2), "**");
  EXPECT_EQ(fortran_i(7.0, 5, 3), "  007");
  EXPECT_EQ(fortran_a("A", 4), "   A");   // shorter text: right-justified
  EXPECT_EQ(fortran_a("ABCD", 2), "AB");  // longer: leftmost characters
  EXPECT_EQ(fortran_a("HELLO", -1), "HELLO");
}

TEST(OutputFormat, SpecExampleWithCharacterArrayAndSequence) {
  // APDL_SCRIPTING §A.9: *VWRITE,SEQU,NM(1),T(1),U(1) with (F4.0,1X,A4,2F10.4)
  const auto f = OutputFormat::parse("(F4.0,1X,A4,2F10.4)");
  EXPECT_EQ(f.n_data(), 4);
  EXPECT_EQ(f.format({1.0, std::string("A"), 0.1, 1.5e-3})[0], "  1.    A    0.1000    0.0015");
  EXPECT_EQ(f.format({3.0, std::string("C"), 0.3, -4e-4})[0], "  3.    C    0.3000   -0.0004");
}

TEST(OutputFormat, RepeatCountsGroupsAndLiterals) {
  EXPECT_EQ(fmt1("(2(F5.1,1X),'end')", {1.0, 2.0}), "  1.0   2.0 end");
  EXPECT_EQ(fmt1("(3F6.2)", {1.0, 2.0, 3.0}), "  1.00  2.00  3.00");
  EXPECT_EQ(fmt1("('it''s',I3)", {5.0}), "it's  5");
  EXPECT_EQ(fmt1("(\"dq\",I2)", {5.0}), "dq 5");
  EXPECT_EQ(fmt1("(5HHello,I3)", {1.0}), "Hello  1");
  EXPECT_EQ(fmt1("('AB',T6,'C',TR2,'D',TL1,'E')", {}), "AB   C  E");
  EXPECT_EQ(fmt1("(1X , F5.1 , 2X , A)", {1.0, std::string("x")}), "   1.0  x");
  EXPECT_EQ(fmt1("(f6.2,e10.2)", {1.0, 2.0}), "  1.00  0.20E+01");  // lower case accepted
}

TEST(OutputFormat, ItemsRunOutOrOverflow) {
  // Items used up: output stops at the next data descriptor, text before it is written.
  EXPECT_EQ(fmt1("('A=',F5.1,' B=',F5.1)", {1.0}), "A=  1.0 B=");
  // No items (all *VWRITE fields blank): only the leading text, e.g. a title or blank line.
  EXPECT_EQ(fmt1("('TITLE',F5.1)", {}), "TITLE");
  EXPECT_EQ(fmt1("(' ')", {}), " ");
  // More items than descriptors: the format starts again on a new line (reversion) ...
  EXPECT_EQ(fmt1("(F5.1)", {1.0, 2.0, 3.0}), "  1.0\n  2.0\n  3.0");
  // ... from the last top-level group.
  EXPECT_EQ(fmt1("('H',2(I2))", {1.0, 2.0, 3.0, 4.0}), "H 1 2\n 3 4");
  // '/' starts a new line; ':' ends when no item is left.
  EXPECT_EQ(fmt1("(I2/I2)", {1.0, 2.0}), " 1\n 2");
  EXPECT_EQ(fmt1("(I2,:,' more')", {1.0}), " 1");
}

TEST(OutputFormat, BlankFieldsForMismatchedItems) {
  std::vector<std::string> warnings;
  const auto f = OutputFormat::parse("(A4,'|',F6.2,'|')");
  EXPECT_EQ(f.format({1.0, std::string("x")}, &warnings)[0], "    |      |");
  EXPECT_EQ(warnings.size(), 2u);
}

TEST(OutputFormat, CStyle) {
  EXPECT_EQ(fmt1("%I items and %G value", {3.0, 1.5e-6}), "3 items and 1.5E-06 value");
  EXPECT_EQ(fmt1("%8.3F|%-6C|%5I|%6C", {1.5, std::string("AB"), 42.0, std::string("CD")}),
            "   1.500|AB    |   42|    CD");
  EXPECT_EQ(fmt1("%C", {std::string("LONGER THAN EIGHT")}), "LONGER THAN EIGHT");
  EXPECT_EQ(fmt1("line1%/line2 %I", {7.0}), "line1\nline2 7");
  EXPECT_EQ(fmt1("100%% done", {}), "100% done");
  EXPECT_EQ(fmt1("%10.3E", {-12346.0}), "-1.235E+04");
  EXPECT_EQ(fmt1("%I %I", {1.0}), "1 ");   // stops at the next conversion
  EXPECT_EQ(fmt1("%I", {1.0, 2.0}), "1");  // extra items ignored
}

TEST(OutputFormat, BadFormatsAreRejected) {
  for (const char* bad :
       {"(F10)", "(Q5)", "(F10.3", "(F10.3))", "('abc", "(0F5.1)", "(EN12.3)", "%Q", "value %"})
    EXPECT_THROW(OutputFormat::parse(bad), FormatError) << bad;
}

}  // namespace test_output_format
