// Thesis example 1, the pendulum (decks pendulum1.inp / pendulum2.inp, unchanged), against
// REFERENCE.md §1: KAN=4, large deflection, Houbolt at the thesis step (101 substeps to 1.5 s).
#include <gtest/gtest.h>

#include <cmath>

#include "../support/run_deck.h"

namespace impactfe::test_pendulum {
namespace {

using testing::run_deck;
using testing::value_at;

std::string deck(const std::string& name) {
  return std::string(IMPACTFE_TEST_DECKS) + "/thesis/" + name;
}

/// Upward crossings of `level`, linearly interpolated between stored points (REFERENCE §1).
std::vector<double> upward_crossings(const std::vector<std::pair<double, double>>& s,
                                     double level) {
  std::vector<double> out;
  for (std::size_t k = 1; k < s.size(); ++k)
    if (s[k - 1].second < level && s[k].second >= level)
      out.push_back(s[k - 1].first + (level - s[k - 1].second) * (s[k].first - s[k - 1].first) /
                                         (s[k].second - s[k - 1].second));
  return out;
}

TEST(PendulumCase1, PeriodAndAmplitudesMatchTheEllipticSolution) {
  const auto run = run_deck(deck("pendulum1.inp"), "pendulum1");
  const auto ux = run.reader->nodal_series(2, "UX");
  const auto uy = run.reader->nodal_series(2, "UY");
  ASSERT_EQ(ux.size(), 102u);  // t = 0 and 101 substeps (ITER,101,5,1 writes every step)

  // Period: exact 4 sqrt(l/g) K(k = 0.5) = 1.0848 (thesis eq. 5-1-7: 1.085); tolerance 1.5 %.
  const auto crossings = upward_crossings(ux, 8.66);
  ASSERT_GE(crossings.size(), 2u);
  EXPECT_NEAR(crossings[1] - crossings[0], 1.0848, 0.015 * 1.0848);

  // Amplitudes (thesis eqs. 5-1-8, 5-1-9; Fig. 5-1-4): max UX 17.3205 on the first swing within
  // 1 %, min UY -5.000 (rigid) / -5.003 (arm stretch) within 1 %.
  double max_ux = -1e9, min_uy = 1e9;
  for (std::size_t k = 0; k < ux.size() && ux[k].first < 0.6; ++k)
    max_ux = std::max(max_ux, ux[k].second);
  for (const auto& p : uy) min_uy = std::min(min_uy, p.second);
  EXPECT_NEAR(max_ux, 17.3205, 0.01 * 17.3205);
  EXPECT_NEAR(min_uy, -5.0, 0.01 * 5.0);

  // Thesis Fig. 5-1-2 (POST1 plots): |u| after 1 substep 0.0373 (exact 0.0369) and after 6
  // substeps 1.31 (exact 1.310); within 2 % of the exact values.
  const double u1 = std::hypot(ux[1].second, uy[1].second);
  const double u6 = std::hypot(ux[6].second, uy[6].second);
  EXPECT_NEAR(ux[1].first, 0.0148515, 1e-6);
  EXPECT_NEAR(u1, 0.0369, 0.02 * 0.0369);
  EXPECT_NEAR(u6, 1.310, 0.02 * 1.310);
}

TEST(PendulumCase2, SpringPendulumMatchesTheOdeSolution) {
  const auto run = run_deck(deck("pendulum2.inp"), "pendulum2");
  const auto ux = run.reader->nodal_series(2, "UX");
  const auto uy = run.reader->nodal_series(2, "UY");
  double max_ux = -1e9, min_uy = 1e9;
  for (const auto& p : ux) max_ux = std::max(max_ux, p.second);
  for (const auto& p : uy) min_uy = std::min(min_uy, p.second);
  // REFERENCE §1 case 2 (high-accuracy ODE solution of eqs. 5-1-3/4): within 2 %.
  EXPECT_NEAR(max_ux, 17.8410, 0.02 * 17.8410);
  EXPECT_NEAR(min_uy, -14.0031, 0.02 * 14.0031);
  // Points of the swing, interpolated linearly: within 2 % of max UX (0.36 in).
  EXPECT_NEAR(value_at(ux, 0.4), 8.846, 0.36);
  EXPECT_NEAR(value_at(uy, 0.4), -13.973, 0.36);
  EXPECT_NEAR(value_at(ux, 0.8), 17.840, 0.36);
  EXPECT_NEAR(value_at(uy, 0.8), -0.072, 0.36);
}

}  // namespace
}  // namespace impactfe::test_pendulum
