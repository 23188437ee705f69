// Restart points of DirectSolution (RESCONTROL, ANTYPE,,RESTART; APDL_MODELING §9.5;
// docs/solution_control.md): what continuing a static / full transient run needs is written at
// the requested converged substeps, and a run in a new process continues from it exactly.
#include <map>

#include "analysis/direct_solution.h"
#include "core/log.h"
#include "time/integrator_history.h"

namespace impactfe {

namespace {

/// A vector over the DOFs `from` (saved) on the DOF numbering `to` (DOFs not saved: 0).
VectorXd remap_saved(const VectorXd& saved, const std::vector<DofKey>& from, const DofMap& to) {
  std::map<DofKey, Eigen::Index> index;
  for (std::size_t i = 0; i < from.size(); ++i) index[from[i]] = static_cast<Eigen::Index>(i);
  VectorXd out = VectorXd::Zero(to.n_active());
  for (int i = 0; i < to.n_active(); ++i) {
    const auto it = index.find(to.key(i));
    if (it != index.end() && it->second < saved.size()) out(i) = saved(it->second);
  }
  return out;
}

}  // namespace

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
  u_ = remap_saved(p.u, p.dofs, *dofs_);
  v_ = remap_saved(p.v, p.dofs, *dofs_);
  a_ = remap_saved(p.a, p.dofs, *dofs_);
  f_ext_old_ = remap_saved(p.f_ext_old, p.dofs, *dofs_);
  f_int_old_ = remap_saved(p.f_int_old, p.dofs, *dofs_);
  f_damp_old_ = remap_saved(p.f_damp_old, p.dofs, *dofs_);
  reactions_ = remap_saved(p.reactions, p.dofs, *dofs_);
  acel_ = p.acel;
  time_ = p.time;
  energy_->restore(p.energy);
  // Contact on deformable targets with large sliding: the DOF lists for the saved positions.
  refresh_connectivity();
  // Committed element states (plastic history, slider slip, status): restored as saved. A
  // status element without a saved state is re-evaluated from the saved displacements and
  // committed. Either way its status is then checked against the saved code (a model that does
  // not match the run continued is refused rather than continued wrongly).
  std::map<int, int> saved;
  for (std::size_t i = 0; i < p.status_ids.size(); ++i)
    saved[p.status_ids[i]] = p.status_codes.at(i);
  VectorXd ue;
  const auto& elements = structure_.elements();
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const auto state = p.element_states.find(elements[e]->id());
    const std::size_t expected = elements[e]->history_state().size();
    const std::size_t given = state == p.element_states.end() ? 0 : state->second.size();
    if (given != expected)
      throw InputError(step.where,
                       fmt::format("continuing from the restart point of load step {} substep "
                                   "{}: element {} has a committed state of {} values there but "
                                   "{} in this model (not the model of the run continued)",
                                   p.load_step, p.substep, elements[e]->id(), given, expected));
    if (given > 0) elements[e]->restore_history_state(state->second);
    if (!elements[e]->has_status()) continue;
    if (given == 0) {
      assembler_->gather(e, u_, ue);
      elements[e]->revert();
      elements[e]->update_status(ctx_, ue);
      elements[e]->commit(ue);
    }
    const auto it = saved.find(elements[e]->id());
    const int code = static_cast<int>(elements[e]->status());
    if (it == saved.end() || it->second != code)
      throw InputError(step.where,
                       fmt::format("continuing from the restart point of load step {} substep "
                                   "{}: element {} has status {} there but {} here (its state "
                                   "cannot be restored)",
                                   p.load_step, p.substep, elements[e]->id(),
                                   it == saved.end() ? -1 : it->second, code));
  }
  if (p.dynamic && transient_) {
    auto* history = dynamic_cast<IntegratorHistory*>(integrator_.get());
    IMPACTFE_CHECK(history != nullptr, "the time integrator cannot restore its history");
    std::vector<VectorXd> remapped;
    for (const VectorXd& h : p.history) remapped.push_back(remap_saved(h, p.dofs, *dofs_));
    history->restore(remapped, p.h);
    dynamics_started_ = true;
  }
  factor_valid_ = false;
  // Time axis and numbering: after the end of load step L the deck's first load step is L + 1;
  // from inside load step L it is the rest of L (from the same start time and step).
  load_step_offset_ = p.last ? p.load_step : p.load_step - 1;
  first_substep_ = p.last ? 1 : p.substep + 1;
  t_end_ = p.last ? p.time : p.t_start;
  // The loads the continued load step ramps from (KBC 0).
  const bool from_step = p.last;
  if (from_step || p.has_previous) {
    LoadStep ramp_start;
    ramp_start.number = from_step ? p.load_step : p.load_step - 1;
    ramp_start.forces = from_step ? p.step_forces : p.previous_forces;
    ramp_start.constraints = from_step ? p.step_constraints : p.previous_constraints;
    ramp_start.acel = from_step ? p.step_acel : p.previous_acel;
    previous_ = ramp_start;
  } else {
    previous_.reset();
  }
  last_dt_ = p.last_dt;
  resume_autots_ = p.last ? std::nullopt : p.autots;
  resume_autots_t_end_ = p.autots_t_end;
  restarted_ = true;
  const std::string note =
      fmt::format("continued from the restart point of load step {} substep {} (t = {:g}) in {}",
                  p.load_step, p.substep, p.time, restart_path(writer_.path()));
  Log::info("{}", note);
  stats_.notes.push_back(note);
}

void DirectSolution::save_restart_point(const LoadStep& step, int substep, bool last,
                                        double t_start, const StepController* control) {
  const RestartControl& rc = step.rescontrol;
  if (!rc.defined || rc.load_steps < 0 || rc.frequency < 0) return;
  if (rc.load_steps > 0 && step.number % rc.load_steps != 0) return;
  if (!last && !(rc.frequency > 0 && substep % rc.frequency == 0)) return;
  RestartPoint p;
  p.load_step = step.number;
  p.substep = substep;
  p.time = time_;
  p.t_start = t_start;
  p.last = last;
  p.dynamic = dynamics_started_ && transient_ && step.time_integration;
  p.h = integrator_ ? integrator_->step() : 0.0;
  p.last_dt = last_dt_;
  for (int i = 0; i < dofs_->n_active(); ++i) p.dofs.push_back(dofs_->key(i));
  p.u = u_;
  p.v = v_;
  p.a = a_;
  p.f_ext_old = f_ext_old_;
  p.f_int_old = f_int_old_;
  p.f_damp_old = f_damp_old_;
  p.reactions = reactions_;
  p.acel = acel_;
  if (p.dynamic)
    if (const auto* history = dynamic_cast<const IntegratorHistory*>(integrator_.get()))
      p.history = history->history();
  p.energy = energy_->state();
  for (const auto& element : structure_.elements()) {
    std::vector<double> state = element->history_state();
    if (!state.empty()) p.element_states[element->id()] = std::move(state);
    if (!element->has_status()) continue;
    p.status_ids.push_back(element->id());
    p.status_codes.push_back(static_cast<int>(element->status()));
  }
  if (control != nullptr && !last) {
    p.autots = control->state();
    p.autots_t_end = control->plan().t_end;
  }
  p.step_forces = step.forces;
  p.step_constraints = step.constraints;
  p.step_acel = step.acel;
  if (previous_) {
    p.has_previous = true;
    p.previous_forces = previous_->forces;
    p.previous_constraints = previous_->constraints;
    p.previous_acel = previous_->acel;
  }
  write_restart_point(restart_path(writer_.path()), p, rc.load_steps == 0);
}

}  // namespace impactfe
