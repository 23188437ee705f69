#include "analysis/restart_points.h"

#include <fmt/format.h>

#include <map>

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

bool restart_point_wanted(const LoadStep& step, int substep, bool last) {
  const RestartControl& rc = step.rescontrol;
  if (!rc.defined || rc.load_steps < 0 || rc.frequency < 0) return false;
  if (rc.load_steps > 0 && step.number % rc.load_steps != 0) return false;
  return last || (rc.frequency > 0 && substep % rc.frequency == 0);
}

RestartPoint capture_restart_point(const RestartSite& site, const Structure& structure,
                                   const Discretisation& disc, const MotionState& state,
                                   const EnergyBalance& energy, const TimeIntegrator* integrator,
                                   const TimeSchedule& schedule) {
  RestartPoint p;
  p.load_step = site.step.number;
  p.substep = site.substep;
  p.time = state.time;
  p.t_start = schedule.timing().t_start;
  p.last = site.last;
  p.dynamic = site.dynamic;
  p.h = integrator != nullptr ? integrator->step() : 0.0;
  p.last_dt = schedule.carried_step();
  for (int i = 0; i < disc.dofs().n_active(); ++i) p.dofs.push_back(disc.dofs().key(i));
  p.u = state.u;
  p.v = state.v;
  p.a = state.a;
  p.f_ext_old = state.f_ext_old;
  p.f_int_old = state.f_int_old;
  p.f_damp_old = state.f_damp_old;
  p.reactions = state.reactions;
  p.acel = state.acel;
  if (p.dynamic)
    if (const auto* history = dynamic_cast<const IntegratorHistory*>(integrator))
      p.history = history->history();
  p.energy = energy.state();
  for (const auto& element : structure.elements()) {
    std::vector<double> s = element->history_state();
    if (!s.empty()) p.element_states[element->id()] = std::move(s);
    if (!element->has_status()) continue;
    p.status_ids.push_back(element->id());
    p.status_codes.push_back(static_cast<int>(element->status()));
  }
  if (!site.last) {
    p.autots = schedule.controller_state();
    if (p.autots) p.autots_t_end = schedule.timing().t_end;
  }
  p.step_forces = site.step.forces;
  p.step_constraints = site.step.constraints;
  p.step_acel = site.step.acel;
  if (site.previous != nullptr) {
    p.has_previous = true;
    p.previous_forces = site.previous->forces;
    p.previous_constraints = site.previous->constraints;
    p.previous_acel = site.previous->acel;
  }
  return p;
}

void restore_motion(const RestartPoint& p, const Discretisation& disc, MotionState& state,
                    EnergyBalance& energy) {
  const DofMap& dofs = disc.dofs();
  state.u = remap_saved(p.u, p.dofs, dofs);
  state.v = remap_saved(p.v, p.dofs, dofs);
  state.a = remap_saved(p.a, p.dofs, dofs);
  state.f_ext_old = remap_saved(p.f_ext_old, p.dofs, dofs);
  state.f_int_old = remap_saved(p.f_int_old, p.dofs, dofs);
  state.f_damp_old = remap_saved(p.f_damp_old, p.dofs, dofs);
  state.reactions = remap_saved(p.reactions, p.dofs, dofs);
  state.acel = p.acel;
  state.time = p.time;
  energy.restore(p.energy);
}

void restore_element_states(const RestartPoint& p, const Structure& structure, Discretisation& disc,
                            const VectorXd& u, const SourceLocation& where) {
  std::map<int, int> saved;
  for (std::size_t i = 0; i < p.status_ids.size(); ++i)
    saved[p.status_ids[i]] = p.status_codes.at(i);
  VectorXd ue;
  const auto& elements = structure.elements();
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const auto state = p.element_states.find(elements[e]->id());
    const std::size_t expected = elements[e]->history_state().size();
    const std::size_t given = state == p.element_states.end() ? 0 : state->second.size();
    if (given != expected)
      throw InputError(where,
                       fmt::format("continuing from the restart point of load step {} substep "
                                   "{}: element {} has a committed state of {} values there but "
                                   "{} in this model (not the model of the run continued)",
                                   p.load_step, p.substep, elements[e]->id(), given, expected));
    if (given > 0) elements[e]->restore_history_state(state->second);
    if (!elements[e]->has_status()) continue;
    if (given == 0) {
      disc.assembler().gather(e, u, ue);
      elements[e]->revert();
      elements[e]->update_status(structure.context(), ue);
      elements[e]->commit(ue);
    }
    const auto it = saved.find(elements[e]->id());
    const int code = static_cast<int>(elements[e]->status());
    if (it == saved.end() || it->second != code)
      throw InputError(where,
                       fmt::format("continuing from the restart point of load step {} substep "
                                   "{}: element {} has status {} there but {} here (its state "
                                   "cannot be restored)",
                                   p.load_step, p.substep, elements[e]->id(),
                                   it == saved.end() ? -1 : it->second, code));
  }
}

void restore_integrator(const RestartPoint& p, const Discretisation& disc,
                        TimeIntegrator& integrator) {
  auto* history = dynamic_cast<IntegratorHistory*>(&integrator);
  IMPACTFE_CHECK(history != nullptr, "the time integrator cannot restore its history");
  std::vector<VectorXd> remapped;
  for (const VectorXd& h : p.history) remapped.push_back(remap_saved(h, p.dofs, disc.dofs()));
  history->restore(remapped, p.h);
}

ScheduleResume schedule_resume(const RestartPoint& p) {
  // After the end of load step L the deck's first load step is L + 1; from inside load step L
  // it is the rest of L (from the same start time and step).
  ScheduleResume r;
  r.t_reached = p.last ? p.time : p.t_start;
  r.carried_step = p.last_dt;
  r.first_substep = p.last ? 1 : p.substep + 1;
  if (!p.last) r.autots = p.autots;
  r.autots_t_end = p.autots_t_end;
  return r;
}

std::optional<LoadStep> ramp_start(const RestartPoint& p) {
  if (!p.last && !p.has_previous) return std::nullopt;
  LoadStep start;
  start.number = p.last ? p.load_step : p.load_step - 1;
  start.forces = p.last ? p.step_forces : p.previous_forces;
  start.constraints = p.last ? p.step_constraints : p.previous_constraints;
  start.acel = p.last ? p.step_acel : p.previous_acel;
  return start;
}

}  // namespace impactfe
