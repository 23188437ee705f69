#include "analysis/direct_solution.h"

#include <chrono>
#include <cmath>
#include <utility>

#include "analysis/restart_points.h"
#include "core/interruption.h"
#include "core/log.h"
#include "results/output_selection.h"

namespace impactfe {

DirectSolution::DirectSolution(Structure& structure, ResultsWriter& writer,
                               const RunSettings& settings, AnalysisStatistics& stats,
                               bool transient)
    : structure_(structure),
      writer_(writer),
      settings_(settings),
      stats_(stats),
      transient_(transient),
      schedule_(transient, structure.options().convergence.max_iterations, stats.notes),
      loads_(structure),
      energy_(structure.elements()),
      increment_(structure, settings_, stats, state_, loads_, energy_),
      sliding_(structure),
      parts_{structure, disc_, state_, energy_, integrator_, schedule_, dynamics_started_, stats},
      storage_(parts_, writer),
      progress_(parts_, settings_.progress),
      contact_log_(parts_),
      energy_report_(parts_, settings_.accept_energy_error) {}

long long DirectSolution::stored_points_at_most(const std::vector<LoadStep>& steps) {
  const auto substeps = schedule_.substeps_ahead();
  if (!substeps || substeps->size() != steps.size()) return 0;
  long long points = transient_ ? 1 : 0;
  for (std::size_t i = 0; i < steps.size(); ++i)
    points += stored_substeps_at_most(steps[i].output, (*substeps)[i]);
  return points;
}

void DirectSolution::begin() {
  if (transient_) integrator_ = make_time_integrator(structure_.options());
  restart_recorder_ = std::make_unique<RestartRecorder>(parts_, restart_path(writer_.path()));
  // After every substep: progress, then the stored point, then the restart point.
  observers_ = {&progress_, &storage_, restart_recorder_.get(), &contact_log_, &energy_report_};
  take_restart_request();
}

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
  const LoadStep* previous = previous_ ? &*previous_ : nullptr;
  schedule_.begin_load_step(step, output_strides(step.output));
  structure_.check_load_step(step);
  set_constraints(step);
  loads_.resolve(*disc_, step, previous);
  const bool dynamic = transient_ && step.time_integration;
  start_load_step(step, previous, dynamic);

  const auto stepping_start = std::chrono::steady_clock::now();
  std::optional<double> impact_period;  // AUTOTS: T/30 of it resolves an impact
  if (dynamic && disc_->contact_frequency())
    if (const auto contact = disc_->contact_frequency()->highest(false))
      impact_period = contact->period();
  schedule_.begin_substeps(impact_period);
  // Under AUTOTS chatter cuts the step; the cut is what is logged.
  if (schedule_.automatic()) disc_->status_loop().set_quiet_freeze(true);
  {
    // Ctrl-C / SIGTERM: read between substeps, so that the run stops on a converged state.
    const StopPoints stop_points;
    while (!schedule_.done()) {
      solve_substep(step, previous, dynamic);
      if (stopping_ != 0) stop_on_request(step);
    }
  }
  if (schedule_.automatic()) disc_->status_loop().set_quiet_freeze(false);
  schedule_.end_load_step();
  stats_.stepping_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - stepping_start).count();

  ++stats_.n_load_steps;
  for (RunObserver* o : observers_) o->load_step_solved(step);
  previous_ = step;
  SolverCounters total = retired_;
  total += disc_->counters();
  record_solver_counters(stats_, total);
}

void DirectSolution::start_load_step(const LoadStep& step, const LoadStep* previous, bool dynamic) {
  const double h0 = schedule_.first_step();
  const double t_start = schedule_.timing().t_start;
  if (!previous && !restarted_ && transient_) {
    // Store the initial state (t = 0) of a transient, so histories start at rest.
    const LoadPoint at0 = loads_.at(0.0, t_start);
    const int nc = disc_->dofs().n_constrained();
    state_.u.tail(nc) = prescribed_displacements(disc_->dofs(), at0).tail(nc);
    if (dynamic) {
      increment_.start_motion(at0, h0);
      dynamics_started_ = true;
      // The strain energy of the initial displacements (½ u₀·f_int(u₀), exact when linear) is
      // energy put in, for the energy check's reference.
      if (state_.f_int_old.size() == state_.u.size())
        energy_.set_initial_strain(0.5 * state_.u.dot(state_.f_int_old));
      energy_.start(disc_->assembler(), state_.u);
    }
    // Initial velocities (IC) bring kinetic energy that the balance must count as put in.
    energy_.set_initial_kinetic(disc_->kinetic_energy(state_.v));
    state_.reactions = VectorXd::Zero(disc_->dofs().n_active());
    state_.acel = frame_acceleration(at0);
    storage_.store(t_start, 0, 0, dynamic,
                   output_selection(step.output, 0, schedule_.timing().n_substeps));
  }
  if (!dynamic) {
    dynamics_started_ = false;
    return;
  }
  if (!dynamics_started_) {
    increment_.start_motion(loads_.at(0.0, t_start), h0);
    dynamics_started_ = true;
  } else if (!schedule_.resumes_automatic()) {
    change_step(h0);  // (continuing inside an AUTOTS step: the controller gives the step)
  }
  time_step_advice(h0, !schedule_.automatic());  // a load step after a contact closed
}

void DirectSolution::solve_substep(const LoadStep& step, const LoadStep* previous, bool dynamic) {
  const Substep s = schedule_.next();
  const LoadPoint at = loads_.at(s.fraction, s.time);
  const bool automatic = schedule_.automatic();
  if (dynamic && automatic) change_step(s.h);
  const StepLabel label{step.number, s.number, s.time};
  // Implicit creep acts over this substep, (t − h, t): the creep laws of the elements read the
  // clock (the deck armed it: RATE, temperature + TOFF). A retry after a cut comes back here
  // with the shorter step.
  CreepClock& creep = *structure_.model().creep_clock;
  creep.time = s.time;
  creep.dt = s.h;
  // Static creep substeps after the first of a load step start from the last increment scaled
  // to this step (linear extrapolation, MAPDL's substep predictor, PRED): creep under a steady
  // load advances the displacements nearly linearly, so Newton starts close to the solution
  // and the force tolerance (CNVTOL 0.5 %) leaves no visible error in the creep strain.
  const bool creep_static = creep.active && !dynamic;
  if (creep_static && creep_load_step_ == step.number && creep_step_ > 0.0 &&
      creep_increment_.size() == state_.u.size())
    increment_.predict_static((s.h / creep_step_) * creep_increment_);
  const VectorXd u_start = creep_static ? state_.u : VectorXd();
  const int iterations_before = stats_.n_iterations;
  const int changes_before = stats_.n_status_changes;
  const SubstepDecision decision =
      schedule_.decide(increment_.find_equilibrium(at, label, dynamic, automatic));
  if (decision != SubstepDecision::Accept) {
    increment_.reject();
    ++stats_.n_cuts;
    if (decision == SubstepDecision::Cut) return;  // retried at the cut step
    const std::string message = schedule_.stop_message(state_.time);
    if (!settings_.continue_on_nonconvergence) throw SolutionError(message);
    Log::warn("{}", message);
    increment_.find_equilibrium(at, label, dynamic, false);  // accepted as it comes (warned)
  }
  increment_.accept();  // commits the element states: the creep increment of the substep
  if (creep_static && u_start.size() == state_.u.size()) {
    creep_increment_ = state_.u - u_start;
    creep_step_ = s.h;
    creep_load_step_ = step.number;
  } else {
    creep_increment_.resize(0);
  }
  // The states are committed at the end of the substep: the results written now (and any
  // evaluation until the next substep) return from them without creeping again.
  creep.dt = 0.0;
  refresh_connectivity();
  ++stats_.n_substeps;
  const int iterations = stats_.n_iterations - iterations_before;
  schedule_.accept(iterations, increment_.status_changes());
  if (dynamic && disc_->contact_frequency()) {
    const auto contact = disc_->contact_frequency()->highest(true);
    // AUTOTS: the contact frequency of the gaps closed now bounds the next step (T/30).
    if (automatic)
      schedule_.set_contact_ceiling(contact ? std::optional<double>(contact->period())
                                            : std::nullopt);
    // The advice names a contact that closed, and a stiffer one when it closes later.
    if (contact && (!closed_highest_ || contact->omega > closed_highest_->omega)) {
      closed_highest_ = contact;
      time_step_advice(s.h, !automatic);
    }
  }
  // Read once: the restart recorder and the loop must agree on whether the run stops here.
  stopping_ = stop_requested();
  const AcceptedSubstep accepted{step,
                                 previous,
                                 s,
                                 iterations,
                                 stats_.n_status_changes - changes_before,
                                 dynamic,
                                 schedule_.done(),
                                 stopping_ != 0};
  for (RunObserver* o : observers_) o->substep_accepted(accepted);
}

void DirectSolution::stop_on_request(const LoadStep& step) {
  // The restart recorder has kept this substep's state (AcceptedSubstep::stopping).
  const std::string message = fmt::format(
      "interrupted by {} at t = {:g} (load step {}, substep {}); the last converged state is "
      "kept as a restart point in {} (ANTYPE,,RESTART continues from it)",
      signal_name(stopping_), state_.time, step.number, schedule_.accepted_substep(),
      restart_path(writer_.path()));
  Log::info("{}", message);
  throw RunInterrupted(stopping_, message);
}

void DirectSolution::finish() {
  if (const std::string note = increment_.condensation_summary(); !note.empty())
    stats_.notes.push_back(note);
  for (RunObserver* o : observers_) o->run_finished();
  if (disc_ && disc_->solver().name() == "MUMPS")
    stats_.notes.push_back(disc_->assembler().assembly_summary());
  if (const std::string note = sliding_.summary(); !note.empty()) stats_.notes.push_back(note);
  SolverCounters total = retired_;
  if (disc_) total += disc_->counters();
  record_solver_counters(stats_, total);
}

// ---- the discretisation and the time step -----------------------------------------------------

void DirectSolution::set_constraints(const LoadStep& step) {
  std::set<DofKey> wanted = structure_.constraints_of(step);
  if (disc_ && wanted == disc_->constrained()) return;
  renumber(std::move(wanted), false);
}

void DirectSolution::renumber(std::set<DofKey> wanted, bool keep_dynamics) {
  auto next = std::make_unique<Discretisation>(structure_, std::move(wanted),
                                               transient_ && settings_.condense);
  if (disc_) {
    state_.remap(disc_->dofs(), next->dofs());
    // The integrator history belongs to the old numbering unless it is remapped.
    dynamics_started_ = keep_dynamics && dynamics_started_ && integrator_ &&
                        remap_integrator_history(*integrator_, disc_->dofs(), next->dofs());
    retired_ += disc_->counters();  // keep the work of the previous numbering in the counts
  } else {
    state_.start(next->dofs(), structure_.model());
  }
  disc_ = std::move(next);
  increment_.bind(*disc_, integrator_.get());
  stats_.n_dofs = disc_->dofs().n_free();
}

void DirectSolution::refresh_connectivity() {
  if (!sliding_.refresh(*disc_, state_.u)) return;
  Log::debug("t = {:g}: contact DOF lists changed (large sliding), DOFs renumbered", state_.time);
  renumber(disc_->constrained(), true);
  loads_.resolve_again(*disc_);
}

void DirectSolution::change_step(double h) {
  if (std::abs(integrator_->step() - h) <= 1e-12 * h) return;
  integrator_->set_step(h);  // Houbolt re-samples its history (spec §10.2)
  disc_->invalidate_factor();
}

void DirectSolution::time_step_advice(double h, bool warn) {
  // Only contacts that have closed in this analysis: one that never touches sets no time scale.
  if (!closed_highest_) return;
  const ContactFrequency& contact = *closed_highest_;
  schedule_.advise(h, contact.period(), contact.omega / (2.0 * M_PI), contact.element, warn);
}

// ---- restart ------------------------------------------------------------------------------------

void DirectSolution::take_restart_request() {
  // The deck hands ANTYPE,,RESTART to one analysis (AnalysisOptions::restart).
  if (!structure_.options().restart) return;
  const RestartRequest q = *structure_.options().restart;
  restart_ = std::make_unique<RestartPoint>(
      read_restart_point(restart_path(writer_.path()), q.load_step, q.substep, q.where));
  if (restart_->dynamic && !transient_)
    throw InputError(q.where, fmt::format("the restart point (load step {}, substep {}) is of a "
                                          "transient; continue it with ANTYPE,TRANS,RESTART",
                                          restart_->load_step, restart_->substep));
}

void DirectSolution::apply_restart(const LoadStep& step) {
  const RestartPoint p = std::move(*restart_);
  restart_.reset();
  set_constraints(step);
  restore_motion(p, *disc_, state_, energy_);
  // Contact on deformable targets with large sliding: the DOF lists for the saved positions.
  refresh_connectivity();
  restore_element_states(p, structure_, *disc_, state_.u, step.where);
  if (p.dynamic && transient_) {
    restore_integrator(p, *disc_, *integrator_);
    dynamics_started_ = true;
  }
  disc_->invalidate_factor();
  // Time axis and numbering: after the end of load step L the deck's first load step is L + 1;
  // from inside load step L it is the rest of L (from the same start time and step).
  load_step_offset_ = p.last ? p.load_step : p.load_step - 1;
  schedule_.resume(schedule_resume(p));
  previous_ = ramp_start(p);
  restarted_ = true;
  const std::string note =
      fmt::format("continued from the restart point of load step {} substep {} (t = {:g}) in {}",
                  p.load_step, p.substep, p.time, restart_path(writer_.path()));
  Log::info("{}", note);
  stats_.notes.push_back(note);
}

}  // namespace impactfe
