#include "time/time_schedule.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/log.h"

namespace impactfe {

namespace {

/// Steps per period: T/30 resolves a vibration, T/10 is the coarsest step that follows it
/// (thesis §III.C, eq. 5-3-1).
constexpr double kResolvingStepsPerPeriod = 30.0;
constexpr double kCoarsestStepsPerPeriod = 10.0;

[[noreturn]] void fail_load_step(const LoadStep& step, const std::string& message) {
  throw InputError(step.where, fmt::format("load step {}: {}", step.number, message));
}

/// The span and constant substeps of a load step starting at t_start. TIME is required in a
/// transient; a static step without TIME ends at its load-step number. DELTIM wins over NSUBST
/// when both were given (the deck keeps only the last of the two); neither gives one substep.
LoadStepTiming load_step_timing(const LoadStep& step, double t_start, bool transient) {
  LoadStepTiming t;
  t.t_start = t_start;
  if (step.time_end) {
    t.t_end = *step.time_end;
  } else if (transient) {
    fail_load_step(step, "TIME (end time) is required in a transient analysis");
  } else {
    t.t_end = static_cast<double>(step.number);  // static default: the load-step number
  }
  if (!(t.t_end > t_start))
    fail_load_step(
        step, fmt::format("end time {} does not increase (previous end {})", t.t_end, t_start));
  const double span = t.t_end - t_start;
  if (step.dt) {
    t.n_substeps = substep_count(step, span, *step.dt);
  } else if (step.n_substeps) {
    if (*step.n_substeps > kMaxSubstepsPerLoadStep)
      fail_load_step(step, fmt::format("{} substeps is more than {}", *step.n_substeps,
                                       kMaxSubstepsPerLoadStep));
    // Positive: check_step_size_settings at the command.
    IMPACTFE_CHECK(*step.n_substeps > 0, "a load step with no substeps");
    t.n_substeps = *step.n_substeps;
  }
  t.h = span / t.n_substeps;
  return t;
}

/// The note when DELTIM does not divide the load step (the substep count is rounded, so the
/// step run differs from the one given), or empty.
std::string rounding_note(const LoadStep& step, const LoadStepTiming& t) {
  if (!step.dt || std::abs(t.h - *step.dt) <= 1e-6 * *step.dt) return {};
  return fmt::format(
      "load step {}: DELTIM {:g} does not divide the load step (t = {:g} to {:g}); it runs {} "
      "substep(s) of {:.6g}",
      step.number, *step.dt, t.t_start, t.t_end, t.n_substeps, t.h);
}

}  // namespace

double resolving_step(double period) {
  return period / kResolvingStepsPerPeriod;
}

double coarsest_step(double period) {
  return period / kCoarsestStepsPerPeriod;
}

void check_step_size_settings(const LoadStep& step, const SourceLocation& where) {
  const auto reject = [&](const std::string& message) { throw InputError(where, message); };
  const StepControl& c = step.control;
  if (step.dt) {  // DELTIM / DTIME: DTIME, DTMIN, DTMAX in time units
    const double dt = *step.dt;
    if (!(dt > 0.0)) reject(fmt::format("time step {} must be positive", dt));
    if (c.dt_min && !(*c.dt_min > 0.0)) reject(fmt::format("DTMIN {} must be positive", *c.dt_min));
    if (c.dt_max && *c.dt_max < dt)
      reject(fmt::format("DTMAX {} is smaller than the time step {}", *c.dt_max, dt));
    if (c.dt_min && *c.dt_min > dt)
      reject(fmt::format("DTMIN {} is larger than the time step {}", *c.dt_min, dt));
  }
  if (step.n_substeps) {  // NSUBST / ITER: NSBSTP, NSBMX, NSBMN in substep counts
    const int n = *step.n_substeps;
    if (n <= 0) reject(fmt::format("number of substeps {} must be positive", n));
    if (c.n_max && *c.n_max < n)
      reject(fmt::format("NSBMX {} (most substeps) is smaller than NSBSTP {}", *c.n_max, n));
    if (c.n_min && (*c.n_min <= 0 || *c.n_min > n))
      reject(fmt::format("NSBMN {} (fewest substeps) must be in 1..NSBSTP ({})", *c.n_min, n));
  }
}

AutoStepPlan auto_step_plan(const LoadStep& step, const StepControl& c, const LoadStepTiming& t,
                            bool transient, bool default_on, std::optional<double> carried) {
  AutoStepPlan p;
  p.automatic = c.automatic.value_or(default_on);
  p.t_start = t.t_start;
  p.t_end = t.t_end;
  p.dt0 = t.h;
  p.n_nominal = t.n_substeps;
  const double span = t.t_end - t.t_start;
  // The largest step defaults to the first one in a transient (growth then only recovers from
  // cuts), to the whole span in a static step (§9.1 [A]).
  const double default_max = transient ? p.dt0 : span;
  if (step.dt) {  // DELTIM,DTIME,DTMIN,DTMAX in time units
    p.dt_min = c.dt_min.value_or(p.dt0 / 1000.0);
    p.dt_max = c.dt_max.value_or(default_max);
    // DTIME was checked against its limits at the command; the step run is DTIME rounded to
    // divide the span. A span shorter than DTIME is one step of the span, whatever DTMIN (MAPDL
    // takes the time left: the Verification Manual's creep decks give DELTIM,1.0,0.99,1.0 from
    // t = 0.1 to 1); with constant steps the limits are not used.
    if (t.n_substeps == 1 && span < *step.dt) p.dt_min = std::min(p.dt_min, p.dt0);
    if (!p.automatic) p.dt_min = std::min(p.dt_min, p.dt0);
    if (p.dt_min > p.dt0 * (1.0 + 1e-9))
      fail_load_step(step, fmt::format("DTMIN {:g} is larger than the time step {:g} (DELTIM)",
                                       p.dt_min, p.dt0));
    if (p.dt_max < p.dt0 * (1.0 - 1e-9))
      fail_load_step(step, fmt::format("DTMAX {:g} is smaller than the time step {:g} (DELTIM)",
                                       p.dt_max, p.dt0));
  } else {  // NSUBST,NSBSTP,NSBMX,NSBMN in substep counts (or one substep by default)
    p.dt_min = c.n_max ? span / *c.n_max : p.dt0 / 1000.0;
    p.dt_max = c.n_min ? span / *c.n_min : default_max;
  }
  // AUTOTS not given, but a largest step above the first (DTMAX > DTIME, NSBMN < NSBSTP): a
  // limit that only automatic time stepping uses, so the deck asks for it (MAPDL's default is
  // AUTOTS ON); carried out rather than accepted and ignored.
  if (!c.automatic && !p.automatic) {
    if (step.dt && c.dt_max && *c.dt_max > p.dt0 * (1.0 + 1e-9) && span > p.dt0 * (1.0 + 1e-9))
      p.implied = fmt::format("DELTIM's DTMAX {:g} exceeds DTIME {:g}", *c.dt_max, p.dt0);
    else if (!step.dt && c.n_min && *c.n_min < t.n_substeps)
      p.implied = fmt::format("NSUBST's NSBMN {} is below NSBSTP {}", *c.n_min, t.n_substeps);
    p.automatic = !p.implied.empty();
  }
  p.dt_min = std::min(p.dt_min, p.dt0);
  p.dt_max = std::min(std::max(p.dt_max, p.dt0), span);
  p.dt_first = p.dt0;
  if (c.carry && carried) p.dt_first = std::clamp(*carried, p.dt_min, p.dt_max);
  return p;
}

TimeSchedule::TimeSchedule(bool transient, int max_iterations, std::vector<std::string>& notes)
    : transient_(transient), easy_iterations_(std::max(1, max_iterations / 4)), notes_(notes) {}

void TimeSchedule::resume(const ScheduleResume& r) {
  t_reached_ = r.t_reached;
  carried_ = r.carried_step;
  first_substep_ = r.first_substep;
  resume_autots_ = r.autots;
  resume_autots_t_end_ = r.autots_t_end;
}

// ---- planning ---------------------------------------------------------------------------------

const LoadStepTiming& TimeSchedule::timing_of(const LoadStep& step, double t_start) {
  for (const Planned& p : planned_)
    if (p.number == step.number && p.time_end == step.time_end && p.dt == step.dt &&
        p.n_substeps == step.n_substeps && p.timing.t_start == t_start)
      return p.timing;
  planned_.push_back({step.number, step.time_end, step.dt, step.n_substeps,
                      load_step_timing(step, t_start, transient_)});
  return planned_.back().timing;
}

void TimeSchedule::look_ahead(const std::vector<LoadStep>& following) {
  following_ = following;
}

void TimeSchedule::plan_following(double t_start) {
  later_substeps_ = 0;
  run_end_ = t_start;
  ahead_valid_ = true;
  for (const LoadStep& next : following_) {
    try {
      const LoadStepTiming& t = timing_of(next, run_end_);
      later_substeps_ += t.n_substeps;
      run_end_ = t.t_end;
    } catch (const InputError&) {
      // Planned again when it begins: its error is raised then, after the steps before it.
      ahead_valid_ = false;
      return;
    }
  }
}

std::optional<std::vector<int>> TimeSchedule::substeps_ahead() {
  plan_following(t_reached_);
  if (!ahead_valid_) return std::nullopt;
  std::vector<int> counts;
  double t = t_reached_;
  for (const LoadStep& next : following_) {
    const LoadStepTiming& timing = timing_of(next, t);
    counts.push_back(timing.n_substeps);
    t = timing.t_end;
  }
  return counts;
}

void TimeSchedule::begin_load_step(const LoadStep& step, std::vector<int> output_strides) {
  // Plans of load steps that ended are not asked for again.
  std::erase_if(planned_, [&](const Planned& p) { return p.timing.t_start < t_reached_; });
  timing_ = timing_of(step, t_reached_);
  load_step_ = step.number;
  plan_ = auto_step_plan(step, step.control, timing_, transient_, kAutotsDefault, carried_);
  // A restart point inside a load step continues it with the same kind of substeps: the state
  // of the step controller is part of a point inside an AUTOTS load step.
  if (first_substep_ > 1 && plan_.automatic != resume_autots_.has_value())
    throw InputError(
        step.where,
        fmt::format("load step {}: the restart point (substep {}) is inside a load "
                    "step solved {}; continue it with AUTOTS,{} as it was solved",
                    step.number, first_substep_ - 1,
                    resume_autots_ ? "with automatic time stepping" : "with constant steps",
                    resume_autots_ ? "ON" : "OFF"));
  if (resume_autots_ &&
      std::abs(resume_autots_t_end_ - plan_.t_end) > 1e-12 * std::max(std::abs(plan_.t_end), 1.0))
    throw InputError(step.where,
                     fmt::format("load step {}: the restart point is inside a load step ending at "
                                 "t = {:g}, but this load step ends at t = {:g} (repeat its TIME)",
                                 step.number, resume_autots_t_end_, plan_.t_end));
  if (const std::string note = rounding_note(step, timing_); !note.empty()) {
    Log::warn("{}", note);
    notes_.push_back(note);
  }
  if (!plan_.implied.empty()) {
    const std::string note = fmt::format(
        "load step {}: automatic time stepping (AUTOTS not given, but {}: a limit "
        "only AUTOTS uses; AUTOTS,OFF for constant steps)",
        step.number, plan_.implied);
    Log::info("{}", note);
    notes_.push_back(note);
  }
  control_.reset();
  if (plan_.automatic) control_.emplace(plan_, std::move(output_strides));
  k_ = first_substep_;
  cuts_ = ceiling_steps_ = 0;
  h_min_ = std::numeric_limits<double>::infinity();
  h_max_ = 0.0;
  impact_limit_ = 0.0;
  plan_following(timing_.t_end);
}

void TimeSchedule::begin_substeps(std::optional<double> impact_period) {
  if (!plan_.automatic) return;
  k_ = 0;
  if (resume_autots_) {  // continuing from a restart point inside this load step
    control_->restore(*resume_autots_);
    resume_autots_.reset();
    k_ = first_substep_ - 1;
  }
  // Impacts are resolved at T/30 of the highest contact frequency of the model (the time-step
  // advice): a step in which a contact opens or closes is cut until it is that short.
  if (impact_period) impact_limit_ = std::max(resolving_step(*impact_period), plan_.dt_min);
  Log::info(
      "load step {}: automatic time stepping from t = {:g} to {:g}: first dt = {:g}, min {:g}, "
      "max {:g}",
      load_step_, timing_.t_start, timing_.t_end, plan_.dt_first, plan_.dt_min, plan_.dt_max);
}

// ---- substeps ---------------------------------------------------------------------------------

bool TimeSchedule::done() const {
  return control_ ? control_->done() : k_ > timing_.n_substeps;
}

Substep TimeSchedule::next() const {
  Substep s;
  if (!control_) {
    s.number = s.grid = k_;
    s.n_grid = timing_.n_substeps;
    s.time = timing_.t_start + k_ * timing_.h;
    s.h = timing_.h;
    s.fraction = static_cast<double>(k_) / timing_.n_substeps;
    return s;
  }
  s.number = k_ + 1;
  s.h = control_->next_step();
  s.time = control_->next_time();
  s.grid = control_->next_grid_index();
  s.n_grid = plan_.n_nominal;
  s.fraction = s.grid == plan_.n_nominal
                   ? 1.0
                   : (s.time - timing_.t_start) / (timing_.t_end - timing_.t_start);
  return s;
}

SubstepDecision TimeSchedule::decide(const SubstepOutcome& outcome) {
  if (!control_) return SubstepDecision::Accept;
  // APDL_MODELING §9.3 item 2: a failed substep, a contact that opened or closed within a step
  // longer than T/30 of the contact frequency (the impact is not resolved) and a KEYOPT(7) = 1
  // contact that penetrated too far are cut.
  if (!outcome.failure.empty()) {
    cut_reason_ = outcome.failure;
  } else if (outcome.status_changes > 0 && impact_limit_ > 0.0 &&
             outcome.step > impact_limit_ * (1 + 1e-9)) {
    cut_reason_ = fmt::format(
        "{} status change(s) in a step longer than {:.4g} (T/30 of the contact "
        "frequency)",
        outcome.status_changes, impact_limit_);
  } else if (!outcome.penetration.empty()) {
    cut_reason_ = outcome.penetration;
  } else {
    return SubstepDecision::Accept;
  }
  ++cuts_;
  const Substep s = next();
  if (!control_->cut()) return SubstepDecision::Stop;
  Log::info("load step {} substep {} (t = {:g}): dt = {:.4g} cut to {:.4g}: {}", load_step_,
            s.number, s.time, s.h, control_->next_step(), cut_reason_);
  return SubstepDecision::Cut;
}

std::string TimeSchedule::stop_message(double time_reached) const {
  const Substep s = next();
  return fmt::format(
      "load step {} substep {} (t = {:g}): the time step {:.4g} cannot be cut below the "
      "minimum {:.4g} (DELTIM DTMIN / NSUBST NSBMX) after {} cuts in this load step: {}; "
      "the results up to t = {:g} are kept. Allow a smaller minimum step, more iterations "
      "(NEQIT), or soften the contact (gap stiffness), or accept such steps with "
      "--continue-on-nonconvergence",
      load_step_, s.number, s.time, s.h, plan_.dt_min, cuts_ - 1, cut_reason_, time_reached);
}

void TimeSchedule::accept(int iterations, int status_changes) {
  if (!control_) {
    ++k_;
    return;
  }
  const double h = control_->next_step();
  ++k_;
  h_min_ = std::min(h_min_, h);
  h_max_ = std::max(h_max_, h);
  control_->accept(iterations <= easy_iterations_ && status_changes == 0);
}

void TimeSchedule::set_contact_ceiling(std::optional<double> closed_contact_period) {
  if (!control_) return;
  control_->set_ceiling(closed_contact_period
                            ? std::optional<double>(resolving_step(*closed_contact_period))
                            : std::nullopt);
  if (closed_contact_period) ++ceiling_steps_;
}

int TimeSchedule::accepted_substep() const {
  return control_ ? k_ : k_ - 1;
}

SubstepProgress TimeSchedule::progress(double time) const {
  if (!control_)
    return {timing_.n_substeps, timing_.n_substeps - accepted_substep() + later_substeps_,
            run_end_};
  const double left = (timing_.t_end - time) / std::max(control_->desired(), 1e-300);
  return {k_ + static_cast<int>(left), static_cast<long long>(left) + later_substeps_, run_end_};
}

std::optional<StepController::State> TimeSchedule::controller_state() const {
  if (!control_ || control_->done()) return std::nullopt;
  return control_->state();
}

void TimeSchedule::end_load_step() {
  first_substep_ = 1;
  t_reached_ = timing_.t_end;
  if (!control_) {
    carried_ = timing_.h;
    return;
  }
  impact_limit_ = 0.0;
  carried_ = control_->desired();
  const std::string summary = fmt::format(
      "automatic time stepping, load step {}: {} substeps, {} cuts, dt from {:.4g} to {:.4g} "
      "(first {:.4g}, min {:.4g}, max {:.4g}){}",
      load_step_, k_, cuts_, h_min_, h_max_, plan_.dt_first, plan_.dt_min, plan_.dt_max,
      ceiling_steps_ > 0
          ? fmt::format("; {} substeps under the contact-frequency ceiling T/30", ceiling_steps_)
          : "");
  Log::info("{}", summary);
  notes_.push_back(summary);
}

void TimeSchedule::advise(double h, double period, double hz, int element, bool warn) {
  if (!advice_note_ || hz > advised_hz_) {
    std::string note = fmt::format(
        "time-step advice: highest contact frequency {:.4g} Hz (element {} closed), T = {:.4g} s, "
        "suggested dt = T/30 = {:.4g} s",
        hz, element, period, resolving_step(period));
    if (advice_note_) {
      notes_[*advice_note_] = std::move(note);
    } else {
      advice_note_ = notes_.size();
      notes_.push_back(std::move(note));
    }
    advised_hz_ = hz;
  }
  if (warn && h > coarsest_step(period))
    Log::warn(
        "dt = {:.4g} s is coarser than T/10 = {:.4g} s of the contact frequency {:.4g} Hz "
        "(element {} closed); suggested dt = T/30 = {:.4g} s",
        h, coarsest_step(period), hz, element, resolving_step(period));
}

}  // namespace impactfe
