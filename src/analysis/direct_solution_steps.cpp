// The substeps of a load step of DirectSolution: constant steps, or automatic time stepping
// (AUTOTS; APDL_MODELING §9.1, §9.3; docs/solution_control.md) with bisection, growth, the
// contact-frequency ceiling and landing on the requested output times.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "analysis/contact_summary.h"
#include "analysis/direct_solution.h"
#include "core/log.h"
#include "time/time_axis.h"

namespace impactfe {

namespace {

/// AUTOTS when the deck does not say: constant steps (docs/solution_control.md, "Default").
constexpr bool kAutotsDefault = false;

}  // namespace

void DirectSolution::solve_load_step(const LoadStep& given) {
  if (restart_) apply_restart(given);  // continuing a run: its state, time and numbering
  // After a restart the load steps are numbered on from the run continued.
  LoadStep renumbered;
  if (load_step_offset_ != 0) {
    renumbered = given;
    renumbered.number += load_step_offset_;
  }
  const LoadStep& step = load_step_offset_ != 0 ? renumbered : given;
  // OUTRES the same for every item: each stored point is complete (no NaN rows to compress).
  writer_.set_sparse_output(!step.output.uniform());
  const bool transient = transient_;
  const LoadStep* previous = previous_ ? &*previous_ : nullptr;
  const LoadStepTiming t = load_step_timing(step, t_end_, transient);
  structure_.check_load_step(step);
  set_constraints(step);
  // F and D of this load step resolved to DOF indices once (no map lookups per substep).
  forces_ = ResolvedDofLoads(*dofs_, step, previous, ResolvedDofLoads::Kind::Forces);
  prescribed_ = ResolvedDofLoads(*dofs_, step, previous, ResolvedDofLoads::Kind::Constraints);
  resolved_step_ = &step;
  resolved_previous_ = previous;
  const bool dynamic = transient && step.time_integration;
  const AutoStepPlan plan =
      auto_step_plan(step, step.control, t, transient, kAutotsDefault, last_dt_);
  // A restart point inside a load step continues it with the same kind of substeps: the state
  // of the step controller is part of a point inside an AUTOTS load step.
  if (first_substep_ > 1 && plan.automatic != resume_autots_.has_value())
    throw InputError(step.where,
                     fmt::format("load step {}: the restart point (substep {}) is inside a load "
                                 "step solved {}; continue it with AUTOTS,{} as it was solved",
                                 step.number, first_substep_ - 1,
                                 resume_autots_ ? "with automatic time stepping"
                                                : "with constant "
                                                  "steps",
                                 resume_autots_ ? "ON" : "OFF"));
  if (resume_autots_ &&
      std::abs(resume_autots_t_end_ - plan.t_end) > 1e-12 * std::max(std::abs(plan.t_end), 1.0))
    throw InputError(step.where,
                     fmt::format("load step {}: the restart point is inside a load step ending at "
                                 "t = {:g}, but this load step ends at t = {:g} (repeat its TIME)",
                                 step.number, resume_autots_t_end_, plan.t_end));
  const double h0 = plan.automatic ? plan.dt_first : t.h;  // the first step
  if (!previous && !restarted_) {
    // Store the initial state (t = 0) of a transient, so histories start at rest.
    if (transient) {
      const LoadPoint at0 = load_point(step, previous, 0.0, t.t_start);
      u_.tail(dofs_->n_constrained()) =
          prescribed_displacements(*dofs_, at0).tail(dofs_->n_constrained());
      if (dynamic) start_dynamics(at0, h0);
      // Initial velocities (IC) bring kinetic energy that the balance must count as put in.
      energy_->set_initial_kinetic(kinetic_energy());
      reactions_ = VectorXd::Zero(dofs_->n_active());
      acel_ = frame_acceleration(at0);
      store(t_end_, 0, 0, dynamic, output_selection(step.output, 0, t.n_substeps));
    }
  }
  if (dynamic) {
    if (!dynamics_started_) {
      start_dynamics(load_point(step, previous, 0.0, t.t_start), h0);
    } else if (!resume_autots_) {
      change_step(h0);  // (continuing inside an AUTOTS step: the controller gives the step)
    }
    time_step_advice(h0);
  } else {
    dynamics_started_ = false;
  }
  // Substeps and end time of the load steps known to follow (progress estimate of the run); a
  // step whose timing is invalid is reported when it is solved, not here.
  long long later_substeps = 0;
  double run_end = t.t_end;
  try {
    for (const LoadStep& next : following_) {
      const LoadStepTiming tn = load_step_timing(next, run_end, transient);
      later_substeps += tn.n_substeps;
      run_end = tn.t_end;
    }
  } catch (const std::exception&) {
  }
  const StepContext context{step, previous, t, dynamic, later_substeps, run_end};
  const auto stepping_start = std::chrono::steady_clock::now();
  if (plan.automatic)
    solve_automatic_steps(context, plan);
  else
    solve_constant_steps(context);
  stats_.stepping_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - stepping_start).count();
  ++stats_.n_load_steps;
  if (const auto contact =
          contact_summary(structure_.elements(), *assembler_, u_, step.number, t.t_end))
    Log::info("{}", *contact);
  previous_ = step;
  t_end_ = t.t_end;
  update_counters();
}

void DirectSolution::solve_constant_steps(const StepContext& c) {
  const LoadStep& step = c.step;
  const LoadStepTiming& t = c.timing;
  for (int k = first_substep_; k <= t.n_substeps; ++k) {
    const double time = t.t_start + k * t.h;
    const LoadPoint at = load_point(step, c.previous, static_cast<double>(k) / t.n_substeps, time);
    const int iterations_before = stats_.n_iterations;
    const int changes_before = stats_.n_status_changes;
    solve_increment(at, StepLabel{step.number, k, time}, c.dynamic);
    ++stats_.n_substeps;
    if (settings_.progress)
      settings_.progress->substep_done({stats_.description, time, t.t_end, step.number, k,
                                        t.n_substeps, t.h, stats_.n_iterations - iterations_before,
                                        stats_.n_status_changes - changes_before,
                                        t.n_substeps - k + c.later_substeps, c.run_end});
    // OUTRES: the items (and nodes / elements) this substep writes; none: no stored point.
    const OutputSelection selection = output_selection(step.output, k, t.n_substeps);
    if (selection.any()) store(time, step.number, k, c.dynamic, selection);
    save_restart_point(step, k, k == t.n_substeps, t.t_start);
  }
  first_substep_ = 1;
  last_dt_ = t.h;
}

void DirectSolution::change_step(double h) {
  if (std::abs(integrator_->step() - h) <= 1e-12 * h) return;
  integrator_->set_step(h);  // Houbolt re-samples its history (spec §10.2)
  factor_valid_ = false;
}

void DirectSolution::solve_automatic_steps(const StepContext& c, const AutoStepPlan& plan) {
  const LoadStep& step = c.step;
  const LoadStepTiming& t = c.timing;
  StepController control(plan, output_strides(step.output));
  int k = 0, cuts = 0, ceiling_steps = 0;
  if (resume_autots_) {  // continuing from a restart point inside this load step
    control.restore(*resume_autots_);
    resume_autots_.reset();
    k = first_substep_ - 1;
  }
  const int easy_iterations = std::max(1, structure_.options().convergence.max_iterations / 4);
  status_loop_->set_quiet_freeze(true);  // chatter cuts the step; the cut is what is logged
  // Impacts are resolved at T/30 of the highest contact frequency of the model (the time-step
  // advice): a step in which a contact opens or closes is cut until it is that short.
  impact_step_limit_ = 0.0;
  if (c.dynamic && contact_frequency_)
    if (const auto contact = contact_frequency_->highest(false))
      impact_step_limit_ = std::max(contact->period() / 30.0, plan.dt_min);
  double h_min = std::numeric_limits<double>::infinity(), h_max = 0.0;
  Log::info(
      "load step {}: automatic time stepping from t = {:g} to {:g}: first dt = {:g}, min {:g}, "
      "max {:g}",
      step.number, t.t_start, t.t_end, plan.dt_first, plan.dt_min, plan.dt_max);
  while (!control.done()) {
    const double h = control.next_step();
    const double time = control.next_time();
    const int grid = control.next_grid_index();
    const double fraction =
        grid == plan.n_nominal ? 1.0 : (time - t.t_start) / (t.t_end - t.t_start);
    const LoadPoint at = load_point(step, c.previous, fraction, time);
    if (c.dynamic) change_step(h);
    const StepLabel label{step.number, k + 1, time};
    const int iterations_before = stats_.n_iterations;
    const int changes_before = stats_.n_status_changes;
    if (!solve_increment(at, label, c.dynamic, true)) {
      ++cuts;
      ++stats_.n_cuts;
      if (control.cut()) {
        Log::info("load step {} substep {} (t = {:g}): dt = {:.4g} cut to {:.4g}: {}", step.number,
                  k + 1, time, h, control.next_step(), cut_reason_);
        continue;
      }
      const std::string message = fmt::format(
          "load step {} substep {} (t = {:g}): the time step {:.4g} cannot be cut below the "
          "minimum {:.4g} (DELTIM DTMIN / NSUBST NSBMX) after {} cuts in this load step: {}; "
          "the results up to t = {:g} are kept. Allow a smaller minimum step, more iterations "
          "(NEQIT), or soften the contact (gap stiffness), or accept such steps with "
          "--continue-on-nonconvergence",
          step.number, k + 1, time, h, plan.dt_min, cuts - 1, cut_reason_, time_);
      if (!settings_.continue_on_nonconvergence) throw SolutionError(message);
      Log::warn("{}", message);
      solve_increment(at, label, c.dynamic, false);  // accepted as it comes (warned there)
    }
    ++k;
    ++stats_.n_substeps;
    h_min = std::min(h_min, h);
    h_max = std::max(h_max, h);
    const int iterations = stats_.n_iterations - iterations_before;
    control.accept(iterations <= easy_iterations && increment_.n_status_changes == 0);
    // The contact frequency of the gaps closed now bounds the next step (T/30, the advice).
    if (c.dynamic && contact_frequency_) {
      const auto contact = contact_frequency_->highest(true);
      control.set_ceiling(contact ? std::optional<double>(contact->period() / 30.0) : std::nullopt);
      if (contact) ++ceiling_steps;
    }
    if (settings_.progress) {
      const double left = (t.t_end - time) / std::max(control.desired(), 1e-300);
      settings_.progress->substep_done(
          {stats_.description, time, t.t_end, step.number, k, k + static_cast<int>(left), h,
           iterations, stats_.n_status_changes - changes_before,
           static_cast<long long>(left) + c.later_substeps, c.run_end});
    }
    // OUTRES: the requested times (grid points) as with constant steps; between them only the
    // items written at every substep (frequency ALL).
    const OutputSelection selection = grid > 0 ? output_selection(step.output, grid, plan.n_nominal)
                                               : output_selection_between(step.output);
    if (selection.any()) store(time, step.number, k, c.dynamic, selection);
    save_restart_point(step, k, control.done(), t.t_start, &control);
  }
  first_substep_ = 1;
  status_loop_->set_quiet_freeze(false);
  impact_step_limit_ = 0.0;
  last_dt_ = control.desired();
  const std::string summary = fmt::format(
      "automatic time stepping, load step {}: {} substeps, {} cuts, dt from {:.4g} to {:.4g} "
      "(first {:.4g}, min {:.4g}, max {:.4g}){}",
      step.number, k, cuts, h_min, h_max, plan.dt_first, plan.dt_min, plan.dt_max,
      ceiling_steps > 0
          ? fmt::format("; {} substeps under the contact-frequency ceiling T/30", ceiling_steps)
          : "");
  Log::info("{}", summary);
  stats_.notes.push_back(summary);
}

void DirectSolution::time_step_advice(double h) {
  if (!contact_frequency_) return;
  const auto contact = contact_frequency_->highest(false);
  if (!contact) return;
  const double period = contact->period();
  const double hz = contact->omega / (2.0 * M_PI);
  if (!advice_given_) {
    stats_.notes.push_back(fmt::format(
        "time-step advice: highest contact frequency {:.4g} Hz (element {} closed), T = {:.4g} s, "
        "suggested dt = T/30 = {:.4g} s",
        hz, contact->element, period, period / 30.0));
    advice_given_ = true;
  }
  if (h > period / 10.0)
    Log::warn(
        "dt = {:.4g} s is coarser than T/10 = {:.4g} s of the contact frequency {:.4g} Hz "
        "(element {} closed); suggested dt = T/30 = {:.4g} s",
        h, period / 10.0, hz, contact->element, period / 30.0);
}

}  // namespace impactfe
