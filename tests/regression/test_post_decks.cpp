// The thesis's second jobs (pendulum1_post.inp, pendulum2_post.inp, unchanged): POST1 decks that
// read the results of the analysis deck of the same case and draw Fig. 5-1-2 / 5-1-3, the
// pendulum's deformed shape at substeps 1, 6, 11, ..., 96 overlaid under /NOERASE.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>

#include "../support/run_deck.h"
#include "core/errors.h"

namespace impactfe::test_post_decks {
namespace {

namespace fs = std::filesystem;
using testing::fresh_directory;
using testing::run_deck_in;

std::string deck(const std::string& name) {
  return std::string(IMPACTFE_TEST_DECKS) + "/thesis/" + name;
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Runs a deck that solves nothing in `dir` (as `impactfe run` does: the working directory is
/// `dir`), optionally with --results.
void run_post_deck(const std::string& path, const fs::path& dir, const std::string& results = {}) {
  const fs::path previous = fs::current_path();
  fs::current_path(dir);
  try {
    DeckOptions options;
    options.results_file = results;
    read_deck(path, options);
  } catch (...) {
    fs::current_path(previous);
    throw;
  }
  fs::current_path(previous);
}

struct Legend {
  int iter;
  double time, dmax;
};

std::vector<Legend> legends(const std::string& svg) {
  std::vector<Legend> out;
  const std::regex line(R"(STEP=1 ITER=(\d+) TIME=([0-9.eE+-]+) DMAX=([0-9.eE+-]+) DSCA=1<)");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), line); it != std::sregex_iterator();
       ++it)
    out.push_back({std::stoi((*it)[1]), std::stod((*it)[2]), std::stod((*it)[3])});
  return out;
}

void check_motion_picture(const std::string& analysis, const std::string& post,
                          const std::string& tag) {
  const fs::path dir = fresh_directory(tag);
  const auto run = run_deck_in(deck(analysis), dir);
  run_post_deck(deck(post), dir);  // finds <case>.h5 by the name of the second job
  const std::string stem = fs::path(post).stem().string();
  const fs::path picture = dir / (stem + "000.svg");
  ASSERT_TRUE(fs::exists(picture));
  EXPECT_FALSE(fs::exists(dir / (stem + "001.svg")));  // /NOERASE: one picture
  const std::string svg = read_file(picture);
  // 20 passes of *DO,MARC,1,20: substeps 1, 6, ..., 96, each a pendulum line and its mass.
  const auto lines = legends(svg);
  ASSERT_EQ(lines.size(), 20u);
  std::size_t polylines = 0, circles = 0;
  for (std::size_t p = svg.find("<polyline"); p != std::string::npos;
       p = svg.find("<polyline", p + 1))
    ++polylines;
  for (std::size_t p = svg.find("<circle"); p != std::string::npos; p = svg.find("<circle", p + 1))
    ++circles;
  EXPECT_EQ(polylines, 20u);
  EXPECT_EQ(circles, 20u);
  const auto ux = run.reader->nodal_series(2, "UX");
  const auto uy = run.reader->nodal_series(2, "UY");
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const int iter = 1 + 5 * static_cast<int>(k);
    EXPECT_EQ(lines[k].iter, iter);
    // The stored series starts at t = 0: substep n is entry n.
    const double t = ux[static_cast<std::size_t>(iter)].first;
    const double d = std::hypot(ux[static_cast<std::size_t>(iter)].second,
                                uy[static_cast<std::size_t>(iter)].second);
    EXPECT_NEAR(lines[k].time, t, 1e-3 * t);
    EXPECT_NEAR(lines[k].dmax, d, 1e-3 * d + 1e-6);
  }
  // The thesis figures' labels, case 1: DMAX = .0373 at ITER=1 and 1.31 at ITER=6 (REFERENCE §1:
  // exact 0.0369 and 1.310).
  if (tag == "post_pendulum1") {
    EXPECT_NEAR(lines[0].dmax, 0.0369, 0.01 * 0.0369);
    EXPECT_NEAR(lines[1].dmax, 1.310, 0.01 * 1.310);
  }
}

TEST(ThesisPostDecks, Pendulum1DrawsFigure512) {
  check_motion_picture("pendulum1.inp", "pendulum1_post.inp", "post_pendulum1");
}

TEST(ThesisPostDecks, Pendulum2DrawsFigure513) {
  check_motion_picture("pendulum2.inp", "pendulum2_post.inp", "post_pendulum2");
}

TEST(ThesisPostDecks, ResultsOptionAndMissingResults) {
  const fs::path solved = fresh_directory("post_results_option_a");
  run_deck_in(deck("pendulum1.inp"), solved);
  // Another directory: the post deck finds nothing there ...
  const fs::path other = fresh_directory("post_results_option_b");
  try {
    run_post_deck(deck("pendulum1_post.inp"), other);
    FAIL() << "a post deck without results must stop";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("pendulum1_post.inp:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("SET: no results to read"), std::string::npos) << msg;
    EXPECT_NE(msg.find("pendulum1.h5"), std::string::npos) << msg;
  }
  // ... and with --results it reads the named file.
  run_post_deck(deck("pendulum1_post.inp"), other, (solved / "pendulum1.h5").string());
  EXPECT_EQ(legends(read_file(other / "pendulum1_post000.svg")).size(), 20u);
}

// examples/crashN_post26.inp, the POST26 companions of the thesis car crash (Figs. 5-2-5 to
// 5-2-10), run against the results of crashN.inp: their target / computed / ratio tables against
// the exact lumped elastic-bar values of REFERENCE §2 (max |UX| of nodes 7 and 1 within 0.5 %,
// max gap force within 2 %, peak stress of element 6 within 3 %) and their three PLVAR graphs.
// Element 1 (far end) is carried by the bar's axial modes, which Houbolt damps at the thesis Δt:
// 2.1 / 5.6 / 12 % low for cases 1 / 2 / 3 (the documented deviation of test_car_crash.cpp),
// so 3 % for case 1 and 15 % for cases 2 and 3.
void check_crash_post26(int crash_case) {
  const std::string name = "crash" + std::to_string(crash_case);
  const fs::path dir = fresh_directory("post_" + name + "_post26");
  run_deck_in(deck(name + ".inp"), dir);
  run_post_deck(std::string(IMPACTFE_TEST_DECKS) + "/../../examples/" + name + "_post26.inp", dir);
  std::ifstream table(dir / (name + "_post26.txt"));
  ASSERT_TRUE(table.good());
  const double tolerance[5] = {0.005, 0.005, 0.02, 0.03, crash_case == 1 ? 0.03 : 0.15};
  double target = 0.0, computed = 0.0, ratio = 0.0;
  int row = 0;
  while (table >> target >> computed >> ratio) {
    ASSERT_LT(row, 5);
    EXPECT_NEAR(ratio, computed / target, 1e-6) << name << " row " << row;
    EXPECT_NEAR(ratio, 1.0, tolerance[row]) << name << " row " << row;
    ++row;
  }
  EXPECT_EQ(row, 5);
  for (const char* suffix : {"_post26000.svg", "_post26001.svg", "_post26002.svg"})
    EXPECT_NE(read_file(dir / (name + suffix)).find("<polyline"), std::string::npos) << suffix;
}

TEST(ThesisPostDecks, Crash1Post26CurvesMatchTheReference) {
  check_crash_post26(1);
}
TEST(ThesisPostDecks, Crash2Post26CurvesMatchTheReference) {
  check_crash_post26(2);
}
TEST(ThesisPostDecks, Crash3Post26CurvesMatchTheReference) {
  check_crash_post26(3);
}

// examples/helmet_post26.inp, the POST26 companion of the thesis helmet (superelement case,
// Figs. 5-3-2 to 5-3-7), run against helmet_segen.inp + helmet_use.inp: crown UZ at its
// first-impact minimum within 0.1 % of the 1.0 travel of REFERENCE §3, the free-fall velocity
// just before the ground gap closes (Houbolt integrates constant acceleration exactly), and its
// six PLVAR graphs.
TEST(ThesisPostDecks, HelmetPost26CurvesMatchTheReference) {
  const fs::path dir = fresh_directory("post_helmet_post26");
  run_deck_in(deck("helmet_segen.inp"), dir);
  run_deck_in(deck("helmet_use.inp"), dir);
  run_post_deck(std::string(IMPACTFE_TEST_DECKS) + "/../../examples/helmet_post26.inp", dir);
  std::ifstream table(dir / "helmet_post26.txt");
  ASSERT_TRUE(table.good());
  const double tolerance[2] = {1e-3, 1e-6};
  double target = 0.0, computed = 0.0, ratio = 0.0;
  int row = 0;
  while (table >> target >> computed >> ratio) {
    ASSERT_LT(row, 2);
    EXPECT_NEAR(ratio, computed / target, 1e-6) << "row " << row;
    EXPECT_NEAR(ratio, 1.0, tolerance[row]) << "row " << row;
    ++row;
  }
  EXPECT_EQ(row, 2);
  for (int k = 0; k < 6; ++k)
    EXPECT_NE(read_file(dir / fmt::format("helmet_post26{:03d}.svg", k)).find("<polyline"),
              std::string::npos)
        << k;
}

}  // namespace
}  // namespace impactfe::test_post_decks
