// The time schedule of a static / full transient run (src/time/time_schedule.h): the rules for
// the values DELTIM / NSUBST give, the plan of each load step (made once, errors of a later
// step raised when it begins), the note of a rounded DELTIM, constant and automatic substeps,
// the accept / cut / stop decision with the T/30 rule for impacts, the T/30 and T/10 numbers
// and the time-step advice, and continuing from a restart point.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "time/time_schedule.h"

namespace impactfe::test_time_schedule {
namespace {

LoadStep step_to(int number, double time_end) {
  LoadStep s;
  s.number = number;
  s.time_end = time_end;
  s.where = SourceLocation{"deck.inp", 10 * number, "SOLVE"};
  return s;
}

std::string error_of(const LoadStep& s, const SourceLocation& where) {
  try {
    check_step_size_settings(s, where);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(TimeSchedule, StepSizeSettingsAreCheckedAtTheCommand) {
  const SourceLocation deltim{"deck.inp", 7, "DELTIM"};
  LoadStep s;
  s.dt = 0.001;
  EXPECT_EQ(error_of(s, deltim), "");
  s.control.dt_min = 0.01;
  EXPECT_EQ(error_of(s, deltim),
            "deck.inp:7: DELTIM: DTMIN 0.01 is larger than the time step 0.001");
  s.control.dt_min = 0.0;
  EXPECT_NE(error_of(s, deltim).find("DTMIN 0 must be positive"), std::string::npos);
  s.control.dt_min.reset();
  s.control.dt_max = 0.0005;
  EXPECT_NE(error_of(s, deltim).find("DTMAX 0.0005 is smaller than the time step 0.001"),
            std::string::npos);
  s = LoadStep{};
  s.dt = -1e-3;
  EXPECT_NE(error_of(s, deltim).find("time step -0.001 must be positive"), std::string::npos);

  const SourceLocation nsubst{"deck.inp", 9, "NSUBST"};
  LoadStep n;
  n.n_substeps = 10;
  n.control.n_max = 5;
  EXPECT_EQ(error_of(n, nsubst),
            "deck.inp:9: NSUBST: NSBMX 5 (most substeps) is smaller than NSBSTP 10");
  n.control.n_max.reset();
  n.control.n_min = 11;
  EXPECT_NE(error_of(n, nsubst).find("NSBMN 11 (fewest substeps) must be in 1..NSBSTP (10)"),
            std::string::npos);
  n.control.n_min.reset();
  n.n_substeps = 0;
  EXPECT_NE(error_of(n, nsubst).find("number of substeps 0 must be positive"), std::string::npos);
}

TEST(TimeSchedule, ConstantSubstepsEndOnTheGrid) {
  std::vector<std::string> notes;
  TimeSchedule schedule(true, 25, notes);
  LoadStep s = step_to(1, 1.0);
  s.n_substeps = 4;
  schedule.begin_load_step(s, {});
  schedule.begin_substeps(std::nullopt);
  std::vector<double> times, fractions;
  while (!schedule.done()) {
    const Substep sub = schedule.next();
    EXPECT_EQ(sub.grid, sub.number);
    EXPECT_EQ(sub.n_grid, 4);
    EXPECT_EQ(sub.h, 0.25);
    times.push_back(sub.time);
    fractions.push_back(sub.fraction);
    EXPECT_EQ(schedule.decide(SubstepOutcome{"no convergence", "", 0, 0.25}),
              SubstepDecision::Accept);  // constant steps are never cut
    schedule.accept(3, 0);
    EXPECT_EQ(schedule.accepted_substep(), sub.number);
  }
  EXPECT_EQ(times, (std::vector<double>{0.25, 0.5, 0.75, 1.0}));
  EXPECT_EQ(fractions, (std::vector<double>{0.25, 0.5, 0.75, 1.0}));
  schedule.end_load_step();
  EXPECT_EQ(schedule.time_reached(), 1.0);
  EXPECT_EQ(schedule.carried_step(), 0.25);
  EXPECT_TRUE(notes.empty());
}

TEST(TimeSchedule, RoundedDeltimIsNoted) {
  std::vector<std::string> notes;
  TimeSchedule schedule(true, 25, notes);
  LoadStep s = step_to(1, 1.0);
  s.dt = 0.3;  // 1 / 0.3 = 3.33: 3 substeps of 0.333
  schedule.begin_load_step(s, {});
  EXPECT_EQ(schedule.timing().n_substeps, 3);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("DELTIM 0.3 does not divide the load step"), std::string::npos);
  EXPECT_NE(notes[0].find("3 substep(s) of 0.333333"), std::string::npos);
  schedule.end_load_step();

  LoadStep coarse = step_to(2, 2.0);
  coarse.dt = 0.7;  // 1 / 0.7 = 1.43: one substep of 1
  schedule.begin_load_step(coarse, {});
  EXPECT_EQ(schedule.timing().n_substeps, 1);
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_NE(notes[1].find("1 substep(s) of 1"), std::string::npos);
  schedule.end_load_step();

  LoadStep exact = step_to(3, 3.0);
  exact.dt = 0.001;  // divides: no note
  schedule.begin_load_step(exact, {});
  EXPECT_EQ(schedule.timing().n_substeps, 1000);
  EXPECT_EQ(notes.size(), 2u);
}

TEST(TimeSchedule, LaterLoadStepsArePlannedOnceAndTheirErrorsWait) {
  std::vector<std::string> notes;
  TimeSchedule schedule(true, 25, notes);
  LoadStep first = step_to(1, 1.0);
  first.n_substeps = 10;
  LoadStep second = step_to(2, 3.0);
  second.dt = 0.5;
  LoadStep third;  // no TIME in a transient: invalid
  third.number = 3;
  third.where = SourceLocation{"deck.inp", 30, "SOLVE"};
  schedule.look_ahead({first, second});
  EXPECT_EQ(schedule.substeps_ahead(), (std::vector<int>{10, 4}));
  schedule.look_ahead({first, second, third});
  EXPECT_EQ(schedule.substeps_ahead(), std::nullopt);
  // The first two load steps run; the third's error comes when it begins.
  schedule.look_ahead({second, third});
  schedule.begin_load_step(first, {});
  EXPECT_EQ(schedule.progress(1.0).run_end, 3.0);  // the valid steps ahead end at 3
  schedule.end_load_step();
  schedule.look_ahead({third});
  schedule.begin_load_step(second, {});
  EXPECT_EQ(schedule.timing().n_substeps, 4);
  schedule.end_load_step();
  try {
    schedule.begin_load_step(third, {});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "deck.inp:30: SOLVE: load step 3: TIME (end time) is required in a transient "
              "analysis");
  }
}

TEST(TimeSchedule, ASpanShorterThanDeltimIsOneStepWhateverDtmin) {
  // DELTIM,1.0,0.99,1.0 from t = 0.1 to 1 (the Verification Manual's creep decks): one step of
  // 0.9, below DTMIN, with constant steps and under AUTOTS alike.
  for (const bool automatic : {false, true}) {
    std::vector<std::string> notes;
    TimeSchedule schedule(false, 25, notes);
    LoadStep first = step_to(1, 0.1);
    first.dt = 0.1;
    schedule.begin_load_step(first, {});
    schedule.begin_substeps(std::nullopt);
    while (!schedule.done()) schedule.accept(1, 0);
    schedule.end_load_step();
    LoadStep s = step_to(2, 1.0);
    s.dt = 1.0;
    s.control.dt_min = 0.99;
    s.control.dt_max = 1.0;
    s.control.automatic = automatic;
    schedule.begin_load_step(s, {});
    schedule.begin_substeps(std::nullopt);
    EXPECT_NEAR(schedule.next().h, 0.9, 1e-12) << automatic;
    EXPECT_NEAR(schedule.next().time, 1.0, 1e-12) << automatic;
  }
  // A DTMIN above a step that divides the span is still refused under AUTOTS.
  std::vector<std::string> notes;
  TimeSchedule schedule(false, 25, notes);
  LoadStep s = step_to(1, 1.0);
  s.dt = 0.25;
  s.control.dt_min = 0.3;
  s.control.automatic = true;
  EXPECT_THROW(schedule.begin_load_step(s, {}), InputError);
}

TEST(TimeSchedule, ImpactInAStepLongerThanT30IsCutThenStops) {
  std::vector<std::string> notes;
  TimeSchedule schedule(true, 8, notes);
  LoadStep s = step_to(1, 1.0);
  s.dt = 0.1;
  s.control.automatic = true;
  s.control.dt_min = 0.02;
  schedule.begin_load_step(s, {});
  ASSERT_TRUE(schedule.automatic());
  // A contact period of 0.9: impacts are resolved in steps of at most 0.9 / 30 = 0.03.
  schedule.begin_substeps(0.9);
  EXPECT_DOUBLE_EQ(resolving_step(0.9), 0.03);
  EXPECT_DOUBLE_EQ(coarsest_step(0.9), 0.09);
  const SubstepOutcome impact{"", "", 1, 0.1};
  EXPECT_EQ(schedule.decide(impact), SubstepDecision::Cut);
  EXPECT_DOUBLE_EQ(schedule.next().h, 0.05);
  EXPECT_EQ(schedule.decide(SubstepOutcome{"", "", 1, 0.05}), SubstepDecision::Cut);
  EXPECT_DOUBLE_EQ(schedule.next().h, 0.025);
  // 0.025 < 0.03 resolves it: accepted.
  EXPECT_EQ(schedule.decide(SubstepOutcome{"", "", 1, 0.025}), SubstepDecision::Accept);
  schedule.accept(2, 1);
  // A failure at the minimum step stops the run, naming the minimum and the reason.
  EXPECT_EQ(schedule.decide(SubstepOutcome{"no convergence", "", 0, 0.025}), SubstepDecision::Cut);
  EXPECT_EQ(schedule.decide(SubstepOutcome{"no convergence", "", 0, 0.02}), SubstepDecision::Stop);
  const std::string message = schedule.stop_message(0.025);
  EXPECT_NE(message.find("cannot be cut below the minimum 0.02"), std::string::npos) << message;
  EXPECT_NE(message.find("no convergence"), std::string::npos) << message;
  // Penetration of a KEYOPT(7) contact cuts too.
  EXPECT_EQ(schedule.decide(SubstepOutcome{"", "contact element 5 penetrated", 0, 0.02}),
            SubstepDecision::Stop);
}

TEST(TimeSchedule, EasySubstepsGrowTheStepAndClosedContactsBoundIt) {
  std::vector<std::string> notes;
  TimeSchedule schedule(false, 8, notes);  // static: the largest step is the span
  LoadStep s = step_to(1, 1.0);
  s.n_substeps = 10;
  s.control.automatic = true;
  schedule.begin_load_step(s, {});
  schedule.begin_substeps(std::nullopt);
  schedule.accept(2, 0);  // easy: at most max(1, 8 / 4) iterations, no status change
  schedule.accept(2, 0);
  // Grown by 1.5 after two easy substeps: 0.15, evened out to land on t = 1 (6 steps of 0.133).
  EXPECT_DOUBLE_EQ(schedule.next().h, 0.8 / 6);
  schedule.set_contact_ceiling(0.6);  // T/30 = 0.02
  EXPECT_NEAR(schedule.next().h, 0.02, 1e-15);
  schedule.accept(3, 0);  // not easy
  EXPECT_EQ(schedule.accepted_substep(), 3);
  while (!schedule.done()) schedule.accept(1, 0);
  schedule.end_load_step();
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("automatic time stepping, load step 1:"), std::string::npos);
  EXPECT_NE(notes[0].find("1 substeps under the contact-frequency ceiling T/30"), std::string::npos)
      << notes[0];
}

TEST(TimeSchedule, AdviceSuggestsT30OnceAndWarnsAboveT10) {
  std::vector<std::string> notes;
  TimeSchedule schedule(true, 25, notes);
  schedule.advise(0.2, 1.5, 1 / 1.5, 7);  // T/10 = 0.15: too coarse
  schedule.advise(0.01, 1.5, 1 / 1.5, 7);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("element 7 closed"), std::string::npos);
  EXPECT_NE(notes[0].find("suggested dt = T/30 = 0.05 s"), std::string::npos) << notes[0];
}

TEST(TimeSchedule, RestartPointContinuesItsLoadStep) {
  std::vector<std::string> notes;
  TimeSchedule schedule(true, 25, notes);
  ScheduleResume r;
  r.t_reached = 1.0;  // the load step 1..2 started at 1; substep 3 of 4 was the point
  r.first_substep = 4;
  r.carried_step = 0.5;
  schedule.resume(r);
  LoadStep s = step_to(2, 2.0);
  s.n_substeps = 4;
  schedule.begin_load_step(s, {});
  schedule.begin_substeps(std::nullopt);
  ASSERT_FALSE(schedule.done());
  EXPECT_EQ(schedule.next().number, 4);
  EXPECT_EQ(schedule.next().time, 2.0);
  schedule.accept(1, 0);
  EXPECT_TRUE(schedule.done());
  // Continued with AUTOTS a load step solved with constant steps is refused.
  TimeSchedule other(true, 25, notes);
  other.resume(r);
  s.control.automatic = true;
  EXPECT_THROW(other.begin_load_step(s, {}), InputError);
}

}  // namespace
}  // namespace impactfe::test_time_schedule
