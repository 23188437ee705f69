#pragma once
/// The time axis and the step size of a static or full transient analysis, in one place
/// (APDL_SUBSET §3.16-3.18, §9.4; APDL_MODELING §9.1, §9.3; docs/solution_control.md):
/// - the rules for the values the deck gives (check_step_size_settings: the DELTIM / DTIME and
///   NSUBST handlers call it at the command, so an error names that command);
/// - each load step's span and substeps from TIME, DELTIM / NSUBST, AUTOTS and Carry, planned
///   once (also for the load steps known to follow: the stored-point count and the progress
///   estimate read those plans);
/// - the substeps: constant, or under AUTOTS proposed by a StepController (time/step_control.h);
///   a substep's outcome decides accept, cut or stop, and easy substeps let the step grow;
/// - the contact-frequency rules: a step of T/30 resolves an impact, a step over T/10 does not.
/// The driver solves; this class says which time comes next.
#include <optional>
#include <string>
#include <vector>

#include "core/model.h"
#include "time/step_control.h"
#include "time/time_axis.h"

namespace impactfe {

/// The step that resolves a vibration of period T: T/30 (thesis eq. 5-3-1; the contact
/// frequency's ceiling under AUTOTS and the suggested step of the time-step advice).
double resolving_step(double period);
/// The coarsest step that still follows a vibration of period T: T/10 (a longer step is warned).
double coarsest_step(double period);

/// The values DELTIM / DTIME or NSUBST gave `step` (the last of the two wins; checks that need
/// no span): a positive step or count, DTMIN > 0, DTMIN ≤ DTIME ≤ DTMAX, NSBMN in 1..NSBSTP ≤
/// NSBMX. Throws InputError at `where` (the command).
void check_step_size_settings(const LoadStep& step, const SourceLocation& where);

/// AUTOTS settings `control` of `step` with timing `t`. Defaults (APDL_MODELING §9.1 [A]):
/// NSBMX = 1000 NSBSTP (DTMIN = DTIME / 1000), NSBMN = 1 in a static step (DTMAX = span) and
/// NSBMN = NSBSTP in a transient one (DTMAX = DTIME). `default_on`: AUTOTS when the deck did not
/// say. `carried`: the last step of the previous load step (Carry ON). Throws InputError at the
/// step's command when DELTIM's DTMIN / DTMAX exclude the step it runs at (DELTIM rounded to
/// divide the span).
AutoStepPlan auto_step_plan(const LoadStep& step, const StepControl& control,
                            const LoadStepTiming& t, bool transient, bool default_on,
                            std::optional<double> carried = std::nullopt);

/// One substep to solve: its number in the load step, end time, size, position in the load step
/// (KBC ramps) and its index on the nominal grid (0 between grid points; output selection).
struct Substep {
  int number = 1;
  double time = 0.0;
  double h = 0.0;
  double fraction = 1.0;
  int grid = 0;
  int n_grid = 1;  // substeps of the nominal grid
};

/// What solving a substep gave: the driver reports it, the schedule decides.
struct SubstepOutcome {
  /// Why the substep failed (no convergence, status chatter, not finite, a solution error);
  /// empty when it converged. Only a substep that may be cut reports a failure.
  std::string failure;
  /// A contact with KEYOPT(7) = 1 that penetrated too far in this substep; empty if none.
  std::string penetration;
  int status_changes = 0;
  double step = 0.0;  // the time integrator's step (0: a static substep)
};

enum class SubstepDecision { Accept, Cut, Stop };

/// The progress figures after a substep: the substeps of the load step (an estimate under
/// AUTOTS), those left in the whole run as known now, and the end time of the last known step.
struct SubstepProgress {
  int substeps = 0;
  long long left = 0;
  double run_end = 0.0;
};

/// Where a restart point puts the schedule (RestartPoint): the time reached, the step Carry
/// starts the next load step with, and for a point inside a load step its next substep and,
/// under AUTOTS, the controller state and the end of the load step it was planned for.
struct ScheduleResume {
  double t_reached = 0.0;
  std::optional<double> carried_step;
  int first_substep = 1;
  std::optional<StepController::State> autots;
  double autots_t_end = 0.0;
};

class TimeSchedule {
 public:
  /// AUTOTS when the deck does not say: constant steps (docs/solution_control.md, "Default").
  static constexpr bool kAutotsDefault = false;

  /// `max_iterations` (NEQIT): a substep of at most max(1, NEQIT/4) iterations and no status
  /// change is easy. `notes`: where the run summary's lines go (rounded DELTIM, AUTOTS summary,
  /// time-step advice).
  TimeSchedule(bool transient, int max_iterations, std::vector<std::string>& notes);

  bool transient() const { return transient_; }

  // ---- the run ----------------------------------------------------------------------------
  /// Continues from a restart point.
  void resume(const ScheduleResume& r);
  /// The load steps known to follow the one begun next. Each is planned once, when first
  /// needed (for the count below, or the progress estimate when the load step before it
  /// begins); the plan is kept for when it begins. A load step whose timing is invalid ends the
  /// look-ahead; its error is raised when it begins, after the load steps before it ran.
  void look_ahead(const std::vector<LoadStep>& following);
  /// The substep counts of the load steps looked ahead at from the time reached, or nullopt
  /// when one of them is invalid.
  std::optional<std::vector<int>> substeps_ahead();
  /// The step Carry starts the next load step with (the last one the previous wanted).
  std::optional<double> carried_step() const { return carried_; }
  double time_reached() const { return t_reached_; }

  // ---- one load step ----------------------------------------------------------------------
  /// Plans `step` from the time reached (InputError for its timing, its AUTOTS limits, or a
  /// restart point that does not fit it). `output_strides`: OUTRES frequencies n > 1 (AUTOTS
  /// lands on their grid points). A DELTIM rounded to divide the span is noted.
  void begin_load_step(const LoadStep& step, std::vector<int> output_strides);
  const LoadStepTiming& timing() const { return timing_; }
  bool automatic() const { return plan_.automatic; }
  /// The first step of the load step.
  double first_step() const { return plan_.automatic ? plan_.dt_first : timing_.h; }
  /// Continuing inside an AUTOTS load step (the controller gives the step: no step change).
  bool resumes_automatic() const { return resume_autots_.has_value(); }
  /// Before the first substep. `impact_period`: the period of the highest contact frequency of
  /// the model (AUTOTS: a substep in which a contact opens or closes is cut until it is at most
  /// T/30); nullopt: no contact, or a static step.
  void begin_substeps(std::optional<double> impact_period);

  bool done() const;
  Substep next() const;
  /// Accept, cut (the step halved, logged) or stop (the step cannot be cut further:
  /// stop_message) after solving next(). Constant steps are always accepted (their failures
  /// are the driver's errors).
  SubstepDecision decide(const SubstepOutcome& outcome);
  /// Why the run stops (a Stop decision); `time_reached`: the last converged time.
  std::string stop_message(double time_reached) const;
  /// next() was accepted after `iterations` iterations (all attempts at its size) with
  /// `status_changes` status changes (AUTOTS: easy substeps let the step grow).
  void accept(int iterations, int status_changes);
  /// AUTOTS of a dynamic step, after accept: the contacts closed now bound the following steps
  /// to T/30 of their period (nullopt: none closed).
  void set_contact_ceiling(std::optional<double> closed_contact_period);
  /// The number of the substep accepted last.
  int accepted_substep() const;
  /// After the substep accepted at `time`.
  SubstepProgress progress(double time) const;
  /// The AUTOTS controller state a restart point inside this load step keeps (nullopt with
  /// constant steps or after the last substep).
  std::optional<StepController::State> controller_state() const;
  double load_step_end() const { return timing_.t_end; }
  /// Ends the load step: the AUTOTS summary (log and run summary), the time reached and the
  /// step Carry takes on.
  void end_load_step();

  /// The time-step advice for a step h against the contact frequency (`period`, `hz`) of
  /// element `element`, a contact that has closed: the run summary suggests T/30 of the highest
  /// such frequency (one note per analysis, replaced when a stiffer contact closes later), and
  /// with `warn` a step over T/10 is warned.
  void advise(double h, double period, double hz, int element, bool warn = true);

 private:
  /// The timing of `step` from t_start, planned once (kept until its load step ended).
  const LoadStepTiming& timing_of(const LoadStep& step, double t_start);
  /// Plans the load steps looked ahead at from t_start, as far as they are valid.
  void plan_following(double t_start);

  bool transient_;
  int easy_iterations_;
  std::vector<std::string>& notes_;
  double t_reached_ = 0.0;
  std::optional<double> carried_;
  int first_substep_ = 1;
  std::optional<StepController::State> resume_autots_;
  double resume_autots_t_end_ = 0.0;
  std::optional<std::size_t> advice_note_;  // index of the advice in notes_
  double advised_hz_ = 0.0;
  // Plans made: the inputs of a load step's timing (and its start) and the timing.
  struct Planned {
    int number;
    std::optional<double> time_end, dt;
    std::optional<int> n_substeps;
    LoadStepTiming timing;
  };
  std::vector<Planned> planned_;
  std::vector<LoadStep> following_;
  long long later_substeps_ = 0;  // substeps of the valid following load steps
  double run_end_ = 0.0;          // end time of the last of them
  bool ahead_valid_ = true;
  // The load step being solved.
  int load_step_ = 0;
  LoadStepTiming timing_;
  AutoStepPlan plan_;
  std::optional<StepController> control_;
  int k_ = 0;                  // the next substep (constant) / substeps accepted (AUTOTS)
  double impact_limit_ = 0.0;  // AUTOTS: a status change in a longer step cuts it (0: off)
  std::string cut_reason_;
  int cuts_ = 0, ceiling_steps_ = 0;
  double h_min_ = 0.0, h_max_ = 0.0;
};

}  // namespace impactfe
