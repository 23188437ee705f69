// Control flow and macros (APDL_SCRIPTING §A.10–§A.13): *DO, *DOWHILE, *IF in every form, *GO
// and labels, *EXIT / *CYCLE, *REPEAT, *CREATE / *USE / macro files with ARG1..AR99, /INPUT,
// /EOF, bounds (nesting, trip counts, line length, recursion), modern abbreviations.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "../support/run_deck.h"
#include "core/log.h"
#include "deck/deck_context.h"
#include "deck/deck_reader.h"

namespace test_deck_control_flow {

using namespace impactfe;

namespace {

Job run(const std::string& text, std::string* out = nullptr,
        std::optional<Dialect> dialect = Dialect::Modern, const std::string& path = "mem.inp") {
  std::ostringstream sink;
  DeckOptions o;
  o.dialect = dialect;
  o.output = &sink;
  Job job = read_deck_text(text, path, o);
  if (out) *out = sink.str();
  return job;
}

std::string output_of(const std::string& text) {
  std::string out;
  run(text, &out);
  return out;
}

std::string error_of(const std::string& text) {
  try {
    run(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

void write_file(const std::filesystem::path& p, const std::string& text) {
  std::ofstream(p) << text;
}

}  // namespace

TEST(DeckControlFlow, DoLoops) {
  EXPECT_EQ(output_of("*DO,I,1,10,3\n*VWRITE,I\n(F4.0)\n*ENDDO\n"), "  1.\n  4.\n  7.\n 10.\n");
  EXPECT_EQ(output_of("*DO,I,3,1,-1\n*VWRITE,I\n(I2)\n*ENDDO\n"), " 3\n 2\n 1\n");
  EXPECT_EQ(output_of("*DO,I,0,1,0.25\n*VWRITE,I\n(F5.2)\n*ENDDO\n"),
            " 0.00\n 0.25\n 0.50\n 0.75\n 1.00\n");
  EXPECT_EQ(output_of("*DO,I,5,1\n/COM,never\n*ENDDO\n"), "");
  // The trip count is fixed at *DO: changing the loop parameter does not change it; after the
  // loop the parameter keeps its last trip value.
  EXPECT_EQ(output_of("N=0\n*DO,I,1,3\nI=I+10\nN=N+1\n*ENDDO\n*VWRITE,N,I\n(2F5.0)\n"),
            "   3.  13.\n");
  // Nested loops.
  EXPECT_EQ(output_of("*DO,I,1,2\n*DO,J,1,2\n*VWRITE,I,J\n(2I2)\n*ENDDO\n*ENDDO\n"),
            " 1 1\n 1 2\n 2 1\n 2 2\n");
}

TEST(DeckControlFlow, ExitCycleAndDoWhile) {
  EXPECT_EQ(output_of("*DO,I,1,5\n*IF,I,EQ,2,CYCLE\n*IF,I,GT,3,EXIT\n*VWRITE,I\n(I2)\n*ENDDO\n"),
            " 1\n 3\n");
  EXPECT_EQ(output_of("*DO,I,1,5\n*IF,I,EQ,3,THEN\n*EXIT\n*ENDIF\n*VWRITE,I\n(I2)\n*ENDDO\n"),
            " 1\n 2\n");
  EXPECT_EQ(output_of("*DO,I,1,3\n*IF,I,EQ,2,THEN\n*CYCLE\n*ENDIF\n*VWRITE,I\n(I2)\n*ENDDO\n"),
            " 1\n 3\n");
  EXPECT_EQ(output_of("N=3\n*DOWHILE,N\n*VWRITE,N\n(I2)\nN=N-1\n*ENDDO\n"), " 3\n 2\n 1\n");
  // *EXIT outside a loop: warned and ignored.
  Log::clear();
  EXPECT_EQ(output_of("*EXIT\n/COM,after\n"), " after\n");
  EXPECT_EQ(Log::warnings().size(), 1u);
}

TEST(DeckControlFlow, IfBlocksAndOneLineForms) {
  const std::string deck = R"(*DO,I,1,4
*IF,I,EQ,1,THEN
/COM,one
*ELSEIF,I,EQ,2
/COM,two
*ELSEIF,I,GT,2,AND,I,LT,4
/COM,three
*ELSE
/COM,other
*ENDIF
*ENDDO
)";
  EXPECT_EQ(output_of(deck), " one\n two\n three\n other\n");
  // AND / OR / XOR joining two clauses, ABLT / ABGT, nested blocks.
  EXPECT_EQ(output_of("A=-5\n*IF,A,ABGT,4,AND,A,LT,0,THEN\n/COM,yes\n*ENDIF\n"), " yes\n");
  EXPECT_EQ(output_of("A=-5\n*IF,A,ABLT,4,OR,A,GT,0,THEN\n/COM,yes\n*ELSE\n/COM,no\n*ENDIF\n"),
            " no\n");
  EXPECT_EQ(output_of("*IF,1,EQ,1,XOR,2,EQ,2,THEN\n/COM,yes\n*ELSE\n/COM,no\n*ENDIF\n"), " no\n");
  EXPECT_EQ(output_of("*IF,1,LE,1,THEN\n*IF,2,GE,3,THEN\n/COM,a\n*ELSE\n/COM,b\n*ENDIF\n*ENDIF\n"),
            " b\n");
  // Tolerance of EQ is absolute 1e-10.
  EXPECT_EQ(output_of("*IF,0.1+0.2,EQ,0.3,THEN\n/COM,equal\n*ENDIF\n"), " equal\n");
  // Character comparisons: EQ / NE only, trailing blanks ignored.
  EXPECT_EQ(output_of("LAB='UX'\n*IF,LAB,EQ,'UX  ',THEN\n/COM,same\n*ENDIF\n"), " same\n");
  EXPECT_NE(error_of("LAB='UX'\n*IF,LAB,LT,'UY',THEN\n*ENDIF\n").find("texts compare only"),
            std::string::npos);
  // STOP ends the run cleanly.
  EXPECT_EQ(output_of("/COM,a\n*IF,1,EQ,1,STOP\n/COM,b\n"), " a\n");
}

TEST(DeckControlFlow, GotoLabels) {
  const std::string deck = R"(N=0
:AGAIN
N=N+1
*IF,N,LT,3,:AGAIN
*VWRITE,N
(I2)
*GO,:END
/COM,skipped
:END
/COM,end
)";
  EXPECT_EQ(output_of(deck), " 3\n end\n");
  EXPECT_NE(error_of("*GO,:NOWHERE\n").find("mem.inp:1: *GO: label :NOWHERE not found"),
            std::string::npos);
  EXPECT_NE(error_of("*DO,I,1,2\n*IF,I,EQ,2,:OUT\n*ENDDO\n:OUT\n").find("may not leave a *DO"),
            std::string::npos);
}

TEST(DeckControlFlow, RepeatThePreviousCommand) {
  const Job job = run("/PREP7\nN,1,0,0,0\n*REPEAT,4,1,2.5\n");
  ASSERT_EQ(job.model.nodes.size(), 4u);
  EXPECT_DOUBLE_EQ(job.model.node(4).x.x(), 7.5);
}

TEST(DeckControlFlow, InMemoryMacrosWithArguments) {
  const std::string deck = R"(/PREP7
*CREATE,SPRING,MAC
N,ARG1,ARG2
*VWRITE,ARG1,ARG2,AR19
(3F5.1)
*END
*USE,SPRING,1,2.5
SPRING,3,4
ARG1 = 7
*USE,SPRING,2*ARG1
)";
  std::string out;
  const Job job = run(deck, &out);
  EXPECT_EQ(out, "  1.0  2.5  0.0\n  3.0  4.0  0.0\n 14.0  0.0  0.0\n");
  EXPECT_EQ(job.model.nodes.size(), 3u);
  EXPECT_DOUBLE_EQ(job.model.node(14).x.x(), 0.0);
  // Character arguments; locals do not leak out of the macro.
  EXPECT_EQ(output_of("*CREATE,SAY\n*MSG,INFO,ARG1\nsay %C\nAR20=5\n*END\n*USE,SAY,'hello'\n"
                      "*VWRITE,AR20\n(F3.0)\n"),
            "say hello\n 0.\n");
}

TEST(DeckControlFlow, MacroFilesOnDiskAndInput) {
  const auto dir = impactfe::testing::fresh_directory("control_flow_files");
  write_file(dir / "twice.mac", "*VWRITE,ARG1*2\n(F5.1)\n");
  write_file(dir / "part.inp", "/COM,in part\n/EOF\n/COM,never\n");
  write_file(dir / "main.inp",
             "TWICE,4\n*USE,twice,1.5\n/INPUT,part\n/INPUT,part,inp\n/COM,back\n");
  std::ostringstream sink;
  DeckOptions o;
  o.output = &sink;
  read_deck((dir / "main.inp").string(), o);
  EXPECT_EQ(sink.str(), "  8.0\n  3.0\n in part\n in part\n back\n");
}

TEST(DeckControlFlow, RecursionIsRefused) {
  const auto dir = impactfe::testing::fresh_directory("control_flow_recursion");
  write_file(dir / "self.inp", "/COM,x\n/INPUT,self,inp\n");
  try {
    read_deck((dir / "self.inp").string());
    FAIL() << "recursive /INPUT accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("self.inp:2: /INPUT: recursive call refused"),
              std::string::npos)
        << e.what();
  }
  EXPECT_NE(error_of("*CREATE,LOOP\n*USE,LOOP\n*END\n*USE,LOOP\n").find("recursive call refused"),
            std::string::npos);
}

TEST(DeckControlFlow, BoundsGiveClearErrors) {
  // A billion trips are refused up front.
  EXPECT_NE(error_of("*DO,I,1,1E9\n*ENDDO\n").find("mem.inp:1: *DO: 1e+09 trips refused"),
            std::string::npos);
  // 20,000 nested *IF blocks: a clear error, not a stack overflow.
  std::string deep;
  for (int i = 0; i < 20000; ++i) deep += "*IF,1,EQ,1,THEN\n";
  for (int i = 0; i < 20000; ++i) deep += "*ENDIF\n";
  EXPECT_NE(error_of(deep).find("mem.inp:101: *IF: *IF blocks nested deeper than 100 levels"),
            std::string::npos);
  std::string deep_do;
  for (int i = 0; i < 25; ++i) deep_do += "*DO,I" + std::to_string(i) + ",1,1\n";
  for (int i = 0; i < 25; ++i) deep_do += "*ENDDO\n";
  EXPECT_NE(error_of(deep_do).find("mem.inp:21: *DO: *DO loops nested deeper than 20"),
            std::string::npos);
  // A line of megabytes is refused with a message.
  const std::string long_line = "/COM,ok\nN,1," + std::string(3 << 20, '1') + "\n";
  EXPECT_NE(error_of(long_line).find("mem.inp:2: N: line of 3145732 characters refused"),
            std::string::npos);
  // A loop that never ends (*DOWHILE) stops at the trip bound.
  EXPECT_NE(error_of("N=1\n*DOWHILE,N\n*ENDDO\n").find("does not end"), std::string::npos);
}

TEST(DeckControlFlow, UnbalancedBlocks) {
  EXPECT_NE(error_of("*DO,I,1,2\n/COM,x\n").find("mem.inp:1: *DO: no matching *ENDDO"),
            std::string::npos);
  EXPECT_NE(error_of("*IF,1,EQ,1,THEN\n/COM,x\n").find("mem.inp:1: *IF: no matching *ENDIF"),
            std::string::npos);
  EXPECT_NE(error_of("*ENDIF\n").find("mem.inp:1: *ENDIF: *ENDIF without a matching opening"),
            std::string::npos);
  EXPECT_NE(error_of("*ELSE\n").find("mem.inp:1: *ELSE: *ELSE without a matching opening"),
            std::string::npos);
  EXPECT_NE(error_of("*DO,I,1,2\n*IF,1,EQ,1,THEN\n*ENDDO\n")
                .find("mem.inp:2: *IF: no matching "
                      "*ENDIF"),
            std::string::npos);
  EXPECT_NE(error_of("*CREATE,M\n/COM,x\n").find("mem.inp:1: *CREATE: no *END"), std::string::npos);
  EXPECT_NE(error_of("*IF,1,EQ,1,THEN\n*ELSE\n*ELSE\n*ENDIF\n").find("after the *ELSE"),
            std::string::npos);
  // An error is raised when execution reaches it, as MAPDL reports it: the lines before run.
  std::ostringstream sink;
  DeckOptions o;
  o.output = &sink;
  EXPECT_THROW(read_deck_text("/COM,first\n*ENDDO\n", "mem.inp", o), InputError);
  EXPECT_EQ(sink.str(), " first\n");
}

TEST(DeckControlFlow, ModernAbbreviations) {
  const Job job = run("/PREP7\nSECT,1,SHELL\nSECD,0.25\nET,1,SHELL181\n");
  ASSERT_EQ(job.model.sections.count(1), 1u);
  EXPECT_DOUBLE_EQ(job.model.sections.at(1).data.at(0), 0.25);
  EXPECT_NE(error_of("/PREP7\nSEC,1\n").find("unknown command"), std::string::npos);
  EXPECT_NE(error_of("/PO\n").find("unknown command"), std::string::npos);  // too short
  EXPECT_NE(error_of("/POST\n").find("ambiguous abbreviation"), std::string::npos);
}

TEST(DeckControlFlow, SkipUnknownCountsWhatItSkipped) {
  DeckOptions o;
  o.skip_unknown = true;
  o.dialect = Dialect::Modern;
  const Job job = read_deck_text("PLCAMP,1\n,2\nJPGPRF\nPLCAMP\n/PREP7\nN,1\n", "mem.inp", o);
  ASSERT_EQ(job.skipped_unknown.size(), 2u);
  EXPECT_EQ(job.skipped_unknown[0].name, "JPGPRF");
  EXPECT_EQ(job.skipped_unknown[0].count, 1);
  EXPECT_EQ(job.skipped_unknown[1].name, "PLCAMP");
  EXPECT_EQ(job.skipped_unknown[1].count, 3);  // with its repeat line
  EXPECT_EQ(job.skipped_unknown[1].first.line, 1);
  EXPECT_EQ(job.model.nodes.size(), 1u);
}

// --skip-unknown skipped TREF, BFUNIF and CP, and vm3 then gave 40000 instead of 19695: it now
// skips only graphics, printing and GUI commands and stops at any other unknown command.
TEST(DeckControlFlow, SkipUnknownStopsAtACommandThatMayChangeTheAnswer) {
  DeckOptions o;
  o.skip_unknown = true;
  o.dialect = Dialect::Modern;
  for (const char* name : {"CEINTF,0.1", "BFE,1,TEMP,1,80", "FOO"}) {
    try {
      read_deck_text(std::string("/PREP7\nJPGPRF,500,100,1\n") + name + "\nN,1\n", "mem.inp", o);
      ADD_FAILURE() << name << " skipped";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("mem.inp:3: " + std::string(name).substr(0, std::string(name).find(',')) +
                          ": unknown command"),
                std::string::npos)
          << what;
      EXPECT_NE(what.find("may"), std::string::npos) << what;
    }
  }
  // Abbreviations and longer spellings of a listed command are that command (four characters).
  for (const char* name :
       {"JPEG,QUAL,100", "JPGP", "PLCA", "PLCAMPBELL", "/VSCALE,1,2", "*VPLOT,X(1),Y(1)"})
    EXPECT_NO_THROW(read_deck_text(std::string(name) + "\n", "mem.inp", o)) << name;
}

// The list of skippable commands and the command table stay apart: a command the program carries
// out is never skipped, and a skippable one is never half carried out.
// TREF, BFUNIF and CP are carried out under --skip-unknown as without it (none is skipped).
TEST(DeckControlFlow, SkipUnknownCarriesOutThermalLoadsAndCouplings) {
  DeckOptions o;
  o.skip_unknown = true;
  o.dialect = Dialect::Modern;
  const Job job = read_deck_text(
      "/PREP7\nN,4\nN,5,1\nN,6,2\nTREF,70\nBFUNIF,TEMP,80\nCP,1,UY,5,4,6\n", "mem.inp", o);
  EXPECT_TRUE(job.skipped_unknown.empty());
  EXPECT_EQ(job.model.current.reference_temperature, 70.0);
  EXPECT_EQ(job.model.current.uniform_temperature.value_or(0.0), 80.0);
  ASSERT_EQ(job.model.coupled_sets.count(1), 1u);
  EXPECT_EQ(job.model.coupled_sets.at(1).nodes, (std::vector<int>{5, 4, 6}));
}

TEST(DeckControlFlow, SkippableCommandsAreNotInTheCommandTable) {
  using namespace impactfe::deck;
  for (std::string_view name : commands_without_effect_on_results()) {
    EXPECT_EQ(find_command(std::string(name)), nullptr) << name;
    EXPECT_TRUE(cannot_change_results(std::string(name))) << name;
  }
  for (const auto& spec : command_table())
    EXPECT_FALSE(cannot_change_results(spec.name)) << spec.name;
  EXPECT_FALSE(cannot_change_results("TREF"));
  EXPECT_FALSE(cannot_change_results("CP"));
  EXPECT_FALSE(cannot_change_results("BFUNIF"));
}

TEST(DeckControlFlow, PercentSubstitution) {
  const Job job =
      run("/PREP7\nN=3\nX=0.25\n/COM,node %N% at %X% (100%%)\nLAB='UY'\n"
          "N,%N%,%X*4%\n/TITLE,case %N%\n",
          nullptr);
  EXPECT_EQ(job.model.title, "case 3");
  EXPECT_DOUBLE_EQ(job.model.node(3).x.x(), 1.0);
  EXPECT_EQ(output_of("N=3\n/COM,node %N% of %2*N% (100%%)\n"), " node 3 of 6 (100%)\n");
  // A character parameter in a label field is its text (D,1,LAB,0 = D,1,UY,0).
  const Job d = run("/PREP7\nET,1,LINK180\nN,1\nLAB='UY'\nD,1,LAB,0\n");
  EXPECT_EQ(d.model.current.constraints.count(DofKey{1, Dof::UY}), 1u);
}

/// The error of `text` read with at most `budget` commands and loop trips ("" if none).
std::string error_within(const std::string& text, long long budget,
                         Dialect dialect = Dialect::Modern) {
  DeckOptions o;
  o.dialect = dialect;
  o.max_commands = budget;
  std::ostringstream sink;
  o.output = &sink;
  try {
    read_deck_text(text, "mem.inp", o);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(DeckControlFlow, InterpretedWorkIsBounded) {
  // A loop of 10 trips with one command: the *DO, 10 trips and 10 commands = 21 units.
  const std::string loop = "*DO,I,1,10\nA=I\n*ENDDO\n";
  EXPECT_EQ(error_within(loop, 21), "");
  EXPECT_NE(error_within(loop, 20).find("mem.inp:2: *SET: more than 20 commands and loop trips"),
            std::string::npos);
  // Empty loops count their trips: nested 10⁷ × 10⁷ trips stop at the budget, not in days.
  EXPECT_NE(error_within("*DO,I,1,1E7\n*DO,J,1,1E7\n*ENDDO\n*ENDDO\n", 1000)
                .find("mem.inp:2: *DO: more than 1000 commands and loop trips executed"),
            std::string::npos);
  // *REPEAT counts its repetitions.
  EXPECT_NE(error_within("/PREP7\nN,1\n*DO,I,1,1E7\n*REPEAT,1E7\n*ENDDO\n", 1000)
                .find("mem.inp:4: *REPEAT: more than 1000"),
            std::string::npos);
  // *DOWHILE trips, and 4x *DO block passes over an empty block.
  EXPECT_NE(error_within("N=1\n*DOWHILE,N\n*ENDDO\n", 1000).find("mem.inp:2: *DOWHILE: more"),
            std::string::npos);
  EXPECT_NE(error_within("*BEGIN,EMPTY\n*END\n*DO,EMPTY,1,100000\n", 1000, Dialect::Classic4x)
                .find("mem.inp:3: *DO: more than 1000"),
            std::string::npos);
}

TEST(DeckControlFlow, FourXBlocksStillReplay) {
  // Thesis decks: *SET,NJIT,1,5 then *DO,MARC,1,3 over a *BEGIN block (APDL_SUBSET §3.29).
  std::string out;
  run("*SET,NJIT,1,5\n*BEGIN,MARC\n*VWRITE,NJIT\n(F4.0)\n*END\n*DO,MARC,1,3\n", &out,
      Dialect::Classic4x);
  EXPECT_EQ(out, "  1.\n  6.\n 11.\n");
}

}  // namespace test_deck_control_flow
