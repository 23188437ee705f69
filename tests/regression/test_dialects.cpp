// Both dialects lower onto one model and the same solvers: the modern translation of pendulum
// case 1 (spec APDL_SUBSET.md Appendix B: ANTYPE,TRANS + TRNOPT,FULL,,,,,HOUB + NLGEOM + NSUBST +
// OUTRES, with a /POST26 block) gives the same history as the thesis's ANSYS 4.2 deck.
#include <gtest/gtest.h>

#include <cmath>

#include "../support/run_deck.h"

namespace impactfe {
namespace {

TEST(Dialects, ModernPendulumMatchesThe42Deck) {
  const std::string decks = IMPACTFE_TEST_DECKS;
  const auto classic = testing::run_deck(decks + "/thesis/pendulum1.inp", "dialect_4x");
  const auto modern = testing::run_deck(decks + "/modern/pendulum1_modern.inp", "dialect_modern");
  for (const char* lab : {"UX", "UY", "VX", "AY"}) {
    const auto a = classic.reader->nodal_series(2, lab);
    const auto b = modern.reader->nodal_series(2, lab);
    ASSERT_EQ(a.size(), b.size()) << lab;
    ASSERT_EQ(a.size(), 102u);
    for (std::size_t k = 0; k < a.size(); ++k) {
      EXPECT_DOUBLE_EQ(a[k].first, b[k].first);
      EXPECT_NEAR(a[k].second, b[k].second, 1e-9 * (1.0 + std::abs(a[k].second))) << lab;
    }
  }
}

}  // namespace
}  // namespace impactfe
