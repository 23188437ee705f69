#pragma once
/// Static and full transient solution on all DOFs (spec §10.3, §10.7; thesis eqs. 4-13..4-15):
/// the loop over load steps and substeps. Its parts:
/// - the time schedule (time/time_schedule.h): the substeps of each load step, constant or
///   automatic (AUTOTS: accept, cut, grow), and the T/30 / T/10 contact-frequency rules;
/// - the discretisation (discretisation.h): DOF numbering, assembler, status loop, solver,
///   condensation, built anew when the constraint set or a sliding contact's DOF list changes
///   (large_sliding.h), the state remapped by DOF key (motion_state.h);
/// - the increment (equilibrium_increment.h): Newton-Raphson with the status loop, full or
///   condensed, its result accepted or rejected;
/// - the observers (run_observers.h): progress, results storage, restart points, contact
///   summary, energy report; the energy balance sums the work of every accepted increment.
/// The driver knows neither element kinds nor the time scheme.
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "analysis/discretisation.h"
#include "analysis/energy_balance.h"
#include "analysis/equilibrium_increment.h"
#include "analysis/large_sliding.h"
#include "analysis/motion_state.h"
#include "analysis/restart_file.h"
#include "analysis/run_observers.h"
#include "analysis/run_statistics.h"
#include "analysis/step_loads.h"
#include "results/results_file.h"
#include "time/time_integrator.h"
#include "time/time_schedule.h"

namespace impactfe {

class DirectSolution {
 public:
  /// `transient`: dynamic steps (unless TIMINT is off for a step).
  DirectSolution(Structure& structure, ResultsWriter& writer, const RunSettings& settings,
                 AnalysisStatistics& stats, bool transient);
  DirectSolution(const DirectSolution&) = delete;
  DirectSolution& operator=(const DirectSolution&) = delete;

  /// The load steps known to come after the next one to be solved (planned once: progress
  /// estimate, stored-point count).
  void look_ahead(const std::vector<LoadStep>& steps) { schedule_.look_ahead(steps); }
  /// The points the load steps looked ahead at (`steps`) store at most with constant substeps
  /// (OUTRES; the initial state of a transient included); 0 when a step's timing is invalid
  /// (reported when the step is solved). Automatic time stepping may store more.
  long long stored_points_at_most(const std::vector<LoadStep>& steps);

  /// MAPDL solves a load step when SOLVE is read: begin, then solve_load_step for each load
  /// step in order, then finish.
  void begin();
  void solve_load_step(const LoadStep& step);
  void finish();

 private:
  /// A new discretisation for the constraint set `wanted`, the state remapped by DOF key.
  /// `keep_dynamics`: the integrator continues (its history remapped) instead of restarting.
  void renumber(std::set<DofKey> wanted, bool keep_dynamics);
  void set_constraints(const LoadStep& step);
  /// After an accepted increment: contacts whose DOF lists follow the deformation re-find them;
  /// a change renumbers.
  void refresh_connectivity();
  /// The initial state of the run's first load step (stored for a transient) and the start of
  /// the time integration.
  void start_load_step(const LoadStep& step, const LoadStep* previous, bool dynamic);
  /// Solves the schedule's next substep; a cut leaves it to be tried again at a smaller step.
  void solve_substep(const LoadStep& step, const LoadStep* previous, bool dynamic);
  /// After the substep at which a stop was requested (SIGINT, SIGTERM): RunInterrupted.
  [[noreturn]] void stop_on_request(const LoadStep& step);
  void change_step(double h);
  /// The time-step advice (TimeSchedule::advise) for step h from the stiffest contact that has
  /// closed so far in the analysis; none before one closes.
  void time_step_advice(double h, bool warn);
  // Restart (ANTYPE,,RESTART): the point read in begin(), applied at the first load step.
  void take_restart_request();
  void apply_restart(const LoadStep& step);

  Structure& structure_;
  ResultsWriter& writer_;
  RunSettings settings_;
  AnalysisStatistics& stats_;
  bool transient_;
  std::optional<ContactFrequency> closed_highest_;  // of the contacts closed so far
  int stopping_ = 0;  // the signal that stops the run after the substep accepted last (0: none)
  // Creep substep predictor: the increment of the last static creep substep, its step and load
  // step (solve_substep).
  VectorXd creep_increment_;
  double creep_step_ = 0.0;
  int creep_load_step_ = 0;

  TimeSchedule schedule_;
  std::unique_ptr<Discretisation> disc_;
  SolverCounters retired_;  // counts of discretisations replaced by a renumbering
  std::unique_ptr<TimeIntegrator> integrator_;
  bool dynamics_started_ = false;
  MotionState state_;
  StepLoads loads_;
  EnergyBalance energy_;
  EquilibriumIncrement increment_;
  LargeSliding sliding_;

  RunParts parts_;
  ResultStorage storage_;
  ProgressReport progress_;
  std::unique_ptr<RestartRecorder> restart_recorder_;
  ContactSummaryLog contact_log_;
  EnergyReport energy_report_;
  std::vector<RunObserver*> observers_;

  std::optional<LoadStep> previous_;  // the last load step solved (KBC ramps start from it)
  // Continuing from a restart point: the point (until applied), the load-step numbering.
  std::unique_ptr<RestartPoint> restart_;
  int load_step_offset_ = 0;
  bool restarted_ = false;
};

}  // namespace impactfe
