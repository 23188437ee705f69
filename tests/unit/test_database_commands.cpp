// /CLEAR, SAVE and RESUME (APDL_SCRIPTING §A.15): several jobs in one deck, each with its own
// results file; the database written and read back.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "../support/run_deck.h"
#include "analysis/job_session.h"
#include "deck/deck_reader.h"
#include "results/results_file.h"

namespace test_database_commands {

using namespace impactfe;

namespace {

/// A spring (k) fixed at node 1 pulled by F at node 2: UX(2) = F / k.
std::string spring_job(const std::string& name, double k, double f) {
  std::ostringstream d;
  d << "/FILNAME," << name << "\n/PREP7\nET,1,COMBIN14\nR,1," << k
    << "\nN,1\nN,2,1\nE,1,2\nFINISH\n/SOLU\nANTYPE,STATIC\nD,1,ALL\nF,2,FX," << f
    << "\nSOLVE\nFINISH\n";
  return d.str();
}

struct DeckRunResult {
  std::string out;
  std::vector<std::string> files;
  Job job;
};

DeckRunResult run_with_session(const std::filesystem::path& dir, const std::string& text) {
  const auto previous = std::filesystem::current_path();
  std::filesystem::current_path(dir);
  DeckRunResult run;
  std::ostringstream sink;
  RunStatistics stats;
  try {
    JobSession session("deck", RunSettings{}, stats);
    DeckOptions o;
    o.host = &session;
    o.output = &sink;
    o.dialect = Dialect::Modern;
    run.job = read_deck_text(text, (dir / "deck.inp").string(), o);
    run.files = session.results_files();
  } catch (...) {
    std::filesystem::current_path(previous);
    throw;
  }
  std::filesystem::current_path(previous);
  run.out = sink.str();
  return run;
}

double final_ux(const std::filesystem::path& file, int node) {
  ResultsReader reader(file.string());
  return reader.nodal_series(node, "UX").back().second;
}

}  // namespace

TEST(DatabaseCommands, ClearStartsANewJobAndResultsFile) {
  const auto dir = impactfe::testing::fresh_directory("database_clear");
  const std::string deck = "K0 = 1\n" + spring_job("first", 100.0, 10.0) + "/CLEAR\n" +
                           spring_job("second", 200.0, 10.0) + "*VWRITE,1\n(F3.0)\n";
  const DeckRunResult run = run_with_session(dir, deck);
  ASSERT_EQ(run.files.size(), 2u);
  EXPECT_EQ(run.files[0], "first.h5");
  EXPECT_EQ(run.files[1], "second.h5");
  EXPECT_NEAR(final_ux(dir / "first.h5", 2), 0.1, 1e-12);
  EXPECT_NEAR(final_ux(dir / "second.h5", 2), 0.05, 1e-12);
  // The job returned is the one after the last /CLEAR.
  EXPECT_EQ(run.job.steps.size(), 1u);
  EXPECT_EQ(run.job.model.real_sets.at(1).values.at(0), 200.0);
}

TEST(DatabaseCommands, ClearDeletesParametersAndResetsSettings) {
  const auto dir = impactfe::testing::fresh_directory("database_clear_params");
  try {
    // X = K0 alone would take MAPDL's undefined-parameter value (warned); in an expression
    // an undefined name is an error.
    run_with_session(dir, "K0 = 1\n*AFUN,DEG\n/CLEAR\nX = K0+1\n");
    FAIL() << "parameter survived /CLEAR";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(":4: *SET: bad expression 'K0"), std::string::npos)
        << e.what();
  }
  const DeckRunResult run =
      run_with_session(dir,
                       "*CREATE,KEEP\n/COM,kept\n*END\n*AFUN,DEG\n/OUT,x,txt\n/CLEAR\n*USE,KEEP\n"
                       "*VWRITE,SIN(30)\n(F6.3)\n");
  EXPECT_EQ(run.out, " kept\n-0.988\n");  // *CREATE files survive, radians again, terminal again
}

TEST(DatabaseCommands, ClearStartsNewModelingAndSolutionStates) {
  // The TB table that TBDATA fills, the TYPE pointer and the 4x /STRESS block belong to the old
  // database: after /CLEAR a TBDATA without TB is an error, not data for a table that is gone.
  const auto dir = impactfe::testing::fresh_directory("database_clear_modeling");
  try {
    run_with_session(dir,
                     "/PREP7\nMP,EX,1,2E5\nTB,BISO,1\nTBDATA,1,250,1000\n/CLEAR\n/PREP7\n"
                     "MP,EX,1,2E5\nTBDATA,1,300,2000\n");
    FAIL() << "TBDATA wrote into a table of the cleared database";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(":8: TBDATA: no TB table is active"), std::string::npos)
        << e.what();
  }
  try {
    run_with_session(dir,
                     "/PREP7\nET,3,COMBIN14\nTYPE,3\n/CLEAR\n/PREP7\nET,1,COMBIN14\n"
                     "R,1,10\nN,1\nN,2,1\nE,1,2\n");
  } catch (const InputError& e) {
    FAIL() << "TYPE pointer survived /CLEAR: " << e.what();
  }
}

TEST(DatabaseCommands, SaveAndResumeWeighByTheSizeOfTheDatabase) {
  // A loop of SAVEs and RESUMEs costs time per database byte, not per command: each weighs
  // 1000 units of the interpreted-work budget (DeckOptions::max_commands) plus one per 16 bytes
  // of the file. A line of 401 nodes writes about 10 kB, so each SAVE or RESUME weighs about
  // 1600 units: a budget of six of them takes 3 trips of SAVE + RESUME but not 4 (with the
  // constant 1000 units of stop 29 the 4th trip would fit as well).
  const auto dir = impactfe::testing::fresh_directory("database_work");
  const auto previous = std::filesystem::current_path();
  std::filesystem::current_path(dir);
  const std::string model = "/PREP7\nN,1\nN,401,400\nFILL\n";
  const auto error_of = [&](int trips, long long budget) -> std::string {
    DeckOptions o;
    o.dialect = Dialect::Modern;
    o.max_commands = budget;
    try {
      read_deck_text(model + "*DO,I,1," + std::to_string(trips) + "\nSAVE\nRESUME\n*ENDDO\n",
                     "loop.inp", o);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  const std::string once = error_of(1, 1'000'000);
  const auto bytes = static_cast<long long>(std::filesystem::file_size(dir / "loop.db"));
  const long long per_operation = 1000 + bytes / 16;
  const long long budget = 6 * per_operation + 50;  // 50: the commands and loop trips
  const std::string within = error_of(3, budget);
  const std::string over = error_of(4, budget);
  std::filesystem::current_path(previous);
  EXPECT_EQ(once, "");
  EXPECT_GT(bytes, 8000);  // the size term matters: over 500 units per database operation
  EXPECT_EQ(within, "");
  EXPECT_NE(over.find(fmt::format("loop.inp:6: SAVE: more than {} commands and loop trips "
                                  "executed (a SAVE or RESUME counts as 1000 plus one per 16 "
                                  "bytes of the database)",
                                  budget)),
            std::string::npos)
      << over;
}

TEST(DatabaseCommands, SaveAndResume) {
  const auto dir = impactfe::testing::fresh_directory("database_save");
  const std::string deck = R"(/PREP7
ET,1,COMBIN14
R,1,100
N,1
N,2,1
E,1,2
M,2,UX
*DIM,V,,3
V(1) = 1,2,3
*DIM,LBL,CHAR,2
LBL(1) = 'A','B'
TXT = 'hello'
D,1,ALL
F,2,FX,10
SAVE
SAVE,model,sav,,MODEL
/CLEAR
RESUME
*VWRITE,V(1),LBL(1)
(F4.1,1X,A)
/CLEAR
RESUME,model,sav
)";
  const DeckRunResult run = run_with_session(dir, deck);
  EXPECT_EQ(run.out, " 1.0 A\n 2.0 B\n 3.0 \n");
  ASSERT_TRUE(std::filesystem::exists(dir / "deck.db"));
  EXPECT_EQ(run.job.model.nodes.size(), 2u);
  EXPECT_EQ(run.job.model.elements.at(1).nodes, (std::vector<int>{1, 2}));
  EXPECT_EQ(run.job.model.masters.size(), 1u);
  EXPECT_TRUE(run.job.model.current.forces.empty());  // MODEL: no loads
  // The full database restores the loads, and a solve after RESUME works.
  const DeckRunResult solved =
      run_with_session(dir, "RESUME\n/SOLU\nANTYPE,STATIC\nSOLVE\nFINISH\n");
  ASSERT_EQ(solved.files.size(), 1u);
  EXPECT_NEAR(final_ux(dir / solved.files[0], 2), 0.1, 1e-12);
  // NOPAR = 1 keeps the current parameters.
  const DeckRunResult kept = run_with_session(dir, "V = 5\nRESUME,,,,1\n*VWRITE,V\n(F3.0)\n");
  EXPECT_EQ(kept.out, " 5.\n");
  try {
    run_with_session(dir, "RESUME,missing\n");
    FAIL() << "missing database accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("RESUME: no database file 'missing.db'"),
              std::string::npos);
  }
}

TEST(DatabaseCommands, SaveAndResumeATitleThatIsNotUtf8) {
  // Bytes that are not UTF-8 (here Latin-1 "ß" and a stray 0x8A) come back as U+FFFD (found by
  // the fuzzer: the JSON library threw "invalid UTF-8 byte" out of SAVE).
  const auto dir = impactfe::testing::fresh_directory("database_latin1");
  const DeckRunResult run =
      run_with_session(dir, "/TITLE,Sto\xdf \x8a test\n/PREP7\nN,1\nSAVE\n/CLEAR\nRESUME\n");
  EXPECT_EQ(run.job.model.title, "Sto\xef\xbf\xbd \xef\xbf\xbd test");
  EXPECT_EQ(run.job.model.nodes.size(), 1u);
}

TEST(DatabaseCommands, SaveAndResumeKeepOutresPerItem) {
  const auto dir = impactfe::testing::fresh_directory("database_outres");
  const std::string deck = R"(/PREP7
ET,1,COMBIN14
R,1,100
N,1
N,2,1
N,3,2
E,1,2
E,2,3
NSEL,S,NODE,,2,3
CM,TIP,NODE
ALLSEL
FINISH
/SOLU
ANTYPE,TRANS
OUTRES,ALL,NONE
OUTRES,NSOL,5,TIP
OUTRES,RSOL,2
SAVE
/CLEAR
RESUME
)";
  const DeckRunResult run = run_with_session(dir, deck);
  const OutputControl& out = run.job.model.current.output;
  EXPECT_EQ(out.every, -1);
  const auto& nsol = out.items[static_cast<int>(OutputItem::NSOL)];
  ASSERT_EQ(nsol.size(), 2u);  // NONE for every node, then every 5th for TIP
  EXPECT_EQ(nsol[0].every, -1);
  EXPECT_TRUE(nsol[0].component.empty());
  EXPECT_EQ(nsol[1].every, 5);
  EXPECT_EQ(nsol[1].component, "TIP");
  EXPECT_EQ(nsol[1].ids, (std::vector<int>{2, 3}));
  const auto& rsol = out.items[static_cast<int>(OutputItem::RSOL)];
  ASSERT_EQ(rsol.size(), 1u);
  EXPECT_EQ(rsol[0].every, 2);
  EXPECT_TRUE(out.items[static_cast<int>(OutputItem::VSOL)].empty());
  // A database written before OUTRES per item (no output_items) resumes with its frequency.
  {
    std::ifstream in(dir / "deck.db");
    nlohmann::json j = nlohmann::json::parse(in);
    ASSERT_TRUE(j.at("loads").contains("output_items"));
    j["loads"].erase("output_items");
    std::ofstream(dir / "old.db") << j.dump(1) << '\n';
  }
  const DeckRunResult old = run_with_session(dir, "RESUME,old,db\n");
  EXPECT_EQ(old.job.model.current.output.every, -1);
  EXPECT_TRUE(old.job.model.current.output.uniform());
}

// Solution controls belong to the model (issue 16): AUTOTS, the DELTIM / NSUBST limits and
// RESCONTROL are part of the load state, saved and resumed with it, reset by /CLEAR, and not
// shared between two decks read in one process.
TEST(DatabaseCommands, SolutionControlsAreSavedResumedAndCleared) {
  const auto dir = impactfe::testing::fresh_directory("database_controls");
  const std::string model = "/PREP7\nET,1,COMBIN14\nR,1,100\nN,1\nN,2,1\nE,1,2\nFINISH\n";
  const std::string deck = model +
                           "/SOLU\nANTYPE,TRANS\nAUTOTS,ON\nDELTIM,0.01,1E-4,0.02,ON\n"
                           "RESCONTROL,DEFINE,ALL,5\nTIME,1\nSAVE,ctl,db\n/CLEAR\n" +
                           "RESUME,ctl,db\n/SOLU\nANTYPE,TRANS\nLSWRITE,1\n";
  DeckOptions o;
  o.dialect = Dialect::Modern;
  const auto previous = std::filesystem::current_path();
  std::filesystem::current_path(dir);
  Job resumed, cleared, other;
  try {
    resumed = read_deck_text(deck, "deck.inp", o);
    // /CLEAR drops them: the job after it has the defaults.
    cleared = read_deck_text(model + "/SOLU\nAUTOTS,ON\nNSUBST,10,100,2\nRESCONTROL\n/CLEAR\n" +
                                 model + "/SOLU\nLSWRITE,1\n",
                             "cleared.inp", o);
    other = read_deck_text(model + "/SOLU\nLSWRITE,1\n", "other.inp", o);
  } catch (...) {
    std::filesystem::current_path(previous);
    throw;
  }
  std::filesystem::current_path(previous);
  const LoadStep& s = resumed.model.current;
  ASSERT_TRUE(s.control.automatic.has_value());
  EXPECT_TRUE(*s.control.automatic);
  EXPECT_EQ(s.control.dt_min, 1e-4);
  EXPECT_EQ(s.control.dt_max, 0.02);
  EXPECT_TRUE(s.control.carry);
  EXPECT_FALSE(s.control.n_max.has_value());
  EXPECT_TRUE(s.rescontrol.defined);
  EXPECT_EQ(s.rescontrol.load_steps, 1);
  EXPECT_EQ(s.rescontrol.frequency, 5);
  EXPECT_EQ(s.dt, 0.01);
  EXPECT_EQ(s.time_end, 1.0);
  for (const Job* j : {&cleared, &other}) {
    const LoadStep& d = j->model.current;
    EXPECT_FALSE(d.control.automatic.has_value());
    EXPECT_FALSE(d.control.dt_min || d.control.dt_max || d.control.n_max || d.control.n_min);
    EXPECT_FALSE(d.control.carry);
    EXPECT_FALSE(d.rescontrol.defined);
  }
  // The saved file lists them (docs/deck_reader.md, "Database file").
  std::ifstream in(dir / "ctl.db");
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j.at("loads").at("step_control").at("autots"), true);
  EXPECT_EQ(j.at("loads").at("step_control").at("rescontrol")[2], 5);
}

}  // namespace test_database_commands
