// Static analysis through the job runner: an unrestrained model stops with a message naming the
// node and DOF (issue 2), and a regular one solves (the verification decks cover the values) and
// reports its linear-solver figures (run summary, results attributes, bench/).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include "../support/run_deck.h"
#include "../support/stored_chunks.h"
#include "results/result_series.h"

namespace impactfe::test_static_analysis {
namespace {

std::string run_text_expecting_error(const std::string& text) {
  try {
    testing::run_deck_text("static_singular", text);
  } catch (const ModelError& e) {
    return e.what();
  }
  return "";
}

TEST(StaticAnalysis, UnrestrainedModelNamesTheNodeAndDof) {
  // A spar along X fixed only in UY/UZ at both ends and in UX nowhere: rigid in X.
  const std::string message = run_text_expecting_error(
      "/PREP7\nET,1,LINK180\nSECTYPE,1,LINK\nSECDATA,1\nMP,EX,1,30E6\nN,1\nN,2,10\nE,1,2\n"
      "FINISH\n/SOLU\nANTYPE,STATIC\nD,1,UY,,,2,1,UZ\nF,2,FX,100\nSOLVE\nFINISH\n");
  EXPECT_NE(message.find("singular"), std::string::npos) << message;
  EXPECT_TRUE(message.find("node 1 UX") != std::string::npos ||
              message.find("node 2 UX") != std::string::npos)
      << message;
}

TEST(StaticAnalysis, MassOnlyDofIsSingularInAStaticSolve) {
  // A point mass hanging on nothing in Y: mass but no stiffness is legitimate in a transient and
  // singular in a static solve (spec §10.1 item 5).
  const std::string message = run_text_expecting_error(
      "/PREP7\nET,1,COMBIN14,,1\nET,2,MASS21,,,4\nR,1,100\nR,2,1\nN,1\nN,2,1\nTYPE,1\nREAL,1\n"
      "E,1,2\nTYPE,2\nREAL,2\nE,2\nFINISH\n/SOLU\nANTYPE,STATIC\nD,1,ALL\nF,2,FX,10\nSOLVE\n"
      "FINISH\n");
  EXPECT_NE(message.find("node 2 UY"), std::string::npos) << message;
}

TEST(StaticAnalysis, ReportsLinearSolverFiguresInStatisticsAndResults) {
  // A chain of n UX springs (k = 100) fixed at node 1, pulled by 10 at node n + 1: n free DOFs,
  // a tridiagonal K (2n - 1 nonzeros in its lower triangle), tip displacement n * 10 / 100.
  const int n = 100;
  std::ostringstream text;
  text << "/PREP7\nET,1,COMBIN14,,1\nR,1,100\n";
  for (int i = 1; i <= n + 1; ++i) text << "N," << i << "," << i - 1 << "\n";
  for (int i = 1; i <= n; ++i) text << "E," << i << "," << i + 1 << "\n";
  text << "FINISH\n/SOLU\nANTYPE,STATIC\nD,1,ALL\nF," << n + 1 << ",FX,10\nSOLVE\nFINISH\n";
  const auto dir = testing::fresh_directory("static_solver_figures");
  const std::string deck = (dir / "chain.inp").string();
  {
    std::ofstream out(deck);
    out << text.str();
  }
  const auto run = testing::run_deck_in(deck, dir);
  ASSERT_EQ(run.statistics.analyses.size(), 1u);
  const AnalysisStatistics& a = run.statistics.analyses[0];
  EXPECT_EQ(a.n_dofs, n);
  EXPECT_EQ(a.n_factorizations, 1);
  EXPECT_EQ(a.matrix_nonzeros, 2 * n - 1);
  EXPECT_GE(a.factor_nonzeros, a.matrix_nonzeros);  // fill-in is never negative
  EXPECT_GE(a.factor_bytes, static_cast<long>(sizeof(double)) * a.factor_nonzeros);
  EXPECT_GT(a.factorize_seconds, 0.0);
  EXPECT_GT(a.solve_seconds, 0.0);
  const auto attributes = run.reader->analyses()[0].numeric_attributes;  // a copy
  EXPECT_EQ(attributes.at("matrix_nonzeros"), static_cast<double>(a.matrix_nonzeros));
  EXPECT_EQ(attributes.at("factor_nonzeros"), static_cast<double>(a.factor_nonzeros));
  EXPECT_EQ(attributes.at("factor_bytes"), static_cast<double>(a.factor_bytes));
  EXPECT_EQ(attributes.at("solves"), static_cast<double>(a.n_solves));
  EXPECT_DOUBLE_EQ(attributes.at("factorize_seconds"), a.factorize_seconds);
  const auto tip = run.reader->nodal_series(n + 1, "UX");
  ASSERT_FALSE(tip.empty());
  EXPECT_NEAR(tip.back().second, n * 10.0 / 100.0, 1e-9);
}

/// Nodal tables of nodes numbered far apart (ids spanning more than 4 × their number + 1024: the
/// tables' rows are then found through a map) and of nodes numbered with a gap (by a vector over
/// the span): two LINK1 spars pulled by FX = 600 at the far end, UX = F L / (E A) per spar, the
/// reaction -600 at the fixed end.
TEST(StaticAnalysis, NodalTablesOfSparselyAndDenselyNumberedNodes) {
  for (const auto& [middle, end] : {std::pair{500000, 123456789}, std::pair{50, 90}}) {
    SCOPED_TRACE(end);
    const std::string text =
        "/PREP7\nET,1,LINK1\nR,1,2.0\nMP,EX,1,30E6\nN,7,0,0\nN," + std::to_string(middle) +
        ",10,0\nN," + std::to_string(end) + ",20,0\nE,7," + std::to_string(middle) + "\nE," +
        std::to_string(middle) + "," + std::to_string(end) + "\nD,7,UX\nD,7,UY\nD," +
        std::to_string(middle) + ",UY\nD," + std::to_string(end) + ",UY\nF," + std::to_string(end) +
        ",FX,600\nFINISH\n/SOLU\nANTYPE,STATIC\nSOLVE\nFINISH\n";
    const auto run = testing::run_deck_text("static_node_ids", text);
    const TimePoint p = run.reader->time_point(1, 0);
    const std::vector<int>& ids = run.reader->node_ids();
    ASSERT_EQ(ids.size(), 3u);
    const auto row = [&](int id) {
      return static_cast<Eigen::Index>(std::find(ids.begin(), ids.end(), id) - ids.begin());
    };
    EXPECT_NEAR(p.displacement(row(middle), 0), 1e-4, 1e-15);  // 600 * 10 / (30e6 * 2)
    EXPECT_NEAR(p.displacement(row(end), 0), 2e-4, 1e-15);
    EXPECT_EQ(p.displacement(row(7), 0), 0.0);
    EXPECT_NEAR(p.reaction(row(7), 0), -600.0, 1e-9);
    EXPECT_TRUE(std::isnan(p.reaction(row(end), 0)));  // not constrained in UX
  }
}

/// Element results come in one table per family, rows in element order, whatever the order in
/// which the families' elements are numbered: a series chain whose spars (elements 1, 3) and
/// springs (2, 4) alternate carries the end force in every element, at each load step.
TEST(StaticAnalysis, ElementResultsOfInterleavedFamiliesAtEveryStoredPoint) {
  const std::string text =
      "/PREP7\nET,1,LINK1\nET,2,COMBIN14\nR,1,2.0\nR,2,1000\nMP,EX,1,30E6\n"
      "N,1,0\nN,2,10\nN,3,11\nN,4,21\nN,5,22\n"
      "TYPE,1\nREAL,1\nE,1,2\nTYPE,2\nREAL,2\nE,2,3\nTYPE,1\nREAL,1\nE,3,4\n"
      "TYPE,2\nREAL,2\nE,4,5\n"
      "D,1,UX\nD,ALL,UY\nD,ALL,UZ\nFINISH\n/SOLU\nANTYPE,STATIC\n"
      "F,5,FX,600\nSOLVE\nF,5,FX,-150\nSOLVE\nFINISH\n";
  const auto run = testing::run_deck_text("static_interleaved_families", text);
  for (const auto& [point, force] : {std::pair{0, 600.0}, std::pair{1, -150.0}}) {
    SCOPED_TRACE(point);
    const TimePoint p = run.reader->time_point(1, point);
    ASSERT_EQ(p.element_results.size(), 2u);
    const ElementResultTable& spars = p.element_results.at("Spar");
    const ElementResultTable& springs = p.element_results.at("SpringDamper");
    EXPECT_EQ(spars.element_ids, (std::vector<int>{1, 3}));
    EXPECT_EQ(springs.element_ids, (std::vector<int>{2, 4}));
    ASSERT_EQ(spars.item_names.front(), "FORC");
    ASSERT_EQ(springs.item_names, (std::vector<std::string>{"FORC", "STRETCH", "SENE"}));
    for (int r = 0; r < 2; ++r) {
      EXPECT_NEAR(spars.values(r, 0), force, 1e-9 * 600.0);
      EXPECT_NEAR(springs.values(r, 0), force, 1e-9 * 600.0);
      EXPECT_NEAR(springs.values(r, 1), force / 1000.0, 1e-9 * 0.6);            // stretch = F / k
      EXPECT_NEAR(springs.values(r, 2), force * force / 2000.0, 1e-9 * 180.0);  // F² / (2 k)
    }
  }
}

/// An ANSYS 4.2 deck freezes its load steps (AFWRITE) before /INPUT,27 runs them: the results
/// file then sizes its time blocks to the points the analysis stores. The thesis pendulum with
/// ITER,100,1,50 (results at substeps 50 and 100) stores 3 points, the initial state included:
/// blocks of 4. The same analysis from SOLVE, which later SOLVEs may continue, keeps blocks of
/// 64; ITER,101,5,1 as the thesis wrote it (NPOST 1) stores 102 points: blocks of 64 too.
TEST(StaticAnalysis, FrozenLoadStepsGiveTimeBlocksThatFitTheirPoints) {
  const auto deck_text = [](const std::string& deck) {
    std::ifstream in(std::string(IMPACTFE_TEST_DECKS) + "/" + deck);
    std::stringstream all;
    all << in.rdbuf();
    return all.str();
  };
  const auto replaced = [](std::string s, const std::string& from, const std::string& to) {
    const auto at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) s.replace(at, from.size(), to);
    return s;
  };
  const std::string frozen = deck_text("thesis/pendulum1.inp");
  const std::string solved = deck_text("modern/pendulum1_modern.inp");
  struct Case {
    std::string tag, deck;
    std::size_t points;
    hsize_t block;
  };
  const std::vector<Case> cases{
      {"frozen_3", replaced(frozen, "ITER,101,5,1", "ITER,100,1,50"), 3, 4},
      {"frozen_102", frozen, 102, result_series::kMaxBlockRows},
      {"solved_3",
       replaced(replaced(solved, "NSUBST,101,101,101", "NSUBST,100,100,100"), "OUTRES,ALL,1",
                "OUTRES,ALL,50"),
       3, result_series::kMaxBlockRows}};
  for (const Case& c : cases) {
    const auto run = testing::run_deck_text(c.tag, c.deck);
    EXPECT_EQ(run.reader->times(1).size(), c.points) << c.tag;
    EXPECT_EQ(testing::stored_layout(run.results_path, "analysis_1/U").chunk.at(0), c.block)
        << c.tag;
  }
}

}  // namespace
}  // namespace impactfe::test_static_analysis
