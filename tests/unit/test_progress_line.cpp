// The progress line of `impactfe run` (src/analysis/progress_line.h): one line within the width
// of an 80- and a 100-column terminal, the time reached and the time left kept to the last, the
// fields of least use dropped first; the time left from the smoothed pace of the run.
#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "analysis/progress_line.h"

namespace impactfe::test_progress_line {
namespace {

ProgressEvent helmet_event() {
  ProgressEvent e;
  e.analysis = "full transient (Houbolt)";
  e.time = 0.00123456;
  e.time_end = 0.005;
  e.load_step = 2;
  e.substep = 4936;
  e.substeps = 20000;
  e.dt = 2.5e-7;
  e.iterations = 3;
  e.status_changes = 12;
  e.substeps_left = 15064;
  e.run_time_end = 0.01;
  return e;
}

TEST(ProgressLine, FitsEightyColumns) {
  const std::string line = progress_line(helmet_event(), 83.4, 245.0, 80);
  EXPECT_LE(line.size(), 80u) << line;
  EXPECT_EQ(line.find('\n'), std::string::npos);
  EXPECT_NE(line.find("t 0.00123456/0.005"), std::string::npos) << line;
  EXPECT_NE(line.find("~4:05 min left"), std::string::npos) << line;
  EXPECT_NE(line.find("4936/20000"), std::string::npos) << line;
  // Dropped first: the status changes and the iterations.
  EXPECT_EQ(line.find("status changes"), std::string::npos) << line;
  EXPECT_EQ(line.find("iter"), std::string::npos) << line;
}

TEST(ProgressLine, HundredColumnsShowMore) {
  const std::string at80 = progress_line(helmet_event(), 83.4, 245.0, 80);
  const std::string at100 = progress_line(helmet_event(), 83.4, 245.0, 100);
  EXPECT_LE(at100.size(), 100u) << at100;
  EXPECT_GT(at100.size(), at80.size());
  EXPECT_NE(at100.find("1:23 min elapsed"), std::string::npos) << at100;
  EXPECT_NE(at100.find("left to t 0.01"), std::string::npos) << at100;
}

TEST(ProgressLine, WideTerminalShowsEveryField) {
  const std::string line = progress_line(helmet_event(), 83.4, 245.0, 400);
  EXPECT_EQ(line,
            "full transient (Houbolt) | t 0.00123456/0.005 | load step 2 substep 4936/20000 | "
            "dt 2.5e-07 | 3 iter | 12 status changes | 1:23 min elapsed | ~4:05 min left to t "
            "0.01");
}

TEST(ProgressLine, NarrowTerminalKeepsTheTimeReached) {
  const std::string line = progress_line(helmet_event(), 83.4, 245.0, 30);
  EXPECT_LE(line.size(), 30u);
  EXPECT_EQ(line.rfind("t 0.00123456/0.005", 0), 0u) << line;
}

TEST(ProgressLine, NoEstimateYetAndNoStatusCount) {
  ProgressEvent e = helmet_event();
  e.status_changes = -1;  // the driver does not count them (reduced transient)
  const std::string line = progress_line(e, 1.0, std::nullopt, 400);
  EXPECT_EQ(line.find("left"), std::string::npos) << line;
  EXPECT_EQ(line.find("status"), std::string::npos) << line;
}

/// An explicit (central difference) run: cycles, the time step and the energy error instead of
/// substeps, iterations and status changes.
ProgressEvent explicit_event() {
  ProgressEvent e;
  e.analysis = "explicit dynamics";
  e.time = 1.25e-4;
  e.time_end = 5e-4;
  e.load_step = 1;
  e.dt = 1.234e-7;
  e.status_changes = -1;
  e.substeps_left = 0;
  e.run_time_end = 1e-3;
  e.cycles = 1013;
  e.energy_error = 0.0042;
  return e;
}

TEST(ProgressLine, ExplicitRunShowsCyclesTimeStepAndEnergyError) {
  EXPECT_EQ(progress_line(explicit_event(), 12.3, 86.0, 400),
            "explicit dynamics | t 0.000125/0.0005 | load step 1 cycle 1013 | dt 1.23e-07 | "
            "energy error 0.42 % | 12.3 s elapsed | ~1:26 min left to t 0.001");
  const std::string at80 = progress_line(explicit_event(), 12.3, 86.0, 80);
  EXPECT_LE(at80.size(), 80u) << at80;
  EXPECT_NE(at80.find("cycle 1013"), std::string::npos) << at80;
  EXPECT_NE(at80.find("err 0.42 %"), std::string::npos) << at80;
  EXPECT_EQ(at80.find("iter"), std::string::npos) << at80;
  ProgressEvent before_a_check = explicit_event();
  before_a_check.energy_error = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(progress_line(before_a_check, 12.3, 86.0, 400).find("err"), std::string::npos);
}

TEST(TimeLeftEstimate, ConstantPaceIsExact) {
  TimeLeftEstimate estimate;
  EXPECT_FALSE(estimate.seconds_for(1.0));
  estimate.add(0.1, 1e-4);  // before a window of 0.25 s closes: the mean of what was seen
  EXPECT_NEAR(*estimate.pace(), 1000.0, 1e-9);
  estimate.reset();
  for (int i = 0; i < 100; ++i) estimate.add(0.0625, 1e-4);  // 625 s per unit of time
  EXPECT_NEAR(*estimate.seconds_for(0.01), 6.25, 1e-9);
}

TEST(TimeLeftEstimate, AChangeOfPaceIsFollowedSmoothly) {
  TimeLeftEstimate estimate;
  for (int i = 0; i < 100; ++i) estimate.add(0.0625, 1e-4);  // 25 windows of 4 substeps
  estimate.add(0.25, 1e-4);                                  // one slow window: 2500 s per unit
  // r = α·2500 + (1 − α)·625: moved by α of the jump, not to it.
  EXPECT_NEAR(*estimate.pace(),
              TimeLeftEstimate::kAlpha * 2500.0 + (1.0 - TimeLeftEstimate::kAlpha) * 625.0, 1e-6);
  for (int i = 0; i < 200; ++i) estimate.add(0.25, 1e-4);  // the new pace lasts: reached
  EXPECT_NEAR(*estimate.pace(), 2500.0, 1e-3);
}

}  // namespace
}  // namespace impactfe::test_progress_line
