// Lexer, numbers, expressions and name matching of the deck reader (APDL_SUBSET §1).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>

#include "core/log.h"
#include "deck/deck_reader.h"
#include "deck/expression.h"
#include "deck/lexer.h"

namespace test_deck_lexer {

using namespace impactfe;
using namespace impactfe::deck;

TEST(DeckLexer, FortranNumbers) {
  EXPECT_DOUBLE_EQ(*parse_fortran_number("2.6E6"), 2.6e6);
  EXPECT_DOUBLE_EQ(*parse_fortran_number(".06"), 0.06);
  EXPECT_DOUBLE_EQ(*parse_fortran_number("1.E-4"), 1e-4);
  EXPECT_DOUBLE_EQ(*parse_fortran_number("1.0D3"), 1000.0);
  EXPECT_DOUBLE_EQ(*parse_fortran_number("1.965d-4"), 1.965e-4);
  EXPECT_DOUBLE_EQ(*parse_fortran_number("-2."), -2.0);
  EXPECT_DOUBLE_EQ(*parse_fortran_number("30E6"), 30e6);
  EXPECT_DOUBLE_EQ(*parse_fortran_number("+5"), 5.0);
  EXPECT_DOUBLE_EQ(*parse_fortran_number("-.5"), -0.5);
  for (const char* bad : {"", ".", "-", "E5", "1.2.3", "1E", "1E+", "abc", "1,2", "1 2", "0x10"})
    EXPECT_FALSE(parse_fortran_number(bad).has_value()) << bad;
}

TEST(DeckLexer, FieldsKeepBlankDistinctFromZero) {
  const auto cmds = lex_line("ET, 1, 63, , , , , 1", "d.inp", 7, Dialect::Classic4x);
  ASSERT_EQ(cmds.size(), 1u);
  EXPECT_EQ(cmds[0].name, "ET");
  EXPECT_EQ(cmds[0].fields, (std::vector<std::string>{"1", "63", "", "", "", "", "1"}));
  EXPECT_EQ(cmds[0].line, 7);
  ASSERT_NE(cmds[0].file, nullptr);
  EXPECT_EQ(*cmds[0].file, "d.inp");
  const auto n = lex_line("n,2,0,,0", "d.inp", 1, Dialect::Modern);
  EXPECT_EQ(n[0].name, "N");  // names are upper-cased
  EXPECT_EQ(n[0].fields, (std::vector<std::string>{"2", "0", "", "0"}));
}

TEST(DeckLexer, CommandsOfATextShareOneFileNameAndLeaveNoSpareCapacity) {
  // A deck of 10⁵ lines holds its commands for the whole run (issue 11: memory).
  const auto cmds =
      lex_text("N,1\nN,2,1 $ N,3,2\n\nE,1,2\n", "a/long/path/to/the/deck.inp", Dialect::Modern);
  ASSERT_EQ(cmds.size(), 4u);
  EXPECT_EQ(cmds.capacity(), cmds.size());
  for (const auto& c : cmds) {
    ASSERT_NE(c.file, nullptr);
    EXPECT_EQ(c.file.get(), cmds[0].file.get());
  }
  EXPECT_EQ(*cmds[3].file, "a/long/path/to/the/deck.inp");
  EXPECT_EQ(cmds[3].line, 4);
}

TEST(DeckLexer, CommentsAndBlankLines) {
  EXPECT_TRUE(lex_line("", "d", 1, Dialect::Modern).empty());
  EXPECT_TRUE(lex_line("   \r", "d", 1, Dialect::Modern).empty());
  EXPECT_TRUE(lex_line("C*** a comment, with commas", "d", 1, Dialect::Classic4x).empty());
  EXPECT_TRUE(lex_line("! whole line", "d", 1, Dialect::Modern).empty());
  const auto c = lex_line("N,1,2.5 ! node one", "d", 1, Dialect::Modern);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].fields, (std::vector<std::string>{"1", "2.5"}));
  const auto com = lex_line("/COM, Hello, World $ x", "d", 1, Dialect::Modern);
  ASSERT_EQ(com.size(), 1u);
  EXPECT_EQ(com[0].name, "/COM");
  EXPECT_EQ(com[0].rest, "Hello, World $ x");
}

TEST(DeckLexer, TitleKeepsCaseAndCommas) {
  const auto t = lex_line("/title,Example #1, Pendulum", "d", 1, Dialect::Modern);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].name, "/TITLE");
  EXPECT_EQ(t[0].rest, "Example #1, Pendulum");
}

// `/COM REF: TEXT, MORE` (a blank after the name, as 20 VM decks write it) is a comment, not the
// unknown command "/COM REF"; so is `/COM,text, with commas`.
TEST(DeckLexer, CommentNameEndsAtABlankOrASign) {
  const auto c = lex_line("/COM   REF: BATHE AND DVORKIN, 1983", "d", 1, Dialect::Modern);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].name, "/COM");
  EXPECT_EQ(c[0].rest, "REF: BATHE AND DVORKIN, 1983");
  const auto d = lex_line("/COM ,text, with commas", "d", 1, Dialect::Modern);
  EXPECT_EQ(d[0].name, "/COM");
  EXPECT_EQ(d[0].rest, "text, with commas");
  const auto t = lex_line("/TITLE VM3, THERMALLY LOADED", "d", 1, Dialect::Modern);
  EXPECT_EQ(t[0].name, "/TITLE");
  EXPECT_EQ(t[0].rest, "VM3, THERMALLY LOADED");
  const auto e = lex_line("/COM", "d", 1, Dialect::Modern);
  EXPECT_EQ(e[0].name, "/COM");
  EXPECT_EQ(e[0].rest, "");
  // The name ends at the first character that is no letter or digit (VM264: `/COM-----`).
  const auto f = lex_line("/COM------ RESULTS COMPARISON ---", "d", 1, Dialect::Modern);
  EXPECT_EQ(f[0].name, "/COM");
  EXPECT_EQ(f[0].rest, "------ RESULTS COMPARISON ---");
}

// MAPDL: "never include a blank space before the * character because the rest of the input
// line (beginning with the *) is interpreted as a comment" (vmd1: `F,53,FZ,-2.5,,1253,200
// *UNIT TWISTING MOMENT (0.2*5)`). A product written without the blank is a product.
TEST(DeckLexer, BlankThenStarStartsAComment) {
  const auto c =
      lex_line("F,53,FZ,-2.5,,1253,200  *UNIT TWISTING (0.2*5)", "d", 1, Dialect::Modern);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].fields, (std::vector<std::string>{"53", "FZ", "-2.5", "", "1253", "200"}));
  EXPECT_TRUE(c[0].star_comment);
  const auto a = lex_line("A = B *C", "d", 1, Dialect::Modern);
  EXPECT_EQ(a[0].fields, (std::vector<std::string>{"A", "B"}));
  const auto p = lex_line("A = B*C $ *REPEAT,2", "d", 1, Dialect::Modern);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0].fields, (std::vector<std::string>{"A", "B*C"}));
  EXPECT_FALSE(p[0].star_comment);
  EXPECT_EQ(p[1].name, "*REPEAT");
  EXPECT_FALSE(p[1].star_comment);
  const auto q = lex_line("/TITLE, a *b", "d", 1, Dialect::Modern);
  EXPECT_EQ(q[0].rest, "a *b");  // titles and comments keep their text
  const auto s = lex_line("LAB = 'x *y'", "d", 1, Dialect::Modern);
  EXPECT_EQ(s[0].fields[1], "'x *y'");
}

TEST(DeckLexer, DollarSeparatesCommandsInModernOnly) {
  const auto m = lex_line("N,1 $ N,2,1.0 $ E,1,2", "d", 3, Dialect::Modern);
  ASSERT_EQ(m.size(), 3u);
  EXPECT_EQ(m[1].name, "N");
  EXPECT_EQ(m[1].fields, (std::vector<std::string>{"2", "1.0"}));
  EXPECT_EQ(m[2].line, 3);
  const auto x = lex_line("N,1 $ N,2", "d", 3, Dialect::Classic4x);
  ASSERT_EQ(x.size(), 1u);
}

TEST(DeckLexer, RepeatLinesAndAssignments) {
  const auto r = lex_line("  ,2,2.5", "d", 1, Dialect::Classic4x);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_TRUE(r[0].repeat);
  EXPECT_TRUE(r[0].name.empty());
  EXPECT_EQ(r[0].fields, (std::vector<std::string>{"2", "2.5"}));
  const auto a = lex_line("L = MOD(7,3)*2 ! comment", "d", 1, Dialect::Modern);
  ASSERT_EQ(a.size(), 1u);
  EXPECT_TRUE(a[0].assignment);
  EXPECT_EQ(a[0].fields, (std::vector<std::string>{"L", "MOD(7,3)*2"}));
}

TEST(DeckExpression, ArithmeticFunctionsAndParameters) {
  Parameters p;
  p.set("len", 10.0);
  EXPECT_DOUBLE_EQ(evaluate("2**3", p), 8.0);
  EXPECT_DOUBLE_EQ(evaluate("2**3**2", p), 512.0);  // right-associative
  EXPECT_DOUBLE_EQ(evaluate("(1+2)*3-4/2", p), 7.0);
  EXPECT_DOUBLE_EQ(evaluate("-LEN/4", p), -2.5);
  EXPECT_DOUBLE_EQ(evaluate("Len*1.0D-1", p), 1.0);
  EXPECT_DOUBLE_EQ(evaluate("SQRT(16)+ABS(-2)", p), 6.0);
  EXPECT_DOUBLE_EQ(evaluate("NINT(2.5)", p), 3.0);
  EXPECT_DOUBLE_EQ(evaluate("NINT(-2.5)", p), -3.0);
  EXPECT_DOUBLE_EQ(evaluate("MOD(7,3)", p), 1.0);
  EXPECT_DOUBLE_EQ(evaluate("LOG10(1000)", p), 3.0);
  EXPECT_NEAR(evaluate("EXP(LOG(5))", p), 5.0, 1e-14);
  EXPECT_NEAR(evaluate("SIN(ACOS(0))", p), 1.0, 1e-15);
  EXPECT_NEAR(evaluate("ATAN(1)*4", p), M_PI, 1e-15);
  p.degrees = true;
  EXPECT_NEAR(evaluate("COS(60)", p), 0.5, 1e-15);
  EXPECT_NEAR(evaluate("ASIN(1)", p), 90.0, 1e-12);
  EXPECT_THROW(evaluate("WIDTH*2", p), ExpressionError);
  EXPECT_THROW(evaluate("1/0", p), ExpressionError);
  EXPECT_THROW(evaluate("(1+2", p), ExpressionError);
  EXPECT_THROW(evaluate("MOD(1,0)", p), ExpressionError);
  EXPECT_THROW(evaluate("FOO(1)", p), ExpressionError);
}

namespace {
Job parse(const std::string& text, std::optional<Dialect> dialect = std::nullopt) {
  DeckOptions o;
  o.dialect = dialect;
  return read_deck_text(text, "mem.inp", o);
}
}  // namespace

TEST(DeckLexer, DialectDetection) {
  EXPECT_EQ(parse("/PREP7\nN,1\n").model.dialect, Dialect::Modern);
  EXPECT_EQ(parse("/PREP7\nKAN,4\n").model.dialect, Dialect::Classic4x);
  EXPECT_EQ(parse("/PREP7\nITER,1\n").model.dialect, Dialect::Classic4x);
  EXPECT_EQ(parse("/PREP7\nN,1\n", Dialect::Classic4x).model.dialect, Dialect::Classic4x);
}

TEST(DeckLexer, FourCharacterNamesIn4xOnly) {
  Log::clear();
  // /FOCUSE -> /FOCUS and DENSITY -> DENS are accepted in the 4x dialect with a warning.
  const Job job = parse("/PREP7\nKAN,0\nDENSITY,1,7.3E-4\n/FOCUSE,,,-7.5\n");
  EXPECT_DOUBLE_EQ(job.model.materials.at(1).get("DENS", 0.0), 7.3e-4);
  // /FOCUS is carried out (it sets the focus point of the pictures), not ignored.
  EXPECT_TRUE(job.ignored_commands.empty());
  int truncation_warnings = 0;
  for (const auto& w : Log::warnings())
    if (w.find("first four characters") != std::string::npos) ++truncation_warnings;
  EXPECT_EQ(truncation_warnings, 2);
  // MAPDL reads only the first four characters of a name (Command Reference §1.2): the modern
  // dialect takes a longer spelling too, when one command has those four (/SOLUTION, 14 VM decks).
  Log::clear();
  const Job modern = parse("/PREP7\nDENSITY,1,7.3E-4\nFINISH\n/SOLUTION\nFINISHED\n/POST1\n");
  EXPECT_DOUBLE_EQ(modern.model.materials.at(1).get("DENS", 0.0), 7.3e-4);
  EXPECT_TRUE(Log::warnings().empty());
  EXPECT_THROW(parse("/SOLUTION\n/PREP7\nN,1\n/SOLUTION\nNOD,2\n"), InputError);  // too short
  // A macro of the name comes first (vm39: SOLVIT is its macro, not SOLVE).
  const Job macro = parse("*CREATE,SOLVIT,MAC\n/PREP7\nN,ARG1\n*END\nSOLVIT,7\n");
  EXPECT_EQ(macro.model.nodes.count(7), 1u);
}

TEST(DeckLexer, RepeatLineReissuesPreviousCommand) {
  const Job job = parse("/PREP7\nN,1\n,2,2.5\n  ,3,4.5,1\n");
  ASSERT_EQ(job.model.nodes.size(), 3u);
  EXPECT_DOUBLE_EQ(job.model.node(2).x.x(), 2.5);
  EXPECT_EQ(job.model.node(3).x, Vec3(4.5, 1.0, 0.0));  // fields are not inherited
}

TEST(DeckLexer, ParameterSubstitutionInNumericFields) {
  const Job job = parse("/PREP7\nL=10\nH = L/2\n*SET,Z,-1.5\nN,1,L,H*2,Z\nN,2,SQRT(L*L)\n");
  EXPECT_EQ(job.model.node(1).x, Vec3(10.0, 10.0, -1.5));
  EXPECT_EQ(job.model.node(2).x, Vec3(10.0, 0.0, 0.0));
}

TEST(DeckLexer, SkipUnknownListsTheCommand) {
  DeckOptions o;
  o.skip_unknown = true;
  const Job job = read_deck_text("/PREP7\nPLCAMP,1\n,2\nN,1\n", "mem.inp", o);
  EXPECT_EQ(job.model.nodes.size(), 1u);
  ASSERT_EQ(job.ignored_commands.size(), 2u);  // PLCAMP and its repeat line
  EXPECT_NE(job.ignored_commands[0].find("mem.inp:2: PLCAMP"), std::string::npos);
  try {
    parse("/PREP7\nFOO,1\n");
    FAIL() << "unknown command accepted";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "mem.inp:2: FOO: unknown command");
  }
}

TEST(DeckLexer, LineOfMegabytesIsRefusedWithItsLocation) {
  // Issue 12, resource bounds: a line of 8 MB (a deck written by a broken program, or a binary
  // file given as a deck) is refused with FILE:LINE at the documented limit (kMaxLineLength,
  // docs/deck_reader.md), without building fields or parameters from it. The text of the line
  // is numbers, so that only the length can be what refuses it.
  const std::string huge(8u << 20, '1');
  for (const std::string& line : {"N,1," + huge, huge, "X = " + huge}) {
    try {
      parse("/PREP7\n" + line + "\nN,2\n");
      FAIL() << "a line of " << line.size() << " characters was accepted";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("mem.inp:2: ", 0), 0u) << what.substr(0, 200);
      EXPECT_NE(what.find(fmt::format("line of {} characters refused (at most {} per line)",
                                      line.size(), kMaxLineLength)),
                std::string::npos)
          << what.substr(0, 200);
      EXPECT_LT(what.size(), 200u);  // the message quotes the command name, not the line
    }
  }
}

}  // namespace test_deck_lexer
