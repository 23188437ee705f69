// The parts of the static / full transient driver on small models read from deck text: the
// discretisation and the remapping of the state by DOF key (renumbering), the increment (a
// static spring reaches F/k; a rejected increment leaves the state alone), the energy balance
// (trapezoidal work, the numerical-dissipation warning, its restart state), the contact
// frequency of the time-step advice against ω = √(k (1/m_I + 1/m_J)), and restart points
// (captured and restored state, where the schedule continues, the loads a ramp starts from).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "../support/run_deck.h"
#include "analysis/discretisation.h"
#include "analysis/energy_balance.h"
#include "analysis/equilibrium_increment.h"
#include "analysis/motion_state.h"
#include "analysis/restart_points.h"
#include "analysis/run_observers.h"
#include "analysis/step_loads.h"
#include "analysis/time_step_advice.h"
#include "core/log.h"
#include "deck/deck_reader.h"

namespace impactfe::test_direct_solution_parts {
namespace {

/// A model read from deck text and its first analysis, with the structure built from them.
struct ModelFixture {
  explicit ModelFixture(const std::string& text)
      : job(read_deck_text(text, "parts.inp")),
        request(*job.steps.at(0).analysis),
        structure(*job.steps.at(0).model_snapshot, request.options, settings) {}
  const LoadStep& step(std::size_t i = 0) const { return request.load_steps.at(i); }
  Job job;
  AnalysisRequest request;
  RunSettings settings;
  Structure structure;
};

// A spring k = 100 from the fixed node 1 to node 2, pulled by F = 10 in X (static).
const char* const kSpring =
    "/PREP7\nET,1,COMBIN14,,1\nR,1,100\nN,1\nN,2,1\nE,1,2\nFINISH\n/SOLU\nANTYPE,STATIC\n"
    "D,1,ALL\nF,2,FX,10\nSOLVE\nFINISH\n";

int index_of(const Discretisation& disc, int node, Dof dof) {
  return disc.dofs().index(DofKey{node, dof});
}

TEST(Discretisation, RenumberingKeepsTheStateOfEachDof) {
  // Two point masses on springs in X and Y; the second constraint set also holds node 3 UY.
  ModelFixture m(
      "/PREP7\nET,1,COMBIN14,,1\nET,2,COMBIN14,,2\nET,3,MASS21,,,4\nR,1,100\nR,2,1\nN,1\nN,2,1\n"
      "N,3,2\nE,1,2\nE,2,3\nTYPE,2\nE,1,2\nE,2,3\nTYPE,3\nREAL,2\nE,2\nE,3\nFINISH\n/SOLU\n"
      "ANTYPE,TRANS\nD,1,ALL\nIC,3,UX,0.5,2\nIC,2,UY,0.25\nTIME,1\nSOLVE\nFINISH\n");
  std::set<DofKey> fixed = m.structure.constraints_of(m.step());
  Discretisation a(m.structure, fixed, false);
  MotionState state;
  state.start(a.dofs(), m.structure.model());
  EXPECT_EQ(state.u(index_of(a, 3, Dof::UX)), 0.5);
  EXPECT_EQ(state.v(index_of(a, 3, Dof::UX)), 2.0);
  EXPECT_EQ(state.u(index_of(a, 2, Dof::UY)), 0.25);
  state.reactions = VectorXd::LinSpaced(a.dofs().n_active(), 1.0, 2.0);
  const double reaction_2x = state.reactions(index_of(a, 2, Dof::UX));

  fixed.insert(DofKey{3, Dof::UY});
  Discretisation b(m.structure, fixed, false);
  EXPECT_EQ(b.dofs().n_free(), a.dofs().n_free() - 1);
  state.remap(a.dofs(), b.dofs());
  EXPECT_EQ(state.u.size(), b.dofs().n_active());
  EXPECT_EQ(state.u(index_of(b, 3, Dof::UX)), 0.5);
  EXPECT_EQ(state.v(index_of(b, 3, Dof::UX)), 2.0);
  EXPECT_EQ(state.u(index_of(b, 2, Dof::UY)), 0.25);
  EXPECT_EQ(state.reactions(index_of(b, 2, Dof::UX)), reaction_2x);
  // A vector that is not over the old numbering is not guessed at: zeros.
  EXPECT_TRUE(remap_by_key(VectorXd::Ones(2), a.dofs(), b.dofs()).isZero());
}

/// The parts of a static run on `m`'s first load step, solved to its end in one increment.
struct StaticRun {
  explicit StaticRun(ModelFixture& m)
      : disc(m.structure, m.structure.constraints_of(m.step()), false),
        loads(m.structure),
        energy(m.structure.elements()),
        increment(m.structure, m.settings, stats, state, loads, energy) {
    state.start(disc.dofs(), m.structure.model());
    loads.resolve(disc, m.step(), nullptr);
    increment.bind(disc, nullptr);
  }
  SubstepOutcome solve(bool may_cut = false) {
    return increment.find_equilibrium(loads.at(1.0, 1.0), StepLabel{1, 1, 1.0}, false, may_cut);
  }
  Discretisation disc;
  AnalysisStatistics stats;
  MotionState state;
  StepLoads loads;
  EnergyBalance energy;
  EquilibriumIncrement increment;
};

TEST(EquilibriumIncrement, StaticSpringReachesForceOverStiffness) {
  ModelFixture m(kSpring);
  StaticRun run(m);
  const SubstepOutcome outcome = run.solve(true);
  EXPECT_EQ(outcome.failure, "");
  EXPECT_EQ(outcome.penetration, "");
  EXPECT_TRUE(run.state.u.isZero());  // solved, not yet accepted
  run.increment.accept();
  const int ux = index_of(run.disc, 2, Dof::UX);
  EXPECT_NEAR(run.state.u(ux), 0.1, 1e-12);
  // The reaction at the support balances the load.
  EXPECT_NEAR(run.state.reactions(index_of(run.disc, 1, Dof::UX)), -10.0, 1e-9);
  EXPECT_EQ(run.state.time, 1.0);
  EXPECT_GE(run.stats.n_iterations, 1);
}

TEST(EquilibriumIncrement, RejectedIncrementLeavesTheStateAlone) {
  ModelFixture m(kSpring);
  StaticRun run(m);
  run.solve();
  run.increment.reject();
  EXPECT_TRUE(run.state.u.isZero());
  EXPECT_FALSE(run.disc.factor_valid());  // the next attempt factorizes again
}

TEST(EnergyBalance, StaticStepWorkIsTrapezoidalAndBalances) {
  ModelFixture m(kSpring);
  StaticRun run(m);
  run.solve();
  run.increment.accept();
  // Load ramped from 0 to 10 over u = 0.1: W = ½ F u = 0.5, all of it strain energy.
  EXPECT_NEAR(run.energy.external_work(), 0.5, 1e-12);
  EXPECT_NEAR(run.energy.strain_energy(), 0.5, 1e-12);
  EXPECT_NEAR(run.energy.numerical_dissipation(0.0), 0.0, 1e-12);
  EXPECT_EQ(run.energy.balance_warning(0.0), std::nullopt);
  // Had 0.1 of it gone as kinetic energy, the balance would be off the other way (created).
  const auto created = run.energy.balance_warning(0.1);
  ASSERT_TRUE(created.has_value());
  EXPECT_NE(created->find("energy created"), std::string::npos) << *created;
  // The restart state carries the sums exactly.
  EnergyBalance copy(m.structure.elements());
  copy.restore(run.energy.state());
  EXPECT_EQ(copy.columns(0.0), run.energy.columns(0.0));
}

TEST(EnergyBalance, WarnsWhenTheIntegratorDissipatesMoreThanFivePercent) {
  ModelFixture m(kSpring);
  EnergyBalance energy(m.structure.elements());
  energy.set_initial_kinetic(1.0);  // all of it should still be there: 10 % lost
  const auto warning = energy.balance_warning(0.9);
  ASSERT_TRUE(warning.has_value());
  EXPECT_NE(warning->find("dissipated 10.0 %"), std::string::npos) << *warning;
  EXPECT_EQ(energy.balance_warning(0.96), std::nullopt);  // 4 %: accepted
}

TEST(EnergyBalance, CreationPastTenPercentOfTheInputIsAnError) {
  ModelFixture m(kSpring);
  EnergyBalance energy(m.structure.elements());
  EXPECT_EQ(energy.creation(1.0), std::nullopt);  // nothing put in: nothing checked
  energy.set_initial_kinetic(1.0);
  EXPECT_EQ(energy.creation(1.09), std::nullopt);  // 9 % created: below the bound
  const auto created = energy.creation(1.2);
  ASSERT_TRUE(created.has_value());
  EXPECT_EQ(created->term, "kinetic + strain energy");
  EXPECT_NEAR(created->created, 0.2, 1e-12);
  EXPECT_NEAR(created->reference, 1.0, 1e-12);
  // The strain energy of IC displacements counts as put in.
  energy.set_initial_strain(1.0);
  EXPECT_EQ(energy.creation(1.15), std::nullopt);
}

// Ground (node 1), mass 2 (node 2) on gap 1, mass 3 (node 3) on gap 2 from node 2; gaps open.
const char* const kTwoGaps =
    "/PREP7\nET,1,COMBIN40,,,2\nET,2,MASS21,,,4\nR,1,600,,,0.1\nR,2,2\nR,3,3\nN,1\nN,2,,1\n"
    "N,3,,2\nE,1,2\nE,2,3\nTYPE,2\nREAL,2\nE,2\nREAL,3\nE,3\nFINISH\n/SOLU\nANTYPE,TRANS\n"
    "D,1,ALL\nD,2,UX\nD,3,UX\nTIME,0.01\nSOLVE\nFINISH\n";

TEST(TimeStepAdvice, ContactFrequencyOfTheBodiesAGapJoins) {
  ModelFixture m(kTwoGaps);
  Discretisation disc(m.structure, m.structure.constraints_of(m.step()), true);
  const ContactFrequencyEstimator* estimator = disc.contact_frequency();
  ASSERT_NE(estimator, nullptr);
  const auto highest = estimator->highest(false);
  ASSERT_TRUE(highest.has_value());
  // Gap 2 joins the masses 2 and 3: ω = √(600 (1/2 + 1/3)) = √500; gap 1 to the ground gives
  // √(600 / 2) = √300 only.
  EXPECT_EQ(highest->element, 2);
  EXPECT_NEAR(highest->omega, std::sqrt(500.0), 1e-9);
  EXPECT_NEAR(highest->period(), 2 * M_PI / std::sqrt(500.0), 1e-12);
  // Both gaps are open: no contact bounds the step.
  EXPECT_EQ(estimator->highest(true), std::nullopt);
}

TEST(RestartPoints, CapturedStateIsRestoredOnAnotherNumbering) {
  ModelFixture m(kSpring);
  StaticRun run(m);
  run.solve();
  run.increment.accept();
  std::vector<std::string> notes;
  TimeSchedule schedule(false, 25, notes);
  schedule.begin_load_step(m.step(), {});
  schedule.accept(1, 0);
  const RestartSite site{m.step(), nullptr, 1, true, false};
  const RestartPoint p =
      capture_restart_point(site, m.structure, run.disc, run.state, run.energy, nullptr, schedule);
  EXPECT_TRUE(p.last);
  EXPECT_EQ(p.time, 1.0);
  EXPECT_EQ(p.t_start, 0.0);
  EXPECT_FALSE(p.autots.has_value());

  // A discretisation that also holds node 2 UY: the saved values land by DOF key.
  std::set<DofKey> fixed = m.structure.constraints_of(m.step());
  fixed.insert(DofKey{2, Dof::UY});
  Discretisation other(m.structure, fixed, false);
  MotionState state;
  EnergyBalance energy(m.structure.elements());
  restore_motion(p, other, state, energy);
  EXPECT_EQ(state.u(index_of(other, 2, Dof::UX)), run.state.u(index_of(run.disc, 2, Dof::UX)));
  EXPECT_EQ(state.reactions(index_of(other, 1, Dof::UX)),
            run.state.reactions(index_of(run.disc, 1, Dof::UX)));
  EXPECT_EQ(state.time, 1.0);
  EXPECT_EQ(energy.external_work(), run.energy.external_work());
  restore_element_states(p, m.structure, other, state.u, m.step().where);

  // After the end of load step 1 the schedule continues at its end time, from substep 1, and
  // the next load step ramps from load step 1's loads.
  const ScheduleResume r = schedule_resume(p);
  EXPECT_EQ(r.t_reached, 1.0);
  EXPECT_EQ(r.first_substep, 1);
  EXPECT_EQ(r.carried_step, std::nullopt);
  const auto ramp = ramp_start(p);
  ASSERT_TRUE(ramp.has_value());
  EXPECT_EQ(ramp->number, 1);
  EXPECT_EQ(ramp->forces, m.step().forces);
  // RESCONTROL: no point unless it was given; every 2nd substep and the last when asked.
  LoadStep s = m.step();
  EXPECT_FALSE(restart_point_wanted(s, 1, true));
  s.rescontrol = RestartControl{true, 0, 2};
  EXPECT_FALSE(restart_point_wanted(s, 1, false));
  EXPECT_TRUE(restart_point_wanted(s, 2, false));
  EXPECT_TRUE(restart_point_wanted(s, 3, true));
}

/// Records the progress events.
struct ProgressLog final : ProgressObserver {
  void substep_done(const ProgressEvent& e) override { events.push_back(e); }
  std::vector<ProgressEvent> events;
};

TEST(RunObservers, ProgressCountsTheSubstepsLeftInTheRun) {
  ModelFixture m(kSpring);
  LoadStep first = m.step();
  first.n_substeps = 4;
  LoadStep second = first;
  second.number = 2;
  second.time_end = 3.0;
  std::vector<std::string> notes;
  TimeSchedule schedule(false, 25, notes);
  schedule.look_ahead({second});
  schedule.begin_load_step(first, {});
  schedule.begin_substeps(std::nullopt);
  auto disc =
      std::make_unique<Discretisation>(m.structure, m.structure.constraints_of(first), false);
  MotionState state;
  state.start(disc->dofs(), m.structure.model());
  EnergyBalance energy(m.structure.elements());
  std::unique_ptr<TimeIntegrator> no_integrator;
  const bool running = false;
  AnalysisStatistics stats;
  stats.description = "static";
  const RunParts parts{m.structure, disc, state, energy, no_integrator, schedule, running, stats};
  ProgressLog log;
  ProgressReport progress(parts, &log);
  const Substep s = schedule.next();
  schedule.accept(2, 0);
  progress.substep_accepted(AcceptedSubstep{first, nullptr, s, 2, 0, false, false});
  ASSERT_EQ(log.events.size(), 1u);
  const ProgressEvent& e = log.events[0];
  EXPECT_EQ(e.analysis, "static");
  EXPECT_EQ(e.substep, 1);
  EXPECT_EQ(e.substeps, 4);
  EXPECT_EQ(e.time, 0.25);
  EXPECT_EQ(e.time_end, 1.0);
  EXPECT_EQ(e.iterations, 2);
  EXPECT_EQ(e.substeps_left, 3 + 4);  // 3 of this load step, 4 of the next
  EXPECT_EQ(e.run_time_end, 3.0);
}

TEST(DirectSolution, RoundedDeltimIsInTheRunSummary) {
  // DELTIM 0.3 over TIME 1: 3 substeps of 1/3 (the nearest whole number), said in the summary.
  const auto run = testing::run_deck_text(
      "rounded_deltim",
      "/PREP7\nET,1,COMBIN14,,1\nET,2,MASS21,,,4\nR,1,100\nR,2,1\nN,1\nN,2,1\nE,1,2\n"
      "TYPE,2\nREAL,2\nE,2\nFINISH\n/SOLU\nANTYPE,TRANS\nD,1,ALL\nD,2,UY\nF,2,FX,1\n"
      "TIME,1\nDELTIM,0.3\nOUTRES,ALL,ALL\nSOLVE\nFINISH\n");
  const AnalysisStatistics& a = run.statistics.analyses.at(0);
  EXPECT_EQ(a.n_substeps, 3);
  bool noted = false;
  for (const std::string& note : a.notes)
    noted = noted || note.find("DELTIM 0.3 does not divide the load step") != std::string::npos;
  EXPECT_TRUE(noted);
  const std::vector<double> times = run.reader->times(1);
  ASSERT_EQ(times.size(), 4u);
  EXPECT_DOUBLE_EQ(times[1], 1.0 / 3);
  EXPECT_EQ(times[3], 1.0);
}

/// A mass (node 2, m = 1) at 50 in/s onto the floor through gap 1 (k = 1e5, GAP `near_gap`;
/// 0.1: it closes at t = 0.002, f = sqrt(1e5) / 2 pi = 50.33 Hz) beside a far stiffer gap 2
/// (k = 1e9, 5033 Hz) whose gap of 100 the mass never crosses; constant steps of 0.004, over
/// T/10 = 0.002 of gap 1.
std::string falling_mass_deck(const std::string& near_gap) {
  return "/PREP7\nET,1,COMBIN40,,,2\nET,2,MASS21,,,4\nR,1,1.0E5,,," + near_gap +
         "\nR,2,1.0E9,,,100\nR,3,1.0\nN,1\nN,2,,1\nN,4\nTYPE,1\nREAL,1\nE,1,2\nREAL,2\n"
         "E,4,2\nTYPE,2\nREAL,3\nE,2\nFINISH\n/SOLU\nANTYPE,TRANS\nTRNOPT,FULL\nD,1,ALL\n"
         "D,4,ALL\nD,2,UX\nIC,2,UY,0,-50\nTIME,0.012\nDELTIM,0.004\nOUTRES,ALL,ALL\nSOLVE\n"
         "FINISH\n";
}

std::vector<std::string> advice_and_warnings(const testing::DeckRun& run) {
  std::vector<std::string> out;
  for (const std::string& note : run.statistics.analyses.at(0).notes)
    if (note.find("contact frequency") != std::string::npos) out.push_back(note);
  for (const std::string& w : Log::warnings())
    if (w.find("contact frequency") != std::string::npos) out.push_back(w);
  return out;
}

TEST(TimeStepAdvice, NamesOnlyContactsThatClosed) {
  Log::clear();
  const auto run = testing::run_deck_text("advice_closed", falling_mass_deck("0.1"));
  const std::vector<std::string> said = advice_and_warnings(run);
  ASSERT_EQ(said.size(), 2u);  // the suggestion in the summary and the warning of dt = 0.004
  for (const std::string& s : said) {
    EXPECT_NE(s.find("50.33 Hz (element 1 closed)"), std::string::npos) << s;
    EXPECT_EQ(s.find("element 2"), std::string::npos) << s;
  }
}

TEST(TimeStepAdvice, NoneWhenNoContactCloses) {
  Log::clear();
  const auto run = testing::run_deck_text("advice_open", falling_mass_deck("100"));
  EXPECT_TRUE(advice_and_warnings(run).empty());
}

}  // namespace
}  // namespace impactfe::test_direct_solution_parts
