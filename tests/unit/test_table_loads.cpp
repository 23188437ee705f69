// Time-function loads (`%TABLE%`, APDL_MODELING §5.5) on the load side: a load value that is a
// reference to a time function is evaluated at each substep's time, whatever KBC says, for F, D,
// ACEL and face pressures. The TABLE parameters themselves belong to the scripting layer; here the
// functions are put into the model directly, as the deck's TABLE arrays will be.
#include <gtest/gtest.h>

#include <filesystem>

#include "../support/run_deck.h"
#include "analysis/job_session.h"
#include "deck/deck_reader.h"

namespace impactfe::test_table_loads {
namespace {

/// Reads `deck` without solving, lets `edit` change the first analysis (model snapshot and load
/// steps), then solves it like `impactfe run` and returns the results.
std::unique_ptr<ResultsReader> solve_edited(const std::string& tag, const std::string& deck,
                                            const std::function<void(Job::Step&)>& edit) {
  namespace fs = std::filesystem;
  Job job = read_deck_text(deck, tag + ".inp", DeckOptions{});
  EXPECT_EQ(job.steps.size(), 1u);
  edit(job.steps.front());
  const fs::path dir = testing::fresh_directory(tag);
  const fs::path previous = fs::current_path();
  fs::current_path(dir);
  RunStatistics stats;
  {
    JobSession session(tag, RunSettings{}, stats);
    session.solve(job, 0);
    session.finish(job);
  }
  fs::current_path(previous);
  return std::make_unique<ResultsReader>((dir / (tag + ".h5")).string());
}

TimeFunction pulse() {
  return TimeFunction{{0.0, 1.0, 2.0}, {0.0, 100.0, 50.0}};
}

const char* kSpring =
    "/PREP7\nET,1,COMBIN14\nR,1,100\nN,1\nN,2,1\nE,1,2\nFINISH\n/SOLU\nANTYPE,STATIC\n"
    "D,1,ALL\nD,2,UY,,,,,UZ\nNSUBST,4\nOUTRES,ALL,ALL\nTIME,2\n";

TEST(TableLoads, ForceFollowsItsTimeFunction) {
  const auto results =
      solve_edited("table_force", std::string(kSpring) + "F,2,FX,1\nSOLVE\n", [](Job::Step& s) {
        s.model_snapshot->time_functions["PULL"] = pulse();
        s.analysis->load_steps[0].force_tables[{2, Dof::UX}] = "PULL";
      });
  const auto ux = results->nodal_series(2, "UX");
  ASSERT_EQ(ux.size(), 4u);
  const double expected[4] = {0.5, 1.0, 0.75, 0.5};  // F(t) / k at t = 0.5, 1, 1.5, 2
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_NEAR(ux[k].first, 0.5 * (k + 1), 1e-12);
    EXPECT_NEAR(ux[k].second, expected[k], 1e-12);
  }
}

TEST(TableLoads, DisplacementAccelerationAndPressureTables) {
  // Prescribed displacement: u(t) from the table, the spring reaction follows.
  const auto d =
      solve_edited("table_disp", std::string(kSpring) + "D,2,UX,1\nSOLVE\n", [](Job::Step& s) {
        s.model_snapshot->time_functions["PULL"] = pulse();
        s.analysis->load_steps[0].constraint_tables[{2, Dof::UX}] = "PULL";
      });
  const auto ux = d->nodal_series(2, "UX");
  ASSERT_EQ(ux.size(), 4u);
  EXPECT_NEAR(ux[0].second, 50.0, 1e-12);
  EXPECT_NEAR(ux[3].second, 50.0, 1e-12);
  EXPECT_NEAR(d->nodal_series(2, "FX")[1].second, 100.0 * 100.0, 1e-8);
  // Frame acceleration on a point mass held by the spring: static u = −m a(t) / k.
  const auto a = solve_edited(
      "table_acel",
      "/PREP7\nET,1,COMBIN14\nET,2,MASS21,,,2\nR,1,100\nR,2,3\nN,1\nN,2,1\nTYPE,1\nREAL,1\n"
      "E,1,2\nTYPE,2\nREAL,2\nE,2\nFINISH\n/SOLU\nANTYPE,STATIC\nD,1,ALL\nD,2,UY,,,,,UZ\n"
      "NSUBST,4\nOUTRES,ALL,ALL\nTIME,2\nACEL,1\nSOLVE\n",
      [](Job::Step& s) {
        s.model_snapshot->time_functions["G"] = pulse();
        s.analysis->load_steps[0].acel_tables[0] = "G";
      });
  EXPECT_NEAR(a->nodal_series(2, "UX")[1].second, -3.0 * 100.0 / 100.0, 1e-12);
  // Face pressure: a unit cube on its bottom face, pressure p(t) on top; the bottom reactions
  // sum to p(t) · 1.
  const auto p = solve_edited(
      "table_pres",
      "/PREP7\nET,1,SOLID185\nMP,EX,1,1E4\nBLOCK,0,1,0,1,0,1\nESIZE,1\nVMESH,1\nFINISH\n/SOLU\n"
      "ANTYPE,STATIC\nNSEL,S,LOC,Z,0\nD,ALL,ALL\nNSEL,S,LOC,Z,1\nSF,ALL,PRES,1\nALLSEL\n"
      "NSUBST,4\nOUTRES,ALL,ALL\nTIME,2\nSOLVE\n",
      [](Job::Step& s) {
        s.model_snapshot->time_functions["P"] = pulse();
        for (auto& [face, load] : s.analysis->load_steps[0].pressures) load.table = "P";
      });
  const std::vector<double> expected = {50, 100, 75, 50};
  for (std::size_t k = 0; k < 4; ++k) {
    double sum = 0.0;
    for (int node : {1, 2, 3, 4})
      sum += testing::value_at(p->nodal_series(node, "FZ"), 0.5 * (k + 1));
    EXPECT_NEAR(sum, expected[k], 1e-8) << k;
  }
}

TEST(TableLoads, AnUndefinedTableIsADeckError) {
  try {
    read_deck_text(std::string(kSpring) + "F,2,FX,%PULL%\n", "t.inp", DeckOptions{});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("table %PULL% is not defined"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace impactfe::test_table_loads
