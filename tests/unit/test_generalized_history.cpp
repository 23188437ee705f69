// The state history of the reduced / mode-superposition transients in bounded memory: points
// past a block go to a temporary file and read back bitwise, across block boundaries and in any
// order; the time axis is generated on demand with the times the stored list had.
#include <gtest/gtest.h>

#include <vector>

#include "analysis/generalized_history.h"
#include "core/memory_budget.h"
#include "time/time_axis.h"

namespace impactfe::test_generalized_history {
namespace {

VectorXd pattern(int n, double base) {
  VectorXd x(n);
  for (int i = 0; i < n; ++i) x(i) = base + 0.001 * i + 1.0 / (3.0 + i);
  return x;
}

TEST(GeneralizedHistory, PointsBeyondTheBlockReadBackFromTheFileBitwise) {
  const int nq = 5, ng = 2, n_points = 1000;
  // A block of 10 records: 990 points go to the file, 10 stay in memory.
  GeneralizedHistory h(nq, ng, 10 * 8 * (3 * nq + ng));
  for (int k = 0; k < n_points; ++k)
    h.append(pattern(nq, k), pattern(nq, -k), pattern(nq, 2.0 * k), pattern(ng, 0.5 * k));
  ASSERT_EQ(h.size(), static_cast<std::size_t>(n_points));
  EXPECT_EQ(h.points_on_file(), 990u);
  for (int k : {999, 0, 989, 990, 500, 1, 998, 10, 9}) {
    const auto r = h.at(static_cast<std::size_t>(k));
    EXPECT_EQ(r.q, pattern(nq, k)) << k;
    EXPECT_EQ(r.v, pattern(nq, -k)) << k;
    EXPECT_EQ(r.a, pattern(nq, 2.0 * k)) << k;
    EXPECT_EQ(r.gap_forces, pattern(ng, 0.5 * k)) << k;
  }
  // Appending after reads still appends at the end of the file.
  h.append(pattern(nq, 7), pattern(nq, 7), pattern(nq, 7), pattern(ng, 7));
  for (int k = 0; k < 20; ++k)
    h.append(pattern(nq, k), pattern(nq, k), pattern(nq, k), pattern(ng, k));
  EXPECT_EQ(h.at(1000).q, pattern(nq, 7));
  EXPECT_EQ(h.at(1020).gap_forces, pattern(ng, 19));
  EXPECT_EQ(h.at(3).a, pattern(nq, 6.0));
}

TEST(GeneralizedHistory, HistoryWithoutGapsAndAWrongSizeIsAnInternalError) {
  GeneralizedHistory h(3, 0, 1);  // one point per block
  h.append(pattern(3, 1), pattern(3, 2), pattern(3, 3), VectorXd());
  h.append(pattern(3, 4), pattern(3, 5), pattern(3, 6), VectorXd());
  EXPECT_EQ(h.at(0).a, pattern(3, 3));
  EXPECT_EQ(h.at(1).q, pattern(3, 4));
  EXPECT_EQ(h.at(1).gap_forces.size(), 0);
  EXPECT_ANY_THROW(h.append(pattern(2, 1), pattern(3, 2), pattern(3, 3), VectorXd()));
}

TEST(GeneralizedHistory, AHistoryLargerThanTheTemporaryDiskIsRefusedWithWhatFits) {
  try {
    GeneralizedHistory::require_disk_space(1e18, 10, 2);
    FAIL() << "10^18 points were accepted";
  } catch (const MemoryLimitError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("temporary file"), std::string::npos) << what;
    EXPECT_NE(what.find("points fit"), std::string::npos) << what;
  }
  EXPECT_NO_THROW(GeneralizedHistory::require_disk_space(1000, 10, 2));
}

TEST(ReducedTimeAxis, GeneratedPointsEqualTheStoredListsTimes) {
  // Load step 1 at t = 0, a span of 7 steps of 0.1 ending exactly at 0.7, then 0.7 -> 1.0 in
  // 0.1 steps (exact), then 1.0 -> 1.25 (not a multiple: 2 or 3 steps end at 1.2 or 1.3).
  std::vector<LoadStep> steps(4);
  for (int i = 0; i < 4; ++i) steps[i].number = i + 1;
  steps[0].dt = 0.1;
  steps[1].time_end = 0.7;
  steps[2].time_end = 1.0;
  steps[3].time_end = 1.25;
  double dt = 0.0;
  std::vector<std::string> notes;
  const ReducedTimeAxis axis = reduced_time_axis(steps, dt, notes);
  ASSERT_EQ(dt, 0.1);
  const std::size_t n = axis.size();
  ASSERT_GE(n, 13u);
  EXPECT_EQ(axis[0].time, 0.0);
  EXPECT_EQ(axis[7].time, 0.7);  // the exact end of the span, not 0 + 7 * 0.1
  EXPECT_EQ(axis[7].substep, 7);
  EXPECT_EQ(axis[8].time, 0.7 + 1 * 0.1);
  EXPECT_EQ(axis[8].load_step, 3);
  EXPECT_EQ(axis[8].step_index, 2);
  EXPECT_EQ(axis[10].time, 1.0);
  EXPECT_DOUBLE_EQ(axis[9].fraction, 2.0 / 3.0);
  EXPECT_EQ(axis.back().load_step, 4);
  EXPECT_FALSE(notes.empty());  // 0.25 is not a multiple of 0.1
  std::size_t count = 0;
  double last = -1.0;
  for (const ReducedPoint& p : axis) {
    EXPECT_GT(p.time, last);
    last = p.time;
    ++count;
  }
  EXPECT_EQ(count, n);
  // Expansion points by bisection over the generated axis: the nearest times.
  const auto chosen =
      expansion_points({{2, 0.0, 1.0, false}}, n, [&](std::size_t i) { return axis[i].time; });
  ASSERT_EQ(chosen.size(), 2u);
  EXPECT_EQ(chosen[0], 5);   // t = 0.5
  EXPECT_EQ(chosen[1], 10);  // t = 1.0
}

}  // namespace
}  // namespace impactfe::test_generalized_history
