// Automatic time stepping bookkeeping (src/time/step_control.h; docs/solution_control.md): the
// limits from NSUBST / DELTIM with their defaults, bisection down to the minimum, growth after
// easy substeps up to the maximum, the ceiling, and landing exactly on the requested output
// times and the load-step end. The integrator history of restart files (IntegratorHistory).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/model.h"
#include "time/integrator_history.h"
#include "time/step_control.h"
#include "time/time_integrator.h"
#include "time/time_schedule.h"

namespace impactfe::test_step_control {
namespace {

LoadStepTiming timing(double t0, double t1, int n) {
  return LoadStepTiming{t0, t1, n, (t1 - t0) / n};
}

TEST(StepControl, DefaultLimitsFollowTheSpec) {
  LoadStep step;
  step.n_substeps = 10;
  const StepControl none;
  // Transient: the largest step is the first one; the smallest a thousandth of it.
  AutoStepPlan p = auto_step_plan(step, none, timing(0.0, 1.0, 10), true, false);
  EXPECT_FALSE(p.automatic);
  EXPECT_DOUBLE_EQ(p.dt0, 0.1);
  EXPECT_DOUBLE_EQ(p.dt_max, 0.1);
  EXPECT_DOUBLE_EQ(p.dt_min, 1e-4);
  // Static: the largest step is the span.
  p = auto_step_plan(step, none, timing(0.0, 1.0, 10), false, true);
  EXPECT_TRUE(p.automatic);
  EXPECT_DOUBLE_EQ(p.dt_max, 1.0);
  // NSUBST,10,40,2: smallest span/40, largest span/2.
  StepControl c;
  c.automatic = true;
  c.n_max = 40;
  c.n_min = 2;
  p = auto_step_plan(step, c, timing(0.0, 1.0, 10), true, false);
  EXPECT_DOUBLE_EQ(p.dt_min, 1.0 / 40);
  EXPECT_DOUBLE_EQ(p.dt_max, 0.5);
  // DELTIM,0.1,0.01,0.3 in time units.
  LoadStep deltim;
  deltim.dt = 0.1;
  StepControl d;
  d.dt_min = 0.01;
  d.dt_max = 0.3;
  p = auto_step_plan(deltim, d, timing(0.0, 1.0, 10), true, false);
  EXPECT_DOUBLE_EQ(p.dt_min, 0.01);
  EXPECT_DOUBLE_EQ(p.dt_max, 0.3);
  d.dt_min = 0.2;  // above the step
  d.automatic = true;
  EXPECT_THROW(auto_step_plan(deltim, d, timing(0.0, 1.0, 10), true, false), InputError);
  d.automatic = false;  // constant steps: MAPDL does not use the limits
  EXPECT_NO_THROW(auto_step_plan(deltim, d, timing(0.0, 1.0, 10), true, false));
}

// AUTOTS not given: constant steps, unless the deck gives a largest step above the first (a
// limit only AUTOTS uses, so it asks for it), which is said in a note.
TEST(StepControl, ALargestStepAboveTheFirstImpliesAutots) {
  LoadStep deltim;
  deltim.dt = 0.1;
  StepControl d;
  d.dt_max = 0.5;
  AutoStepPlan p = auto_step_plan(deltim, d, timing(0.0, 1.0, 10), false, false);
  EXPECT_TRUE(p.automatic);
  EXPECT_NE(p.implied.find("DTMAX 0.5 exceeds DTIME 0.1"), std::string::npos) << p.implied;
  EXPECT_DOUBLE_EQ(p.dt_max, 0.5);
  d.dt_max = 0.1;  // no growth asked for
  EXPECT_FALSE(auto_step_plan(deltim, d, timing(0.0, 1.0, 10), false, false).automatic);
  d.dt_max = 0.5;
  d.automatic = false;  // AUTOTS,OFF said: constant steps
  p = auto_step_plan(deltim, d, timing(0.0, 1.0, 10), false, false);
  EXPECT_FALSE(p.automatic);
  EXPECT_TRUE(p.implied.empty());
  LoadStep nsubst;
  nsubst.n_substeps = 10;
  StepControl n;
  n.n_min = 2;  // NSUBST,10,,2
  p = auto_step_plan(nsubst, n, timing(0.0, 1.0, 10), true, false);
  EXPECT_TRUE(p.automatic);
  EXPECT_NE(p.implied.find("NSBMN 2 is below NSBSTP 10"), std::string::npos) << p.implied;
  n.n_min = 10;
  EXPECT_FALSE(auto_step_plan(nsubst, n, timing(0.0, 1.0, 10), true, false).automatic);
}

AutoStepPlan plan(double dt0, double dt_min, double dt_max, double t_end = 1.0) {
  AutoStepPlan p;
  p.automatic = true;
  p.t_start = 0.0;
  p.t_end = t_end;
  p.dt0 = p.dt_first = dt0;
  p.dt_min = dt_min;
  p.dt_max = dt_max;
  p.n_nominal = static_cast<int>(std::lround(t_end / dt0));
  return p;
}

TEST(StepControl, BisectsDownToTheMinimumThenFails) {
  StepController c(plan(0.1, 0.02, 0.1), {});
  EXPECT_DOUBLE_EQ(c.next_step(), 0.1);
  EXPECT_TRUE(c.cut());
  EXPECT_DOUBLE_EQ(c.next_step(), 0.05);
  EXPECT_TRUE(c.cut());
  EXPECT_DOUBLE_EQ(c.next_step(), 0.025);
  EXPECT_TRUE(c.cut());  // 0.0125 is below the minimum: the last try is at the minimum
  EXPECT_DOUBLE_EQ(c.next_step(), 0.02);
  EXPECT_FALSE(c.cut());
}

TEST(StepControl, GrowsAfterTwoEasySubstepsUpToTheMaximum) {
  StepController c(plan(0.01, 1e-5, 0.03, 10.0), {});
  std::vector<double> desired;
  for (int i = 0; i < 8; ++i) {
    desired.push_back(c.desired());
    // The step taken is the desired one evened out towards the end time 10 (never longer).
    EXPECT_LE(c.next_step(), c.desired() * (1 + 1e-12));
    EXPECT_GE(c.next_step(), c.desired() * 0.99);
    c.accept(true);
  }
  const std::vector<double> expected{0.01, 0.01, 0.015, 0.015, 0.0225, 0.0225, 0.03, 0.03};
  for (std::size_t i = 0; i < desired.size(); ++i) EXPECT_NEAR(desired[i], expected[i], 1e-15) << i;
  // A hard substep restarts the count.
  c.accept(false);
  c.accept(true);
  EXPECT_NEAR(c.desired(), 0.03, 1e-15);
}

// A restart point inside an AUTOTS load step keeps state(); a new controller of the same plan
// restored from it proposes exactly the steps the original goes on with (cuts, growth streak,
// ceiling, landing on the output times).
TEST(StepControl, RestoredStateContinuesTheSameSteps) {
  const AutoStepPlan p = plan(0.01, 1e-4, 0.04, 1.0);
  StepController a(p, {25});
  a.accept(true);
  a.cut();
  a.accept(true);  // half of the easy streak
  a.set_ceiling(0.007);
  const StepController::State s = a.state();
  StepController b(p, {25});
  b.restore(s);
  for (int i = 0; i < 2000 && !a.done(); ++i) {
    ASSERT_EQ(a.next_step(), b.next_step()) << i;
    ASSERT_EQ(a.next_time(), b.next_time()) << i;
    ASSERT_EQ(a.next_grid_index(), b.next_grid_index()) << i;
    if (i == 3) {
      a.set_ceiling(std::nullopt);
      b.set_ceiling(std::nullopt);
    }
    if (i % 11 == 5) {
      ASSERT_EQ(a.cut(), b.cut());
      continue;
    }
    a.accept(i % 5 != 0);
    b.accept(i % 5 != 0);
    ASSERT_EQ(a.done(), b.done());
  }
  EXPECT_TRUE(a.done()) << a.time() << " " << a.desired() << " " << a.next_step();
}

TEST(StepControl, CeilingBoundsTheStepButNotBelowTheMinimum) {
  StepController c(plan(0.1, 0.01, 0.1), {});
  c.set_ceiling(0.03);
  EXPECT_DOUBLE_EQ(c.desired(), 0.03);
  c.set_ceiling(0.001);
  EXPECT_DOUBLE_EQ(c.desired(), 0.01);
  c.set_ceiling(std::nullopt);
  EXPECT_DOUBLE_EQ(c.next_step(), 0.01);  // grows again from the step taken under it
}

TEST(StepControl, LandsExactlyOnOutputTimesAndTheEnd) {
  // dt0 = 0.01 (100 nominal substeps), OUTRES every 10: times 0.1, 0.2, ... and 1.0.
  StepController c(plan(0.01, 1e-4, 0.04), {10});
  std::vector<double> landed;
  int guard = 0;
  while (!c.done() && ++guard < 1000) {
    const int grid = c.next_grid_index();
    const double t = c.next_time();
    if (grid > 0) landed.push_back(t);
    EXPECT_LE(c.next_step(), 0.04 + 1e-15);
    c.accept(true);
  }
  ASSERT_TRUE(c.done());
  ASSERT_EQ(landed.size(), 10u);
  for (std::size_t j = 0; j < landed.size(); ++j)
    EXPECT_NEAR(landed[j], 0.1 * static_cast<double>(j + 1), 1e-14) << j;
  EXPECT_EQ(c.time(), 1.0);  // exactly the load-step end
}

TEST(IntegratorHistory, RestoredIntegratorContinuesIdentically) {
  // Houbolt keeps two past displacements: a copy restored from the history must produce the
  // same next steps bit for bit.
  for (auto make : {+[] { return make_houbolt(); },
                    +[] { return make_generalized_alpha(GeneralizedAlphaParameters{}); }}) {
    auto a = make();
    Eigen::VectorXd u(2), v(2), acc(2);
    u << 0.1, -0.2;
    v << 1.0, 0.5;
    acc << -3.0, 2.0;
    a->start(u, v, acc, 0.01);
    for (int i = 1; i <= 3; ++i) a->advance(u + 0.01 * i * v);
    auto b = make();
    dynamic_cast<IntegratorHistory&>(*b).restore(dynamic_cast<IntegratorHistory&>(*a).history(),
                                                 a->step());
    for (int i = 4; i <= 6; ++i) {
      const Eigen::VectorXd next = u + 0.01 * i * v + 0.001 * i * i * acc;
      a->advance(next);
      b->advance(next);
      EXPECT_EQ(a->v(), b->v());
      EXPECT_EQ(a->a(), b->a());
      EXPECT_EQ(a->predict(), b->predict());
    }
  }
}

}  // namespace
}  // namespace impactfe::test_step_control
