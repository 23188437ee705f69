#include "analysis/run_observers.h"

#include <fmt/format.h>
#include "analysis/contact_summary.h"
#include "analysis/restart_points.h"

#include "core/errors.h"
#include "core/log.h"

namespace impactfe {

void ResultStorage::substep_accepted(const AcceptedSubstep& s) {
  // OUTRES: the items (and nodes / elements) this substep writes; none: no stored point.
  const OutputSelection selection =
      s.substep.grid > 0 ? output_selection(s.step.output, s.substep.grid, s.substep.n_grid)
                         : output_selection_between(s.step.output);
  if (selection.any()) store(s.substep.time, s.step.number, s.substep.number, s.dynamic, selection);
}

void ResultStorage::store(double time, int load_step, int substep, bool dynamic,
                          const OutputSelection& selection) {
  const Structure& structure = run_.structure;
  const Discretisation& disc = *run_.disc;
  const MotionState& state = run_.state;
  TimePoint point;
  point.time = time;
  point.load_step = load_step;
  point.substep = substep;
  // Quantities OUTRES does not write at this point are not computed (absent, NaN in the file).
  const auto wanted = [&](OutputItem i) { return !selection[i].none(); };
  if (wanted(OutputItem::NSOL))
    point.displacement = structure.displacement_table(disc.dofs(), state.u);
  if (dynamic || structure.options().type == AnalysisType::Transient) {
    if (wanted(OutputItem::VSOL)) point.velocity = structure.nodal_table(disc.dofs(), state.v);
    if (wanted(OutputItem::ASOL)) point.acceleration = structure.nodal_table(disc.dofs(), state.a);
  }
  if (wanted(OutputItem::RSOL))
    point.reaction = structure.reaction_table(disc.dofs(), state.reactions);
  if (selection.any_element_item())
    point.element_results = structure.element_results(disc.assembler(), state.u, state.v);
  apply_output_selection(selection, writer_.node_ids(), point);
  point.energy = run_.energy.columns(disc.kinetic_energy(state.v));
  point.frame_acceleration = state.acel;
  writer_.append(std::move(point));
  ++run_.stats.n_stored;
}

void ProgressReport::substep_accepted(const AcceptedSubstep& s) {
  if (progress_ == nullptr) return;
  const SubstepProgress p = run_.schedule.progress(s.substep.time);
  progress_->substep_done({run_.stats.description, s.substep.time, run_.schedule.load_step_end(),
                           s.step.number, s.substep.number, p.substeps, s.substep.h, s.iterations,
                           s.status_changes, p.left, p.run_end});
}

void RestartRecorder::substep_accepted(const AcceptedSubstep& s) {
  const bool wanted = restart_point_wanted(s.step, s.substep.number, s.last);
  if (!wanted && !s.stopping) return;
  const RestartSite site{s.step, s.previous, s.substep.number, s.last,
                         run_.integrator_running && s.dynamic};
  const RestartPoint p = capture_restart_point(site, run_.structure, *run_.disc, run_.state,
                                               run_.energy, run_.integrator.get(), run_.schedule);
  // A point kept only because the run stops drops none of those RESCONTROL asked for.
  write_restart_point(path_, p, wanted && s.step.rescontrol.load_steps == 0);
}

void ContactSummaryLog::load_step_solved(const LoadStep& step) {
  if (const auto contact =
          contact_summary(run_.structure.elements(), run_.disc->assembler(), run_.state.u,
                          step.number, run_.schedule.load_step_end()))
    Log::info("{}", *contact);
}

void EnergyReport::substep_accepted(const AcceptedSubstep& s) {
  if (!run_.schedule.transient() || !run_.disc || (accept_error_ && warned_)) return;
  const auto created = run_.energy.creation(run_.disc->kinetic_energy(run_.state.v));
  steps_over_ = created ? steps_over_ + 1 : 0;
  if (steps_over_ < kStepsOver) return;
  const std::string message = fmt::format(
      "load step {} substep {} (t = {:g}): energy created: the {} grew by {:.4g} beyond the "
      "balance, {:.1f} % of the {:.4g} put in (bound {:.0f} %, passed for {} steps): {}. The "
      "results up to this step are kept; --accept-energy-error goes on",
      s.step.number, s.substep.number, s.substep.time, created->term, created->created,
      100.0 * created->created / created->reference, created->reference,
      100.0 * EnergyBalance::kCreationBound, kStepsOver, created->cause);
  if (!accept_error_) throw SolutionError(message);
  Log::warn("{} (accepted: --accept-energy-error)", message);
  warned_ = true;
}

void EnergyReport::run_finished() {
  if (!run_.schedule.transient() || !run_.disc) return;
  const double kinetic = run_.disc->kinetic_energy(run_.state.v);
  run_.stats.notes.push_back(run_.energy.summary(run_.state.time, kinetic));
  if (const auto warning = run_.energy.balance_warning(kinetic)) Log::warn("{}", *warning);
}

}  // namespace impactfe
