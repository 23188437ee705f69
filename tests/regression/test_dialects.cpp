// Both dialects lower onto one model and the same solvers: the modern translation of pendulum
// case 1 (spec APDL_SUBSET.md Appendix B: ANTYPE,TRANS + TRNOPT,FULL,,,,,HOUB + NLGEOM + NSUBST +
// OUTRES, with a /POST26 block) gives the same history as the thesis's ANSYS 4.2 deck.
#include <gtest/gtest.h>

#include <cmath>

#include "../support/run_deck.h"

namespace impactfe::test_dialects {
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
}  // namespace impactfe::test_dialects

namespace impactfe::test_dialects {
namespace {

TEST(Dialects, ModernReducedCrashMatchesThe42Deck) {
  // Car crash case 1: KAN,5 + /STRESS (4.2) against TRNOPT,REDUC + EXPASS (modern). Master
  // histories must agree at every step; element stresses wherever both passes expanded.
  const std::string decks = IMPACTFE_TEST_DECKS;
  const auto classic = testing::run_deck(decks + "/thesis/crash1.inp", "dialect_crash_4x");
  const auto modern =
      testing::run_deck(decks + "/modern/crash1_modern.inp", "dialect_crash_modern");
  const auto a = classic.reader->nodal_series(7, "UX");
  const auto b = modern.reader->nodal_series(7, "UX");
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_NEAR(a[k].first, b[k].first, 1e-12);
    EXPECT_NEAR(a[k].second, b[k].second, 1e-12);
  }
  const auto s_classic = classic.reader->element_series(6, "SAXL");
  const auto s_modern = modern.reader->element_series(6, "SAXL");
  ASSERT_EQ(s_classic.size(), 60u);
  ASSERT_EQ(s_modern.size(), 61u);  // NUMEXP,ALL also expands t = 0
  int matched = 0;
  for (const auto& [t, s] : s_classic)
    for (const auto& [u, r] : s_modern)
      if (std::abs(t - u) < 1e-12) {
        EXPECT_NEAR(s, r, 1e-9 * (1.0 + std::abs(s)));
        ++matched;
      }
  EXPECT_EQ(matched, 60);
}

}  // namespace
}  // namespace impactfe::test_dialects

namespace impactfe::test_dialects {
namespace {

TEST(Dialects, ModernSuperelementGenerationAndUse) {
  // ANTYPE,SUBSTR + SEOPT,bar writes bar.sub.h5; SE,bar reads it in the use pass.
  const std::string decks = IMPACTFE_TEST_DECKS;
  const auto dir = testing::fresh_directory("dialect_superelement");
  testing::run_deck_in(decks + "/modern/se_generate_bar.inp", dir);
  EXPECT_TRUE(std::filesystem::exists(dir / "bar.sub.h5"));
  const auto use = testing::run_deck_in(decks + "/modern/se_use_spring.inp", dir);
  const auto u = use.reader->nodal_series(11, "UX");
  ASSERT_EQ(u.size(), 1u);
  EXPECT_NEAR(u[0].second, 1000.0 / (3.0e6 + 1000.0), 1e-12);
}

}  // namespace
}  // namespace impactfe::test_dialects
