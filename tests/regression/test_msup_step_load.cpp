// Load timing of the mode-superposition transient: a one-DOF oscillator (COMBIN40, k = 200,
// m = 0.5, omega = 20 rad/s) under a force F = 200 from t = 0. A stepped load (KBC,1) acts from
// the start of its load step, u = F/k (1 - cos wt) (as MAPDL, vm75); a ramped load (KBC,0)
// grows linearly over the load step, u = F/k (t/T - sin(wt)/(wT)). With dt = 2.5e-3 the
// Newmark period error keeps both within 0.1 % of F/k; a stepped load that acted half a step
// late would be off by F/k w dt/2 = 2.5 %.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "../support/run_deck.h"

namespace impactfe::test_msup_step_load {
namespace {

std::string oscillator_deck(int kbc) {
  return "/PREP7\n"
         "ET,1,COMBIN40,,,2,,,2\n"
         "R,1,200,,.5\n"
         "N,1\n"
         "N,2,1\n"
         "E,1,2\n"
         "D,1,UY\n"
         "FINISH\n"
         "/SOLU\n"
         "ANTYPE,MODAL\n"
         "MODOPT,LANB,1\n"
         "MXPAND,1\n"
         "SOLVE\n"
         "FINISH\n"
         "/SOLU\n"
         "ANTYPE,TRANSIENT\n"
         "TRNOPT,MSUP,1\n"
         "DELTIM,2.5E-3\n"
         "KBC," +
         std::to_string(kbc) +
         "\n"
         "OUTRES,NSOL,1\n"
         "F,2,FY,0\n"
         "SOLVE\n"
         "TIME,0.2\n"
         "F,2,FY,200\n"
         "SOLVE\n"
         "FINISH\n";
}

TEST(MsupStepLoad, SteppedLoadActsFromTheStartOfItsLoadStep) {
  const auto run = testing::run_deck_text("msup_stepped", oscillator_deck(1));
  const auto series = run.reader->nodal_series(2, "UY");
  ASSERT_GT(series.size(), 70u);
  double worst = 0.0;
  for (const auto& [t, u] : series)
    worst = std::max(worst, std::abs(u - (1.0 - std::cos(20.0 * t))));
  EXPECT_LT(worst, 1e-3);
}

TEST(MsupStepLoad, RampedLoadGrowsOverItsLoadStep) {
  const auto run = testing::run_deck_text("msup_ramped", oscillator_deck(0));
  const auto series = run.reader->nodal_series(2, "UY");
  ASSERT_GT(series.size(), 70u);
  const double big_t = 0.2;
  double worst = 0.0;
  for (const auto& [t, u] : series)
    worst = std::max(worst, std::abs(u - (t / big_t - std::sin(20.0 * t) / (20.0 * big_t))));
  EXPECT_LT(worst, 1e-3);
}

}  // namespace
}  // namespace impactfe::test_msup_step_load
