// Verification decks of the MAPDL kind (tests/decks/post_verification): each solves a case with
// a closed-form answer, fetches its results inside the deck (*GET, *VGET, ETABLE, FSUM, POST26),
// holds the targets in *DIM arrays and writes a target / computed / ratio table with *VWRITE
// into <deck>.txt through *CFOPEN. The test reads the table back and checks every row: the
// ratio within the deck's `! RATIO-TOL:` and consistent with the two numbers beside it, and the
// row count the deck announces (`! ROWS:`), so a deck that stops early or skips a fetch fails.
// Static (4), modal, full transient (2), full transient with a gap, reduced transient with a GP
// gap, mode superposition and substructuring.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <regex>
#include <sstream>

#include "../support/run_deck.h"

namespace impactfe::test_post_verification {
namespace {

namespace fs = std::filesystem;

std::string deck_path(const std::string& name) {
  return std::string(IMPACTFE_TEST_DECKS) + "/post_verification/" + name + ".inp";
}

/// The text after `! KEY:` in the deck's comment lines ("" when absent).
std::string header_text(const std::string& deck, const std::string& key) {
  std::ifstream in(deck);
  std::string line;
  const std::regex re("^\\s*!\\s*" + key + ":\\s*(\\S+)");
  std::smatch m;
  while (std::getline(in, line))
    if (std::regex_search(line, m, re)) return m[1];
  return {};
}

double header_value(const std::string& deck, const std::string& key) {
  const std::string text = header_text(deck, key);
  if (text.empty()) ADD_FAILURE() << deck << ": no '! " << key << ":' line";
  return text.empty() ? 0.0 : std::stod(text);
}

class PostVerification : public ::testing::TestWithParam<std::string> {};

TEST_P(PostVerification, TableRatiosWithinTolerance) {
  const std::string name = GetParam();
  const std::string deck = deck_path(name);
  const double tol = header_value(deck, "RATIO-TOL");
  const int rows_expected = static_cast<int>(header_value(deck, "ROWS"));
  const fs::path dir = testing::fresh_directory("post_verification_" + name);
  // `! RUN-FIRST: dir/deck.inp`: a deck (relative to tests/decks) whose files this one reads,
  // such as the generation pass of a superelement.
  if (const std::string first = header_text(deck, "RUN-FIRST"); !first.empty())
    testing::run_deck_in(std::string(IMPACTFE_TEST_DECKS) + "/" + first, dir);
  testing::run_deck_in(deck, dir);
  std::ifstream table(dir / (name + ".txt"));
  ASSERT_TRUE(table.good()) << "the deck wrote no " << name << ".txt";
  std::string line;
  int rows = 0;
  while (std::getline(table, line)) {
    std::istringstream fields(line);
    double target = 0.0, computed = 0.0, ratio = 0.0;
    if (!(fields >> target >> computed >> ratio)) {
      ADD_FAILURE() << "not a target/computed/ratio row: '" << line << "'";
      continue;
    }
    ++rows;
    SCOPED_TRACE(line);
    ASSERT_NE(target, 0.0);
    // The ratio the deck computed (*VOPER) agrees with its own columns (8 printed digits) ...
    EXPECT_NEAR(ratio, computed / target, 1e-6 * std::fabs(ratio));
    // ... and the computed value matches the closed form.
    EXPECT_NEAR(ratio, 1.0, tol) << "row " << rows;
  }
  EXPECT_EQ(rows, rows_expected);
  // `! PICTURES: n`: the plot commands (PLDISP, PLNSOL, PLVAR) wrote n complete SVG files.
  const std::string pictures = header_text(deck, "PICTURES");
  int svg = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".svg") continue;
    ++svg;
    std::ifstream in(entry.path());
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text.rfind("<svg", 0), 0u) << entry.path();
    // Something drawn inside the plot area (graph curves are polylines, elements lines).
    const auto plot = text.find("clip-path=");
    ASSERT_NE(plot, std::string::npos) << entry.path();
    EXPECT_TRUE(text.find("<polyline", plot) != std::string::npos ||
                text.find("<line", plot) != std::string::npos)
        << entry.path();
    EXPECT_NE(text.find("</svg>"), std::string::npos) << entry.path();
  }
  EXPECT_EQ(svg, pictures.empty() ? 0 : std::stoi(pictures));
}

INSTANTIATE_TEST_SUITE_P(
    Decks, PostVerification,
    ::testing::Values("truss_static_get", "spring_chain_components", "bar_indeterminate_sort",
                      "tripod_etable_3d", "static_gap_select", "chain_modes_get",
                      "oscillator_post26", "damped_oscillator_post26", "gap_impact_post26",
                      "reduced_gap_post26", "msup_step_post26", "msup_lvscale_post26",
                      "substructure_use_get"),
    [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace impactfe::test_post_verification
