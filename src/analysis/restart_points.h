#pragma once
/// Restart points of a static / full transient run (RESCONTROL, ANTYPE,,RESTART; APDL_MODELING
/// §9.5; docs/solution_control.md): what a converged substep keeps for continuing
/// (capture_restart_point) and how a run in a new process takes it back (restore_*), exactly.
/// The file format is restart_file.h.
#include <optional>

#include "analysis/discretisation.h"
#include "analysis/energy_balance.h"
#include "analysis/motion_state.h"
#include "analysis/restart_file.h"
#include "time/time_integrator.h"
#include "time/time_schedule.h"

namespace impactfe {

/// Whether RESCONTROL asks for a point at `substep` of `step` (`last`: its last substep).
bool restart_point_wanted(const LoadStep& step, int substep, bool last);

/// Where a point is taken: the load step and the one before it (the loads a KBC 0 ramp starts
/// from), the substep, and the schedule (start time, carried step, AUTOTS controller state).
struct RestartSite {
  const LoadStep& step;
  const LoadStep* previous;
  int substep;
  bool last;
  bool dynamic;  // the integrator runs (its history is part of the point)
};

/// The point of the converged state `state` on `disc` at `site`.
RestartPoint capture_restart_point(const RestartSite& site, const Structure& structure,
                                   const Discretisation& disc, const MotionState& state,
                                   const EnergyBalance& energy, const TimeIntegrator* integrator,
                                   const TimeSchedule& schedule);

/// The saved state on `disc`'s numbering (by DOF key) and the energy sums.
void restore_motion(const RestartPoint& p, const Discretisation& disc, MotionState& state,
                    EnergyBalance& energy);
/// The committed element states (plastic history, slider slip, contact state), checked against
/// the model: InputError at `where` when an element's state or status does not match (not the
/// model of the run continued). A status element without a saved state is re-evaluated from
/// the saved displacements.
void restore_element_states(const RestartPoint& p, const Structure& structure, Discretisation& disc,
                            const VectorXd& u, const SourceLocation& where);
/// The integrator's history on `disc`'s numbering.
void restore_integrator(const RestartPoint& p, const Discretisation& disc,
                        TimeIntegrator& integrator);
/// Where the schedule continues: after the end of the point's load step, or inside it.
ScheduleResume schedule_resume(const RestartPoint& p);
/// The loads the continued load step ramps from (KBC 0), nullopt when none.
std::optional<LoadStep> ramp_start(const RestartPoint& p);

}  // namespace impactfe
