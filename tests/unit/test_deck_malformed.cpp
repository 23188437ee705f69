// Every deck in tests/decks/malformed must be rejected with a user error (InputError, ModelError,
// SolutionError: a LocatedError) naming the file, line and command stated in its first line
// ("! EXPECT-ERROR: <line> <COMMAND>: <fragment>"). The deck runs as `impactfe run` runs it
// (a job session solves each request), since some errors (a mechanism, a non-converged step)
// are found by the solution. tests/run_malformed.py checks the same through the CLI, with the
// exit status.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "../support/run_deck.h"
#include "deck/deck_reader.h"

namespace test_deck_malformed {

using namespace impactfe;

namespace {

struct Expectation {
  int line = 0;
  std::string command;
  std::string fragment;
};

Expectation read_expectation(const std::filesystem::path& deck) {
  std::ifstream in(deck);
  std::string first;
  std::getline(in, first);
  std::smatch m;
  static const std::regex re(R"(^!\s*EXPECT-ERROR:\s*(\d+)\s+(\S+):\s*(.+?)\s*$)");
  if (!std::regex_match(first, m, re)) return {};
  return {std::stoi(m[1]), m[2], m[3]};
}

std::vector<std::filesystem::path> malformed_decks() {
  std::vector<std::filesystem::path> out;
  for (const auto& e :
       std::filesystem::directory_iterator(std::string(IMPACTFE_TEST_DECKS) + "/malformed"))
    if (e.path().extension() == ".inp") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST(DeckMalformed, AtLeastFifteenDecks) {
  EXPECT_GE(malformed_decks().size(), 15u);
}

TEST(DeckMalformed, EachDeckFailsWhereItsHeaderSays) {
  for (const auto& deck : malformed_decks()) {
    SCOPED_TRACE(deck.string());
    const Expectation ex = read_expectation(deck);
    ASSERT_GT(ex.line, 0) << "missing or bad EXPECT-ERROR header";
    try {
      // As `impactfe run DECK` (no jobname option: /FILNAME takes effect).
      const auto dir = impactfe::testing::fresh_directory("malformed_" + deck.stem().string());
      const auto previous = std::filesystem::current_path();
      std::filesystem::current_path(dir);
      struct Back {
        std::filesystem::path to;
        ~Back() { std::filesystem::current_path(to); }
      } back{previous};
      RunStatistics stats;
      JobSession session(deck.stem().string(), RunSettings{}, stats);
      DeckOptions options;
      options.host = &session;
      read_deck(deck.string(), options);
      ADD_FAILURE() << "no error raised";
    } catch (const LocatedError& e) {
      const std::string what = e.what();
      const std::string location =
          deck.string() + ":" + std::to_string(ex.line) + ": " + ex.command + ":";
      EXPECT_EQ(e.where().line, ex.line) << what;
      EXPECT_EQ(e.where().command, ex.command) << what;
      EXPECT_NE(what.find(location), std::string::npos) << what;
      EXPECT_NE(what.find(ex.fragment), std::string::npos) << what;
    }
  }
}

}  // namespace test_deck_malformed
