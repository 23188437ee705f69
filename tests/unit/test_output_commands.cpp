// Output commands (APDL_SCRIPTING §A.9, §A.14; APDL_MODELING §10.4): *VWRITE looping over
// arrays, /OUT to a file and back, *CFOPEN / *CFWRITE / *CFCLOS, *MSG, *STATUS, *LIST, /COM.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "../support/run_deck.h"
#include "core/log.h"
#include "deck/deck_reader.h"
#include "deck/output.h"

namespace test_output_commands {

using namespace impactfe;

namespace {

std::string run(const std::string& text) {
  std::ostringstream sink;
  DeckOptions o;
  o.dialect = Dialect::Modern;
  o.output = &sink;
  read_deck_text(text, "mem.inp", o);
  return sink.str();
}

std::string error_of(const std::string& text) {
  try {
    run(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

std::string file_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Runs `text` with the working directory in a fresh directory; returns the printed output.
std::string run_in(const std::filesystem::path& dir, const std::string& text) {
  const auto previous = std::filesystem::current_path();
  std::filesystem::current_path(dir);
  std::string out;
  try {
    out = run(text);
  } catch (...) {
    std::filesystem::current_path(previous);
    throw;
  }
  std::filesystem::current_path(previous);
  return out;
}

}  // namespace

TEST(OutputCommands, VwriteLoopsOverArraysFromTheirStart) {
  const std::string deck = R"(*DIM,T,,3
*DIM,U,,2,2
*DIM,NM,CHAR,3
T(1) = 0.1,0.2,0.3
U(1,2) = 5,6
NM(1) = 'A','B','C'
X = 9
*VWRITE,SEQU,NM(1),T(1),U(1,2),X
(F4.0,1X,A4,F8.3,F5.1,F4.0)
*VWRITE,T(2),NM(3)
(F6.2,2X,A)
*VWRITE
(' title line')
*VWRITE,'LABEL',X*2
(A8,F6.1)
)";
  EXPECT_EQ(run(deck),
            "  1.    A   0.100  5.0  9.\n"
            "  2.    B   0.200  6.0  9.\n"
            "  3.    C   0.300  0.0  9.\n"  // the shorter column pads with 0
            "  0.20  C\n"
            "  0.30  \n"  // ... and a CHAR column with blanks
            " title line\n"
            "   LABEL  18.0\n");
}

TEST(OutputCommands, VwriteErrors) {
  EXPECT_NE(error_of("*VWRITE,1\n").find("mem.inp:1: *VWRITE: format line missing"),
            std::string::npos);
  EXPECT_NE(error_of("*VWRITE,1\n(F10)\n").find("mem.inp:1: *VWRITE: bad format '(F10)'"),
            std::string::npos);
  EXPECT_NE(error_of("*DIM,A,,2\n*VWRITE,A(3)\n(F5.1)\n").find("A(3,1,1) is out of range"),
            std::string::npos);
  EXPECT_NE(error_of("*VWRITE,Q\n(F5.1)\n").find("'Q' is not a defined parameter"),
            std::string::npos);
}

TEST(OutputCommands, OutputToAFileAndBack) {
  const auto dir = impactfe::testing::fresh_directory("output_commands_out");
  const std::string out = run_in(dir, R"(/COM,to the terminal
/OUT,table,txt
*VWRITE,1.5
(F6.2)
/COM,in the file
/OUT
/COM,terminal again
/OUT,table,txt,,APPEND
*MSG,INFO,7
appended %I
/OUTPUT,TERM
)");
  EXPECT_EQ(out, " to the terminal\n terminal again\n");
  EXPECT_EQ(file_text(dir / "table.txt"), "  1.50\n in the file\nappended 7\n");
}

TEST(OutputCommands, CommandFiles) {
  const auto dir = impactfe::testing::fresh_directory("output_commands_cf");
  const std::string out = run_in(dir, R"(N = 3
*CFOPEN,cmds,mac
*CFWRITE,N,N,2.5*N,0
*CFWRITE,D,%N%,UX,0
*CFWRITE,A = 5
*CFWRITE,B = ,N*2
*VWRITE,N
('! written ',F3.0)
*CFCLOS
*VWRITE,N
(F3.0)
)");
  EXPECT_EQ(out, " 3.\n");
  EXPECT_EQ(file_text(dir / "cmds.mac"), "N,3,7.5,0\nD,3,UX,0\nA = 5\nB =,6\n! written  3.\n");
  // Without Fname: <jobname>.cmd.
  run_in(dir, "*CFOPEN\n*CFWRITE,FINISH\n*CFCLOS\n");
  EXPECT_EQ(file_text(dir / "mem.cmd"), "FINISH\n");
  EXPECT_NE(error_of("*CFWRITE,N,1\n").find("no command file open"), std::string::npos);
}

TEST(OutputCommands, MessagesAndStatus) {
  Log::clear();
  const std::string out = run(R"(N = 4
LAB = 'UX'
*MSG,NOTE,N,LAB,1.5E-6
%I nodes, label %C, value %G &
continued
*MSG,WARN
careful
*DIM,V,,3
V(1) = 1,2
*STATUS,N
*STATUS,V,2,3
)");
  EXPECT_NE(out.find(" *** NOTE ***\n4 nodes, label UX, value 1.5E-06 continued\n"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find(" *** WARNING ***\ncareful\n"), std::string::npos);
  EXPECT_EQ(Log::warnings().size(), 1u);
  EXPECT_NE(out.find(" N" + std::string(32, ' ') + "4"), std::string::npos) << out;
  EXPECT_NE(out.find("        2       1       1   2\n        3       1       1   0\n"),
            std::string::npos)
      << out;
  EXPECT_NE(error_of("*MSG,ERROR\nstop here %I\n").find("mem.inp:1: *MSG: stop here"),
            std::string::npos);
  // Found by the fuzzer: an empty message line still gives the user a reason, not "".
  EXPECT_NE(error_of("R = 2.5\n*MSG,ERROR,R\n\nN,1\n")
                .find("mem.inp:2: *MSG: *MSG,ERROR stopped the run (its message line is empty)"),
            std::string::npos)
      << error_of("R = 2.5\n*MSG,ERROR,R\n\nN,1\n");
}

// *STATUS,PARM (vm129, vm130) lists the parameters as ALL does; _PRM and PRM_ list only the
// names that begin or end with an underbar (MAPDL *STATUS).
TEST(OutputCommands, StatusParameterGroups) {
  const std::string deck = "A = 1\n_B = 2\nC_ = 3\n*STATUS,";
  const std::string parm = run(deck + "PARM\n");
  EXPECT_NE(parm.find("(1 PARAMETERS DEFINED)"), std::string::npos) << parm;
  EXPECT_NE(parm.find(" A "), std::string::npos) << parm;
  EXPECT_EQ(parm, run(deck + "ALL\n"));
  const std::string under = run(deck + "_PRM\n");
  EXPECT_NE(under.find(" _B "), std::string::npos) << under;
  EXPECT_EQ(under.find(" A "), std::string::npos) << under;
  const std::string trailing = run(deck + "PRM_\n");
  EXPECT_NE(trailing.find(" C_ "), std::string::npos) << trailing;
  EXPECT_EQ(trailing.find(" _B "), std::string::npos) << trailing;
  EXPECT_NE(error_of(deck + "D\n").find("parameter D is not defined"), std::string::npos);
}

TEST(OutputCommands, ListAFile) {
  EXPECT_EQ(run("*CREATE,MAC1,MAC\nN,1\n/COM,x ! kept\n*END\n*LIST,MAC1,MAC\n"),
            "N,1\n/COM,x ! kept\n");
  EXPECT_NE(error_of("*LIST,nothing,here\n").find("not found"), std::string::npos);
}

TEST(OutputCommands, SinkWithoutTerminalLogs) {
  Log::clear();
  deck::OutputSink sink;
  sink.print("line one\nline two");
  EXPECT_EQ(sink.n_lines(), 2);
}

TEST(OutputCommands, DeleteFiles) {
  const auto dir = impactfe::testing::fresh_directory("output_commands_delete");
  std::ofstream(dir / "old.txt") << "x\n";
  run_in(dir, "*CREATE,MAC2,MAC\nN,1\n*END\n/DELETE,old,txt\n/DELETE,MAC2,MAC\n/DELETE,none,txt\n");
  EXPECT_FALSE(std::filesystem::exists(dir / "old.txt"));
  EXPECT_NE(
      error_of("*CREATE,MAC2,MAC\nN,1\n*END\n/DELETE,MAC2,MAC\n*LIST,MAC2,MAC\n").find("not found"),
      std::string::npos);
  EXPECT_THROW(run_in(dir, "/OUT,held,txt\n/DELETE,held,txt\n"), InputError);  // still open
}

}  // namespace test_output_commands
