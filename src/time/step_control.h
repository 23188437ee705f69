#pragma once
/// Automatic time stepping of one load step (AUTOTS; APDL_MODELING §9.1, §9.3;
/// docs/solution_control.md): the step sizes from NSUBST / DELTIM with their minimum and
/// maximum, bisection after a failed substep, growth after easy ones, a ceiling (the contact
/// frequency while gaps are closed), and landing exactly on the requested output times and the
/// load-step end. Pure bookkeeping of times, owned by TimeSchedule (time/time_schedule.h): it
/// proposes the next step and hears whether it was accepted.
#include <optional>
#include <string>
#include <vector>

namespace impactfe {

/// The step limits of a load step under AUTOTS (all in time units; auto_step_plan in
/// time/time_schedule.h).
struct AutoStepPlan {
  bool automatic = false;  // AUTOTS ON / AUTO, or unset with a largest step above the first
  std::string implied;     // why AUTOTS was implied (a note for the summary), or empty
  double t_start = 0.0, t_end = 0.0;
  double dt0 = 0.0;       // first step (NSUBST NSBSTP / DELTIM DTIME): the nominal grid
  double dt_min = 0.0;    // smallest step a cut may reach (NSBMX / DTMIN)
  double dt_max = 0.0;    // largest step growth may reach (NSBMN / DTMAX)
  int n_nominal = 1;      // substeps of the nominal grid (span / dt0)
  double dt_first = 0.0;  // the step the load step starts with (dt0, or the carried one)
};

class StepController {
 public:
  /// Cut factor (CUTCONTROL CUTBACKFACTOR default) and growth rule (§9.3 item 4 [A]): the step
  /// grows by kGrowth after kEasyStreak consecutive easy substeps.
  static constexpr double kCutFactor = 0.5;
  static constexpr double kGrowth = 1.5;
  static constexpr int kEasyStreak = 2;

  /// `output_strides`: OUTRES frequencies n > 1 of the load step: the nominal grid points
  /// j·dt0 with j a multiple of one of them are landed on exactly (the load-step end always).
  StepController(const AutoStepPlan& plan, std::vector<int> output_strides);

  bool done() const { return done_; }
  /// End time of the last accepted substep.
  double time() const { return t_; }
  /// The step to try next and its end time (exactly the next landing time when it lands).
  double next_step() const;
  double next_time() const;
  /// Nominal grid index of next_time() when it is a grid point (0 otherwise).
  int next_grid_index() const;
  /// Accepts the step proposed by next_step(). `easy`: converged in few iterations with no
  /// status change (growth counts these).
  void accept(bool easy);
  /// Halves the step after a failed attempt; false when the attempted step was already at the
  /// minimum (the load step fails).
  bool cut();
  /// Upper bound on the step (nullopt: none), e.g. T/30 of the contact frequency while gaps are
  /// closed; never below the minimum step.
  void set_ceiling(std::optional<double> ceiling);
  const AutoStepPlan& plan() const { return plan_; }
  /// The step size the controller wants (before landing and ceiling).
  double desired() const { return dt_; }

  /// Everything the controller has learnt in its load step so far (restart points inside an
  /// AUTOTS load step): time reached, the step it wants, the ceiling, the easy-step streak.
  /// The next landing (output) time follows from the time reached and the plan.
  struct State {
    double time = 0.0;
    double dt = 0.0;
    std::optional<double> ceiling;
    int easy = 0;
    bool done = false;
  };
  State state() const { return {t_, dt_, ceiling_, easy_, done_}; }
  /// Continues from `s` (a state() of a controller of the same plan).
  void restore(const State& s);

 private:
  struct Proposal {
    double h = 0.0;
    double time = 0.0;
    int grid_index = 0;
  };
  Proposal propose() const;
  /// Next landing time after t_ (grid point of a stride, or t_end) and its grid index.
  double next_landing(int& grid_index) const;
  double grid_time(long long j) const;

  AutoStepPlan plan_;
  std::vector<int> strides_;
  double t_;
  double dt_;
  std::optional<double> ceiling_;
  int easy_ = 0;
  bool done_ = false;
};

}  // namespace impactfe
